// Initial cycles: nested iteration on the first step of a run
// (doc/adaptivity.md, "Initial cycles").

#include <deal.II/base/timer.h>

#include "acceleration/initial_cycles.h"
#include "mesh/mesh_adaptation.h"
#include "viscoplastic_contact.h"

#include <array>

namespace ViscoContact
{
  // @sect4{InitialCycles::solve}
  //
  // Nested iteration on the first step (doc/adaptivity.md, "Initial
  // cycles"). A cold start's active-set iteration overshoots: its first solve,
  // with every node out of contact, pushes a region of nodes to the rigid
  // limit that the following iterations release from its edge, some half of
  // the surplus per iteration, so the count grows with the number of contact
  // nodes (doc/performance.md). On a mesh twice as coarse the same step costs
  // less than a quarter, and its contact zone, interpolated to the fine mesh,
  // is wrong only at the front, within a cell or two of the coarse mesh.
  //
  // So step 1 is solved on the first mesh of the cycles, and then, cycle by
  // cycle, the mesh is refined (every cell, or by the indicator of the
  // adaptive meshes), u and the contact pressure are carried over by
  // MeshAdaptation::refine_and_transfer(), the new contact nodes get the pieces
  // the carried pressure and u name, and step 1 is solved again from there. The
  // history of step 1 is the initial one on every mesh (setup_on_mesh() leaves
  // it so), so each re-solve is the same step problem, only warm-started: its
  // solution is the unique one of the step problem on that mesh, whatever the
  // start (tests/initial_cycles). The last solve, on the last mesh, is run()'s
  // step 1; this function leaves its starting point: the mesh, the state
  // carried over to it, and its external load.
  //
  // The schedule is restored after the coarse solves, so that a step cut on
  // a coarse mesh does not change the schedule of the run (the cut solve is
  // still a start). Their active-set iterations are counted apart from those
  // of the run's steps, and their Newton and inner iterations not at all, so
  // that the run summary's counts are those of the recorded steps.
  template <int dim>
  void
  InitialCycles<dim>::solve(ViscoplasticContact<dim> &problem)
  {
    TimerOutput::Scope t(problem.report.timer(), "Initial cycles");
    const bool         global = problem.parameters.initial_refinement
                        == Parameters::InitialRefinement::global;
    for (unsigned int cycle = 0; cycle < problem.plan.initial_cycles(); ++cycle)
      {
        const TimeSchedule                run_schedule = problem.schedule;
        const std::array<unsigned int, 3> counts_before
          = problem.report.step_counts();
        const ActiveSetResult result = problem.solve_step_with_recovery(
          StepControl<dim>::save_start(problem));
        // The time the solution is at (a cut step ends before t_1), whose
        // gaps give the next mesh's contact nodes their pieces.
        const double state_time = problem.schedule.next_time();
        problem.report.count_initial_cycle(result.iterations());
        problem.report.restore_step_counts(counts_before);
        if (problem.parameters.verbose
            || problem.parameters.print_iteration_history)
          problem.pcout << "Initial cycle " << cycle << ": "
                        << problem.triangulation->n_global_active_cells()
                        << " cells, " << problem.dof_handler.n_dofs()
                        << " dofs, "
                        << (problem.contact_enabled
                              ? problem.contact_set.n_global_nodes()
                              : 0)
                        << " contact nodes, " << result.iterations()
                        << " active-set iterations" << std::endl;
        if (problem.parameters.print_iteration_history)
          problem.pcout << result.describe() << std::flush;

        // The next mesh: every cell refined, or the marking of the adaptive
        // meshes, whose indicator also looks at the plastic zone of step 1's
        // stresses (computed here, on the mesh that is left behind).
        bool marked = true;
        if (problem.discretisation.has_simplices())
          {
            // A simplex mesh is built anew, one coarsening less.
            problem.schedule = run_schedule;
            MeshAdaptation<dim>::rebuild_and_transfer(
              problem,
              problem.plan.initial_cycles() - cycle - 1,
              state_time);
            problem.assemble_external_load(problem.schedule.next_time());
            continue;
          }
        if (global)
          {
            for (const auto &cell :
                 problem.triangulation->active_cell_iterators())
              if (cell->is_locally_owned())
                cell->set_refine_flag();
          }
        else
          {
            if (problem.parameters.any_plasticity())
              problem.update_stresses(problem.schedule.step_length(), 0.);
            marked = MeshAdaptation<dim>::mark_cells(problem);
          }
        problem.schedule = run_schedule;
        if (!marked)
          break;
        MeshAdaptation<dim>::refine_and_transfer(
          problem,
          /*transfer_stress_points=*/false,
          state_time);
        // The external load of step 1 on the new mesh (the history load of the
        // initial state is zero, as setup_on_mesh() left it).
        problem.assemble_external_load(problem.schedule.next_time());
      }
    // The mesh of the run from here on, and its back end, which the header
    // (on the first mesh of the cycles) does not show.
    problem.pcout << "Initial cycles done: "
                  << problem.triangulation->n_global_active_cells()
                  << " cells, " << problem.dof_handler.n_dofs() << " dofs, "
                  << (problem.contact_enabled
                        ? problem.contact_set.n_global_nodes()
                        : 0)
                  << " contact nodes for step 1; back end: "
                  << problem.contact_solver->description() << " ("
                  << problem.plan.back_end().reason << ")" << std::endl;
    // The header announced the step cycles auto chose from its estimate;
    // with the condensed back end on this mesh none run.
    if (problem.plan.step_cycles_dropped())
      problem.pcout
        << "Step cycles: none after all (Step cycles = auto: Method = "
           "auto chose the condensed back end for this mesh)"
        << std::endl;
  }


  template class InitialCycles<2>;
  template class InitialCycles<3>;
} // namespace ViscoContact
