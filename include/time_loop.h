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

  // @sect3{Adaptive time steps}
  //
  // The step-size controller of Time step control = adaptive
  // (doc/adaptivity.md) as pure functions of numbers every rank has alike, so
  // that every rank takes the same decision without communication.

  // The controller's constants: the relative Error tolerance, the range of
  // steps (Minimum time step; Maximum time step, for the explicit update
  // also 0.9 times its stability limit), and the usual safety factor and
  // bounds of one change of the step.
  struct TimeStepController
  {
    double tolerance;
    double minimum_step;
    double maximum_step;
    double safety     = 0.9;
    double max_growth = 2.;
    double max_shrink = 0.2;
  };

  // What the controller makes of a step of length step with the relative
  // error estimate error: accepted or rejected, and the step it proposes
  // (the next one after an accepted step, the repetition after a rejected
  // one), in [minimum_step, maximum_step], before it is fitted to the
  // targets (next_time_level()).
  struct TimeStepDecision
  {
    bool   accepted;
    double step;
  };

  // The elementary controller for a method of order p = 1 (the estimate is
  // O(k^2)): step * min(max_growth, max(max_shrink, safety (tol/error)^(1/2))).
  // desired_step is the step the controller proposed for this step before it
  // was shortened to land on a target: the growth is bounded relative to it,
  // so that landing on a target does not cost the steps after it their
  // length. A step above the tolerance is rejected unless it is already the
  // minimum step.
  TimeStepDecision
  control_time_step(const TimeStepController &controller,
                    const double              step,
                    const double              error,
                    const double              desired_step);

  // The next time level after time for a proposed step: the first target
  // after time (targets sorted, the last one End time) is reached exactly
  // if the step reaches it, and approached in two equal steps if the step
  // would leave less than one step before it, so that no step is tiny.
  double
  next_time_level(const double               time,
                  const double               step,
                  const std::vector<double> &targets);

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
