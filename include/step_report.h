#ifndef viscoplastic_contact_step_report_h
#define viscoplastic_contact_step_report_h

#include <deal.II/base/conditional_ostream.h>

#include "contact_nodes.h"
#include "parameters.h"

#include <array>
#include <string>

namespace ViscoContact
{
  using namespace dealii;

  // @sect3{The report of a time step}

  // The line a verbose run prints per step (the tests compare it).
  void
  print_step_line(ConditionalOStream                &out,
                  const unsigned int                 step,
                  const double                       time,
                  const unsigned int                 iterations,
                  const std::array<unsigned int, 3> &contact_states,
                  const double                       total_contact_force);

  // With adaptive steps the line has the step length and the error estimate
  // at the end.
  void
  print_adaptive_step_line(ConditionalOStream                &out,
                           const unsigned int                 step,
                           const double                       time,
                           const unsigned int                 iterations,
                           const std::array<unsigned int, 3> &contact_states,
                           const double total_contact_force,
                           const double time_step,
                           const double error_estimate);

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
