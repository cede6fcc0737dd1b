#ifndef viscoplastic_contact_hardening_plasticity_h
#define viscoplastic_contact_hardening_plasticity_h

#include <deal.II/base/symmetric_tensor.h>

#include "material.h"
#include "material_law.h"

namespace ViscoContact
{
  using namespace dealii;

  // @sect3{Rate-independent plasticity with isotropic hardening}
  //
  // The second law behind MaterialLaw (material_law.h), the one of deal.II's
  // step-42: von Mises plasticity with linear isotropic hardening, the yield
  // stress sigma_Y + H alpha growing with the equivalent plastic strain
  // alpha (the point's internal variable). Backward Euler is the radial
  // return of the deviator of the trial stress, exact for this law:
  //
  //   q_tr = sqrt(3/2) |dev trial|, f = q_tr - (sigma_Y + H alpha_{n-1}),
  //   f <= 0: sigma = trial; else d_gamma = f / (3 mu + H),
  //   sigma = trial - 3 mu d_gamma dev trial / q_tr,
  //   alpha_n = alpha_{n-1} + d_gamma,
  //
  // with the consistent tangent
  //   C = K I(x)I + 2 mu beta I_dev - 2 mu (3 mu / (3 mu + H) - 3 mu d_gamma
  //       / q_tr) n(x)n,   beta = 1 - 3 mu d_gamma / q_tr, n = dev / |dev|.
  //
  // With H = 0 it is perfect plasticity, the limit of Perzyna's law as the
  // viscosity goes to zero. The law has no rate: it runs with the implicit
  // update only, in 3D and in 2D plane strain (the parameters refuse the
  // rest). Its elastic part is Hooke's law of an elastic PerzynaMaterial.
  template <int dim>
  class HardeningPlasticity : public MaterialLaw<dim>
  {
  public:
    HardeningPlasticity(const double young_modulus,
                        const double poisson_ratio,
                        const double yield_stress,
                        const double hardening_modulus,
                        const bool   plane_strain);

    const SymmetricTensor<4, dim> &
    elasticity_tensor() const override;
    double
    largest_elastic_eigenvalue() const override;
    double
    out_of_plane_elastic_stress(
      const SymmetricTensor<2, dim> &strain) const override;
    double
    complementary_energy(const SymmetricTensor<2, dim> &tau,
                         const double                   tau_zz) const override;
    double
    equivalent_stress(const SymmetricTensor<2, dim> &tau,
                      const double                   tau_zz) const override;
    double
    yield_stress() const override;
    bool
    is_plastic() const override;

    bool
    has_rate_form() const override;
    double
    explicit_stability_limit() const override;
    SymmetricTensor<2, dim>
    rate(const SymmetricTensor<2, dim> &sigma,
         const double                   sigma_zz,
         double                        &rate_zz,
         double                        &internal_variable) const override;

    SymmetricTensor<2, dim>
    implicit_update(const SymmetricTensor<2, dim> &trial,
                    const double                   trial_zz,
                    const double                   time_step,
                    double                        &stress_zz,
                    SymmetricTensor<4, dim>       *tangent,
                    double &internal_variable) const override;
    bool
    internal_variable_is_guess() const override;

    // The radial return in 3D: sigma from the trial stress, alpha updated,
    // d sigma / d eps into tangent if given.
    SymmetricTensor<2, 3>
    return_map(const SymmetricTensor<2, 3> &trial,
               double                      &alpha,
               SymmetricTensor<4, 3>       *tangent) const;

  private:
    PerzynaMaterial<dim> elastic;
    PerzynaMaterial<3>   elastic_3d;
    double               sigma_yield;
    double               hardening;
    double               shear_modulus;
    double               bulk_modulus;
    bool                 plane_strain;
  };
} // namespace ViscoContact

#endif
