// Rate-independent von Mises plasticity with linear isotropic hardening
// (hardening_plasticity.h): the radial return and its consistent tangent,
// in 3D and, through the 3D law, in 2D plane strain.

#include <deal.II/base/exceptions.h>

#include "hardening_plasticity.h"

#include <cmath>
#include <limits>

namespace ViscoContact
{
  template <int dim>
  HardeningPlasticity<dim>::HardeningPlasticity(const double young_modulus,
                                                const double poisson_ratio,
                                                const double yield_stress,
                                                const double hardening_modulus,
                                                const bool   plane_strain)
    : elastic(young_modulus,
              poisson_ratio,
              1.,
              yield_stress,
              false,
              plane_strain)
    , elastic_3d(young_modulus, poisson_ratio, 1., yield_stress, false)
    , sigma_yield(yield_stress)
    , hardening(hardening_modulus)
    , shear_modulus(young_modulus / (2 * (1 + poisson_ratio)))
    , bulk_modulus(young_modulus / (3 * (1 - 2 * poisson_ratio)))
    , plane_strain(dim == 2 && plane_strain)
  {
    AssertThrow(dim == 3 || this->plane_strain,
                ExcMessage("Law = hardening plasticity needs plane strain in "
                           "2D."));
  }



  template <int dim>
  const SymmetricTensor<4, dim> &
  HardeningPlasticity<dim>::elasticity_tensor() const
  {
    return elastic.elasticity_tensor();
  }



  template <int dim>
  double
  HardeningPlasticity<dim>::largest_elastic_eigenvalue() const
  {
    return elastic.largest_elastic_eigenvalue();
  }



  template <int dim>
  double
  HardeningPlasticity<dim>::out_of_plane_elastic_stress(
    const SymmetricTensor<2, dim> &strain) const
  {
    return elastic.out_of_plane_elastic_stress(strain);
  }



  template <int dim>
  double
  HardeningPlasticity<dim>::complementary_energy(
    const SymmetricTensor<2, dim> &tau,
    const double                   tau_zz) const
  {
    return elastic.complementary_energy(tau, tau_zz);
  }



  template <int dim>
  double
  HardeningPlasticity<dim>::equivalent_stress(
    const SymmetricTensor<2, dim> &tau,
    const double                   tau_zz) const
  {
    return elastic.equivalent_stress(tau, tau_zz);
  }



  template <int dim>
  double
  HardeningPlasticity<dim>::yield_stress() const
  {
    return sigma_yield;
  }



  template <int dim>
  bool
  HardeningPlasticity<dim>::is_plastic() const
  {
    return true;
  }



  // No rate: the parameters allow this law with the implicit update only.
  template <int dim>
  bool
  HardeningPlasticity<dim>::has_rate_form() const
  {
    return false;
  }



  template <int dim>
  double
  HardeningPlasticity<dim>::explicit_stability_limit() const
  {
    return std::numeric_limits<double>::infinity();
  }



  template <int dim>
  SymmetricTensor<2, dim>
  HardeningPlasticity<dim>::rate(const SymmetricTensor<2, dim> &,
                                 const double,
                                 double &,
                                 double &) const
  {
    AssertThrow(false,
                ExcMessage("Law = hardening plasticity has no rate for the "
                           "explicit history update."));
    return {};
  }



  // @sect4{HardeningPlasticity::return_map}
  template <int dim>
  SymmetricTensor<2, 3>
  HardeningPlasticity<dim>::return_map(const SymmetricTensor<2, 3> &trial,
                                       double                      &alpha,
                                       SymmetricTensor<4, 3> *tangent) const
  {
    const SymmetricTensor<2, 3> s       = deviator(trial);
    const double                q_trial = std::sqrt(1.5) * s.norm();
    const double                f = q_trial - (sigma_yield + hardening * alpha);
    if (f <= 0 || q_trial == 0)
      {
        if (tangent != nullptr)
          *tangent = elastic_3d.elasticity_tensor();
        return trial;
      }
    const double three_mu = 3 * shear_modulus;
    const double d_gamma  = f / (three_mu + hardening);
    const double beta     = 1 - three_mu * d_gamma / q_trial;
    alpha += d_gamma;
    if (tangent != nullptr)
      {
        const SymmetricTensor<2, 3> n = s / s.norm();
        *tangent                      = bulk_modulus
                     * outer_product(unit_symmetric_tensor<3>(),
                                     unit_symmetric_tensor<3>())
                   + 2 * shear_modulus * beta * deviator_tensor<3>()
                   - 2 * shear_modulus
                       * (three_mu / (three_mu + hardening) - (1 - beta))
                       * outer_product(n, n);
      }
    return trial - (1 - beta) * s;
  }



  // @sect4{HardeningPlasticity::implicit_update}
  //
  // The step's length does not enter a rate-independent law. In 2D plane
  // strain the in-plane trial stress and its zz component make the 3D
  // trial stress; the in-plane components of the 3D sigma and tangent are
  // returned, and sigma_zz beside them.
  template <int dim>
  SymmetricTensor<2, dim>
  HardeningPlasticity<dim>::implicit_update(
    const SymmetricTensor<2, dim> &trial,
    const double                   trial_zz,
    const double,
    double                  &stress_zz,
    SymmetricTensor<4, dim> *tangent,
    double                  &internal_variable) const
  {
    SymmetricTensor<2, 3> trial_3d;
    for (unsigned int i = 0; i < dim; ++i)
      for (unsigned int j = i; j < dim; ++j)
        trial_3d[i][j] = trial[i][j];
    if (dim == 2)
      trial_3d[2][2] = trial_zz;
    SymmetricTensor<4, 3>       tangent_3d;
    const SymmetricTensor<2, 3> sigma_3d
      = return_map(trial_3d,
                   internal_variable,
                   tangent != nullptr ? &tangent_3d : nullptr);
    SymmetricTensor<2, dim> sigma;
    for (unsigned int i = 0; i < dim; ++i)
      for (unsigned int j = i; j < dim; ++j)
        sigma[i][j] = sigma_3d[i][j];
    stress_zz = (dim == 2 ? sigma_3d[2][2] : 0.);
    if (tangent != nullptr)
      for (unsigned int i = 0; i < dim; ++i)
        for (unsigned int j = i; j < dim; ++j)
          for (unsigned int k = 0; k < dim; ++k)
            for (unsigned int l = k; l < dim; ++l)
              (*tangent)[i][j][k][l] = tangent_3d[i][j][k][l];
    return sigma;
  }



  // alpha is the law's state: only an accepted step updates it.
  template <int dim>
  bool
  HardeningPlasticity<dim>::internal_variable_is_guess() const
  {
    return false;
  }



  template class HardeningPlasticity<2>;
  template class HardeningPlasticity<3>;
} // namespace ViscoContact
