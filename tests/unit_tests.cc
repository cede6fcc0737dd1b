// Unit tests of the pieces where the physics lives: the E-norm projection
// onto the von Mises set, the contact law and its pieces, the lumped contact
// weights, the active-set iteration on the condensed contact problem, the
// sparse direct solvers, the simplex patterns of the generated box, the Q1
// transfer of stress-point data between a cell and its children, and the
// parallel tools (exchange of keyed records, collective text files). Each
// expectation states its tolerance; reference values are computed by hand
// or by an independent method written out here (bisection, exhaustive
// enumeration, a Krylov solve). The executable also runs on two MPI ranks
// (ctest unit_tests.np2), where the parallel tools exchange across ranks.

#include <deal.II/base/mpi.h>
#include <deal.II/base/multithread_info.h>
#include <deal.II/base/function.h>
#include <deal.II/base/geometry_info.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/base/symmetric_tensor.h>

#include <deal.II/distributed/fully_distributed_tria.h>
#include <deal.II/distributed/tria.h>

#include <deal.II/dofs/dof_handler.h>
#include <deal.II/dofs/dof_tools.h>

#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_simplex_p.h>
#include <deal.II/fe/fe_system.h>

#include <deal.II/fe/fe_values.h>
#include <deal.II/fe/mapping_fe.h>
#include <deal.II/fe/mapping_q1.h>

#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/grid_in.h>
#include <deal.II/grid/grid_tools.h>
#include <deal.II/grid/tria.h>
#include <deal.II/grid/tria_description.h>

#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/lapack_full_matrix.h>
#include <deal.II/lac/sparse_direct.h>
#include <deal.II/lac/sparse_matrix.h>
#include <deal.II/lac/sparsity_tools.h>

#include <deal.II/numerics/matrix_tools.h>
#include <deal.II/numerics/vector_tools.h>

#include <gtest/gtest.h>

#include "back_ends/blas_threads.h"
#include "back_ends/condensed_system.h"
#include "back_ends/cost_model.h"
#include "back_ends/rigid_body_modes.h"
#include "contact_law.h"
#include "contact_nodes.h"
#include "contact_set.h"
#include "material.h"
#include "mesh/coarse_cell_order.h"
#include "mesh/mesh.h"
#include "archard_wear.h"
#include "bonding_field.h"
#include "cohesive_damage.h"
#include "normal_memory.h"
#include "rigid_motions.h"
#include "robustness/checkpoint_file.h"
#include "robustness/mpi_tools.h"
#include "robustness/output_folder.h"
#include "stress_point_transfer.h"
#include "time_schedule.h"
#include "unit/test_scenes.h"

#include "back_ends/direct_solver.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <map>
#include <random>
#include <regex>
#include <sstream>

using namespace dealii;
using namespace ViscoContact;

namespace
{
  // The pieces of the given indices as they act at the nodes of the
  // condensed system (no bonding, no memory), and the pieces of the nodes
  // as they act with their memory pressures.
  std::vector<ContactLawPiece>
  acting_pieces(const ContactLaws               &laws,
                const std::vector<unsigned int> &pieces)
  {
    std::vector<ContactLawPiece> result;
    for (const unsigned int piece : pieces)
      result.push_back(laws.piece(piece));
    return result;
  }

  std::vector<ContactLawPiece>
  acting_pieces(const ContactNodes &nodes)
  {
    std::vector<ContactLawPiece> result;
    for (unsigned int i = 0; i < nodes.size(); ++i)
      {
        result.push_back(nodes.current_piece(i));
        if (!result.back().vertical)
          result.back().intercept += nodes.history_pressure(i);
      }
    return result;
  }


  // The benchmark material: E = 1000, k = 0.4, lambda = 50, sigma_Y = 2.
  template <int dim>
  PerzynaMaterial<dim>
  benchmark_material()
  {
    return PerzynaMaterial<dim>(1000., 0.4, 50., 2.);
  }

  template <int dim>
  SymmetricTensor<2, dim>
  random_tensor(std::mt19937 &generator, const double scale)
  {
    std::uniform_real_distribution<double> uniform(-scale, scale);
    SymmetricTensor<2, dim>                t;
    for (unsigned int i = 0; i < dim; ++i)
      for (unsigned int j = i; j < dim; ++j)
        t[i][j] = uniform(generator);
    return t;
  }

  // The variational inequality that characterises P_K in the E inner
  // product: (E (tau - P tau), eta - P tau) <= 0 for all eta in K. Checked
  // for random eta in K (scaled into K if needed) and eta on the boundary.
  template <int dim>
  void
  check_projection_properties(const unsigned int n_samples)
  {
    const PerzynaMaterial<dim> material = benchmark_material<dim>();
    const double               sigma_Y  = material.yield_stress();
    std::mt19937               generator(42);
    for (unsigned int s = 0; s < n_samples; ++s)
      {
        const SymmetricTensor<2, dim> tau = random_tensor<dim>(generator, 20.);
        const SymmetricTensor<2, dim> p = material.project_onto_yield_set(tau);
        const double                  scale = tau.norm() + sigma_Y;

        if (material.equivalent_stress(tau) <= sigma_Y)
          EXPECT_LE((p - tau).norm(), 1e-15 * scale); // identity inside K
        else // on the yield surface, to machine precision
          EXPECT_NEAR(material.equivalent_stress(p), sigma_Y, 1e-13 * sigma_Y);

        // A guess of the multiplier (as the time loop passes the previous
        // step's) changes nothing but the number of iterations.
        for (const double factor : {0.5, 0.99, 1.0, 1.7})
          {
            double multiplier = 0;
            material.project_onto_yield_set(tau, &multiplier);
            multiplier *= factor;
            EXPECT_LE(
              (material.project_onto_yield_set(tau, &multiplier) - p).norm(),
              1e-13 * scale);
          }

        // Idempotent.
        EXPECT_LE((material.project_onto_yield_set(p) - p).norm(),
                  1e-13 * scale);

        for (unsigned int e = 0; e < 20; ++e)
          {
            SymmetricTensor<2, dim> eta = random_tensor<dim>(generator, 5.);
            const double            eq  = material.equivalent_stress(eta);
            if (eq > sigma_Y)
              eta *= sigma_Y / eq * (e % 2 == 0 ? 1. : 0.5);
            EXPECT_LE(material.energy_product(tau - p, eta - p),
                      1e-9 * scale * scale);
          }
      }
  }
} // namespace



TEST(Projection2D, VariationalInequalityIdempotenceAndSurface)
{
  check_projection_properties<2>(2000);
}



TEST(Projection3D, VariationalInequalityIdempotenceAndSurface)
{
  check_projection_properties<3>(2000);
}



// Hand-computed cases. Pure shear and a pure spherical stress excite one
// mode each, so the E-projection is the radial scaling onto the surface:
//   tau_12 = 2: eq = sqrt(3) 2, P tau_12 = 2/sqrt(3);
//   tau = diag(3,3): eq = 3, P tau = diag(2,2).
TEST(Projection2D, HandComputedSingleModeCases)
{
  const PerzynaMaterial<2> material = benchmark_material<2>();
  SymmetricTensor<2, 2>    shear;
  shear[0][1]                   = 2.;
  const SymmetricTensor<2, 2> p = material.project_onto_yield_set(shear);
  EXPECT_NEAR(p[0][1], 2. / std::sqrt(3.), 1e-14);
  EXPECT_NEAR(p[0][0], 0., 1e-14);
  EXPECT_NEAR(p[1][1], 0., 1e-14);

  const SymmetricTensor<2, 2> spherical = 3. * unit_symmetric_tensor<2>();
  const SymmetricTensor<2, 2> q = material.project_onto_yield_set(spherical);
  EXPECT_NEAR(q[0][0], 2., 1e-14);
  EXPECT_NEAR(q[1][1], 2., 1e-14);
  EXPECT_NEAR(q[0][1], 0., 1e-14);
}



// tau = diag(4, 0) mixes the spherical and deviatoric modes, whose E
// eigenvalues differ (E/(1-k) vs E/(1+k)): the E-projection is NOT the
// radial scaling. Reference: the multiplier equation
//   1/2 (E_a y_a/(E_a + mu/2))^2 + 3/2 (E_b y_b/(E_b + 3 mu/2))^2 = sigma_Y^2
// solved here by plain bisection, independently of the program's Newton.
TEST(Projection2D, MixedCaseAgainstBisection)
{
  const PerzynaMaterial<2> material = benchmark_material<2>();
  SymmetricTensor<2, 2>    tau;
  tau[0][0]        = 4.;
  const double E_a = 1000. / 0.6, E_b = 1000. / 1.4, sigma_Y = 2.;
  const double y_a = 4. / std::sqrt(2.), y_b = 4. / std::sqrt(2.);
  const auto   f = [&](const double mu) {
    const double xa = E_a * y_a / (E_a + 0.5 * mu);
    const double xb = E_b * y_b / (E_b + 1.5 * mu);
    return 0.5 * xa * xa + 1.5 * xb * xb - sigma_Y * sigma_Y;
  };
  double lo = 0, hi = 1e6;
  for (unsigned int i = 0; i < 200; ++i)
    (f(0.5 * (lo + hi)) > 0 ? lo : hi) = 0.5 * (lo + hi);
  const double mu = 0.5 * (lo + hi);
  const double xa = E_a * y_a / (E_a + 0.5 * mu);
  const double xb = E_b * y_b / (E_b + 1.5 * mu);

  double                      multiplier = 0;
  const SymmetricTensor<2, 2> p
    = material.project_onto_yield_set(tau, &multiplier);
  EXPECT_NEAR(multiplier, mu, 1e-10 * mu);
  EXPECT_NEAR(p[0][0], (xa + xb) / std::sqrt(2.), 1e-12);
  EXPECT_NEAR(p[1][1], (xa - xb) / std::sqrt(2.), 1e-12);
  EXPECT_NEAR(p[0][1], 0., 1e-14);

  const SymmetricTensor<2, 2> radial
    = tau * (sigma_Y / material.equivalent_stress(tau));
  EXPECT_GT((p - radial).norm(), 1e-2); // not a radial scaling
}



// 3D: the radial return keeps the trace and scales the deviator.
TEST(Projection3D, RadialReturnOfTheDeviator)
{
  const PerzynaMaterial<3> material = benchmark_material<3>();
  std::mt19937             generator(7);
  for (unsigned int s = 0; s < 100; ++s)
    {
      const SymmetricTensor<2, 3> tau = random_tensor<3>(generator, 20.);
      const SymmetricTensor<2, 3> p   = material.project_onto_yield_set(tau);
      EXPECT_NEAR(trace(p), trace(tau), 1e-12 * tau.norm());
      const double eq = material.equivalent_stress(tau);
      if (eq > 2.)
        {
          EXPECT_LE((deviator(p) - deviator(tau) * (2. / eq)).norm(),
                    1e-13 * tau.norm());
        }
    }
}



// The backward-Euler update: sigma + a E (sigma - P_K sigma) = trial holds
// to rounding, inside K the update is the identity, and the tangent
// d sigma / d trial agrees with central finite differences (step 1e-6
// relative, tolerance 1e-6 relative to |T|).
template <int dim>
void
check_implicit_update()
{
  const PerzynaMaterial<dim> material = benchmark_material<dim>();
  std::mt19937               generator(3);
  for (const double a : {1e-4, 1e-3, 1e-1})
    for (unsigned int sample = 0; sample < 200; ++sample)
      {
        const SymmetricTensor<2, dim> trial
          = random_tensor<dim>(generator, 20.);
        SymmetricTensor<4, dim>       tangent;
        const SymmetricTensor<2, dim> sigma
          = material.implicit_stress_update(trial, a, &tangent);
        const SymmetricTensor<2, dim> residual
          = sigma
            + a
                * (material.elasticity_tensor()
                   * (sigma - material.project_onto_yield_set(sigma)))
            - trial;
        EXPECT_LE(residual.norm(), 1e-12 * trial.norm());

        const double step = 1e-6 * trial.norm();
        for (unsigned int i = 0; i < dim; ++i)
          for (unsigned int j = i; j < dim; ++j)
            {
              SymmetricTensor<2, dim> direction;
              direction[i][j] = 1;
              const SymmetricTensor<2, dim> difference
                = (material.implicit_stress_update(trial + step * direction, a)
                   - material.implicit_stress_update(trial - step * direction,
                                                     a))
                  / (2 * step);
              EXPECT_LE((difference - tangent * direction).norm(),
                        1e-6 * (tangent.norm() + 1));
            }
      }
  SymmetricTensor<2, dim> inside;
  inside[0][1] = 0.1;
  SymmetricTensor<4, dim> tangent;
  EXPECT_EQ(
    (material.implicit_stress_update(inside, 0.01, &tangent) - inside).norm(),
    0.);
  EXPECT_EQ((tangent - identity_tensor<dim>()).norm(), 0.);
}

TEST(ImplicitUpdate2D, SolvesLocalEquationAndTangentMatchesFiniteDifferences)
{
  check_implicit_update<2>();
}

TEST(ImplicitUpdate3D, SolvesLocalEquationAndTangentMatchesFiniteDifferences)
{
  check_implicit_update<3>();
}



// Plane strain: with eps_zz = 0 and a history H (with its zz part), the 2D
// update of E eps + H is the 3D update of the embedded tensor (sigma and
// sigma_zz, and the rate), and the consistent tangent d sigma / d eps
// agrees with central finite differences in the in-plane strain.
TEST(PlaneStrain, IsTheThreeDimensionalLawAndTangentMatchesFiniteDifferences)
{
  const PerzynaMaterial<2> plane(1000, 0.3, 50, 2, true, true);
  const PerzynaMaterial<3> solid(1000, 0.3, 50, 2, true);
  std::mt19937             generator(5);
  const auto embed = [](const SymmetricTensor<2, 2> &t, const double zz) {
    SymmetricTensor<2, 3> e;
    e[0][0] = t[0][0];
    e[1][1] = t[1][1];
    e[0][1] = t[0][1];
    e[2][2] = zz;
    return e;
  };
  for (const double a : {1e-4, 1e-2})
    for (unsigned int sample = 0; sample < 100; ++sample)
      {
        const SymmetricTensor<2, 2> strain  = random_tensor<2>(generator, 0.02);
        const SymmetricTensor<2, 2> history = random_tensor<2>(generator, 5.);
        const double                history_zz
          = std::uniform_real_distribution<>(-5, 5)(generator);
        const auto stress_of = [&](const SymmetricTensor<2, 2> &eps,
                                   double                      &zz,
                                   SymmetricTensor<4, 2>       *tangent) {
          return plane.implicit_stress_update(
            plane.elasticity_tensor() * eps + history,
            plane.out_of_plane_elastic_stress(eps) + history_zz,
            a,
            zz,
            tangent,
            nullptr);
        };
        double                      sigma_zz = 0;
        SymmetricTensor<4, 2>       tangent;
        const SymmetricTensor<2, 2> sigma
          = stress_of(strain, sigma_zz, &tangent);
        const SymmetricTensor<2, 3> expected
          = solid.implicit_stress_update(solid.elasticity_tensor()
                                             * embed(strain, 0)
                                           + embed(history, history_zz),
                                         a);
        EXPECT_LE((embed(sigma, sigma_zz) - expected).norm(),
                  1e-12 * (expected.norm() + 1));
        EXPECT_NEAR(plane.equivalent_stress(sigma, sigma_zz),
                    solid.equivalent_stress(expected),
                    1e-12 * (expected.norm() + 1));
        double                      rate_zz = 0;
        const SymmetricTensor<2, 2> rate
          = plane.viscoplastic_rate(sigma, sigma_zz, rate_zz);
        EXPECT_LE(
          (embed(rate, rate_zz) - solid.viscoplastic_rate(expected)).norm(),
          1e-12 * (expected.norm() + 1));

        const double step = 1e-6 * strain.norm();
        for (unsigned int i = 0; i < 2; ++i)
          for (unsigned int j = i; j < 2; ++j)
            {
              SymmetricTensor<2, 2> direction;
              direction[i][j]                     = (i == j ? 1. : 0.5);
              double                      zz_plus = 0, zz_minus = 0;
              const SymmetricTensor<2, 2> difference
                = (stress_of(strain + step * direction, zz_plus, nullptr)
                   - stress_of(strain - step * direction, zz_minus, nullptr))
                  / (2 * step);
              EXPECT_LE((difference - tangent * direction).norm(),
                        1e-6 * (tangent.norm() + 1));
            }
      }
}



TEST(Perzyna, RateVanishesInsideAndRelaxesOutside)
{
  const PerzynaMaterial<2> material = benchmark_material<2>();
  SymmetricTensor<2, 2>    inside;
  inside[0][1] = 0.5;
  EXPECT_EQ(material.viscoplastic_rate(inside).norm(), 0.);
  SymmetricTensor<2, 2> outside;
  outside[0][1] = 5.;
  // Pure shear: G = -(1/(2 lambda)) E (tau - P tau), E acts as E/(1+k) on it.
  const double expected = -1. / 100. * 1000. / 1.4 * (5. - 2. / std::sqrt(3.));
  EXPECT_NEAR(material.viscoplastic_rate(outside)[0][1], expected, 1e-11);
}



// The benchmark law: pieces (-inf,0] flat, [0,u1] slope c1, [u1,g] slope c2,
// and the rigid limit at g = 0.01 with p(g-) = c1 u1 + c2 (g - u1) = 1.4.
TEST(ContactLaw, BenchmarkLawPieces)
{
  const ContactLaw law({0., 0.006}, {0., 300., -100.}, {0., 0.}, true, 0.01);
  ASSERT_EQ(law.n_pieces(), 4u);
  EXPECT_TRUE(law.piece(3).rigid);
  EXPECT_NEAR(law.piece(3).p_lower, 1.4, 1e-14);
  EXPECT_NEAR(law.compliance_pressure(-1.), 0., 1e-14);
  EXPECT_NEAR(law.compliance_pressure(0.003), 0.9, 1e-14);
  EXPECT_NEAR(law.compliance_pressure(0.006), 1.8, 1e-14);
  EXPECT_NEAR(law.compliance_pressure(0.008), 1.6, 1e-14);
  EXPECT_NEAR(law.piece(2).slope, -100., 1e-14);
  EXPECT_EQ(law.steepest_softening(), 100.);

  // q = p + c r names the piece: with c = 1000,
  //   piece 0: q <= 0; piece 1: q in [0, 1.8 + 6 = 7.8];
  //   piece 2: [7.8, 1.4 + 10 = 11.4]; rigid: q >= 11.4.
  EXPECT_EQ(law.find_piece(-1., 1000.), 0u);
  EXPECT_EQ(law.find_piece(5., 1000.), 1u);
  EXPECT_EQ(law.find_piece(9., 1000.), 2u);
  EXPECT_EQ(law.find_piece(11.3, 1000.), 2u);
  EXPECT_EQ(law.find_piece(11.5, 1000.), 3u);
}



// g = u1: the softening branch is cut off, the law the body sees is
// monotone.
TEST(ContactLaw, MonotoneCaseGapEqualsU1)
{
  const ContactLaw law({0., 0.006}, {0., 300., -100.}, {0., 0.}, true, 0.006);
  ASSERT_EQ(law.n_pieces(), 3u);
  EXPECT_NEAR(law.piece(2).p_lower, 1.8, 1e-14);
  EXPECT_EQ(law.steepest_softening(), 0.);
}



// The multivalued law of model.md, section 5 (a = 0.002, b = 1): a vertical
// piece [0, b] at r = 0, then softening to zero; no rigid limit.
TEST(ContactLaw, AdhesiveLawWithJump)
{
  const ContactLaw law({0., 0.002}, {0., -500., 0.}, {1., 0.}, false, 0.01);
  ASSERT_EQ(law.n_pieces(), 4u);
  EXPECT_TRUE(law.piece(1).vertical);
  EXPECT_FALSE(law.piece(1).rigid);
  EXPECT_NEAR(law.piece(1).p_upper, 1., 1e-14);
  EXPECT_NEAR(law.compliance_pressure(0.001), 0.5, 1e-14);
  EXPECT_NEAR(law.compliance_pressure(0.005), 0., 1e-14);
  EXPECT_FALSE(law.has_rigid_limit());
  // Signorini with gap 0 and no compliance is one flat piece plus the rigid
  // limit.
  const ContactLaw signorini({}, {0.}, {}, true, 0.);
  EXPECT_EQ(signorini.n_pieces(), 2u);
  EXPECT_FALSE(signorini.is_void());
  EXPECT_TRUE(ContactLaw({}, {0.}, {}, false, 0.).is_void());
}



// The lumped weights w_i = int phi_i sum to the measure of Gamma_3 (the
// clamped corner included), interior nodes get h, end nodes h/2, and the
// normals are the outward ones, also on a rotated (not axis-aligned) mesh.
template <int dim>
void
check_lumped_weights(const bool simplex, const double angle)
{
  Triangulation<dim> triangulation;
  const unsigned int N = 8;
  if (simplex)
    GridGenerator::subdivided_hyper_cube_with_simplices(triangulation, N);
  else
    GridGenerator::subdivided_hyper_cube(triangulation, N);
  for (const auto &face : triangulation.active_face_iterators())
    if (face->at_boundary())
      face->set_boundary_id(std::abs(face->center()[dim - 1]) < 1e-12 ? 7 : 0);
  if (angle != 0)
    GridTools::rotate(angle, triangulation);

  const ReferenceCell cell = (simplex ? ReferenceCells::get_simplex<dim>()
                                      : ReferenceCells::get_hypercube<dim>());
  DoFHandler<dim>     dof_handler(triangulation);
  if (simplex)
    dof_handler.distribute_dofs(FESystem<dim>(FE_SimplexP<dim>(1), dim));
  else
    dof_handler.distribute_dofs(FESystem<dim>(FE_Q<dim>(1), dim));
  VectorType weights(complete_index_set(dof_handler.n_dofs()), MPI_COMM_SELF);
  VectorType normals(weights);
  assemble_lumped_weights<dim>(
    hp::MappingCollection<dim>(cell.template get_default_linear_mapping<dim>()),
    dof_handler,
    hp::QCollection<dim - 1>(
      cell.face_reference_cell(0).template get_gauss_type_quadrature<dim - 1>(
        2)),
    {7},
    weights,
    normals);

  // The vertices on the boundary part, each with its weight and normal.
  std::map<unsigned int, std::pair<Point<dim>, types::global_dof_index>>
    vertices;
  for (const auto &c : dof_handler.active_cell_iterators())
    for (const unsigned int f : c->face_indices())
      if (c->face(f)->at_boundary() && c->face(f)->boundary_id() == 7)
        for (const unsigned int v : c->face(f)->vertex_indices())
          vertices[c->face(f)->vertex_index(v)]
            = {c->face(f)->vertex(v), c->face(f)->vertex_dof_index(v, 0)};
  EXPECT_EQ(vertices.size(), (dim == 2 ? N + 1 : (N + 1) * (N + 1)));
  double sum = 0;
  for (const auto &[vertex, data] : vertices)
    {
      const double weight = weights(data.second);
      sum += weight;
      Tensor<1, dim> normal;
      for (unsigned int c = 0; c < dim; ++c)
        normal[c] = normals(data.second + c);
      normal /= normal.norm();
      Tensor<1, dim> expected_normal;
      expected_normal[dim - 1] = -1;
      if (dim == 2 && angle != 0)
        expected_normal = Tensor<1, dim>({std::sin(angle), -std::cos(angle)});
      EXPECT_LE((normal - expected_normal).norm(), 1e-12);
      if (dim == 2)
        {
          const double s   = data.first.norm();
          const bool   end = (s < 1e-12 || std::abs(s - 1.) < 1e-12);
          EXPECT_NEAR(weight, (end ? 0.5 : 1.) / N, 1e-13);
        }
    }
  EXPECT_NEAR(sum, 1., 1e-12);
  EXPECT_NEAR(weights.l1_norm(), 1., 1e-12); // nothing off the boundary part
}

