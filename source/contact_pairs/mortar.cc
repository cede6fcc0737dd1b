// Mortar coupling of two sides in 2D with the dual basis (mortar.h).

#include <deal.II/base/exceptions.h>

#include "contact_pairs/mortar.h"

#include <algorithm>
#include <cmath>

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
    // [0, 1], N_a = 1 - xi, N_b = xi, psi_a = 2 - 3 xi, psi_b = 3 xi - 1)
    // and master segment (vertices c, d): the master vertices projected
    // along the slave normal onto the slave line, xi_c and xi_d (the
    // projection keeps the tangential coordinate), the overlap of [xi_c,
    // xi_d] with [0, 1], and on it the master parameter eta(xi) = (xi -
    // xi_c) / (xi_d - xi_c), affine. The integrands psi N^m are quadratic in
    // xi there: two Gauss points.
    Coupling
    couple(const Side &slave, const Side &master)
    {
      Coupling          coupling;
      const std::size_t n_slave = slave.vertices.size();
      coupling.D.assign(n_slave, 0.);
      coupling.M.assign(n_slave, {});
      coupling.normals.assign(n_slave, Tensor<1, 2>());

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
              const double middle = (low + high) / 2, half = (high - low) / 2;
              for (const double offset :
                   {-1 / std::sqrt(3.), 1 / std::sqrt(3.)})
                {
                  const double       xi        = middle + offset * half;
                  const double       weight    = half * length;
                  const double       eta       = (xi - xi_c) / (xi_d - xi_c);
                  const double       psi[2]    = {2 - 3 * xi, 3 * xi - 1};
                  const unsigned int vertex[2] = {a, b};
                  for (unsigned int v = 0; v < 2; ++v)
                    {
                      coupling.D[vertex[v]] += weight * psi[v];
                      coupling.M[vertex[v]][c] += weight * psi[v] * (1 - eta);
                      coupling.M[vertex[v]][d] += weight * psi[v] * eta;
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
