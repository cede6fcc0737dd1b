// The stress update of ViscoplasticContact<dim>: sigma_n at every stress
// point, and the history of the next step with its load; and the
// stress-point helpers the update, the assembly and the output share (kept
// in this file, where the hot loop of the explicit update can inline them).

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
    const bool         implicit
      = parameters.plasticity
        && parameters.stress_update == Parameters::StressUpdate::implicit_euler;
    const bool update_history
      = parameters.plasticity && !implicit && next_time_step > 0;
    const double a = current_time_step / (2 * material.viscosity());
    const SymmetricTensor<4, dim> &E   = material.elasticity_tensor();
    const unsigned int             n_q = stress_quadrature.size();
    Vector<double>                 cell_vector(n_cell_vertices * dim);

    if (update_history)
      history_load = 0;
    double local_max_von_mises = 0;
    for (unsigned int k = 0; k < owned_cells.size(); ++k)
      {
        std::fill(cell_vector.begin(), cell_vector.end(), 0.);
        for (unsigned int q = 0; q < n_q; ++q)
          {
            QuadraturePointHistory<dim> &state
              = quadrature_point_history[std::size_t(k) * n_q + q];
            const SymmetricTensor<2, dim> elastic_stress
              = E * symmetrize(displacement_gradient_at(solution, k, q));
            if (implicit)
              {
                state.stress
                  = material.implicit_stress_update(elastic_stress
                                                      + state.history,
                                                    a,
                                                    nullptr,
                                                    &state.plastic_multiplier);
                state.history = state.stress - elastic_stress;
              }
            else
              state.stress = elastic_stress + state.history;
            const double von_mises = material.equivalent_stress(state.stress);
            local_max_von_mises    = std::isfinite(von_mises)
                                       ? std::max(local_max_von_mises, von_mises)
                                       : std::numeric_limits<double>::infinity();
            if (update_history)
              {
                state.history
                  += next_time_step
                     * material.viscoplastic_rate(state.stress,
                                                  &state.plastic_multiplier);
                add_stress_point_load(-state.history, k, q, cell_vector);
              }
          }
        if (update_history)
          {
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
                  "large: it is stable for k < 4 lambda / lambda_max(E) = "
                  + std::to_string(4 * material.viscosity()
                                   / material.largest_elastic_eigenvalue())
                  + " s (doc/model.md, section 3); <Time step> in subsection "
                    "<Time> is "
                  + std::to_string(parameters.time_step) + " s."));
  }



  // @sect4{ViscoplasticContact::displacement_gradient_at}
  //
  // grad u = sum_a u_a (x) grad N_a at stress point q of the k-th owned
  // cell, from the geometry stored at set-up and the ghosted entries of u.
  template <int dim>
  Tensor<2, dim>
  ViscoplasticContact<dim>::displacement_gradient_at(
    const VectorType  &displacement,
    const unsigned int k,
    const unsigned int q) const
  {
    const unsigned int    n_a    = n_cell_vertices;
    const unsigned int   *dofs   = &cell_local_dofs[std::size_t(k) * n_a * dim];
    const double         *values = displacement.get_values(); // owned, ghosts
    const Tensor<1, dim> *gradients
      = &stress_point_gradients[(std::size_t(k) * stress_quadrature.size() + q)
                                * n_a];
    Assert(displacement.has_ghost_elements()
             || Utilities::MPI::n_mpi_processes(mpi_communicator) == 1,
           ExcMessage("The displacement needs its ghost values here."));
    Tensor<2, dim> gradient;
    for (unsigned int a = 0; a < n_a; ++a)
      for (unsigned int c = 0; c < dim; ++c)
        gradient[c] += values[dofs[a * dim + c]] * gradients[a];
    return gradient;
  }



  // @sect4{ViscoplasticContact::add_stress_point_load}
  //
  // cell_vector += (tau, eps(v)) JxW at stress point q of the k-th owned
  // cell: with eps(N_a e_c) = sym(e_c (x) grad N_a) and tau symmetric, the
  // entry of the cell's dof (a, c) is JxW (tau grad N_a)_c.
  template <int dim>
  void
  ViscoplasticContact<dim>::add_stress_point_load(
    const SymmetricTensor<2, dim> &tau,
    const unsigned int             k,
    const unsigned int             q,
    Vector<double>                &cell_vector) const
  {
    const std::size_t     point = std::size_t(k) * stress_quadrature.size() + q;
    const Tensor<1, dim> *gradients
      = &stress_point_gradients[point * n_cell_vertices];
    const double JxW = stress_point_JxW[point];
    for (unsigned int a = 0; a < n_cell_vertices; ++a)
      {
        const Tensor<1, dim> force = tau * gradients[a];
        for (unsigned int c = 0; c < dim; ++c)
          cell_vector[a * dim + c] += JxW * force[c];
      }
  }



  // @sect4{ViscoplasticContact::distribute_cell_vector}
  //
  // target += the cell vector of the k-th owned cell (dofs ordered (vertex
  // a, component c)). Cells without constrained dofs add straight into the
  // local storage; the others go through the constraints (hanging nodes,
  // the clamped Gamma_1). The caller compresses.
  template <int dim>
  void
  ViscoplasticContact<dim>::distribute_cell_vector(
    const unsigned int    k,
    const Vector<double> &cell_vector,
    VectorType           &target) const
  {
    const unsigned int  n_local = n_cell_vertices * dim;
    const unsigned int *dofs    = &cell_local_dofs[std::size_t(k) * n_local];
    if (!cell_is_constrained[k])
      {
        double *values = target.get_values(); // owned entries, then ghosts
        for (unsigned int i = 0; i < n_local; ++i)
          values[dofs[i]] += cell_vector[i];
        return;
      }
    std::vector<types::global_dof_index> global_dofs(n_local);
    const auto &partitioner = *target.get_partitioner();
    for (unsigned int i = 0; i < n_local; ++i)
      global_dofs[i] = partitioner.local_to_global(dofs[i]);
    constraints.distribute_local_to_global(cell_vector, global_dofs, target);
  }



  template class ViscoplasticContact<2>;
  template class ViscoplasticContact<3>;
} // namespace ViscoContact
