#ifndef viscoplastic_contact_material_h
#define viscoplastic_contact_material_h

#include <deal.II/base/symmetric_tensor.h>

#include "material_law.h"

#include <memory>

namespace ViscoContact
{
  using namespace dealii;

  // The state of the material at one stress point (a cell of a simplex mesh,
  // a Gauss point of a hypercube mesh).
  //
  // In 2D plane strain eps_zz = 0, but sigma_zz and the history's zz part
  // are not: a 2D record carries them (zero in plane stress); a 3D record has
  // them among its components.
  template <int dim>
  struct OutOfPlaneState
  {};

  template <>
  struct OutOfPlaneState<2>
  {
    double stress_zz  = 0;
    double history_zz = 0;
    double rate_zz    = 0;
  };

  template <int dim>
  struct QuadraturePointHistory : OutOfPlaneState<dim>
  {
    SymmetricTensor<2, dim> stress;  // sigma_n
    SymmetricTensor<2, dim> history; // H_{n+1}: the history part of the
                                     // stress of the next step
    double                  internal_variable = 0; // the law's (material_law.h)
    SymmetricTensor<2, dim> rate; // G(sigma_n): the history rate of the
                                  // last update, for the error estimate
                                  // (doc/adaptivity.md)
  };

  // @sect3{The Perzyna viscoplastic material}
  //
  // Everything that happens at one quadrature point: Hooke's law
  // (plane stress or plane strain in 2D, isotropic in 3D), the von Mises set K,
  // the orthogonal projection onto K in the energy inner product (E tau, tau)
  // and the Perzyna rate G(sigma) = -(1/(2 lambda)) E (sigma - P_K sigma) of
  // doc/model.md, section 1.
  //
  // In 2D the projection is the solution of one scalar monotone equation for
  // a Lagrange multiplier, solved to machine precision; in 3D, for isotropic
  // E, it is the radial return of the deviator.
  template <int dim>
  class PerzynaMaterial : public MaterialLaw<dim>
  {
  public:
    // plasticity = false: an elastic material (G = 0), whose stress points
    // keep no history. plane_strain (2D): eps_zz = 0 instead of
    // sigma_zz = 0.
    PerzynaMaterial(const double young_modulus,
                    const double poisson_ratio,
                    const double viscosity,
                    const double yield_stress,
                    const bool   plasticity   = true,
                    const bool   plane_strain = false);

    const SymmetricTensor<4, dim> &
    elasticity_tensor() const override;

    // @sect4{As a MaterialLaw}
    //
    // The interface of material_law.h: the rate G(sigma) of the explicit
    // update with the multiplier of the projection as the internal variable
    // (a starting guess), and the implicit update with a = k/(2 lambda).
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

    // The von Mises equivalent stress; tau is in K iff it is <= sigma_Y.
    double
    equivalent_stress(const SymmetricTensor<2, dim> &tau) const;

    // @sect4{Plane strain}
    //
    // In 2D plane strain the state is the in-plane tensor and its zz
    // component, and the law is the 3D one on the tensor they make
    // (is_plane_strain(); elsewhere these ignore the zz arguments and are
    // the functions above). The zz component of E eps is lambda tr(eps);
    // the implicit update returns the consistent tangent d sigma / d eps
    // of the in-plane components itself (E included).
    bool
    is_plane_strain() const;
    double
    out_of_plane_elastic_stress(
      const SymmetricTensor<2, dim> &strain) const override;
    double
    equivalent_stress(const SymmetricTensor<2, dim> &tau,
                      const double                   tau_zz) const override;
    SymmetricTensor<2, dim>
    viscoplastic_rate(const SymmetricTensor<2, dim> &sigma,
                      const double                   sigma_zz,
                      double                        &rate_zz,
                      double *multiplier = nullptr) const;
    SymmetricTensor<2, dim>
    implicit_stress_update(const SymmetricTensor<2, dim> &trial,
                           const double                   trial_zz,
                           const double                   a,
                           double                        &stress_zz,
                           SymmetricTensor<4, dim>       *consistent_tangent,
                           double                        *multiplier) const;
    // (E^-1 tau, tau), for the error estimate's norm.
    double
    complementary_energy(const SymmetricTensor<2, dim> &tau,
                         const double                   tau_zz) const override;

