// The dense contact problem on the contact nodes for fixed pieces: the heart
// of the condensed back end (doc/model.md, section 2, "(a) Condensed").
// Given the compliance S = N K^{-1} N^T and the free normal displacements d,
// it finds the nodal forces z that put every node on its piece, and
// r = d - S z.

#include <deal.II/base/exceptions.h>

#include <deal.II/lac/exceptions.h>

#include "back_ends/condensed_system.h"

#include <utility>

#include <algorithm>
#include <cmath>

namespace ViscoContact
{
  namespace
  {
    // The largest defect a solve corrected for changed rows may leave, after
    // at most one step of iterative refinement (a factorisation leaves a few
    // 1e-15).
    constexpr double largest_updated_defect = 1e-14;

    // The slope, relative to a node's stiffness, below which a piece is
    // flat at the node (is_flat()).
    constexpr double flat_slope = 1e-13;
  } // namespace



  // @sect4{CondensedContactSystem::reinit}
  //
  // A new compliance (a new operator) invalidates the dense factorisation:
  // clearing the rows it was made for makes the next solve() factorise
  // again, even if the pieces have not changed.
  void
  CondensedContactSystem::reinit(const ContactLaws         &laws,
                                 FullMatrix<double>         compliance,
                                 const std::vector<double> &weights)
  {
    AssertDimension(compliance.m(), weights.size());
    AssertDimension(compliance.n(), weights.size());
    contact_laws = laws;
    S            = std::move(compliance);
    w            = weights;
    factorized_rows.clear();
    updated_rows.clear();
  }



  // @sect4{The rows of the dense problem}
  //
  // Derivation of the rows: on a sloped piece z_i = w_i (o + s r_i) with
  // r_i = d_i - (S z)_i gives z_i / (w_i s) + (S z)_i = d_i + o / s; on a
  // vertical piece at beta, r_i = beta gives (S z)_i = d_i - beta; on a flat
  // piece (s = 0) the force z_i = w_i o is known, written as the row
  // |S_ii| z_i = |S_ii| w_i o (the scale of the other rows). With softening
  // slopes (s < 0) the diagonal 1 / (w_i s) is negative and the matrix, though
  // symmetric for symmetric S, need not be definite; for a tangent S is not
  // even symmetric. Hence a general LU factorisation with pivoting.
  CondensedContactSystem::Row
  CondensedContactSystem::row(const unsigned int     node,
                              const ContactLawPiece &piece) const
  {
    if (piece.vertical)
      return {true, 0.};
    if (!is_flat(node, piece))
      return {true, 1. / (w[node] * piece.slope)};
    const double scale = std::abs(S(node, node));
    return {false, scale > 0 ? scale : 1.};
  }



  // A piece counts as flat at a node (a known force w_i o) where its slope
  // is below flat_slope times the node's stiffness k_i = 1 / (w_i S_ii): the
  // force w_i s r_i it leaves out is then below the rounding of the forces
  // the body carries, while 1 / (w_i s) would overflow the rows for slopes
  // like 1e-300.
  bool
  CondensedContactSystem::is_flat(const unsigned int     node,
                                  const ContactLawPiece &piece) const
  {
    return !piece.vertical
           && std::abs(piece.slope) * w[node] * std::abs(S(node, node))
                <= flat_slope;
  }



  // @sect4{CondensedContactSystem::factorize}
  //
  // The base for the given pieces. Ordered so that the nodes of unknown
  // force come first, its matrix is block triangular: the rows of known
  // forces are diagonal, so only the block of the unknown ones is
  // factorised (LAPACK's LU with partial pivoting); nodes out of contact
  // cost nothing. The dense problem stays on one BLAS thread: a threaded
  // BLAS keeps its threads spinning for a while after each call, competing
  // with the threads of the solves and the stress update that follow (by
  // hand, 3D cube: two threads saved 4 ms of the dense work per step at 1056
  // contact nodes, within the noise of a 175 ms step, and made the step
  // slower at 272).
  void
  CondensedContactSystem::factorize(const std::vector<ContactLawPiece> &pieces)
  {
    const unsigned int m = w.size();
    factorized_rows.resize(m);
    unknown_nodes.clear();
    known_nodes.clear();
    for (unsigned int i = 0; i < m; ++i)
      {
        factorized_rows[i] = row(i, pieces[i]);
        (factorized_rows[i].unknown_force ? unknown_nodes : known_nodes)
          .push_back(i);
      }
    const unsigned int n = unknown_nodes.size();
    factorized_matrix.reinit(n, n);
    for (unsigned int a = 0; a < n; ++a)
      {
        for (unsigned int b = 0; b < n; ++b)
          factorized_matrix(a, b) = S(unknown_nodes[a], unknown_nodes[b]);
        factorized_matrix(a, a) += factorized_rows[unknown_nodes[a]].diagonal;
      }
    if (n > 0)
      {
        factorized_matrix.compute_lu_factorization();
        ++factorization_count;
      }
    // Nothing has changed against the new base yet.
    responses.clear();
    response_of_node.assign(m, -1);
    changed_nodes.clear();
    changed_rows.clear();
    updated_rows = factorized_rows;
  }



