// Assembly of ViscoplasticContact<dim>: the right-hand side of a step (the
// external load and the history load) and the implicit update's tangent
// system.

#include <deal.II/base/exceptions.h>
#include <deal.II/base/timer.h>

#include <deal.II/fe/fe_values.h>

#include <deal.II/hp/fe_values.h>

#include "elastic_operator.h"
#include "robustness/file_output.h"
#include "viscoplastic_contact.h"

#include <algorithm>
#include <map>
#include <cmath>
#include <sstream>

namespace ViscoContact
{



  // @sect4{assemble_elastic_operator}
  //
  // Each rank assembles its own cells. E has the major symmetry, so only the
  // lower triangle of the cell matrix is computed, and then mirrored.
  template <int dim>
  void
  assemble_elastic_operator(const hp::MappingCollection<dim> &mapping,
                            const DoFHandler<dim>            &dof_handler,
                            const hp::QCollection<dim>       &quadrature,
                            const ElasticityOfCell<dim>      &elasticity,
                            const AffineConstraints<double>  &constraints,
                            TrilinosWrappers::SparseMatrix   &matrix)
  {
    hp::FEValues<dim>                    hp_fe_values(mapping,
                                   dof_handler.get_fe_collection(),
                                   quadrature,
                                   update_gradients | update_JxW_values);
    const FEValuesExtractors::Vector     displacement(0);
    FullMatrix<double>                   cell_matrix;
    std::vector<types::global_dof_index> local_dof_indices;
    std::vector<SymmetricTensor<2, dim>> strains;

    for (const auto &cell : dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          const SymmetricTensor<4, dim> &E = elasticity(cell);
          hp_fe_values.reinit(cell);
          const FEValues<dim> &fe_values = hp_fe_values.get_present_fe_values();
          const unsigned int   dofs_per_cell = cell->get_fe().n_dofs_per_cell();
          cell_matrix.reinit(dofs_per_cell, dofs_per_cell);
          local_dof_indices.resize(dofs_per_cell);
          strains.resize(dofs_per_cell);
          for (const unsigned int q : fe_values.quadrature_point_indices())
            {
              for (unsigned int i = 0; i < dofs_per_cell; ++i)
                strains[i] = fe_values[displacement].symmetric_gradient(i, q);
              for (unsigned int i = 0; i < dofs_per_cell; ++i)
                {
                  const SymmetricTensor<2, dim> stress_i
                    = E * strains[i] * fe_values.JxW(q);
                  for (unsigned int j = 0; j <= i; ++j)
                    cell_matrix(i, j) += stress_i * strains[j];
                }
            }
          for (unsigned int i = 0; i < dofs_per_cell; ++i)
            for (unsigned int j = i + 1; j < dofs_per_cell; ++j)
              cell_matrix(i, j) = cell_matrix(j, i);
          // The constraints condense the cell matrix as it is added. Rows of
          // ghost dofs are collected locally and sent to their owners by
          // compress(add), which also finishes the matrix for Trilinos.
          cell->get_dof_indices(local_dof_indices);
          constraints.distribute_local_to_global(cell_matrix,
                                                 local_dof_indices,
                                                 matrix);
        }
    matrix.compress(VectorOperation::add);
  }



