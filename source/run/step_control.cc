// The control of a time step: the state a failed or rejected attempt is
// undone with, the cut of a failed step, and the error test of an adaptive
// step (doc/algorithm.md, "Failed solves"; doc/adaptivity.md).

#include <deal.II/base/exceptions.h>

#include "run/step_control.h"
#include "viscoplastic_contact.h"

#include <iomanip>

namespace ViscoContact
{
  // @sect4{StepControl::save_start}
  //
  // What a failed attempt is undone with: u_{n-1} and the contact state (the
  // pieces and (r, z) of every owned node; each rank keeps its own part). The
  // stress points need no copy for that: a failed attempt changes nothing
  // there but the starting guesses of the plastic multipliers, since sigma_n
  // and the history are only written by update_stresses() (and by the
  // rescaling of a cut step). A rejected adaptive step has updated them, so
  // with adaptive steps they are copied too, with the step length the
  // stored history H_n was advanced for.
  template <int dim>
  StepStart<dim>
  StepControl<dim>::save_start(const ViscoplasticContact<dim> &problem)
  {
    StepStart<dim> start{problem.solution, problem.contact_set.state(), {}, 0.};
    if (problem.schedule.is_adaptive())
      start.stress_point_records = problem.quadrature_point_history;
    start.step_length = problem.schedule.step_length();
    return start;
  }



  template <int dim>
  void
  StepControl<dim>::restore_start(ViscoplasticContact<dim> &problem,
                                  const StepStart<dim>     &start)
  {
    problem.solution = start.solution;
    problem.solution.update_ghost_values();
    problem.contact_set.set_state(start.contact);
    // The laws of the last accepted step (memory pressures, bonding, worn
    // depths), not the attempt's: what a failed step writes and reports.
    for (ContactHistory *history : problem.contact_histories.all())
      if (problem.contact_enabled && history->active())
        history->apply_accepted(problem.contact_set);
  }



  // @sect4{StepControl::cut_failed_step}
  //
  // Recovery from a failed solve (doc/algorithm.md, "Failed solves"): the
  // step is halved (TimeSchedule::cut_step()), only if On solver failure =
  // cut time step, and never below Minimum time step; otherwise the caller
  // stops the run with failure_report(). The decision uses only data every
  // rank has alike, so all ranks cut or stop together.
  template <int dim>
  bool
  StepControl<dim>::cut_failed_step(ViscoplasticContact<dim> &problem,
                                    const std::string        &failure)
  {
    const double k = problem.schedule.step_length();
    if (problem.parameters.on_failure
          != Parameters::FailurePolicy::cut_time_step
        || k / 2 < problem.parameters.minimum_time_step)
      return false;
    problem.pcout << "Step " << problem.schedule.step_number() + 1
                  << " (t = " << problem.schedule.next_time() << ", k = " << k
                  << ") failed: " << failure
                  << "\n  Cutting the time step to k = " << k / 2 << ".\n";
    problem.schedule.cut_step();
    return true;
  }



  // @sect4{StepControl::accept_adaptive_step}
  //
  // The controller's decision on a solved step, from the error estimate of its
  // stress update. An accepted step returns true with the step the controller
  // proposes next. A rejected step is repeated from the state at its start,
  // restored exactly: u_{n-1}, the contact state, and every stress-point
  // record (sigma_{n-1}, the history H_n, the rates and multipliers); the
  // history increment is then rescaled to the shorter step, as for a cut.
  // Every rank has the same estimate (a sum over the ranks), so all take the
  // same decision.
  template <int dim>
  bool
  StepControl<dim>::accept_adaptive_step(ViscoplasticContact<dim> &problem,
                                         const StepStart<dim>     &start,
                                         double &proposed_step)
  {
    const TimeStepController &controller = problem.step_controller;
    const double              k          = problem.schedule.step_length();
    const TimeStepDecision    decision
      = control_time_step(controller,
                          k,
                          problem.error_estimate,
                          problem.schedule.proposed_step());
    if (decision.accepted)
      {
        if (problem.error_estimate > controller.tolerance
            && problem.parameters.verbose)
          problem.pcout << "  Step " << problem.schedule.step_number() + 1
                        << " is at <Minimum time step> = "
                        << controller.minimum_step
                        << " and accepted above <Error tolerance>.\n";
        proposed_step = decision.step;
        return true;
      }

    // Rejected: the shorter step, fitted to the targets like any other.
    const double rejected_time = problem.schedule.next_time();
    problem.schedule.reject_step(decision.step);
    if (problem.parameters.verbose)
      problem.pcout << "  Step " << problem.schedule.step_number() + 1
                    << " (t = " << rejected_time << ", k = " << k
                    << ") rejected: error estimate " << std::setprecision(3)
                    << problem.error_estimate << " > " << controller.tolerance
                    << "; repeated with k = " << std::setprecision(6)
                    << problem.schedule.step_length() << '\n';
    restore_start(problem, start);
    problem.quadrature_point_history = start.stress_point_records;
    if (problem.parameters.explicit_history_update())
      problem.rescale_history_increment(start.step_length,
                                        problem.schedule.step_length());
    return false;
  }


  template class StepControl<2>;
  template class StepControl<3>;
} // namespace ViscoContact