TEST(LumpedWeights, TrianglesSumToLength)
{
  check_lumped_weights<2>(true, 0.);
}

TEST(LumpedWeights, QuadrilateralsSumToLength)
{
  check_lumped_weights<2>(false, 0.);
}

TEST(LumpedWeights, RotatedTrianglesHaveRotatedNormals)
{
  check_lumped_weights<2>(true, 0.3);
}

TEST(LumpedWeights, TetrahedraSumToArea)
{
  check_lumped_weights<3>(true, 0.);
}



namespace
{
  const ContactLaw benchmark_law({0., 0.006},
                                 {0., 300., -100.},
                                 {0., 0.},
                                 true,
                                 0.01);

  // The solution of r = d - s z, z = w p(r) for one decoupled node (spring
  // compliance s) with the benchmark law, by hand, piece by piece.
  double
  decoupled_force(const double d, const double s, const double w)
  {
    const double c1 = 300, c2 = -100, u1 = 0.006, g = 0.01;
    if (d <= 0)
      return 0;                      // no contact
    double r = d / (1 + s * w * c1); // on [0, u1]
    if (r <= u1)
      return w * c1 * r;
    r = (d - s * w * (c1 * u1 - c2 * u1)) / (1 + s * w * c2); // on [u1, g]
    if (r <= g)
      return w * (c1 * u1 + c2 * (r - u1));
    return (d - g) / s; // at the rigid limit
  }

  // The condensed active set as the program runs it on one rank: the nodes
  // of ContactNodes, moved by ContactNodes::solve around the dense solves
  // of CondensedContactSystem (what the condensed back end does for fixed
  // pieces). The parameter c_i = 1/(w_i S_ii) is the node's condensed
  // stiffness per unit weight.
  struct DenseActiveSet
  {
    // zones: the zone of each node (empty: all in zone 0).
    DenseActiveSet(const ContactLaws               &laws,
                   const FullMatrix<double>        &S,
                   const std::vector<double>       &w,
                   const std::vector<unsigned int> &zones = {})
    {
      nodes.reinit(laws,
                   zones.empty() ? std::vector<unsigned int>(w.size(), 0)
                                 : zones,
                   w);
      std::vector<double> c(w.size());
      for (unsigned int i = 0; i < w.size(); ++i)
        c[i] = std::max(1. / (w[i] * S(i, i)),
                        2 * laws.zone_law(nodes.zone(i)).steepest_softening());
      nodes.set_parameters(c);
      system.reinit(laws, S, w);
    }

    ActiveSetResult
    solve(const Vector<double> &d,
          const unsigned int    max_iterations,
          const double          tolerance)
    {
      return nodes.solve(
        [&](const LinearSolveRequest &) {
          LinearSolveReport report;
          Vector<double>    r, z;
          report.residual = system.solve(acting_pieces(nodes), d, r, z);
          std::copy(r.begin(), r.end(), nodes.r.begin());
          std::copy(z.begin(), z.end(), nodes.z.begin());
          return report;
        },
        max_iterations,
        tolerance,
        MPI_COMM_SELF);
    }

    ContactNodes           nodes;
    CondensedContactSystem system;
  };

  // Five decoupled nodes (a diagonal compliance), one on each piece of the
  // benchmark law and one out of contact: their data d, S and w.
  struct DecoupledNodes
  {
    const std::vector<double> d = {-0.001, 0.002, 0.0075, 0.009, 0.03};
    const unsigned int        m = d.size();
    FullMatrix<double>        S{m, m};
    const std::vector<double> w = std::vector<double>(m, 0.03125);
    DecoupledNodes()
    {
      for (unsigned int i = 0; i < m; ++i)
        S(i, i) = 0.01 * (1 + 0.1 * i);
    }
  };
} // namespace



// The stick/slip rule of one frictional node on a rigid support (Signorini,
// gap 0), w = 0.5, c = 100, with q = t + c w ds: the state it names, the
// directions of its equations, and the forces store_solution() derives.
TEST(Friction, StickSlipRuleOfOneNode)
{
  const ContactLaws signorini(ContactLaw({}, {0.}, {}, true, 0.));
  ContactNodes      nodes;
  nodes.reinit(signorini, {0}, {0.5});
  nodes.set_friction({std::make_shared<CoulombFriction>(0.3)}, {1}, {0.});
  nodes.set_parameters({100.});
  // Stuck at the start: the tangential direction is fixed at s_{n-1} = 0.
  EXPECT_EQ(nodes.friction_state(0), ContactNodes::stick);
  NodeDirections directions = nodes.directions(0, 0.);
  ASSERT_EQ(directions.size, 2u);
  EXPECT_TRUE(directions.direction[1].fixed);
  EXPECT_EQ(directions.direction[1].value, 0.);

  // z = 10, so g = 3: |q| = 2 sticks, |q| = 4 slips along +x.
  nodes.z[0] = 10;
  nodes.t[0] = {{2, 0}};
  nodes.update_pieces();
  EXPECT_EQ(nodes.friction_state(0), ContactNodes::stick);
  nodes.t[0] = {{4, 0}};
  EXPECT_EQ(nodes.update_pieces()[0], 1u);
  EXPECT_EQ(nodes.friction_state(0), ContactNodes::slip);
  EXPECT_NEAR(nodes.slip_bound(0), 3., 1e-15);

  // Slipping, the force along d is coupled to the normal force: mu z.
  directions = nodes.directions(0, 0.);
  EXPECT_FALSE(directions.direction[1].fixed);
  EXPECT_EQ(directions.direction[1].frame[1], 1.);
  EXPECT_EQ(directions.direction[1].coupling, 0.3);
  const double displacements[2] = {0., 0.01}, forces[2] = {10., 0.};
  nodes.store_solution(0, 0., directions, displacements, forces);
  EXPECT_NEAR(nodes.t[0][0], 3., 1e-15);
  EXPECT_NEAR(nodes.s[0][0], 0.01, 1e-15);
  // q = 3 + 100 * 0.5 * 0.01 = 3.5 keeps it slipping, unchanged.
  EXPECT_EQ(nodes.update_pieces()[0], 0u);
  EXPECT_EQ(nodes.friction_state(0), ContactNodes::slip);

  // A q that turns against the slip goes through stick, not to a reversed
  // slip; a zero normal force leaves the node free.
  // q = 3 + 50 (-0.2) = -7.
  nodes.s[0] = {{-0.2, 0}};
  nodes.update_pieces();
  EXPECT_EQ(nodes.friction_state(0), ContactNodes::stick);
  nodes.z[0] = 0;
  nodes.update_pieces();
  EXPECT_EQ(nodes.friction_state(0), ContactNodes::free_tangential);
  EXPECT_FALSE(nodes.directions(0, 0.).direction[1].fixed);
}



// A moving obstacle: a node stuck to an obstacle that moves by (0.3, -0.1)
// over the step is held at its last position plus that motion, its slip
// is measured relative to the obstacle (q = t + c w (s - s_n-1 - o)), and
// the accepted step's slip is the motion relative to it.
TEST(Friction, StickToAMovingObstacle)
{
  const ContactLaws signorini(ContactLaw({}, {0.}, {}, true, 0.));
  ContactNodes      nodes;
  nodes.reinit(signorini, {0}, {0.5});
  nodes.set_friction({std::make_shared<TrescaFriction>()}, {2}, {1.});
  nodes.set_parameters({100.});
  nodes.reset_slip({{{1., 2.}}}, {{{0., 0.}}});
  nodes.set_obstacle_slip({{{0.3, -0.1}}});
  ASSERT_EQ(nodes.friction_state(0), ContactNodes::stick);
  const NodeDirections stuck = nodes.directions(0, 0.);
  EXPECT_TRUE(stuck.direction[1].fixed);
  EXPECT_EQ(stuck.direction[1].value, 1.3);
  EXPECT_EQ(stuck.direction[2].value, 1.9);
  // At the obstacle's position with a small force: still stuck.
  nodes.z[0] = 10;
  nodes.s[0] = {{1.3, 1.9}};
  nodes.t[0] = {{0.5, 0.}};
  nodes.update_pieces();
  EXPECT_EQ(nodes.friction_state(0), ContactNodes::stick);
  // Left behind by 0.1 along x, relative to the obstacle: q = t + c w ds
  // = (0.5 - 5, 0), beyond the bound: slips along -x.
  nodes.s[0] = {{1.2, 1.9}};
  nodes.update_pieces();
  ASSERT_EQ(nodes.friction_state(0), ContactNodes::slip);
  EXPECT_NEAR(nodes.directions(0, 0.).direction[1].frame[1], -1., 1e-15);
  // The step's slip relative to the obstacle, and none in the next step.
  nodes.accept_slip({{{1.2, 1.9}}});
  EXPECT_NEAR(nodes.step_slip(0)[0], -0.1, 1e-15);
  EXPECT_NEAR(nodes.step_slip(0)[1], 0., 1e-15);
  nodes.set_friction_state(0, ContactNodes::stick);
  EXPECT_EQ(nodes.directions(0, 0.).direction[1].value, 1.2);
}



// Slip weakening at a node (Coulomb mu = 0.5, f from 1 to 0.6 over a slip
// of 0.005): the bound follows the slip accumulated over the accepted
// steps, and a slipping node's coupling to its normal force weakens with
// it.
TEST(Friction, BoundWeakensWithTheAccumulatedSlip)
{
  const ContactLaws signorini(ContactLaw({}, {0.}, {}, true, 0.));
  auto              coulomb = std::make_shared<CoulombFriction>(0.5);
  coulomb->weakening        = {{0., 0.005}, {1., 0.6}};
  ContactNodes nodes;
  nodes.reinit(signorini, {0}, {0.5});
  nodes.set_friction({coulomb}, {1}, {0.});
  nodes.set_parameters({100.});
  nodes.z[0] = 10;
  nodes.t[0] = {{-6., 0.}};
  nodes.update_pieces();
  ASSERT_EQ(nodes.friction_state(0), ContactNodes::slip);
  EXPECT_EQ(nodes.slip_bound(0), 5.);
  EXPECT_EQ(nodes.directions(0, 0.).direction[1].coupling, 0.5);
  // Two accepted steps of slip 0.00125: S = 0.0025, f = 0.8.
  for (const double s : {0.00125, 0.0025})
    nodes.accept_slip({{{s, 0.}}}, 0.125);
  EXPECT_NEAR(nodes.weakening_variable(0), 0.0025, 1e-15);
  nodes.update_pieces();
  EXPECT_NEAR(nodes.slip_bound(0), 4., 1e-12);
  EXPECT_NEAR(nodes.directions(0, 0.).direction[1].coupling, 0.4, 1e-15);
  EXPECT_TRUE(nodes.has_slip_weakening());
}



// Rate weakening at a node (Tresca g = 1, f from 1 to 0.5 over a slip rate
// of 0.04): the bound follows the rate of the last accepted step's slip,
// not the path; a step without a length (a new mesh, a checkpoint) keeps
// the rate.
TEST(Friction, BoundWeakensWithTheSlipRate)
{
  const ContactLaws signorini(ContactLaw({}, {0.}, {}, true, 0.));
  auto              tresca = std::make_shared<TrescaFriction>();
  tresca->weakening        = {{0., 0.04}, {1., 0.5}, /*of_rate=*/true};
  ContactNodes nodes;
  nodes.reinit(signorini, {0}, {0.5});
  nodes.set_friction({tresca}, {1}, {1.});
  nodes.set_parameters({100.});
  nodes.z[0] = 10;
  nodes.accept_slip({{{0.0025, 0.}}}, 0.125); // v = 0.02: f = 0.75
  EXPECT_NEAR(nodes.weakening_variable(0), 0.02, 1e-15);
  nodes.accept_slip({{{0.0075, 0.}}}, 0.125); // v = 0.04: f = 0.5
  EXPECT_NEAR(nodes.weakening_variable(0), 0.04, 1e-15);
  nodes.reset_slip({{{0.0075, 0.}}}, {{{0., 0.}}});
  EXPECT_NEAR(nodes.weakening_variable(0), 0.04, 1e-15);
  nodes.t[0] = {{2., 0.}};
  nodes.update_pieces();
  ASSERT_EQ(nodes.friction_state(0), ContactNodes::slip);
  EXPECT_NEAR(nodes.slip_bound(0), 0.5, 1e-15);
  EXPECT_NEAR(nodes.directions(0, 0.).direction[1].value, 0.5, 1e-15);
}



// An iteration that returns to the same pieces stops with "cycles" in its
// failure: a node on Signorini's law whose solve penetrates when it is free
// and pulls when it is held (no solution of the linear problems is
// consistent), instead of running to Maximum iterations.
TEST(ActiveSetSolver, ReportsACycle)
{
  const ContactLaws signorini(ContactLaw({}, {0.}, {}, true, 0.));
  ContactNodes      nodes;
  nodes.reinit(signorini, {0}, {1.});
  nodes.set_parameters({100.});
  const ActiveSetResult result = nodes.solve(
    [&](const LinearSolveRequest &) {
      const bool held = nodes.current_piece(0).vertical;
      nodes.r[0]      = held ? 0. : 1.;
      nodes.z[0]      = held ? -1. : 0.;
      return LinearSolveReport();
    },
    50,
    1e-10,
    MPI_COMM_SELF);
  EXPECT_FALSE(result.converged);
  EXPECT_NE(result.failure.find("cycles"), std::string::npos) << result.failure;
  EXPECT_LT(result.iterations(), 10u);
}



namespace
{
  // One node of a 3D contact zone on a rigid support (Signorini, gap 0),
  // w = 0.5, c = 100 (c w = 50), pressed with z = 10, under Tresca's bound
  // g = 1.
  ContactNodes
  pressed_tresca_node_3d()
  {
    const ContactLaws signorini(ContactLaw({}, {0.}, {}, true, 0.));
    ContactNodes      nodes;
    nodes.reinit(signorini, {0}, {0.5});
    nodes.set_friction({std::make_shared<TrescaFriction>()}, {2}, {1.});
    nodes.set_parameters({100.});
    nodes.z[0] = 10;
    return nodes;
  }
} // namespace



// In 3D a slipping node gets the Newton stiffness across its slip
// direction: Tresca bound g = 1, q = (3, 4), gamma = g / |q| = 0.2,
// k = c w gamma / (1 - gamma) = 100 * 0.5 * 0.25.
TEST(Friction, TransverseStiffnessOfA3DSlip)
{
  ContactNodes nodes = pressed_tresca_node_3d();
  nodes.t[0]         = {{3, 4}};
  nodes.update_pieces();
  ASSERT_EQ(nodes.friction_state(0), ContactNodes::slip);
  const NodeDirections directions = nodes.directions(0, 0.);
  ASSERT_EQ(directions.size, 3u);
  const NodeDirection &along  = directions.direction[1],
                      &across = directions.direction[2];
  EXPECT_NEAR(along.frame[1], 0.6, 1e-15);
  EXPECT_NEAR(along.frame[2], 0.8, 1e-15);
  EXPECT_EQ(along.value, 1.);
  EXPECT_EQ(along.coupling, 0.);
  EXPECT_NEAR(across.frame[1] * along.frame[1]
                + across.frame[2] * along.frame[2],
              0.,
              1e-15);
  EXPECT_NEAR(across.stiffness, 12.5, 1e-12);
}



// A turn of the slip direction keeps the active-set iteration going while
// the change of q across d it stands for, |q| times the change of d,
// exceeds the friction tolerance (1e-7) times the larger of |q| and the
// force c w of the node's spring over the slip scale (the largest
// displacement |(u.nu, s)| of a frictional node). Tresca, g = 1, |q| = 5, c w =
// 50: at a scale of 1e-3 (c w scale = 0.05, below |q|) a turn of 1e-6 counts
// and one of 5e-8 does not; at a scale of 10 (c w scale = 500) the turn must
// exceed 1e-5: 1e-6 does not count, 1e-4 does. (A node of a small bound on the
// frictional cube at 108k dofs turned by about 1e-6 in every iteration while
// its displacement stood still to 1e-12, and the step ran out of iterations.)
TEST(Friction, ATurnCountsByTheChangeOfQItStandsFor)
{
  ContactNodes nodes = pressed_tresca_node_3d();
  // The slip direction at the angle given, against the one before.
  const auto turns = [&nodes](const double angle, const double scale) {
    nodes.r[0] = scale;
    nodes.t[0] = {{5 * std::cos(angle), 5 * std::sin(angle)}};
    return nodes.update_all_pieces(MPI_COMM_SELF)[2];
  };
  turns(0., 1e-3);
  ASSERT_EQ(nodes.friction_state(0), ContactNodes::slip);
  EXPECT_EQ(turns(1e-6, 1e-3), 1u);
  EXPECT_EQ(turns(1.05e-6, 1e-3), 0u);
  EXPECT_EQ(turns(2.05e-6, 10.), 0u);
  EXPECT_EQ(turns(1.0205e-4, 10.), 1u);
  EXPECT_EQ(nodes.friction_state(0), ContactNodes::slip);
}



// The slip scale is a displacement, not a gap: beside the node above
// (u.nu = 1e-3), a frictional node out of contact at the gap 10 of a curved
// obstacle (u.nu = 0, r = -10) leaves the scale at 1e-3, so a turn of 1e-6
// still counts (measured against the largest |r|, 10, it would not).
TEST(Friction, TheSlipScaleIgnoresTheGapsOfFreeNodes)
{
  const ContactLaws signorini(ContactLaw({}, {0.}, {}, true, 0.));
  ContactNodes      nodes;
  nodes.reinit(signorini, {0, 0}, {0.5, 0.5});
  nodes.set_friction({std::make_shared<TrescaFriction>()}, {2, 2}, {1., 1.});
  nodes.set_parameters({100., 100.});
  const double gap              = 10;
  const double displacements[3] = {0, 0, 0};
  const double fixed_forces[3]  = {0, 0, 0};
  nodes.store_solution(1,
                       gap,
                       nodes.directions(1, gap),
                       displacements,
                       fixed_forces);
  ASSERT_EQ(nodes.r[1], -gap);
  nodes.z[0]       = 10;
  nodes.r[0]       = 1e-3;
  const auto turns = [&nodes](const double angle) {
    nodes.t[0] = {{5 * std::cos(angle), 5 * std::sin(angle)}};
    return nodes.update_all_pieces(MPI_COMM_SELF)[2];
  };
  turns(0.);
  ASSERT_EQ(nodes.friction_state(0), ContactNodes::slip);
  ASSERT_NE(nodes.friction_state(1), ContactNodes::slip);
  EXPECT_EQ(turns(1e-6), 1u);
  EXPECT_EQ(turns(1.05e-6), 0u);
}



// A diagonal compliance decouples the nodes: every node has a closed-form
// answer. Five nodes cover the four pieces.
TEST(ActiveSetSolver, DecoupledNodesMatchClosedForm)
{
  const DecoupledNodes       nodes;
  const std::vector<double> &d = nodes.d, &w = nodes.w;
  const unsigned int         m = nodes.m;
  const FullMatrix<double>  &S = nodes.S;

  DenseActiveSet solver(benchmark_law, S, w);
  Vector<double> d_vector(d.begin(), d.end());
  const auto     result = solver.solve(d_vector, 50, 1e-12);
  ASSERT_TRUE(result.converged);
  for (unsigned int i = 0; i < m; ++i)
    EXPECT_NEAR(solver.nodes.z[i], decoupled_force(d[i], S(i, i), w[i]), 1e-13);
  EXPECT_NEAR(solver.nodes.r[4], 0.01, 1e-15);

  // Warm start: the same data again is solved in one iteration, with the
  // LU factorisation of the unchanged active set reused.
  const unsigned int factorizations = solver.system.n_factorizations();
  EXPECT_EQ(solver.solve(d_vector, 50, 1e-12).iterations(), 1u);
  EXPECT_EQ(solver.system.n_factorizations(), factorizations);
}



// A memory pressure m_i per node moves node i's law up by m_i: the five
// decoupled nodes, each with its own m_i, end on the graph p(r) + m_i with
// r = d - S z (below the rigid limit), or at r = g with at least
// p(g-) + m_i; the node out of contact (d < 0) is pressed by its memory
// alone, z = w m, without penetrating. The same on the full space path:
// ContactNodes::directions() gives the free normal force w (o + m + s r).
TEST(ActiveSetSolver, MemoryPressureMovesTheLawUp)
{
  const DecoupledNodes       nodes;
  const std::vector<double> &d = nodes.d, &w = nodes.w;
  const FullMatrix<double>  &S      = nodes.S;
  const std::vector<double>  memory = {0.5, 0.25, 1.0, 0.75, 0.1};

  DenseActiveSet solver(benchmark_law, S, w);
  solver.nodes.set_history_pressure(memory);
  Vector<double> d_vector(d.begin(), d.end());
  const auto     result = solver.solve(d_vector, 50, 1e-12);
  ASSERT_TRUE(result.converged);
  const ContactLaw &law = benchmark_law;
  for (unsigned int i = 0; i < nodes.m; ++i)
    {
      const double z = solver.nodes.z[i], r = solver.nodes.r[i];
      EXPECT_NEAR(r, d[i] - S(i, i) * z, 1e-14) << "node " << i;
      if (solver.nodes.current_piece(i).rigid)
        {
          EXPECT_NEAR(r, law.gap(), 1e-14);
          EXPECT_GE(z / w[i], law.compliance_pressure(law.gap()) + memory[i]);
          EXPECT_NEAR(solver.nodes.compliance_pressure(i),
                      law.compliance_pressure(law.gap()) + memory[i],
                      1e-12);
        }
      else
        EXPECT_NEAR(z / w[i], law.compliance_pressure(r) + memory[i], 1e-10)
          << "node " << i;
    }
  // Out of contact: pressed by the memory, r = d - S w m < 0.
  EXPECT_NEAR(solver.nodes.z[0], w[0] * memory[0], 1e-14);
  EXPECT_LT(solver.nodes.r[0], 0.);
  EXPECT_EQ(solver.nodes.status(0), 1u);
  // The free normal direction of a node on a sloped piece carries the
  // memory in its constant force.
  const unsigned int node = 1; // on the c1 piece
  ASSERT_FALSE(solver.nodes.current_piece(node).vertical);
  const NodeDirections directions = solver.nodes.directions(node, 0.);
  EXPECT_NEAR(directions.direction[0].value,
              w[node]
                * (solver.nodes.current_piece(node).intercept + memory[node]),
              1e-15);
}



