// Assembly of ViscoplasticContact<dim>: the right-hand side of a step (the
// external load and the history load) and the implicit update's tangent
// system.

#include <deal.II/base/exceptions.h>
#include <deal.II/base/timer.h>

#include <deal.II/fe/fe_values.h>

#include "viscoplastic_contact.h"

#include <algorithm>

namespace ViscoContact
{
  // @sect4{ViscoplasticContact::assemble_right_hand_side}
  //
  // b_n = (f_n, v) - (H_n, eps(v)). The history part was assembled by the
  // previous stress update; the external part is assembled once if the
  // loads do not depend on time. The implicit update has the history
  // inside its internal force, so its right-hand side is the external load.
  template <int dim>
  void
  ViscoplasticContact<dim>::assemble_right_hand_side(const double time)
  {
    TimerOutput::Scope t(computing_timer, "Assemble right-hand side");
    if (loads_depend_on_time || n_external_load_assemblies == 0)
      assemble_external_load(time);
    system_rhs = external_load;
    if (parameters.plasticity
        && parameters.stress_update == Parameters::StressUpdate::explicit_euler)
      system_rhs += history_load;
  }



  // @sect4{ViscoplasticContact::assemble_external_load}
  //
  // (f_0, v) + (f_2, v)_Gamma2 on the locally owned cells; a zero body
  // force is not integrated at all.
  template <int dim>
  void
  ViscoplasticContact<dim>::assemble_external_load(const double time)
  {
    external_load = 0;
    body_force.set_time(time);
    surface_traction.set_time(time);
    const unsigned int                   dofs_per_cell = fe->n_dofs_per_cell();
    Vector<double>                       cell_rhs(dofs_per_cell);
    std::vector<types::global_dof_index> local_dof_indices(dofs_per_cell);
    Vector<double>                       load_value(dim);
    FEValues<dim>                        fe_values(mapping,
                            *fe,
                            load_quadrature,
                            update_values | update_quadrature_points
                              | update_JxW_values);
    FEFaceValues<dim>                    fe_face_values(mapping,
                                     *fe,
                                     face_quadrature,
                                     update_values | update_quadrature_points
                                       | update_JxW_values);
    const auto is_loaded = [&](const types::boundary_id id) {
      return std::find(parameters.loaded_ids.begin(),
                       parameters.loaded_ids.end(),
                       id)
             != parameters.loaded_ids.end();
    };

    for (const auto &cell : owned_cells)
      {
        cell_rhs       = 0;
        bool has_loads = false;
        if (!body_force_is_zero)
          {
            fe_values.reinit(cell);
            for (const unsigned int q : fe_values.quadrature_point_indices())
              {
                body_force.vector_value(fe_values.quadrature_point(q),
                                        load_value);
                for (unsigned int i = 0; i < dofs_per_cell; ++i)
                  cell_rhs(i)
                    += load_value(fe->system_to_component_index(i).first)
                       * fe_values.shape_value(i, q) * fe_values.JxW(q);
              }
            has_loads = true;
          }
        for (const unsigned int f : cell->face_indices())
          if (cell->face(f)->at_boundary()
              && is_loaded(cell->face(f)->boundary_id()))
            {
              fe_face_values.reinit(cell, f);
              for (const unsigned int q :
                   fe_face_values.quadrature_point_indices())
                {
                  surface_traction.vector_value(fe_face_values.quadrature_point(
                                                  q),
                                                load_value);
                  for (unsigned int i = 0; i < dofs_per_cell; ++i)
                    cell_rhs(i)
                      += load_value(fe->system_to_component_index(i).first)
                         * fe_face_values.shape_value(i, q)
                         * fe_face_values.JxW(q);
                }
              has_loads = true;
            }
        if (has_loads)
          {
            cell->get_dof_indices(local_dof_indices);
            constraints.distribute_local_to_global(cell_rhs,
                                                   local_dof_indices,
                                                   external_load);
          }
      }
    external_load.compress(VectorOperation::add);
    ++n_external_load_assemblies;
  }



