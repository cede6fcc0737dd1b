// Unit tests of rate-independent von Mises plasticity with linear isotropic
// hardening (hardening_plasticity.h): the radial return against the closed
// form of uniaxial strain, the consistent tangent against finite
// differences, plane strain as the 3D law, and the state: alpha grows only
// when the point yields, and the update does not depend on the step length.

#include <deal.II/base/symmetric_tensor.h>

#include <gtest/gtest.h>

#include "hardening_plasticity.h"

#include <cmath>

using namespace dealii;
using namespace ViscoContact;

namespace
{
  constexpr double E = 1000, nu = 0.3, sigma_Y = 1, H = 50;
  const double     mu = E / (2 * (1 + nu)), K = E / (3 * (1 - 2 * nu));

  SymmetricTensor<2, 3>
  uniaxial(const double e)
  {
    SymmetricTensor<2, 3> strain;
    strain[2][2] = e;
    return strain;
  }
} // namespace



// Uniaxial strain eps = e e_z (x) e_z, loaded in steps from e = 0 to
// -0.01: the stress is elastic, sigma_zz = (K + 4 mu / 3) e, until
// |sigma_zz - sigma_xx| = 2 mu |e| reaches sigma_Y, and beyond grows with
// the elastoplastic modulus K + (4 mu / 3) H / (3 mu + H). The radial
// return is exact on this proportional path, whatever the steps.
TEST(HardeningPlasticity, UniaxialStrainClosedForm)
{
  const HardeningPlasticity<3> law(E, nu, sigma_Y, H, false);
  const double                 e_yield = sigma_Y / (2 * mu);
  SymmetricTensor<2, 3>        history; // sigma - E eps
  double                       alpha = 0;
  for (unsigned int n = 1; n <= 20; ++n)
    {
      const double                e  = -0.0005 * n;
      double                      zz = 0;
      const SymmetricTensor<2, 3> trial
        = law.elasticity_tensor() * uniaxial(e) + history;
      const SymmetricTensor<2, 3> sigma
        = law.implicit_update(trial, 0, 0.1, zz, nullptr, alpha);
      history = sigma - law.elasticity_tensor() * uniaxial(e);
      const double expected
        = std::abs(e) <= e_yield
            ? (K + 4 * mu / 3) * e
            : -(K + 4 * mu / 3) * e_yield
                + (K + 4 * mu / 3 * H / (3 * mu + H)) * (e + e_yield);
      EXPECT_NEAR(sigma[2][2], expected, 1e-12 * std::abs(expected))
        << "e = " << e;
      // The equivalent stress is the hardened yield stress while yielding.
      if (std::abs(e) > e_yield)
        EXPECT_NEAR(law.equivalent_stress(sigma, 0),
                    sigma_Y + H * alpha,
                    1e-12 * sigma_Y);
      else
        EXPECT_EQ(alpha, 0.);
    }
  EXPECT_GT(alpha, 0.);
}

// d sigma / d eps of the update against central differences of the update
// at a yielding state (a general strain, alpha > 0).
TEST(HardeningPlasticity, ConsistentTangentMatchesFiniteDifferences)
{
  const HardeningPlasticity<3> law(E, nu, sigma_Y, H, false);
  SymmetricTensor<2, 3>        strain;
  strain[0][0] = 0.002;
  strain[1][1] = -0.001;
  strain[2][2] = -0.004;
  strain[0][1] = 0.0015;
  strain[1][2] = -0.0007;
  SymmetricTensor<2, 3> history;
  history[0][0]               = 0.3;
  history[2][2]               = -0.2;
  const double          a0    = 0.001;
  double                alpha = a0, zz = 0;
  SymmetricTensor<4, 3> tangent;
  law.implicit_update(law.elasticity_tensor() * strain + history,
                      0,
                      1.,
                      zz,
                      &tangent,
                      alpha);
  ASSERT_GT(alpha, a0) << "the state does not yield";
  const double h = 1e-7;
  for (unsigned int k = 0; k < 3; ++k)
    for (unsigned int l = k; l < 3; ++l)
      {
        SymmetricTensor<2, 3> d;
        d[k][l]       = h;
        double     a1 = a0, a2 = a0;
        const auto plus
          = law.implicit_update(law.elasticity_tensor() * (strain + d)
                                  + history,
                                0,
                                1.,
                                zz,
                                nullptr,
                                a1);
        const auto minus
          = law.implicit_update(law.elasticity_tensor() * (strain - d)
                                  + history,
                                0,
                                1.,
                                zz,
                                nullptr,
                                a2);
        for (unsigned int i = 0; i < 3; ++i)
          for (unsigned int j = i; j < 3; ++j)
            {
              // A symmetric perturbation of an off-diagonal strain changes
              // both [k][l] and [l][k].
              const double expected = (plus[i][j] - minus[i][j]) / (2 * h);
              const double computed = tangent[i][j][k][l] * (k == l ? 1 : 2);
              EXPECT_NEAR(computed, expected, 1e-5 * E) << i << j << k << l;
            }
      }
}

