// Mortar coupling of two sides with the dual basis (mortar.h).

#include <deal.II/base/bounding_box.h>
#include <deal.II/base/exceptions.h>
#include <deal.II/base/quadrature_lib.h>

#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/identity_matrix.h>
#include <deal.II/lac/vector.h>

#include <deal.II/numerics/rtree.h>

#include "contact_pairs/mortar.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace ViscoContact
{
  namespace Mortar
  {
    namespace
    {
      // The unit normal of a segment from a to b: its tangent turned
      // clockwise.
      Tensor<1, 2>
      segment_normal(const Point<2> &a, const Point<2> &b)
      {
        const Tensor<1, 2> t = (b - a) / (b - a).norm();
        Tensor<1, 2>       n;
        n[0] = t[1];
        n[1] = -t[0];
        return n;
      }
    } // namespace



    // @sect4{Mortar::couple}
    //
    // Per slave segment (vertices a, b; x(xi) = x_a + xi (x_b - x_a), xi in
    // [0, 1], N_a = 1 - xi, N_b = xi) and master segment (vertices c, d):
    // the master vertices projected along the slave normal onto the slave
    // line, xi_c and xi_d (the projection keeps the tangential coordinate),
    // the overlap of [xi_c, xi_d] with [0, 1], and on it the master
    // parameter eta(xi) = (xi - xi_c) / (xi_d - xi_c), affine. The
    // integrands psi N^m are quadratic in xi there: two Gauss points.
    //
    // The dual basis psi_j = sum_k A_jk N_k of a segment is biorthogonal on
    // the part the master side covers, A = diag(d) m^{-1} with d_j = int N_j
    // and m_jk = int N_j N_k over that part: psi_a = 2 - 3 xi, psi_b =
    // 3 xi - 1 on a covered segment, and on one the master side ends in a
    // basis that keeps D_j = int psi_j = int N_j >= 0 and the linear fields
    // reproduced (the standard dual basis would give a D_j of either sign
    // there). Below 1% coverage, where m is nearly singular, the segment
    // takes the standard basis psi_j = N_j: D_j = int N_j still, the rows
    // still sum to D_j.
    Coupling<2>
    couple(const Side<2> &slave,
           const Side<2> &master,
           const double   search_distance)
    {
      Coupling<2>       coupling;
      const std::size_t n_slave = slave.vertices.size();
      coupling.D.assign(n_slave, 0.);
      coupling.M.assign(n_slave, {});
      coupling.normals.assign(n_slave, Tensor<1, 2>());
      const double gauss[2] = {-1 / std::sqrt(3.), 1 / std::sqrt(3.)};

      // The part of a slave segment one master segment covers.
      struct Overlap
      {
        double       low, high, xi_c, xi_d;
        unsigned int c, d;
      };
      // The master segments a slave segment can meet lie in its box
      // widened by the search distance (an R-tree of their boxes, as in
      // 3D); without a finite search distance every one is tried.
      std::vector<std::pair<BoundingBox<2>, unsigned int>> master_boxes;
      for (unsigned int g = 0; g < master.faces.size(); ++g)
        master_boxes.emplace_back(BoundingBox<2>(std::vector<Point<2>>{
                                    master.vertices[master.faces[g][0]],
                                    master.vertices[master.faces[g][1]]}),
                                  g);
      const bool                within_reach = std::isfinite(search_distance);
      const auto                master_tree  = pack_rtree(master_boxes);
      std::vector<unsigned int> candidates;
      for (const std::vector<unsigned int> &segment : slave.faces)
        {
          const unsigned int a = segment[0], b = segment[1];
          const Point<2>    &x_a    = slave.vertices[a];
          const Point<2>    &x_b    = slave.vertices[b];
          const double       length = (x_b - x_a).norm();
          AssertThrow(length > 0,
                      ExcMessage("A slave segment has length zero."));
          const Tensor<1, 2> tangent = (x_b - x_a) / length;
          const Tensor<1, 2> normal  = segment_normal(x_a, x_b);
          coupling.normals[a] += normal;
          coupling.normals[b] += normal;

          candidates.clear();
          if (within_reach)
            {
              BoundingBox<2> reach(std::vector<Point<2>>{x_a, x_b});
              reach.extend(search_distance);
              std::vector<std::pair<BoundingBox<2>, unsigned int>> near;
              master_tree.query(boost::geometry::index::intersects(reach),
                                std::back_inserter(near));
              for (const auto &[box, g] : near)
                candidates.push_back(g);
              // In the order of the faces, as without the tree (the sums
              // below then do not depend on the tree's order).
              std::sort(candidates.begin(), candidates.end());
            }
          else
            for (unsigned int g = 0; g < master.faces.size(); ++g)
              candidates.push_back(g);

          std::vector<Overlap> overlaps;
          for (const unsigned int g : candidates)
            {
              const unsigned int c = master.faces[g][0], d = master.faces[g][1];
              const Point<2>    &x_c = master.vertices[c];
              const Point<2>    &x_d = master.vertices[d];
              if ((x_d - x_c).norm() == 0
                  || normal * segment_normal(x_c, x_d) >= 0)
                continue;
              const double xi_c = (x_c - x_a) * tangent / length;
              const double xi_d = (x_d - x_a) * tangent / length;
              const double low  = std::max(0., std::min(xi_c, xi_d));
              const double high = std::min(1., std::max(xi_c, xi_d));
              if (high - low <= 1e-14)
                continue;
              // The distance of the master segment from the slave line
              // along the normal at the ends of the overlap.
              const double g_c = (x_c - x_a) * normal,
                           g_d = (x_d - x_a) * normal;
              double distance  = 0;
              for (const double xi : {low, high})
                distance = std::max(
                  distance,
                  std::abs(g_c + (g_d - g_c) * (xi - xi_c) / (xi_d - xi_c)));
              coupling.closest_distance
                = std::min(coupling.closest_distance, distance);
              if (distance <= search_distance)
                overlaps.push_back({low, high, xi_c, xi_d, c, d});
            }

          // d and m over the covered part, and the coefficients A.
          double covered = 0, d[2] = {0, 0}, m[2][2] = {{0, 0}, {0, 0}};
          for (const Overlap &overlap : overlaps)
            {
              covered += overlap.high - overlap.low;
              const double middle = (overlap.low + overlap.high) / 2,
                           half   = (overlap.high - overlap.low) / 2;
              for (const double offset : gauss)
                {
                  const double xi   = middle + offset * half;
                  const double N[2] = {1 - xi, xi};
                  for (unsigned int j = 0; j < 2; ++j)
                    {
                      d[j] += half * N[j];
                      for (unsigned int k = 0; k < 2; ++k)
                        m[j][k] += half * N[j] * N[k];
                    }
                }
            }
          double A[2][2] = {{1, 0}, {0, 1}};
          if (covered >= 0.01)
            {
              const double det = m[0][0] * m[1][1] - m[0][1] * m[1][0];
              A[0][0]          = d[0] * m[1][1] / det;
              A[0][1]          = -d[0] * m[0][1] / det;
              A[1][0]          = -d[1] * m[1][0] / det;
              A[1][1]          = d[1] * m[0][0] / det;
            }

          for (const Overlap &overlap : overlaps)
            {
              const double middle = (overlap.low + overlap.high) / 2,
                           half   = (overlap.high - overlap.low) / 2;
              for (const double offset : gauss)
                {
                  const double xi     = middle + offset * half;
                  const double weight = half * length;
                  const double eta
                    = (xi - overlap.xi_c) / (overlap.xi_d - overlap.xi_c);
                  const double       N[2]      = {1 - xi, xi};
                  const unsigned int vertex[2] = {a, b};
                  for (unsigned int v = 0; v < 2; ++v)
                    {
                      const double psi = A[v][0] * N[0] + A[v][1] * N[1];
                      coupling.D[vertex[v]] += weight * psi;
                      coupling.M[vertex[v]][overlap.c]
                        += weight * psi * (1 - eta);
                      coupling.M[vertex[v]][overlap.d] += weight * psi * eta;
                    }
                }
            }
        }
      for (Tensor<1, 2> &normal : coupling.normals)
        if (normal.norm() > 0)
          normal /= normal.norm();
      return coupling;
    }



    namespace
    {
      // The unit normal of a face in 3D, (x_1 - x_0) x (x_2 - x_0) for a
      // triangle and the cross product of the diagonals for a
      // quadrilateral, both in cyclic order.
      Tensor<1, 3>
      face_normal(const std::vector<Point<3>> &x)
      {
        const Tensor<1, 3> n = x.size() == 3
                                 ? cross_product_3d(x[1] - x[0], x[2] - x[0])
                                 : cross_product_3d(x[2] - x[0], x[3] - x[1]);
        return n / n.norm();
      }

      // The shape functions of a face at local coordinates s, t (Side).
      std::array<double, 4>
      shape_values(const unsigned int n_vertices, const Point<2> &st)
      {
        const double s = st[0], t = st[1];
        if (n_vertices == 3)
          return {{1 - s - t, s, t, 0}};
        return {{(1 - s) * (1 - t), s * (1 - t), s * t, (1 - s) * t}};
      }

      // The local coordinates of the point q of a triangle or quadrilateral
      // p in a plane: solved directly on a triangle, by Newton's method on
      // a quadrilateral (exact in one step on a parallelogram).
      Point<2>
      local_coordinates(const std::vector<Point<2>> &p, const Point<2> &q)
      {
        Point<2> st(1. / 3, 1. / 3);
        if (p.size() == 4)
          st = Point<2>(0.5, 0.5);
        for (unsigned int iteration = 0; iteration < 20; ++iteration)
          {
            const std::array<double, 4> N        = shape_values(p.size(), st);
            Tensor<1, 2>                residual = -q;
            for (unsigned int k = 0; k < p.size(); ++k)
              residual += N[k] * p[k];
            Tensor<2, 2> jacobian;
            if (p.size() == 3)
              for (unsigned int d = 0; d < 2; ++d)
                {
                  jacobian[d][0] = p[1][d] - p[0][d];
                  jacobian[d][1] = p[2][d] - p[0][d];
                }
            else
              for (unsigned int d = 0; d < 2; ++d)
                {
                  jacobian[d][0] = (1 - st[1]) * (p[1][d] - p[0][d])
                                   + st[1] * (p[2][d] - p[3][d]);
                  jacobian[d][1] = (1 - st[0]) * (p[3][d] - p[0][d])
                                   + st[0] * (p[2][d] - p[1][d]);
                }
            AssertThrow(std::abs(determinant(jacobian)) > 0,
                        ExcMessage("A contact face is collapsed: its local "
                                   "coordinates are not defined."));
            const Tensor<1, 2> step = invert(jacobian) * residual;
            st -= step;
            if (p.size() == 3 || step.norm() < 1e-14)
              return st;
          }
        AssertThrow(false,
                    ExcMessage("The local coordinates of a point on a "
                               "quadrilateral contact face did not converge "
                               "(a face too warped, or not convex, seen along "
                               "the other side's normal)."));
        return st;
      }

      // The signed area of a polygon in a plane (positive if
      // counterclockwise).
      double
      signed_area(const std::vector<Point<2>> &polygon)
      {
        double area = 0;
        for (unsigned int i = 0; i < polygon.size(); ++i)
          {
            const Point<2> &a = polygon[i];
            const Point<2> &b = polygon[(i + 1) % polygon.size()];
            area += a[0] * b[1] - a[1] * b[0];
          }
        return area / 2;
      }

      // The part of the polygon subject inside the convex polygon clip,
      // both counterclockwise (Sutherland and Hodgman).
      std::vector<Point<2>>
      clip_polygon(std::vector<Point<2>>        subject,
                   const std::vector<Point<2>> &clip)
      {
        for (unsigned int e = 0; e < clip.size() && !subject.empty(); ++e)
          {
            const Point<2>    &a    = clip[e];
            const Tensor<1, 2> edge = clip[(e + 1) % clip.size()] - a;
            // How far a point lies to the left of the edge (inside), times
            // the edge's length (only the sign and ratios of two are used:
            // a collapsed edge leaves every point inside).
            const auto inside = [&](const Point<2> &q) {
              return edge[0] * (q[1] - a[1]) - edge[1] * (q[0] - a[0]);
            };
            std::vector<Point<2>> kept;
            for (unsigned int i = 0; i < subject.size(); ++i)
              {
                const Point<2> &from   = subject[i];
                const Point<2> &to     = subject[(i + 1) % subject.size()];
                const double    h_from = inside(from), h_to = inside(to);
                if (h_from >= 0)
                  kept.push_back(from);
                if ((h_from >= 0) != (h_to >= 0))
                  kept.push_back(from + h_from / (h_from - h_to) * (to - from));
              }
            subject = std::move(kept);
          }
        return subject;
      }
    } // namespace



    // @sect4{Mortar::couple in 3D}
    //
    // Per slave face: its plane (centre c, unit normal n, orthonormal axes
    // e_1, e_2 with e_1 x e_2 = n), its vertices and each master face's
    // projected onto it, the master polygon (reversed: it faces the other
    // way, so it is clockwise seen from n) clipping the slave polygon, and
    // on the clipped polygon's triangles the points of QGaussSimplex<2>(3)
    // (degree 5) with the local coordinates of each face at them. The dual
    // basis is made biorthogonal on the covered part with these same
    // points, A = diag(d) m^{-1} as in 2D.
    Coupling<3>
    couple(const Side<3> &slave,
           const Side<3> &master,
           const double   search_distance)
    {
      Coupling<3>       coupling;
      const std::size_t n_slave = slave.vertices.size();
      coupling.D.assign(n_slave, 0.);
      coupling.M.assign(n_slave, {});
      coupling.normals.assign(n_slave, Tensor<1, 3>());
      const QGaussSimplex<2> rule(3);

      std::vector<std::vector<Point<3>>>                   master_faces;
      std::vector<Tensor<1, 3>>                            master_normals;
      std::vector<std::pair<BoundingBox<3>, unsigned int>> master_boxes;
      for (const std::vector<unsigned int> &face : master.faces)
        {
          std::vector<Point<3>> x;
          for (const unsigned int k : face)
            x.push_back(master.vertices[k]);
          master_normals.push_back(face_normal(x));
          master_boxes.emplace_back(BoundingBox<3>(x), master_faces.size());
          master_faces.push_back(std::move(x));
        }
      // The master faces a slave face can meet lie in its box widened by
      // the search distance: an R-tree of their boxes finds them, instead
      // of trying every master face against every slave face.
      const bool within_reach = std::isfinite(search_distance);
      const auto master_tree  = pack_rtree(master_boxes);

      // A quadrature point of a slave face: its weight, the slave shape
      // functions, the master face and its shape functions.
      struct FacePoint
      {
        double                weight;
        std::array<double, 4> N;
        unsigned int          master_face;
        std::array<double, 4> N_master;
      };
      for (const std::vector<unsigned int> &face : slave.faces)
        {
          const unsigned int    n = face.size();
          std::vector<Point<3>> x;
          Point<3>              centre;
          for (const unsigned int j : face)
            {
              x.push_back(slave.vertices[j]);
              centre += slave.vertices[j] / double(n);
            }
          const Tensor<1, 3> normal = face_normal(x);
          // The first axis along the longest edge (an edge may be
          // collapsed).
          Tensor<1, 3> e_1;
          for (unsigned int k = 0; k < n; ++k)
            if ((x[(k + 1) % n] - x[k]).norm() > e_1.norm())
              e_1 = x[(k + 1) % n] - x[k];
          e_1 -= (e_1 * normal) * normal;
          e_1 /= e_1.norm();
          const Tensor<1, 3> e_2      = cross_product_3d(normal, e_1);
          const auto         in_plane = [&](const Point<3> &y) {
            return Point<2>((y - centre) * e_1, (y - centre) * e_2);
          };
          for (const unsigned int j : face)
            coupling.normals[j] += normal;

          std::vector<Point<2>> slave_polygon;
          for (const Point<3> &y : x)
            slave_polygon.push_back(in_plane(y));
          const double face_area = signed_area(slave_polygon);
          AssertThrow(face_area > 0, ExcMessage("A slave face has area zero."));

          std::vector<unsigned int> candidates;
          if (within_reach)
            {
              BoundingBox<3> reach(x);
              reach.extend(search_distance);
              std::vector<std::pair<BoundingBox<3>, unsigned int>> near;
              master_tree.query(boost::geometry::index::intersects(reach),
                                std::back_inserter(near));
              for (const auto &[box, g] : near)
                candidates.push_back(g);
            }
          else
            for (unsigned int g = 0; g < master_faces.size(); ++g)
              candidates.push_back(g);

          std::vector<FacePoint> points;
          for (const unsigned int g : candidates)
            {
              if (normal * master_normals[g] >= 0)
                continue;
              std::vector<Point<2>> master_polygon;
              for (const Point<3> &y : master_faces[g])
                master_polygon.push_back(in_plane(y));
              std::vector<Point<2>> reversed(master_polygon.rbegin(),
                                             master_polygon.rend());
              if (signed_area(reversed) <= 1e-12 * face_area)
                continue; // seen edge-on
              const std::vector<Point<2>> overlap
                = clip_polygon(slave_polygon, reversed);
              if (overlap.size() < 3
                  || signed_area(overlap) <= 1e-12 * face_area)
                continue;
              // The distance of the master face from the slave plane along
              // the normal at the corners of the overlap.
              double distance = 0;
              for (const Point<2> &q : overlap)
                {
                  const std::array<double, 4> N_master
                    = shape_values(master_polygon.size(),
                                   local_coordinates(master_polygon, q));
                  double height = 0;
                  for (unsigned int k = 0; k < master_polygon.size(); ++k)
                    height
                      += N_master[k] * ((master_faces[g][k] - centre) * normal);
                  distance = std::max(distance, std::abs(height));
                }
              coupling.closest_distance
                = std::min(coupling.closest_distance, distance);
              if (distance > search_distance)
                continue;
              for (unsigned int t = 1; t + 1 < overlap.size(); ++t)
                {
                  const Tensor<1, 2> a  = overlap[t] - overlap[0],
                                     b  = overlap[t + 1] - overlap[0];
                  const double jacobian = a[0] * b[1] - a[1] * b[0];
                  for (unsigned int q = 0; q < rule.size(); ++q)
                    {
                      const Point<2> point = overlap[0] + rule.point(q)[0] * a
                                             + rule.point(q)[1] * b;
                      points.push_back(
                        {rule.weight(q) * jacobian,
                         shape_values(n,
                                      local_coordinates(slave_polygon, point)),
                         g,
                         shape_values(master_polygon.size(),
                                      local_coordinates(master_polygon,
                                                        point))});
                    }
                }
            }

          // d and m over the covered part, and the coefficients A.
          double             covered = 0;
          Vector<double>     d(n);
          FullMatrix<double> m(n, n), A{IdentityMatrix(n)};
          for (const FacePoint &point : points)
            {
              covered += point.weight;
              for (unsigned int j = 0; j < n; ++j)
                {
                  d[j] += point.weight * point.N[j];
                  for (unsigned int k = 0; k < n; ++k)
                    m(j, k) += point.weight * point.N[j] * point.N[k];
                }
            }
          if (covered >= 0.01 * face_area)
            {
              m.gauss_jordan();
              for (unsigned int j = 0; j < n; ++j)
                for (unsigned int k = 0; k < n; ++k)
                  A(j, k) = d[j] * m(j, k);
            }

          for (const FacePoint &point : points)
            {
              const std::vector<unsigned int> &master_face
                = master.faces[point.master_face];
              for (unsigned int j = 0; j < n; ++j)
                {
                  double psi = 0;
                  for (unsigned int k = 0; k < n; ++k)
                    psi += A(j, k) * point.N[k];
                  coupling.D[face[j]] += point.weight * psi;
                  for (unsigned int k = 0; k < master_face.size(); ++k)
                    coupling.M[face[j]][master_face[k]]
                      += point.weight * psi * point.N_master[k];
                }
            }
        }
      for (Tensor<1, 3> &normal : coupling.normals)
        if (normal.norm() > 0)
          normal /= normal.norm();
      return coupling;
    }



    // @sect4{Mortar::weighted_gaps}
    template <int dim>
    std::vector<double>
    weighted_gaps(const Coupling<dim>               &coupling,
                  const Side<dim>                   &slave,
                  const Side<dim>                   &master,
                  const std::vector<Tensor<1, dim>> &slave_displacement,
                  const std::vector<Tensor<1, dim>> &master_displacement)
    {
      AssertDimension(slave_displacement.size(), slave.vertices.size());
      AssertDimension(master_displacement.size(), master.vertices.size());
      std::vector<double> gaps(slave.vertices.size(), 0.);
      for (unsigned int j = 0; j < gaps.size(); ++j)
        {
          Tensor<1, dim> difference
            = -coupling.D[j] * (slave.vertices[j] + slave_displacement[j]);
          for (const auto &[k, m] : coupling.M[j])
            difference += m * (master.vertices[k] + master_displacement[k]);
          gaps[j] = coupling.normals[j] * difference;
        }
      return gaps;
    }



    template std::vector<double>
    weighted_gaps(const Coupling<2> &,
                  const Side<2> &,
                  const Side<2> &,
                  const std::vector<Tensor<1, 2>> &,
                  const std::vector<Tensor<1, 2>> &);
    template std::vector<double>
    weighted_gaps(const Coupling<3> &,
                  const Side<3> &,
                  const Side<3> &,
                  const std::vector<Tensor<1, 3>> &,
                  const std::vector<Tensor<1, 3>> &);
  } // namespace Mortar
} // namespace ViscoContact
