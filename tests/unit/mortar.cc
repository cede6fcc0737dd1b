// Unit tests of the mortar coupling of two sides in 2D (contact_pairs/
// mortar.h): a rigid translation has no weighted gap, a linear field is
// reproduced on a straight interface with non-matching vertices (the patch
// test), a gap is measured exactly, and two independently meshed arcs of
// one circle miss each other by no more than their sagittas allow.

#include <gtest/gtest.h>

#include "contact_pairs/mortar.h"

#include <cmath>
#include <numeric>

using namespace dealii;
using namespace ViscoContact;

namespace
{
  // n_segments + 1 vertices on the line y = height from x0 to x1, the
  // segments oriented so that their normals point up (the side of a body
  // below the line) or down (of a body above it).
  Mortar::Side
  straight_side(const unsigned int n_segments,
                const double       x0,
                const double       x1,
                const double       height,
                const bool         normal_up)
  {
    Mortar::Side side;
    for (unsigned int i = 0; i <= n_segments; ++i)
      side.vertices.emplace_back(x0 + (x1 - x0) * i / n_segments, height);
    for (unsigned int i = 0; i < n_segments; ++i)
      side.segments.push_back(normal_up
                                ? std::array<unsigned int, 2>{{i + 1, i}}
                                : std::array<unsigned int, 2>{{i, i + 1}});
    return side;
  }

  double
  row_sum(const Mortar::Coupling &coupling, const unsigned int j)
  {
    double sum = 0;
    for (const auto &[k, m] : coupling.M[j])
      sum += m;
    return sum;
  }
} // namespace

// 7 slave segments on [0, 1] under 3 master segments on [-0.1, 1.1]: every
// slave segment is covered, and no vertex matches.
TEST(Mortar, PatchTestOnNonMatchingStraightSides)
{
  const Mortar::Side     slave  = straight_side(7, 0, 1, 0, /*up=*/true);
  const Mortar::Side     master = straight_side(3, -0.1, 1.1, 0, false);
  const Mortar::Coupling c      = Mortar::couple(slave, master);
  const double           h      = 1. / 7;
  for (unsigned int j = 0; j < slave.vertices.size(); ++j)
    {
      // D_j is the integral of N_j: h inside, h/2 at the ends.
      const bool end = (j == 0 || j == 7);
      EXPECT_NEAR(c.D[j], end ? h / 2 : h, 1e-15);
      EXPECT_NEAR(c.normals[j][0], 0, 1e-15);
      EXPECT_NEAR(c.normals[j][1], 1, 1e-15);
      // Constants and linear fields: sum_k M_jk = D_j, sum_k M_jk x_k =
      // D_j x_j.
      EXPECT_NEAR(row_sum(c, j), c.D[j], 1e-15);
      Tensor<1, 2> first_moment;
      for (const auto &[k, m] : c.M[j])
        first_moment += m * master.vertices[k];
      EXPECT_NEAR(first_moment[0], c.D[j] * slave.vertices[j][0], 1e-15);
      EXPECT_NEAR(first_moment[1], 0, 1e-15);
    }

  // No gap; a master side lifted by 0.01 has the gap 0.01 D_j; a rigid
  // motion of both sides changes nothing; compressing the master side
  // against the slave by 0.002 gives a negative gap.
  const std::vector<Tensor<1, 2>> no_slave(slave.vertices.size()),
    no_master(master.vertices.size());
  Tensor<1, 2> lift, translation, push;
  lift[1]        = 0.01;
  translation[0] = 0.3;
  translation[1] = -0.2;
  push[1]        = -0.002;
  const auto gaps_of
    = [&](const Tensor<1, 2> &slave_u, const Tensor<1, 2> &master_u) {
        return Mortar::weighted_gaps(
          c,
          slave,
          master,
          std::vector<Tensor<1, 2>>(slave.vertices.size(), slave_u),
          std::vector<Tensor<1, 2>>(master.vertices.size(), master_u));
      };
  const std::vector<double> touching = gaps_of(Tensor<1, 2>(), Tensor<1, 2>());
  const std::vector<double> lifted   = gaps_of(Tensor<1, 2>(), lift);
  const std::vector<double> moved    = gaps_of(translation, lift + translation);
  const std::vector<double> pushed   = gaps_of(Tensor<1, 2>(), push);
  for (unsigned int j = 0; j < slave.vertices.size(); ++j)
    {
      EXPECT_NEAR(touching[j], 0, 1e-16);
      EXPECT_NEAR(lifted[j], 0.01 * c.D[j], 1e-16);
      EXPECT_NEAR(moved[j], 0.01 * c.D[j], 1e-16);
      EXPECT_NEAR(pushed[j], -0.002 * c.D[j], 1e-16);
    }
}

