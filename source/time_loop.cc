// Pieces of the time loop: the schedule, the line per step, cutting a
// failed step, and the report of a step that failed.

#include <deal.II/base/exceptions.h>

#include "time_loop.h"

#include <cmath>
#include <iomanip>
#include <sstream>

namespace ViscoContact
{
  std::vector<double>
  time_levels(const double end_time, const double time_step)
  {
    const unsigned int N = static_cast<unsigned int>(
      std::ceil(end_time / time_step * (1 - 1e-12)));
    std::vector<double> times(N + 1);
    for (unsigned int n = 0; n < N; ++n)
      times[n] = n * time_step;
    times[N] = end_time;
    return times;
  }



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
        << total_contact_force << '\n';
  }



  bool
  cut_failed_step(const Parameters::AllParameters &parameters,
                  ConditionalOStream              &out,
                  const unsigned int               step,
                  std::vector<double>             &times,
                  const std::string               &failure)
  {
    const double k = times[step] - times[step - 1];
    if (parameters.on_failure != Parameters::FailurePolicy::cut_time_step
        || k / 2 < parameters.minimum_time_step)
      return false;
    out << "Step " << step << " (t = " << times[step] << ", k = " << k
        << ") failed: " << failure
        << "\n  Cutting the time step to k = " << k / 2 << ".\n";
    times.insert(times.begin() + step, times[step - 1] + k / 2);
    return true;
  }



  std::string
  failed_state_file(const unsigned int step, const std::string &extension)
  {
    std::ostringstream name;
    name << "failed_step_" << std::setw(4) << std::setfill('0') << step << '.'
         << extension;
    return name.str();
  }



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
    if (parameters.on_failure == Parameters::FailurePolicy::cut_time_step)
      message << "Cutting the step further would go below <Minimum time "
                 "step> = "
              << parameters.minimum_time_step << " in subsection <Time>.\n";
    else
      message << "<On solver failure> = cut time step in subsection <Time> "
                 "retries failing steps with smaller time steps.\n";
    message << "If the contact law softens more than the body can carry "
               "(doc/model.md, section 4) the step problem may have several "
               "solutions or none.";
    return message.str();
  }
} // namespace ViscoContact