// The memory's history over a few steps (normal_memory.h) against the
// formula written out here: two terms (a fading and a permanent one), a
// repeated step with another length that does not count, the kernel's
// integral, and the history as nodal variables.
TEST(NormalMemory, ExplicitHistoryOfTwoTerms)
{
  NormalMemory::Kernel kernel{{500., 100.}, {2., 0.}};
  EXPECT_NEAR(kernel.integral(0.5),
              500. * (1 - std::exp(-1.)) / 2. + 100. * 0.5,
              1e-12);
  NormalMemory memory;
  memory.reinit({NormalMemory::Kernel{}, kernel}, {1, 0, 1});
  EXPECT_TRUE(memory.active());
  EXPECT_EQ(memory.n_variables(), 3u);
  EXPECT_EQ(memory.n_nodal_fields(2), 2u);
  EXPECT_EQ(memory.n_nodal_fields(3), 1u);
  memory.accept_step({0.002, 0.5, -0.001}); // r_0: penetrated, -, lifted off

  double h1 = 0, h2 = 0, r = 0.002;
  for (const double k : {0.1, 0.05, 0.2})
    {
      // A first attempt with twice the step, then the step taken.
      memory.start_step(2 * k);
      const std::vector<double> m = memory.start_step(k);
      h1 = std::exp(-2 * k) * h1 + 500. * (1 - std::exp(-2 * k)) / 2. * r;
      h2 = h2 + 100. * k * r;
      EXPECT_NEAR(m[0], h1 + h2, 1e-13);
      EXPECT_EQ(m[1], 0.); // a zone without memory
      EXPECT_EQ(m[2], 0.); // never penetrated
      r = 0.001 + k;
      memory.accept_step({r, 0.5, -1.});
    }
  EXPECT_NEAR(memory.variable(0, 0), h1, 1e-13);
  EXPECT_NEAR(memory.variable(0, 1), h2, 1e-13);
  EXPECT_EQ(memory.variable(0, 2), r);
  // Restored variables give the same next step.
  NormalMemory restored;
  restored.reinit({NormalMemory::Kernel{}, kernel}, {1, 0, 1});
  for (unsigned int v = 0; v < 3; ++v)
    restored.set_variable(0, v, memory.variable(0, v));
  EXPECT_EQ(restored.start_step(0.1)[0], memory.start_step(0.1)[0]);
}



// The adhesive branch of a law (contact_law.h): for Signorini's condition
// with gap 0 it is the whole law below r = 0 (the constant tension
// -gamma L below -L, the slope gamma up to 0); on the benchmark law it
// replaces the zero pressure below r = 0 and the rest stays. Scaled by a
// node's beta^2, the pieces keep their intervals and find_piece() finds
// the point of the scaled graph.
TEST(ContactLaw, AdhesiveBranchBelowZero)
{
  const AdhesiveBranch glue{1000., 0.01};
  const ContactLaw     glued({}, {0.}, {}, true, 0., glue);
  ASSERT_EQ(glued.n_pieces(), 3u);
  EXPECT_TRUE(glued.has_adhesion());
  EXPECT_TRUE(glued.piece(0).adhesive && glued.piece(1).adhesive);
  EXPECT_EQ(glued.piece(0).r_upper, -0.01);
  EXPECT_EQ(glued.piece(0).intercept, -10.);
  EXPECT_EQ(glued.piece(1).slope, 1000.);
  EXPECT_TRUE(glued.piece(2).rigid);
  EXPECT_EQ(glued.piece(2).p_lower, 0.);
  EXPECT_EQ(glued.steepest_softening(), 0.);

  const ContactLaw benchmark({0., 0.006},
                             {0., 300., -100.},
                             {0., 0.},
                             true,
                             0.01,
                             glue);
  ASSERT_EQ(benchmark.n_pieces(), benchmark_law.n_pieces() + 1);
  for (unsigned int i = 2; i < benchmark.n_pieces(); ++i)
    EXPECT_TRUE(benchmark.piece(i) == benchmark_law.piece(i - 1)) << i;
  EXPECT_EQ(benchmark.compliance_pressure(-0.004), -4.);
  EXPECT_EQ(benchmark.compliance_pressure(-1.), -10.);

  // At beta^2 = 1/4 the graph point r = -0.004, p = -1 (bond piece) and
  // r = -0.02, p = -2.5 (tension piece), with c = 500.
  const double a = 0.25, c = 500.;
  EXPECT_EQ(glued.piece(1).scaled(a).slope, 250.);
  EXPECT_EQ(glued.piece(0).scaled(a).intercept, -2.5);
  EXPECT_TRUE(glued.piece(2).scaled(a) == glued.piece(2));
  EXPECT_EQ(glued.find_piece(-1. + c * -0.004, c, {a}), 1u);
  EXPECT_EQ(glued.find_piece(-2.5 + c * -0.02, c, {a}), 0u);
  // Unscaled, the second point's q lies on the bond piece's stretch.
  EXPECT_EQ(glued.find_piece(-2.5 + c * -0.02, c), 1u);
}



// A cohesive interface (contact_law.h, cohesive_damage.h) with K = 1000,
// T_c = 10, G_c = 0.2: delta_0 = 0.01, delta_f = 0.04, the softening slope
// -T_c / (delta_f - delta_0) = -1000/3 below r = -0.01. A node that has
// opened to m = 0.02 has T(m) = 20/3 and the secant slope T(m) / m = 1000/3
// (damage 2/3) on [-m, 0], the envelope beyond; one opened beyond delta_f
// has no tension left (damage 1). find_piece() finds the points of the
// node's own graph. With the damage from the last step the law is the
// secant and a plateau at the reached tension instead. Exponential
// softening is a polygon that encloses G_c. The history keeps the largest
// opening of its zone's nodes only.
TEST(ContactLaw, CohesiveBranchRemembersItsOpening)
{
  const ContactLaw law({}, {0.}, {}, true, 0., {}, {1000., 10., 0.2});
  ASSERT_EQ(law.n_pieces(), 4u);
  EXPECT_TRUE(law.has_cohesion());
  EXPECT_FALSE(law.has_adhesion());
  EXPECT_EQ(law.piece(0).r_upper, -0.04);
  EXPECT_NEAR(law.piece(1).slope, -1000. / 3, 1e-12);
  EXPECT_NEAR(law.piece(1).intercept + law.piece(1).slope * -0.01, -10., 1e-12);
  EXPECT_EQ(law.piece(2).slope, 1000.);
  EXPECT_TRUE(law.piece(3).rigid);
  EXPECT_NEAR(law.steepest_softening(), 1000. / 3, 1e-12);
  EXPECT_EQ(law.damage(0.005), 0.);
  EXPECT_NEAR(law.damage(0.02), 2. / 3, 1e-12);
  EXPECT_EQ(law.damage(0.05), 1.);

  const NodeLawState    opened{1., 0.02};
  const ContactLawPiece secant = law.piece(2, opened);
  EXPECT_EQ(secant.r_lower, -0.02);
  EXPECT_EQ(secant.r_upper, 0.);
  EXPECT_NEAR(secant.slope, 1000. / 3, 1e-12);
  EXPECT_EQ(secant.intercept, 0.);
  EXPECT_EQ(law.piece(1, opened).r_upper, -0.02);
  EXPECT_EQ(law.piece(1, opened).slope, law.piece(1).slope);
  EXPECT_TRUE(law.piece(0, opened) == law.piece(0));
  // Before the reached opening passes delta_0 the elastic piece is its own
  // secant.
  EXPECT_TRUE(law.piece(2, {1., 0.005}) == law.piece(2));

  // r = -0.018: on the secant p = -6 (q = -24 with c = 1000); the intact
  // law has q = -24 on its softening piece. r = -0.03: on the envelope.
  const double c = 1000.;
  EXPECT_EQ(law.find_piece(-6. + c * -0.018, c, opened), 2u);
  EXPECT_EQ(law.find_piece(-6. + c * -0.018, c), 1u);
  EXPECT_EQ(law.find_piece(-10. / 3 + c * -0.03, c, opened), 1u);
  EXPECT_EQ(law.find_piece(c * -0.05, c, opened), 0u);

  // Opened beyond delta_f: the pieces within the opening shrink to the
  // point r = -m, and no piece carries a tension.
  const NodeLawState broken{1., 0.05};
  EXPECT_EQ(law.piece(0, broken).r_upper, -0.05);
  EXPECT_EQ(law.piece(1, broken).r_lower, -0.05);
  EXPECT_EQ(law.piece(1, broken).r_upper, -0.05);
  EXPECT_EQ(law.piece(2, broken).slope, 0.);
  EXPECT_EQ(law.find_piece(c * -0.03, c, broken), 2u);

  // With the damage from the last step: the plateau at T(m*) beyond
  // m* = max(m, delta_0), the point r = -m*, the secant; no softening.
  const ContactLaw lagged({}, {0.}, {}, true, 0., {}, {1000., 10., 0.2, true});
  EXPECT_EQ(lagged.steepest_softening(), 0.);
  for (const double m : {0., 0.005, 0.02, 0.05})
    {
      const double reached = std::max(m, 0.01);
      const double tension = m < 0.04 ? 10. * (0.04 - reached) / 0.03 : 0.;
      const NodeLawState    node{1., m};
      const ContactLawPiece plateau = lagged.piece(0, node);
      const ContactLawPiece point   = lagged.piece(1, node);
      const ContactLawPiece chord   = lagged.piece(2, node);
      EXPECT_EQ(plateau.slope, 0.) << m;
      EXPECT_NEAR(plateau.intercept, -tension, 1e-12) << m;
      EXPECT_EQ(plateau.r_upper, -reached) << m;
      EXPECT_EQ(point.r_lower, -reached) << m;
      EXPECT_EQ(point.r_upper, -reached) << m;
      EXPECT_EQ(chord.r_lower, -reached) << m;
      EXPECT_EQ(chord.r_upper, 0.) << m;
      EXPECT_NEAR(chord.slope * reached, tension, 1e-12) << m;
      // Beyond m* the node holds the plateau's tension.
      EXPECT_EQ(lagged.find_piece(-tension + c * -(reached + 0.01), c, node),
                0u)
        << m;
    }

  // Exponential softening: the polygon from (delta_0, T_c) down through
  // T_c exp(-x / lambda) encloses G_c exactly; its pieces follow it, and
  // the damage at a reached opening is that of the polygon.
  CohesiveBranch exponential{1000., 10., 0.2};
  exponential.exponential = true;
  const auto points       = cohesive_envelope(exponential);
  ASSERT_EQ(points.size(), CohesiveBranch::exponential_pieces + 2);
  EXPECT_EQ(points[1][0], 0.01);
  EXPECT_EQ(points[1][1], 10.);
  double area = 0;
  for (unsigned int k = 0; k + 1 < points.size(); ++k)
    {
      area += (points[k + 1][0] - points[k][0])
              * (points[k][1] + points[k + 1][1]) / 2;
      EXPECT_GT(points[k + 1][0], points[k][0]);
      if (k > 0)
        {
          EXPECT_LT(points[k + 1][1], points[k][1]);
        }
    }
  EXPECT_NEAR(area, 0.2, 1e-14);
  // lambda = (G_c - T_c delta_0 / 2) / T_c = 0.015: the second point lies
  // on T_c exp(-x / lambda') with the tail stretched by a factor near 1.
  const double stretch = (points[2][0] - 0.01) / (0.015 * std::log(1000.) / 15);
  EXPECT_NEAR(points[2][1], 10. * std::exp(-std::log(1000.) / 15), 1e-12);
  EXPECT_NEAR(stretch, 1., 0.05);
  const ContactLaw curved({}, {0.}, {}, true, 0., {}, exponential);
  ASSERT_EQ(curved.n_pieces(), points.size() + 1);
  const double middle        = (points[5][0] + points[6][0]) / 2;
  const double tension_there = (points[5][1] + points[6][1]) / 2;
  EXPECT_NEAR(curved.damage(middle),
              1 - tension_there / (1000. * middle),
              1e-12);
  // The elastic piece last, the steepest softening right after the peak.
  EXPECT_NEAR(curved.piece(points.size() - 1).slope, 1000., 1e-12);
  EXPECT_NEAR(curved.steepest_softening(),
              -curved.piece(points.size() - 2).slope,
              1e-12);

  CohesiveDamage damage;
  damage.reinit({false, true}, {1, 0, 1});
  EXPECT_TRUE(damage.active());
  ContactNodes nodes;
  nodes.reinit(ContactLaws({ContactLaw({}, {0.}, {}, true, 0.), law}),
               {1, 0, 1},
               {1., 1., 1.});
  for (const std::array<double, 3> &r :
       {std::array<double, 3>{{-0.02, -0.02, 0.001}},
        std::array<double, 3>{{-0.01, -0.03, -0.005}}})
    {
      nodes.r.assign(r.begin(), r.end());
      damage.accept_step(nodes);
    }
  damage.start_step(0.1, nodes);
  EXPECT_TRUE(nodes.has_cohesion());
  EXPECT_EQ(nodes.reached_opening(0), 0.02); // the largest, not the last
  EXPECT_EQ(nodes.reached_opening(1), 0.);   // no cohesive interface
  EXPECT_EQ(nodes.reached_opening(2), 0.005);
  EXPECT_NEAR(nodes.damage(0), 2. / 3, 1e-12);
  EXPECT_EQ(nodes.damage(1), 0.);
}



// The bonding's explicit step (bonding_field.h) against the formula written
// out here: it holds below the adhesion energy, falls with the separation,
// never grows (a node pressed or back in contact keeps its bonding), stops
// at 0, and is restored from its variables; zones without adhesion keep
// beta = 1.
TEST(BondingField, ExplicitDebonding)
{
  const BondingField::Law glue{1000., 0.01, 0.001, 10.};
  // beta gamma R^2 = 0.9 * 1000 * 0.005^2 = 0.0225 > epsilon: beta at the
  // end of the step, (beta + k kappa eps) / (1 + k kappa gamma R^2).
  EXPECT_NEAR(glue.evolve(0.9, -0.005, 0.1),
              (0.9 + 0.1 * 10. * 0.001) / (1 + 0.1 * 10. * 0.025),
              1e-15);
  EXPECT_EQ(glue.evolve(0.9, -0.0005, 0.1), 0.9); // below the energy
  EXPECT_EQ(glue.evolve(0.9, 0.003, 0.1), 0.9);   // pressed
  // Beyond L the separation counts as L; however long the step, beta stays
  // above the level eps / (gamma L^2) = 0.01 where the ODE levels off.
  EXPECT_EQ(glue.evolve(0.5, -1., 0.1), glue.evolve(0.5, -0.01, 0.1));
  EXPECT_NEAR(glue.evolve(0.5, -1., 10.), 0.6 / 11., 1e-15);
  EXPECT_GT(glue.evolve(0.5, -1., 1e6), 0.01);
  EXPECT_LT(glue.evolve(0.5, -1., 1e6), 0.0101);

  BondingField field;
  field.reinit({BondingField::Law{}, glue}, {1, 0, 1}, {0.8, 0.3, 1.});
  EXPECT_TRUE(field.active());
  EXPECT_EQ(field.n_nodal_fields(2), 1u);
  EXPECT_EQ(field.variable(1, 0), 1.); // no adhesion in zone 0
  ContactNodes nodes;
  nodes.reinit(ContactLaw({}, {0.}, {}, true, 0.), {0, 0, 0}, {1., 1., 1.});
  field.accept_step({-0.005, -0.005, 0.});
  double beta = 0.8;
  for (const double k : {0.1, 0.05})
    {
      field.start_step(2 * k, nodes); // an attempt that is not accepted
      field.start_step(k, nodes);
      beta = glue.evolve(beta, -0.005, k);
      EXPECT_EQ(field.bonding(0), beta);
      EXPECT_EQ(nodes.bonding(0), beta);
      EXPECT_EQ(nodes.law_state(0).adhesion_scale, beta * beta);
      EXPECT_EQ(nodes.bonding(1), 1.);
      EXPECT_EQ(nodes.bonding(2), 1.); // never separated
      field.accept_step({-0.005, -0.005, 0.});
    }
  BondingField restored;
  restored.reinit({BondingField::Law{}, glue}, {1, 0, 1}, {1., 1., 1.});
  for (unsigned int i = 0; i < 3; ++i)
    for (unsigned int v = 0; v < 2; ++v)
      restored.set_variable(i, v, field.variable(i, v));
  ContactNodes other;
  other.reinit(ContactLaw({}, {0.}, {}, true, 0.), {0, 0, 0}, {1., 1., 1.});
  restored.start_step(0.1, other);
  field.start_step(0.1, nodes);
  EXPECT_EQ(other.bonding(0), nodes.bonding(0));
}



// Archard's wear (archard_wear.h): w += k_w max(p, 0) |slip| per accepted
// step, with the node's own pressure and slip; a frictionless node, a node
// of a zone without wear, a lifted node and a sticking one do not wear;
// the depths reach the gaps through ContactNodes::wear().
TEST(ArchardWear, DepthGrowsWithPressureTimesSlip)
{
  const ContactLaw signorini({}, {0.}, {}, true, 0.);
  ContactNodes     nodes;
  nodes.reinit(ContactLaws({signorini, signorini}),
               {0, 0, 0, 1},
               {0.5, 0.5, 0.5, 0.5});
  const FrictionLaw coulomb = std::make_shared<CoulombFriction>(0.3);
  nodes.set_friction({coulomb, coulomb}, {1, 1, 0, 1}, {0., 0., 0., 0.});
  ArchardWear wear;
  wear.reinit({0.01, 0.}, {0, 0, 0, 1});
  ASSERT_TRUE(wear.active());
  EXPECT_EQ(wear.n_nodal_fields(2), 1u);
  // Node 0 pressed (z / w = 4) and slipping by 0.03, node 1 lifted
  // (z = -1), node 2 frictionless, node 3 in a zone without wear.
  nodes.z = {2., -0.5, 2., 2.};
  nodes.accept_slip({{{0.03, 0.}}, {{0.03, 0.}}, {{0., 0.}}, {{0.03, 0.}}});
  wear.accept_step(nodes);
  wear.apply_accepted(nodes);
  EXPECT_NEAR(nodes.wear(0), 0.01 * 4. * 0.03, 1e-17);
  EXPECT_EQ(nodes.wear(1), 0.);
  EXPECT_EQ(nodes.wear(2), 0.);
  EXPECT_EQ(nodes.wear(3), 0.);
  // A second step: 0.04 more in the other direction, at z / w = 2.
  nodes.z = {1., 1., 1., 1.};
  nodes.accept_slip({{{-0.01, 0.}}, {{0.03, 0.}}, {{0., 0.}}, {{0.03, 0.}}});
  wear.accept_step(nodes);
  wear.start_step(0.1, nodes);
  EXPECT_NEAR(nodes.wear(0), 0.0012 + 0.01 * 2. * 0.04, 1e-17);
  EXPECT_EQ(nodes.wear(1), 0.); // no slip in this step
  EXPECT_EQ(wear.variable(0, 0), nodes.wear(0));
}



// Decoupled nodes pulled off a glued support (d < 0) by the condensed active
// set: each on the bond piece with its own beta, z = w a (d - S z), so
// z = w a d / (1 + w a S) with a = gamma beta^2, or on the tension piece
// (z = -w a L) where that would take r below -L; a node pressed (d > 0)
// at the rigid limit.
TEST(ActiveSetSolver, GluedNodesPulledWithTheirOwnBonding)
{
  const DecoupledNodes      nodes;
  const std::vector<double> w     = nodes.w;
  const FullMatrix<double> &S     = nodes.S;
  const std::vector<double> d     = {-0.001, -0.004, -0.03, 0.002, -0.002};
  const std::vector<double> beta  = {1., 0.5, 0.9, 0.7, 0.};
  const double              gamma = 1000., L = 0.01;
  const ContactLaw          glued({}, {0.}, {}, true, 0., {gamma, L});

  DenseActiveSet solver(glued, S, w);
  solver.nodes.set_bonding(beta);
  Vector<double> d_vector(d.begin(), d.end());
  ASSERT_TRUE(solver.solve(d_vector, 50, 1e-12).converged);
  for (const unsigned int i : {0u, 1u, 4u})
    {
      const double a        = gamma * beta[i] * beta[i];
      const double expected = w[i] * a * d[i] / (1 + w[i] * a * S(i, i));
      EXPECT_NEAR(solver.nodes.z[i], expected, 1e-13 * std::abs(expected))
        << "node " << i;
    }
  EXPECT_NEAR(solver.nodes.z[2], -w[2] * gamma * 0.81 * L, 1e-15);
  EXPECT_LT(solver.nodes.r[2], -L);
  EXPECT_TRUE(solver.nodes.current_piece(3).rigid);
  EXPECT_NEAR(solver.nodes.z[3], d[3] / S(3, 3), 1e-12);
  // Held by the glue while bonded and closer than L; node 2 is beyond L,
  // node 4 has no bond left.
  EXPECT_EQ(solver.nodes.status(1), 1u);
  EXPECT_EQ(solver.nodes.status(2), 0u);
  EXPECT_EQ(solver.nodes.status(4), 0u);
}



// Contact zones: the decoupled nodes alternately on the benchmark law and
// on Signorini's condition with gap 0.004 (r <= g: z = 0 below it,
// z = (d - g) / S_ii at it) each reach the closed form of their own law,
// and the pieces are those of their zone's part of the table.
TEST(ActiveSetSolver, ZonesFollowTheirOwnLaws)
{
  const DecoupledNodes            nodes;
  const std::vector<double>      &d = nodes.d, &w = nodes.w;
  const FullMatrix<double>       &S = nodes.S;
  const ContactLaw                signorini({}, {0.}, {}, true, 0.004);
  const ContactLaws               laws({benchmark_law, signorini});
  const std::vector<unsigned int> zones = {0, 1, 0, 1, 0};

  DenseActiveSet solver(laws, S, w, zones);
  Vector<double> d_vector(d.begin(), d.end());
  ASSERT_TRUE(solver.solve(d_vector, 50, 1e-12).converged);
  for (unsigned int i = 0; i < nodes.m; ++i)
    {
      EXPECT_EQ(laws.zone_of_piece(solver.nodes.piece(i)), zones[i]);
      const double expected = zones[i] == 0
                                ? decoupled_force(d[i], S(i, i), w[i])
                                : std::max(0., (d[i] - 0.004) / S(i, i));
      EXPECT_NEAR(solver.nodes.z[i], expected, 1e-13) << "node " << i;
    }
  // Node 1 (d = 0.002) is short of the gap, node 3 (d = 0.009) at it.
  EXPECT_FALSE(solver.nodes.current_piece(1).rigid);
  EXPECT_TRUE(solver.nodes.current_piece(3).rigid);
  EXPECT_EQ(solver.nodes.status(3), 2u);
  const std::vector<double> forces = solver.nodes.zone_forces(MPI_COMM_SELF);
  EXPECT_NEAR(forces[0],
              solver.nodes.z[0] + solver.nodes.z[2] + solver.nodes.z[4],
              1e-14);
  EXPECT_NEAR(forces[1], solver.nodes.z[1] + solver.nodes.z[3], 1e-14);
}