// Plane strain: the in-plane stresses, sigma_zz and the in-plane tangent are
// those of the 3D law on the strain with eps_zz = 0.
TEST(HardeningPlasticity, PlaneStrainIsTheThreeDimensionalLaw)
{
  const HardeningPlasticity<2> planar(E, nu, sigma_Y, H, true);
  const HardeningPlasticity<3> solid(E, nu, sigma_Y, H, false);
  SymmetricTensor<2, 2>        strain;
  strain[0][0] = 0.003;
  strain[1][1] = -0.004;
  strain[0][1] = 0.001;
  SymmetricTensor<2, 3> strain_3d;
  for (unsigned int i = 0; i < 2; ++i)
    for (unsigned int j = i; j < 2; ++j)
      strain_3d[i][j] = strain[i][j];
  double                alpha_2d = 0, alpha_3d = 0, zz = 0, zz_3d = 0;
  SymmetricTensor<4, 2> tangent;
  SymmetricTensor<4, 3> tangent_3d;
  const auto            sigma
    = planar.implicit_update(planar.elasticity_tensor() * strain,
                             planar.out_of_plane_elastic_stress(strain),
                             1.,
                             zz,
                             &tangent,
                             alpha_2d);
  const auto sigma_3d
    = solid.implicit_update(solid.elasticity_tensor() * strain_3d,
                            0,
                            1.,
                            zz_3d,
                            &tangent_3d,
                            alpha_3d);
  EXPECT_GT(alpha_3d, 0.);
  EXPECT_NEAR(alpha_2d, alpha_3d, 1e-15);
  EXPECT_NEAR(zz, sigma_3d[2][2], 1e-12 * E);
  for (unsigned int i = 0; i < 2; ++i)
    for (unsigned int j = i; j < 2; ++j)
      {
        EXPECT_NEAR(sigma[i][j], sigma_3d[i][j], 1e-12 * E);
        for (unsigned int k = 0; k < 2; ++k)
          for (unsigned int l = k; l < 2; ++l)
            EXPECT_NEAR(tangent[i][j][k][l], tangent_3d[i][j][k][l], 1e-9 * E);
      }
}

// Inside the yield set nothing changes; the step length does not enter;
// the law runs with the implicit update only.
TEST(HardeningPlasticity, ElasticInsideAndRateIndependent)
{
  const HardeningPlasticity<3> law(E, nu, sigma_Y, H, false);
  double                       alpha = 0, zz = 0;
  const SymmetricTensor<2, 3>  trial
    = law.elasticity_tensor() * uniaxial(-0.0001);
  EXPECT_EQ(law.implicit_update(trial, 0, 1., zz, nullptr, alpha), trial);
  EXPECT_EQ(alpha, 0.);
  const SymmetricTensor<2, 3> beyond
    = law.elasticity_tensor() * uniaxial(-0.005);
  double     alpha_short = 0, alpha_long = 0;
  const auto short_step
    = law.implicit_update(beyond, 0, 1e-6, zz, nullptr, alpha_short);
  const auto long_step
    = law.implicit_update(beyond, 0, 1e6, zz, nullptr, alpha_long);
  EXPECT_EQ(short_step, long_step);
  EXPECT_EQ(alpha_short, alpha_long);
  EXPECT_FALSE(law.has_rate_form());
  EXPECT_FALSE(law.internal_variable_is_guess());
}