// A master side that covers only [0.25, 0.8] of the slave side, ending
// inside two slave segments: the rows still sum to D_j (a translation has
// no gap), D_j is the covered integral of N_j, never negative (the
// standard dual basis gives D_1 = -0.022 and D_6 = -0.0086 here), the D_j
// add up to the covered length, and linear fields are reproduced on the
// partly covered segments too.
TEST(Mortar, PartlyCoveredSlaveSide)
{
  const Mortar::Side     slave  = straight_side(7, 0, 1, 0, true);
  const Mortar::Side     master = straight_side(2, 0.25, 0.8, 0, false);
  const Mortar::Coupling c      = Mortar::couple(slave, master);
  const double           h      = 1. / 7;
  // The covered integral of the hat of vertex j.
  const auto covered_hat = [&](const unsigned int j) {
    double integral = 0;
    for (const int side : {-1, 1})
      {
        const double x_j = j * h, x_n = x_j + side * h;
        if (x_n < -1e-12 || x_n > 1 + 1e-12)
          continue;
        const double lo = std::max(std::min(x_j, x_n), 0.25),
                     hi = std::min(std::max(x_j, x_n), 0.8);
        // On this side |x - x_j| = side (x - x_j).
        if (hi > lo)
          integral += (hi - lo)
                      - side * (std::pow(hi - x_j, 2) - std::pow(lo - x_j, 2))
                          / (2 * h);
      }
    return integral;
  };
  for (unsigned int j = 0; j < slave.vertices.size(); ++j)
    {
      EXPECT_NEAR(row_sum(c, j), c.D[j], 1e-15);
      EXPECT_GE(c.D[j], 0.);
      EXPECT_NEAR(c.D[j], covered_hat(j), 1e-15) << "vertex " << j;
      Tensor<1, 2> first_moment;
      for (const auto &[k, m] : c.M[j])
        first_moment += m * master.vertices[k];
      EXPECT_NEAR(first_moment[0], c.D[j] * slave.vertices[j][0], 1e-14);
    }
  EXPECT_NEAR(std::accumulate(c.D.begin(), c.D.end(), 0.), 0.55, 1e-15);
  // Vertices far from the covered part are not coupled.
  EXPECT_TRUE(c.M[0].empty());
  EXPECT_TRUE(c.M[7].empty());
}

// A master side that faces the same way as the slave side is no other side
// of a contact: nothing is coupled.
TEST(Mortar, SidesFacingTheSameWayAreNotCoupled)
{
  const Mortar::Side     slave  = straight_side(4, 0, 1, 0, true);
  const Mortar::Side     master = straight_side(3, 0, 1, 0, true);
  const Mortar::Coupling c      = Mortar::couple(slave, master);
  for (unsigned int j = 0; j < slave.vertices.size(); ++j)
    {
      EXPECT_EQ(c.D[j], 0.);
      EXPECT_TRUE(c.M[j].empty());
    }
}

// Two independently meshed arcs of the circle of radius R (a quarter, with
// 12 and 17 segments: the scene of an interference fit): every vertex lies
// on the circle, the chords inside it by up to the sagitta s = h^2 / (8 R),
// so the two polygons lie apart by up to s_slave + s_master, and since
// int |psi_j| = 5/3 int N_j, |g_j| / D_j <= 5/3 (s_slave + s_master) =
// 5.3e-3. Observed: at most 7.4e-4 (0.14 of that); the bound below is the
// observed one times 1.5. The rows sum to D_j as ever.
TEST(Mortar, NonMatchingArcsOfOneCircle)
{
  const double R = 1, quarter = M_PI / 2;
  const auto   arc = [&](const unsigned int n, const bool outward) {
    Mortar::Side side;
    for (unsigned int i = 0; i <= n; ++i)
      side.vertices.emplace_back(R * std::cos(quarter * i / n),
                                 R * std::sin(quarter * i / n));
    // Counter-clockwise segments have outward normals (the shaft, slave);
    // clockwise ones inward normals (the bore of the ring, master).
    for (unsigned int i = 0; i < n; ++i)
      side.segments.push_back(outward
                                ? std::array<unsigned int, 2>{{i, i + 1}}
                                : std::array<unsigned int, 2>{{i + 1, i}});
    return side;
  };
  const Mortar::Side     shaft = arc(12, true), ring = arc(17, false);
  const Mortar::Coupling c       = Mortar::couple(shaft, ring);
  const auto             sagitta = [&](const unsigned int n) {
    const double h = 2 * R * std::sin(quarter / n / 2);
    return h * h / (8 * R);
  };
  EXPECT_NEAR(5. / 3 * (sagitta(12) + sagitta(17)), 5.35e-3, 1e-5);
  const double              bound = 1.5 * 7.4e-4;
  const std::vector<double> gaps
    = Mortar::weighted_gaps(c,
                            shaft,
                            ring,
                            std::vector<Tensor<1, 2>>(13),
                            std::vector<Tensor<1, 2>>(18));
  for (unsigned int j = 0; j <= 12; ++j)
    {
      EXPECT_NEAR(row_sum(c, j), c.D[j], 1e-14);
      EXPECT_LE(std::abs(gaps[j]), bound * c.D[j]) << "vertex " << j;
      // The vertex normals point out of the shaft.
      EXPECT_NEAR(c.normals[j] * (shaft.vertices[j] / R), 1, 1e-2);
    }
}