  // @sect4{ViscoplasticContact::assemble_history_load}
  //
  // -(H, eps(v)) from the history stored at the stress points. The time
  // loop gets this vector from update_stresses(), which assembles it while
  // it computes H; this stand-alone version serves a cut step (whose
  // history increment was rescaled), a resumed run, and the cost
  // measurement of the run summary.
  template <int dim>
  void
  ViscoplasticContact<dim>::assemble_history_load()
  {
    history_load           = 0;
    const unsigned int n_q = stress_quadrature.size();
    Vector<double>     cell_vector(n_cell_vertices * dim);
    for (unsigned int k = 0; k < owned_cells.size(); ++k)
      {
        std::fill(cell_vector.begin(), cell_vector.end(), 0.);
        for (unsigned int q = 0; q < n_q; ++q)
          add_stress_point_load(
            -quadrature_point_history[std::size_t(k) * n_q + q].history,
            k,
            q,
            cell_vector);
        distribute_cell_vector(k, cell_vector, history_load);
      }
    history_load.compress(VectorOperation::add);
  }



  // @sect4{ViscoplasticContact::assemble_tangent_system}
  //
  // For the implicit scheme: at the displacement u, the stresses
  // sigma(eps(u)) of the backward-Euler update at every stress point, the
  // internal force (sigma, eps(v)) and the tangent stiffness
  // (C_alg eps(w), eps(v)) with the consistent tangent
  // C_alg = (d sigma / d trial) E (doc/model.md, section 3). The state at
  // the stress points is not changed (only the multiplier guesses).
  template <int dim>
  void
  ViscoplasticContact<dim>::assemble_tangent_system(
    const VectorType &displacement,
    const double      a)
  {
    TimerOutput::Scope t(computing_timer, "Assemble tangent system");
    tangent_matrix                               = 0;
    internal_force                               = 0;
    const SymmetricTensor<4, dim>       &E       = material.elasticity_tensor();
    const unsigned int                   n_q     = stress_quadrature.size();
    const unsigned int                   n_a     = n_cell_vertices;
    const unsigned int                   n_local = n_a * dim;
    FullMatrix<double>                   cell_matrix(n_local, n_local);
    Vector<double>                       cell_force(n_local);
    std::vector<types::global_dof_index> global_dofs(n_local);
    const auto &partitioner = *displacement.get_partitioner();

    for (unsigned int k = 0; k < owned_cells.size(); ++k)
      {
        cell_matrix = 0;
        cell_force  = 0;
        for (unsigned int q = 0; q < n_q; ++q)
          {
            const std::size_t     point = std::size_t(k) * n_q + q;
            const Tensor<1, dim> *gradients
              = &stress_point_gradients[point * n_a];
            const double         JxW = stress_point_JxW[point];
            const Tensor<2, dim> displacement_gradient
              = displacement_gradient_at(displacement, k, q);

            QuadraturePointHistory<dim> &state
              = quadrature_point_history[point];
            SymmetricTensor<4, dim> trial_tangent = identity_tensor<dim>();
            const SymmetricTensor<2, dim> stress
              = (parameters.plasticity ? material.implicit_stress_update(
                   E * symmetrize(displacement_gradient) + state.history,
                   a,
                   &trial_tangent,
                   &state.plastic_multiplier)
                                       : E * symmetrize(displacement_gradient));
            const SymmetricTensor<4, dim> C = trial_tangent * E;

            for (unsigned int i = 0; i < n_local; ++i)
              {
                const unsigned int ai = i / dim, ci = i % dim;
                cell_force(i) += JxW * (stress * gradients[ai])[ci];
                for (unsigned int j = 0; j < n_local; ++j)
                  {
                    const unsigned int bj = j / dim, cj = j % dim;
                    double             value = 0;
                    for (unsigned int m = 0; m < dim; ++m)
                      for (unsigned int l = 0; l < dim; ++l)
                        value += C[ci][m][cj][l] * gradients[ai][m]
                                 * gradients[bj][l];
                    cell_matrix(i, j) += JxW * value;
                  }
              }
          }
        const unsigned int *dofs = &cell_local_dofs[std::size_t(k) * n_local];
        for (unsigned int i = 0; i < n_local; ++i)
          global_dofs[i] = partitioner.local_to_global(dofs[i]);
        constraints.distribute_local_to_global(cell_matrix,
                                               cell_force,
                                               global_dofs,
                                               tangent_matrix,
                                               internal_force);
      }
    tangent_matrix.compress(VectorOperation::add);
    internal_force.compress(VectorOperation::add);
    ++n_operator_assemblies;
  }



  template class ViscoplasticContact<2>;
  template class ViscoplasticContact<3>;
} // namespace ViscoContact
