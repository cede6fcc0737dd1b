// Unit tests of PredictedStart: on a path linear in time the extrapolated
// start of a step is exact (the displacement, and the contact nodes' forces
// and r = n.u - s), and nothing moves without a start to extrapolate from;
// where the pieces may not be predicted, only u is extrapolated.

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
