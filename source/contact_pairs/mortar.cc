// Mortar coupling of two sides in 2D with the dual basis (mortar.h).

#include <deal.II/base/exceptions.h>

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
    Coupling
    couple(const Side &slave, const Side &master, const double search_distance)
    {
      Coupling          coupling;
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
      for (const auto &[a, b] : slave.segments)
        {
          const Point<2> &x_a    = slave.vertices[a];
          const Point<2> &x_b    = slave.vertices[b];
          const double    length = (x_b - x_a).norm();
          AssertThrow(length > 0,
                      ExcMessage("A slave segment has length zero."));
          const Tensor<1, 2> tangent = (x_b - x_a) / length;
          const Tensor<1, 2> normal  = segment_normal(x_a, x_b);
          coupling.normals[a] += normal;
          coupling.normals[b] += normal;

          std::vector<Overlap> overlaps;
          for (const auto &[c, d] : master.segments)
            {
              const Point<2> &x_c = master.vertices[c];
              const Point<2> &x_d = master.vertices[d];
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



    // @sect4{Mortar::weighted_gaps}
    std::vector<double>
    weighted_gaps(const Coupling                  &coupling,
                  const Side                      &slave,
                  const Side                      &master,
                  const std::vector<Tensor<1, 2>> &slave_displacement,
                  const std::vector<Tensor<1, 2>> &master_displacement)
    {
      AssertDimension(slave_displacement.size(), slave.vertices.size());
      AssertDimension(master_displacement.size(), master.vertices.size());
      std::vector<double> gaps(slave.vertices.size(), 0.);
      for (unsigned int j = 0; j < gaps.size(); ++j)
        {
          Tensor<1, 2> difference
            = -coupling.D[j] * (slave.vertices[j] + slave_displacement[j]);
          for (const auto &[k, m] : coupling.M[j])
            difference += m * (master.vertices[k] + master_displacement[k]);
          gaps[j] = coupling.normals[j] * difference;
        }
      return gaps;
    }
  } // namespace Mortar
} // namespace ViscoContact
