#ifndef viscoplastic_contact_stress_point_transfer_h
#define viscoplastic_contact_stress_point_transfer_h

#include <deal.II/base/quadrature.h>

#include <deal.II/lac/full_matrix.h>

#include <vector>

namespace ViscoContact
{
  using namespace dealii;

  // @sect3{Transfer of stress-point data between a cell and its children}
  //
  // On a hypercube the 2^dim Gauss points of a cell form a tensor grid, so
  // their values define a unique Q1 (tensor-product multilinear) polynomial on
  // the reference cell. When the mesh changes (mesh/mesh_adaptation.cc):
  //  - refinement: each child's Gauss values are the parent's Q1 interpolant
  //    evaluated at the child's Gauss points;
  //  - coarsening: the parent's Gauss values are those of the least-squares
  //    Q1 fit of the 2^dim x 2^dim children's values.
  // Both are exact for Q1 fields in the reference coordinates of the parent
  // (on an affine cell: for fields linear in space), and coarsening undoes
  // refinement. Data per cell: n_q x n_fields doubles, point by point
  // (values[q * n_fields + f]).
  template <int dim>
  class StressPointTransfer
  {
  public:
    // quadrature: the 2^dim-point Gauss rule of the cells' stress points.
    StressPointTransfer(const Quadrature<dim> &quadrature,
                        const unsigned int     n_fields);

    // The values of the 2^dim children (in deal.II's child order) from
    // those of the parent.
    std::vector<std::vector<double>>
    refine(const std::vector<double> &parent) const;

    // The values of the parent from those of its children.
    std::vector<double>
    coarsen(const std::vector<std::vector<double>> &children) const;

  private:
    const unsigned int n_q;
    const unsigned int n_fields;
    // child_matrices[c](q, j): the parent's Lagrange function of point j at
    // the child's point q; fit(j, c * n_q + q): the least-squares operator.
    std::vector<FullMatrix<double>> child_matrices;
    FullMatrix<double>              fit;
  };
} // namespace ViscoContact

#endif
