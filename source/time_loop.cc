// Pieces of the time loop: the schedule, the line per step, cutting a failed
// step, and the report of a step that failed.
//
// They depend only on the parameters, the schedule and values that every
// rank has alike, so every rank computes the same schedule and takes the
// same decisions without communication; the time loop itself
// (viscoplastic_contact.cc, time_step.cc) calls them.

#include <deal.II/base/exceptions.h>

#include "time_loop.h"

#include <cmath>
#include <iomanip>
#include <sstream>

namespace ViscoContact
{
  // @sect4{time_levels}
  //
  // The schedule t_0 = 0 < t_1 < ... < t_N = T of the run: equal steps k,
  // the last one shortened so that the run ends at T exactly. A failed step
  // may later insert levels (cut_failed_step()).
  std::vector<double>
  time_levels(const double end_time, const double time_step)
  {
    // N = ceil(T/k), computed with a relative margin of 1e-12 so that a T
    // that is a multiple of k up to rounding does not get a spurious last
    // step of length almost zero.
    const unsigned int N = static_cast<unsigned int>(
      std::ceil(end_time / time_step * (1 - 1e-12)));
    std::vector<double> times(N + 1);
    for (unsigned int n = 0; n < N; ++n)
      times[n] = n * time_step;
    // The last level is T itself, not N k, which may differ by rounding (or
    // by a shortened last step).
    times[N] = end_time;
    return times;
  }



  // @sect4{control_time_step}
  //
  // The elementary (I-) controller of doc/adaptivity.md. The estimate of a
  // step of length k is the local error of forward Euler, C k^2, so the step
  // that would just meet the tolerance is k (tol/error)^(1/2); the safety
  // factor aims below it, so that the next step is rarely rejected, and the
  // change per step is bounded (growth by at most max_growth, shrinking by at
  // most max_shrink), since C itself changes from step to step. The growth
  // is bounded relative to the step the controller wanted for this step, not
  // to the one taken when landing on a target shortened it: the estimate per
  // k^2 is the same either way.
  TimeStepDecision
  control_time_step(const TimeStepController &controller,
                    const double              step,
                    const double              error,
                    const double              desired_step)
  {
    // A step at the minimum is accepted whatever its estimate: there is no
    // shorter one to try (the run says so).
    const bool at_minimum = step <= controller.minimum_step * (1 + 1e-12);
    const bool accepted   = error <= controller.tolerance || at_minimum;
    // The optimal factor; an estimate of zero (no plasticity, or a history
    // that does not change) lets the step grow as fast as allowed.
    const double optimal
      = error > 0 ? controller.safety * std::sqrt(controller.tolerance / error)
                  : controller.max_growth;
    double proposed = step * std::max(controller.max_shrink, optimal);
    // A rejected step is never repeated with a longer one; an accepted one
    // grows by at most max_growth relative to what the controller wanted.
    if (accepted)
      proposed = std::min(proposed,
                          controller.max_growth * std::max(step, desired_step));
    else
      proposed = std::min(proposed, step);
    proposed = std::min(std::max(proposed, controller.minimum_step),
                        controller.maximum_step);
    return {accepted, proposed};
  }



  // @sect4{next_time_level}
  //
  // Landing on the targets (End time, the Profile times): with r the distance
  // to the next target, a step k >= r is shortened to r and the target is
  // reached exactly (the level is the target itself, not time + r, which may
  // differ by rounding); a step with r/2 < k < r would leave a remainder
  // shorter than k, possibly tiny, before the target, so the remainder is
  // split into two equal steps instead; a step k <= r/2 is taken as it is.
  // Targets at or before time (within a relative 1e-12 of the last target)
  // are passed.
  double
  next_time_level(const double               time,
                  const double               step,
                  const std::vector<double> &targets)
  {
    Assert(!targets.empty(), ExcInternalError());
    const double end       = targets.back();
    const double tolerance = 1e-12 * end;
    for (const double target : targets)
      {
        if (target <= time + tolerance)
          continue;
        const double remainder = target - time;
        if (step >= remainder - tolerance)
          return target;
        if (2 * step > remainder)
          return time + remainder / 2;
        return time + step;
      }
    // Past the last target: nothing to land on (the caller stops at End
    // time before).
    return time + step;
  }



  namespace
  {
    // The part of the line per step that fixed and adaptive steps share,
    // without the end of the line.
    void
    print_step_line_start(ConditionalOStream                &out,
                          const unsigned int                 step,
                          const double                       time,
                          const unsigned int                 iterations,
                          const std::array<unsigned int, 3> &contact_states,
                          const double total_contact_force)
    {
      out << "Step " << std::setw(4) << step << "  t = " << std::setw(9)
          << std::setprecision(6) << time << "  active-set iterations "
          << std::setw(2) << iterations << "  unilateral " << std::setw(4)
          << contact_states[0] << "  compliance " << std::setw(4)
          << contact_states[1] << "  no contact " << std::setw(4)
          << contact_states[2] << "  contact force " << std::setprecision(8)
          << total_contact_force;
    }
  } // namespace



  // @sect4{print_step_line}
  //
  // One line per step for a verbose run: the step, the time, the active-set
  // iterations, the contact states (rigid limit, normal compliance, no
  // contact, as ContactNodes::count_states() returns them) and the total
  // contact force. The regression tests compare these lines, so their format
  // is fixed. Each line is flushed, so that a log file shows the progress of
  // a batch job as it happens.
  void
  print_step_line(ConditionalOStream                &out,
                  const unsigned int                 step,
                  const double                       time,
                  const unsigned int                 iterations,
                  const std::array<unsigned int, 3> &contact_states,
                  const double                       total_contact_force)
  {
    print_step_line_start(out,
                          step,
                          time,
                          iterations,
                          contact_states,
                          total_contact_force);
    out << std::endl;
  }



