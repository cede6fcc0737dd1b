// ViscoplasticContact<dim>: the constructor, the algorithm (run), and the
// access the convergence study needs.

#include <deal.II/base/exceptions.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/utilities.h>


#include "scene/loads.h"
#include "mesh/mesh.h"
#include "robustness/checkpoint_file.h"
#include "mesh/mesh_checks.h"
#include "robustness/stop_signals.h"
#include "step_report.h"
#include "viscoplastic_contact.h"

#include <algorithm>
#include <map>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <limits>
#include <sstream>

namespace ViscoContact
{



  // @sect4{ViscoplasticContact::ViscoplasticContact}
  //
  // The choice between simplices and hypercubes is made here, once: the
  // cell types give the mappings, the finite elements (P1 or Q1) and the
  // quadratures (discretisation.h), and everything else is written for
  // either. On simplices the P1 strain is constant per cell and one stress
  // point per cell is the piecewise-constant stress space; on hypercubes the
  // stresses live at the 2^dim Gauss points (doc/model.md, section 2). The
  // same stress quadrature is used to assemble K, so that (sigma, eps(v))
  // summed over the stress points is exactly (K u)(v) + (H, eps(v)): the
  // operator and the history load are integrated alike.
  //
  // Nothing is done with the mesh yet: the constructor creates the elements
  // and the quadratures, and builds the scene from the parameters
  // (materials, loads, Dirichlet parts, contact zones); run() builds
  // everything else.
  template <int dim>
  ViscoplasticContact<dim>::ViscoplasticContact(
    const Parameters::AllParameters &parameters,
    const MPI_Comm                   communicator)
    : parameters(parameters)
    , mpi_communicator(communicator)
    , mesh_group_root(parameters.cell_type != Parameters::CellType::hypercube
                      && Utilities::MPI::this_mpi_process(communicator)
                             % mesh_group_size(parameters, communicator)
                           == 0)
    , pcout(std::cout, Utilities::MPI::this_mpi_process(communicator) == 0)
    , report(this->parameters, communicator, pcout, mesh_group_root)
    , plan(this->parameters, communicator, mesh_group_root)
    , discretisation(parameters.cell_type)
    , materials(parameters)
    , loads(parameters)
    , prescribed(parameters, communicator)
    , contact_zones(parameters)
  {
    // main() instantiates the class for the Dimension the parameter file names;
    // a mismatch is a programming error.
    AssertThrow(parameters.dimension == dim, ExcInternalError());
  }



  // @sect4{ViscoplasticContact::~ViscoplasticContact}
  template <int dim>
  ViscoplasticContact<dim>::~ViscoplasticContact()
  {
    // The DoFHandlers refer to the triangulation: release them first, after
    // the coarser step problem, whose transfer refers to them.
    step_cycles.forget();
    scalar_dof_handler.clear();
    dof_handler.clear();
  }



  // @sect4{ViscoplasticContact::run}
  //
  // The algorithm of doc/model.md, section 2, as the reader would write it
  // down: set up, then step by step through the schedule: assemble the
  // right-hand side, solve the step's variational-hemivariational inequality
  // by the active-set method (for the implicit update: a Newton iteration of
  // such solves), update the stresses and the history (do_time_step()), and
  // write the results (finish_time_step()).
  template <int dim>
  void
  ViscoplasticContact<dim>::run()
  {
    // Set-up: a folder with another run's files is refused and a generated
    // mesh far too large for the machine is refused before any work is done;
    // then the mesh, and everything that depends on it (setup_on_mesh()). A
    // scheduler's signal during the set-up stops the run between its phases
    // (there is no step to save yet).
    output.open_folder(parameters, mpi_communicator);
    plan.check_memory();
    plan.choose_initial_cycles();
    plan.choose_step_cycles(discretisation.has_simplices());
    make_grid();
    StopSignals::stop_if_received(mpi_communicator, "after the mesh");
    setup_on_mesh();
    StopSignals::stop_if_received(mpi_communicator,
                                  "after the operator and the back end");
    set_up_schedule();
    prepare_output();

    // The time loop. Only the steps count as compute time; output is timed
    // apart. The wall time written per step counts from the start of the
    // original run: a resumed run adds the time the interrupted run had
    // spent up to its checkpoint. The step lines say how far the run is and
    // estimate the time left.
    report.start_time_loop(schedule.step_number(), schedule.current_time());
    while (!schedule.is_at_end())
      {
        Timer                 step_timer;
        const ActiveSetResult result = do_time_step();
        report.add_compute_time(step_timer.wall_time());
        if (!finish_time_step(result, report.wall_time()))
          break;
      }

    output.print_summary(*this);
  }



  // @sect4{ViscoplasticContact::set_up_schedule}
  //
  // Fixed steps: t_n = n k with the last step shortened to end at T.
  // Adaptive steps: t_1 after the first step, Time step within the
  // controller's range, fitted to the targets; each accepted step adds the
  // next level (doc/adaptivity.md). A resumed run replaces the schedule by the
  // one of its checkpoint (with the cut steps of the interrupted run),
  // restores the state, and continues after the checkpoint's step. All of
  // this happens before the output folder is prepared, so that a load that
  // is not finite, or a damaged or mismatched checkpoint, stops the run
  // before anything is written.
  template <int dim>
  void
  ViscoplasticContact<dim>::set_up_schedule()
  {
    step_controller
      = make_time_step_controller(parameters.error_tolerance,
                                  parameters.minimum_time_step,
                                  parameters.maximum_time_step,
                                  parameters.explicit_history_update()
                                    ? materials.explicit_stability_limit()
                                    : std::numeric_limits<double>::infinity());
    if (parameters.time_step_control == Parameters::TimeStepControl::adaptive)
      schedule = TimeSchedule::adaptive_steps(
        landing_targets(parameters.profile_times, parameters.end_time),
        std::min(std::max(parameters.time_step, step_controller.minimum_step),
                 step_controller.maximum_step),
        parameters.time_step);
    else
      schedule
        = TimeSchedule::fixed_steps(parameters.end_time, parameters.time_step);
    check_scene_values();
    if (parameters.resume)
      checkpoints.resume(*this);
  }



