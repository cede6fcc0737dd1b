#ifndef viscoplastic_contact_time_loop_h
#define viscoplastic_contact_time_loop_h

#include <deal.II/base/conditional_ostream.h>

#include "active_set.h"
#include "parameters.h"

#include <array>
#include <string>
#include <vector>

namespace ViscoContact
{
  using namespace dealii;

  // @sect3{Pieces of the time loop}

  // t_n = n k, with the last step shortened so that the run ends at T.
  std::vector<double>
  time_levels(const double end_time, const double time_step);

  // The line a verbose run prints per step (the tests compare it).
  void
  print_step_line(ConditionalOStream                &out,
                  const unsigned int                 step,
                  const double                       time,
                  const unsigned int                 iterations,
                  const std::array<unsigned int, 3> &contact_states,
                  const double                       total_contact_force);

  // After a failed solve of step n: with On solver failure = cut time step
  // and half the step not below Minimum time step, insert the level
  // t_{n-1} + k/2 into the schedule, say so, and return true; otherwise
  // return false (the run stops).
  bool
  cut_failed_step(const Parameters::AllParameters &parameters,
                  ConditionalOStream              &out,
                  const unsigned int               step,
                  std::vector<double>             &times,
                  const std::string               &failure);

  // failed_step_NNNN.<extension>: where the last accepted state of a run
  // stopped at step NNNN is written.
  std::string
  failed_state_file(const unsigned int step, const std::string &extension);

  // The report of a time step whose solve failed and that is not cut
  // (again): the step, its time and length, why it failed, the iteration
  // history, the contact state of the last iterate, where the last accepted
  // state was written, and what can be changed.
  std::string
  failure_report(const Parameters::AllParameters   &parameters,
                 const unsigned int                 step,
                 const double                       time,
                 const double                       time_step,
                 const ActiveSetResult             &result,
                 const std::array<unsigned int, 3> &contact_states,
                 const std::string                 &state_file);
} // namespace ViscoContact

#endif
