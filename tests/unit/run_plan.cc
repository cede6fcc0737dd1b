// Unit tests of the plan of a run (run/run_plan.h): the choices of the
// nested iteration as set and as auto makes them, with their reasons; the
// back end as set and as auto chooses it for a mesh; the bound on the steps.

#include <deal.II/base/mpi.h>

#include <gtest/gtest.h>

#include "parameters.h"
#include "run/run_plan.h"
#include "test_scenes.h"

#include <string>

using namespace dealii;
using namespace ViscoContact;

using TestScenes::parse_parameters;



// Set by hand, the cycles are what the parameter file says, without a
// reason; Method set by hand is the back end of every mesh.
TEST(RunPlan, ChoicesSetByHand)
{
  const Parameters::AllParameters parameters
    = parse_parameters("subsection Geometry\n"
                       "  set Cell type    = hypercube\n"
                       "  set Subdivisions = 16\n"
                       "end\n"
                       "subsection Mesh adaptation\n"
                       "  set Initial cycles = 2\n"
                       "  set Step cycles    = 1\n"
                       "end\n"
                       "subsection Linear solver\n"
                       "  set Method = full space\n"
                       "end\n");
  RunPlan<2> plan(parameters, MPI_COMM_SELF, false);
  plan.choose_initial_cycles();
  plan.choose_step_cycles(false);
  EXPECT_EQ(plan.initial_cycles(), 2u);
  EXPECT_EQ(plan.step_cycles(), 1u);
  EXPECT_EQ(plan.initial_cycles_reason(), "");
  EXPECT_EQ(plan.step_cycles_reason(), "");
  plan.choose_back_end(578, 17, 1, 64, false, 0);
  EXPECT_EQ(plan.back_end().method, Parameters::Method::full_space);
  EXPECT_FALSE(plan.step_cycles_dropped());
}

// auto on the benchmark's small mesh: no cycles, each with its reason; the
// condensed back end for the mesh.
TEST(RunPlan, AutoOnASmallMesh)
{
  const Parameters::AllParameters parameters = parse_parameters("");
  RunPlan<2>                      plan(parameters, MPI_COMM_SELF, false);
  plan.check_memory();
  plan.choose_initial_cycles();
  plan.choose_step_cycles(true);
  EXPECT_EQ(plan.initial_cycles(), 0u);
  EXPECT_EQ(plan.step_cycles(), 0u);
  EXPECT_NE(plan.initial_cycles_reason().find("condensed back end"),
            std::string::npos)
    << plan.initial_cycles_reason();
  EXPECT_NE(plan.step_cycles_reason().find("on simplices"), std::string::npos)
    << plan.step_cycles_reason();
  plan.choose_back_end(2178, 33, 1, 64, false, 0);
  EXPECT_EQ(plan.back_end().method, Parameters::Method::condensed);
  EXPECT_FALSE(plan.back_end().reason.empty());
}

// Step cycles are not for friction, nor for the implicit update.
TEST(RunPlan, StepCyclesReasons)
{
  RunPlan<2> friction(parse_parameters("subsection Geometry\n"
                                       "  set Cell type = hypercube\n"
                                       "end\n"
                                       "subsection Contact\n"
                                       "  set Tangential law       = Coulomb\n"
                                       "  set Friction coefficient = 0.3\n"
                                       "end\n"),
                      MPI_COMM_SELF,
                      false);
  friction.choose_step_cycles(false);
  EXPECT_EQ(friction.step_cycles(), 0u);
  EXPECT_EQ(friction.step_cycles_reason(),
            "friction: on the frictional cube they saved no active-set "
            "iteration; set Step cycles to run them");
}

// A step beyond Maximum number of steps stops the run, naming the entry.
TEST(RunPlan, StepCount)
{
  const Parameters::AllParameters parameters
    = parse_parameters("subsection Time\n"
                       "  set Maximum number of steps = 64\n"
                       "end\n");
  const RunPlan<2> plan(parameters, MPI_COMM_SELF, false);
  EXPECT_NO_THROW(plan.check_step_count(64, 0.98));
  try
    {
      plan.check_step_count(65, 0.99);
      FAIL() << "step 65 of at most 64 was accepted";
    }
  catch (const ExceptionBase &exc)
    {
      std::ostringstream message;
      exc.print_info(message);
      EXPECT_NE(message.str().find("<Maximum number of steps>"),
                std::string::npos)
        << message.str();
    }
}
