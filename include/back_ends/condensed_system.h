#ifndef viscoplastic_contact_condensed_system_h
#define viscoplastic_contact_condensed_system_h

#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/lapack_full_matrix.h>
#include <deal.II/lac/vector.h>

#include "contact_law.h"

#include <optional>
#include <vector>

namespace ViscoContact
{
  using namespace dealii;

  // @sect3{The contact problem condensed to the contact nodes}
  //
  // With the operator K factorised, the displacement of a step problem is
  // u = K^{-1} (b - N^T z), N taking u to its normal components r = N u at
  // the m contact nodes and z the nodal normal forces. Hence
  //   r = d - S z,   d = N K^{-1} b,   S = N K^{-1} N^T (m x m),
  // and for fixed pieces of the contact law the nodal equations are linear
  // in z alone: a node on a sloped piece (slope s, intercept o) has
  // z_i = w_i (o + s r_i), i.e. the row
  //   z_i / (w_i s) + (S z)_i = d_i + o / s,
  // a node on a vertical piece at r = beta has (S z)_i = d_i - beta, and a
  // node on a flat piece (s = 0) has the known force z_i = w_i o.
  //
  // A node's row depends on its own piece only. The dense matrix of the
  // rows is factorised for the pieces of one iteration (the base) and kept;
  // when some nodes move to pieces with other rows, the matrix changes in
  // those rows only, and the solve corrects the base's with a small dense
  // system on the changed rows (the Sherman-Morrison-Woodbury formula)
  // instead of factorising again, until so many rows have changed that a
  // new factorisation is cheaper.
  class CondensedContactSystem
  {
  public:
    // The law, the contact compliance S (taken over: pass a temporary or
    // std::move, so that m^2 doubles are not copied) and the lumped weights
    // of all m contact nodes.
    void
    reinit(const ContactLaws         &laws,
           FullMatrix<double>         compliance,
           const std::vector<double> &weights);

    // z and r = d - S z for the pieces of all nodes, as they act at each
    // node (a piece of the law, scaled by the node's bonding and moved up
    // by its memory pressure: the laws of two nodes on the same piece may
    // differ), and the free normal displacements d = N K^{-1} b. Returns
    // how far the nodes are from the linear equations of their pieces
    // (rounding), relative to the size of the normal displacements
    // involved.
    double
    solve(const std::vector<ContactLawPiece> &node_pieces,
          const Vector<double>               &free_normal_displacement,
          Vector<double>                     &r,
          Vector<double>                     &z);

    const FullMatrix<double> &
    compliance() const;
    // Drops the kept factorisation: the next solve factorises its pieces'
    // matrix afresh, as the first solve after reinit() does.
    void
    forget_factorization();
    // How often the dense matrix was factorised, and how often a solve
    // corrected a kept factorisation for changed rows instead.
    unsigned int
    n_factorizations() const;
    unsigned int
    n_updated_solves() const;

  private:
    // Row i of the dense matrix: S(i, :) + diagonal e_i^T for a node whose
    // force is unknown (diagonal 1 / (w_i s) on a sloped piece, 0 on a
    // vertical one), diagonal e_i^T alone for a node whose force is known
    // (diagonal |S(i, i)|, the scale of the other rows, or 1 if zero).
    struct Row
    {
      bool   unknown_force;
      double diagonal;
      bool
      operator==(const Row &other) const
      {
        return unknown_force == other.unknown_force
               && diagonal == other.diagonal;
      }
    };
    Row
    row(const unsigned int node, const ContactLawPiece &piece) const;
    bool
    is_flat(const unsigned int node, const ContactLawPiece &piece) const;

    void
    factorize(const std::vector<ContactLawPiece> &pieces);
    void
    solve_with_factorization(Vector<double> &x) const;
    void
    compute_responses(const std::vector<unsigned int> &nodes);
    double
    changed_row_times(const unsigned int a, const Vector<double> &x) const;
    bool
    update_changed_rows(const std::vector<ContactLawPiece> &pieces);
    void
    apply_inverse(Vector<double> &x) const;

    ContactLaws         contact_laws;
    FullMatrix<double>  S;
    std::vector<double> w;

    // The base: the rows it was factorised for, its nodes of unknown force
    // (row and column a of factorized_matrix belong to unknown_nodes[a]),
    // those of known force, and the LU factorisation of the block of the
    // unknown ones (the rows of known forces are diagonal and need none).
    std::vector<Row>          factorized_rows;
    std::vector<unsigned int> unknown_nodes, known_nodes;
    LAPACKFullMatrix<double>  factorized_matrix;

    // Since the base: the responses M_0^{-1} e_j of the base matrix M_0 to
    // a unit entry at node j, kept for every node whose row has changed in
    // some solve (response_of_node[j], or -1), the nodes whose rows differ
    // now, their new rows, and the LU factorisation of the small matrix
    // I + V Y of the Woodbury formula (V: the changes of those rows, Y: the
    // responses) for the rows it was built for.
    std::vector<Vector<double>> responses;
    std::vector<int>            response_of_node;
    std::vector<unsigned int>   changed_nodes;
    std::vector<Row>            changed_rows;
    LAPACKFullMatrix<double>    capacitance;
    std::vector<Row>            updated_rows;

    unsigned int factorization_count = 0;
    unsigned int updated_solve_count = 0;
  };
} // namespace ViscoContact

#endif
