// The Q1 transfer of stress-point data between a hypercube cell and its
// children (stress_point_transfer.h).

#include <deal.II/base/exceptions.h>
#include <deal.II/base/geometry_info.h>

#include "stress_point_transfer.h"

#include <cmath>

namespace ViscoContact
{
  // @sect4{StressPointTransfer::StressPointTransfer}
  //
  // The Lagrange basis of the 2^dim Gauss points is the tensor product of the
  // two 1D Lagrange polynomials through the 1D Gauss points g_0 < g_1; point
  // q of the rule has the 1D indices (q & 1, (q >> 1) & 1, ...) since deal.II's
  // tensor-product rules run through x fastest. Child c occupies the part of
  // the parent given by GeometryInfo::child_to_cell_coordinates (isotropic
  // refinement), so child_matrices[c](q, j) = L_j(child_to_cell(p_q, c)).
  // Stacking them gives the matrix A (2^dim n_q rows) that maps the parent's
  // Gauss values to the children's; the least-squares fit is
  // (A^T A)^{-1} A^T. The children's points form a 4^dim tensor grid, on
  // which a Q1 function vanishing everywhere is zero: A has full column rank
  // and A^T A is invertible.
  template <int dim>
  StressPointTransfer<dim>::StressPointTransfer(
    const Quadrature<dim> &quadrature,
    const unsigned int     n_fields)
    : n_q(quadrature.size())
    , n_fields(n_fields)
  {
    AssertThrow(n_q == GeometryInfo<dim>::vertices_per_cell,
                ExcMessage("The Q1 transfer of stress-point data needs the "
                           "2^dim Gauss points of a hypercube."));
    const double g[2]        = {quadrature.point(0)[0], quadrature.point(1)[0]};
    const auto   lagrange_1d = [&](const unsigned int i, const double x) {
      return (x - g[1 - i]) / (g[i] - g[1 - i]);
    };
    const auto lagrange = [&](const unsigned int j, const Point<dim> &x) {
      double value = 1;
      for (unsigned int d = 0; d < dim; ++d)
        value *= lagrange_1d((j >> d) & 1, x[d]);
      return value;
    };

    const unsigned int n_children = GeometryInfo<dim>::max_children_per_cell;
    child_matrices.assign(n_children, FullMatrix<double>(n_q, n_q));
    FullMatrix<double> A(n_children * n_q, n_q);
    for (unsigned int c = 0; c < n_children; ++c)
      for (unsigned int q = 0; q < n_q; ++q)
        {
          const Point<dim> x
            = GeometryInfo<dim>::child_to_cell_coordinates(quadrature.point(q),
                                                           c);
          for (unsigned int j = 0; j < n_q; ++j)
            A(c * n_q + q, j) = child_matrices[c](q, j) = lagrange(j, x);
        }
    FullMatrix<double> normal(n_q, n_q);
    A.Tmmult(normal, A);
    normal.gauss_jordan();
    fit.reinit(n_q, n_children * n_q);
    normal.mTmult(fit, A);
  }



  template <int dim>
  std::vector<std::vector<double>>
  StressPointTransfer<dim>::refine(const std::vector<double> &parent) const
  {
    AssertDimension(parent.size(), n_q * n_fields);
    std::vector<std::vector<double>> children(
      child_matrices.size(),
      std::vector<double>(n_q * n_fields, 0.));
    for (unsigned int c = 0; c < child_matrices.size(); ++c)
      for (unsigned int q = 0; q < n_q; ++q)
        for (unsigned int j = 0; j < n_q; ++j)
          for (unsigned int f = 0; f < n_fields; ++f)
            children[c][q * n_fields + f]
              += child_matrices[c](q, j) * parent[j * n_fields + f];
    return children;
  }



  template <int dim>
  std::vector<double>
  StressPointTransfer<dim>::coarsen(
    const std::vector<std::vector<double>> &children) const
  {
    AssertDimension(children.size(), child_matrices.size());
    std::vector<double> parent(n_q * n_fields, 0.);
    for (unsigned int c = 0; c < children.size(); ++c)
      {
        AssertDimension(children[c].size(), n_q * n_fields);
        for (unsigned int q = 0; q < n_q; ++q)
          for (unsigned int j = 0; j < n_q; ++j)
            for (unsigned int f = 0; f < n_fields; ++f)
              parent[j * n_fields + f]
                += fit(j, c * n_q + q) * children[c][q * n_fields + f];
      }
    return parent;
  }



  template class StressPointTransfer<2>;
  template class StressPointTransfer<3>;
} // namespace ViscoContact
