// StepCycles<dim>: nested iteration in every time step
// (acceleration/step_cycles.h).

#include <deal.II/base/exceptions.h>
#include <deal.II/base/timer.h>

#include <deal.II/multigrid/mg_transfer_global_coarsening.h>

#include "acceleration/step_cycles.h"
#include "back_ends/cost_model.h"
#include "viscoplastic_contact.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <utility>

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
  struct StepCycles<dim>::CoarserProblem
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

    // A nodal field of this mesh in the displacement layout injected into
    // the coarser mesh's (that of layout), with its ghosts.
    VectorType
    injected(const VectorType &field, const VectorType &layout) const
    {
      std::vector<unsigned int> all_components(dim);
      std::iota(all_components.begin(), all_components.end(), 0);
      VectorType coarse_field(layout);
      coarse_field = 0;
      transfer_components(field, coarse_field, false, all_components, true);
      coarse_field.update_ghost_values();
      return coarse_field;
    }
  };



  template <int dim>
  StepCycles<dim>::StepCycles() = default;



  template <int dim>
  StepCycles<dim>::~StepCycles() = default;



  template <int dim>
  void
  StepCycles<dim>::forget()
  {
    coarser.reset();
  }



  template <int dim>
  ActiveSetResult
  StepCycles<dim>::take_last_result()
  {
    return std::exchange(last_result, ActiveSetResult());
  }



  template <int dim>
  bool
  StepCycles<dim>::due(const ViscoplasticContact<dim> &problem) const
  {
    return problem.plan.step_cycles() > 0 && problem.contact_enabled
           && problem.predicted_start.pieces_predictable()
           && !(problem.schedule.step_number() == 0
                && problem.plan.initial_cycles() > 0)
           && !problem.plan.step_cycles_dropped();
  }



  // @sect4{StepCycles::set_up}
  //
  // The coarser problem is a ViscoplasticContact of the parameter file
  // coarsened once (parameters.check_step_cycles() made sure its mesh is
  // this one coarsened uniformly: the same coarse cells refined once less,
  // AllParameters::nested_coarsened()), with Step cycles - 1 of its own, set up
  // as run() sets up a run but without output, checks or schedule: it only
  // ever solves step problems for this object, silently.
  template <int dim>
  void
  StepCycles<dim>::set_up(ViscoplasticContact<dim> &problem)
  {
    TimerOutput::Scope        t(problem.report.timer(), "Setup: step cycles");
    Parameters::AllParameters coarse_parameters
      = problem.parameters.nested_coarsened();
    coarse_parameters.step_cycles_entry
      = std::to_string(problem.plan.step_cycles() - 1);
    coarse_parameters.initial_cycles_entry = "0";
    // The back end of this mesh: the cost model of Method = auto would
    // choose for the coarser mesh alone, without the memory this one holds
    // (a matrix-based back end there could take more than the matrix-free
    // one here).
    coarse_parameters.method                  = problem.plan.back_end().method;
    coarse_parameters.verbose                 = false;
    coarse_parameters.print_iteration_history = false;
    coarse_parameters.print_timing_summary    = false;
    coarse_parameters.measure_cost_ratios     = false;
    coarse_parameters.write_vtu               = false;
    coarse_parameters.resume                  = false;
    coarse_parameters.checkpoint_interval     = 0;

    coarser = std::make_unique<CoarserProblem>();
    coarser->problem
      = std::make_unique<ViscoplasticContact<dim>>(coarse_parameters,
                                                   problem.mpi_communicator);
    ViscoplasticContact<dim> &coarse = *coarser->problem;
    coarse.pcout.set_condition(false);
    coarse.plan.choose_step_cycles(problem.discretisation.has_simplices());
    coarse.make_grid();
    coarse.setup_on_mesh();
    AssertThrow(coarse.contact_enabled == problem.contact_enabled
                  && coarse.contact_set.n_global_nodes() > 0,
                ExcInternalError());
    // Plain transfers: on uniformly refined meshes there are no hanging
    // nodes, and the constrained entries are set by each mesh's constraints
    // after the transfer.
    coarser->transfer.reinit_geometric_transfer(problem.scalar_dof_handler,
                                                coarse.scalar_dof_handler);
    coarser->fine_components
      = component_indices(problem.dof_handler,
                          problem.scalar_dof_handler,
                          *problem.solution.get_partitioner(),
                          *problem.scalar_partitioner);
    coarser->coarse_components
      = component_indices(coarse.dof_handler,
                          coarse.scalar_dof_handler,
                          *coarse.solution.get_partitioner(),
                          *coarse.scalar_partitioner);
    coarser->fine_field.reinit(problem.scalar_partitioner);
    coarser->coarse_field.reinit(coarse.scalar_partitioner);
    // A fine vertex is a vertex of the coarser mesh where it is a vertex of
    // its cell's parent (every cell here has one: the mesh is the coarser
    // one refined).
    coarser->coarser_vertices.reinit(problem.scalar_partitioner);
    std::vector<types::global_dof_index> dofs(
      problem.discretisation.scalar_fe[0].n_dofs_per_cell());
    for (const auto &cell : problem.scalar_dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          cell->get_dof_indices(dofs);
          const auto parent = cell->parent();
          for (const unsigned int a : cell->vertex_indices())
            for (const unsigned int b : parent->vertex_indices())
              if (cell->vertex_index(a) == parent->vertex_index(b)
                  && problem.scalar_partitioner->in_local_range(dofs[a]))
                coarser->coarser_vertices[dofs[a]] = 1;
        }
  }



  // @sect4{StepCycles::inject_contact_state}
  //
  // The laws' state at the start of the step, injected into the coarser
  // mesh's contact nodes (each a contact node of this mesh at the same
  // vertex), so that the coarser problem is this step's problem there: the
  // histories of the laws (memory, bonding, wear, damage) as the last
  // accepted step left them, then their law for this step; with friction
  // the slip measured from u_{n-1} (step_start) in the coarser mesh's own
  // tangential frames, the weakening variables, the obstacle's step, and
  // every node stuck at the start, as after set-up (so that the coarser
  // problem keeps no state between steps). coarse_step_start is u_{n-1}
  // injected.
  template <int dim>
  void
  StepCycles<dim>::inject_contact_state(const ViscoplasticContact<dim> &problem,
                                        const VectorType &coarse_step_start)
  {
    ViscoplasticContact<dim> &coarse = *coarser->problem;
    ContactSet<dim>          &nodes  = coarse.contact_set;
    const auto                inject = [&](const VectorType &field) {
      return coarser->injected(field, coarse.solution);
    };

    std::vector<VectorType> histories;
    for (const VectorType &field :
         nodal_fields_of(problem.contact_histories.all(),
                         problem.contact_set,
                         problem.solution,
                         problem.prescribed.hanging_node_constraints()))
      histories.push_back(inject(field));
    restore_from_nodal_fields(coarse.contact_histories.all(), nodes, histories);
    for (ContactHistory *history : coarse.contact_histories.all())
      if (history->active())
        history->start_step(problem.schedule.step_length(), nodes);

    if (!nodes.has_friction())
      return;
    for (unsigned int i = 0; i < nodes.size(); ++i)
      if (nodes.n_tangential(i) > 0)
        nodes.set_friction_state(i, ContactNodes::stick);
    nodes.reset_slip(
      nodes.tangential_displacements(coarse_step_start),
      std::vector<ContactNodes::Tangential>(nodes.size(),
                                            ContactNodes::Tangential{{0, 0}}));
    if (nodes.has_slip_weakening())
      nodes.set_weakening_from(inject(problem.contact_set.weakening_field(
        problem.solution,
        problem.prescribed.hanging_node_constraints())));
    if (coarse.contact_zones.has_obstacle_motion())
      nodes.set_obstacle_steps(
        coarse.contact_zones.obstacle_steps(problem.schedule.current_time(),
                                            problem.schedule.next_time()));
  }



  // @sect4{StepCycles::start_from_coarser_mesh}
  template <int dim>
  void
  StepCycles<dim>::start_from_coarser_mesh(ViscoplasticContact<dim> &problem,
                                           const VectorType         &step_start)
  {
    if (!coarser)
      set_up(problem);
    TimerOutput::Scope        t(problem.report.timer(), "Solve: step cycles");
    ViscoplasticContact<dim> &coarse   = *coarser->problem;
    const CoarserProblem     &transfer = *coarser;
    std::vector<unsigned int> all_components(dim);
    std::iota(all_components.begin(), all_components.end(), 0);
    // The pressure lives at the x-dofs of the contact nodes.
    const std::vector<unsigned int> first_component{0};

    // The same step: its time levels, its history load restricted, its
    // external load, prescribed values and gaps at t_n on the coarser mesh.
    coarse.schedule     = problem.schedule;
    coarse.history_load = 0;
    if (problem.parameters.explicit_history_update())
      transfer.transfer_components(problem.history_load,
                                   coarse.history_load,
                                   false,
                                   all_components);
    coarse.assemble_right_hand_side(problem.schedule.next_time());

    // The start: u and the contact pressure of this step's start, injected.
    VectorType pressure = problem.contact_set.pressure_field(
      problem.solution,
      problem.prescribed.hanging_node_constraints());
    coarse.solution.zero_out_ghost_values();
    transfer.transfer_components(problem.solution,
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
    const VectorType coarse_step_start
      = transfer.injected(step_start, coarse.solution);
    inject_contact_state(problem, coarse_step_start);
    coarse.contact_set.set_state_from(coarse.solution,
                                      coarse_pressure,
                                      /*with_friction=*/false);

    // The coarser problem's own coarser meshes first, then its solve.
    const unsigned int deeper_iterations
      = coarse.report.step_cycle_iterations();
    if (coarse.step_cycles.due(coarse))
      coarse.step_cycles.start_from_coarser_mesh(coarse, coarse_step_start);
    last_result = coarse.solve_contact_problem(coarse.system_rhs);
    problem.report.count_step_cycle_iterations(
      last_result.iterations() + coarse.report.step_cycle_iterations()
      - deeper_iterations);
    if (!last_result.converged)
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
    if (last_result.iterations() < 3)
      return;
    problem.solution.zero_out_ghost_values();
    transfer.transfer_components(coarse.solution,
                                 problem.solution,
                                 true,
                                 all_components);
    pressure.zero_out_ghost_values();
    pressure = 0;
    transfer.transfer_components(
      coarse.contact_set.pressure_field(
        coarse.solution,
        coarse.prescribed.hanging_node_constraints()),
      pressure,
      true,
      first_component);
    problem.prescribed.distribute(problem.solution, problem.constraints);
    problem.solution.update_ghost_values();
    pressure.update_ghost_values();
    // With friction the coarser mesh's tangential tractions too, so that
    // the nodes the front reached start stuck or slipping as there.
    const bool with_friction = problem.contact_set.has_friction();
    if (with_friction)
      {
        VectorType traction(problem.solution);
        traction = 0;
        transfer.transfer_components(
          coarse.contact_set.tangential_traction_field(coarse.solution),
          traction,
          true,
          all_components);
        traction.update_ghost_values();
        problem.contact_set.set_tangential_state_from(problem.solution,
                                                      traction);
      }
    problem.contact_set.set_state_from(problem.solution,
                                       pressure,
                                       with_friction);
  }



  template class StepCycles<2>;
  template class StepCycles<3>;
} // namespace ViscoContact
