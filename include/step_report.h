#ifndef viscoplastic_contact_step_report_h
#define viscoplastic_contact_step_report_h

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/timer.h>

#include "contact_nodes.h"
#include "parameters.h"

#include <array>
#include <string>

namespace ViscoContact
{
  using namespace dealii;

  // @sect3{The report of a time step}

  // The line a verbose run prints per step (the tests compare it), with the
  // progress of the run (RunProgress::text()) at its end.
  void
  print_step_line(ConditionalOStream                &out,
                  const unsigned int                 step,
                  const double                       time,
                  const unsigned int                 iterations,
                  const std::array<unsigned int, 3> &contact_states,
                  const double                       total_contact_force,
                  const std::string                 &progress);

  // With adaptive steps the line has the step length and the error estimate
  // at the end.
  void
  print_adaptive_step_line(ConditionalOStream                &out,
                           const unsigned int                 step,
                           const double                       time,
                           const unsigned int                 iterations,
                           const std::array<unsigned int, 3> &contact_states,
                           const double       total_contact_force,
                           const double       time_step,
                           const double       error_estimate,
                           const std::string &progress);

  // @sect3{The progress of a run}
  //
  // What the step lines say of the run as a whole: how far it is (step n of
  // N with fixed steps, t of T with adaptive ones), the wall time it has
  // taken, and an estimate of the time left from the rate of the steps this
  // process has taken so far (a resumed run counts from its first step).
  class RunProgress
  {
  public:
    // The time loop starts now, at step first_step and time start_time;
    // earlier_wall_time is that of the run a resumed run continues.
    RunProgress(const unsigned int first_step,
                const double       start_time,
                const double       earlier_wall_time);

    // The wall time of the run up to now.
    double
    wall_time() const;

    // "[step 3 of 16, 0.41 s, about 1.80 s left]" after step n (n_steps
    // steps in all), or with adaptive steps (n_steps = 0) "[t 0.25 of 1,
    // ...]"; the estimate is left out after the first step and at the end.
    std::string
    text(const unsigned int step,
         const unsigned int n_steps,
         const double       time,
         const double       end_time) const;

  private:
    unsigned int first_step;
    double       start_time;
    double       earlier_wall_time;
    Timer        timer;
  };

  // A duration for a person: "0.41 s", "1.80 s", "12 s", "3 min 05 s",
  // "2 h 07 min".
  std::string
  format_duration(const double seconds);

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
