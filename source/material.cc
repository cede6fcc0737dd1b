#include <deal.II/base/exceptions.h>

#include "material.h"

#include <array>
#include <cmath>
#include <limits>

namespace ViscoContact
{
  // @sect4{PerzynaMaterial::PerzynaMaterial}
  //
  // Hooke's law is stored as a rank-4 symmetric tensor
  // E = lambda* I (x) I + 2 mu* Id. In 2D plane stress the Lame-type
  // constants are lambda* = E k/(1-k^2), 2 mu* = E/(1+k), which is the
  // formula of doc/model.md; in 3D and in 2D plane strain (the in-plane
  // part of the 3D law) they are the usual isotropic ones.
  template <int dim>
  PerzynaMaterial<dim>::PerzynaMaterial(const double young_modulus,
                                        const double poisson_ratio,
                                        const double viscosity,
                                        const double yield_stress,
                                        const bool   plasticity,
                                        const bool   plane_strain)
    : young_modulus(young_modulus)
    , poisson_ratio(poisson_ratio)
    , lambda_viscosity(viscosity)
    , sigma_yield(yield_stress)
    , plastic(plasticity)
    , plane_strain(dim == 2 && plane_strain)
  {
    if (this->plane_strain)
      three_dimensional
        = std::make_shared<const PerzynaMaterial<3>>(young_modulus,
                                                     poisson_ratio,
                                                     viscosity,
                                                     yield_stress,
                                                     plasticity);
    const double E = young_modulus, k = poisson_ratio;
    const double lame_lambda
      = (dim == 2 && !this->plane_strain ? E * k / (1 - k * k)
                                         : E * k / ((1 + k) * (1 - 2 * k)));
    const double two_mu = E / (1 + k);
    stiffness           = lame_lambda
                  * outer_product(unit_symmetric_tensor<dim>(),
                                  unit_symmetric_tensor<dim>())
                + two_mu * identity_tensor<dim>();
    // Inverted at the scale of E's largest eigenvalue.
    const double modulus = largest_elastic_eigenvalue();
    compliance           = invert(stiffness / modulus) / modulus;
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
  PerzynaMaterial<dim>::viscoplastic_rate(const SymmetricTensor<2, dim> &sigma,
                                          double *multiplier) const
  {
    return (-1. / (2. * lambda_viscosity))
           * (stiffness * (sigma - project_onto_yield_set(sigma, multiplier)));
  }



  template <int dim>
  double
  PerzynaMaterial<dim>::largest_elastic_eigenvalue() const
  {
    const double E = young_modulus, k = poisson_ratio;
    // Plane stress: E/(1-k) on the spherical part, E/(1+k) on the
    // deviatoric part; 3D and plane strain: 3 kappa = E/(1-2k) and
    // 2 mu = E/(1+k).
    return (dim == 2 && !plane_strain ? std::max(E / (1 - k), E / (1 + k))
                                      : std::max(E / (1 - 2 * k), E / (1 + k)));
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



  template <int dim>
  bool
  PerzynaMaterial<dim>::is_plastic() const
  {
    return plastic;
  }



  // @sect4{Plane strain}
  //
  // The 2D state (tau, tau_zz) is the 3D tensor with these components
  // (tau_xz = tau_yz = 0, which the isotropic law keeps zero), and every
  // function is the 3D one on it.
  namespace
  {
    template <int dim>
    SymmetricTensor<2, 3>
    embed(const SymmetricTensor<2, dim> &tau, const double tau_zz)
    {
      SymmetricTensor<2, 3> t;
      for (unsigned int i = 0; i < dim; ++i)
        for (unsigned int j = i; j < dim; ++j)
          t[i][j] = tau[i][j];
      t[2][2] = tau_zz;
      return t;
    }

    template <int dim>
    SymmetricTensor<2, dim>
    in_plane(const SymmetricTensor<2, 3> &t)
    {
      SymmetricTensor<2, dim> tau;
      for (unsigned int i = 0; i < dim; ++i)
        for (unsigned int j = i; j < dim; ++j)
          tau[i][j] = t[i][j];
      return tau;
    }
  } // namespace

  template <int dim>
  bool
  PerzynaMaterial<dim>::is_plane_strain() const
  {
    return plane_strain;
  }

  template <int dim>
  double
  PerzynaMaterial<dim>::out_of_plane_elastic_stress(
    const SymmetricTensor<2, dim> &strain) const
  {
    const double E = young_modulus, k = poisson_ratio;
    return plane_strain ? E * k / ((1 + k) * (1 - 2 * k)) * trace(strain) : 0.;
  }

  template <int dim>
  double
  PerzynaMaterial<dim>::equivalent_stress(const SymmetricTensor<2, dim> &tau,
                                          const double tau_zz) const
  {
    return plane_strain
             ? three_dimensional->equivalent_stress(embed(tau, tau_zz))
             : equivalent_stress(tau);
  }

  template <int dim>
  SymmetricTensor<2, dim>
  PerzynaMaterial<dim>::viscoplastic_rate(const SymmetricTensor<2, dim> &sigma,
                                          const double sigma_zz,
                                          double      &rate_zz,
                                          double      *multiplier) const
  {
    rate_zz = 0;
    if (!plane_strain)
      return viscoplastic_rate(sigma, multiplier);
    const SymmetricTensor<2, 3> rate
      = three_dimensional->viscoplastic_rate(embed(sigma, sigma_zz),
                                             multiplier);
    rate_zz = rate[2][2];
    return in_plane<dim>(rate);
  }

  // The consistent tangent: trial = E eps + H with eps_zz = 0, so
  // d sigma / d eps = (d sigma / d trial) E of the 3D law, restricted to the
  // in-plane components (the zz row of E, lambda I, enters through the
  // contraction).
  template <int dim>
  SymmetricTensor<2, dim>
  PerzynaMaterial<dim>::implicit_stress_update(
    const SymmetricTensor<2, dim> &trial,
    const double                   trial_zz,
    const double                   a,
    double                        &stress_zz,
    SymmetricTensor<4, dim>       *consistent_tangent,
    double                        *multiplier) const
  {
    if (!plane_strain)
      {
        stress_zz = 0;
        const SymmetricTensor<2, dim> sigma
          = implicit_stress_update(trial, a, consistent_tangent, multiplier);
        if (consistent_tangent != nullptr)
          *consistent_tangent = *consistent_tangent * stiffness;
        return sigma;
      }
    SymmetricTensor<4, 3>       tangent;
    const SymmetricTensor<2, 3> sigma
      = three_dimensional->implicit_stress_update(embed(trial, trial_zz),
                                                  a,
                                                  consistent_tangent != nullptr
                                                    ? &tangent
                                                    : nullptr,
                                                  multiplier);
    stress_zz = sigma[2][2];
    if (consistent_tangent != nullptr)
      {
        const SymmetricTensor<4, 3> C
          = tangent * three_dimensional->elasticity_tensor();
        for (unsigned int i = 0; i < dim; ++i)
          for (unsigned int j = i; j < dim; ++j)
            for (unsigned int k = 0; k < dim; ++k)
              for (unsigned int l = k; l < dim; ++l)
                (*consistent_tangent)[i][j][k][l] = C[i][j][k][l];
      }
    return in_plane<dim>(sigma);
  }

  // (E^-1 tau, tau) with the compliance of the constructor; in plane strain
  // that of the 3D law on the embedded tensor.
  template <int dim>
  double
  PerzynaMaterial<dim>::complementary_energy(const SymmetricTensor<2, dim> &tau,
                                             const double tau_zz) const
  {
    if (plane_strain)
      return three_dimensional->complementary_energy(embed(tau, tau_zz), 0.);
    Assert(tau_zz == 0, ExcInternalError()); // sigma_zz = 0 or 3D
    return (compliance * tau) * tau;
  }



  // @sect4{The 2D plane-stress von Mises set and its E-norm projection}
  //
  // In the orthonormal coordinates a = (t11+t22)/sqrt2, b = (t11-t22)/sqrt2,
  // c = sqrt2 t12 (so that tau:tau = a^2+b^2+c^2) both the plane-stress E
  // and the quadratic form of K are diagonal:
  //   E = diag(E/(1-k), E/(1+k), E/(1+k)),
  //   t11^2 + t22^2 - t11 t22 + 3 t12^2 = a^2/2 + 3/2 (b^2 + c^2) = x.Mx.
  // So only two modes interact: the spherical one (a) and the deviatoric
  // one (b, c), with the ratios t_s = M_a/E_a = (1-k)/(2E) and
  // t_d = M_b/E_b = 3(1+k)/(2E). The optimality condition
  // E (x - y) + mu M x = 0 of min |x - y|_E^2 subject to x.Mx <= sigma_Y^2
  // scales each mode: x_a = y_a/(1 + mu t_s), x_{b,c} = y_{b,c}/(1 + mu t_d),
  // and the multiplier mu > 0 is the root of
  //   |x(mu)|_M^2 = A/(1 + mu t_s)^2 + D/(1 + mu t_d)^2 = sigma_Y^2,
  // A = y_a^2/2, D = 3/2 (y_b^2 + y_c^2), whose left side decreases strictly.
  // We apply Newton's method to phi(mu) = 1/|x(mu)|_M - 1/sigma_Y, which is
  // affine if one mode is absent and close to affine otherwise, starting
  // from a guess the caller may give (the previous step's multiplier), or
  // from the lower bound mu_0 = (|y|_M/sigma_Y - 1)/max(t) of the root (the
  // root itself if only the dominant mode is present). A bracket of the root
  // is kept and bisection takes over should an iterate ever leave it; the
  // iteration stops at machine precision, typically after 3 or 4 steps.
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

    double
    yield_norm(const PlaneStressCoordinates &c)
    {
      return std::sqrt(0.5 * c.x[0] * c.x[0]
                       + 1.5 * (c.x[1] * c.x[1] + c.x[2] * c.x[2]));
    }

    // The root mu > 0 of |x(mu)|_M = sigma_Y for
    // x_a = y_a/(1 + mu t_s), x_{b,c} = y_{b,c}/(1 + mu t_d): the multiplier
    // of the E-norm projection (t = M/E) and, with other ratios t, of the
    // backward-Euler update. y must lie outside K (|y|_M = y_norm > sigma_Y).
    double
    two_mode_multiplier(const PlaneStressCoordinates &y,
                        const double                  y_norm,
                        const double                  t_s,
                        const double                  t_d,
                        const double                  sigma_yield,
                        const double                  guess)
    {
      const double A = 0.5 * y.x[0] * y.x[0];
      const double D = 1.5 * (y.x[1] * y.x[1] + y.x[2] * y.x[2]);

      // |y|_M/(1 + mu t_max) <= |x(mu)|_M <= |y|_M/(1 + mu t_min).
      const double t_max  = (D > 0 ? std::max(t_s, t_d) : t_s);
      const double t_min  = (A > 0 ? std::min(t_s, t_d) : t_d);
      const double excess = y_norm / sigma_yield - 1;
      double       lower = excess / t_max, upper = excess / t_min;
      double       mu = (guess > lower && guess < upper ? guess : lower);
      for (unsigned int iteration = 0; iteration < 100; ++iteration)
        {
          const double s_s     = 1. / (1 + mu * t_s);
          const double s_d     = 1. / (1 + mu * t_d);
          const double norm_sq = A * s_s * s_s + D * s_d * s_d;
          const double norm    = std::sqrt(norm_sq);
          const double phi     = 1. / norm - 1. / sigma_yield;
          if (phi < 0)
            lower = std::max(lower, mu);
          else
            upper = std::min(upper, mu);
          // phi' = (A t_s s_s^3 + D t_d s_d^3) / |x|^3 > 0.
          const double d_phi
            = (A * t_s * s_s * s_s * s_s + D * t_d * s_d * s_d * s_d)
              / (norm_sq * norm);
          double next = mu - phi / d_phi;
          if (!(next >= lower && next <= upper))
            next = 0.5 * (lower + upper);
          // Newton converges quadratically: once a step is below 1e-8
          // relative, the error of the next iterate is of order 1e-16.
          const bool converged = std::abs(next - mu) <= 1e-8 * std::abs(next);
          mu                   = next;
          if (converged || phi == 0)
            break;
        }

      return mu;
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
    PlaneStressCoordinates y     = to_coordinates(tau);
    const double           guess = (multiplier != nullptr ? *multiplier : 0.);
    if (multiplier != nullptr)
      *multiplier = 0;
    const double y_norm = yield_norm(y);
    if (y_norm <= sigma_yield)
      return tau;

    const double k   = poisson_ratio;
    const double t_s = 0.5 * (1 - k) / young_modulus;
    const double t_d = 1.5 * (1 + k) / young_modulus;
    const double mu
      = two_mode_multiplier(y, y_norm, t_s, t_d, sigma_yield, guess);

    if (multiplier != nullptr)
      *multiplier = mu;
    y.x[0] /= (1 + mu * t_s);
    y.x[1] /= (1 + mu * t_d);
    y.x[2] /= (1 + mu * t_d);
    return from_coordinates(y);
  }



  // @sect4{The 2D backward-Euler update and its tangent}
  //
  // With P_K sigma = D(mu) sigma mode by mode, the equation
  // sigma + a E (sigma - P_K sigma) = y gives, per mode i,
  //   sigma_i = y_i (1 + mu t_i) / (1 + mu tau_i),   tau_i = t_i (1 + a E_i),
  //   (P_K sigma)_i = y_i / (1 + mu tau_i),
  // so mu is the multiplier of the same two-mode equation as the projection,
  // with the ratios tau instead of t. Differentiating sigma_i = f_i(mu) y_i,
  // with mu(y) from |P_K sigma|_M = sigma_Y, gives in the mode coordinates
  //   T_ij = delta_ij f_i - a v_i v_j / D,  v_i = M_i y_i s_i^2,
  //   D = sum_l M_l y_l^2 tau_l s_l^3,  s_i = 1/(1 + mu tau_i):
  // symmetric, as d sigma / d trial must be. The
  // consistent tangent T E is not (E_i differ between the modes), so the
  // implicit scheme's stiffness matrix is unsymmetric.
  template <>
  SymmetricTensor<2, 2>
  PerzynaMaterial<2>::implicit_stress_update(const SymmetricTensor<2, 2> &trial,
                                             const double                 a,
                                             SymmetricTensor<4, 2> *tangent,
                                             double *multiplier) const
  {
    const PlaneStressCoordinates y = to_coordinates(trial);
    const double guess             = (multiplier != nullptr ? *multiplier : 0.);
    const double y_norm            = yield_norm(y);
    if (multiplier != nullptr)
      *multiplier = 0;
    if (y_norm <= sigma_yield)
      {
        if (tangent != nullptr)
          *tangent = identity_tensor<2>();
        return trial;
      }

    const double k         = poisson_ratio;
    const double E_mode[3] = {young_modulus / (1 - k),
                              young_modulus / (1 + k),
                              young_modulus / (1 + k)};
    const double M_mode[3] = {0.5, 1.5, 1.5};
    double       t_mode[3], tau_mode[3];
    for (unsigned int i = 0; i < 3; ++i)
      {
        t_mode[i]   = M_mode[i] / E_mode[i];
        tau_mode[i] = t_mode[i] * (1 + a * E_mode[i]);
      }
    const double mu = two_mode_multiplier(y,
                                          y_norm,
                                          tau_mode[0],
                                          tau_mode[1],
                                          sigma_yield,
                                          guess);
    if (multiplier != nullptr)
      *multiplier = mu;

    PlaneStressCoordinates sigma;
    double                 s[3];
    for (unsigned int i = 0; i < 3; ++i)
      {
        s[i]       = 1. / (1 + mu * tau_mode[i]);
        sigma.x[i] = y.x[i] * (1 + mu * t_mode[i]) * s[i];
      }

    if (tangent != nullptr)
      {
        double denominator = 0;
        for (unsigned int l = 0; l < 3; ++l)
          denominator
            += M_mode[l] * y.x[l] * y.x[l] * tau_mode[l] * s[l] * s[l] * s[l];
        // The basis tensors of the mode coordinates.
        std::array<SymmetricTensor<2, 2>, 3> basis;
        for (unsigned int i = 0; i < 3; ++i)
          {
            PlaneStressCoordinates unit{{0., 0., 0.}};
            unit.x[i] = 1;
            basis[i]  = from_coordinates(unit);
          }
        *tangent = SymmetricTensor<4, 2>();
        for (unsigned int i = 0; i < 3; ++i)
          for (unsigned int j = 0; j < 3; ++j)
            {
              const double T_ij = (i == j ? (1 + mu * t_mode[i]) * s[i] : 0.)
                                  - a * M_mode[i] * y.x[i] * s[i] * s[i]
                                      * M_mode[j] * y.x[j] * s[j] * s[j]
                                      / denominator;
              *tangent += T_ij * outer_product(basis[i], basis[j]);
            }
      }
    return from_coordinates(sigma);
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



  // The 3D update: the trace is untouched, the deviator scaled by
  // f = (1 + mu t)/(1 + mu tau), t = 3/(4G), tau = t (1 + 2 a G), with
  // 1 + mu tau = q/sigma_Y, q = sqrt(3/2)|dev trial|; differentiating gives
  // T = P_vol + f P_dev - (9 a / (4 tau q^3)) sigma_Y dev y (x) dev y.
  template <>
  SymmetricTensor<2, 3>
  PerzynaMaterial<3>::implicit_stress_update(const SymmetricTensor<2, 3> &trial,
                                             const double                 a,
                                             SymmetricTensor<4, 3> *tangent,
                                             double *multiplier) const
  {
    const double q = equivalent_stress(trial);
    if (multiplier != nullptr)
      *multiplier = 0;
    if (q <= sigma_yield)
      {
        if (tangent != nullptr)
          *tangent = identity_tensor<3>();
        return trial;
      }
    const double two_G = young_modulus / (1 + poisson_ratio);
    const double t     = 1.5 / two_G;
    const double tau   = t * (1 + a * two_G);
    const double mu    = (q / sigma_yield - 1) / tau;
    const double f     = (1 + mu * t) / (1 + mu * tau);
    if (multiplier != nullptr)
      *multiplier = mu;
    const SymmetricTensor<2, 3> s = deviator(trial);
    if (tangent != nullptr)
      *tangent = (identity_tensor<3>() - deviator_tensor<3>())
                 + f * deviator_tensor<3>()
                 - (9. * a * sigma_yield / (4. * tau * q * q * q))
                     * outer_product(s, s);
    return (trial - s) + f * s;
  }



  // @sect4{PerzynaMaterial as a MaterialLaw}
  template <int dim>
  bool
  PerzynaMaterial<dim>::has_rate_form() const
  {
    return true;
  }



  // Forward Euler on the relaxation is stable for k < 4 lambda /
  // lambda_max(E) (doc/model.md, section 3); an elastic material sets no
  // limit.
  template <int dim>
  double
  PerzynaMaterial<dim>::explicit_stability_limit() const
  {
    return plastic ? 4 * lambda_viscosity / largest_elastic_eigenvalue()
                   : std::numeric_limits<double>::infinity();
  }



  template <int dim>
  SymmetricTensor<2, dim>
  PerzynaMaterial<dim>::rate(const SymmetricTensor<2, dim> &sigma,
                             const double                   sigma_zz,
                             double                        &rate_zz,
                             double &internal_variable) const
  {
    return viscoplastic_rate(sigma, sigma_zz, rate_zz, &internal_variable);
  }



  template <int dim>
  SymmetricTensor<2, dim>
  PerzynaMaterial<dim>::implicit_update(const SymmetricTensor<2, dim> &trial,
                                        const double                   trial_zz,
                                        const double             time_step,
                                        double                  &stress_zz,
                                        SymmetricTensor<4, dim> *tangent,
                                        double &internal_variable) const
  {
    return implicit_stress_update(trial,
                                  trial_zz,
                                  time_step / (2 * lambda_viscosity),
                                  stress_zz,
                                  tangent,
                                  &internal_variable);
  }



  // The multiplier only starts the next projection: any value is right.
  template <int dim>
  bool
  PerzynaMaterial<dim>::internal_variable_is_guess() const
  {
    return true;
  }



  template class PerzynaMaterial<2>;
  template class PerzynaMaterial<3>;
} // namespace ViscoContact
