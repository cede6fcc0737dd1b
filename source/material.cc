#include <deal.II/base/exceptions.h>

#include "material.h"

#include <cmath>
#include <limits>

namespace ViscoContact
{
  // @sect4{PerzynaMaterial::PerzynaMaterial}
  //
  // Hooke's law is stored as a rank-4 symmetric tensor
  // E = lambda* I (x) I + 2 mu* Id. In 2D (plane stress) the Lame-type
  // constants are lambda* = E k/(1-k^2), 2 mu* = E/(1+k), which is the
  // formula of model.md; in 3D they are the usual isotropic ones.
  template <int dim>
  PerzynaMaterial<dim>::PerzynaMaterial(const double young_modulus,
                                        const double poisson_ratio,
                                        const double viscosity,
                                        const double yield_stress)
    : young_modulus(young_modulus)
    , poisson_ratio(poisson_ratio)
    , lambda_viscosity(viscosity)
    , sigma_yield(yield_stress)
  {
    const double E = young_modulus, k = poisson_ratio;
    const double lame_lambda =
      (dim == 2 ? E * k / (1 - k * k) : E * k / ((1 + k) * (1 - 2 * k)));
    const double two_mu = E / (1 + k);
    stiffness =
      lame_lambda * outer_product(unit_symmetric_tensor<dim>(),
                                  unit_symmetric_tensor<dim>()) +
      two_mu * identity_tensor<dim>();
  }



  template <int dim>
  const SymmetricTensor<4, dim> &
  PerzynaMaterial<dim>::elasticity_tensor() const
  {
    return stiffness;
  }



  template <int dim>
  double
  PerzynaMaterial<dim>::energy_product(const SymmetricTensor<2, dim> &a,
                                       const SymmetricTensor<2, dim> &b) const
  {
    return (stiffness * a) * b;
  }



  template <int dim>
  SymmetricTensor<2, dim>
  PerzynaMaterial<dim>::viscoplastic_rate(
    const SymmetricTensor<2, dim> &sigma) const
  {
    return (-1. / (2. * lambda_viscosity)) *
           (stiffness * (sigma - project_onto_yield_set(sigma)));
  }



  template <int dim>
  double
  PerzynaMaterial<dim>::smallest_elastic_eigenvalue() const
  {
    const double E = young_modulus, k = poisson_ratio;
    // 2D: E/(1-k) on the spherical part, E/(1+k) on the deviatoric part;
    // 3D: 3 kappa = E/(1-2k) and 2 mu = E/(1+k).
    return (dim == 2 ? std::min(E / (1 - k), E / (1 + k)) :
                       std::min(E / (1 - 2 * k), E / (1 + k)));
  }



  template <int dim>
  double
  PerzynaMaterial<dim>::largest_elastic_eigenvalue() const
  {
    const double E = young_modulus, k = poisson_ratio;
    return (dim == 2 ? std::max(E / (1 - k), E / (1 + k)) :
                       std::max(E / (1 - 2 * k), E / (1 + k)));
  }



  template <int dim>
  double
  PerzynaMaterial<dim>::viscosity() const
  {
    return lambda_viscosity;
  }



  template <int dim>
  double
  PerzynaMaterial<dim>::yield_stress() const
  {
    return sigma_yield;
  }



  // @sect4{The 2D plane-stress von Mises set and its E-norm projection}
  //
  // In the orthonormal coordinates a = (t11+t22)/sqrt2, b = (t11-t22)/sqrt2,
  // c = sqrt2 t12 (so that tau:tau = a^2+b^2+c^2) both the plane-stress E
  // and the quadratic form of K are diagonal:
  //   E = diag(E/(1-k), E/(1+k), E/(1+k)),
  //   t11^2 + t22^2 - t11 t22 + 3 t12^2 = a^2/2 + 3/2 (b^2 + c^2) = x.Mx.
  // The optimality condition E (x - y) + mu M x = 0 of the projection
  // min |x - y|_E^2 subject to x.Mx <= sigma_Y^2 gives
  // x_i(mu) = E_i/(E_i + mu M_i) y_i, and mu > 0 is the root of the scalar
  // equation |x(mu)|_M = sigma_Y, whose left side decreases strictly.
  // We apply Newton's method to phi(mu) = 1/|x(mu)|_M - 1/sigma_Y: phi is
  // affine in mu when M_i/E_i is the same for all i, and close to affine
  // otherwise, so Newton converges in a few steps from any distance.
  // A bracket [lower, upper] of the root is kept and bisection takes over
  // should an iterate ever leave it; the iteration stops at machine
  // precision.
  namespace
  {
    struct PlaneStressCoordinates
    {
      double x[3];
    };

    PlaneStressCoordinates
    to_coordinates(const SymmetricTensor<2, 2> &t)
    {
      return {{(t[0][0] + t[1][1]) / std::sqrt(2.),
               (t[0][0] - t[1][1]) / std::sqrt(2.),
               std::sqrt(2.) * t[0][1]}};
    }

    SymmetricTensor<2, 2>
    from_coordinates(const PlaneStressCoordinates &c)
    {
      SymmetricTensor<2, 2> t;
      t[0][0] = (c.x[0] + c.x[1]) / std::sqrt(2.);
      t[1][1] = (c.x[0] - c.x[1]) / std::sqrt(2.);
      t[0][1] = c.x[2] / std::sqrt(2.);
      return t;
    }

