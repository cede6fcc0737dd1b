// Unit tests of the scene's builders from the parameters (loads.h,
// dirichlet_parts.h, contact_zones.h): what each builds from a parameter
// text, its values at points and times against the expressions evaluated
// by hand, and the message naming the entry of a value that is not finite.
// Exact comparisons: the expressions are evaluated by muparser in double
// precision from the same numbers.

#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>

#include <deal.II/distributed/tria.h>

#include <deal.II/dofs/dof_handler.h>

#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_system.h>

#include <deal.II/hp/fe_collection.h>

#include <deal.II/grid/grid_generator.h>

#include <deal.II/lac/vector.h>

#include <gtest/gtest.h>

#include "scene/contact_zones.h"
#include "scene/dirichlet_parts.h"
#include "scene/loads.h"
#include "parameters.h"
#include "test_scenes.h"

#include <string>

using namespace dealii;
using namespace ViscoContact;

using TestScenes::parse_parameters;



// The body force and the top's traction of the benchmark, and a pressure
// on the right side: values at a point and a time, the part of each
// boundary id, -p n along the given normal, and the time dependence.
TEST(Loads, BodyForceTractionAndPressure)
{
  const Parameters::AllParameters parameters
    = parse_parameters("subsection Boundary\n"
                       "  set Loaded boundary ids = 3\n"
                       "end\n"
                       "subsection Loads\n"
                       "  set Body force       = x; 2 * t\n"
                       "  set Surface traction = 0; -5\n"
                       "  subsection Surface load 1\n"
                       "    set Boundary ids = 1\n"
                       "    set Type         = pressure\n"
                       "    set Value        = 3 * y\n"
                       "  end\n"
                       "end\n",
                       0,
                       1);
  Loads<2> loads(parameters);
  EXPECT_TRUE(loads.depend_on_time());
  EXPECT_FALSE(loads.body_force_is_zero());
  EXPECT_EQ(loads.n_surface_parts(), 2u);
  EXPECT_EQ(loads.surface_part_of(3), 0u);
  EXPECT_EQ(loads.surface_part_of(1), 1u);
  EXPECT_EQ(loads.surface_part_of(2), numbers::invalid_unsigned_int);

  loads.set_time(0.25);
  EXPECT_EQ(loads.get_time(), 0.25);
  Vector<double> value(2);
  EXPECT_EQ(loads.body_force(Point<2>(0.5, 0.75), value), "");
  EXPECT_EQ(value(0), 0.5);
  EXPECT_EQ(value(1), 0.5);
  EXPECT_EQ(
    loads.surface_load(0, Point<2>(0.5, 1), Tensor<1, 2>({0, 1}), value),
    "");
  EXPECT_EQ(value(0), 0.);
  EXPECT_EQ(value(1), -5.);
  // A pressure of 3 y = 1.5 at y = 0.5 on the side with outward normal
  // (1, 0): the traction -p n.
  EXPECT_EQ(
    loads.surface_load(1, Point<2>(1, 0.5), Tensor<1, 2>({1, 0}), value),
    "");
  EXPECT_EQ(value(0), -1.5);
  EXPECT_EQ(value(1), 0.);
}

TEST(Loads, ZeroAndConstantLoads)
{
  const Parameters::AllParameters parameters
    = parse_parameters("subsection Boundary\n"
                       "  set Loaded boundary ids = 3\n"
                       "end\n"
                       "subsection Loads\n"
                       "  set Body force       = 0; 0\n"
                       "  set Surface traction = 0; -5\n"
                       "end\n");
  const Loads<2> loads(parameters);
  EXPECT_TRUE(loads.body_force_is_zero());
  EXPECT_FALSE(loads.depend_on_time());
}

// A value that is not finite: the message names the subsection, the entry,
// the expression, the point and the time.
TEST(Loads, NonFiniteValueNamesTheEntry)
{
  const Parameters::AllParameters parameters
    = parse_parameters("subsection Boundary\n"
                       "  set Loaded boundary ids = 3\n"
                       "end\n"
                       "subsection Loads\n"
                       "  set Body force       = 1 / x; 0\n"
                       "  set Surface traction = 0; -5\n"
                       "end\n");
  Loads<2> loads(parameters);
  loads.set_time(0.5);
  Vector<double>    value(2);
  const std::string message = loads.body_force(Point<2>(0, 0.25), value);
  EXPECT_NE(message.find("Invalid parameter <Body force> in subsection "
                         "<Loads>: value <1 / x; 0> is not finite at the "
                         "point (0, 0.25) at t = 0.5"),
            std::string::npos)
    << message;
}

