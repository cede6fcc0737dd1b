// The time schedule of a run (time_schedule.h): its levels, cut steps, the
// adaptive step controller, and its copy in a checkpoint.

#include <deal.II/base/exceptions.h>

#include "robustness/checkpoint_file.h"
#include "time_schedule.h"

#include <algorithm>
#include <cmath>

namespace ViscoContact
{
  using namespace dealii;

  // @sect4{fixed_step_count and n_fixed_steps}
  double
  fixed_step_count(const double end_time, const double time_step)
  {
    return std::ceil(end_time / time_step * (1 - 1e-12));
  }



  std::uint64_t
  n_fixed_steps(const double end_time, const double time_step)
  {
    return static_cast<std::uint64_t>(fixed_step_count(end_time, time_step));
  }



  // @sect4{TimeSchedule::fixed_steps}
  //
  // The grid t_m = m k, m < N, and t_N = T itself, not N k, which may differ
  // by rounding (or by a shortened last step).
  TimeSchedule
  TimeSchedule::fixed_steps(const double end_time, const double time_step)
  {
    TimeSchedule schedule;
    schedule.final_time      = end_time;
    schedule.grid_step       = time_step;
    schedule.n_grid_steps    = n_fixed_steps(end_time, time_step);
    schedule.next            = schedule.grid_level(1);
    schedule.next_grid_level = 2;
    return schedule;
  }



  // @sect4{TimeSchedule::adaptive_steps}
  TimeSchedule
  TimeSchedule::adaptive_steps(const std::vector<double> &targets,
                               const double               first_step,
                               const double               grid_step)
  {
    Assert(!targets.empty(), ExcInternalError());
    TimeSchedule schedule;
    schedule.adaptive     = true;
    schedule.final_time   = targets.back();
    schedule.grid_step    = grid_step;
    schedule.n_grid_steps = n_fixed_steps(schedule.final_time, grid_step);
    schedule.targets      = targets;
    schedule.desired_step = first_step;
    schedule.next         = next_time_level(0., first_step, targets);
    return schedule;
  }



  // @sect4{TimeSchedule: the levels}
  bool
  TimeSchedule::is_adaptive() const
  {
    return adaptive;
  }



  bool
  TimeSchedule::is_at_end() const
  {
    return at_end;
  }



  std::uint64_t
  TimeSchedule::step_number() const
  {
    return steps_taken;
  }



  // The levels still planned with fixed steps: the next one, those inserted
  // by cuts after it, and the rest of the grid.
  std::uint64_t
  TimeSchedule::n_steps() const
  {
    if (adaptive || at_end)
      return steps_taken;
    const std::uint64_t grid_left = next_grid_level <= n_grid_steps
                                      ? n_grid_steps - next_grid_level + 1
                                      : 0;
    return steps_taken + 1 + inserted_levels.size() + grid_left;
  }



  double
  TimeSchedule::current_time() const
  {
    return current;
  }



  double
  TimeSchedule::next_time() const
  {
    return next;
  }



  double
  TimeSchedule::previous_time() const
  {
    return previous;
  }



  double
  TimeSchedule::step_length() const
  {
    return at_end ? 0. : next - current;
  }



  double
  TimeSchedule::previous_step_length() const
  {
    return steps_taken > 0 ? current - previous : 0.;
  }



  double
  TimeSchedule::following_step_length() const
  {
    if (adaptive || at_end)
      return 0.;
    const double after_next = level_after_next();
    return after_next >= 0 ? after_next - next : 0.;
  }



  double
  TimeSchedule::end_time() const
  {
    return final_time;
  }



  double
  TimeSchedule::proposed_step() const
  {
    return desired_step;
  }



  std::uint64_t
  TimeSchedule::n_rejected_steps() const
  {
    return n_rejected;
  }



  std::uint64_t
  TimeSchedule::n_grid_levels() const
  {
    return n_grid_steps + 1;
  }



  double
  TimeSchedule::grid_step_length() const
  {
    return grid_step;
  }


  double
  TimeSchedule::grid_level(const std::uint64_t m) const
  {
    return m < n_grid_steps ? m * grid_step : final_time;
  }



  double
  TimeSchedule::level_after_next() const
  {
    if (!inserted_levels.empty())
      return inserted_levels.back();
    if (next_grid_level <= n_grid_steps)
      return grid_level(next_grid_level);
    return -1.;
  }



  // @sect4{TimeSchedule::cut_step}
  //
  // The old t_n stays in the schedule as the level after the new one (fixed
  // steps), so the run still reaches every level of the original schedule.
  // With adaptive steps the controller chooses the level after an accepted
  // step anew, so the old one is not kept.
  void
  TimeSchedule::cut_step()
  {
    const double k = next - current;
    if (!adaptive)
      inserted_levels.push_back(next);
    next = current + k / 2;
  }