// The table of pieces of several zones: zone by zone, each piece found
// through its zone's law.
TEST(ContactLaw, ZonesShareOneTableOfPieces)
{
  const ContactLaw   signorini({}, {0.}, {}, true, 0.004);
  const ContactLaws  laws({benchmark_law, signorini});
  const unsigned int first = benchmark_law.n_pieces();
  ASSERT_EQ(laws.n_zones(), 2u);
  ASSERT_EQ(laws.n_pieces(), first + signorini.n_pieces());
  for (unsigned int p = 0; p < laws.n_pieces(); ++p)
    EXPECT_EQ(laws.zone_of_piece(p), p < first ? 0u : 1u);
  EXPECT_TRUE(laws.piece(first + 1).rigid);
  EXPECT_EQ(laws.piece(first + 1).r_lower, 0.004);
  for (const double q : {-1., 0., 0.5, 3., 100.})
    {
      EXPECT_EQ(laws.find_piece(0, q, 1000.),
                benchmark_law.find_piece(q, 1000.));
      EXPECT_EQ(laws.find_piece(1, q, 1000.),
                first + signorini.find_piece(q, 1000.));
      EXPECT_EQ(laws.next_piece(1, first, q, 1000.),
                first + signorini.next_piece(0, q, 1000.));
    }
  EXPECT_EQ(laws.steepest_softening(), 100.);
  EXPECT_EQ(laws.largest_gap(), 0.01);
}



namespace
{
  // The decoupled nodes, their exact active-set iteration (a dense solve
  // per iteration, Tolerance 1e-12), and the same nodes again for an
  // iteration with inexact solves.
  struct EarlySolveNodes
  {
    const DecoupledNodes  nodes;
    const Vector<double>  d = Vector<double>(nodes.d.begin(), nodes.d.end());
    DenseActiveSet        exact{benchmark_law, nodes.S, nodes.w};
    DenseActiveSet        inexact{benchmark_law, nodes.S, nodes.w};
    const ActiveSetResult exact_result = exact.solve(d, 50, 1e-12);

    // The iteration with inexact solves (solve_for_pieces) must converge
    // in as many iterations as the exact one.
    void
    solve_inexact(
      const std::function<LinearSolveReport(const LinearSolveRequest &)>
        &solve_for_pieces)
    {
      const ActiveSetResult result
        = inexact.nodes.solve(solve_for_pieces, 50, 1e-12, MPI_COMM_SELF);
      ASSERT_TRUE(result.converged);
      EXPECT_EQ(result.iterations(), exact_result.iterations());
    }

    // The inexact iteration ended on the exact one's pieces, with its
    // forces off by the last solve's accuracy 1e-12, relative.
    void
    expect_exact_pieces_and_forces() const
    {
      for (unsigned int i = 0; i < nodes.m; ++i)
        {
          EXPECT_EQ(inexact.nodes.piece(i), exact.nodes.piece(i));
          EXPECT_NEAR(inexact.nodes.z[i],
                      exact.nodes.z[i],
                      2e-12 * std::abs(exact.nodes.z[i]));
        }
    }
  };
} // namespace



// Inexact early solves: a back end that solves only to the accuracy it is
// asked for (here: the exact dense solution, off by that accuracy) must be
// asked for sqrt(Tolerance) while the pieces change, then for Tolerance on
// the same pieces, and end with the exact iteration's pieces, forces and
// number of iterations.
TEST(ActiveSetSolver, InexactEarlySolvesEndAtTheExactSolution)
{
  EarlySolveNodes scene;
  ASSERT_TRUE(scene.exact_result.converged);

  std::vector<double> asked;
  scene.solve_inexact([&](const LinearSolveRequest &request) {
    const double accuracy = request.accuracy;
    asked.push_back(accuracy);
    LinearSolveReport report;
    Vector<double>    r, z;
    scene.inexact.system.solve(acting_pieces(scene.inexact.nodes),
                               scene.d,
                               r,
                               z);
    for (unsigned int i = 0; i < scene.nodes.m; ++i)
      {
        scene.inexact.nodes.r[i] = r[i] * (1 + accuracy);
        scene.inexact.nodes.z[i] = z[i] * (1 - accuracy);
      }
    report.residual = accuracy;
    return report;
  });
  // One early solve per iteration, the last one continued to the tolerance.
  ASSERT_EQ(asked.size(), scene.exact_result.iterations() + 1);
  for (unsigned int k = 0; k + 1 < asked.size(); ++k)
    EXPECT_DOUBLE_EQ(asked[k], 1e-6);
  EXPECT_DOUBLE_EQ(asked.back(), 1e-12);
  scene.expect_exact_pieces_and_forces();
}



// Going on without a restart: a back end that honours the request (as CG
// does) stores its early iterate, asks the nodes whether they stay and, if
// they do, goes on to the tolerance in the same solve. The nodes must be
// asked once per iteration, without changing their state, answer no while
// the pieces change and yes at the last iteration, which then needs no
// second solve: the exact iteration's pieces, forces and iterations, one
// solve per iteration.
TEST(ActiveSetSolver, EarlySolvesGoOnWhenThePiecesStay)
{
  EarlySolveNodes scene;
  ASSERT_TRUE(scene.exact_result.converged);

  std::vector<bool> answers;
  unsigned int      solves = 0;
  scene.solve_inexact([&](const LinearSolveRequest &request) {
    ++solves;
    Vector<double> r, z;
    scene.inexact.system.solve(acting_pieces(scene.inexact.nodes),
                               scene.d,
                               r,
                               z);
    const auto store = [&](const double accuracy) {
      for (unsigned int i = 0; i < scene.nodes.m; ++i)
        {
          scene.inexact.nodes.r[i] = r[i] * (1 + accuracy);
          scene.inexact.nodes.z[i] = z[i] * (1 - accuracy);
        }
    };
    LinearSolveReport report;
    report.residual = request.accuracy;
    store(request.accuracy);
    if (request.pieces_stay)
      {
        const std::vector<unsigned int> pieces = scene.inexact.nodes.pieces();
        answers.push_back(request.pieces_stay());
        EXPECT_EQ(scene.inexact.nodes.pieces(), pieces);
        if (answers.back())
          report.residual = request.settled_accuracy;
      }
    store(report.residual);
    return report;
  });
  EXPECT_EQ(solves, scene.exact_result.iterations());
  ASSERT_EQ(answers.size(), scene.exact_result.iterations());
  for (unsigned int k = 0; k + 1 < answers.size(); ++k)
    EXPECT_FALSE(answers[k]);
  EXPECT_TRUE(answers.back());
  scene.expect_exact_pieces_and_forces();
}



// Coupled nodes: a dense SPD compliance. Reference: try every combination of
// pieces (4^4 = 256), solve its linear system, and keep the combinations
// whose solution lies on its pieces. The problem is strongly convex here
// (the softening w |c2| is small against 1/S), so exactly one survives.
TEST(ActiveSetSolver, CoupledNodesMatchExhaustiveEnumeration)
{
  const unsigned int  m = 4;
  FullMatrix<double>  S(m, m);
  std::vector<double> w(m, 0.03125);
  for (unsigned int i = 0; i < m; ++i)
    for (unsigned int j = 0; j < m; ++j)
      S(i, j) = 0.004 * std::exp(-std::abs(double(i) - double(j)));
  const std::vector<double> d = {0.001, 0.007, 0.012, 0.02};
  Vector<double>            d_vector(d.begin(), d.end());

  std::vector<Vector<double>> solutions;
  for (unsigned int code = 0; code < 256; ++code)
    {
      std::vector<unsigned int> pieces(m);
      for (unsigned int i = 0, c = code; i < m; ++i, c /= 4)
        pieces[i] = c % 4;
      // Unknown z: rows z_i - w s_i (d - S z)_i = w o_i (sloped) or
      // (d - S z)_i = g (rigid).
      FullMatrix<double> A(m, m);
      Vector<double>     b(m), z(m);
      for (unsigned int i = 0; i < m; ++i)
        {
          const ContactLawPiece &p = benchmark_law.piece(pieces[i]);
          for (unsigned int j = 0; j < m; ++j)
            A(i, j) = (p.vertical ? S(i, j) : w[i] * p.slope * S(i, j));
          if (p.vertical)
            b[i] = d[i] - p.r_lower;
          else
            {
              A(i, i) += 1;
              b[i] = w[i] * (p.intercept + p.slope * d[i]);
            }
        }
      A.gauss_jordan();
      A.vmult(z, b);
      Vector<double> r(m);
      S.vmult(r, z);
      r.sadd(-1., 1., d_vector);
      bool consistent = true;
      for (unsigned int i = 0; i < m; ++i)
        {
          const ContactLawPiece &p   = benchmark_law.piece(pieces[i]);
          const double           tol = 1e-12;
          if (p.vertical)
            consistent = consistent && z[i] / w[i] >= p.p_lower - tol;
          else
            consistent = consistent && r[i] >= p.r_lower - tol
                         && r[i] <= p.r_upper + tol;
        }
      if (consistent)
        solutions.push_back(z);
    }
  ASSERT_EQ(solutions.size(), 1u);

  DenseActiveSet solver(benchmark_law, S, w);
  const auto     result = solver.solve(d_vector, 50, 1e-12);
  ASSERT_TRUE(result.converged);
  for (unsigned int i = 0; i < m; ++i)
    EXPECT_NEAR(solver.nodes.z[i], solutions[0][i], 1e-12);
}



namespace
{
  // The dense problem of the given pieces solved twice: by a system that
  // has solved earlier pieces (and may correct its kept factorisation for
  // the rows that changed) and by a new one, which factorises. Both must
  // find the same forces and normal displacements, up to rounding, and
  // meet the pieces' equations to the defect a factorisation leaves.
  void
  expect_same_as_new_factorisation(CondensedContactSystem          &updated,
                                   const std::vector<unsigned int> &pieces,
                                   const FullMatrix<double>        &S,
                                   const std::vector<double>       &w,
                                   const Vector<double>            &d,
                                   const ContactLaw &law = benchmark_law)
  {
    CondensedContactSystem new_system;
    new_system.reinit(law, S, w);
    Vector<double> r, z, r_new, z_new;
    const double   defect = updated.solve(acting_pieces(law, pieces), d, r, z);
    const double   new_defect
      = new_system.solve(acting_pieces(law, pieces), d, r_new, z_new);
    EXPECT_LE(new_defect, 1e-14);
    EXPECT_LE(defect, 1e-14);
    for (unsigned int i = 0; i < w.size(); ++i)
      {
        EXPECT_NEAR(z[i], z_new[i], 1e-12 * z_new.linfty_norm()) << i;
        EXPECT_NEAR(r[i], r_new[i], 1e-12 * r_new.linfty_norm()) << i;
      }
  }
} // namespace



// Changed pieces without a new factorisation: the Woodbury correction of
// the kept one for rows that changed between the pieces' kinds (a known
// force becoming unknown and back, sloped to vertical, softening to
// hardening), for changes added and taken back, must give what a new
// factorisation gives; a change of more than a quarter of the rows
// factorises again.
TEST(CondensedContactSystem, ChangedRowsAgreeWithANewFactorisation)
{
  const unsigned int  m = 60;
  FullMatrix<double>  S(m, m);
  std::vector<double> w(m);
  Vector<double>      d(m);
  for (unsigned int i = 0; i < m; ++i)
    {
      for (unsigned int j = 0; j < m; ++j)
        S(i, j) = 0.004 * std::exp(-std::abs(double(i) - double(j)) / 2);
      w[i] = 0.02 + 0.005 * (i % 3);
      d[i] = 0.02 * std::sin(0.37 * i);
    }
  // Every node on piece i % 4: out of contact (a known force), the
  // hardening and the softening slope, the rigid limit.
  std::vector<unsigned int> pieces(m);
  for (unsigned int i = 0; i < m; ++i)
    pieces[i] = i % 4;
  CondensedContactSystem system;
  system.reinit(benchmark_law, S, w);
  expect_same_as_new_factorisation(system, pieces, S, w, d);
  ASSERT_EQ(system.n_factorizations(), 1u);

  // Three nodes change kind: a known force becomes unknown, an unknown one
  // known, a sloped piece vertical.
  const std::vector<unsigned int> base = pieces;
  pieces[0]                            = 1;
  pieces[1]                            = 0;
  pieces[2]                            = 3;
  expect_same_as_new_factorisation(system, pieces, S, w, d);
  // Ten more, each to the next piece.
  for (unsigned int i = 10; i < 20; ++i)
    pieces[i] = (pieces[i] + 1) % 4;
  expect_same_as_new_factorisation(system, pieces, S, w, d);
  // The first three back as in the factorisation, one more changed.
  for (unsigned int i = 0; i < 3; ++i)
    pieces[i] = base[i];
  pieces[30] = 2;
  expect_same_as_new_factorisation(system, pieces, S, w, d);
  EXPECT_EQ(system.n_factorizations(), 1u);
  EXPECT_EQ(system.n_updated_solves(), 3u);

  // Half of the nodes change: a new factorisation.
  for (unsigned int i = 0; i < m; i += 2)
    pieces[i] = (pieces[i] + 2) % 4;
  expect_same_as_new_factorisation(system, pieces, S, w, d);
  EXPECT_EQ(system.n_factorizations(), 2u);
  EXPECT_EQ(system.n_updated_solves(), 3u);
}



namespace
{
  // The kept factorisation is for node 0 on a nearly flat piece (slope
  // `slope`, so the diagonal 1 / (w_0 slope) dwarfs the compliance), the
  // new pieces put that node at the rigid limit, where its row is the row
  // of S alone: a well-conditioned matrix, but the Woodbury correction
  // cancels the large diagonal. Returns how often the system factorised.
  unsigned int
  factorisations_after_leaving_a_nearly_flat_piece(const double slope)
  {
    const ContactLaw law({0., 0.006}, {0., slope, -100.}, {0., 0.}, true, 0.01);
    const unsigned int  m = 20;
    FullMatrix<double>  S(m, m);
    std::vector<double> w(m, 0.03);
    Vector<double>      d(m);
    for (unsigned int i = 0; i < m; ++i)
      {
        S(i, i) = 0.01;
        if (i > 0)
          S(i, i - 1) = S(i - 1, i) = 0.002;
        d[i] = 0.004 + 0.0001 * i;
      }
    std::vector<unsigned int> pieces(m, 2);
    pieces[0] = 1;
    CondensedContactSystem system;
    system.reinit(law, S, w);
    Vector<double> r, z;
    system.solve(acting_pieces(law, pieces), d, r, z);
    pieces[0] = 3;
    expect_same_as_new_factorisation(system, pieces, S, w, d, law);
    return system.n_factorizations();
  }
} // namespace



// A moderately large diagonal in the kept factorisation leaves a defect
// that one step of iterative refinement removes; a much larger one cannot
// be corrected, and the solve must notice by its defect and factorise the
// new pieces' matrix instead.
TEST(CondensedContactSystem, CancellingCorrectionIsRefinedOrReplaced)
{
  EXPECT_EQ(factorisations_after_leaving_a_nearly_flat_piece(1e-4), 1u);
  EXPECT_EQ(factorisations_after_leaving_a_nearly_flat_piece(1e-9), 2u);
}



// Nearly flat pieces: a slope below 1e-13 of the node's stiffness
// 1 / (w_i S_ii) is flat (a known force), so slopes down to 1e-300 give the
// forces of the flat piece (to 1e-12 relative), finite and with a defect
// at rounding level; slightly above the threshold the defect, measured in
// the node's stiffness, is at rounding level too (before, the residual in r
// divided the pressure's rounding by the slope, and c2 = 1e-6 could never
// meet 1e-10).
TEST(CondensedContactSystem, NearlyFlatPiecesSolveToRounding)
{
  const unsigned int  m = 20;
  FullMatrix<double>  S(m, m);
  std::vector<double> w(m, 0.03);
  Vector<double>      d(m);
  for (unsigned int i = 0; i < m; ++i)
    {
      S(i, i) = 0.01;
      if (i > 0)
        S(i, i - 1) = S(i - 1, i) = 0.002;
      d[i] = 0.008 + 0.0001 * i;
    }
  // Every node on the second piece, r > 0.006, with slope c2.
  const auto solve = [&](const double c2, Vector<double> &z) {
    const ContactLaw law({0., 0.006}, {0., 300., c2}, {0., 0.}, true, 0.01);
    CondensedContactSystem system;
    system.reinit(law, S, w);
    Vector<double> r;
    return system.solve(acting_pieces(law, std::vector<unsigned int>(m, 2)),
                        d,
                        r,
                        z);
  };
  Vector<double> flat, z;
  EXPECT_LT(solve(0., flat), 1e-14);
  for (const double c2 : {1e-300, 1e-100, 1e-20})
    {
      EXPECT_LT(solve(c2, z), 1e-14) << "c2 = " << c2;
      for (unsigned int i = 0; i < m; ++i)
        EXPECT_NEAR(z[i], flat[i], 1e-12 * std::abs(flat[i])) << "c2 = " << c2;
    }
  for (const double c2 : {1e-9, 1e-6, 1e-3})
    EXPECT_LT(solve(c2, z), 1e-13) << "c2 = " << c2;
}



// The condensation on a finite element problem: the plane-stress benchmark
// body (6 x 6 squares split into triangles, clamped at x = 0, pressed down
// by (0, -15) on the top, the benchmark law on the bottom). Reference: with
// the pieces the active-set method ends on, the full-space system
// (K + sum_sloped w s nu nu^T) u = b - sum_sloped w o nu, with u . nu = g
// imposed at the nodes at the rigid limit, solved directly. Then, from the
// residual of the unmodified system, the KKT conditions of the contact
// problem are checked on their own: r <= g everywhere, the foundation force
// is >= 0 at the rigid limit, and every node lies on the law's graph.
TEST(ActiveSetSolver, CondensationMatchesFullSpaceSolveAndKKT)
{
  const unsigned int dim = 2;
  Triangulation<dim> triangulation;
  GridGenerator::subdivided_hyper_cube_with_simplices(triangulation, 6);
  for (const auto &face : triangulation.active_face_iterators())
    if (face->at_boundary())
      {
        const Point<dim> c = face->center();
        face->set_boundary_id(c[0] < 1e-12       ? 0
                              : c[1] < 1e-12     ? 2
                              : c[1] > 1 - 1e-12 ? 3
                                                 : 1);
      }
  const ReferenceCell cell_type = ReferenceCells::get_simplex<dim>();
  const Mapping<dim> &mapping   = cell_type.get_default_linear_mapping<dim>();
  const FESystem<dim> fe(FE_SimplexP<dim>(1), dim);
  DoFHandler<dim>     dof_handler(triangulation);
  dof_handler.distribute_dofs(fe);
  const unsigned int n = dof_handler.n_dofs();

  AffineConstraints<double> constraints;
  VectorTools::interpolate_boundary_values(mapping,
                                           dof_handler,
                                           0,
                                           Functions::ZeroFunction<dim>(dim),
                                           constraints);
  constraints.close();
  DynamicSparsityPattern dsp(n);
  DoFTools::make_sparsity_pattern(dof_handler, dsp, constraints, false);
  SparsityPattern sparsity;
  sparsity.copy_from(dsp);
  SparseMatrix<double> K(sparsity);
  Vector<double>       b(n);

  // Stiffness and the traction load, as the program assembles them.
  const PerzynaMaterial<dim> material = benchmark_material<dim>();
  const auto quadrature = cell_type.get_gauss_type_quadrature<dim>(1);
  const auto face_quadrature
    = cell_type.face_reference_cell(0).get_gauss_type_quadrature<dim - 1>(2);
  FEValues<dim>                        fe_values(mapping,
                          fe,
                          quadrature,
                          update_gradients | update_JxW_values);
  FEFaceValues<dim>                    fe_face_values(mapping,
                                   fe,
                                   face_quadrature,
                                   update_values | update_JxW_values);
  const FEValuesExtractors::Vector     displacement(0);
  FullMatrix<double>                   cell_matrix(6, 6);
  Vector<double>                       cell_rhs(6);
  std::vector<types::global_dof_index> indices(6);
  for (const auto &cell : dof_handler.active_cell_iterators())
    {
      fe_values.reinit(cell);
      cell_matrix = 0;
      cell_rhs    = 0;
      for (unsigned int i = 0; i < 6; ++i)
        for (unsigned int j = 0; j < 6; ++j)
          cell_matrix(i, j)
            = (material.elasticity_tensor()
               * fe_values[displacement].symmetric_gradient(j, 0))
              * fe_values[displacement].symmetric_gradient(i, 0)
              * fe_values.JxW(0);
      for (const unsigned int f : cell->face_indices())
        if (cell->face(f)->at_boundary() && cell->face(f)->boundary_id() == 3)
          {
            fe_face_values.reinit(cell, f);
            for (unsigned int q = 0; q < face_quadrature.size(); ++q)
              for (unsigned int i = 0; i < 6; ++i)
                if (fe.system_to_component_index(i).first == 1)
                  cell_rhs(i) += -15. * fe_face_values.shape_value(i, q)
                                 * fe_face_values.JxW(q);
          }
      cell->get_dof_indices(indices);
      constraints.distribute_local_to_global(cell_matrix,
                                             cell_rhs,
                                             indices,
                                             K,
                                             b);
    }

  // The free contact nodes (normal (0,-1): r = -u_y) and their weights.
  VectorType weights(complete_index_set(n), MPI_COMM_SELF), normals(weights);
  assemble_lumped_weights<dim>(hp::MappingCollection<dim>(mapping),
                               dof_handler,
                               hp::QCollection<dim - 1>(face_quadrature),
                               {2},
                               weights,
                               normals);
  std::vector<types::global_dof_index> y_dof;
  std::vector<double>                  w;
  for (const auto &cell : dof_handler.active_cell_iterators())
    for (const unsigned int v : cell->vertex_indices())
      if (weights(cell->vertex_dof_index(v, 0)) > 0
          && !constraints.is_constrained(cell->vertex_dof_index(v, 1))
          && std::find(y_dof.begin(), y_dof.end(), cell->vertex_dof_index(v, 1))
               == y_dof.end())
        {
          y_dof.push_back(cell->vertex_dof_index(v, 1));
          w.push_back(weights(cell->vertex_dof_index(v, 0)));
        }
  const unsigned int m = y_dof.size();
  ASSERT_EQ(m, 6u);

  // Condensed: S = N K^{-1} N^T, d = N K^{-1} b, active set, u.
  SparseDirectUMFPACK K_inverse;
  K_inverse.initialize(K);
  FullMatrix<double> S(m, m);
  for (unsigned int j = 0; j < m; ++j)
    {
      Vector<double> column(n);
      column[y_dof[j]] = -1.;
      K_inverse.solve(column);
      for (unsigned int i = 0; i < m; ++i)
        S(i, j) = -column[y_dof[i]];
    }
  Vector<double> u_free = b;
  K_inverse.solve(u_free);
  Vector<double> d(m);
  for (unsigned int i = 0; i < m; ++i)
    d[i] = -u_free[y_dof[i]];
  DenseActiveSet solver(benchmark_law, S, w);
  ASSERT_TRUE(solver.solve(d, 50, 1e-12).converged);
  Vector<double> u_condensed = b;
  for (unsigned int i = 0; i < m; ++i)
    u_condensed[y_dof[i]] += solver.nodes.z[i]; // b - N^T z
  K_inverse.solve(u_condensed);

  // Full space with the final pieces.
  SparseMatrix<double> K_full(sparsity);
  K_full.copy_from(K);
  Vector<double>                            b_full = b, u_full(n);
  std::map<types::global_dof_index, double> rigid_values;
  unsigned int                              n_rigid = 0;
  for (unsigned int i = 0; i < m; ++i)
    {
      const ContactLawPiece &p = benchmark_law.piece(solver.nodes.piece(i));
      if (p.vertical)
        {
          rigid_values[y_dof[i]] = -p.r_lower;
          ++n_rigid;
        }
      else
        {
          K_full.add(y_dof[i], y_dof[i], w[i] * p.slope);
          b_full[y_dof[i]] += w[i] * p.intercept;
        }
    }
  ASSERT_GT(n_rigid, 0u);
  ASSERT_LT(n_rigid, m);
  MatrixTools::apply_boundary_values(rigid_values, K_full, u_full, b_full);
  SparseDirectUMFPACK K_full_inverse;
  K_full_inverse.initialize(K_full);
  K_full_inverse.vmult(u_full, b_full);

  Vector<double> difference = u_full;
  difference -= u_condensed;
  EXPECT_LE(difference.linfty_norm(), 1e-10 * u_full.linfty_norm());

  // KKT from the residual of the unmodified system: z = (K u - b)_y.
  Vector<double> residual(n);
  K.vmult(residual, u_full);
  residual -= b;
  for (unsigned int i = 0; i < m; ++i)
    {
      const double r = -u_full[y_dof[i]], z = residual[y_dof[i]];
      EXPECT_LE(r, 0.01 + 1e-12);
      if (std::abs(r - 0.01) < 1e-12)
        EXPECT_GE(z / w[i] - benchmark_law.compliance_pressure(0.01), -1e-9);
      else
        EXPECT_NEAR(z / w[i], benchmark_law.compliance_pressure(r), 1e-9);
      EXPECT_NEAR(z, solver.nodes.z[i], 1e-9);
    }
}



