// The report of a run (run/run_report.h): counts, timers, progress, peak
// memory, the summary and the cost measurement's report.

#include <deal.II/base/multithread_info.h>
#include <deal.II/base/utilities.h>

#include "robustness/checkpoint_file.h"
#include "run/run_report.h"

#include <algorithm>
#include <iomanip>
#include <sstream>

namespace ViscoContact
{
  RunReport::RunReport(const Parameters::AllParameters &parameters,
                       const MPI_Comm                   communicator,
                       ConditionalOStream              &pcout,
                       const bool                       mesh_group_root)
    : parameters(parameters)
    , communicator(communicator)
    , pcout(pcout)
    , mesh_group_root(mesh_group_root)
    , computing_timer(communicator,
                      pcout,
                      TimerOutput::never,
                      TimerOutput::wall_times)
  {}



  TimerOutput &
  RunReport::timer()
  {
    return computing_timer;
  }



  // @sect4{Counts}
  void
  RunReport::count_operator_assembly()
  {
    ++operator_assemblies;
  }



  void
  RunReport::count_external_load_assembly()
  {
    ++external_load_assemblies;
  }



  unsigned int
  RunReport::n_external_load_assemblies() const
  {
    return external_load_assemblies;
  }



  void
  RunReport::count_newton_iteration()
  {
    ++newton_iterations;
  }



  void
  RunReport::count_active_set_iterations(const unsigned int iterations)
  {
    active_set_iterations += iterations;
  }



  void
  RunReport::count_inner_iterations(const unsigned int iterations)
  {
    inner_iterations += iterations;
  }



  std::array<unsigned int, 3>
  RunReport::step_counts() const
  {
    return {{active_set_iterations, newton_iterations, inner_iterations}};
  }



  void
  RunReport::restore_step_counts(const std::array<unsigned int, 3> &counts)
  {
    active_set_iterations = counts[0];
    newton_iterations     = counts[1];
    inner_iterations      = counts[2];
  }



  void
  RunReport::count_initial_cycle(const unsigned int iterations)
  {
    initial_cycle_iterations += iterations;
    ++initial_cycles;
  }



  unsigned int
  RunReport::n_initial_cycles() const
  {
    return initial_cycles;
  }



  void
  RunReport::count_step_cycle_iterations(const unsigned int iterations)
  {
    step_cycles_iterations += iterations;
  }



  unsigned int
  RunReport::step_cycle_iterations() const
  {
    return step_cycles_iterations;
  }



  // @sect4{The time loop}
  void
  RunReport::start_time_loop(const unsigned int step, const double time)
  {
    loop_progress.emplace(step, time, earlier_wall_time);
  }



  double
  RunReport::wall_time() const
  {
    return loop_progress ? loop_progress->wall_time() : earlier_wall_time;
  }



  void
  RunReport::add_compute_time(const double seconds)
  {
    compute_time += seconds;
  }



  std::string
  RunReport::progress(const unsigned int step,
                      const unsigned int n_steps,
                      const double       time,
                      const double       end_time) const
  {
    return loop_progress ? loop_progress->text(step, n_steps, time, end_time)
                         : "";
  }



  // @sect4{Memory}
  bool
  RunReport::reports_set_up_memory() const
  {
    return parameters.print_timing_summary && !set_up_reported;
  }



  void
  RunReport::set_up_done()
  {
    set_up_reported = true;
  }



  // The high-water mark of each rank's resident memory up to now (VmHWM):
  // the sum over the ranks, the largest rank, and on simplex meshes the
  // largest group root (which held the whole mesh during set-up, mesh.cc)
  // and the largest other rank apart. Measured now (collective), printed
  // with the run summary, so that the start of a run shows the scene and
  // its steps.
  void
  RunReport::record_peak_memory(const std::string &when)
  {
    Utilities::System::MemoryStats memory;
    Utilities::System::get_memory_stats(memory);
    const double peak = memory.VmHWM / 1024.;
    // A stream of its own: the console keeps its precision.
    std::ostringstream line;
    line << std::setprecision(5) << "  peak memory " << when
         << " [MB]: sum over ranks " << Utilities::MPI::sum(peak, communicator)
         << ", largest rank " << Utilities::MPI::max(peak, communicator);
    if (parameters.cell_type != Parameters::CellType::hypercube)
      {
        const double root_peak
          = Utilities::MPI::max(mesh_group_root ? peak : 0., communicator);
        const double member_peak
          = Utilities::MPI::max(mesh_group_root ? 0. : peak, communicator);
        line << ", largest group root " << root_peak << ", largest member ";
        if (member_peak > 0)
          line << member_peak;
        else
          line << "none";
      }
    peak_memory_lines.push_back(line.str());
  }



