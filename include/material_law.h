#ifndef viscoplastic_contact_material_law_h
#define viscoplastic_contact_material_law_h

#include <deal.II/base/symmetric_tensor.h>

namespace ViscoContact
{
  using namespace dealii;

  // @sect3{Material laws}
  //
  // What the time loop asks of the material at a stress point, behind one
  // interface, so that a law is one class (and one file): Hooke's law and
  // its inverse (for the estimate's norm), the von Mises stress, and how
  // the stress leaves the elastic range, in the two forms the stress
  // updates of doc/model.md, section 3, use: a rate G(sigma) for the
  // explicit history update (a viscoplastic law has one; a rate-independent
  // law has none and runs with the implicit update only), and the
  // backward-Euler update of a step with its consistent tangent for the
  // implicit one.
  //
  // The state a stress point carries is the same for every law and is
  // declared once (QuadraturePointHistory, material.h), so that
  // checkpoints, the transfer to a new mesh and the output follow it: sigma,
  // the history H (for the implicit update sigma - E eps), the rate of the
  // last update, and one scalar internal variable whose meaning is the
  // law's (internal_variable: Perzyna's multiplier of the last projection,
  // a starting guess; the equivalent plastic strain of hardening
  // plasticity). In 2D plane strain each tensor has its zz component beside
  // it; the methods below take and give it (zero in plane stress and 3D).
  //
  // PerzynaMaterial (material.h) is the paper's viscoplastic law,
  // HardeningPlasticity (hardening_plasticity.h) rate-independent von Mises
  // plasticity with linear isotropic hardening.
  template <int dim>
  class MaterialLaw
  {
  public:
    virtual ~MaterialLaw() = default;

    // Hooke's law E, its largest eigenvalue (the scale of stresses per
    // strain), the zz stress lambda tr(eps) of a strain in plane strain (0
    // otherwise), and (E^-1 tau, tau).
    virtual const SymmetricTensor<4, dim> &
    elasticity_tensor() const = 0;
    virtual double
    largest_elastic_eigenvalue() const = 0;
    virtual double
    out_of_plane_elastic_stress(
      const SymmetricTensor<2, dim> &strain) const = 0;
    virtual double
    complementary_energy(const SymmetricTensor<2, dim> &tau,
                         const double                   tau_zz) const = 0;

    // The von Mises stress and the initial yield stress sigma_Y; whether
    // the law leaves the elastic range at all (else it keeps no history).
    virtual double
    equivalent_stress(const SymmetricTensor<2, dim> &tau,
                      const double                   tau_zz) const = 0;
    virtual double
    yield_stress() const = 0;
    virtual bool
    is_plastic() const = 0;

    // @sect4{The explicit history update}
    //
    // Whether the law has a rate G(sigma), the largest step of the explicit
    // history update that is stable with it (infinity for an elastic
    // material), and G(sigma) (with its zz component); internal_variable is
    // the point's, which the law may update.
    virtual bool
    has_rate_form() const = 0;
    virtual double
    explicit_stability_limit() const = 0;
    virtual SymmetricTensor<2, dim>
    rate(const SymmetricTensor<2, dim> &sigma,
         const double                   sigma_zz,
         double                        &rate_zz,
         double                        &internal_variable) const = 0;

    // @sect4{The implicit update}
    //
    // sigma_n of a step of length k from the trial stress E eps_n + H (and
    // its zz component), and, if tangent is given, the consistent tangent
    // d sigma / d eps (E included). internal_variable: on input the point's
    // at the start of the step, on output its value at sigma_n (the caller
    // keeps it only once the step is accepted, unless it is only a guess:
    // internal_variable_is_guess()).
    virtual SymmetricTensor<2, dim>
    implicit_update(const SymmetricTensor<2, dim> &trial,
                    const double                   trial_zz,
                    const double                   time_step,
                    double                        &stress_zz,
                    SymmetricTensor<4, dim>       *tangent,
                    double                        &internal_variable) const = 0;
    virtual bool
    internal_variable_is_guess() const = 0;
  };
} // namespace ViscoContact

#endif