  // @sect4{elastic_node_blocks}
  //
  // The cell matrices of the cells around the vertices, restricted to the
  // pairs of dofs of one vertex.
  template <int dim>
  std::vector<Tensor<2, dim>>
  elastic_node_blocks(
    const hp::MappingCollection<dim>                            &mapping,
    const DoFHandler<dim>                                       &dof_handler,
    const hp::QCollection<dim>                                  &quadrature,
    const ElasticityOfCell<dim>                                 &elasticity,
    const std::vector<std::array<types::global_dof_index, dim>> &node_dofs)
  {
    std::vector<Tensor<2, dim>> blocks(node_dofs.size());
    // Which node and component a dof is.
    std::map<types::global_dof_index, std::pair<unsigned int, unsigned int>>
      node_of_dof;
    for (unsigned int i = 0; i < node_dofs.size(); ++i)
      for (unsigned int c = 0; c < dim; ++c)
        node_of_dof[node_dofs[i][c]] = {i, c};
    hp::FEValues<dim>                    hp_fe_values(mapping,
                                   dof_handler.get_fe_collection(),
                                   quadrature,
                                   update_gradients | update_JxW_values);
    const FEValuesExtractors::Vector     displacement(0);
    std::vector<types::global_dof_index> dof_indices;
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (!cell->is_artificial())
        {
          const unsigned int dofs_per_cell = cell->get_fe().n_dofs_per_cell();
          dof_indices.resize(dofs_per_cell);
          cell->get_dof_indices(dof_indices);
          std::vector<std::pair<unsigned int, decltype(node_of_dof.begin())>>
            local;
          for (unsigned int k = 0; k < dofs_per_cell; ++k)
            if (const auto entry = node_of_dof.find(dof_indices[k]);
                entry != node_of_dof.end())
              local.emplace_back(k, entry);
          if (local.empty())
            continue;
          const SymmetricTensor<4, dim> &E = elasticity(cell);
          hp_fe_values.reinit(cell);
          const FEValues<dim> &fe_values = hp_fe_values.get_present_fe_values();
          for (const unsigned int q : fe_values.quadrature_point_indices())
            for (const auto &[k, row] : local)
              {
                const SymmetricTensor<2, dim> stress
                  = E * fe_values[displacement].symmetric_gradient(k, q)
                    * fe_values.JxW(q);
                for (const auto &[l, column] : local)
                  if (column->second.first == row->second.first)
                    blocks[row->second.first][row->second.second]
                          [column->second.second]
                      += stress
                         * fe_values[displacement].symmetric_gradient(l, q);
              }
        }
    return blocks;
  }



  // @sect4{ViscoplasticContact::assemble_right_hand_side}
  //
  // b_n = (f_n, v) - (H_n, eps(v)) - (E eps(g_n), eps(v)). The history part
  // was assembled by the previous stress update; the external part is
  // assembled once if the loads do not depend on time; the lifting of the
  // prescribed displacements g_n (boundary_conditions.cc) per step. The
  // implicit update has the history inside its internal force, so its
  // right-hand side is the external load.
  //
  // So in the common case of constant loads a step costs no assembly at all
  // here: one copy and one vector addition, on the owned entries of each rank,
  // with no communication.
  template <int dim>
  void
  ViscoplasticContact<dim>::assemble_right_hand_side(const double time)
  {
    TimerOutput::Scope t(report.timer(), "Assemble right-hand side");
    // The first call always assembles (the counter is still 0); later calls
    // only if f_0 or f_2 mention t.
    if (loads.depend_on_time() || report.n_external_load_assemblies() == 0)
      assemble_external_load(time);
    set_dirichlet_values(time);
    if (contact_zones.gap_depends_on_time())
      set_gaps(time);
    system_rhs = external_load;
    // The lifting of the prescribed displacements (the implicit update has
    // them in its iterate instead).
    if (prescribed.has_values() && !parameters.implicit_update())
      system_rhs += prescribed.lifting_load();
    // Without plasticity H_n = sigma_0 - E eps(u_0) = 0 for all n, and
    // history_load stays zero; with the implicit update the history enters
    // through the internal force of implicit_newton().
    if (parameters.explicit_history_update())
      system_rhs += history_load;
  }