  // @sect4{RunReport::print_summary}
  //
  // What a user checks after a run: norms of the final state, iteration
  // counts, how often the operator was assembled and set up by the back end
  // (once and once for the explicit update), and with the timing summary
  // the peak memory.
  void
  RunReport::print_summary(const FinalState &state) const
  {
    pcout << std::setprecision(8) << "\nRun summary\n"
          << "  final state: ||eps(u)||_L2 = " << state.strain_norm
          << ", ||sigma||_L2 = " << state.stress_norm
          << ", max von Mises = " << state.max_von_mises << '\n'
          << "  final contact: " << state.contact_states[0] << " unilateral, "
          << state.contact_states[1] << " compliance, "
          << state.contact_states[2]
          << " no contact, total force = " << state.contact_force << '\n';
    if (state.implicit_update)
      pcout << "  Newton iterations (implicit scheme): " << newton_iterations
            << '\n';
    pcout << "  active-set iterations: " << active_set_iterations << " in "
          << state.steps << " steps\n";
    // The solves of step 1 on the coarser meshes of the initial cycles (not
    // in the count above, which is that of the recorded steps).
    if (initial_cycles > 0)
      pcout << "  initial cycles: " << initial_cycle_iterations
            << " active-set iterations on " << initial_cycles
            << " coarser meshes\n";
    // The solves of the steps on the coarser meshes of the Step cycles.
    if (state.step_cycles_dropped)
      pcout << "  step cycles: none (Method = auto chose the condensed back "
               "end for the mesh of the run)\n";
    else if (state.n_step_cycles > 0)
      pcout << "  step cycles: " << step_cycles_iterations
            << " active-set iterations on " << state.n_step_cycles
            << " coarser mesh" << (state.n_step_cycles > 1 ? "es" : "") << '\n';
    if (parameters.time_step_control == Parameters::TimeStepControl::adaptive)
      pcout << "  adaptive time steps: " << state.steps << " accepted, "
            << state.rejected_steps << " rejected\n";
    pcout << "  operator: assembled " << operator_assemblies
          << "x, set up by the back end " << state.operator_setups
          << "x; external load assembled " << external_load_assemblies << "x\n"
          << "  back end: " << state.solves << " solves, "
          << state.krylov_iterations << " Krylov iterations\n"
          << "Final displacement: l2 norm " << state.l2_norm << ", max norm "
          << state.max_norm << '\n';
    if (parameters.print_timing_summary)
      {
        for (const std::string &line : peak_memory_lines)
          pcout << line << '\n';
        pcout << std::flush;
      }
  }



  // @sect4{RunReport::print_cost_measurement}
  //
  // The average step of this run (solve and
  // stress update, without output; the maximum over the ranks, as the
  // slowest rank sets the pace) against the reference costs.
  void
  RunReport::print_timer_summary()
  {
    computing_timer.print_summary();
  }



  void
  RunReport::print_cost_measurement(const CostMeasurement &cost) const
  {
    const double step_time = Utilities::MPI::max(compute_time, communicator)
                             / std::max<double>(1, cost.steps);
    pcout
      << std::setprecision(4)
      << "Cost measurement (wall time, maximum over the ranks):\n"
      << "  threads per rank: " << MultithreadInfo::n_threads()
      << " (BLAS in the sparse factorisation: " << cost.factorisation_threads
      << ")\n"
      << "  average time step (without output): " << step_time * 1e3 << " ms\n"
      << "  one solve with the step operator, no contact: "
      << cost.solve_time * 1e3 << " ms (" << cost.krylov_iterations
      << " Krylov iterations)"
      << (cost.holding_load ? " on the load K u of the final displacement" : "")
      << "\n"
      << "  one operator application: " << cost.operator_time * 1e3 << " ms\n"
      << "  one stress update with the history load: " << cost.update_time * 1e3
      << " ms\n"
      << "  ratio step / solve: " << step_time / cost.solve_time << '\n'
      << "  ratio step / (solve + stress update): "
      << step_time / (cost.solve_time + cost.update_time) << '\n'
      << "  per dof and step: " << step_time / cost.n_dofs * 1e6 << " us\n"
      << "  time loop (without output): " << compute_time << " s\n";
  }



  // @sect4{Checkpoints}
  void
  RunReport::save(ByteWriter &writer, const double wall_time) const
  {
    writer.write(wall_time);
    writer.write(compute_time);
    writer.write<std::uint32_t>(active_set_iterations);
    writer.write<std::uint32_t>(newton_iterations);
    writer.write<std::uint32_t>(inner_iterations);
  }



  void
  RunReport::load(ByteReader &reader)
  {
    earlier_wall_time     = reader.read<double>();
    compute_time          = reader.read<double>();
    active_set_iterations = reader.read<std::uint32_t>();
    newton_iterations     = reader.read<std::uint32_t>();
    inner_iterations      = reader.read<std::uint32_t>();
  }
} // namespace ViscoContact
