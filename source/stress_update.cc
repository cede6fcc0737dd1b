// The stress update of ViscoplasticContact<dim>: sigma_n at every stress
// point, and the history of the next step with its load.

#include <deal.II/base/exceptions.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/timer.h>

#include "viscoplastic_contact.h"

#include <cmath>
#include <limits>

namespace ViscoContact
{
  // @sect4{ViscoplasticContact::update_stresses}
  //
  // sigma_n = E eps(u_n) + H_n at every stress point of the locally owned
  // cells, and, with plasticity, the explicit history update
  // H_{n+1} = H_n + k_{n+1} G(sigma_n) of doc/model.md, section 2. The
  // same loop assembles -(H_{n+1}, eps(v)), the history load of the next
  // step, so the stress points are visited once per step. The projection
  // onto the stress space is the identity here: E eps(u_n) is piecewise
  // constant on P1 simplices, and on hypercubes the stresses are stored at
  // the quadrature points themselves.
  //
  // With the implicit update, sigma_n solves the backward-Euler equation at
  // each stress point (as in the last Newton iteration), and the history of
  // the next step is what of sigma_n is not elastic.
  template <int dim>
  void
  ViscoplasticContact<dim>::update_stresses(const double current_time_step,
                                            const double next_time_step)
  {
    TimerOutput::Scope t(computing_timer, "Stress update");
    const bool         implicit =
      parameters.plasticity &&
      parameters.stress_update == Parameters::StressUpdate::implicit_euler;
    const bool update_history =
      parameters.plasticity && !implicit && next_time_step > 0;
    const double a = current_time_step / (2 * material.viscosity());
    const SymmetricTensor<4, dim> &E   = material.elasticity_tensor();
    const unsigned int             n_q = stress_quadrature.size();
    Vector<double>                 cell_vector(n_cell_vertices * dim);

    if (update_history)
      history_load = 0;
    double local_max_von_mises = 0;
    for (unsigned int k = 0; k < owned_cells.size(); ++k)
      {
        cell_vector = 0;
        for (unsigned int q = 0; q < n_q; ++q)
          {
            QuadraturePointHistory<dim> &state =
              quadrature_point_history[std::size_t(k) * n_q + q];
            const SymmetricTensor<2, dim> elastic_stress =
              E * symmetrize(displacement_gradient_at(solution, k, q));
            if (implicit)
              {
                state.stress =
                  material.implicit_stress_update(elastic_stress + state.history,
                                                  a,
                                                  nullptr,
                                                  &state.plastic_multiplier);
                state.history = state.stress - elastic_stress;
              }
            else
              state.stress = elastic_stress + state.history;
            const double von_mises = material.equivalent_stress(state.stress);
            local_max_von_mises =
              std::isfinite(von_mises) ?
                std::max(local_max_von_mises, von_mises) :
                std::numeric_limits<double>::infinity();
            if (update_history)
              {
                state.history +=
                  next_time_step *
                  material.viscoplastic_rate(state.stress,
                                             &state.plastic_multiplier);
                add_stress_point_load(state.history, k, q, cell_vector);
              }
          }
        if (update_history)
          {
            cell_vector *= -1.;
            distribute_cell_vector(k, cell_vector, history_load);
          }
      }
    if (update_history)
      history_load.compress(VectorOperation::add);
    max_von_mises = Utilities::MPI::max(local_max_von_mises, mpi_communicator);

    // An unstable explicit update ends in stresses that overflow: stop
    // rather than go on with (and write) infinite or NaN fields.
    AssertThrow(std::isfinite(max_von_mises),
                ExcMessage(
                  "The stresses are no longer finite (NaN or Inf). With the "
                  "explicit history update this means the time step is too "
                  "large: it is stable for k < 4 lambda / lambda_max(E) = " +
                  std::to_string(4 * material.viscosity() /
                                 material.largest_elastic_eigenvalue()) +
                  " s (doc/model.md, section 3); <Time step> in subsection "
                  "<Time> is " +
                  std::to_string(parameters.time_step) + " s."));
  }



  template class ViscoplasticContact<2>;
  template class ViscoplasticContact<3>;
} // namespace ViscoContact
