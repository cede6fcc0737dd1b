// The report of a time step (step_report.h): the line a verbose run prints
// per step and the report of a step whose solve failed. Both depend only on
// values every rank has alike.

#include <deal.II/base/exceptions.h>

#include "step_report.h"

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
