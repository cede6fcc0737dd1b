// The report of a time step (step_report.h): the line a verbose run prints
// per step and the report of a step whose solve failed. Both depend only on
// values every rank has alike.

#include <deal.II/base/exceptions.h>

#include "step_report.h"

#include <cmath>
#include <iomanip>
#include <sstream>

namespace ViscoContact
{
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
  // contact force; then, in brackets, the progress of the run
  // (RunProgress::text()). The regression tests compare these lines up to
  // the brackets (whose times differ from run to run), so that part of
  // their format is fixed. Each line is flushed, so that a log file shows
  // the progress of a batch job as it happens.
  void
  print_step_line(ConditionalOStream                &out,
                  const unsigned int                 step,
                  const double                       time,
                  const unsigned int                 iterations,
                  const std::array<unsigned int, 3> &contact_states,
                  const double                       total_contact_force,
                  const std::string                 &progress)
  {
    print_step_line_start(out,
                          step,
                          time,
                          iterations,
                          contact_states,
                          total_contact_force);
    out << "  " << progress << std::endl;
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
                           const double       total_contact_force,
                           const double       time_step,
                           const double       error_estimate,
                           const std::string &progress)
  {
    print_step_line_start(out,
                          step,
                          time,
                          iterations,
                          contact_states,
                          total_contact_force);
    out << "  k " << std::setprecision(6) << time_step << "  estimate "
        << std::setprecision(3) << error_estimate << "  " << progress
        << std::endl;
  }



  // @sect4{RunProgress}
  RunProgress::RunProgress(const unsigned int first_step,
                           const double       start_time,
                           const double       earlier_wall_time)
    : first_step(first_step)
    , start_time(start_time)
    , earlier_wall_time(earlier_wall_time)
  {}



  double
  RunProgress::wall_time() const
  {
    return earlier_wall_time + timer.wall_time();
  }



  // The time left is the time of this process's steps so far, scaled by
  // what is left of the run: steps with fixed steps, simulated time with
  // adaptive ones (whose step lengths are not known ahead).
  std::string
  RunProgress::text(const unsigned int step,
                    const unsigned int n_steps,
                    const double       time,
                    const double       end_time) const
  {
    std::ostringstream line;
    line << std::setprecision(6) << '[';
    if (n_steps > 0)
      line << "step " << step << " of " << n_steps;
    else
      line << "t " << time << " of " << end_time;
    line << ", " << format_duration(wall_time());
    const double elapsed = timer.wall_time();
    const double done
      = n_steps > 0 ? double(step - first_step) : time - start_time;
    const double left = n_steps > 0 ? double(n_steps) - step : end_time - time;
    // One step says little of the rate (it has the cold start and the set-up
    // of solvers); from the second on the estimate is printed.
    if (step > first_step + 1 && done > 0 && left > 0)
      line << ", about " << format_duration(elapsed / done * left) << " left";
    line << ']';
    return line.str();
  }



  // @sect4{format_duration}
  std::string
  format_duration(const double seconds)
  {
    std::ostringstream text;
    if (!std::isfinite(seconds))
      return "?";
    if (!(seconds < 60))
      {
        const long total = std::lround(seconds);
        if (total < 3600)
          text << total / 60 << " min " << std::setw(2) << std::setfill('0')
               << total % 60 << " s";
        else
          text << total / 3600 << " h " << std::setw(2) << std::setfill('0')
               << (total % 3600) / 60 << " min";
      }
    else if (seconds < 10)
      text << std::setprecision(2) << std::fixed << seconds << " s";
    else
      text << std::lround(seconds) << " s";
    return text.str();
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