  // @sect4{print_adaptive_step_line}
  //
  // The line of print_step_line() with the step length and the relative
  // error estimate appended.
  void
  print_adaptive_step_line(ConditionalOStream                &out,
                           const unsigned int                 step,
                           const double                       time,
                           const unsigned int                 iterations,
                           const std::array<unsigned int, 3> &contact_states,
                           const double total_contact_force,
                           const double time_step,
                           const double error_estimate)
  {
    print_step_line_start(out,
                          step,
                          time,
                          iterations,
                          contact_states,
                          total_contact_force);
    out << "  k " << std::setprecision(6) << time_step << "  estimate "
        << std::setprecision(3) << error_estimate << std::endl;
  }



  // @sect4{cut_failed_step}
  //
  // Recovery from a failed solve (doc/algorithm.md, "Failed solves"): the
  // step from t_{n-1} to t_n is halved by inserting the level t_{n-1} + k/2
  // as the new t_n; the old t_n follows as the next level, so the run still
  // reaches every level of the original schedule. Only if On solver failure
  // = cut time step, and never below Minimum time step; otherwise the caller
  // stops the run with failure_report(). The decision uses only data every
  // rank has alike, so all ranks cut or stop together.
  bool
  cut_failed_step(const Parameters::AllParameters &parameters,
                  ConditionalOStream              &out,
                  const unsigned int               step,
                  std::vector<double>             &times,
                  const std::string               &failure)
  {
    // The length of the step that failed.
    const double k = times[step] - times[step - 1];
    if (parameters.on_failure != Parameters::FailurePolicy::cut_time_step
        || k / 2 < parameters.minimum_time_step)
      return false;
    // Say what failed and how the step is cut (rank 0 prints).
    out << "Step " << step << " (t = " << times[step] << ", k = " << k
        << ") failed: " << failure
        << "\n  Cutting the time step to k = " << k / 2 << ".\n";
    times.insert(times.begin() + step, times[step - 1] + k / 2);
    return true;
  }



  // @sect4{failed_state_file}
  //
  // failed_step_NNNN.ext, with the step number padded to four digits.
  std::string
  failed_state_file(const unsigned int step, const std::string &extension)
  {
    std::ostringstream name;
    name << "failed_step_" << std::setw(4) << std::setfill('0') << step << '.'
         << extension;
    return name.str();
  }



  // @sect4{failure_report}
  //
  // The message with which a run stops after a step that failed and is not
  // cut (again): what failed and why, the iteration history of the last
  // active-set run, the contact state of the last iterate, where the last
  // accepted state (t_{n-1}, at t - k) was written, and what can be changed
  // in the parameter file. The message is the same on every rank.
  std::string
  failure_report(const Parameters::AllParameters   &parameters,
                 const unsigned int                 step,
                 const double                       time,
                 const double                       time_step,
                 const ActiveSetResult             &result,
                 const std::array<unsigned int, 3> &contact_states,
                 const std::string                 &state_file)
  {
    std::ostringstream message;
    message << "Time step " << step << " (t = " << time << ", k = " << time_step
            << ") failed. " << result.failure << '\n'
            << "Iteration history:\n"
            << result.describe()
            << "Contact state of the last iterate: " << contact_states[0]
            << " nodes at the rigid limit, " << contact_states[1]
            << " in normal-compliance contact, " << contact_states[2]
            << " out of contact.\n"
            << "The last accepted state (t = " << time - time_step
            << ") is written to " << state_file << ".\n";
    // Pieces that settled, with linear solves that stay above the
    // tolerance: neither a shorter step nor the uniqueness condition is the
    // matter, but the accuracy the linear problem of the pieces allows.
    const auto &history = result.history;
    if (history.size() >= 2 && history.back().changed_nodes == 0
        && history[history.size() - 2].changed_nodes == 0
        && history.back().linear_residual > parameters.tolerance)
      {
        unsigned int settled = history.size();
        while (settled > 1 && history[settled - 2].changed_nodes == 0)
          --settled;
        message << "The pieces of the contact law settled in iteration "
                << settled
                << " (no node changed its piece after it), but the linear "
                   "solves stayed at a relative residual of "
                << history.back().linear_residual
                << ", above <Tolerance> = " << parameters.tolerance
                << " in subsection <Active set solver>: the linear problem "
                   "of these pieces cannot be solved more accurately (its "
                   "rounding). A Tolerance above the residual accepts it.";
        return message.str();
      }
    // What can be changed depends on the failure policy: with cutting, the
    // minimum step was reached; without, cutting is the remedy to try.
    if (parameters.on_failure == Parameters::FailurePolicy::cut_time_step)
      message << "Cutting the step further would go below <Minimum time "
                 "step> = "
              << parameters.minimum_time_step << " in subsection <Time>.\n";
    else
      message << "<On solver failure> = cut time step in subsection <Time> "
                 "retries failing steps with smaller time steps.\n";
    // And the mathematical reason a step problem can fail at all: the
    // uniqueness condition of doc/model.md, section 4.
    message << "If the contact law softens more than the body can carry "
               "(doc/model.md, section 4) the step problem may have several "
               "solutions or none.";
    return message.str();
  }
} // namespace ViscoContact