  // x = M_0^{-1} x with the base matrix M_0: the known forces first, then
  // the unknown ones from the factorised block, with the known forces'
  // displacements moved to the right-hand side.
  void
  CondensedContactSystem::solve_with_factorization(Vector<double> &x) const
  {
    for (const unsigned int j : known_nodes)
      x[j] /= factorized_rows[j].diagonal;
    const unsigned int n = unknown_nodes.size();
    if (n == 0)
      return;
    Vector<double> y(n);
    for (unsigned int a = 0; a < n; ++a)
      {
        double value = x[unknown_nodes[a]];
        for (const unsigned int j : known_nodes)
          value -= S(unknown_nodes[a], j) * x[j];
        y[a] = value;
      }
    factorized_matrix.solve(y);
    for (unsigned int a = 0; a < n; ++a)
      x[unknown_nodes[a]] = y[a];
  }



  // @sect4{Changed rows: the Woodbury formula}
  //
  // When the rows of k nodes (the set J) differ from the base's, the matrix
  // is M = M_0 + E_J V, with E_J the unit columns of those nodes and V the
  // k x m differences of their rows. Then
  //   M^{-1} b = y - Y (I + V Y)^{-1} V y,   y = M_0^{-1} b,
  //   Y = M_0^{-1} E_J,
  // which costs k solves with the base for Y (once per node and base: the
  // responses are kept), the LU factorisation of the k x k matrix I + V Y,
  // and per solve one solve with the base and O(k m). A factorisation
  // costs (2/3) n^3 for n nodes of unknown force, the responses 2 n^2 each
  // (in one solve with many right-hand sides), so the base is replaced once
  // more than a quarter of the rows (at least 16) have changed.
  //
  // The responses of the given nodes to a unit entry at their own row,
  // M_0^{-1} e_j, by one solve with as many right-hand sides.
  void
  CondensedContactSystem::compute_responses(
    const std::vector<unsigned int> &nodes)
  {
    const unsigned int       m = w.size(), n = unknown_nodes.size();
    LAPACKFullMatrix<double> right_hand_sides(n, nodes.size());
    for (unsigned int c = 0; c < nodes.size(); ++c)
      {
        const unsigned int j = nodes[c];
        if (factorized_rows[j].unknown_force)
          right_hand_sides(std::lower_bound(unknown_nodes.begin(),
                                            unknown_nodes.end(),
                                            j)
                             - unknown_nodes.begin(),
                           c)
            = 1.;
        else
          for (unsigned int a = 0; a < n; ++a)
            right_hand_sides(a, c)
              = -S(unknown_nodes[a], j) / factorized_rows[j].diagonal;
      }
    if (n > 0 && nodes.size() > 0)
      factorized_matrix.solve(right_hand_sides);
    for (unsigned int c = 0; c < nodes.size(); ++c)
      {
        const unsigned int j = nodes[c];
        Vector<double>     response(m);
        for (unsigned int a = 0; a < n; ++a)
          response[unknown_nodes[a]] = right_hand_sides(a, c);
        if (!factorized_rows[j].unknown_force)
          response[j] = 1. / factorized_rows[j].diagonal;
        response_of_node[j] = responses.size();
        responses.push_back(std::move(response));
      }
  }