// The iteration limit is honoured and reported.
TEST(ActiveSetSolver, ReportsIterationLimit)
{
  FullMatrix<double> S(2, 2);
  S(0, 0) = S(1, 1) = 0.01;
  S(0, 1) = S(1, 0) = 0.005;
  DenseActiveSet solver(benchmark_law, S, {0.03, 0.03});
  Vector<double> d(2);
  d[0] = d[1]       = 0.05;
  const auto result = solver.solve(d, 1, 1e-12);
  EXPECT_FALSE(result.converged);
  EXPECT_EQ(result.iterations(), 1u);
  EXPECT_NE(result.describe().find("iteration 1"), std::string::npos);
}



// @sect3{The simplex patterns of the generated box}
//
// Every pattern tiles the box with positively oriented simplices, gives the
// faces the colorized boundary ids, cuts the squares along the diagonals it
// names, and (all but deal.II's five tetrahedra) is nested: every simplex of
// the box with 2n subdivisions lies inside one simplex of the box with n.
namespace
{
  template <int dim>
  double
  simplex_measure(const typename Triangulation<dim>::active_cell_iterator &cell)
  {
    Tensor<2, dim> J;
    for (unsigned int a = 1; a <= dim; ++a)
      for (unsigned int d = 0; d < dim; ++d)
        J[d][a - 1] = cell->vertex(a)[d] - cell->vertex(0)[d];
    return determinant(J) / (dim == 2 ? 2. : 6.);
  }

  // Barycentric coordinates of p in the simplex.
  template <int dim>
  std::array<double, dim + 1>
  barycentric(const typename Triangulation<dim>::active_cell_iterator &cell,
              const Point<dim>                                        &p)
  {
    Tensor<2, dim> J;
    for (unsigned int a = 1; a <= dim; ++a)
      for (unsigned int d = 0; d < dim; ++d)
        J[d][a - 1] = cell->vertex(a)[d] - cell->vertex(0)[d];
    const Tensor<1, dim>        lambda = invert(J) * (p - cell->vertex(0));
    std::array<double, dim + 1> weights;
    weights[0] = 1;
    for (unsigned int a = 0; a < dim; ++a)
      {
        weights[a + 1] = lambda[a];
        weights[0] -= lambda[a];
      }
    return weights;
  }

  template <int dim>
  void
  check_pattern(const Parameters::SimplexPattern pattern,
                const unsigned int               cells_per_square,
                const bool                       nested)
  {
    const std::vector<double> lengths(dim, 1.);
    Triangulation<dim>        coarse, fine;
    create_simplex_box(coarse, lengths, 2, pattern);
    create_simplex_box(fine, lengths, 4, pattern);
    EXPECT_EQ(fine.n_active_cells(),
              cells_per_square * Utilities::pow(4u, dim));

    double volume = 0;
    for (const auto &cell : fine.active_cell_iterators())
      {
        EXPECT_GT(simplex_measure<dim>(cell), 1e-14);
        volume += simplex_measure<dim>(cell);
      }
    EXPECT_NEAR(volume, 1., 1e-12);

    std::map<types::boundary_id, double> boundary_measure;
    for (const auto &face : fine.active_face_iterators())
      if (face->at_boundary())
        boundary_measure[face->boundary_id()] += face->measure();
    EXPECT_EQ(boundary_measure.size(), 2 * dim);
    for (const auto &[id, measure] : boundary_measure)
      EXPECT_NEAR(measure, 1., 1e-12) << "boundary id " << int(id);

    if (!nested)
      return;
    for (const auto &cell : fine.active_cell_iterators())
      {
        unsigned int containing = 0;
        for (const auto &coarse_cell : coarse.active_cell_iterators())
          {
            bool inside = true;
            for (const unsigned int v : cell->vertex_indices())
              for (const double weight :
                   barycentric<dim>(coarse_cell, cell->vertex(v)))
                inside = inside && weight >= -1e-12;
            containing += inside;
          }
        EXPECT_EQ(containing, 1u);
      }
  }

  // The number of edges of the 2D mesh along the directions (1, 1) and
  // (1, -1).
  std::array<unsigned int, 2>
  count_diagonals(const Parameters::SimplexPattern pattern)
  {
    Triangulation<2> triangulation;
    create_simplex_box(triangulation, {1., 1.}, 4, pattern);
    std::array<unsigned int, 2> counts = {{0, 0}};
    for (const auto &line : triangulation.active_face_iterators())
      {
        const Tensor<1, 2> t = line->vertex(1) - line->vertex(0);
        if (std::abs(std::abs(t[0]) - std::abs(t[1])) < 1e-12)
          ++counts[t[0] * t[1] > 0 ? 0 : 1];
      }
    return counts;
  }
} // namespace

TEST(SimplexPatterns, TwoDimensional)
{
  using Pattern = Parameters::SimplexPattern;
  check_pattern<2>(Pattern::slash, 2, true);
  check_pattern<2>(Pattern::backslash, 2, true);
  check_pattern<2>(Pattern::union_jack, 2, true);
  check_pattern<2>(Pattern::crossed, 4, true);
  // 16 squares: "/" has 16 diagonals along (1,1), "\" 16 along (1,-1),
  // the union jack 8 of each, crossed 32 half-diagonals of each.
  EXPECT_EQ(count_diagonals(Pattern::slash),
            (std::array<unsigned int, 2>{{16, 0}}));
  EXPECT_EQ(count_diagonals(Pattern::backslash),
            (std::array<unsigned int, 2>{{0, 16}}));
  EXPECT_EQ(count_diagonals(Pattern::union_jack),
            (std::array<unsigned int, 2>{{8, 8}}));
  EXPECT_EQ(count_diagonals(Pattern::crossed),
            (std::array<unsigned int, 2>{{32, 32}}));
}

TEST(SimplexPatterns, ThreeDimensional)
{
  check_pattern<3>(Parameters::SimplexPattern::slash, 6, true);
  check_pattern<3>(Parameters::SimplexPattern::five_tetrahedra, 5, false);
}



// @sect3{Sparse direct solvers}
//
// A 1D-Laplacian-like matrix distributed over the ranks, made unsymmetric
// on request; the solution of A x = b for a known x, with one and with
// several right-hand sides.
namespace
{
  void
  check_direct_solver(const Parameters::DirectSolver kind, const bool symmetric)
  {
    const MPI_Comm     comm    = MPI_COMM_WORLD;
    const unsigned int n_ranks = Utilities::MPI::n_mpi_processes(comm);
    const unsigned int rank    = Utilities::MPI::this_mpi_process(comm);
    const unsigned int n       = 40;
    IndexSet           owned(n);
    owned.add_range(n * rank / n_ranks, n * (rank + 1) / n_ranks);
    DynamicSparsityPattern dsp(n, n, owned);
    for (const auto i : owned)
      for (unsigned int j = (i > 0 ? i - 1 : 0); j <= std::min(i + 1, n - 1);
           ++j)
        dsp.add(i, j);
    MatrixType A;
    A.reinit(owned, owned, dsp, comm);
    for (const auto i : owned)
      {
        A.set(i, i, 2.5 + 0.01 * i);
        if (i > 0)
          A.set(i, i - 1, symmetric ? -1. : -1.2);
        if (i + 1 < n)
          A.set(i, i + 1, -1.);
      }
    A.compress(VectorOperation::insert);

    VectorType x_true(owned, comm), b(x_true), x(x_true);
    for (const auto i : owned)
      x_true(i) = std::sin(0.3 * i) + 0.1 * i;
    A.vmult(b, x_true);

    SparseDirectSolver solver(kind, comm);
    solver.factorize(A, symmetric);
    solver.solve(x, b);
    x -= x_true;
    EXPECT_LE(x.linfty_norm(), 1e-12 * x_true.linfty_norm())
      << solver.description();

    // Three columns at once: b, 2 b, -b.
    const unsigned int  n_local = owned.n_elements();
    std::vector<double> columns(3 * n_local);
    for (unsigned int k = 0; k < n_local; ++k)
      {
        columns[k]               = b.local_element(k);
        columns[n_local + k]     = 2 * b.local_element(k);
        columns[2 * n_local + k] = -b.local_element(k);
      }
    solver.solve(columns, 3);
    double error = 0;
    for (unsigned int k = 0; k < n_local; ++k)
      error = std::max(
        {error,
         std::abs(columns[k] - x_true.local_element(k)),
         std::abs(columns[n_local + k] - 2 * x_true.local_element(k)),
         std::abs(columns[2 * n_local + k] + x_true.local_element(k))});
    EXPECT_LE(Utilities::MPI::max(error, comm), 1e-11 * x_true.linfty_norm());
  }
} // namespace

TEST(SparseDirectSolver, SolvesSymmetricAndUnsymmetricSystems)
{
  check_direct_solver(Parameters::DirectSolver::mumps, true);
  check_direct_solver(Parameters::DirectSolver::mumps, false);
  if (Utilities::MPI::n_mpi_processes(MPI_COMM_WORLD) == 1)
    {
      check_direct_solver(Parameters::DirectSolver::cholmod, true);
      check_direct_solver(Parameters::DirectSolver::cholmod, false); // UMFPACK
      check_direct_solver(Parameters::DirectSolver::umfpack, true);
      check_direct_solver(Parameters::DirectSolver::umfpack, false);
    }
}



// A 5-point Laplacian on a side x side grid (unknown j * side + i at grid
// point (i, j)) plus a small varying shift, on one rank.
void
shifted_grid_laplacian(const unsigned int side, MatrixType &A)
{
  const MPI_Comm         comm  = MPI_COMM_WORLD;
  const unsigned int     n     = side * side;
  const IndexSet         owned = complete_index_set(n);
  DynamicSparsityPattern dsp(n, n, owned);
  const auto             index = [&](const int i, const int j) {
    return static_cast<unsigned int>(j * side + i);
  };
  const auto inside = [&](const int i, const int j) {
    return i >= 0 && i < int(side) && j >= 0 && j < int(side);
  };
  for (unsigned int j = 0; j < side; ++j)
    for (unsigned int i = 0; i < side; ++i)
      for (const auto &[di, dj] :
           {std::pair{0, 0}, {1, 0}, {-1, 0}, {0, 1}, {0, -1}})
        if (inside(i + di, j + dj))
          dsp.add(index(i, j), index(i + di, j + dj));
  A.reinit(owned, owned, dsp, comm);
  for (unsigned int j = 0; j < side; ++j)
    for (unsigned int i = 0; i < side; ++i)
      for (const auto &[di, dj] : {std::pair{1, 0}, {-1, 0}, {0, 1}, {0, -1}})
        if (inside(i + di, j + dj))
          {
            A.add(index(i, j), index(i, j), 1.);
            A.add(index(i, j), index(i + di, j + dj), -1.);
          }
  for (unsigned int k = 0; k < n; ++k)
    A.add(k, k, 0.01 + 0.001 * k);
  A.compress(VectorOperation::add);
}



// The same Laplacian for two displacement-like components per grid point
// (unknowns 2 (j * side + i) and 2 (j * side + i) + 1), coupled by the SPD
// block [[2, 1], [1, 3]]: A kron B, so that the two rows of a grid point
// have the same pattern, as the dim rows of a vertex of the program's
// operator have.
void
shifted_grid_laplacian_with_blocks(const unsigned int side, MatrixType &A)
{
  MatrixType scalar;
  shifted_grid_laplacian(side, scalar);
  const MPI_Comm         comm  = MPI_COMM_WORLD;
  const unsigned int     n     = 2 * side * side;
  const IndexSet         owned = complete_index_set(n);
  DynamicSparsityPattern dsp(n, n, owned);
  const double           block[2][2] = {{2., 1.}, {1., 3.}};
  for (const auto &entry : scalar)
    for (unsigned int a = 0; a < 2; ++a)
      for (unsigned int b = 0; b < 2; ++b)
        dsp.add(2 * entry.row() + a, 2 * entry.column() + b);
  A.reinit(owned, owned, dsp, comm);
  for (const auto &entry : scalar)
    for (unsigned int a = 0; a < 2; ++a)
      for (unsigned int b = 0; b < 2; ++b)
        A.set(2 * entry.row() + a,
              2 * entry.column() + b,
              entry.value() * block[a][b]);
  A.compress(VectorOperation::insert);
}



// The elimination order that ends with given rows (CHOLMOD, one rank): the
// last block L_c of the factor must give A^{-1} on these rows as
// L_c^{-T} L_c^{-1}, and the split solve with a change of the last block
// must equal a solve with the corresponding right-hand side: A^{-1} (b - f)
// for f on the last rows is the forward half of b, the change
// -L_c^{-1} f_c, and the backward half.
void
check_last_block(const MatrixType                &A,
                 const std::vector<unsigned int> &last_rows)
{
  const MPI_Comm     comm  = MPI_COMM_WORLD;
  const unsigned int n     = A.m();
  const IndexSet     owned = complete_index_set(n);
  SparseDirectSolver solver(Parameters::DirectSolver::cholmod, comm);
  solver.factorize(A, true, last_rows);
  ASSERT_TRUE(solver.has_last_block()) << solver.description();
  const LAPACKFullMatrix<double>  &L_c   = solver.last_block_factor();
  const std::vector<unsigned int> &order = solver.last_block_order();
  const unsigned int               m     = last_rows.size();
  ASSERT_EQ(order.size(), m);

  // (A^{-1})_{kl} on the last rows from solves with unit vectors, against
  // (L_c^{-T} L_c^{-1})_{kl} = sum_p (L_c^{-1})_{pk} (L_c^{-1})_{pl}.
  LAPACKFullMatrix<double> inverse_factor(m, m);
  for (unsigned int k = 0; k < m; ++k)
    inverse_factor(k, k) = 1.;
  L_c.solve(inverse_factor); // L_c^{-1}
  VectorType unit(owned, comm), column(owned, comm);
  for (unsigned int l = 0; l < m; ++l)
    {
      unit                      = 0;
      unit(last_rows[order[l]]) = 1.;
      solver.solve(column, unit);
      for (unsigned int k = 0; k < m; ++k)
        {
          double from_block = 0;
          for (unsigned int p = 0; p < m; ++p)
            from_block += inverse_factor(p, k) * inverse_factor(p, l);
          EXPECT_NEAR(from_block, column(last_rows[order[k]]), 1e-12)
            << "entry " << k << ", " << l;
        }
    }

  // The split solve.
  VectorType b(owned, comm), f(owned, comm), expected(owned, comm),
    split(owned, comm);
  for (unsigned int k = 0; k < n; ++k)
    b(k) = std::cos(0.7 * k);
  Vector<double> f_last(m);
  for (unsigned int k = 0; k < m; ++k)
    {
      f_last[k]              = 1. + 0.5 * k;
      f(last_rows[order[k]]) = f_last[k];
    }
  VectorType rhs(b);
  rhs -= f;
  solver.solve(expected, rhs);
  Vector<double> forward_last;
  solver.forward_solve(b, forward_last);
  EXPECT_EQ(forward_last.size(), m);
  L_c.solve(f_last); // L_c^{-1} f_c
  f_last *= -1.;
  solver.backward_solve(f_last, split);
  split -= expected;
  EXPECT_LE(split.linfty_norm(), 1e-12 * expected.linfty_norm());
}


// The rows requested last: those of the grid's bottom line in a scrambled
// order (every third grid point first), and with several rows per grid
// point only its last one (as the contact dofs are the normal components
// only).
std::vector<unsigned int>
bottom_line_rows(const unsigned int side, const unsigned int rows_per_point)
{
  std::vector<unsigned int> rows;
  for (unsigned int start = 0; start < 3; ++start)
    for (unsigned int i = start; i < side; i += 3)
      rows.push_back(rows_per_point * (i + 1) - 1);
  return rows;
}

// A 5-point Laplacian on a 12 x 12 grid plus a shift.
TEST(SparseDirectSolver, LastBlockOfTheCholeskyFactor)
{
  if (Utilities::MPI::n_mpi_processes(MPI_COMM_WORLD) > 1)
    return; // CHOLMOD factorises on one rank only
  MatrixType A;
  shifted_grid_laplacian(12, A);
  check_last_block(A, bottom_line_rows(12, 1));
}

// The same with two rows per grid point, which the elimination order keeps
// together, except on the bottom line, where only one of them is requested.
TEST(SparseDirectSolver, LastBlockWithTwoRowsPerGridPoint)
{
  if (Utilities::MPI::n_mpi_processes(MPI_COMM_WORLD) > 1)
    return;
  MatrixType A;
  shifted_grid_laplacian_with_blocks(12, A);
  check_last_block(A, bottom_line_rows(12, 2));
}


// The single right-hand side solves with the CHOLMOD factor run on threads,
// subtree by subtree of the elimination tree (supernodal_solve.h). On a
// 64 x 64 grid Laplacian (4096 unknowns, enough for a cut into many
// subtrees): the solution A^{-1} A x must return x to 1e-10 relative, agree
// with CHOLMOD's own solve (the path of several right-hand sides) to 1e-12
// relative, and be the same to the last bit with one and with two threads.
TEST(SparseDirectSolver, ThreadedSolvesMatchCholmodOnAnyNumberOfThreads)
{
  if (Utilities::MPI::n_mpi_processes(MPI_COMM_WORLD) > 1)
    return; // CHOLMOD factorises on one rank only
  const MPI_Comm     comm = MPI_COMM_WORLD;
  const unsigned int side = 64, n = side * side;
  const IndexSet     owned = complete_index_set(n);
  MatrixType         A;
  shifted_grid_laplacian(side, A);
  VectorType x_true(owned, comm), b(owned, comm);
  for (unsigned int k = 0; k < n; ++k)
    x_true(k) = std::sin(0.37 * k) + 0.001 * k;
  A.vmult(b, x_true);

  SparseDirectSolver solver(Parameters::DirectSolver::cholmod, comm);
  solver.factorize(A, true);
  EXPECT_GE(solver.n_threaded_subtrees(), 8u);

  std::vector<VectorType> solutions;
  for (const unsigned int threads : {1u, 2u})
    {
      MultithreadInfo::set_thread_limit(threads);
      solutions.emplace_back(owned, comm);
      solver.solve(solutions.back(), b);
    }
  MultithreadInfo::set_thread_limit();
  for (unsigned int k = 0; k < n; ++k)
    ASSERT_EQ(solutions[0](k), solutions[1](k)) << "entry " << k;

  VectorType error(solutions[0]);
  error -= x_true;
  EXPECT_LE(error.linfty_norm(), 1e-10 * x_true.linfty_norm());
  std::vector<double> columns(2 * n);
  for (unsigned int k = 0; k < n; ++k)
    columns[k] = columns[n + k] = b(k);
  solver.solve(columns, 2);
  double difference = 0;
  for (unsigned int k = 0; k < n; ++k)
    difference = std::max(difference, std::abs(columns[k] - solutions[0](k)));
  EXPECT_LE(difference, 1e-12 * x_true.linfty_norm());
}



// @sect3{Parallel tools}
//
// Every rank holds records under its own keys and one under a shared key,
// and asks for the keys of the next rank: each answer must be that rank's
// payload; the shared key brings one payload per rank, in rank order.
// @sect3{The Q1 transfer of stress-point data}
//
// Two fields at the 2^dim Gauss points: a multilinear one (x y (z) and an
// affine part), which refinement and coarsening must reproduce exactly, and a
// quadratic one, for which coarsening must undo refinement (the refined
// values are a Q1 field again) but refinement itself cannot be exact. Points
// are in the reference coordinates of the parent; child c of deal.II's
// isotropic refinement covers child_to_cell_coordinates(., c). Tolerance
// 1e-13 (the matrices are built from 1/sqrt(3)).
template <int dim>
void
check_stress_point_transfer()
{
  const QGauss<dim>              gauss(2);
  const unsigned int             n_q = gauss.size(), n_children = 1u << dim;
  const StressPointTransfer<dim> transfer(gauss, 2);
  const auto                     multilinear = [](const Point<dim> &x) {
    double product = 1;
    for (unsigned int d = 0; d < dim; ++d)
      product *= x[d];
    return 0.5 + 2 * x[0] - x[dim - 1] + 3 * product;
  };
  const auto quadratic = [](const Point<dim> &x) { return x.square(); };
  std::vector<double> parent(2 * n_q);
  for (unsigned int q = 0; q < n_q; ++q)
    {
      parent[2 * q]     = multilinear(gauss.point(q));
      parent[2 * q + 1] = quadratic(gauss.point(q));
    }
  const auto children = transfer.refine(parent);
  ASSERT_EQ(children.size(), n_children);
  for (unsigned int c = 0; c < n_children; ++c)
    for (unsigned int q = 0; q < n_q; ++q)
      EXPECT_NEAR(children[c][2 * q],
                  multilinear(
                    GeometryInfo<dim>::child_to_cell_coordinates(gauss.point(q),
                                                                 c)),
                  1e-13);
  // Coarsening undoes refinement, for both fields.
  const auto back = transfer.coarsen(children);
  for (unsigned int i = 0; i < parent.size(); ++i)
    EXPECT_NEAR(back[i], parent[i], 1e-13);
  // Coarsening children's values of a multilinear field gives the parent's
  // values exactly; of the quadratic one, the least-squares fit, which
  // preserves the mean over the children's points (the constant is in Q1).
  std::vector<std::vector<double>> fine(n_children,
                                        std::vector<double>(2 * n_q));
  double                           fine_mean = 0;
  for (unsigned int c = 0; c < n_children; ++c)
    for (unsigned int q = 0; q < n_q; ++q)
      {
        const Point<dim> x
          = GeometryInfo<dim>::child_to_cell_coordinates(gauss.point(q), c);
        fine[c][2 * q]     = multilinear(x);
        fine[c][2 * q + 1] = quadratic(x);
        fine_mean += quadratic(x) / (n_children * n_q);
      }
  const auto coarse      = transfer.coarsen(fine);
  double     coarse_mean = 0;
  for (unsigned int q = 0; q < n_q; ++q)
    {
      EXPECT_NEAR(coarse[2 * q], parent[2 * q], 1e-13);
      coarse_mean += coarse[2 * q + 1] / n_q;
    }
  EXPECT_NEAR(coarse_mean, fine_mean, 1e-13);
}

