#ifndef viscoplastic_contact_run_report_h
#define viscoplastic_contact_run_report_h

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/timer.h>

#include "contact_nodes.h"
#include "parameters.h"
#include "step_report.h"

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace ViscoContact
{
  class ByteReader;
  class ByteWriter;

  // @sect3{The report of a run}
  //
  // What a run tells about itself beside its results: the work it did (the
  // assemblies of the operator and of the external load; the active-set,
  // Krylov and Newton iterations of its steps, and those on the coarser
  // meshes of the initial and the step cycles), the wall times of its phases
  // (deal.II's TimerOutput) and of the time loop, the progress of the steps,
  // the peak memory after each phase of the first set-up, and the summary at
  // the end with the cost measurement. It observes the time loop and never
  // computes anything of the physics: what the summary says of the state
  // and what the cost measurement timed are handed to it.
  //
  // The counts and times of the steps belong to the run, not to the process:
  // a checkpoint stores them (save(), load()), and a resumed run continues
  // them.
  class RunReport
  {
  public:
    // mesh_group_root: whether this rank built the whole mesh of its group
    // (simplex meshes), for the peak memory of the group roots.
    RunReport(const Parameters::AllParameters &parameters,
              const MPI_Comm                   communicator,
              ConditionalOStream              &pcout,
              const bool                       mesh_group_root);

    // The timer of the phases (TimerOutput::Scope).
    TimerOutput &
    timer();

    // @sect4{Counts}
    void
    count_operator_assembly();
    void
    count_external_load_assembly();
    unsigned int
    n_external_load_assemblies() const;
    void
    count_newton_iteration();
    void
    count_active_set_iterations(const unsigned int iterations);
    void
    count_inner_iterations(const unsigned int iterations);
    // The counts of the recorded steps (active-set, Newton, Krylov), which a
    // solve outside them (an initial cycle) restores.
    std::array<unsigned int, 3>
    step_counts() const;
    void
    restore_step_counts(const std::array<unsigned int, 3> &counts);
    // The solves of step 1 on the coarser meshes of the initial cycles, and
    // the active-set iterations of the steps on the coarser meshes of the
    // step cycles.
    void
    count_initial_cycle(const unsigned int iterations);
    unsigned int
    n_initial_cycles() const;
    void
    count_step_cycle_iterations(const unsigned int iterations);
    unsigned int
    step_cycle_iterations() const;

    // @sect4{The time loop}
    //
    // start_time_loop() before the first step of this process (step and
    // time: where it starts); wall_time() is that of the run, a resumed run
    // included; add_compute_time() the time of a step without its output.
    void
    start_time_loop(const unsigned int step, const double time);
    double
    wall_time() const;
    void
    add_compute_time(const double seconds);
    // The progress of the run for a step line (RunProgress::text()).
    std::string
    progress(const unsigned int step,
             const unsigned int n_steps,
             const double       time,
             const double       end_time) const;

    // @sect4{Memory}
    //
    // Collective: the peak memory of the ranks after a phase of the first
    // set-up (set_up_done() ends it; later set-ups, on adapted meshes, are
    // not reported) or over the run, printed with the summary.
    bool
    reports_set_up_memory() const;
    void
    set_up_done();
    void
    record_peak_memory(const std::string &when);

    // @sect4{The summary}
    //
    // The state at the end and what the back end did, as the class hands
    // them over; the counts are the report's own.
    struct FinalState
    {
      bool                        implicit_update;
      double                      strain_norm;
      double                      stress_norm;
      double                      max_von_mises;
      std::array<unsigned int, 3> contact_states;
      double                      contact_force;
      double                      l2_norm;
      double                      max_norm;
      std::uint64_t               steps;
      std::uint64_t               rejected_steps;
      unsigned int                n_step_cycles;
      bool                        step_cycles_dropped;
      unsigned int                operator_setups;
      unsigned int                solves;
      unsigned int                krylov_iterations;
    };
    void
    print_summary(const FinalState &state) const;

    // The reference costs a step is compared with, measured by the class
    // after the run (with Measure cost ratios): one solve with the step
    // operator and no contact, one stress update with the history load.
    struct CostMeasurement
    {
      std::uint64_t steps;
      double        solve_time;
      unsigned int  krylov_iterations;
      double        operator_time; // one product with the operator
      bool          holding_load;
      double        update_time;
      unsigned int  factorisation_threads;
      double        n_dofs;
    };
    // deal.II's timer summary (before the cost measurement, whose solves
    // and stress updates are not the run's), then the costs (collective).
    void
    print_timer_summary();
    void
    print_cost_measurement(const CostMeasurement &cost) const;

    // @sect4{Checkpoints}
    //
    // The run's wall time up to the checkpoint (given: the step's), compute
    // time and counts.
    void
    save(ByteWriter &writer, const double wall_time) const;
    void
    load(ByteReader &reader);

  private:
    const Parameters::AllParameters parameters;
    MPI_Comm                        communicator;
    ConditionalOStream             &pcout;
    const bool                      mesh_group_root;
    TimerOutput                     computing_timer;
    bool                            set_up_reported = false;
    std::vector<std::string>        peak_memory_lines;
    unsigned int                    operator_assemblies      = 0;
    unsigned int                    external_load_assemblies = 0;
    unsigned int                    newton_iterations        = 0;
    unsigned int                    active_set_iterations    = 0;
    unsigned int                    inner_iterations         = 0;
    unsigned int                    initial_cycle_iterations = 0;
    unsigned int                    initial_cycles           = 0;
    unsigned int                    step_cycles_iterations   = 0;
    double                          compute_time             = 0;
    double                          earlier_wall_time        = 0;
    std::optional<RunProgress>      loop_progress;
  };
} // namespace ViscoContact

#endif
