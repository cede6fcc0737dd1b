// The dense contact problem on the contact nodes for fixed pieces.

#include <deal.II/base/exceptions.h>

#include "condensed_system.h"

#include <algorithm>
#include <cmath>

namespace ViscoContact
{
  void
  CondensedContactSystem::reinit(const ContactLaw          &law,
                                 const FullMatrix<double>  &compliance,
                                 const std::vector<double> &weights)
  {
    AssertDimension(compliance.m(), weights.size());
    AssertDimension(compliance.n(), weights.size());
    contact_law.emplace(law);
    S = compliance;
    w = weights;
    factorized_pieces.clear();
  }



  // @sect4{CondensedContactSystem::solve}
  //
  // The known forces first, then the right-hand side of the unknown ones,
  // one dense solve, and r = d - S z. The defect is what rounding leaves of
  // the pieces' equations; it is the condensed back end's "linear
  // residual".
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
    const auto is_unknown = [&](const unsigned int i) {
      const ContactLawPiece &piece = contact_law->piece(pieces[i]);
      return piece.vertical || piece.slope != 0;
    };

    if (pieces != factorized_pieces)
      {
        unknown_nodes.clear();
        for (unsigned int i = 0; i < m; ++i)
          if (is_unknown(i))
            unknown_nodes.push_back(i);
        const unsigned int n = unknown_nodes.size();
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
        if (n > 0)
          {
            system_matrix.compute_lu_factorization();
            ++factorization_count;
          }
        factorized_pieces = pieces;
      }

    for (unsigned int i = 0; i < m; ++i)
      z[i]
        = is_unknown(i) ? 0. : w[i] * contact_law->piece(pieces[i]).intercept;
    Vector<double> rhs(unknown_nodes.size());
    for (unsigned int a = 0; a < unknown_nodes.size(); ++a)
      {
        const unsigned int     i     = unknown_nodes[a];
        const ContactLawPiece &piece = contact_law->piece(pieces[i]);
        double                 value = d[i];
        for (unsigned int j = 0; j < m; ++j)
          value -= S(i, j) * z[j];
        value
          += (piece.vertical ? -piece.r_lower : piece.intercept / piece.slope);
        rhs[a] = value;
      }
    if (rhs.size() > 0)
      system_matrix.solve(rhs);
    for (unsigned int a = 0; a < unknown_nodes.size(); ++a)
      z[unknown_nodes[a]] = rhs[a];

    S.vmult(r, z);
    r.sadd(-1., 1., d);
    double scale = std::max(d.linfty_norm(), contact_law->gap());
    if (!(scale > 0))
      scale = 1;
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



  const FullMatrix<double> &
  CondensedContactSystem::compliance() const
  {
    return S;
  }



  unsigned int
  CondensedContactSystem::n_factorizations() const
  {
    return factorization_count;
  }
} // namespace ViscoContact