TEST(StressPointTransfer, ExactForMultilinearFields2D)
{
  check_stress_point_transfer<2>();
}

TEST(StressPointTransfer, ExactForMultilinearFields3D)
{
  check_stress_point_transfer<3>();
}


TEST(MPITools, ExchangeRecordsAcrossRanks)
{
  const MPI_Comm     comm    = MPI_COMM_WORLD;
  const unsigned int n_ranks = Utilities::MPI::n_mpi_processes(comm);
  const unsigned int rank    = Utilities::MPI::this_mpi_process(comm);
  const auto         key     = [](const unsigned int r, const unsigned int i) {
    return "rank " + std::to_string(r) + " record " + std::to_string(i);
  };
  std::vector<MPITools::Record> records;
  for (unsigned int i = 0; i < 50; ++i)
    records.emplace_back(key(rank, i), std::vector<double>{1. * rank, 1. * i});
  records.emplace_back("shared", std::vector<double>{1. * rank});
  std::vector<std::string> requests;
  const unsigned int       next = (rank + 1) % n_ranks;
  for (unsigned int i = 0; i < 50; i += 7)
    requests.push_back(key(next, i));
  requests.push_back("shared");
  requests.push_back("nobody has this key");

  const auto found = MPITools::exchange_records(records, requests, comm);
  EXPECT_EQ(found.size(), requests.size() - 1);
  for (unsigned int i = 0; i < 50; i += 7)
    {
      ASSERT_EQ(found.count(key(next, i)), 1u);
      EXPECT_EQ(found.at(key(next, i)),
                (std::vector<std::vector<double>>{{1. * next, 1. * i}}));
    }
  ASSERT_EQ(found.at("shared").size(), n_ranks);
  for (unsigned int r = 0; r < n_ranks; ++r)
    EXPECT_EQ(found.at("shared")[r], std::vector<double>{1. * r});
}

// The same exchange in rounds (a checkpoint read a piece at a time): rank r
// holds records 0..10 r + 9 of its own, handed over in batches of 4 (so the
// ranks have different numbers of batches, and call deliver() with empty
// ones at the end); each rank asks once for every third record of the next
// rank and for a key nobody has. Every requested record arrives once, with
// its payload, and nothing else.
TEST(MPITools, RecordRouterInRounds)
{
  const MPI_Comm     comm    = MPI_COMM_WORLD;
  const unsigned int n_ranks = Utilities::MPI::n_mpi_processes(comm);
  const unsigned int rank    = Utilities::MPI::this_mpi_process(comm);
  const unsigned int next    = (rank + 1) % n_ranks;
  const auto         key     = [](const unsigned int r, const unsigned int i) {
    return "rank " + std::to_string(r) + " record " + std::to_string(i);
  };
  const auto n_records = [](const unsigned int r) { return 10 * r + 10; };
  std::vector<std::string> requests{"nobody has this key"};
  for (unsigned int i = 0; i < n_records(next); i += 3)
    requests.push_back(key(next, i));
  const MPITools::RecordRouter router(requests, comm);

  const unsigned int batch = 4;
  const unsigned int n_rounds
    = Utilities::MPI::max((n_records(rank) + batch - 1) / batch, comm);
  std::map<std::string, std::vector<std::vector<double>>> arrived;
  for (unsigned int round = 0; round < n_rounds; ++round)
    {
      std::vector<MPITools::Record> records;
      for (unsigned int i = round * batch;
           i < std::min(n_records(rank), (round + 1) * batch);
           ++i)
        records.emplace_back(key(rank, i),
                             std::vector<double>{1. * rank, 1. * i});
      for (auto &[record_key, payload] : router.deliver(records))
        arrived[record_key].push_back(payload);
    }
  EXPECT_EQ(arrived.size(), requests.size() - 1);
  for (unsigned int i = 0; i < n_records(next); i += 3)
    EXPECT_EQ(arrived[key(next, i)],
              (std::vector<std::vector<double>>{{1. * next, 1. * i}}));
}

// The output folder's collective write: the blocks of all ranks in rank
// order after rank 0's prefix, staged and committed; nothing under the
// final name before the commit; a name that exists and is not the run's is
// not replaced (the commit throws on every rank and leaves that file as it
// was); a failed collective write (a rank fails as on a full disk) leaves
// neither the file nor a temporary.
TEST(OutputFolder, CollectiveFileInRankOrder)
{
  const MPI_Comm     comm     = MPI_COMM_WORLD;
  const unsigned int rank     = Utilities::MPI::this_mpi_process(comm);
  const unsigned int n_ranks  = Utilities::MPI::n_mpi_processes(comm);
  const std::string directory = "output_folder_test_" + std::to_string(n_ranks);
  if (rank == 0)
    std::filesystem::remove_all(directory);
  MPI_Barrier(comm);
  {
    OutputFolder folder(directory, OutputFolder::Mode::new_run, "", comm);
    folder.prepare();
    folder.record_files({"blocks.txt", "foreign.txt"});
    const std::string block = std::string(rank + 1, 'a' + rank) + "\n";
    folder.stage_collectively("blocks.txt",
                              "prefix\n",
                              block.data(),
                              block.size(),
                              comm);
    EXPECT_FALSE(std::filesystem::exists(folder.path("blocks.txt")));
    // The same blocks made piece by piece, 2 bytes at a time (the
    // checkpoints' way): the same file.
    folder.record_files({"pieces.txt"});
    folder.stage_collectively(
      "pieces.txt",
      "prefix\n",
      block.size(),
      2,
      [&](const std::size_t begin, const std::size_t size, char *buffer) {
        ASSERT_LE(size, 2u);
        ASSERT_LE(begin + size, block.size());
        std::memcpy(buffer, block.data() + begin, size);
      },
      comm);
    folder.commit();
    if (rank == 0)
      {
        std::ifstream pieces(folder.path("pieces.txt")),
          blocks(folder.path("blocks.txt"));
        std::stringstream pieces_content, blocks_content;
        pieces_content << pieces.rdbuf();
        blocks_content << blocks.rdbuf();
        EXPECT_EQ(pieces_content.str(), blocks_content.str());
      }
    if (rank == 0)
      {
        std::ifstream in(folder.path("blocks.txt"));
        std::string   expected = "prefix\n", line, content;
        for (unsigned int r = 0; r < n_ranks; ++r)
          expected += std::string(r + 1, 'a' + r) + "\n";
        while (std::getline(in, line))
          content += line + "\n";
        EXPECT_EQ(content, expected);
        std::ofstream(folder.path("foreign.txt")) << "not the run's\n";
      }
    MPI_Barrier(comm);
    if (rank == 0)
      folder.stage("foreign.txt", "the run's\n");
    EXPECT_THROW(folder.commit(), ExceptionBase);
    if (rank == 0)
      {
        std::ifstream in(folder.path("foreign.txt"));
        std::string   line;
        std::getline(in, line);
        EXPECT_EQ(line, "not the run's");
      }
    MPI_Barrier(comm);
    ::setenv("VISCOPLASTIC_CONTACT_FAIL_WRITE", "failing.txt", 1);
    folder.record_files({"failing.txt"});
    folder.stage_collectively("failing.txt",
                              "",
                              block.data(),
                              block.size(),
                              comm);
    EXPECT_THROW(folder.commit(), ExceptionBase);
    ::unsetenv("VISCOPLASTIC_CONTACT_FAIL_WRITE");
    EXPECT_FALSE(std::filesystem::exists(folder.path("failing.txt")));
  }
  // The folder holds the three files, the manifest and nothing else (no
  // temporaries, no lock).
  MPI_Barrier(comm);
  if (rank == 0)
    {
      std::vector<std::string> names;
      for (const auto &entry : std::filesystem::directory_iterator(directory))
        names.push_back(entry.path().filename().string());
      std::sort(names.begin(), names.end());
      EXPECT_EQ(names,
                (std::vector<std::string>{OutputFolder::manifest_name,
                                          "blocks.txt",
                                          "foreign.txt",
                                          "pieces.txt"}));
      std::filesystem::remove_all(directory);
    }
}



// @sect3{Entries rejected by their patterns}
//
// A value that its entry's pattern rejects is reported as every rejected
// entry is: the subsection, the entry, the value, what is accepted in words,
// and the line of the file. Ranges with open ends (E > 0) are patterns of
// their own.
TEST(Parameters, PatternErrorsNameTheEntry)
{
  const auto message_of = [](const std::string &text) {
    const std::string file
      = "pattern_error_"
        + std::to_string(Utilities::MPI::this_mpi_process(MPI_COMM_WORLD))
        + ".prm";
    std::ofstream(file) << text;
    Parameters::AllParameters parameters;
    ParameterHandler          prm;
    parameters.add_parameters(prm);
    std::string message;
    try
      {
        Parameters::parse_parameter_file(prm, file);
      }
    catch (const ExceptionBase &exc)
      {
        message = exc.what();
      }
    std::filesystem::remove(file);
    // deal.II wraps the message's lines: one blank between words.
    return std::regex_replace(message, std::regex("\\s+"), " ");
  };
  const std::string modulus = message_of("subsection Material\n"
                                         "  set Young's modulus = 0 # E\n"
                                         "end\n");
  EXPECT_NE(modulus.find("Invalid parameter <Young's modulus> in subsection "
                         "<Material>: value <0>; accepted: a number > 0 "
                         "(line 2 of pattern_error_"),
            std::string::npos)
    << modulus;
  const std::string fraction = message_of("subsection Mesh adaptation\n"
                                          "  set Refine fraction = 1.5\n"
                                          "end\n");
  EXPECT_NE(fraction.find("<Refine fraction> in subsection <Mesh adaptation>: "
                          "value <1.5>; accepted: a number in [0, 1] (line 2"),
            std::string::npos)
    << fraction;
  const std::string method = message_of("subsection Linear solver\n"
                                        "  set Method = distributed\n"
                                        "end\n");
  EXPECT_NE(method.find("<Method> in subsection <Linear solver>: value "
                        "<distributed>; accepted: one of auto|condensed|full "
                        "space|matrix free (line 2"),
            std::string::npos)
    << method;
  const std::string top = message_of("set Dimension = 4\n");
  EXPECT_NE(top.find("Invalid parameter <Dimension>: value <4>; accepted: "),
            std::string::npos)
    << top;
  // deal.II also reads SUBSECTION and END.
  const std::string upper = message_of("SUBSECTION Time\n"
                                       "  set End time = -1\n"
                                       "END\n");
  EXPECT_NE(upper.find("<End time> in subsection <Time>: value <-1>"),
            std::string::npos)
    << upper;
  // Only numbers as deal.II reads them: "0x10" would be read as 0.
  const std::string hexadecimal = message_of("subsection Material\n"
                                             "  set Young's modulus = 0x10\n"
                                             "end\n");
  EXPECT_NE(hexadecimal.find("<Young's modulus> in subsection <Material>: "
                             "value <0x10>; accepted: a number > 0"),
            std::string::npos)
    << hexadecimal;
  // A number that is not finite is no number of a range.
  const std::string infinite = message_of("subsection Time\n"
                                          "  set End time = inf\n"
                                          "end\n");
  EXPECT_NE(infinite.find("<End time> in subsection <Time>: value <inf>; "
                          "accepted: a number > 0"),
            std::string::npos)
    << infinite;
}

// @sect3{Canonical entry values}
//
// What a resumed run compares with its checkpoint: the values, not their
// spelling. Numbers are parsed and printed with the fewest digits that give
// them back; expressions and words stay as written (trimmed).
TEST(Parameters, CanonicalValues)
{
  using Parameters::canonical_value;
  EXPECT_EQ(canonical_value("0.1"), "0.1");
  EXPECT_EQ(canonical_value("1e-1"), canonical_value("0.1"));
  EXPECT_EQ(canonical_value("0.015625"), "0.015625");
  EXPECT_EQ(canonical_value("1,1"), "1, 1");
  EXPECT_EQ(canonical_value(" 1 ,  1.0 "), "1, 1");
  EXPECT_EQ(canonical_value(" 0 ;  -5 "), "0; -5");
  EXPECT_EQ(canonical_value("x*t; 0"), "x*t; 0");
  EXPECT_EQ(canonical_value("true"), "true");
  EXPECT_EQ(canonical_value(""), "");
  EXPECT_NE(canonical_value("0.1"), canonical_value("0.10000000000000002"));
  EXPECT_EQ(canonical_value("0.30000000000000004"), "0.30000000000000004");
}

// @sect3{The time schedule}
//
// TimeSchedule with fixed steps: t_n = n k with the last step shortened to
// end at T (never stretched); a cut step inserts the midpoint and keeps the
// old level as the next one; the profile step is the level closest to a
// requested time (the first of two equally close); a resumed schedule with
// another End time continues on the grid of k; the checkpoint's copy
// restores every level. Exact comparisons: the levels are m k or T, the
// cut levels t + k/2, computed alike.
TEST(TimeSchedule, FixedStepsCutsAndEnd)
{
  TimeSchedule schedule = TimeSchedule::fixed_steps(1.05, 0.25);
  EXPECT_EQ(schedule.n_steps(), 5u);
  std::vector<double> levels = {schedule.current_time()};
  std::vector<double> following;
  bool                cut = false;
  while (!schedule.is_at_end())
    {
      // Cut the second step twice: 0.25 -> 0.3125, then 0.375 and 0.5 follow.
      if (schedule.step_number() == 1 && !cut)
        {
          schedule.cut_step();
          EXPECT_EQ(schedule.next_time(), 0.375);
          EXPECT_EQ(schedule.following_step_length(), 0.125);
          schedule.cut_step();
          EXPECT_EQ(schedule.next_time(), 0.3125);
          EXPECT_EQ(schedule.n_steps(), 7u);
          cut = true;
        }
      following.push_back(schedule.following_step_length());
      schedule.advance_time();
      levels.push_back(schedule.current_time());
    }
  EXPECT_EQ(levels,
            (std::vector<double>{0, 0.25, 0.3125, 0.375, 0.5, 0.75, 1., 1.05}));
  EXPECT_EQ(following.back(), 0.);
  EXPECT_NEAR(following[following.size() - 2], 0.05, 1e-15);
  EXPECT_EQ(schedule.step_number(), 7u);
  EXPECT_EQ(schedule.n_steps(), 7u);
  EXPECT_EQ(schedule.step_length(), 0.);
  // A T that is a multiple of k up to rounding has no spurious tiny step.
  EXPECT_EQ(TimeSchedule::fixed_steps(0.3, 0.1).n_steps(), 3u);
  EXPECT_EQ(n_fixed_steps(1e6, 1e-3), 1000000000u);
}

// The grid of Time step k that every reader of the time levels asks for:
// t_m = m k, m < N, and t_N = T, N = ceil(T/k); for adaptive steps the grid
// of the step the loads are checked at.
TEST(TimeSchedule, GridOfTheTimeStep)
{
  const TimeSchedule fixed = TimeSchedule::fixed_steps(1., 0.3);
  EXPECT_EQ(fixed.n_grid_levels(), 5u);
  EXPECT_EQ(fixed.grid_level(0), 0.);
  EXPECT_EQ(fixed.grid_level(3), 3 * 0.3);
  EXPECT_EQ(fixed.grid_level(4), 1.);
  EXPECT_EQ(fixed.grid_step_length(), 0.3);
  EXPECT_EQ(fixed_step_count(1., 0.25), 4.);
  EXPECT_EQ(n_fixed_steps(1., 0.3), 4u);
  const TimeSchedule adaptive
    = TimeSchedule::adaptive_steps({0.5, 1.}, 0.2, 0.25);
  EXPECT_EQ(adaptive.n_grid_levels(), 5u);
  EXPECT_EQ(adaptive.grid_level(2), 0.5);
  EXPECT_EQ(adaptive.grid_step_length(), 0.25);
}

TEST(TimeSchedule, ClosestLevelAndResume)
{
  TimeSchedule               schedule = TimeSchedule::fixed_steps(1., 0.1);
  std::vector<std::uint64_t> profile_steps;
  std::vector<std::uint64_t> tie_steps;
  ByteWriter                 saved;
  while (!schedule.is_at_end())
    {
      schedule.advance_time();
      if (schedule.current_time_is_closest_to(0.33))
        profile_steps.push_back(schedule.step_number());
      // 0.45 is equally close to 0.4 and 0.5 (up to rounding): one step.
      if (schedule.current_time_is_closest_to(0.45))
        tie_steps.push_back(schedule.step_number());
      if (schedule.current_time_is_closest_to(0.))
        profile_steps.push_back(1000);
      if (schedule.step_number() == 4)
        schedule.save(saved);
    }
  EXPECT_EQ(profile_steps, (std::vector<std::uint64_t>{3}));
  EXPECT_EQ(tie_steps.size(), 1u);

  // The checkpoint of step 4, restored and continued to End time 1.25 on
  // the same grid: the levels 0.5, ..., 1.2 and 1.25.
  TimeSchedule restored;
  ByteReader   reader(saved.bytes, "schedule");
  restored.load(reader);
  EXPECT_EQ(restored.step_number(), 4u);
  EXPECT_EQ(restored.current_time(), 4 * 0.1);
  restored.continue_to({1.25});
  EXPECT_EQ(restored.next_time(), 5 * 0.1);
  EXPECT_EQ(restored.n_steps(), 13u);
  while (!restored.is_at_end())
    restored.advance_time();
  EXPECT_EQ(restored.current_time(), 1.25);
  EXPECT_NEAR(restored.previous_step_length(), 0.05, 1e-15);
}

TEST(TimeSchedule, AdaptiveStepsLandRejectAndResume)
{
  TimeSchedule schedule = TimeSchedule::adaptive_steps({0.5, 1.}, 0.2, 0.2);
  EXPECT_TRUE(schedule.is_adaptive());
  EXPECT_NEAR(schedule.next_time(), 0.2, 1e-15);
  EXPECT_EQ(schedule.following_step_length(), 0.);
  schedule.reject_step(0.1);
  EXPECT_NEAR(schedule.next_time(), 0.1, 1e-15);
  EXPECT_EQ(schedule.n_rejected_steps(), 1u);
  // A cut with adaptive steps does not keep the old level: the controller
  // proposes the next one.
  schedule.cut_step();
  EXPECT_NEAR(schedule.next_time(), 0.05, 1e-15);
  schedule.advance_time(0.3);
  EXPECT_NEAR(schedule.current_time(), 0.05, 1e-15);
  EXPECT_NEAR(schedule.next_time(), 0.275, 1e-15); // two steps to 0.5
  EXPECT_EQ(schedule.proposed_step(), 0.3);
  schedule.advance_time(0.3);
  schedule.advance_time(0.3);
  EXPECT_EQ(schedule.current_time(), 0.5);
  EXPECT_EQ(schedule.n_steps(), 3u);
  // Resumed with End time 0.6: the next level lands on it.
  schedule.continue_to({0.6});
  EXPECT_EQ(schedule.next_time(), 0.6);
  schedule.advance_time(0.3);
  EXPECT_TRUE(schedule.is_at_end());
}

// @sect3{The time-step controller}
//
// control_time_step() and next_time_level() as pure functions
// (doc/adaptivity.md): the step grows by at most a factor 2 when the
// estimate is far below the tolerance or zero, follows k (tol/error)^(1/2)
// times the safety factor 0.9 in between, is rejected above the tolerance
// (shrinking by at most a factor 5), stays within [minimum, maximum], and
// lands on the targets exactly, in at most two equal steps. Tolerances:
// relative 1e-14 (a few roundings).
TEST(TimeStepController, GrowthShrinkAndCaps)
{
  TimeStepController controller;
  controller.tolerance    = 1e-3;
  controller.minimum_step = 1e-4;
  controller.maximum_step = 0.25;
  const double k          = 0.01;
  // Zero estimate (no plasticity): the largest growth.
  TimeStepDecision d = control_time_step(controller, k, 0., k);
  EXPECT_TRUE(d.accepted);
  EXPECT_NEAR(d.step, 2 * k, 1e-14 * k);
  // An estimate 100 times below the tolerance: 0.9 * 10 is above the growth
  // bound 2.
  d = control_time_step(controller, k, 1e-5, k);
  EXPECT_TRUE(d.accepted);
  EXPECT_NEAR(d.step, 2 * k, 1e-14 * k);
  // Between: the optimal factor 0.9 (tol/error)^(1/2) = 0.9 * 1.2.
  d = control_time_step(controller, k, 1e-3 / 1.44, k);
  EXPECT_TRUE(d.accepted);
  EXPECT_NEAR(d.step, 0.9 * 1.2 * k, 1e-14 * k);
  // At the tolerance: accepted, next step 0.9 k.
  d = control_time_step(controller, k, 1e-3, k);
  EXPECT_TRUE(d.accepted);
  EXPECT_NEAR(d.step, 0.9 * k, 1e-14 * k);
  // Four times the tolerance: rejected, repeated with 0.9 * 0.5 k.
  d = control_time_step(controller, k, 4e-3, k);
  EXPECT_FALSE(d.accepted);
  EXPECT_NEAR(d.step, 0.45 * k, 1e-14 * k);
  // 10^4 times the tolerance: shrinking is bounded by the factor 0.2.
  d = control_time_step(controller, k, 10., k);
  EXPECT_FALSE(d.accepted);
  EXPECT_NEAR(d.step, 0.2 * k, 1e-14 * k);
  // The maximum caps growth; the minimum caps shrinking, and a step at the
  // minimum is accepted whatever its estimate.
  d = control_time_step(controller, 0.2, 0., 0.2);
  EXPECT_NEAR(d.step, 0.25, 1e-14);
  d = control_time_step(controller, 2e-4, 10., 2e-4);
  EXPECT_FALSE(d.accepted);
  EXPECT_NEAR(d.step, 1e-4, 1e-18);
  d = control_time_step(controller, 1e-4, 10., 1e-4);
  EXPECT_TRUE(d.accepted);
  EXPECT_NEAR(d.step, 1e-4, 1e-18);
  // A step shortened to land on a target (0.003 instead of the desired
  // 0.01) with a small estimate grows relative to the desired step, not to
  // the short one: 2 * 0.01.
  d = control_time_step(controller, 0.003, 1e-6, 0.01);
  EXPECT_TRUE(d.accepted);
  EXPECT_NEAR(d.step, 0.02, 1e-14);
}

