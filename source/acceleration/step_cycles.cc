// Step cycles of ViscoplasticContact<dim>: nested iteration in every time
// step (doc/algorithm.md, "Step cycles").
//
// At a fixed time step the front of the rigid zone crosses more rows of
// nodes per step on a finer mesh, and the active-set iteration finds them a
// batch per iteration, so the iterations per step grow with the mesh
// (doc/performance.md, "Active-set iterations, the mesh and the time step").
// The same step problem on the mesh coarsened once has half as many rows to
// cross and an eighth of the dofs (in 3D); its contact zone, prolongated, is
// wrong only within a coarse cell of the front, so the iteration on the fine
// mesh starts next to its end. Where the step's own start was already right
// at the coarser resolution, it is kept (start_from_coarser_mesh()).
//
// The coarser problem is the step problem restricted to the coarser space:
// its operator is K of the coarser mesh (for Q1 on nested meshes the
// Galerkin product P^T K P), its external load and prescribed values are its
// own, and its history load is P^T of this mesh's, so the viscoplastic
// history of this mesh, not a coarser one's, drives it. It starts from this
// step's start (after the prediction), injected into the coarser space. So
// the coarser problem keeps no state between steps: a cut, rejected or
// resumed step has the same coarser solve as an uninterrupted one.
//
// The transfers are deal.II's MGTwoLevelTransfer between the two meshes
// (the global-coarsening transfer of step-75), on any partition of either:
// the prolongation P and the restriction P^T. They need the meshes nested
// with the same coarse cells: on p4est by construction, and for simplices,
// which are built whole and handed out, by building both from the same
// coarse box (AllParameters::nested_coarsened()). Written here rather than
// taken from deal.II as it is: in deal.II 9.4 the geometric transfer of a
// vector-valued P1 element on simplices and its injection (interpolate())
// on simplices are wrong (a linear field is not reproduced; checked by
// hand), while the scalar P1 and Q1 prolongations are exact. So every field
// is transferred component by component with the scalar element of the
// nodal output fields, and the injection of a fine field f into the
// coarser mesh is P^T applied to f kept at the fine vertices that are
// vertices of the coarser mesh and zeroed elsewhere: there the rows of P
// are unit vectors, so P^T gives f at each coarser vertex.

#include <deal.II/base/exceptions.h>
#include <deal.II/base/timer.h>

#include <deal.II/multigrid/mg_transfer_global_coarsening.h>

