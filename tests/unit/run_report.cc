// Unit tests of the report of a run (run/run_report.h): the counts and
// their restoration around an initial cycle, the checkpoint's copy of the
// counts and times, the progress of a step line, and durations.

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/mpi.h>

#include <gtest/gtest.h>

#include "parameters.h"
#include "robustness/checkpoint_file.h"
#include "run/run_report.h"
#include "step_report.h"

#include <limits>
#include <regex>
#include <sstream>
#include <string>

using namespace dealii;
using namespace ViscoContact;

TEST(RunReport, CountsAndTheirRestoration)
{
  const Parameters::AllParameters parameters;
  std::ostringstream              out;
  ConditionalOStream              pcout(out, true);
  RunReport report(parameters, MPI_COMM_SELF, pcout, false);
  report.count_active_set_iterations(5);
  report.count_newton_iteration();
  report.count_inner_iterations(40);
  const auto before = report.step_counts();
  EXPECT_EQ(before, (std::array<unsigned int, 3>{{5, 1, 40}}));
  // An initial cycle's solve counts apart, and the steps' counts are
  // restored after it.
  report.count_active_set_iterations(7);
  report.count_inner_iterations(3);
  report.count_initial_cycle(7);
  report.restore_step_counts(before);
  EXPECT_EQ(report.step_counts(), before);
  EXPECT_EQ(report.n_initial_cycles(), 1u);
  report.count_step_cycle_iterations(4);
  report.count_step_cycle_iterations(2);
  EXPECT_EQ(report.step_cycle_iterations(), 6u);
  EXPECT_EQ(report.n_external_load_assemblies(), 0u);
  report.count_external_load_assembly();
  EXPECT_EQ(report.n_external_load_assemblies(), 1u);
}

// What a checkpoint stores comes back in a resumed run's report: the
// counts, and the wall time of the run as the start of the resumed one's.
TEST(RunReport, CheckpointCopy)
{
  const Parameters::AllParameters parameters;
  std::ostringstream              out;
  ConditionalOStream              pcout(out, true);
  RunReport written(parameters, MPI_COMM_SELF, pcout, false);
  written.count_active_set_iterations(12);
  written.count_newton_iteration();
  written.count_inner_iterations(99);
  written.add_compute_time(3.5);
  ByteWriter writer;
  written.save(writer, 1000.);

  RunReport  resumed(parameters, MPI_COMM_SELF, pcout, false);
  ByteReader reader(writer.bytes, "checkpoint");
  resumed.load(reader);
  EXPECT_EQ(resumed.step_counts(), written.step_counts());
  EXPECT_GE(resumed.wall_time(), 1000.);
  resumed.start_time_loop(7, 0.5);
  EXPECT_GE(resumed.wall_time(), 1000.);
  EXPECT_LT(resumed.wall_time(), 1100.);
}

// The step lines' progress: step n of N with fixed steps, t of T with
// adaptive ones; the time left only from the second step of the process
// on and not after the last.
TEST(RunReport, ProgressOfTheStepLines)
{
  const RunProgress progress(4, 0.5, 5.);
  EXPECT_TRUE(
    std::regex_match(progress.text(5, 16, 0.6, 1),
                     std::regex("\\[step 5 of 16, 5\\.[0-9]{2} s\\]")))
    << progress.text(5, 16, 0.6, 1);
  EXPECT_TRUE(std::regex_match(progress.text(6, 16, 0.7, 1),
                               std::regex("\\[step 6 of 16, 5\\.[0-9]{2} s, "
                                          "about [0-9.]+ s left\\]")))
    << progress.text(6, 16, 0.7, 1);
  EXPECT_TRUE(std::regex_match(progress.text(16, 16, 1, 1),
                               std::regex("\\[step 16 of 16, [0-9.]+ s\\]")))
    << progress.text(16, 16, 1, 1);
  EXPECT_TRUE(std::regex_match(progress.text(6, 0, 0.75, 1),
                               std::regex("\\[t 0\\.75 of 1, [0-9.]+ s, about "
                                          "[0-9.]+ s left\\]")))
    << progress.text(6, 0, 0.75, 1);
}

TEST(RunReport, Durations)
{
  EXPECT_EQ(format_duration(0.414), "0.41 s");
  EXPECT_EQ(format_duration(9.994), "9.99 s");
  EXPECT_EQ(format_duration(12.4), "12 s");
  EXPECT_EQ(format_duration(185), "3 min 05 s");
  EXPECT_EQ(format_duration(7620), "2 h 07 min");
  EXPECT_EQ(format_duration(std::numeric_limits<double>::infinity()), "?");
}
