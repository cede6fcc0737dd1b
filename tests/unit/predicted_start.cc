// Unit tests of PredictedStart: on a path linear in time the extrapolated
// start of a step is exact (the displacement, and the contact nodes' forces
// and r = n.u - s), and nothing moves without a start to extrapolate from;
// where the pieces may not be predicted, only u is extrapolated; a run
// starts at rest only where nothing acts at t_0.

#include <deal.II/base/function.h>

#include <gtest/gtest.h>

#include "acceleration/predicted_start.h"
#include "test_scenes.h"

#include <cmath>

using namespace dealii;
using namespace ViscoContact;

namespace
{
  // The unit square refined twice with the paper's layer law on its bottom
  // edge (boundary id 2); u(t) = a + t b and z_i(t) = 1 + 2 t + i on a path
  // through t_0 = 0.1, t_1 = 0.3 and t_2 = 0.4.
  struct Scene : TestScenes::SquareWithContactZone
  {
    Scene()
      : SquareWithContactZone(Parameters::Contact())
    {
      // The active-set parameter c_i of every node (above the law's
      // steepest softening), as the program sets it from K.
      contact.set_parameters(
        std::vector<double>(contact.size(),
                            10. * (1. + contact.laws().steepest_softening())));
    }

    VectorType
    displacement(const double t) const
    {
      VectorType u(layout);
      for (unsigned int k = 0; k < u.locally_owned_size(); ++k)
        {
          const double g     = u.get_partitioner()->local_to_global(k);
          u.local_element(k) = std::sin(1. + g) + t * std::cos(2. * g);
        }
      u.update_ghost_values();
      return u;
    }
    std::vector<double>
    forces(const double t) const
    {
      std::vector<double> z(contact.size());
      for (unsigned int i = 0; i < z.size(); ++i)
        z[i] = 1. + 2. * t + i;
      return z;
    }
  };

  void
  check_prediction(const bool pieces_predictable)
  {
    Scene               scene;
    PredictedStart<2>   start;
    const double        ratio = (0.4 - 0.3) / (0.3 - 0.1);
    VectorType          u     = scene.displacement(0.3);
    std::vector<double> z     = scene.forces(0.3);

    // Nothing to extrapolate from yet.
    EXPECT_FALSE(start.has_start());
    scene.contact.z = z;
    start.predict(ratio, u, &scene.contact);
    VectorType difference = u;
    difference -= scene.displacement(0.3);
    EXPECT_EQ(difference.linfty_norm(), 0.);
    EXPECT_EQ(scene.contact.z, z);

    start.set_pieces_predictable(pieces_predictable);
    start.remember(scene.displacement(0.1), scene.forces(0.1));
    ASSERT_TRUE(start.has_start());
    EXPECT_EQ(start.contact_forces(), scene.forces(0.1));
    start.predict(ratio, u, &scene.contact);
    difference = u;
    difference -= scene.displacement(0.4);
    EXPECT_LT(difference.linfty_norm(), 1e-14);
    EXPECT_TRUE(u.has_ghost_elements());
    const std::vector<double> expected
      = pieces_predictable ? scene.forces(0.4) : z;
    for (unsigned int i = 0; i < scene.contact.size(); ++i)
      {
        EXPECT_NEAR(scene.contact.z[i], expected[i], 1e-14);
        if (pieces_predictable)
          {
            EXPECT_NEAR(scene.contact.r[i],
                        scene.contact.normal_component(u, i)
                          - scene.contact.gap(i),
                        1e-15);
          }
      }

    start.forget();
    EXPECT_FALSE(start.has_start());
  }
} // namespace

TEST(PredictedStart, ExactOnALinearPath)
{
  check_prediction(true);
}

TEST(PredictedStart, OnlyTheDisplacementWherePiecesMustBeKept)
{
  check_prediction(false);
}