  // @sect4{ViscoplasticContact::assemble_external_load}
  //
  // (f_0, v) + (f_2, v)_Gamma2 on the locally owned cells; a zero body
  // force is not integrated at all.
  //
  // This loop uses FEValues: the loads are evaluated at the points of their own
  // quadrature (and of the face quadrature on the loaded boundary), not at the
  // stress points, and with time-independent loads it runs only once per run.
  template <int dim>
  void
  ViscoplasticContact<dim>::assemble_external_load(const double time)
  {
    // external_load = 0 also clears the ghost entries, into which the cells add
    // the contributions to dofs other ranks own.
    external_load = 0;
    loads.set_time(time);
    Vector<double>                       cell_rhs;
    std::vector<types::global_dof_index> local_dof_indices;
    LoadValues<dim>                      values(discretisation);
    // The first value that is not finite, if any (check_scene_values() has
    // checked the loads before the run, possibly only at some of the points).
    std::string problem;
    for (const auto &cell : stress_points.cells())
      // Cells without any load contribute nothing and are skipped. The
      // constraints drop the entries of Dirichlet dofs and distribute those
      // of hanging nodes.
      if (loads.cell_load(cell, values.cell, values.face, cell_rhs, problem))
        {
          local_dof_indices.resize(cell->get_fe().n_dofs_per_cell());
          cell->get_dof_indices(local_dof_indices);
          constraints.distribute_local_to_global(cell_rhs,
                                                 local_dof_indices,
                                                 external_load);
        }
    // Contributions to ghost dofs are sent to and added by their owners; the
    // vector then holds owned entries only.
    external_load.compress(VectorOperation::add);
    FileOutput::agree_on_problem(problem, mpi_communicator);
    report.count_external_load_assembly();
  }