TEST(TimeStepController, RangeAndTheCapOfTheExplicitUpdate)
{
  // Without a stability limit the range is the one given.
  const double       infinity = std::numeric_limits<double>::infinity();
  TimeStepController c = make_time_step_controller(1e-3, 1e-4, 0.25, infinity);
  EXPECT_EQ(c.tolerance, 1e-3);
  EXPECT_EQ(c.minimum_step, 1e-4);
  EXPECT_EQ(c.maximum_step, 0.25);
  // The explicit update: at most 0.9 times its limit.
  c = make_time_step_controller(1e-3, 1e-4, 0.25, 0.1);
  EXPECT_EQ(c.maximum_step, 0.9 * 0.1);
  // A minimum above that wins.
  c = make_time_step_controller(1e-3, 0.2, 0.25, 0.1);
  EXPECT_EQ(c.maximum_step, 0.2);
}

TEST(TimeStepController, LandingTargetsInsideTheRunThenEndTime)
{
  // Sorted, without the times outside (0, T), End time last.
  EXPECT_EQ(landing_targets({0.5, 0, 0.25, 2, 1}, 1),
            (std::vector<double>{0.25, 0.5, 1}));
  EXPECT_EQ(landing_targets({}, 3), (std::vector<double>{3}));
}

TEST(TimeStepController, LandsOnTargets)
{
  const std::vector<double> targets = {0.5, 1.};
  // Far from the target: the step as it is.
  EXPECT_NEAR(next_time_level(0.1, 0.1, targets), 0.2, 1e-15);
  // A step that reaches or passes the target ends on it, exactly.
  EXPECT_EQ(next_time_level(0.45, 0.1, targets), 0.5);
  EXPECT_EQ(next_time_level(0.4, 0.1 * (1 - 1e-14), targets), 0.5);
  // A step that would leave less than a step before the target: the rest
  // in two equal steps (0.42 + 0.04, then 0.04 to the target).
  EXPECT_NEAR(next_time_level(0.42, 0.06, targets), 0.46, 1e-15);
  EXPECT_EQ(next_time_level(0.46, 0.06, targets), 0.5);
  // A target just passed (within 1e-12 T) does not stop the next step; the
  // next target is End time.
  EXPECT_NEAR(next_time_level(0.5, 0.2, targets), 0.7, 1e-15);
  EXPECT_EQ(next_time_level(0.9, 0.25, targets), 1.);
  // Time levels from 0 with a fixed proposal 0.15: never beyond a target,
  // every target reached exactly, and no step below half the proposal.
  std::vector<double> levels = {0.};
  while (levels.back() < 1.)
    levels.push_back(next_time_level(levels.back(), 0.15, targets));
  EXPECT_NE(std::find(levels.begin(), levels.end(), 0.5), levels.end());
  EXPECT_EQ(levels.back(), 1.);
  for (unsigned int i = 1; i < levels.size(); ++i)
    {
      EXPECT_LE(levels[i] - levels[i - 1], 0.15 + 1e-15);
      EXPECT_GE(levels[i] - levels[i - 1], 0.075 - 1e-15);
    }
}



// The near-null space given to ML: every mode is a rigid motion, so it
// changes no distance to first order, (v(x) - v(y)) . (x - y) = 0 for any
// two points; the dim translations are the unit vectors, and in 3D the
// three rotations are independent (about three different axes).
template <int dim>
void
check_rigid_body_modes()
{
  std::vector<Point<dim>> points(3);
  for (unsigned int p = 0; p < points.size(); ++p)
    for (unsigned int d = 0; d < dim; ++d)
      points[p][d] = std::sin(1.7 * p + 0.9 * d + 0.4) * (1 + p);
  const auto field = [](const Point<dim> &y, const unsigned int mode) {
    Tensor<1, dim> v;
    for (unsigned int c = 0; c < dim; ++c)
      v[c] = rigid_body_mode_components(c, y)[mode];
    return v;
  };
  const unsigned int n_modes = (dim == 2 ? 3 : 6);
  for (unsigned int mode = 0; mode < n_modes; ++mode)
    {
      for (unsigned int p = 0; p < points.size(); ++p)
        for (unsigned int q = 0; q < points.size(); ++q)
          EXPECT_NEAR((field(points[p], mode) - field(points[q], mode))
                        * (points[p] - points[q]),
                      0.,
                      1e-14)
            << "mode " << mode;
      if (mode < dim)
        for (unsigned int c = 0; c < dim; ++c)
          EXPECT_EQ(field(points[0], mode)[c], c == mode ? 1. : 0.);
      else
        // A rotation vanishes at the origin and not at the points.
        EXPECT_GT(field(points[1], mode).norm(), 1e-3) << "mode " << mode;
    }
  if constexpr (dim == 3)
    {
      // No two rotations are parallel at a point away from every axis.
      for (unsigned int a = 3; a < 6; ++a)
        for (unsigned int b = a + 1; b < 6; ++b)
          EXPECT_GT(
            cross_product_3d(field(points[1], a), field(points[1], b)).norm(),
            1e-3);
    }
}

TEST(RigidBodyModes, RigidMotionsIn2D)
{
  check_rigid_body_modes<2>();
}

TEST(RigidBodyModes, RigidMotionsIn3D)
{
  check_rigid_body_modes<3>();
}



// The BLAS's threads (blas_threads.h): a scope gives a BLAS with threads
// (OpenBLAS built with pthreads, which scripts/install_dependencies.sh
// installs) the rank's threads and restores the number before at its end;
// a BLAS without threads stays at one.
TEST(BlasThreads, ScopeGivesTheRanksThreadsAndRestores)
{
  MultithreadInfo::set_thread_limit(2);
  const unsigned int rank_threads = MultithreadInfo::n_threads();
  // Whether the BLAS has threads to set at all.
  set_blas_threads(2);
  const bool threaded = (blas_threads() == 2);
  set_blas_threads(1);
  ASSERT_EQ(blas_threads(), 1u);
  {
    const BlasThreadsOfRank threads;
    EXPECT_EQ(blas_threads(), threaded ? rank_threads : 1u);
  }
  EXPECT_EQ(blas_threads(), 1u);
  MultithreadInfo::set_thread_limit();
}


// @sect3{Free rigid motions}
//
// free_rigid_motions() (rigid_motions.h) on the unit square of
// quadrilaterals with hanging nodes (p4est), of triangles (fully
// distributed), and on the unit cube of hexahedra, with the boundary ids
// of colorize (0 and 1 at x = 0 and 1, 2 and 3 at y = 0 and 1, 4 and 5 at
// z = 0 and 1). The combination: u_x = 0 at the vertex (0, 1) alone leaves
// free the translation in y and a translation in x plus a rotation about
// z, a t_x + w r_z, whose u_x = a - w (y - 1/2)/sqrt(2) vanishes at y = 1
// (the rotation is about the centre of the box, its positions scaled by
// the diameter sqrt(2)): a = w/(2 sqrt(2)), the unit vector (1/3, 0,
// sqrt(8)/3).
namespace
{
  // The free rigid motions with the hanging-node constraints and those
  // add_constraints adds, stored on the locally relevant dofs and
  // more_lines.
  template <int dim>
  std::vector<std::string>
  free_motions_with(
    const Mapping<dim>                                     &mapping,
    const DoFHandler<dim>                                  &dof_handler,
    const std::function<void(AffineConstraints<double> &)> &add_constraints,
    const IndexSet                                         &more_lines = {})
  {
    IndexSet lines = DoFTools::extract_locally_relevant_dofs(dof_handler);
    if (more_lines.size() > 0)
      lines.add_indices(more_lines);
    AffineConstraints<double> constraints(lines);
    DoFTools::make_hanging_node_constraints(dof_handler, constraints);
    add_constraints(constraints);
    constraints.close();
    const auto free = free_rigid_motions(hp::MappingCollection<dim>(mapping),
                                         dof_handler,
                                         constraints,
                                         MPI_COMM_WORLD);
    if (free.empty())
      return {};
    EXPECT_EQ(free.size(), 1u);
    EXPECT_EQ(free.front().n_bodies, 1u);
    return free.front().motions;
  }

  // u_c = 0 for the components c of mask on the boundary part id.
  template <int dim>
  std::function<void(AffineConstraints<double> &)>
  fix_on_boundary(const Mapping<dim>      &mapping,
                  const DoFHandler<dim>   &dof_handler,
                  const types::boundary_id id,
                  const ComponentMask     &mask)
  {
    return [&mapping, &dof_handler, id, mask](
             AffineConstraints<double> &constraints) {
      VectorTools::interpolate_boundary_values(mapping,
                                               dof_handler,
                                               id,
                                               Functions::ZeroFunction<dim>(
                                                 dim),
                                               constraints,
                                               mask);
    };
  }

  // u_c = 0 at the vertex p, on every rank that has a cell there.
  template <int dim>
  std::function<void(AffineConstraints<double> &)>
  fix_at_vertex(const DoFHandler<dim> &dof_handler,
                const Point<dim>      &p,
                const unsigned int     c)
  {
    return [&dof_handler, p, c](AffineConstraints<double> &constraints) {
      for (const auto &cell : dof_handler.active_cell_iterators())
        if (!cell->is_artificial())
          for (const unsigned int v : cell->vertex_indices())
            if (cell->vertex(v).distance(p) < 1e-12)
              {
                const types::global_dof_index i = cell->vertex_dof_index(v, c);
                if (!constraints.is_constrained(i))
                  constraints.add_line(i);
              }
    };
  }

  // The dofs of the vertex x, one per component, on every rank.
  template <int dim>
  std::vector<types::global_dof_index>
  vertex_dofs(const DoFHandler<dim> &dof_handler, const Point<dim> &x)
  {
    std::vector<types::global_dof_index> dofs(dim, 0);
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (!cell->is_artificial())
        for (const unsigned int v : cell->vertex_indices())
          if (cell->vertex(v).distance(x) < 1e-12)
            for (unsigned int c = 0; c < dim; ++c)
              dofs[c] = cell->vertex_dof_index(v, c);
    for (types::global_dof_index &dof : dofs)
      dof = Utilities::MPI::max(dof, MPI_COMM_WORLD);
    return dofs;
  }

  // Both together.
  std::function<void(AffineConstraints<double> &)>
  both(const std::function<void(AffineConstraints<double> &)> &first,
       const std::function<void(AffineConstraints<double> &)> &second)
  {
    return [first, second](AffineConstraints<double> &constraints) {
      first(constraints);
      second(constraints);
    };
  }

  // The cases of the unit square: (a) no constraints (only hanging nodes),
  // (b) u_x = 0 on the left side, (c) u = 0 on the left side, (d) u_y = 0
  // at the bottom and u_x = 0 on the left side, (e) u_y = 0 at the corner
  // (1, 0) and u_x = 0 on the left side, (f) u_x = 0 at the corner (0, 1)
  // alone, (g) u(0, 0) = u(1, 1), which only the translations satisfy.
  void
  check_free_rigid_motions_of_square(const Mapping<2>    &mapping,
                                     const DoFHandler<2> &dof_handler)
  {
    using Names                 = std::vector<std::string>;
    const ComponentMask x_only  = std::vector<bool>{true, false};
    const ComponentMask y_only  = std::vector<bool>{false, true};
    const ComponentMask all     = std::vector<bool>{true, true};
    const auto          nothing = [](AffineConstraints<double> &) {};

    EXPECT_EQ(
      free_motions_with<2>(mapping, dof_handler, nothing),
      (Names{"translation in x", "translation in y", "rotation about z"}));
    EXPECT_EQ(
      free_motions_with<2>(mapping,
                           dof_handler,
                           fix_on_boundary<2>(mapping, dof_handler, 0, x_only)),
      Names{"translation in y"});
    EXPECT_EQ(
      free_motions_with<2>(mapping,
                           dof_handler,
                           fix_on_boundary<2>(mapping, dof_handler, 0, all)),
      Names{});
    EXPECT_EQ(free_motions_with<2>(
                mapping,
                dof_handler,
                both(fix_on_boundary<2>(mapping, dof_handler, 2, y_only),
                     fix_on_boundary<2>(mapping, dof_handler, 0, x_only))),
              Names{});
    EXPECT_EQ(free_motions_with<2>(
                mapping,
                dof_handler,
                both(fix_at_vertex<2>(dof_handler, Point<2>(1., 0.), 1),
                     fix_on_boundary<2>(mapping, dof_handler, 0, x_only))),
              Names{});
    EXPECT_EQ(
      free_motions_with<2>(mapping,
                           dof_handler,
                           fix_at_vertex<2>(dof_handler, Point<2>(0., 1.), 0)),
      (Names{"0.33 translation in x + 0.94 rotation about z",
             "translation in y"}));
    // (g) stores the lines of both vertices on every rank (deal.II's
    // assertions want the dofs of every entry among the stored lines), so
    // that the rank owning (0, 0) need not know (1, 1): free_rigid_motions()
    // then asks the owner of (1, 1) for its modes.
    const auto p    = vertex_dofs<2>(dof_handler, Point<2>(0., 0.));
    const auto q    = vertex_dofs<2>(dof_handler, Point<2>(1., 1.));
    const auto ties = [&p, &q](AffineConstraints<double> &constraints) {
      for (unsigned int c = 0; c < 2; ++c)
        {
          constraints.add_line(p[c]);
          constraints.add_entry(p[c], q[c], 1.);
        }
    };
    IndexSet tied(dof_handler.n_dofs());
    tied.add_indices(p.begin(), p.end());
    tied.add_indices(q.begin(), q.end());
    EXPECT_EQ(free_motions_with<2>(mapping, dof_handler, ties, tied),
              (Names{"translation in x", "translation in y"}));
  }
} // namespace

// Quadrilaterals on p4est, the lower left quarter refined once more: the
// hanging nodes stop nothing.
TEST(RigidMotions, QuadrilateralsWithHangingNodes)
{
  parallel::distributed::Triangulation<2> triangulation(MPI_COMM_WORLD);
  GridGenerator::hyper_cube(triangulation, 0., 1., true);
  triangulation.refine_global(3);
  for (const auto &cell : triangulation.active_cell_iterators())
    if (cell->is_locally_owned() && cell->center()[0] < 0.5
        && cell->center()[1] < 0.5)
      cell->set_refine_flag();
  triangulation.execute_coarsening_and_refinement();

  const FESystem<2> fe(FE_Q<2>(1), 2);
  DoFHandler<2>     dof_handler(triangulation);
  dof_handler.distribute_dofs(fe);
  const MappingQ1<2> mapping;

  AffineConstraints<double> hanging_nodes(
    DoFTools::extract_locally_relevant_dofs(dof_handler));
  DoFTools::make_hanging_node_constraints(dof_handler, hanging_nodes);
  ASSERT_GT(Utilities::MPI::sum(hanging_nodes.n_constraints(), MPI_COMM_WORLD),
            0u);

  check_free_rigid_motions_of_square(mapping, dof_handler);
}

// Two bodies (the squares [0, 1]^2 and [2, 3] x [0, 1], separate
// components of one p4est mesh): u = 0 on the left side of the first
// leaves all three motions of the second free, and names it and its
// bounding box; u_x = 0 on the right side of the second as well leaves its
// translation in y alone.
TEST(RigidMotions, TwoBodies)
{
  Triangulation<2> left, right, merged;
  GridGenerator::hyper_rectangle(left, Point<2>(0., 0.), Point<2>(1., 1.));
  GridGenerator::hyper_rectangle(right, Point<2>(2., 0.), Point<2>(3., 1.));
  GridGenerator::merge_triangulations(left, right, merged);
  parallel::distributed::Triangulation<2> triangulation(MPI_COMM_WORLD);
  triangulation.copy_triangulation(merged);
  for (const auto &cell : triangulation.active_cell_iterators())
    for (const auto &face : cell->face_iterators())
      if (face->at_boundary())
        face->set_boundary_id(face->center()[0] < 1e-12        ? 0
                              : face->center()[0] > 3. - 1e-12 ? 1
                                                               : 2);
  triangulation.refine_global(3);
  const FESystem<2> fe(FE_Q<2>(1), 2);
  DoFHandler<2>     dof_handler(triangulation);
  dof_handler.distribute_dofs(fe);
  const MappingQ1<2>  mapping;
  const ComponentMask all    = std::vector<bool>{true, true};
  const ComponentMask x_only = std::vector<bool>{true, false};

  const auto free_bodies
    = [&](const std::function<void(AffineConstraints<double> &)> &add) {
        AffineConstraints<double> constraints(
          DoFTools::extract_locally_relevant_dofs(dof_handler));
        add(constraints);
        constraints.close();
        return free_rigid_motions(hp::MappingCollection<2>(mapping),
                                  dof_handler,
                                  constraints,
                                  MPI_COMM_WORLD);
      };
  const auto one
    = free_bodies(fix_on_boundary<2>(mapping, dof_handler, 0, all));
  ASSERT_EQ(one.size(), 1u);
  EXPECT_EQ(one[0].number, 2u);
  EXPECT_EQ(one[0].n_bodies, 2u);
  EXPECT_EQ(one[0].lower, Point<2>(2., 0.));
  EXPECT_EQ(one[0].upper, Point<2>(3., 1.));
  EXPECT_EQ(one[0].motions,
            (std::vector<std::string>{"translation in x",
                                      "translation in y",
                                      "rotation about z"}));
  const auto two
    = free_bodies(both(fix_on_boundary<2>(mapping, dof_handler, 0, all),
                       fix_on_boundary<2>(mapping, dof_handler, 1, x_only)));
  ASSERT_EQ(two.size(), 1u);
  EXPECT_EQ(two[0].motions, std::vector<std::string>{"translation in y"});
}

// Triangles on a fully distributed mesh (partitioned by METIS).
TEST(RigidMotions, Triangles)
{
  Triangulation<2> serial_mesh;
  create_simplex_box(serial_mesh,
                     {1., 1.},
                     8,
                     Parameters::SimplexPattern::slash);
  GridTools::partition_triangulation(Utilities::MPI::n_mpi_processes(
                                       MPI_COMM_WORLD),
                                     serial_mesh);
  parallel::fullydistributed::Triangulation<2> triangulation(MPI_COMM_WORLD);
  triangulation.create_triangulation(
    TriangulationDescription::Utilities::create_description_from_triangulation(
      serial_mesh,
      MPI_COMM_WORLD));

  const FESystem<2> fe(FE_SimplexP<2>(1), 2);
  DoFHandler<2>     dof_handler(triangulation);
  dof_handler.distribute_dofs(fe);
  const MappingFE<2> mapping(FE_SimplexP<2>(1));

  check_free_rigid_motions_of_square(mapping, dof_handler);
}

// Hexahedra: all six motions of the free cube; u_x = 0 on the face x = 0
// leaves the translations in y and z and the rotation about x; u = 0 there
// stops everything.
TEST(RigidMotions, Hexahedra)
{
  parallel::distributed::Triangulation<3> triangulation(MPI_COMM_WORLD);
  GridGenerator::hyper_cube(triangulation, 0., 1., true);
  triangulation.refine_global(2);
  const FESystem<3> fe(FE_Q<3>(1), 3);
  DoFHandler<3>     dof_handler(triangulation);
  dof_handler.distribute_dofs(fe);
  const MappingQ1<3> mapping;

  using Names = std::vector<std::string>;
  EXPECT_EQ(free_motions_with<3>(mapping,
                                 dof_handler,
                                 [](AffineConstraints<double> &) {}),
            (Names{"translation in x",
                   "translation in y",
                   "translation in z",
                   "rotation about x",
                   "rotation about y",
                   "rotation about z"}));
  EXPECT_EQ(
    free_motions_with<3>(
      mapping,
      dof_handler,
      fix_on_boundary<3>(mapping,
                         dof_handler,
                         0,
                         std::vector<bool>{true, false, false})),
    (Names{"translation in y", "translation in z", "rotation about x"}));
  EXPECT_EQ(free_motions_with<3>(mapping,
                                 dof_handler,
                                 fix_on_boundary<3>(mapping,
                                                    dof_handler,
                                                    0,
                                                    ComponentMask(3, true))),
            Names{});
}


// @sect3{The cost model of Method = auto}
//
// The scenes of doc/back_ends/method_choice.md, where every back end was
// timed (benchmarks/run_method_choice.py): auto must take the one that was
// fastest, and never one that cannot run the scene or does not fit.

namespace
{
  SceneSize
  scene_of(const unsigned int dim,
           const bool         simplex,
           const double       dofs,
           const double       contact_nodes,
           const double       steps,
           const unsigned int ranks = 1)
  {
    SceneSize scene;
    scene.dim             = dim;
    scene.simplex         = simplex;
    scene.dofs            = dofs;
    scene.contact_nodes   = contact_nodes;
    scene.steps           = steps;
    scene.ranks           = ranks;
    scene.memory_per_rank = 24e9 / ranks;
    return scene;
  }
} // namespace

TEST(CostModel, MethodSetInTheParameterFileIsKept)
{
  const SceneSize scene = scene_of(2, true, 526338, 512, 1);
  for (const auto method : {Parameters::Method::condensed,
                            Parameters::Method::full_space,
                            Parameters::Method::matrix_free})
    {
      const MethodChoice choice = choose_method(method, scene);
      EXPECT_EQ(choice.method, method);
      EXPECT_EQ(choice.reason, "set in the parameter file");
    }
}

TEST(CostModel, MatrixFreeOnlyForHypercubesAndTheExplicitUpdate)
{
  SceneSize scene = scene_of(3, true, 1.2e6, 5000, 32);
  EXPECT_FALSE(
    estimate_cost(Parameters::Method::matrix_free, scene).unavailable.empty());
  EXPECT_NE(choose_method(Parameters::Method::automatic, scene).method,
            Parameters::Method::matrix_free);
  scene.simplex         = false;
  scene.implicit_update = true;
  EXPECT_FALSE(
    estimate_cost(Parameters::Method::matrix_free, scene).unavailable.empty());
  EXPECT_NE(choose_method(Parameters::Method::automatic, scene).method,
            Parameters::Method::matrix_free);
}

TEST(CostModel, MatrixFreeOnlyWithCoarserMeshes)
{
  // The Hertz sphere's graded Gmsh mesh at 108k dofs on two ranks: with
  // coarser meshes the model takes matrix free; without, its multigrid
  // would be one level, and auto takes another back end.
  SceneSize scene = scene_of(3, false, 107811, 1089, 1, 2);
  EXPECT_EQ(choose_method(Parameters::Method::automatic, scene).method,
            Parameters::Method::matrix_free);
  scene.coarser_meshes = false;
  const BackEndCost cost
    = estimate_cost(Parameters::Method::matrix_free, scene);
  // It can run the scene (a named Method still takes it); auto does not.
  EXPECT_TRUE(cost.unavailable.empty());
  EXPECT_NE(cost.not_taken.find("no coarser mesh"), std::string::npos);
  const MethodChoice choice
    = choose_method(Parameters::Method::automatic, scene);
  EXPECT_NE(choice.method, Parameters::Method::matrix_free);
  EXPECT_NE(choice.reason.find("matrix free not taken"), std::string::npos);
}