  // (V x)_a for the a-th changed row: its new row minus the base's, times
  // x. Rows differ by their diagonal and, where a node's force turned from
  // known to unknown or back, by the row of S.
  double
  CondensedContactSystem::changed_row_times(const unsigned int    a,
                                            const Vector<double> &x) const
  {
    const unsigned int i      = changed_nodes[a];
    const Row         &now    = changed_rows[a];
    const Row         &before = factorized_rows[i];
    double             result = (now.diagonal - before.diagonal) * x[i];
    if (now.unknown_force != before.unknown_force)
      {
        double row_of_S_times_x = 0;
        for (unsigned int j = 0; j < x.size(); ++j)
          row_of_S_times_x += S(i, j) * x[j];
        result += (now.unknown_force ? 1. : -1.) * row_of_S_times_x;
      }
    return result;
  }



  // The changed rows for the given pieces, their responses and the LU
  // factorisation of I + V Y; false if so many rows have changed that the
  // base should be replaced instead (also when the kept responses would
  // grow beyond twice that many).
  bool
  CondensedContactSystem::update_changed_rows(
    const std::vector<ContactLawPiece> &pieces)
  {
    const unsigned int m = w.size();
    changed_nodes.clear();
    changed_rows.clear();
    unsigned int     n_unknown = 0;
    std::vector<Row> rows(m);
    for (unsigned int i = 0; i < m; ++i)
      {
        const Row now = rows[i] = row(i, pieces[i]);
        n_unknown += now.unknown_force;
        if (!(now == factorized_rows[i]))
          {
            changed_nodes.push_back(i);
            changed_rows.push_back(now);
          }
      }
    std::vector<unsigned int> without_response;
    for (const unsigned int j : changed_nodes)
      if (response_of_node[j] < 0)
        without_response.push_back(j);
    const unsigned int k            = changed_nodes.size(),
                       most_changes = std::max(16u, n_unknown / 4);
    if (k > most_changes
        || responses.size() + without_response.size() > 2 * most_changes)
      return false;

    compute_responses(without_response);
    capacitance.reinit(k, k);
    for (unsigned int b = 0; b < k; ++b)
      {
        const Vector<double> &response
          = responses[response_of_node[changed_nodes[b]]];
        for (unsigned int a = 0; a < k; ++a)
          capacitance(a, b)
            = (a == b ? 1. : 0.) + changed_row_times(a, response);
      }
    // A singular I + V Y means a singular matrix of the pieces, or a
    // correction that cancelled all digits: factorising the pieces' own
    // matrix tells which.
    if (k > 0)
      try
        {
          capacitance.compute_lu_factorization();
        }
      catch (const LACExceptions::ExcSingular &)
        {
          return false;
        }
    updated_rows = std::move(rows);
    return true;
  }



  // x = M^{-1} x for the matrix of the pieces last updated for: a solve
  // with the base, corrected for the changed rows.
  void
  CondensedContactSystem::apply_inverse(Vector<double> &x) const
  {
    solve_with_factorization(x);
    const unsigned int k = changed_nodes.size();
    if (k == 0)
      return;
    Vector<double> correction(k);
    for (unsigned int a = 0; a < k; ++a)
      correction[a] = changed_row_times(a, x);
    capacitance.solve(correction);
    for (unsigned int b = 0; b < k; ++b)
      x.add(-correction[b], responses[response_of_node[changed_nodes[b]]]);
  }



