// Unit tests of the mortar coupling of two sides (contact_pairs/
// mortar.h): a rigid translation has no weighted gap, a linear field is
// reproduced on a straight interface with non-matching vertices (the patch
// test), a gap is measured exactly, and two independently meshed arcs of
// one circle miss each other by no more than their sagittas allow.

#include <gtest/gtest.h>

#include "contact_pairs/mortar.h"

#include <algorithm>
#include <cmath>
#include <numeric>

using namespace dealii;
using namespace ViscoContact;

namespace
{
  // n_segments + 1 vertices on the line y = height from x0 to x1, the
  // segments oriented so that their normals point up (the side of a body
  // below the line) or down (of a body above it).
  Mortar::Side<2>
  straight_side(const unsigned int n_segments,
                const double       x0,
                const double       x1,
                const double       height,
                const bool         normal_up)
  {
    Mortar::Side<2> side;
    for (unsigned int i = 0; i <= n_segments; ++i)
      side.vertices.emplace_back(x0 + (x1 - x0) * i / n_segments, height);
    for (unsigned int i = 0; i < n_segments; ++i)
      side.faces.push_back(normal_up ? std::vector<unsigned int>{i + 1, i}
                                     : std::vector<unsigned int>{i, i + 1});
    return side;
  }

  double
  row_sum(const Mortar::Coupling<2> &coupling, const unsigned int j)
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
  const Mortar::Side<2>     slave  = straight_side(7, 0, 1, 0, /*up=*/true);
  const Mortar::Side<2>     master = straight_side(3, -0.1, 1.1, 0, false);
  const Mortar::Coupling<2> c      = Mortar::couple(slave, master);
  const double              h      = 1. / 7;
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
  const Mortar::Side<2>     slave  = straight_side(7, 0, 1, 0, true);
  const Mortar::Side<2>     master = straight_side(2, 0.25, 0.8, 0, false);
  const Mortar::Coupling<2> c      = Mortar::couple(slave, master);
  const double              h      = 1. / 7;
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
  const Mortar::Side<2>     slave  = straight_side(4, 0, 1, 0, true);
  const Mortar::Side<2>     master = straight_side(3, 0, 1, 0, true);
  const Mortar::Coupling<2> c      = Mortar::couple(slave, master);
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
    Mortar::Side<2> side;
    for (unsigned int i = 0; i <= n; ++i)
      side.vertices.emplace_back(R * std::cos(quarter * i / n),
                                 R * std::sin(quarter * i / n));
    // Counter-clockwise segments have outward normals (the shaft, slave);
    // clockwise ones inward normals (the bore of the ring, master).
    for (unsigned int i = 0; i < n; ++i)
      side.faces.push_back(outward ? std::vector<unsigned int>{i, i + 1}
                                   : std::vector<unsigned int>{i + 1, i});
    return side;
  };
  const Mortar::Side<2>     shaft = arc(12, true), ring = arc(17, false);
  const Mortar::Coupling<2> c       = Mortar::couple(shaft, ring);
  const auto                sagitta = [&](const unsigned int n) {
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

namespace
{
  // A side in 3D on the plane z = slope_x x + slope_y y over the rectangle
  // [x0, x1] x [y0, y1] with nx x ny cells, quadrilaterals (their interior
  // vertices moved by up to a quarter of a cell when distorted) or
  // triangles, oriented so that their normals point up or down.
  Mortar::Side<3>
  flat_side_3d(const unsigned int nx,
               const unsigned int ny,
               const Point<2>    &lower,
               const Point<2>    &upper,
               const bool         triangles,
               const bool         normal_up,
               const bool         distorted,
               const double       slope_x = 0,
               const double       slope_y = 0)
  {
    Mortar::Side<3> side;
    const double    hx = (upper[0] - lower[0]) / nx,
                 hy    = (upper[1] - lower[1]) / ny;
    for (unsigned int j = 0; j <= ny; ++j)
      for (unsigned int i = 0; i <= nx; ++i)
        {
          double x = lower[0] + i * hx, y = lower[1] + j * hy;
          if (distorted && i > 0 && i < nx && j > 0 && j < ny)
            {
              x += 0.25 * hx * std::sin(3. * i + 7. * j);
              y += 0.25 * hy * std::cos(5. * i + 2. * j);
            }
          side.vertices.emplace_back(x, y, slope_x * x + slope_y * y);
        }
    const auto v = [&](const unsigned int i, const unsigned int j) {
      return j * (nx + 1) + i;
    };
    const auto add = [&](std::vector<unsigned int> face) {
      if (!normal_up)
        std::reverse(face.begin(), face.end());
      side.faces.push_back(face);
    };
    for (unsigned int j = 0; j < ny; ++j)
      for (unsigned int i = 0; i < nx; ++i)
        if (triangles)
          {
            add({v(i, j), v(i + 1, j), v(i + 1, j + 1)});
            add({v(i, j), v(i + 1, j + 1), v(i, j + 1)});
          }
        else
          add({v(i, j), v(i + 1, j), v(i + 1, j + 1), v(i, j + 1)});
    return side;
  }

  // Sum_k M_jk x_k = D_j x_j and sum_k M_jk = D_j at every slave vertex,
  // to round-off.
  void
  expect_linear_fields_reproduced(const Mortar::Coupling<3> &c,
                                  const Mortar::Side<3>     &slave,
                                  const Mortar::Side<3>     &master)
  {
    for (unsigned int j = 0; j < slave.vertices.size(); ++j)
      {
        double       sum = 0;
        Tensor<1, 3> first_moment;
        for (const auto &[k, m] : c.M[j])
          {
            sum += m;
            first_moment += m * master.vertices[k];
          }
        EXPECT_NEAR(sum, c.D[j], 1e-14) << "vertex " << j;
        for (unsigned int d = 0; d < 3; ++d)
          EXPECT_NEAR(first_moment[d], c.D[j] * slave.vertices[j][d], 1e-14)
            << "vertex " << j << ", component " << d;
      }
  }
} // namespace

// 3D: distorted quadrilaterals (5 x 3 on [0, 1] x [0, 0.6]) under
// triangles (4 x 4 squares cut in two on [-0.1, 1.1] x [-0.1, 0.7]), and
// triangles under distorted quadrilaterals, on a tilted plane: every slave
// face is covered; D_j adds up to the slave side's area, the rows sum to
// D_j, linear fields are reproduced (the patch test on non-matching
// meshes), and a master side lifted along the normal by 0.01 has the gap
// 0.01 D_j.
TEST(Mortar, PatchTestOnNonMatchingFlatSides3D)
{
  for (const bool slave_triangles : {false, true})
    {
      const double              sx = 0.3, sy = -0.2;
      const Mortar::Side<3>     slave  = flat_side_3d(5,
                                                 3,
                                                 Point<2>(0, 0),
                                                 Point<2>(1, 0.6),
                                                 slave_triangles,
                                                 true,
                                                 !slave_triangles,
                                                 sx,
                                                 sy);
      const Mortar::Side<3>     master = flat_side_3d(4,
                                                  4,
                                                  Point<2>(-0.1, -0.1),
                                                  Point<2>(1.1, 0.7),
                                                  !slave_triangles,
                                                  false,
                                                  slave_triangles,
                                                  sx,
                                                  sy);
      const Mortar::Coupling<3> c      = Mortar::couple(slave, master);
      const double              area   = 0.6 * std::sqrt(1 + sx * sx + sy * sy);
      EXPECT_NEAR(std::accumulate(c.D.begin(), c.D.end(), 0.), area, 1e-14);
      for (const double D : c.D)
        EXPECT_GT(D, 0);
      expect_linear_fields_reproduced(c, slave, master);

      Tensor<1, 3> normal({-sx, -sy, 1.});
      normal /= normal.norm();
      const std::vector<double> lifted = Mortar::weighted_gaps(
        c,
        slave,
        master,
        std::vector<Tensor<1, 3>>(slave.vertices.size()),
        std::vector<Tensor<1, 3>>(master.vertices.size(), 0.01 * normal));
      for (unsigned int j = 0; j < slave.vertices.size(); ++j)
        {
          EXPECT_NEAR(c.normals[j] * normal, 1, 1e-14);
          EXPECT_NEAR(lifted[j], 0.01 * c.D[j], 1e-15);
        }
    }
}

// 3D: a master side (3 x 2 quadrilaterals on [0.25, 0.8] x [0.1, 0.45])
// that covers a slave side (5 x 3 triangles' squares on [0, 1] x [0, 0.6])
// only in part, ending inside slave faces: D_j >= 0, the D_j add up to the
// covered area, the rows sum to D_j and linear fields are reproduced; a
// master side facing the same way, or farther than the search distance,
// couples nothing.
TEST(Mortar, PartlyCoveredAndFacingAway3D)
{
  const Mortar::Side<3> slave
    = flat_side_3d(5, 3, Point<2>(0, 0), Point<2>(1, 0.6), true, true, false);
  const Mortar::Side<3>     master = flat_side_3d(3,
                                              2,
                                              Point<2>(0.25, 0.1),
                                              Point<2>(0.8, 0.45),
                                              false,
                                              false,
                                              false);
  const Mortar::Coupling<3> c      = Mortar::couple(slave, master);
  EXPECT_NEAR(std::accumulate(c.D.begin(), c.D.end(), 0.), 0.55 * 0.35, 1e-14);
  for (const double D : c.D)
    EXPECT_GE(D, 0);
  expect_linear_fields_reproduced(c, slave, master);

  const Mortar::Side<3>     same_way = flat_side_3d(3,
                                                2,
                                                Point<2>(0.25, 0.1),
                                                Point<2>(0.8, 0.45),
                                                false,
                                                true,
                                                false);
  const Mortar::Coupling<3> none     = Mortar::couple(slave, same_way);
  EXPECT_EQ(std::accumulate(none.D.begin(), none.D.end(), 0.), 0.);
  EXPECT_EQ(none.closest_distance, std::numeric_limits<double>::infinity());

  Mortar::Side<3> far = master;
  for (Point<3> &vertex : far.vertices)
    vertex[2] = 0.1;
  const Mortar::Coupling<3> beyond = Mortar::couple(slave, far, 0.05);
  EXPECT_EQ(std::accumulate(beyond.D.begin(), beyond.D.end(), 0.), 0.);
  // How far it lies: with an infinite search distance every master face
  // is looked at.
  EXPECT_NEAR(Mortar::couple(slave, far).closest_distance, 0.1, 1e-15);
}

// 3D: two independently meshed patches of one sphere (radius 1, around its
// north pole): warped quadrilaterals (6 x 6, the slave side, normals out of
// the sphere) against triangles (7 x 7 squares cut in two, the master side,
// normals into it, covering the slave patch). Every vertex lies on the
// sphere, the faces are chords of it: the rows still sum to D_j, every D_j
// is positive, the vertex normals are radial, and the weighted gap per unit
// D_j stays within 5/3 of the sum of the two sides' sagittas d^2 / (8 R),
// d the longest face diagonal, as for arcs in 2D.
TEST(Mortar, NonMatchingPatchesOfOneSphere3D)
{
  const auto patch = [](const unsigned int n,
                        const double       half_width,
                        const bool         triangles,
                        const bool         outward) {
    Mortar::Side<3> side = flat_side_3d(n,
                                        n,
                                        Point<2>(-half_width, -half_width),
                                        Point<2>(half_width, half_width),
                                        triangles,
                                        outward,
                                        false);
    for (Point<3> &vertex : side.vertices)
      {
        vertex[2] = 1;
        vertex /= vertex.norm();
      }
    return side;
  };
  const Mortar::Side<3>     slave   = patch(6, 0.5, false, true);
  const Mortar::Side<3>     master  = patch(7, 0.6, true, false);
  const Mortar::Coupling<3> c       = Mortar::couple(slave, master);
  const auto                sagitta = [](const Mortar::Side<3> &side) {
    double diagonal = 0;
    for (const auto &face : side.faces)
      for (unsigned int a = 0; a < face.size(); ++a)
        for (unsigned int b = 0; b < a; ++b)
          diagonal = std::max(
            diagonal,
            (side.vertices[face[a]] - side.vertices[face[b]]).norm());
    return diagonal * diagonal / 8;
  };
  const double              bound = 5. / 3 * (sagitta(slave) + sagitta(master));
  const std::vector<double> gaps
    = Mortar::weighted_gaps(c,
                            slave,
                            master,
                            std::vector<Tensor<1, 3>>(slave.vertices.size()),
                            std::vector<Tensor<1, 3>>(master.vertices.size()));
  for (unsigned int j = 0; j < slave.vertices.size(); ++j)
    {
      double sum = 0;
      for (const auto &[k, m] : c.M[j])
        sum += m;
      EXPECT_GT(c.D[j], 0) << "vertex " << j;
      EXPECT_NEAR(sum, c.D[j], 1e-14) << "vertex " << j;
      EXPECT_NEAR(c.normals[j] * slave.vertices[j], 1, 1e-2) << "vertex " << j;
      EXPECT_LE(std::abs(gaps[j]), bound * c.D[j]) << "vertex " << j;
    }
}