  // @sect4{TimeSchedule::advance_time}
  void
  TimeSchedule::advance_time(const double proposed_step)
  {
    Assert(!at_end, ExcInternalError());
    previous = current;
    current  = next;
    ++steps_taken;
    if (adaptive)
      {
        desired_step = proposed_step;
        inserted_levels.clear();
        if (current < final_time * (1 - 1e-12))
          next = next_time_level(current, desired_step, targets);
        else
          at_end = true;
      }
    else if (!inserted_levels.empty())
      {
        next = inserted_levels.back();
        inserted_levels.pop_back();
      }
    else if (next_grid_level <= n_grid_steps)
      next = grid_level(next_grid_level++);
    else
      at_end = true;
  }



  // @sect4{TimeSchedule::reject_step}
  //
  // The shorter step ends before the level it replaces, which was at most a
  // target, so fitting it to the targets never passes one.
  void
  TimeSchedule::reject_step(const double proposed_step)
  {
    Assert(adaptive, ExcInternalError());
    desired_step = proposed_step;
    inserted_levels.clear();
    next = next_time_level(current, proposed_step, targets);
    ++n_rejected;
  }



  // @sect4{TimeSchedule::continue_to}
  void
  TimeSchedule::continue_to(const std::vector<double> &new_targets)
  {
    const double new_end = new_targets.back();
    if (!adaptive && new_end == final_time)
      return;
    final_time = new_end;
    inserted_levels.clear();
    at_end = false;
    if (adaptive)
      {
        targets = new_targets;
        if (current < final_time * (1 - 1e-12))
          next = next_time_level(current, desired_step, targets);
        else
          at_end = true;
        return;
      }
    // The first level of the new grid after the current time (the caller has
    // checked that there is one).
    n_grid_steps            = n_fixed_steps(final_time, grid_step);
    const double  threshold = current * (1 + 1e-12) + 1e-300;
    std::uint64_t m
      = std::min<std::uint64_t>(static_cast<std::uint64_t>(
                                  std::floor(current / grid_step)),
                                n_grid_steps);
    while (m > 0 && grid_level(m - 1) > threshold)
      --m;
    while (m <= n_grid_steps && grid_level(m) <= threshold)
      ++m;
    if (m > n_grid_steps)
      {
        at_end = true;
        return;
      }
    next            = grid_level(m);
    next_grid_level = m + 1;
  }



  // @sect4{TimeSchedule::current_time_is_closest_to}
  //
  // The distance of the levels to time decreases strictly up to time and
  // increases strictly after it, so the first level closest to time is the
  // one closer than the level before it and at least as close as the level
  // after it.
  bool
  TimeSchedule::current_time_is_closest_to(const double time) const
  {
    if (steps_taken == 0)
      return false;
    const double distance = std::abs(current - time);
    return distance < std::abs(previous - time)
           && (at_end || distance <= std::abs(next - time));
  }



  // @sect4{TimeSchedule::save and load}
  void
  TimeSchedule::save(ByteWriter &writer) const
  {
    writer.write<std::uint32_t>(adaptive);
    writer.write<std::uint32_t>(at_end);
    writer.write(final_time);
    writer.write(grid_step);
    writer.write(n_grid_steps);
    writer.write(next_grid_level);
    writer.write(steps_taken);
    writer.write(previous);
    writer.write(current);
    writer.write(next);
    writer.write_vector(inserted_levels);
    writer.write_vector(targets);
    writer.write(desired_step);
    writer.write(n_rejected);
  }



  void
  TimeSchedule::load(ByteReader &reader)
  {
    adaptive        = reader.read<std::uint32_t>() == 1;
    at_end          = reader.read<std::uint32_t>() == 1;
    final_time      = reader.read<double>();
    grid_step       = reader.read<double>();
    n_grid_steps    = reader.read<std::uint64_t>();
    next_grid_level = reader.read<std::uint64_t>();
    steps_taken     = reader.read<std::uint64_t>();
    previous        = reader.read<double>();
    current         = reader.read<double>();
    next            = reader.read<double>();
    inserted_levels = reader.read_vector<double>();
    targets         = reader.read_vector<double>();
    desired_step    = reader.read<double>();
    n_rejected      = reader.read<std::uint64_t>();
  }



  // @sect4{make_time_step_controller}
  TimeStepController
  make_time_step_controller(const double tolerance,
                            const double minimum_step,
                            const double maximum_step,
                            const double stability_limit)
  {
    TimeStepController controller;
    controller.tolerance    = tolerance;
    controller.minimum_step = minimum_step;
    controller.maximum_step
      = std::max(std::min(maximum_step, 0.9 * stability_limit), minimum_step);
    return controller;
  }



  // @sect4{landing_targets}
  std::vector<double>
  landing_targets(const std::vector<double> &profile_times,
                  const double               end_time)
  {
    std::vector<double> targets;
    for (const double t : profile_times)
      if (t > 0 && t < end_time)
        targets.push_back(t);
    std::sort(targets.begin(), targets.end());
    targets.push_back(end_time);
    return targets;
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
} // namespace ViscoContact
