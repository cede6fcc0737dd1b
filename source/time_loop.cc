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
    out << "Step " << std::setw(4) << step << "  t = " << std::setw(9)
        << std::setprecision(6) << time << "  active-set iterations "
        << std::setw(2) << iterations << "  unilateral " << std::setw(4)
        << contact_states[0] << "  compliance " << std::setw(4)
        << contact_states[1] << "  no contact " << std::setw(4)
        << contact_states[2] << "  contact force " << std::setprecision(8)
        << total_contact_force << std::endl;
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