  // @sect4{ViscoplasticContact::prepare_output}
  //
  // The .vtu records must fit on the disk; then the folder is prepared (a
  // resumed run keeps what its checkpoint's step had written). The header and
  // the limits of the scheme go to the console before the first step, so
  // that a user sees a warning (unstable time step, several solutions
  // possible) at once and not after the run. The initial state u_0 = 0,
  // sigma_0 = 0 is record 0; a resumed run has it already.
  template <int dim>
  void
  ViscoplasticContact<dim>::prepare_output()
  {
    plan.check_output_volume(triangulation->n_global_active_cells(),
                             discretisation.max_vertices(),
                             schedule.n_steps());
    StopSignals::stop_if_received(mpi_communicator,
                                  "before the output folder was prepared");
    output.prepare_folder(*this, schedule.step_number());
    output.print_header(*this, schedule.n_steps());
    report_scheme_limits();
    if (parameters.write_vtu && schedule.step_number() == 0)
      output.write_results(*this, 0, 0.);
  }



  // @sect4{ViscoplasticContact::finish_time_step}
  //
  // What follows an accepted step n, in this order: the observer of a study,
  // the time-series row and the step line (sums over the ranks: every rank
  // calls the collective ContactNodes::count_states() and total_force(),
  // rank 0 prints), the contact profile and the .pvtu record (written by all
  // ranks into shared files), the mesh adaptation, the checkpoint, and the
  // scheduler's signals. The mesh is adapted after the output of step n
  // (which shows the mesh step n was computed on) and before its checkpoint
  // (which stores the adapted mesh and state); the checkpoint comes after
  // the output, so that a run resumed from it has everything of step n on
  // disk, and the .pvd list it stores includes step n.
  template <int dim>
  bool
  ViscoplasticContact<dim>::finish_time_step(const ActiveSetResult &result,
                                             const double           wall_time)
  {
    const unsigned int n = schedule.step_number();
    const double       t = schedule.current_time();
    const double       k = t - schedule.previous_time();
    if (step_observer)
      step_observer(n, t);

    output.write_time_series_row(*this, n, t, k, result, wall_time);
    // The iteration history is read under its step's line.
    const bool step_line
      = parameters.verbose || parameters.print_iteration_history;
    const std::string progress_text
      = report.progress(n,
                        schedule.is_adaptive() ? 0 : schedule.n_steps(),
                        t,
                        schedule.end_time());
    if (step_line && !schedule.is_adaptive())
      print_step_line(pcout,
                      n,
                      t,
                      result.iterations(),
                      contact_set.count_states(mpi_communicator),
                      contact_set.total_force(mpi_communicator),
                      progress_text);
    if (step_line && schedule.is_adaptive())
      print_adaptive_step_line(pcout,
                               n,
                               t,
                               result.iterations(),
                               contact_set.count_states(mpi_communicator),
                               contact_set.total_force(mpi_communicator),
                               k,
                               error_estimate,
                               progress_text);
    const ActiveSetResult coarser_result = step_cycles.take_last_result();
    if (parameters.print_iteration_history)
      {
        if (!coarser_result.history.empty())
          pcout << "    step cycles: " << coarser_result.iterations()
                << " active-set iterations on the coarser mesh\n";
        pcout << result.describe() << std::flush;
      }
    // The profile for a requested time is written at the step closest to it
    // (adaptive steps land on it exactly).
    if (contact_enabled
        && std::any_of(parameters.profile_times.begin(),
                       parameters.profile_times.end(),
                       [&](const double target) {
                         return schedule.current_time_is_closest_to(target);
                       }))
      output.write_contact_profile(*this, n, t);
    if (parameters.write_vtu
        && (n % parameters.interval == 0 || schedule.is_at_end()))
      output.write_results(*this, n, t);
    if (MeshAdaptation<dim>::due(*this))
      MeshAdaptation<dim>::adapt(*this, t);
    const bool checkpoint_due = parameters.checkpoint_interval > 0
                                && n % parameters.checkpoint_interval == 0;
    if (checkpoint_due)
      checkpoints.write(*this, wall_time);
    checkpoints.stop_if_signalled(*this, checkpoint_due, wall_time);

    // For tests of the checkpoints: end the loop here as if the run had
    // been killed after the checkpoint; the summary is still printed.
    if (n == parameters.stop_after_step)
      {
        pcout << "Stopped after step " << n
              << " as requested (Stop after step, subsection "
                 "<Checkpoint>).\n";
        return false;
      }
    return true;
  }



  // @sect4{Access for studies}
  //
  // The convergence study runs several ViscoplasticContact objects and compares
  // their states at every time level. It installs an observer that run() calls
  // after every accepted step and reads (stress_point_state()), per locally
  // owned cell k and stress point q, the stress, the displacement gradient and
  // the weight JxW: the same (k, q) indexing as the stress-point arrays, so it
  // needs no FEValues either. All of this is local to a rank; the study itself
  // sends the cells where they are needed.
  template <int dim>
  void
  ViscoplasticContact<dim>::set_step_observer(
    const std::function<void(const unsigned int, const double)> &observer)
  {
    step_observer = observer;
  }



  // Both dimensions are compiled into the library; main() and the convergence
  // study pick one at run time.
  template class ViscoplasticContact<2>;
  template class ViscoplasticContact<3>;
} // namespace ViscoContact
