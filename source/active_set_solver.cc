#include <deal.II/base/exceptions.h>

#include "active_set_solver.h"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>

namespace ViscoContact
{
  std::string
  ContactActiveSetSolver::Result::describe() const
  {
    std::ostringstream out;
    for (unsigned int i = 0; i < history.size(); ++i)
      out << "    iteration " << i + 1 << ": " << history[i].changed_nodes
          << " nodes changed their piece, " << history[i].rigid_nodes
          << " nodes at the rigid limit, linear residual "
          << std::setprecision(3) << history[i].linear_residual << '\n';
    return out.str();
  }



  // @sect4{ContactActiveSetSolver::reinit}
  //
  // The parameter c of the active-set criterion is scaled like the condensed
  // stiffness of the node, 1/(w_i S_ii) in units of pressure per length, as
  // step-41 and step-42 scale it with the stiffness diagonal. It must exceed
  // the steepest softening of the law for q = p + c r to order the graph.
  void
  ContactActiveSetSolver::reinit(const ContactLaw          &law,
                                 const FullMatrix<double>  &compliance,
                                 const std::vector<double> &weights)
  {
    AssertDimension(compliance.m(), weights.size());
    AssertDimension(compliance.n(), weights.size());
    contact_law.emplace(law);
    S = compliance;
    w = weights;

    const unsigned int m = weights.size();
    c.resize(m);
    for (unsigned int i = 0; i < m; ++i)
      c[i] = std::max(1. / (w[i] * S(i, i)), 2 * law.steepest_softening());

    r.reinit(m);
    z.reinit(m);
    node_pieces.resize(m);
    for (unsigned int i = 0; i < m; ++i)
      node_pieces[i] = law.find_piece(0., c[i]);
    factorized_pieces.clear();
  }



  void
  ContactActiveSetSolver::update_compliance(
    const FullMatrix<double> &compliance)
  {
    AssertDimension(compliance.m(), n_nodes());
    S = compliance;
    for (unsigned int i = 0; i < n_nodes(); ++i)
      c[i] = std::max(1. / (w[i] * S(i, i)),
                      2 * contact_law->steepest_softening());
    factorized_pieces.clear();
  }



  // @sect4{ContactActiveSetSolver::update_forces}
  //
  // For fixed pieces the nodal equations are linear. A node on a sloped piece
  // with slope s and intercept o satisfies z_i = w_i (o + s r_i) with
  // r = d - S z, i.e. the symmetric row
  //   z_i / (w_i s) + (S z)_i = d_i + o / s,
  // a node on a vertical piece at r = beta satisfies (S z)_i = d_i - beta, and
  // a node on a flat piece (s = 0) has the known force z_i = w_i o. Only the
  // unknown forces enter the dense system, whose LU factorisation is kept
  // while the pieces do not change.
  double
  ContactActiveSetSolver::update_forces(const Vector<double> &d)
  {
    const unsigned int m          = n_nodes();
    const auto         is_unknown = [&](const unsigned int i) {
      const ContactLawPiece &piece = contact_law->piece(node_pieces[i]);
      return piece.vertical || piece.slope != 0;
    };

    if (node_pieces != factorized_pieces)
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
              = contact_law->piece(node_pieces[unknown_nodes[a]]);
            if (!piece.vertical)
              system_matrix(a, a) += 1. / (w[unknown_nodes[a]] * piece.slope);
          }
        if (n > 0)
          {
            system_matrix.compute_lu_factorization();
            ++factorization_count;
          }
        factorized_pieces = node_pieces;
      }

    // Known forces first, then the right-hand side of the unknown ones.
    for (unsigned int i = 0; i < m; ++i)
      if (!is_unknown(i))
        z[i] = w[i] * contact_law->piece(node_pieces[i]).intercept;
      else
        z[i] = 0;
    Vector<double> rhs(unknown_nodes.size());
    for (unsigned int a = 0; a < unknown_nodes.size(); ++a)
      {
        const unsigned int     i     = unknown_nodes[a];
        const ContactLawPiece &piece = contact_law->piece(node_pieces[i]);
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

    // r = d - S z, and how far the nodes are from the linear equations of
    // their pieces, relative to the size of the displacements involved.
    S.vmult(r, z);
    r.sadd(-1., 1., d);
    double scale = std::max(d.linfty_norm(), contact_law->gap());
    if (!(scale > 0))
      scale = 1;
    double residual = 0;
    for (const unsigned int i : unknown_nodes)
      {
        const ContactLawPiece &piece = contact_law->piece(node_pieces[i]);
        const double           defect
          = (piece.vertical
               ? r[i] - piece.r_lower
               : r[i] - (z[i] / w[i] - piece.intercept) / piece.slope);
        residual = std::max(residual, std::abs(defect) / scale);
      }
    return residual;
  }



  // @sect4{ContactActiveSetSolver::solve}
  //
  // The iteration itself: solve for the forces on the current pieces, move
  // each node to the piece that q_i = z_i/w_i + c_i r_i names, stop when no
  // node moves and the linear equations hold to the tolerance
  // (ContactLaw::next_piece() keeps a node within rounding of its piece).
  ContactActiveSetSolver::Result
  ContactActiveSetSolver::solve(const Vector<double> &d,
                                const unsigned int    max_iterations,
                                const double          tolerance)
  {
    AssertDimension(d.size(), n_nodes());
    Result result{false, {}, 0, {}};
    if (n_nodes() == 0)
      {
        result.converged = true;
        return result;
      }

    for (unsigned int iteration = 0; iteration < max_iterations; ++iteration)
      {
        const double residual = update_forces(d);

        unsigned int changed = 0, rigid = 0;
        for (unsigned int i = 0; i < n_nodes(); ++i)
          {
            const unsigned int next
              = contact_law->next_piece(node_pieces[i],
                                        z[i] / w[i] + c[i] * r[i],
                                        c[i]);
            if (next != node_pieces[i])
              {
                node_pieces[i] = next;
                ++changed;
              }
            if (contact_law->piece(node_pieces[i]).rigid)
              ++rigid;
          }
        result.history.push_back({changed, rigid, residual});

        if (changed == 0)
          {
            result.converged = (residual <= tolerance);
            break;
          }
      }
    return result;
  }



  ContactActiveSetSolver::State
  ContactActiveSetSolver::state() const
  {
    return {node_pieces, r, z};
  }



  void
  ContactActiveSetSolver::set_state(const State &state)
  {
    AssertDimension(state.pieces.size(), n_nodes());
    node_pieces = state.pieces;
    r           = state.r;
    z           = state.z;
  }



  unsigned int
  ContactActiveSetSolver::n_nodes() const
  {
    return w.size();
  }



  const std::vector<unsigned int> &
  ContactActiveSetSolver::pieces() const
  {
    return node_pieces;
  }



  const ContactLaw &
  ContactActiveSetSolver::law() const
  {
    return *contact_law;
  }



  const Vector<double> &
  ContactActiveSetSolver::normal_displacements() const
  {
    return r;
  }



  const Vector<double> &
  ContactActiveSetSolver::normal_forces() const
  {
    return z;
  }



  unsigned int
  ContactActiveSetSolver::n_factorizations() const
  {
    return factorization_count;
  }
} // namespace ViscoContact