  // @sect4{CondensedContactSystem::solve}
  //
  // The matrix depends on the rows of the pieces and on S only, not on d, so
  // a solve with the same rows as the last one reuses everything: O(m^2). Each
  // time step starts from the pieces of the previous one, so a step that needs
  // a single active-set iteration (most steps once the contact zone has formed,
  // doc/model.md, section 2) factorises nothing at all; when the pieces of some
  // nodes change, the Woodbury correction above takes them into account without
  // a new factorisation while they are few.
  double
  CondensedContactSystem::solve(const std::vector<ContactLawPiece> &pieces,
                                const Vector<double>               &d,
                                Vector<double>                     &r,
                                Vector<double>                     &z)
  {
    const unsigned int m = w.size();
    AssertDimension(pieces.size(), m);
    AssertDimension(d.size(), m);
    // Only the rows enter the matrix: a piece that moved up by a memory
    // pressure, or whose slope changed by less than a flat one, keeps its
    // row and the kept factorisation as it is.
    bool same_rows = !factorized_rows.empty();
    for (unsigned int i = 0; i < m && same_rows; ++i)
      same_rows = row(i, pieces[i]) == updated_rows[i];
    if (factorized_rows.empty() || (!same_rows && !update_changed_rows(pieces)))
      factorize(pieces);

    // The right-hand side of each row: d_i plus the piece's constant,
    // -beta on a vertical piece and o / s on a sloped one; |S_ii| w_i o for a
    // known force.
    z.reinit(m);
    for (unsigned int i = 0; i < m; ++i)
      {
        const ContactLawPiece &piece = pieces[i];
        if (piece.vertical)
          z[i] = d[i] - piece.r_lower;
        else if (!is_flat(i, piece))
          z[i] = d[i] + piece.intercept / piece.slope;
        else
          z[i] = row(i, piece).diagonal * w[i] * piece.intercept;
      }
    apply_inverse(z);

    // The residual of the rows for the forces z, after setting the known
    // forces exactly and computing r = d - S z: for a node of unknown force
    // how far r_i is from the piece's relation, r_i = beta on a vertical
    // piece, r_i = (z_i / w_i - o) / s on a sloped one (this is the row's
    // residual, which the refinement below corrects), zero for a known
    // force. The defect is its largest entry relative to the size of the
    // normal displacements involved (the larger of |d|_inf and the gap; 1 if
    // both vanish), the condensed back end's "linear residual".
    //
    // On a nearly flat piece the row's residual divides the rounding of the
    // pressure z_i / w_i by the small slope s (c2 = 1e-6 left 6e-8 of
    // rounding, and the active set could never meet its tolerance). The
    // defect therefore measures the row in the node's own stiffness: the
    // pressure residual z_i / w_i - o - s r_i = -s residual_i divided by
    // |s| + k_i, where k_i = 1 / (w_i S_ii) is the pressure the body needs
    // to move the node by a unit. For |s| >> k_i this is the residual in r;
    // for s -> 0 it is the pressure's residual in displacement units, the
    // accuracy the body's stiffness allows.
    double scale = std::max(d.linfty_norm(), contact_laws.largest_gap());
    if (!(scale > 0))
      scale = 1;
    Vector<double> residual(m);
    const auto     defect_of_forces = [&]() {
      for (unsigned int i = 0; i < m; ++i)
        {
          const ContactLawPiece &piece = pieces[i];
          if (is_flat(i, piece))
            z[i] = w[i] * piece.intercept;
        }
      r.reinit(m);
      S.vmult(r, z);
      r.sadd(-1., 1., d);
      double largest = 0;
      for (unsigned int i = 0; i < m; ++i)
        {
          const ContactLawPiece &piece = pieces[i];
          const bool             flat  = is_flat(i, piece);
          residual[i]            = piece.vertical ? r[i] - piece.r_lower
                                       : !flat
                                         ? r[i] - (z[i] / w[i] - piece.intercept) / piece.slope
                                         : 0.;
          const double stiffness = S(i, i) > 0 ? 1. / (w[i] * S(i, i)) : 0.;
          const double weight
            = piece.vertical || flat
                    ? 1.
                    : std::abs(piece.slope) / (std::abs(piece.slope) + stiffness);
          largest = std::max(largest, std::abs(residual[i]) * weight);
        }
      return largest / scale;
    };
    double defect = defect_of_forces();

    // A factorisation leaves a defect of a few 1e-15; the Woodbury
    // correction may leave a hundred times more (3D cube, 1056 nodes), which
    // one step of iterative refinement removes. Should more remain (the
    // correction cancels digits where a changed row's diagonal was much
    // larger than the compliance, as on a nearly flat piece), the pieces'
    // own matrix is factorised.
    if (!changed_nodes.empty())
      {
        ++updated_solve_count;
        if (!(defect <= largest_updated_defect))
          {
            apply_inverse(residual);
            z += residual;
            defect = defect_of_forces();
          }
        if (!(defect <= largest_updated_defect))
          {
            factorize(pieces);
            return solve(pieces, d, r, z);
          }
      }
    return defect;
  }



  void
  CondensedContactSystem::forget_factorization()
  {
    factorized_rows.clear();
    updated_rows.clear();
  }



  // The compliance of all contact nodes; the condensed back end's
  // apply_compliance() multiplies with its rows.
  const FullMatrix<double> &
  CondensedContactSystem::compliance() const
  {
    return S;
  }



  // How often the dense matrix was factorised: the unit tests check with it
  // that unchanged pieces reuse the factorisation.
  unsigned int
  CondensedContactSystem::n_factorizations() const
  {
    return factorization_count;
  }



  unsigned int
  CondensedContactSystem::n_updated_solves() const
  {
    return updated_solve_count;
  }
} // namespace ViscoContact
