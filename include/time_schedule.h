#ifndef viscoplastic_contact_time_schedule_h
#define viscoplastic_contact_time_schedule_h

#include <cstdint>
#include <vector>

namespace ViscoContact
{
  class ByteReader;
  class ByteWriter;

  // @sect3{The time schedule}
  //
  // The time levels 0 = t_0 < t_1 < ... of a run, in the image of deal.II's
  // DiscreteTime: current_time() is the time the solution is known at (t_{n-1}
  // while step n is solved), next_time() the end of the step being solved,
  // advance_time() moves on once it is accepted. Two things DiscreteTime does
  // not do are why the program has its own class: a step can be cut (a failed
  // solve halves it, and the rest of it becomes the next step) and the
  // schedule is saved and restored with a checkpoint. Its last fixed step is
  // shortened to end at End time, never stretched, and step counts are 64-bit.
  //
  // Fixed steps: t_m = m k on a grid of N = ceil(T/k) steps with t_N = T;
  // levels inserted by cut steps lie between the current time and the next
  // grid level. Adaptive steps: the next level is proposed by the step
  // controller (control_time_step()) and fitted to the landing targets
  // (Profile times, End time) by next_time_level().
  //
  // Every rank holds the same schedule and takes the same decisions with it,
  // without communication.
  class TimeSchedule
  {
  public:
    TimeSchedule() = default;

    // Fixed steps of length time_step to end_time.
    static TimeSchedule
    fixed_steps(const double end_time, const double time_step);
    // Adaptive steps to the last of targets (sorted; the last is End time),
    // the first step proposed as first_step; grid_step is the step of the
    // grid at which the loads are checked before the run (grid_level()).
    static TimeSchedule
    adaptive_steps(const std::vector<double> &targets,
                   const double               first_step,
                   const double               grid_step);

    bool
    is_adaptive() const;
    // Whether the run has reached its end: no step is left.
    bool
    is_at_end() const;
    // Steps accepted so far; the step being solved is step_number() + 1.
    std::uint64_t
    step_number() const;
    // The number of steps of the run as far as it is known: with fixed steps
    // those taken and those planned, with adaptive steps those taken.
    std::uint64_t
    n_steps() const;

    // t_{n-1}, t_n and t_{n-2} while step n is solved; after advance_time()
    // the same names refer to step n + 1. previous_time() is 0 at the start.
    double
    current_time() const;
    double
    next_time() const;
    double
    previous_time() const;
    // t_n - t_{n-1}, and t_{n-1} - t_{n-2} (0 at the start).
    double
    step_length() const;
    double
    previous_step_length() const;
    // t_{n+1} - t_n where it is known before step n is accepted (fixed
    // steps; 0 after the last step and with adaptive steps).
    double
    following_step_length() const;
    // The end time of the run.
    double
    end_time() const;
    // The grid of the run's Time step k: the levels t_m = m k, m < N, and
    // t_N = T, m = 0, ..., N (n_grid_levels() = N + 1), and k. Fixed steps
    // are its levels (and those cuts insert); with adaptive steps it is
    // the sample of times at which the loads are checked before the run.
    std::uint64_t
    n_grid_levels() const;
    double
    grid_level(const std::uint64_t m) const;
    double
    grid_step_length() const;

    // Halve the step being solved: t_{n-1} + k/2 becomes the new t_n, the old
    // t_n the level after it (with fixed steps; with adaptive steps the
    // controller decides the next level anew).
    void
    cut_step();
    // The step being solved was accepted: move to the next one. With adaptive
    // steps the controller proposes the step after it (kept as
    // proposed_step()), and the next level is that step fitted to the targets.
    void
    advance_time(const double proposed_step = 0);
    // With adaptive steps, a rejected step: it is repeated from the current
    // time with the shorter step the controller proposes, fitted to the
    // targets.
    void
    reject_step(const double proposed_step);
    // The controller's state: the step it proposed last, before it was
    // fitted to a target, and the steps it rejected.
    double
    proposed_step() const;
    std::uint64_t
    n_rejected_steps() const;

    // For a resumed run, whose End time (and Profile times) may differ from
    // the interrupted run's: the levels up to current_time() stay those of
    // the interrupted run, the next ones are those of a run to the new end
    // (fixed steps: the grid of its step, only if End time changed;
    // adaptive steps: the proposed step fitted to the new targets).
    void
    continue_to(const std::vector<double> &targets);

    // Whether current_time() is the level of the whole schedule closest to
    // time (the first one, if two are equally close): the step whose contact
    // profile is written for a requested time.
    bool
    current_time_is_closest_to(const double time) const;

    // The checkpoint's copy of the schedule.
    void
    save(ByteWriter &writer) const;
    void
    load(ByteReader &reader);

  private:
    // The level after next_time() of the current plan (fixed steps), or a
    // negative number after the last one.
    double
    level_after_next() const;

    bool          adaptive        = false;
    bool          at_end          = false;
    double        final_time      = 0;
    double        grid_step       = 0;
    std::uint64_t n_grid_steps    = 0;
    std::uint64_t next_grid_level = 0;
    std::uint64_t steps_taken     = 0;
    double        previous        = 0;
    double        current         = 0;
    double        next            = 0;
    // Levels inserted by cut steps after next_time(), the nearest last.
    std::vector<double> inserted_levels;
    // Adaptive steps: the landing targets and the controller's state.
    std::vector<double> targets;
    double              desired_step = 0;
    std::uint64_t       n_rejected   = 0;
  };

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

  // The controller of Time step control = adaptive with its tolerance and
  // range of steps: with the explicit update (a finite stability_limit,
  // 4 lambda / lambda_max(E)) the steps stay below 0.9 times the limit:
  // beyond it the error estimate would not see the instability before the
  // stresses oscillate, and the margin keeps the steps off the limit, where
  // the damping of forward Euler vanishes. (If the minimum is above that,
  // the minimum wins; the header warns.)
  TimeStepController
  make_time_step_controller(const double tolerance,
                            const double minimum_step,
                            const double maximum_step,
                            const double stability_limit);

  // The times adaptive steps land on exactly: the profile times inside
  // (0, end_time) (their profiles are then written at the requested time,
  // not at the closest step), sorted, and end_time.
  std::vector<double>
  landing_targets(const std::vector<double> &profile_times,
                  const double               end_time);

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

  // The number of steps ceil(T/k) of a fixed schedule, with a relative margin
  // of 1e-12 so that a T that is a multiple of k up to rounding does not get a
  // spurious last step of length almost zero; in floating point (for the
  // checks of the parameters, before the count is known to fit a counter)
  // and as the counter.
  double
  fixed_step_count(const double end_time, const double time_step);
  std::uint64_t
  n_fixed_steps(const double end_time, const double time_step);
} // namespace ViscoContact

#endif