#include "back_ends/cost_model.h"
#include "viscoplastic_contact.h"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace ViscoContact
{
  namespace
  {
    // For every owned dof of the scalar element, the local indices of the
    // dim dofs of the vector-valued element at the same vertex (scalar dof
    // s, component c: entry s * dim + c). A vertex's dofs are owned by the
    // same rank in both DoFHandlers.
    template <int dim>
    std::vector<unsigned int>
    component_indices(const DoFHandler<dim>             &dof_handler,
                      const DoFHandler<dim>             &scalar_dof_handler,
                      const Utilities::MPI::Partitioner &vector_layout,
                      const Utilities::MPI::Partitioner &scalar_layout)
    {
      const FiniteElement<dim> &fe = dof_handler.get_fe();
      std::vector<unsigned int> indices(scalar_layout.locally_owned_size()
                                          * dim,
                                        numbers::invalid_unsigned_int);
      std::vector<types::global_dof_index> vector_dofs(fe.n_dofs_per_cell());
      std::vector<types::global_dof_index> scalar_dofs(
        scalar_dof_handler.get_fe().n_dofs_per_cell());
      for (const auto &cell : dof_handler.active_cell_iterators())
        if (cell->is_locally_owned())
          {
            cell->get_dof_indices(vector_dofs);
            const typename DoFHandler<dim>::active_cell_iterator scalar_cell(
              &cell->get_triangulation(),
              cell->level(),
              cell->index(),
              &scalar_dof_handler);
            scalar_cell->get_dof_indices(scalar_dofs);
            for (unsigned int a = 0; a < scalar_dofs.size(); ++a)
              if (scalar_layout.in_local_range(scalar_dofs[a]))
                for (unsigned int c = 0; c < dim; ++c)
                  {
                    const types::global_dof_index dof
                      = vector_dofs[fe.component_to_system_index(c, a)];
                    AssertThrow(vector_layout.in_local_range(dof),
                                ExcInternalError());
                    indices[scalar_layout.global_to_local(scalar_dofs[a]) * dim
                            + c]
                      = vector_layout.global_to_local(dof);
                  }
          }
      return indices;
    }
  } // namespace



  template <int dim>
  struct ViscoplasticContact<dim>::CoarserStepProblem
  {
    // The step problem on the mesh coarsened once, and the scalar transfer
    // between it and this mesh (declared after it: it goes first).
    std::unique_ptr<ViscoplasticContact<dim>> problem;
    MGTwoLevelTransfer<dim, VectorType>       transfer;
    // component_indices() of this mesh and of the coarser one.
    std::vector<unsigned int> fine_components, coarse_components;
    // 1 at the owned scalar dofs of this mesh that are vertices of the
    // coarser mesh, 0 elsewhere (the injection).
    VectorType coarser_vertices;
    // Scratch: a scalar field of each mesh.
    mutable VectorType fine_field, coarse_field;

    // P (prolongate = true: dst on this mesh) or P^T, of component c of
    // src into component c of dst, for every c in components (dst's other
    // entries are left alone, the constrained ones too).
    void
    transfer_components(const VectorType                &src,
                        VectorType                      &dst,
                        const bool                       prolongate,
                        const std::vector<unsigned int> &components,
                        const bool only_coarser_vertices = false) const
    {
      VectorType &from = prolongate ? coarse_field : fine_field;
      VectorType &to   = prolongate ? fine_field : coarse_field;
      const std::vector<unsigned int> &from_indices
        = prolongate ? coarse_components : fine_components;
      const std::vector<unsigned int> &to_indices
        = prolongate ? fine_components : coarse_components;
      for (const unsigned int c : components)
        {
          for (unsigned int s = 0; s < from.locally_owned_size(); ++s)
            from.local_element(s)
              = src.local_element(from_indices[s * dim + c]);
          if (only_coarser_vertices)
            from.scale(coarser_vertices);
          to = 0;
          if (prolongate)
            transfer.prolongate_and_add(to, from);
          else
            transfer.restrict_and_add(to, from);
          for (unsigned int s = 0; s < to.locally_owned_size(); ++s)
            dst.local_element(to_indices[s * dim + c]) = to.local_element(s);
        }
    }
  };



  // @sect4{ViscoplasticContact::step_cycles_due}
  //
  // Where the coarser meshes start the step: with contact, on every step but
  // one that the initial cycles start, and not where the uniqueness check
  // found that the step problem may have several solutions (there the nodes
  // keep the pieces of the branch the run is on, PredictedStart).
  template <int dim>
  bool
  ViscoplasticContact<dim>::step_cycles_due() const
  {
    return plan.step_cycles() > 0 && contact_enabled
           && predicted_start.pieces_predictable()
           && !(schedule.step_number() == 0 && plan.initial_cycles() > 0)
           && !plan.step_cycles_dropped();
  }



  // @sect4{ViscoplasticContact::set_up_coarser_step_problem}
  //
  // The coarser problem is a ViscoplasticContact of the parameter file
  // coarsened once (parameters.check_step_cycles() made sure its mesh is
  // this one coarsened uniformly: the same coarse cells refined once less,
  // AllParameters::nested_coarsened()), with Step cycles - 1 of its own, set up
  // as run() sets up a run but without output, checks or schedule: it only
  // ever solves step problems for this object, silently.
  template <int dim>
  void
  ViscoplasticContact<dim>::set_up_coarser_step_problem()
  {
    TimerOutput::Scope        t(report.timer(), "Setup: step cycles");
    Parameters::AllParameters coarse_parameters = parameters.nested_coarsened();
    coarse_parameters.step_cycles_entry
      = std::to_string(plan.step_cycles() - 1);
    coarse_parameters.initial_cycles_entry = "0";
    // The back end of this mesh: the cost model of Method = auto would
    // choose for the coarser mesh alone, without the memory this one holds
    // (a matrix-based back end there could take more than the matrix-free
    // one here).
    coarse_parameters.method                  = plan.back_end().method;
    coarse_parameters.verbose                 = false;
    coarse_parameters.print_iteration_history = false;
    coarse_parameters.print_timing_summary    = false;
    coarse_parameters.write_vtu               = false;
    coarse_parameters.resume                  = false;
    coarse_parameters.checkpoint_interval     = 0;

    coarser_step_problem = std::make_shared<CoarserStepProblem>();
    coarser_step_problem->problem
      = std::make_unique<ViscoplasticContact<dim>>(coarse_parameters,
                                                   mpi_communicator);
    ViscoplasticContact<dim> &coarse = *coarser_step_problem->problem;
    coarse.pcout.set_condition(false);
    coarse.plan.choose_step_cycles(reference_cell.is_simplex());
    coarse.make_grid();
    coarse.setup_on_mesh();
    AssertThrow(coarse.contact_enabled == contact_enabled
                  && coarse.contact_set.n_global_nodes() > 0,
                ExcInternalError());
    // Plain transfers: on uniformly refined meshes there are no hanging
    // nodes, and the constrained entries are set by each mesh's constraints
    // after the transfer.
    CoarserStepProblem &coarser = *coarser_step_problem;
    coarser.transfer.reinit_geometric_transfer(scalar_dof_handler,
                                               coarse.scalar_dof_handler);
    coarser.fine_components = component_indices(dof_handler,
                                                scalar_dof_handler,
                                                *solution.get_partitioner(),
                                                *scalar_partitioner);
    coarser.coarse_components
      = component_indices(coarse.dof_handler,
                          coarse.scalar_dof_handler,
                          *coarse.solution.get_partitioner(),
                          *coarse.scalar_partitioner);
    coarser.fine_field.reinit(scalar_partitioner);
    coarser.coarse_field.reinit(coarse.scalar_partitioner);
    // A fine vertex is a vertex of the coarser mesh where it is a vertex of
    // its cell's parent (every cell here has one: the mesh is the coarser
    // one refined).
    coarser.coarser_vertices.reinit(scalar_partitioner);
    std::vector<types::global_dof_index> dofs(scalar_fe->n_dofs_per_cell());
    for (const auto &cell : scalar_dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          cell->get_dof_indices(dofs);
          const auto parent = cell->parent();
          for (const unsigned int a : cell->vertex_indices())
            for (const unsigned int b : parent->vertex_indices())
              if (cell->vertex_index(a) == parent->vertex_index(b)
                  && scalar_partitioner->in_local_range(dofs[a]))
                coarser.coarser_vertices[dofs[a]] = 1;
        }
  }



  // @sect4{ViscoplasticContact::start_from_coarser_mesh}
  //
  // Called once the step's right-hand side is assembled and its start
  // predicted: the coarser problem is solved from the injected start, and
  // its u and contact pressure are prolongated into this step's start. A
  // coarser solve that fails leaves the start as it was (the step then
  // starts from the prediction, as without step cycles).
  template <int dim>
  void
  ViscoplasticContact<dim>::start_from_coarser_mesh()
  {
    if (!coarser_step_problem)
      set_up_coarser_step_problem();
    TimerOutput::Scope        t(report.timer(), "Solve: step cycles");
    ViscoplasticContact<dim> &coarse   = *coarser_step_problem->problem;
    const CoarserStepProblem &transfer = *coarser_step_problem;
    std::vector<unsigned int> all_components(dim);
    std::iota(all_components.begin(), all_components.end(), 0);
    // The pressure lives at the x-dofs of the contact nodes.
    const std::vector<unsigned int> first_component{0};

    // The same step: its time levels, its history load restricted, its
    // external load, prescribed values and gaps at t_n on the coarser mesh.
    coarse.schedule     = schedule;
    coarse.history_load = 0;
    if (explicit_history_update())
      transfer.transfer_components(history_load,
                                   coarse.history_load,
                                   false,
                                   all_components);
    coarse.assemble_right_hand_side(schedule.next_time());

    // The start: u and the contact pressure of this step's start, injected.
    VectorType pressure = contact_pressure_field();
    coarse.solution.zero_out_ghost_values();
    transfer.transfer_components(solution,
                                 coarse.solution,
                                 false,
                                 all_components,
                                 true);
    VectorType coarse_pressure(coarse.solution);
    coarse_pressure = 0;
    transfer.transfer_components(pressure,
                                 coarse_pressure,
                                 false,
                                 first_component,
                                 true);
    coarse.prescribed.distribute(coarse.solution, coarse.constraints);
    coarse.solution.update_ghost_values();
    coarse_pressure.update_ghost_values();
    coarse.set_pieces_from(coarse_pressure);

    // The coarser problem's own coarser meshes first, then its solve.
    const unsigned int deeper_iterations
      = coarse.report.step_cycle_iterations();
    if (coarse.step_cycles_due())
      coarse.start_from_coarser_mesh();
    coarser_step_result = coarse.solve_contact_problem(coarse.system_rhs);
    report.count_step_cycle_iterations(coarser_step_result.iterations()
                                       + coarse.report.step_cycle_iterations()
                                       - deeper_iterations);
    if (!coarser_step_result.converged)
      return;

    // Where the coarser iteration took one or two iterations, this step's
    // start was right at the coarser resolution: the coarser mesh's own
    // front sits up to a coarser cell off this mesh's, which one batch of
    // coarser nodes moving accounts for. The start is then kept: where the
    // prediction holds it is exact to the resolution of this mesh, and the
    // coarser state prolongated is not (taken there, it cost an iteration
    // per step on the cube after the contact zone formed). From three on,
    // the front went further than the start says, and the fine iteration
    // would find it in about twice as many batches: the coarser u and
    // pressure, prolongated, start this step.
    if (coarser_step_result.iterations() < 3)
      return;
    solution.zero_out_ghost_values();
    transfer.transfer_components(coarse.solution,
                                 solution,
                                 true,
                                 all_components);
    pressure.zero_out_ghost_values();
    pressure = 0;
    transfer.transfer_components(coarse.contact_pressure_field(),
                                 pressure,
                                 true,
                                 first_component);
    prescribed.distribute(solution, constraints);
    solution.update_ghost_values();
    pressure.update_ghost_values();
    set_pieces_from(pressure);
  }



  // @sect4{ViscoplasticContact::set_pieces_from}
  //
  // Each contact node's r = u.nu - s and z = w p from u and the pressure
  // field p, and the piece they name; the stick/slip states are updated
  // too only if asked (the step cycles leave them as PredictedStart::predict()
  // does; a transfer to a new mesh updates them, then resets the slip).
  template <int dim>
  void
  ViscoplasticContact<dim>::set_pieces_from(const VectorType &pressure,
                                            const bool        with_friction)
  {
    for (unsigned int i = 0; i < contact_set.size(); ++i)
      {
        contact_set.r[i]
          = contact_set.normal_component(solution, i) - contact_set.gap(i);
        contact_set.z[i]
          = contact_set.weight(i)
            * pressure.local_element(contact_set.node(i).local_dofs[0]);
      }
    contact_set.update_pieces(with_friction);
  }



  template class ViscoplasticContact<2>;
  template class ViscoplasticContact<3>;
} // namespace ViscoContact