// Clamped ids first (all components, no function), then a prescribed part
// with its components, its function and its name.
TEST(DirichletParts, ClampedThenPrescribed)
{
  const Parameters::AllParameters parameters
    = parse_parameters("subsection Boundary\n"
                       "  set Clamped boundary ids = 0\n"
                       "  set Loaded boundary ids  =\n"
                       "  subsection Prescribed displacement 1\n"
                       "    set Boundary ids = 3\n"
                       "    set Components   = y\n"
                       "    set Displacement = -0.01 * t * x\n"
                       "  end\n"
                       "end\n",
                       1);
  const DirichletParts<2> dirichlet(parameters);
  ASSERT_EQ(dirichlet.size(), 2u);
  EXPECT_EQ(dirichlet.name(0), "clamped");
  EXPECT_EQ(dirichlet.name(1), "prescribed_1");
  EXPECT_EQ(dirichlet.components(0), (std::vector<unsigned int>{0, 1}));
  EXPECT_EQ(dirichlet.components(1), (std::vector<unsigned int>{1}));
  EXPECT_EQ(dirichlet.parts()[0].boundary_ids,
            (std::vector<types::boundary_id>{0}));
  EXPECT_EQ(dirichlet.parts()[1].boundary_ids,
            (std::vector<types::boundary_id>{3}));
  EXPECT_FALSE(dirichlet.parts()[1].components[0]);
  EXPECT_TRUE(dirichlet.parts()[1].components[1]);
  EXPECT_FALSE(dirichlet.prescribes_function(0));
  EXPECT_TRUE(dirichlet.prescribes_function(1));
  EXPECT_TRUE(dirichlet.has_values());
  EXPECT_TRUE(dirichlet.depend_on_time());
  const auto [value, message] = dirichlet.value(1, 1, Point<2>(0.5, 1), 2.);
  EXPECT_EQ(value, -0.01 * 2. * 0.5);
  EXPECT_EQ(message, "");
}

TEST(DirichletParts, NonFiniteValueNamesTheEntry)
{
  const Parameters::AllParameters parameters
    = parse_parameters("subsection Boundary\n"
                       "  set Clamped boundary ids  =\n"
                       "  set Loaded boundary ids   =\n"
                       "  set Symmetry boundary ids = 0, 1\n"
                       "  subsection Prescribed displacement 1\n"
                       "    set Boundary ids = 3\n"
                       "    set Components   = y\n"
                       "    set Displacement = -0.01 / (1 - t)\n"
                       "  end\n"
                       "end\n",
                       1);
  const DirichletParts<2> dirichlet(parameters);
  const auto [value, message] = dirichlet.value(0, 1, Point<2>(0.5, 1), 1.);
  EXPECT_FALSE(std::isfinite(value));
  EXPECT_NE(message.find("Invalid parameter <Displacement> in subsection "
                         "<Boundary/Prescribed displacement 1>: its component "
                         "y is not finite"),
            std::string::npos)
    << message;
}

// Two zones: subsection Contact (a layer, Coulomb friction, a moving
// obstacle along a direction) and Contact zone 2 (Signorini, Tresca with a
// slip bound of x); a zone whose law does nothing is left out.
TEST(ContactZones, LawsGapsDirectionsAndFriction)
{
  const Parameters::AllParameters parameters
    = parse_parameters("subsection Boundary\n"
                       "  set Contact boundary ids = 2\n"
                       "end\n"
                       "subsection Contact\n"
                       "  set Initial gap          = 0.001 - 0.01 * t\n"
                       "  set Gap direction        = 0, -2\n"
                       "  set Tangential law       = Coulomb\n"
                       "  set Friction coefficient = 0.3\n"
                       "end\n"
                       "subsection Contact zone 2\n"
                       "  set Boundary ids          = 1\n"
                       "  set Unilateral constraint = true\n"
                       "  set Normal compliance     = false\n"
                       "  set Layer thickness       = 0\n"
                       "  set Tangential law        = Tresca\n"
                       "  set Slip bound            = x\n"
                       "end\n",
                       0,
                       0,
                       1);
  const ContactZones<2> zones(parameters);
  ASSERT_EQ(zones.descriptions().size(), 2u);
  EXPECT_EQ(zones.numbers(), (std::vector<unsigned int>{1, 2}));
  EXPECT_EQ(zones.frictional_numbers(), (std::vector<unsigned int>{1, 2}));
  const auto &contact = zones.descriptions()[0];
  EXPECT_EQ(contact.subsection, "Contact");
  EXPECT_EQ(contact.boundary_ids, (std::vector<types::boundary_id>{2}));
  ASSERT_TRUE(contact.direction.has_value());
  EXPECT_EQ((*contact.direction)[0], 0.);
  EXPECT_EQ((*contact.direction)[1], -1.);
  const auto *coulomb
    = dynamic_cast<const CoulombFriction *>(contact.friction.get());
  ASSERT_NE(coulomb, nullptr);
  EXPECT_EQ(coulomb->coefficient(), 0.3);
  EXPECT_NE(dynamic_cast<const TrescaFriction *>(
              zones.descriptions()[1].friction.get()),
            nullptr);
  EXPECT_FALSE(zones.descriptions()[1].direction.has_value());
  EXPECT_TRUE(zones.has_gap());
  EXPECT_TRUE(zones.gap_depends_on_time());
  const auto gaps = zones.gaps();
  ASSERT_NE(gaps[0], nullptr);
  EXPECT_EQ(gaps[1], nullptr);
  gaps[0]->set_time(0.5);
  EXPECT_EQ(gaps[0]->value(Point<2>(0.25, 0)), 0.001 - 0.01 * 0.5);
  const auto bounds = zones.slip_bounds();
  EXPECT_EQ(bounds[0], nullptr);
  ASSERT_NE(bounds[1], nullptr);
  EXPECT_EQ(bounds[1]->value(Point<2>(0.25, 0)), 0.25);
}

