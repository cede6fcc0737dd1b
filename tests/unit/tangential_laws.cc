// Unit tests of the tangential laws (tangential_law.h): each law's bound of
// a node and the force of a slipping node in the step problem, and the law
// of a zone's parameters.

#include <gtest/gtest.h>

#include "parameters.h"
#include "tangential_law.h"

using namespace ViscoContact;

TEST(TangentialLaws, BoundsAndSlipForces)
{
  const Frictionless frictionless;
  EXPECT_FALSE(frictionless.has_friction());
  EXPECT_EQ(frictionless.bound(3., 2.), 0.);
  EXPECT_EQ(frictionless.slip_force(0.).value, 0.);
  EXPECT_EQ(frictionless.slip_force(0.).coupling, 0.);

  // Tresca: the node's share of the Slip bound, whatever the normal force.
  const TrescaFriction tresca;
  EXPECT_TRUE(tresca.has_friction());
  EXPECT_TRUE(tresca.uses_node_bounds());
  EXPECT_EQ(tresca.bound(3., 0.25), 0.25);
  EXPECT_EQ(tresca.bound(0., 0.25), 0.25);
  EXPECT_EQ(tresca.slip_force(0.25).value, 0.25);
  EXPECT_EQ(tresca.slip_force(0.25).coupling, 0.);

  // Coulomb: mu z in contact, nothing out of it; the slip force is coupled
  // to the normal force of the same solve.
  const CoulombFriction coulomb(0.3);
  EXPECT_TRUE(coulomb.has_friction());
  EXPECT_FALSE(coulomb.uses_node_bounds());
  EXPECT_EQ(coulomb.bound(2., 5.), 0.3 * 2.);
  EXPECT_EQ(coulomb.bound(-1., 5.), 0.);
  EXPECT_EQ(coulomb.slip_force(0.6).value, 0.);
  EXPECT_EQ(coulomb.slip_force(0.6).coupling, 0.3);
}

TEST(TangentialLaws, FromParameters)
{
  Parameters::Contact contact;
  contact.tangential_law       = Parameters::TangentialLawType::coulomb;
  contact.friction_coefficient = 0.4;
  const auto coulomb           = TangentialLaw::from_parameters(contact);
  ASSERT_NE(dynamic_cast<const CoulombFriction *>(coulomb.get()), nullptr);
  EXPECT_EQ(coulomb->bound(1., 0.), 0.4);
  contact.tangential_law = Parameters::TangentialLawType::tresca;
  EXPECT_NE(dynamic_cast<const TrescaFriction *>(
              TangentialLaw::from_parameters(contact).get()),
            nullptr);
  contact.tangential_law = Parameters::TangentialLawType::frictionless;
  EXPECT_FALSE(TangentialLaw::from_parameters(contact)->has_friction());
}

// Slip weakening: f through the points (0, 1), (0.005, 0.6), (0.01, 0.5),
// constant beyond them; a law without points does not weaken; the law of
// the parameters carries the points.
TEST(TangentialLaws, SlipWeakeningFactor)
{
  const SlipWeakening none;
  EXPECT_EQ(none.factor(1.), 1.);
  const SlipWeakening weakening{{0., 0.005, 0.01}, {1., 0.6, 0.5}};
  EXPECT_EQ(weakening.factor(0.), 1.);
  EXPECT_NEAR(weakening.factor(0.0025), 0.8, 1e-15);
  EXPECT_NEAR(weakening.factor(0.0075), 0.55, 1e-15);
  EXPECT_EQ(weakening.factor(0.02), 0.5);
  const SlipWeakening late{{0.001}, {0.7}};
  EXPECT_EQ(late.factor(0.), 0.7);

  Parameters::Contact contact;
  contact.tangential_law       = Parameters::TangentialLawType::coulomb;
  contact.friction_coefficient = 0.5;
  contact.weakening_slips      = {0., 0.005};
  contact.weakening_factors    = {1., 0.6};
  const auto law               = TangentialLaw::from_parameters(contact);
  EXPECT_NEAR(law->weakening.factor(0.005), 0.6, 1e-15);
  EXPECT_EQ(law->bound(2., 0.), 1.); // unweakened: ContactNodes applies f
}