  // @sect4{ViscoplasticContact::assemble_history_load}
  //
  // -(H, eps(v)) from the history stored at the stress points. The time
  // loop gets this vector from update_stresses(), which assembles it while
  // it computes H; this stand-alone version serves a cut step (whose
  // history increment was rescaled) and a resumed run.
  //
  // It works on the stored stress-point geometry, like update_stresses(): per
  // owned cell k the contributions of its stress points are summed into a cell
  // vector ordered (vertex a, component c), which is then added to the global
  // vector.
  template <int dim>
  void
  ViscoplasticContact<dim>::assemble_history_load()
  {
    // Zero also in the ghost entries, which collect the contributions to dofs
    // of other ranks until compress().
    history_load            = 0;
    const unsigned int  n_q = discretisation.n_stress_points();
    std::vector<double> cell_vector(stress_points.n_vertices() * dim);
    // The history of stress point q of the k-th owned cell is record
    // k * n_q + q; the cells of elastic materials have none.
    for (unsigned int k = 0; k < stress_points.cells().size(); ++k)
      if (materials.of_cell(k).is_plastic())
        {
          std::fill(cell_vector.begin(), cell_vector.end(), 0.);
          for (unsigned int q = 0; q < n_q; ++q)
            stress_points.add_load(
              -quadrature_point_history[std::size_t(k) * n_q + q].history,
              k,
              q,
              make_array_view(cell_vector));
          stress_points.distribute(k,
                                   make_array_view(cell_vector),
                                   history_load);
        }
    // Send the ghost contributions to their owners.
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
  //
  // This is one Newton linearisation of the step problem: with F_int(u) the
  // internal force and K_T = dF_int/du, the next iterate solves
  // K_T u = f - F_int(u_k) + K_T u_k - N^T z. In 2D plane stress K_T is
  // unsymmetric (the projection is orthogonal in the energy inner product, not
  // the Euclidean one), so the full matrix is assembled, not a triangle. The
  // step length k of a = k/(2 lambda) may be smaller than the step's own while
  // the continuation of solve_implicit_step() runs.
  template <int dim>
  void
  ViscoplasticContact<dim>::assemble_tangent_system(
    const VectorType &displacement,
    const double      time_step)
  {
    TimerOutput::Scope t(report.timer(), "Assemble tangent system");
    // Reset values only; the sparsity pattern of K is kept.
    tangent_matrix                           = 0;
    internal_force                           = 0;
    const unsigned int                   n_q = discretisation.n_stress_points();
    const unsigned int                   n_a = stress_points.n_vertices();
    const unsigned int                   n_local = n_a * dim;
    FullMatrix<double>                   cell_matrix(n_local, n_local);
    Vector<double>                       cell_force(n_local);
    std::vector<types::global_dof_index> global_dofs(n_local);
    // The partitioner turns the stored local dof indices back into global ones,
    // below. The displacement must hold its ghost values (the caller updates
    // them), since stress_points.displacement_gradient() reads every dof of the
    // owned cells.
    const auto &partitioner = *displacement.get_partitioner();

    for (unsigned int k = 0; k < stress_points.cells().size(); ++k)
      {
        const MaterialLaw<dim>        &material = materials.of_cell(k);
        const SymmetricTensor<4, dim> &E        = material.elasticity_tensor();
        cell_matrix                             = 0;
        cell_force                              = 0;
        for (unsigned int q = 0; q < n_q; ++q)
          {
            const std::size_t    point = std::size_t(k) * n_q + q;
            const Tensor<2, dim> displacement_gradient
              = stress_points.displacement_gradient(displacement, k, q);

            // The trial stress is E eps(u) plus the history
            // sigma_{n-1} - E eps(u_{n-1}) stored at the point, and the
            // backward-Euler update returns sigma and its derivative with
            // respect to the strain. The internal variable is written back
            // only where it is a starting guess (Perzyna's multiplier);
            // sigma_n and the law's state are stored by update_stresses()
            // once the step has converged. In an elastic material the stress is
            // elastic and the tangent is E. In 2D plane strain the trial stress
            // has its zz component (lambda tr eps + H_zz) too, and the update
            // gives the in-plane consistent tangent C = d sigma / d eps.
            QuadraturePointHistory<dim> &state
              = quadrature_point_history[point];
            const SymmetricTensor<2, dim> strain
              = symmetrize(displacement_gradient);
            double history_zz = 0, stress_zz = 0;
            if constexpr (dim == 2)
              history_zz = state.history_zz;
            SymmetricTensor<4, dim> C        = E;
            double                  internal = state.internal_variable;
            double &internal_variable = material.internal_variable_is_guess()
                                          ? state.internal_variable
                                          : internal;
            const SymmetricTensor<2, dim> stress
              = (material.is_plastic() ? material.implicit_update(
                   E * strain + state.history,
                   material.out_of_plane_elastic_stress(strain) + history_zz,
                   time_step,
                   stress_zz,
                   &C,
                   internal_variable)
                                       : E * strain);

            // The internal force (sigma, eps(v)) and the tangent
            // (C eps(w), eps(v)) of the point.
            stress_points.add_load(stress, k, q, make_array_view(cell_force));
            stress_points.add_tangent(C, k, q, cell_matrix);
          }
        // The local indices back to global dof numbers, since the matrix (a
        // Trilinos matrix) is addressed globally, and every cell goes through
        // the constraints here.
        const unsigned int *dofs = stress_points.local_dofs(k);
        for (unsigned int i = 0; i < n_local; ++i)
          global_dofs[i] = partitioner.local_to_global(dofs[i]);
        constraints.distribute_local_to_global(cell_matrix,
                                               cell_force,
                                               global_dofs,
                                               tangent_matrix,
                                               internal_force);
      }
    // The rows of ghost dofs and the ghost entries of the internal force go to
    // their owners.
    tangent_matrix.compress(VectorOperation::add);
    internal_force.compress(VectorOperation::add);
    report.count_operator_assembly();
  }



  template void
  assemble_elastic_operator(const hp::MappingCollection<2> &,
                            const DoFHandler<2> &,
                            const hp::QCollection<2> &,
                            const ElasticityOfCell<2> &,
                            const AffineConstraints<double> &,
                            TrilinosWrappers::SparseMatrix &);
  template void
  assemble_elastic_operator(const hp::MappingCollection<3> &,
                            const DoFHandler<3> &,
                            const hp::QCollection<3> &,
                            const ElasticityOfCell<3> &,
                            const AffineConstraints<double> &,
                            TrilinosWrappers::SparseMatrix &);
  template std::vector<Tensor<2, 2>>
  elastic_node_blocks<2>(
    const hp::MappingCollection<2> &,
    const DoFHandler<2> &,
    const hp::QCollection<2> &,
    const ElasticityOfCell<2> &,
    const std::vector<std::array<types::global_dof_index, 2>> &);
  template std::vector<Tensor<2, 3>>
  elastic_node_blocks<3>(
    const hp::MappingCollection<3> &,
    const DoFHandler<3> &,
    const hp::QCollection<3> &,
    const ElasticityOfCell<3> &,
    const std::vector<std::array<types::global_dof_index, 3>> &);
  template class ViscoplasticContact<2>;
  template class ViscoplasticContact<3>;
} // namespace ViscoContact