TEST(ContactZones, VoidLawHasNoZone)
{
  const Parameters::AllParameters parameters
    = parse_parameters("subsection Boundary\n"
                       "  set Contact boundary ids = 2\n"
                       "end\n"
                       "subsection Contact\n"
                       "  set Unilateral constraint = false\n"
                       "  set Normal compliance     = false\n"
                       "end\n");
  const ContactZones<2> zones(parameters);
  EXPECT_TRUE(zones.empty());
  EXPECT_FALSE(zones.has_gap());
}



// ContactZones::expected_contact_fraction(): the vertices of the top of the
// box [0, 4] x [0, 1] (32 x 8 cells, 33 vertices on the top, spacing 1/8)
// that a parabolic obstacle overlaps, s = (x - c)^2 / 4 - d <= 0, i.e.
// |x - c| <= 2 sqrt(d).
TEST(ContactZones, ExpectedContactFractionIsTheObstaclesOverlap)
{
  parallel::distributed::Triangulation<2> mesh(MPI_COMM_WORLD);
  GridGenerator::subdivided_hyper_rectangle(mesh,
                                            {32, 8},
                                            Point<2>(0, 0),
                                            Point<2>(4, 1),
                                            /*colorize=*/true);
  DoFHandler<2> dof_handler(mesh);
  dof_handler.distribute_dofs(FESystem<2>(FE_Q<2>(1), 2));
  const auto fraction = [&](const std::string         &obstacle,
                            const std::vector<double> &times,
                            const DoFHandler<2>       &dofs) {
    const Parameters::AllParameters parameters
      = parse_parameters("subsection Boundary\n"
                         "  set Contact boundary ids = 3\n"
                         "  set Loaded boundary ids =\n"
                         "end\n"
                         "subsection Contact\n"
                         "  set Normal compliance = false\n"
                         "  set Gap direction = 0, 1\n"
                         "  set Tangential law = Coulomb\n"
                         "  set Friction coefficient = 0.5\n"
                         + obstacle + "end\n");
    return ContactZones<2>(parameters)
      .expected_contact_fraction(dofs, times, MPI_COMM_WORLD);
  };
  // Pressed in by d = 0.01 t: at t = 0.5 and 1 the vertices at
  // |x - 1| <= 0.14 and 0.2, x = 0.875, 1 and 1.125 at both.
  EXPECT_DOUBLE_EQ(fraction("  set Initial gap = (x - 1)^2 / 4 - 0.01 * t\n",
                            {0.5, 1.},
                            dof_handler),
                   3. / 33);
  // Dragged by o(t) = (t, 0) to c = 1 + t: the most at one time, not the
  // union of the track (at t = 1.0625 the four vertices 1.875 to 2.25, the
  // outer two by a margin of 0.0125; at t = 0.5 and 2 three).
  EXPECT_DOUBLE_EQ(fraction("  set Initial gap = (x - 1)^2 / 4 - 0.01\n"
                            "  set Obstacle motion = t; 0\n",
                            {0.5, 1.0625, 2.},
                            dof_handler),
                   4. / 33);
  // The same obstacle at rest: the body is pushed by its loads, and any
  // vertex may come into contact.
  EXPECT_DOUBLE_EQ(fraction("  set Initial gap = (x - 1)^2 / 4 - 0.01\n",
                            {0.5, 1.},
                            dof_handler),
                   1.);
  // The same count with two elements (as Cell type = mixed has), the
  // cells right of x = 1 on the second: the vertex dofs are those of each
  // cell's element.
  DoFHandler<2> hp_dof_handler(mesh);
  for (const auto &cell : hp_dof_handler.active_cell_iterators())
    if (cell->is_locally_owned())
      cell->set_active_fe_index(cell->center()[0] > 1);
  hp_dof_handler.distribute_dofs(
    hp::FECollection<2>(FESystem<2>(FE_Q<2>(1), 2),
                        FESystem<2>(FE_Q<2>(1), 2)));
  EXPECT_DOUBLE_EQ(fraction("  set Initial gap = (x - 1)^2 / 4 - 0.01 * t\n",
                            {0.5, 1.},
                            hp_dof_handler),
                   3. / 33);
}
