// Unit tests of the contact rows (ContactSet::row()): the rows of N that
// the back ends see, as short sparse vectors over dofs. Today every row lies
// on its node's own dofs; these tests pin that down, so that rows spanning
// several nodes (contact between two bodies) change the rows and nothing
// the back ends rely on: the entries are the nonzero components of the
// node's normal and tangents in component order, and the operations on
// rows agree with those in the node's frame to rounding.

#include <gtest/gtest.h>

#include "contact_set.h"
#include "parameters.h"
#include "test_scenes.h"

#include <cmath>

using namespace dealii;
using namespace ViscoContact;

namespace
{
  // The unit square turned by angle, refined twice, with a Coulomb zone on
  // its bottom edge (boundary id 2): the nodes' normals have one nonzero
  // component at angle 0 and two otherwise.
  void
  check_rows_of_the_bottom_edge(const double angle)
  {
    Parameters::Contact entries;
    entries.tangential_law       = Parameters::TangentialLawType::coulomb;
    entries.friction_coefficient = 0.3;
    TestScenes::SquareWithContactZone square(entries, angle);
    const ContactSet<2>              &contact = square.contact;
    const VectorType                 &layout  = square.layout;
    EXPECT_EQ(contact.n_global_nodes(), 5u);

    // A displacement with distinct entries.
    VectorType u(layout);
    for (unsigned int k = 0; k < u.locally_owned_size(); ++k)
      u.local_element(k)
        = std::sin(1. + u.get_partitioner()->local_to_global(k));

    const unsigned int expected_entries = (angle == 0 ? 1 : 2);
    for (unsigned int i = 0; i < contact.size(); ++i)
      {
        const auto &node = contact.node(i);
        ASSERT_EQ(contact.n_tangential(i), 1u);
        for (unsigned int j = 0; j < 2; ++j)
          {
            const Tensor<1, 2> vector
              = (j == 0 ? node.normal : node.tangent_rows[0]);
            const auto row = contact.row(i, j);
            ASSERT_EQ(row.size(), expected_entries);
            // The nonzero components in component order, on the node's dofs.
            unsigned int k = 0;
            for (unsigned int c = 0; c < 2; ++c)
              if (vector[c] != 0)
                {
                  EXPECT_EQ(row[k].dof, node.dofs[c]);
                  EXPECT_EQ(row[k].local_dof, node.local_dofs[c]);
                  EXPECT_EQ(row[k].value, vector[c]);
                  ++k;
                }
            // r = row . u as the node's frame has it.
            std::array<double, 3> frame{{0, 0, 0}};
            frame[j] = 1;
            EXPECT_NEAR(contact.row_component(u, i, j),
                        contact.node_component(u,
                                               i,
                                               contact.frame_row(i, frame)),
                        1e-15);
            // v = value row, so that v . u = value (row . u).
            VectorType v(layout);
            contact.add_to_row(v, i, j, 2.5);
            double v_dot_u = 0;
            for (unsigned int k = 0; k < v.locally_owned_size(); ++k)
              v_dot_u += v.local_element(k) * u.local_element(k);
            EXPECT_NEAR(v_dot_u, 2.5 * contact.row_component(u, i, j), 1e-14);
          }
        // The normal and the tangent: unit rows, orthogonal.
        const auto dot = [&](const unsigned int a, const unsigned int b) {
          double sum = 0;
          for (const auto &x : contact.row(i, a))
            for (const auto &y : contact.row(i, b))
              if (x.dof == y.dof)
                sum += x.value * y.value;
          return sum;
        };
        EXPECT_NEAR(dot(0, 0), 1, 1e-14);
        EXPECT_NEAR(dot(1, 1), 1, 1e-14);
        EXPECT_NEAR(dot(0, 1), 0, 1e-14);
        EXPECT_EQ(contact.normal_component(u, i),
                  contact.row_component(u, i, 0));
      }
  }
} // namespace



TEST(ContactRows, AxisAlignedEdge)
{
  check_rows_of_the_bottom_edge(0);
}



TEST(ContactRows, TurnedEdge)
{
  check_rows_of_the_bottom_edge(0.3);
}



// The contact state across a change of mesh: the pressure z_i / w_i as a
// nodal field (ContactSet::pressure_field()) and back
// (ContactSet::set_state_from()) gives every node its z and, from u, its
// r = nu . u - s.
TEST(ContactSet, PressureFieldAndBack)
{
  Parameters::Contact               entries;
  TestScenes::SquareWithContactZone square(entries, 0.3);
  ContactSet<2>                    &contact = square.contact;
  ASSERT_EQ(contact.n_global_nodes(), 5u);
  for (unsigned int i = 0; i < contact.size(); ++i)
    contact.z[i] = (1. + i) * contact.weight(i);
  const VectorType pressure
    = contact.pressure_field(square.layout, square.constraints);
  VectorType u(square.layout);
  for (unsigned int k = 0; k < u.locally_owned_size(); ++k)
    u.local_element(k) = 1e-3 * std::cos(1. + k);
  u.update_ghost_values();
  for (unsigned int i = 0; i < contact.size(); ++i)
    contact.z[i] = contact.r[i] = 0;
  // The active-set parameters c_i, from unit blocks, name the pieces.
  Tensor<2, 2> unit;
  unit[0][0] = unit[1][1] = 1;
  contact.set_operator(std::vector<Tensor<2, 2>>(contact.size(), unit));
  contact.set_state_from(u, pressure, /*with_friction=*/false);
  for (unsigned int i = 0; i < contact.size(); ++i)
    {
      EXPECT_NEAR(contact.z[i], (1. + i) * contact.weight(i), 1e-14);
      EXPECT_NEAR(contact.r[i],
                  contact.normal_component(u, i) - contact.gap(i),
                  1e-16);
    }
}