    // P_K tau in the inner product (E a, b). If given, *multiplier is on
    // input a guess of the Lagrange multiplier of the constraint (e.g. the
    // one of the previous time step at this point, which saves iterations
    // in 2D) and on output the multiplier itself (0 inside K).
    SymmetricTensor<2, dim>
    project_onto_yield_set(const SymmetricTensor<2, dim> &tau,
                           double *multiplier = nullptr) const;

    // G(sigma) = -(1/(2 lambda)) E (sigma - P_K sigma); multiplier as for
    // project_onto_yield_set().
    SymmetricTensor<2, dim>
    viscoplastic_rate(const SymmetricTensor<2, dim> &sigma,
                      double *multiplier = nullptr) const;

    // The backward-Euler (implicit) stress update of doc/model.md, section 3:
    // the sigma with sigma + a E (sigma - P_K sigma) = trial, a = k/(2 lambda),
    // solved to machine precision. If tangent is given it receives
    // d sigma / d trial (multiply by E for the consistent tangent
    // d sigma / d eps); multiplier as for project_onto_yield_set().
    SymmetricTensor<2, dim>
    implicit_stress_update(const SymmetricTensor<2, dim> &trial,
                           const double                   a,
                           SymmetricTensor<4, dim>       *tangent = nullptr,
                           double *multiplier = nullptr) const;

    // (E a, b), the energy inner product the projection is orthogonal in.
    double
    energy_product(const SymmetricTensor<2, dim> &a,
                   const SymmetricTensor<2, dim> &b) const;

    // The largest eigenvalue of E: it sets the stability limit of the
    // explicit history update.
    double
    largest_elastic_eigenvalue() const override;

    double
    viscosity() const;
    double
    yield_stress() const override;
    bool
    is_plastic() const override;

  private:
    double                  young_modulus;
    double                  poisson_ratio;
    double                  lambda_viscosity;
    double                  sigma_yield;
    bool                    plastic;
    bool                    plane_strain;
    SymmetricTensor<4, dim> stiffness;
    // E^-1 (plane stress and 3D), for the error estimate's norm.
    SymmetricTensor<4, dim> compliance;
    // Plane strain: the same material in 3D.
    std::shared_ptr<const PerzynaMaterial<3>> three_dimensional;
  };

  // The dimension-specific members, defined in material.cc.
  template <>
  double
  PerzynaMaterial<2>::equivalent_stress(const SymmetricTensor<2, 2> &) const;
  template <>
  double
  PerzynaMaterial<3>::equivalent_stress(const SymmetricTensor<2, 3> &) const;
  template <>
  SymmetricTensor<2, 2>
  PerzynaMaterial<2>::project_onto_yield_set(const SymmetricTensor<2, 2> &,
                                             double *) const;
  template <>
  SymmetricTensor<2, 3>
  PerzynaMaterial<3>::project_onto_yield_set(const SymmetricTensor<2, 3> &,
                                             double *) const;
  template <>
  SymmetricTensor<2, 2>
  PerzynaMaterial<2>::implicit_stress_update(const SymmetricTensor<2, 2> &,
                                             const double,
                                             SymmetricTensor<4, 2> *,
                                             double *) const;
  template <>
  SymmetricTensor<2, 3>
  PerzynaMaterial<3>::implicit_stress_update(const SymmetricTensor<2, 3> &,
                                             const double,
                                             SymmetricTensor<4, 3> *,
                                             double *) const;
} // namespace ViscoContact

#endif