TEST(CostModel, MatrixFreeNotTakenForBondedZones)
{
  // The same scene with a bonded contact zone: the matrix-free multigrid's
  // coarser levels do not hold its springs, and auto takes another back end.
  SceneSize scene        = scene_of(3, false, 107811, 1089, 1, 2);
  scene.bonded_interface = true;
  const BackEndCost cost
    = estimate_cost(Parameters::Method::matrix_free, scene);
  EXPECT_TRUE(cost.unavailable.empty());
  EXPECT_NE(cost.not_taken.find("bonded contact zone"), std::string::npos);
  EXPECT_NE(choose_method(Parameters::Method::automatic, scene).method,
            Parameters::Method::matrix_free);
}

TEST(CostModel, MatrixFreeNotTakenWhereEveryCellDiffers)
{
  // The Hertz sphere's graded box (Box map) at 353k dofs on one rank, one
  // step with its initial cycles: every cell is evaluated by sum
  // factorisation, and the matrix-free back end took 83.4 s against the
  // full space back end's 27.9 s (whole processes): auto takes full space,
  // where on the unmapped box of the same size it takes matrix free.
  SceneSize scene        = scene_of(3, false, 352947, 2401, 1);
  scene.nested_iteration = true;
  EXPECT_EQ(choose_method(Parameters::Method::automatic, scene).method,
            Parameters::Method::matrix_free);
  scene.distinct_cells = true;
  const BackEndCost cost
    = estimate_cost(Parameters::Method::matrix_free, scene);
  EXPECT_TRUE(cost.unavailable.empty());
  EXPECT_NE(cost.not_taken.find("own shape"), std::string::npos);
  EXPECT_EQ(choose_method(Parameters::Method::automatic, scene).method,
            Parameters::Method::full_space);
}

TEST(CostModel, ChoosesTheMeasuredFastest)
{
  const auto automatic = Parameters::Method::automatic;
  // The static scene (one cold step) on triangles: the condensed back end on
  // one rank, the full space one on two (S by one MUMPS solve per node).
  for (const double n : {128., 256., 512.})
    {
      const double dofs = 2 * (n + 1) * (n + 1);
      EXPECT_EQ(choose_method(automatic, scene_of(2, true, dofs, n, 1)).method,
                Parameters::Method::condensed);
      EXPECT_EQ(
        choose_method(automatic, scene_of(2, true, dofs, n, 1, 2)).method,
        Parameters::Method::full_space);
    }
  // cube_3d.prm (32 steps) at 15k and 108k dofs: condensed on one rank; at
  // 15k on two ranks matrix free on hexahedra (whole processes: 2.6 s
  // against 4.3 s full space and 4.8 s condensed), condensed on tetrahedra
  // (4.8 s against 6.8 s full space: MUMPS's solves in 3D cost about what
  // CHOLMOD's do, and the full space steps cost more than on hexahedra).
  EXPECT_EQ(choose_method(automatic, scene_of(3, false, 14739, 289, 32)).method,
            Parameters::Method::condensed);
  EXPECT_EQ(
    choose_method(automatic, scene_of(3, false, 14739, 289, 32, 2)).method,
    Parameters::Method::matrix_free);
  EXPECT_EQ(
    choose_method(automatic, scene_of(3, true, 14739, 289, 32, 2)).method,
    Parameters::Method::condensed);
  EXPECT_EQ(
    choose_method(automatic, scene_of(3, false, 107811, 1089, 32)).method,
    Parameters::Method::condensed);
  // On two ranks at 47k and 108k dofs: matrix free (6.0 s and 18.3 s
  // against 8.7 s and 19.5 s full space; the condensed one's MUMPS solves
  // take 31 s and 169 s).
  for (const auto &[dofs, nodes] :
       std::vector<std::pair<double, double>>{{46875, 600}, {107811, 1056}})
    EXPECT_EQ(
      choose_method(automatic, scene_of(3, false, dofs, nodes, 32, 2)).method,
      Parameters::Method::matrix_free);
  // At 1.2M dofs the factor does not fit: matrix free on hexahedra (over
  // whole runs at 353k dofs its steps took 4.0 s against 4.6 s full space),
  // full space on tetrahedra, ...
  EXPECT_EQ(
    choose_method(automatic, scene_of(3, false, 1.2e6, 5329, 32)).method,
    Parameters::Method::matrix_free);
  EXPECT_EQ(choose_method(automatic, scene_of(3, true, 1.2e6, 5329, 32)).method,
            Parameters::Method::full_space);
  // ... and matrix free for the two steps where the contact zone forms,
  // where the full space back end rebuilds its AMG (19.7 s per step
  // against 51.6 s).
  SceneSize forming        = scene_of(3, false, 1.167e6, 5256, 2);
  forming.nested_iteration = true;
  EXPECT_EQ(choose_method(automatic, forming).method,
            Parameters::Method::matrix_free);
}

TEST(CostModel, ImplicitUpdateCountsAKrylovSolvePerNewtonIteration)
{
  // stability_lambda_50_implicit.prm: 1024 implicit steps on 578 dofs (16 x
  // 16 triangles, 17 contact nodes); every Newton iteration of the
  // iterative back ends is a Krylov solve, so one rank takes the condensed
  // back end (measured 1.65 times faster than full space), two ranks the
  // full space one (MUMPS's solves per Newton iteration: measured 1.8
  // times slower).
  SceneSize scene       = scene_of(2, true, 578, 17, 1024);
  scene.implicit_update = true;
  EXPECT_EQ(choose_method(Parameters::Method::automatic, scene).method,
            Parameters::Method::condensed);
  const BackEndCost explicit_cost
    = estimate_cost(Parameters::Method::full_space,
                    scene_of(2, true, 578, 17, 1024));
  EXPECT_GT(estimate_cost(Parameters::Method::full_space, scene).steps_seconds,
            1.9 * explicit_cost.steps_seconds);
  scene                 = scene_of(2, true, 578, 17, 1024, 2);
  scene.implicit_update = true;
  EXPECT_EQ(choose_method(Parameters::Method::automatic, scene).method,
            Parameters::Method::full_space);
}

TEST(CostModel, FrictionFactorisesTheDenseProblemEveryIteration)
{
  // dragged_punch.prm (Coulomb friction, 257 contact nodes, 514 rows of the
  // dense problem, 32 steps): on one rank condensed (whole processes 1.35 s
  // against 1.86 s full space), on two ranks full space (1.64 s against
  // 2.08 s: S from 514 MUMPS solves, and an LU of the dense problem in each
  // of the 97 active-set iterations).
  SceneSize scene     = scene_of(2, false, 3976, 257, 32);
  scene.node_unknowns = 2;
  EXPECT_EQ(choose_method(Parameters::Method::automatic, scene).method,
            Parameters::Method::condensed);
  scene.ranks = 2;
  EXPECT_EQ(choose_method(Parameters::Method::automatic, scene).method,
            Parameters::Method::full_space);
}

TEST(CostModel, CondensedFrictionCostsTheNodesInContact)
{
  // weakening_punch_3d.prm on one rank (Coulomb friction, 1089 contact
  // nodes, 32 steps): with the rows of every contact node in its dense
  // problem the condensed back end would cost the most; the punch overlaps
  // about 20 of them at once (14 are in contact), and the condensed back end
  // is the fastest (whole processes 8.0 s against 14.1 s full space and
  // 18.7 s matrix free).
  SceneSize scene     = scene_of(3, false, 22806, 1089, 32);
  scene.node_unknowns = 3;
  EXPECT_NE(choose_method(Parameters::Method::automatic, scene).method,
            Parameters::Method::condensed);
  scene.contact_fraction = 20. / 1089;
  const MethodChoice choice
    = choose_method(Parameters::Method::automatic, scene);
  EXPECT_EQ(choice.method, Parameters::Method::condensed);
  EXPECT_NE(choice.reason.find("1089 contact nodes (about 20 in contact at "
                               "once)"),
            std::string::npos)
    << choice.reason;
}

TEST(CostModel, MemoryDecides)
{
  // The condensed back end is fastest on the static scene on
  // quadrilaterals, but does not fit in 1.5 GB per rank; the matrix-free
  // back end does; with 100 MB nothing fits, and auto takes the back end of
  // least memory.
  SceneSize scene = scene_of(2, false, 526338, 512, 1);
  EXPECT_EQ(choose_method(Parameters::Method::automatic, scene).method,
            Parameters::Method::condensed);
  scene.memory_per_rank = 1.5e9;
  EXPECT_EQ(choose_method(Parameters::Method::automatic, scene).method,
            Parameters::Method::matrix_free);
  scene.memory_per_rank = 1e8;
  const MethodChoice choice
    = choose_method(Parameters::Method::automatic, scene);
  EXPECT_EQ(choice.method, Parameters::Method::matrix_free);
  EXPECT_NE(choice.reason.find("none fits"), std::string::npos);
}

TEST(CostModel, CostsGrowWithTheMeshAndShrinkWithRanks)
{
  for (const auto method : {Parameters::Method::condensed,
                            Parameters::Method::full_space,
                            Parameters::Method::matrix_free})
    for (const unsigned int dim : {2u, 3u})
      {
        const BackEndCost small
          = estimate_cost(method, scene_of(dim, false, 1e5, 300, 10));
        const BackEndCost large
          = estimate_cost(method, scene_of(dim, false, 1e6, 1000, 10));
        const BackEndCost shared
          = estimate_cost(method, scene_of(dim, false, 1e6, 1000, 10, 4));
        EXPECT_LT(small.bytes_per_rank, large.bytes_per_rank);
        EXPECT_LT(small.run_seconds(), large.run_seconds());
        EXPECT_LT(shared.bytes_per_rank, large.bytes_per_rank);
        EXPECT_GT(small.bytes_per_rank, library_bytes_per_rank);
      }
}


// The default Profile times (1/64, 1/2, 1) in a run that ends at t = 1/4:
// the one within the run is kept. Profile times a parameter file sets must
// lie in the run.
TEST(Parameters, DefaultProfileTimesWithinAShortRun)
{
  const auto parse = [](const std::string &text) {
    return TestScenes::parse_parameters(text);
  };
  const std::string short_run = "subsection Time\n"
                                "  set End time  = 0.25\n"
                                "  set Time step = 0.015625\n"
                                "end\n";
  EXPECT_EQ(parse(short_run).profile_times, std::vector<double>{0.015625});
  EXPECT_EQ(parse("").profile_times, (std::vector<double>{0.015625, 0.5, 1}));
  EXPECT_ANY_THROW(parse(short_run
                         + "subsection Output\n"
                           "  set Profile times = 0.015625, 0.5\n"
                           "end\n"));
}

TEST(InitialCycles, CoarseningsOfTheParameterFilesMesh)
{
  // Global refinements first, then the factors of 2 of a generated box's
  // Subdivisions; on p4est not with a Material id function (the cells of
  // the coarse box would carry other materials), on simplices (built anew
  // per cycle) always; a Gmsh file only by its refinements.
  Parameters::AllParameters parameters;
  parameters.subdivisions       = 12;
  parameters.global_refinements = 2;
  parameters.cell_type          = Parameters::CellType::hypercube;
  EXPECT_EQ(parameters.uniform_coarsenings(), 4u);
  const Parameters::AllParameters coarse = parameters.coarsened(3);
  EXPECT_EQ(coarse.global_refinements, 0u);
  EXPECT_EQ(coarse.subdivisions, 6u);
  EXPECT_EQ(parameters.coarsened(4).subdivisions, 3u);
  EXPECT_EQ(parameters.coarsened(0).subdivisions, 12u);
  EXPECT_EQ(parameters.coarsened(0).global_refinements, 2u);
  parameters.material_id_function = "x < 0.5 ? 1 : 2";
  EXPECT_EQ(parameters.uniform_coarsenings(), 2u);
  parameters.cell_type = Parameters::CellType::simplex;
  EXPECT_EQ(parameters.uniform_coarsenings(), 4u);
  parameters.mesh_file = "mesh.msh";
  EXPECT_EQ(parameters.uniform_coarsenings(), 2u);
}


TEST(Mesh, CoarseCellsNumberedAsP4estTrees)
{
  // A box of 7^3 coarse cells (Subdivisions = 14: 7 refined once), whose
  // generated numbering p4est would permute (asserted first, on the box as
  // GridGenerator numbers it): deal.II's coarse cells are p4est's trees in
  // p4est's order, and the colorized faces keep their boundary ids (7^2
  // level-0 faces on each side of the box). 7^3 cells, not more: the test
  // runs in Debug too.
  constexpr unsigned int n = 7;
  {
    Triangulation<3> generated;
    GridGenerator::subdivided_hyper_cube(generated, n);
    DynamicSparsityPattern connectivity;
    GridTools::get_vertex_connectivity_of_cells(generated, connectivity);
    std::vector<types::global_dof_index> tree_of_cell(generated.n_cells(0));
    SparsityTools::reorder_hierarchical(connectivity, tree_of_cell);
    unsigned int moved = 0;
    for (unsigned int i = 0; i < tree_of_cell.size(); ++i)
      moved += (tree_of_cell[i] != i);
    ASSERT_GT(moved, 0u);
  }
  Parameters::AllParameters parameters;
  parameters.dimension    = 3;
  parameters.lengths      = {1, 1, 1};
  parameters.subdivisions = 2 * n;
  parameters.cell_type    = Parameters::CellType::hypercube;
  const auto mesh
    = create_distributed_mesh<3>(parameters, MPI_COMM_WORLD, false);
  const auto &p4est_mesh
    = dynamic_cast<const parallel::distributed::Triangulation<3> &>(*mesh);
  ASSERT_EQ(p4est_mesh.n_cells(0), n * n * n);
  std::array<unsigned int, 6> faces_on_side{};
  for (const auto &cell : p4est_mesh.cell_iterators_on_level(0))
    {
      ASSERT_EQ(cell->id().get_coarse_cell_id(),
                static_cast<types::coarse_cell_id>(cell->index()));
      for (const auto &face : cell->face_iterators())
        if (face->at_boundary())
          ++faces_on_side.at(face->boundary_id());
    }
  for (const unsigned int count : faces_on_side)
    EXPECT_EQ(count, n * n);
}

namespace
{
  // The graph of cells that share a vertex, as p4est's tree order sees it.
  template <int dim>
  DynamicSparsityPattern
  vertex_connectivity(const Triangulation<dim> &mesh)
  {
    DynamicSparsityPattern connectivity;
    GridTools::get_vertex_connectivity_of_cells(mesh, connectivity);
    return connectivity;
  }

  // The cells of a mesh in a random order.
  template <int dim>
  void
  shuffle_cells(Triangulation<dim> &mesh, const unsigned int seed)
  {
    std::vector<CellData<dim>> cells;
    for (const auto &cell : mesh.active_cell_iterators())
      {
        CellData<dim> data(cell->n_vertices());
        for (const unsigned int v : cell->vertex_indices())
          data.vertices[v] = cell->vertex_index(v);
        cells.push_back(data);
      }
    std::shuffle(cells.begin(), cells.end(), std::mt19937(seed));
    const std::vector<Point<dim>> vertices = mesh.get_vertices();
    mesh.clear();
    mesh.create_triangulation(vertices, cells, SubCellData());
  }
} // namespace

TEST(Mesh, HierarchicalOrderIsDealIIs)
{
  // hierarchical_order() must give the numbers deal.II's
  // reorder_hierarchical() gives (p4est's tree order), exactly: on boxes of
  // hexahedra and triangles in their generated and in a random order, on a
  // mesh of two separate parts, and on random graphs, where ties between
  // candidate pivots are common.
  const auto expect_same = [](const DynamicSparsityPattern &graph) {
    std::vector<types::global_dof_index> expected(graph.n_rows());
    SparsityTools::reorder_hierarchical(graph, expected);
    EXPECT_EQ(hierarchical_order(graph), expected);
  };

  Triangulation<3> hexahedra;
  GridGenerator::subdivided_hyper_rectangle(hexahedra,
                                            {7, 5, 6},
                                            Point<3>(),
                                            Point<3>(1, 1, 1));
  expect_same(vertex_connectivity(hexahedra));
  shuffle_cells(hexahedra, 1);
  expect_same(vertex_connectivity(hexahedra));

  Triangulation<2> triangles;
  GridGenerator::subdivided_hyper_rectangle_with_simplices(triangles,
                                                           {12, 9},
                                                           Point<2>(),
                                                           Point<2>(1, 1));
  shuffle_cells(triangles, 2);
  expect_same(vertex_connectivity(triangles));

  Triangulation<2> left, right, two_parts;
  GridGenerator::subdivided_hyper_rectangle(left,
                                            {4, 6},
                                            Point<2>(),
                                            Point<2>(1, 1));
  GridGenerator::subdivided_hyper_rectangle(right,
                                            {5, 3},
                                            Point<2>(2, 0),
                                            Point<2>(3, 1));
  GridGenerator::merge_triangulations(left, right, two_parts);
  shuffle_cells(two_parts, 3);
  expect_same(vertex_connectivity(two_parts));

  std::mt19937 random(4);
  for (const unsigned int rows : {1u, 2u, 50u, 400u})
    {
      DynamicSparsityPattern                      graph(rows, rows);
      std::uniform_int_distribution<unsigned int> row(0, rows - 1);
      for (unsigned int r = 0; r < rows; ++r)
        graph.add(r, r);
      for (unsigned int e = 0; e < 3 * rows; ++e)
        {
          const unsigned int i = row(random), j = row(random);
          graph.add(i, j);
          graph.add(j, i);
        }
      expect_same(graph);
    }
}

TEST(Mesh, GmshBoundaryIdsKeptWhenCoarseCellsAreRenumbered)
{
  // A Gmsh mesh of hexahedra (the quarter sphere of the Hertz benchmark):
  // its coarse cells become p4est's trees in p4est's order, and every
  // boundary face keeps the boundary id the file gives it, found by its
  // centre.
  const std::string file
    = std::string(VC_MESH_DIR) + "/hertz_sphere_hexahedron_8.msh";
  Triangulation<3> file_mesh;
  GridIn<3>        grid_in;
  grid_in.attach_triangulation(file_mesh);
  std::ifstream in(file);
  grid_in.read_msh(in);
  std::map<std::array<long, 3>, types::boundary_id> id_at;
  const auto key = [](const Point<3> &p) {
    return std::array<long, 3>{{std::lround(p[0] * 1e6),
                                std::lround(p[1] * 1e6),
                                std::lround(p[2] * 1e6)}};
  };
  for (const auto &cell : file_mesh.active_cell_iterators())
    for (const auto &face : cell->face_iterators())
      if (face->at_boundary())
        id_at[key(face->center())] = face->boundary_id();

  Parameters::AllParameters parameters;
  parameters.dimension   = 3;
  parameters.cell_type   = Parameters::CellType::hypercube;
  parameters.mesh_file   = file;
  parameters.clamped_ids = {};
  parameters.contact_ids = {4};
  parameters.loaded_ids  = {};
  const auto mesh
    = create_distributed_mesh<3>(parameters, MPI_COMM_WORLD, false);
  unsigned int boundary_faces = 0;
  for (const auto &cell : mesh->cell_iterators_on_level(0))
    {
      ASSERT_EQ(cell->id().get_coarse_cell_id(),
                static_cast<types::coarse_cell_id>(cell->index()));
      for (const auto &face : cell->face_iterators())
        if (face->at_boundary())
          {
            ++boundary_faces;
            const auto found = id_at.find(key(face->center()));
            ASSERT_NE(found, id_at.end());
            EXPECT_EQ(face->boundary_id(), found->second);
          }
    }
  EXPECT_EQ(boundary_faces, id_at.size());
}


namespace
{
  // Whether every vertex of the mesh's active cells is the map
  // (x^2, 1 - (1 - y)^2[, z^2]) of a point of the uniform grid of n cells per
  // edge on the unit box, to rounding: its preimage times n is whole.
  template <int dim>
  bool
  vertices_on_mapped_grid(const Triangulation<dim> &mesh, const unsigned int n)
  {
    for (const auto &cell : mesh.active_cell_iterators())
      for (const unsigned int v : cell->vertex_indices())
        {
          const Point<dim> x = cell->vertex(v);
          for (unsigned int d = 0; d < dim; ++d)
            {
              const double box
                = (d == 1) ? 1 - std::sqrt(1 - x[d]) : std::sqrt(x[d]);
              if (std::abs(box * n - std::round(box * n)) > 1e-9)
                return false;
            }
        }
    return true;
  }
} // namespace

TEST(Mesh, BoxMapMovesTheBoxAndItsRefinements)
{
  // The Hertz sphere's grading, x^2 and 1 - (1 - y)^2, on the box of
  // Subdivisions = 12 hexahedra (built as 3 per edge refined twice) with
  // Global refinements = 1, and of 8 triangles ("/", built as 1 refined
  // three times) with Global refinements = 1: every vertex is the map of a
  // point of the uniform grid of 24 (16) per edge, also those that
  // refinement added. Without the map's manifold, refinement would put new
  // vertices at the midpoints of the mapped edges, off that grid.
  {
    Parameters::AllParameters parameters;
    parameters.dimension          = 3;
    parameters.lengths            = {1, 1, 1};
    parameters.subdivisions       = 12;
    parameters.global_refinements = 1;
    parameters.cell_type          = Parameters::CellType::hypercube;
    parameters.box_map            = "x^2; 1 - (1 - y)^2; z^2";
    parameters.box_map_inverse    = "sqrt(x); 1 - sqrt(1 - y); sqrt(z)";
    const auto mesh
      = create_distributed_mesh<3>(parameters, MPI_COMM_WORLD, false);
    EXPECT_EQ(mesh->n_cells(0), 27u);
    EXPECT_EQ(mesh->n_global_active_cells(), 24u * 24u * 24u);
    EXPECT_TRUE(vertices_on_mapped_grid(*mesh, 24));
    EXPECT_FALSE(vertices_on_mapped_grid(*mesh, 12));
  }
  {
    Parameters::AllParameters parameters;
    parameters.dimension          = 2;
    parameters.lengths            = {1, 1};
    parameters.subdivisions       = 8;
    parameters.global_refinements = 1;
    parameters.cell_type          = Parameters::CellType::simplex;
    parameters.box_map            = "x^2; 1 - (1 - y)^2";
    parameters.box_map_inverse    = "sqrt(x); 1 - sqrt(1 - y)";
    const auto mesh
      = create_distributed_mesh<2>(parameters, MPI_COMM_WORLD, false);
    EXPECT_EQ(mesh->n_global_active_cells(), 2u * 16u * 16u);
    EXPECT_TRUE(vertices_on_mapped_grid(*mesh, 16));
  }
}


int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  ::testing::InitGoogleTest(&argc, argv);
  // Every rank runs every test; only rank 0 reports, but a failure on any
  // rank makes the exit status non-zero.
  if (Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) != 0)
    delete ::testing::UnitTest::GetInstance()->listeners().Release(
      ::testing::UnitTest::GetInstance()->listeners().default_result_printer());
  const int status = RUN_ALL_TESTS();
  return Utilities::MPI::max(status, MPI_COMM_WORLD);
}
