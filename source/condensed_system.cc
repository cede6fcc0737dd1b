// The dense contact problem on the contact nodes for fixed pieces: the heart
// of the condensed back end (doc/model.md, section 2, "(a) Condensed").
// Given the compliance S = N K^{-1} N^T and the free normal displacements d,
// it finds the nodal forces z that put every node on its piece, and
// r = d - S z.

#include <deal.II/base/exceptions.h>

#include "condensed_system.h"

#include <utility>

#include <algorithm>
#include <cmath>

namespace ViscoContact
{
  // @sect4{CondensedContactSystem::reinit}
  //
  // A new compliance (a new operator) invalidates the dense factorisation:
  // clearing the remembered pieces makes the next solve() factorise again,
  // even if the pieces have not changed.
  void
  CondensedContactSystem::reinit(const ContactLaw          &law,
                                 FullMatrix<double>         compliance,
                                 const std::vector<double> &weights)
  {
    AssertDimension(compliance.m(), weights.size());
    AssertDimension(compliance.n(), weights.size());
    contact_law.emplace(law);
    S = std::move(compliance);
    w = weights;
    factorized_pieces.clear();
  }



  // @sect4{CondensedContactSystem::solve}
  //
  // The known forces first, then the right-hand side of the unknown ones,
  // one dense solve, and r = d - S z. The defect is what rounding leaves of
  // the pieces' equations; it is the condensed back end's "linear residual".
  //
  // Derivation of the rows: on a sloped piece z_i = w_i (o + s r_i) with
  // r_i = d_i - (S z)_i gives z_i / (w_i s) + (S z)_i = d_i + o / s; on a
  // vertical piece at beta, r_i = beta gives (S z)_i = d_i - beta; on a flat
  // piece (s = 0) the force z_i = w_i o is known and only enters the other
  // rows. The matrix of the unknown rows is the block of S of the unknown
  // nodes plus the diagonal 1 / (w_i s) of the sloped ones. With softening
  // slopes (s < 0) that diagonal is negative and the matrix, though
  // symmetric for symmetric S, need not be definite; for a tangent S is not
  // even symmetric. Hence a general LU factorisation with pivoting.
  //
  // The matrix depends on the pieces and on S only, not on d, so the LU
  // factorisation is kept and reused while the pieces do not change; a solve
  // then costs O(m^2) (triangular solves and products with S) instead of the
  // O(m^3) of a factorisation. Each time step starts from the pieces of the
  // previous one, so a step that needs a single active-set iteration (most
  // steps once the contact zone has formed, doc/model.md, section 2)
  // factorises nothing at all.
  double
  CondensedContactSystem::solve(const std::vector<unsigned int> &pieces,
                                const Vector<double>            &d,
                                Vector<double>                  &r,
                                Vector<double>                  &z)
  {
    const unsigned int m = w.size();
    AssertDimension(pieces.size(), m);
    AssertDimension(d.size(), m);
    r.reinit(m);
    z.reinit(m);
    // A node's force is unknown unless its piece is flat (sloped with slope
    // zero), where the law prescribes it.
    const auto is_unknown = [&](const unsigned int i) {
      const ContactLawPiece &piece = contact_law->piece(pieces[i]);
      return piece.vertical || piece.slope != 0;
    };

    // Factorise only when the pieces differ from those of the factorisation
    // kept (or after reinit()).
    if (pieces != factorized_pieces)
      {
        // The unknown nodes, in global order: row and column a of the dense
        // matrix belong to node unknown_nodes[a].
        unknown_nodes.clear();
        for (unsigned int i = 0; i < m; ++i)
          if (is_unknown(i))
            unknown_nodes.push_back(i);
        const unsigned int n = unknown_nodes.size();
        // The block of S, plus 1 / (w s) on the diagonal of the sloped rows;
        // vertical rows are the rows of S alone.
        system_matrix.reinit(n, n);
        for (unsigned int a = 0; a < n; ++a)
          {
            for (unsigned int b = 0; b < n; ++b)
              system_matrix(a, b) = S(unknown_nodes[a], unknown_nodes[b]);
            const ContactLawPiece &piece
              = contact_law->piece(pieces[unknown_nodes[a]]);
            if (!piece.vertical)
              system_matrix(a, a) += 1. / (w[unknown_nodes[a]] * piece.slope);
          }
        // LAPACK's LU factorisation with partial pivoting, skipped when
        // every node is on a flat piece (then all forces are known).
        if (n > 0)
          {
            system_matrix.compute_lu_factorization();
            ++factorization_count;
          }
        factorized_pieces = pieces;
      }

    // The known forces z_i = w_i o of the nodes on flat pieces; the unknown
    // entries are zero for now. Only the known ones enter the right-hand
    // side (usually there are none).
    std::vector<unsigned int> known_nodes;
    for (unsigned int i = 0; i < m; ++i)
      {
        z[i] = 0.;
        if (!is_unknown(i))
          {
            z[i] = w[i] * contact_law->piece(pieces[i]).intercept;
            known_nodes.push_back(i);
          }
      }
    // The right-hand side of each unknown row: d_i minus what the known
    // forces displace at node i, plus the piece's constant, -beta on a
    // vertical piece and o / s on a sloped one.
    Vector<double> rhs(unknown_nodes.size());
    for (unsigned int a = 0; a < unknown_nodes.size(); ++a)
      {
        const unsigned int     i     = unknown_nodes[a];
        const ContactLawPiece &piece = contact_law->piece(pieces[i]);
        double                 value = d[i];
        for (const unsigned int j : known_nodes)
          value -= S(i, j) * z[j];
        value
          += (piece.vertical ? -piece.r_lower : piece.intercept / piece.slope);
        rhs[a] = value;
      }
    // One solve with the kept factorisation gives the unknown forces, which
    // are then put in their places.
    if (rhs.size() > 0)
      system_matrix.solve(rhs);
    for (unsigned int a = 0; a < unknown_nodes.size(); ++a)
      z[unknown_nodes[a]] = rhs[a];

    // The normal displacements that go with all the forces.
    S.vmult(r, z);
    r.sadd(-1., 1., d);
    // The defect is measured relative to the size of the normal
    // displacements involved, the larger of |d|_inf and the gap; 1 if both
    // vanish.
    double scale = std::max(d.linfty_norm(), contact_law->gap());
    if (!(scale > 0))
      scale = 1;
    // For every unknown node: how far r_i is from the piece's relation,
    // r_i = beta on a vertical piece, r_i = (z_i / w_i - o) / s on a sloped
    // one. The nodes on flat pieces satisfy theirs exactly.
    double defect = 0;
    for (const unsigned int i : unknown_nodes)
      {
        const ContactLawPiece &piece = contact_law->piece(pieces[i]);
        const double           error
          = (piece.vertical
               ? r[i] - piece.r_lower
               : r[i] - (z[i] / w[i] - piece.intercept) / piece.slope);
        defect = std::max(defect, std::abs(error) / scale);
      }
    return defect;
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
} // namespace ViscoContact