    constexpr double yield_form[3] = {0.5, 1.5, 1.5};

    double
    yield_norm(const PlaneStressCoordinates &c)
    {
      double s = 0;
      for (unsigned int i = 0; i < 3; ++i)
        s += yield_form[i] * c.x[i] * c.x[i];
      return std::sqrt(s);
    }
  } // namespace



  template <>
  double
  PerzynaMaterial<2>::equivalent_stress(const SymmetricTensor<2, 2> &tau) const
  {
    return yield_norm(to_coordinates(tau));
  }



  template <>
  SymmetricTensor<2, 2>
  PerzynaMaterial<2>::project_onto_yield_set(const SymmetricTensor<2, 2> &tau,
                                             double *multiplier) const
  {
    const PlaneStressCoordinates y = to_coordinates(tau);
    if (multiplier != nullptr)
      *multiplier = 0;
    if (yield_norm(y) <= sigma_yield)
      return tau;

    const double k              = poisson_ratio;
    const double E_diagonal[3]  = {young_modulus / (1 - k),
                                  young_modulus / (1 + k),
                                  young_modulus / (1 + k)};
    const auto   x_of           = [&](const double mu) {
      PlaneStressCoordinates x;
      for (unsigned int i = 0; i < 3; ++i)
        x.x[i] = E_diagonal[i] / (E_diagonal[i] + mu * yield_form[i]) * y.x[i];
      return x;
    };

    // With t_i = M_i/E_i, |y|_M/(1 + mu t_max) <= |x(mu)|_M <=
    // |y|_M/(1 + mu t_min): the root lies in [mu_lower, mu_upper] below, and
    // the lower end, exact when the deviatoric part dominates, is the start.
    double t_min = std::numeric_limits<double>::max(), t_max = 0;
    for (unsigned int i = 0; i < 3; ++i)
      if (y.x[i] != 0)
        {
          t_min = std::min(t_min, yield_form[i] / E_diagonal[i]);
          t_max = std::max(t_max, yield_form[i] / E_diagonal[i]);
        }
    const double excess = yield_norm(y) / sigma_yield - 1;
    double       lower  = excess / t_max;
    double       upper  = excess / t_min;
    double       mu     = lower;
    for (unsigned int iteration = 0; iteration < 100; ++iteration)
      {
        const PlaneStressCoordinates x    = x_of(mu);
        const double                 norm = yield_norm(x);
        const double                 phi  = 1. / norm - 1. / sigma_yield;
        if (phi < 0)
          lower = std::max(lower, mu);
        else
          upper = std::min(upper, mu);
        if (std::abs(phi) * sigma_yield <=
            4 * std::numeric_limits<double>::epsilon())
          break;

        // d|x|_M/dmu = -sum_i M_i^2 x_i^2 / (E_i + mu M_i) / |x|_M.
        double d_norm = 0;
        for (unsigned int i = 0; i < 3; ++i)
          d_norm -= yield_form[i] * yield_form[i] * x.x[i] * x.x[i] /
                    (E_diagonal[i] + mu * yield_form[i]);
        d_norm /= norm;
        const double d_phi = -d_norm / (norm * norm);

        double next = mu - phi / d_phi;
        if (!(next > lower && next < upper))
          next = 0.5 * (lower + upper);
        if (std::abs(next - mu) <=
            2 * std::numeric_limits<double>::epsilon() * std::abs(next))
          {
            mu = next;
            break;
          }
        mu = next;
      }

    if (multiplier != nullptr)
      *multiplier = mu;
    return from_coordinates(x_of(mu));
  }



  // @sect4{The 3D von Mises set and the radial return}
  //
  // K = {(3/2)|dev tau|^2 <= sigma_Y^2}. For isotropic E the optimality
  // condition splits into the spherical part (unchanged) and the deviator,
  // which is scaled radially onto the yield surface.
  template <>
  double
  PerzynaMaterial<3>::equivalent_stress(const SymmetricTensor<2, 3> &tau) const
  {
    const SymmetricTensor<2, 3> s = deviator(tau);
    return std::sqrt(1.5 * (s * s));
  }



  template <>
  SymmetricTensor<2, 3>
  PerzynaMaterial<3>::project_onto_yield_set(const SymmetricTensor<2, 3> &tau,
                                             double *multiplier) const
  {
    const double equivalent = equivalent_stress(tau);
    if (multiplier != nullptr)
      *multiplier = 0;
    if (equivalent <= sigma_yield)
      return tau;
    // E(x - y) + 3 mu dev x = 0 with 2 G = E/(1+k) gives
    // dev x = 2G/(2G + 3 mu) dev y.
    const double scaling = sigma_yield / equivalent;
    if (multiplier != nullptr)
      *multiplier = young_modulus / (1 + poisson_ratio) * (1 / scaling - 1) / 3;
    const SymmetricTensor<2, 3> spherical = tau - deviator(tau);
    return spherical + scaling * deviator(tau);
  }



  template class PerzynaMaterial<2>;
  template class PerzynaMaterial<3>;
} // namespace ViscoContact