namespace
{
  // Whether a Scene with the given contact entries and obstacle gap s
  // starts at rest with u_0 = 0 and a zero right-hand side.
  bool
  starts_at_rest(const Parameters::Contact &entries, const double gap)
  {
    TestScenes::SquareWithContactZone scene(entries);
    scene.contact.set_parameters(std::vector<double>(
      scene.contact.size(),
      10. * (1. + scene.contact.laws().steepest_softening())));
    Functions::ConstantFunction<2> obstacle_gap(gap);
    EXPECT_EQ(scene.contact.set_gaps({&obstacle_gap}, 0.), "");
    const VectorType zero(scene.layout);
    return PredictedStart<2>::starts_at_rest(zero,
                                             zero,
                                             &scene.contact,
                                             MPI_COMM_WORLD);
  }
} // namespace

// u_0 = 0 solves the problem at t_0 only without a displacement, a load or
// a contact force there: the paper's layer law (p = 0 for r <= 0) rests
// where the obstacle touches (s = 0) or is away (s > 0), not where it
// overlaps the body (s < 0: r = -s > 0 inside the layer pushes); an
// adhesive branch pulls at r < 0, so there only s = 0 rests; a memory
// pressure moves the graph.
TEST(PredictedStart, StartsAtRestOnlyWhereNothingActs)
{
  const Parameters::Contact layer;
  EXPECT_TRUE(starts_at_rest(layer, 0.));
  EXPECT_TRUE(starts_at_rest(layer, 1e-3));
  EXPECT_FALSE(starts_at_rest(layer, -1e-3));
  EXPECT_FALSE(starts_at_rest(layer, -0.1)); // beyond the rigid limit g

  Parameters::Contact adhesive;
  adhesive.adhesion_stiffness = 100;
  adhesive.adhesion_length    = 0.01;
  EXPECT_TRUE(starts_at_rest(adhesive, 0.));
  EXPECT_FALSE(starts_at_rest(adhesive, 1e-3));

  // A law with a jump at r = 0 (p in [0, 1] there): at s = 0 a force of 0
  // lies on its vertical piece, and it still does with a memory pressure
  // m = -1/2 (the graph moved down: p - m = 1/2 in [0, 1]), not with
  // m = 1/2.
  Parameters::Contact jump;
  jump.unilateral_constraint = false;
  jump.law_type              = Parameters::ContactLawType::piecewise_linear;
  jump.breakpoints           = {0.};
  jump.slopes                = {0., 100.};
  jump.jumps                 = {1.};
  EXPECT_TRUE(starts_at_rest(jump, 0.));
  EXPECT_FALSE(starts_at_rest(jump, -1e-3));
  for (const double m : {-0.5, 0.5})
    {
      TestScenes::SquareWithContactZone scene(jump);
      scene.contact.set_parameters(
        std::vector<double>(scene.contact.size(), 10.));
      scene.contact.set_history_pressure(
        std::vector<double>(scene.contact.size(), m));
      const VectorType zero(scene.layout);
      EXPECT_EQ(PredictedStart<2>::starts_at_rest(zero,
                                                  zero,
                                                  &scene.contact,
                                                  MPI_COMM_WORLD),
                m < 0)
        << "memory pressure " << m;
    }

  // A prescribed displacement, a load, or a memory pressure that moves the
  // graph up.
  TestScenes::SquareWithContactZone scene(layer);
  scene.contact.set_parameters(
    std::vector<double>(scene.contact.size(),
                        10.
                          * (1. + scene.contact.laws().steepest_softening())));
  VectorType zero(scene.layout), nonzero(scene.layout);
  if (nonzero.locally_owned_size() > 0)
    nonzero.local_element(0) = 1e-12;
  EXPECT_FALSE(PredictedStart<2>::starts_at_rest(nonzero,
                                                 zero,
                                                 &scene.contact,
                                                 MPI_COMM_WORLD));
  EXPECT_FALSE(PredictedStart<2>::starts_at_rest(zero,
                                                 nonzero,
                                                 &scene.contact,
                                                 MPI_COMM_WORLD));
  EXPECT_TRUE(
    PredictedStart<2>::starts_at_rest(zero, zero, nullptr, MPI_COMM_WORLD));
  scene.contact.set_history_pressure(
    std::vector<double>(scene.contact.size(), 1.));
  EXPECT_FALSE(PredictedStart<2>::starts_at_rest(zero,
                                                 zero,
                                                 &scene.contact,
                                                 MPI_COMM_WORLD));
}
