// The active-set iteration on the pieces of the contact law, and the state
// of the contact nodes it moves.
//
// This is the semismooth Newton method of doc/model.md, section 2 ("Moving
// between pieces"), written once for every back end and every number of
// ranks: the back end only solves the linear problem of the current pieces
// and writes r and z; everything this file does is local to the nodes of a
// rank, except for a few sums of counts over the ranks, which make every
// rank take the same decisions.

#include <deal.II/base/exceptions.h>
#include <deal.II/base/mpi.h>

#include "contact_nodes.h"

#include <cmath>
#include <iomanip>
#include <sstream>

namespace ViscoContact
{
  namespace
  {
    // Element-wise sums of a few counters over all ranks, in one reduction.
    // Every rank receives the same sums, so decisions based on them agree.
    template <std::size_t N>
    std::array<unsigned int, N>
    sum_over_ranks(const std::array<unsigned int, N> &local,
                   const MPI_Comm                     communicator)
    {
      std::array<unsigned int, N> sums;
      Utilities::MPI::sum(ArrayView<const unsigned int>(local.data(), N),
                          communicator,
                          ArrayView<unsigned int>(sums.data(), N));
      return sums;
    }
  } // namespace



  // @sect4{ActiveSetResult}
  //
  // The number of iterations of a time step: those of earlier active-set
  // runs of the step (the implicit scheme runs one per Newton iteration)
  // plus those of the last run, one record each.
  unsigned int
  ActiveSetResult::iterations() const
  {
    return earlier_iterations + history.size();
  }



  // Krylov iterations, likewise (0 for the condensed back end, whose solves
  // are direct).
  unsigned int
  ActiveSetResult::inner_iterations() const
  {
    unsigned int sum = earlier_inner_iterations;
    for (const IterationRecord &record : history)
      sum += record.inner_iterations;
    return sum;
  }



  // The iteration history of the last run, one line per iteration, for the
  // report of a failed step (step_report.cc): how many nodes moved, how many
  // sit at the rigid limit, and how well the linear solve did.
  std::string
  ActiveSetResult::describe() const
  {
    std::ostringstream out;
    for (unsigned int i = 0; i < history.size(); ++i)
      out << "    iteration " << i + 1 << ": " << history[i].changed_nodes
          << " nodes changed their piece, " << history[i].rigid_nodes
          << " nodes at the rigid limit, linear residual "
          << std::setprecision(3) << history[i].linear_residual
          << (history[i].inner_iterations > 0
                ? " after " + std::to_string(history[i].inner_iterations)
                    + " Krylov iterations"
                : std::string())
          << '\n';
    return out.str();
  }



  // @sect4{ContactNodes::reinit}
  //
  // Every node starts at r = z = 0 with no parameter yet; its piece is
  // chosen by the first set_parameters(), since finding the piece of a state
  // needs c.
  void
  ContactNodes::reinit(const ContactLaws               &laws,
                       const std::vector<unsigned int> &zones,
                       const std::vector<double>       &weights)
  {
    AssertDimension(zones.size(), weights.size());
    contact_laws = laws;
    node_zones   = zones;
    w            = weights;
    c.assign(w.size(), 0.);
    r.assign(w.size(), 0.);
    z.assign(w.size(), 0.);
    node_pieces.assign(w.size(), 0);
    placed = false;
  }



  // @sect4{ContactNodes::set_parameters}
  //
  // The parameter c_i scales the normal displacement into a pressure; it
  // changes with the operator (the implicit scheme's tangent), the pieces do
  // not: they are the warm start of the next solve.
  //
  // c_i must exceed the steepest softening, or q = p + c r would not grow
  // strictly along the graph and the update rule could name no piece or
  // several. ContactSet::set_operator() guarantees this with its factor 2,
  // so a violation is an internal error, not a user's.
  void
  ContactNodes::set_parameters(const std::vector<double> &parameters)
  {
    AssertDimension(parameters.size(), size());
    for (unsigned int i = 0; i < size(); ++i)
      AssertThrow(parameters[i]
                    > contact_laws.zone_law(node_zones[i]).steepest_softening(),
                  ExcInternalError());
    c = parameters;
    // The first call places every node on the piece of its state r = z = 0
    // (q = 0), the state before the first load. Later calls keep the pieces.
    if (!placed)
      for (unsigned int i = 0; i < size(); ++i)
        node_pieces[i] = contact_laws.find_piece(node_zones[i], 0., c[i]);
    placed = true;
  }



  // @sect4{ContactNodes::update_pieces}
  //
  // The update rule at every node of this rank: q_i = z_i / w_i + c_i r_i
  // from the last solve names the next piece (ContactLaw::next_piece). The
  // counts are this rank's only; ContactNodes::solve() sums them.
  std::array<unsigned int, 2>
  ContactNodes::update_pieces()
  {
    unsigned int changed = 0, rigid = 0;
    for (unsigned int i = 0; i < size(); ++i)
      {
        const unsigned int next
          = contact_laws.next_piece(node_zones[i],
                                    node_pieces[i],
                                    z[i] / w[i] + c[i] * r[i],
                                    c[i]);
        if (next != node_pieces[i])
          {
            node_pieces[i] = next;
            ++changed;
          }
        // After the move: the nodes now at the rigid limit, for the
        // iteration history.
        if (current_piece(i).rigid)
          ++rigid;
      }
    return {{changed, rigid}};
  }



  // @sect4{ContactNodes::solve}
  //
  // The iteration itself, the same for every back end and rank count: the
  // decision to stop depends on sums over all ranks only, so every rank
  // takes it at the same iteration.
  //
  // Each iteration solves the linear problem of the current pieces (the back
  // end writes r and z), moves every node to the piece that its q names, and
  // stops when no node has moved on any rank and the linear solve met the
  // tolerance. Since the step problem has the same fixed points whatever the
  // c_i, a converged iteration has solved the step problem of the current
  // operator.
  //
  // Inexact early solves: while the pieces are still changing, a solve only
  // has to tell each node which piece it goes to next, not the final
  // displacement. So the iteration asks for the relative accuracy
  // sqrt(tolerance) (1e-5 for the default 1e-10) until a solve moves no
  // node; that solve is then continued to the full tolerance, and every
  // later one asks for the full tolerance. The last solve is always a full
  // one, so the result is the one of the exact iteration; what
  // changes is the cost of the solves before the pieces settle, which the
  // full space back end's Krylov method stops early (the condensed back end
  // solves exactly anyway, and its report then meets the tolerance at once,
  // which leaves its iteration as it was).
  ActiveSetResult
  ContactNodes::solve(
    const std::function<LinearSolveReport(double)> &solve_for_pieces,
    const unsigned int                              max_iterations,
    const double                                    tolerance,
    const MPI_Comm                                  communicator)
  {
    ActiveSetResult result;
    const double    early_tolerance = std::max(std::sqrt(tolerance), tolerance);
    bool            pieces_settled  = false;
    for (unsigned int iteration = 0; iteration < max_iterations; ++iteration)
      {
        // The linear problem of the current pieces. A failed solve (a Krylov
        // method that did not converge) fails on every rank alike, because
        // the Krylov methods decide with global norms; the iteration ends
        // with the back end's reason.
        LinearSolveReport report
          = solve_for_pieces(pieces_settled ? tolerance : early_tolerance);
        if (!report.converged)
          {
            result.failure = report.failure;
            return result;
          }
        // Every node moves (or stays), and all ranks learn how many moved
        // and how many are at the rigid limit.
        std::array<unsigned int, 2> moved
          = sum_over_ranks(update_pieces(), communicator);
        // An early solve that moved no node: the pieces have settled, so the
        // same linear problem is solved on to the full tolerance (from the
        // early solution), and the nodes are checked once more. This is
        // still the same iteration, on the same pieces, so an iteration
        // counts the sets of pieces tried, as with exact solves.
        if (moved[0] == 0 && !pieces_settled && report.residual > tolerance)
          {
            pieces_settled                  = true;
            const LinearSolveReport refined = solve_for_pieces(tolerance);
            if (!refined.converged)
              {
                result.failure = refined.failure;
                return result;
              }
            report.residual = refined.residual;
            report.inner_iterations += refined.inner_iterations;
            moved = sum_over_ranks(update_pieces(), communicator);
          }
        result.history.push_back(
          {moved[0], moved[1], report.residual, report.inner_iterations});
        // Converged: the pieces the last solve used are the ones the nodes
        // sit on now, so (r, z) lies on the graph of the law at every node.
        // The residual is a global norm, the same on every rank.
        if (moved[0] == 0 && report.residual <= tolerance)
          {
            result.converged = true;
            return result;
          }
        if (moved[0] == 0)
          pieces_settled = true;
        // Settled pieces whose linear solves no longer improve (three solves
        // in a row without halving the residual): the accuracy of the linear
        // problem is exhausted, and more iterations would only repeat it.
        const std::size_t n = result.history.size();
        if (n >= 3 && moved[0] == 0)
          {
            bool stagnant = true;
            for (std::size_t j = n - 2; j < n; ++j)
              stagnant = stagnant && result.history[j].changed_nodes == 0
                         && result.history[j - 1].changed_nodes == 0
                         && result.history[j].linear_residual
                              > 0.5 * result.history[j - 1].linear_residual;
            if (stagnant)
              {
                std::ostringstream reason;
                reason << "The pieces of the contact law settled, but the "
                          "linear solves stagnate at a relative residual of "
                       << report.residual << ", above Tolerance = " << tolerance
                       << " in subsection <Active set solver>.";
                result.failure = reason.str();
                return result;
              }
          }
      }
    // Out of iterations: the caller cuts the time step or stops the run with
    // this reason, which names the parameters that bound the iteration.
    std::ostringstream reason;
    reason << "The active-set iteration did not converge within "
           << max_iterations
           << " iterations (Maximum iterations = " << max_iterations
           << ", Tolerance = " << tolerance
           << " in subsection <Active set solver>).";
    result.failure = reason.str();
    return result;
  }



  // @sect4{ContactNodes::state and set_state}
  //
  // The pieces and the last (r, z): what a time step that has to be retried
  // restores before it starts again (time_step.cc).
  ContactNodes::State
  ContactNodes::state() const
  {
    return {node_pieces, r, z};
  }



  void
  ContactNodes::set_state(const State &state)
  {
    AssertDimension(state.pieces.size(), size());
    node_pieces = state.pieces;
    r           = state.r;
    z           = state.z;
  }



  // @sect4{Access to the nodes}
  //
  // Plain access: the number of nodes of this rank, the laws, and per node
  // the zone, the weight w_i and the piece. set_piece() is for
  // restoring a state node by node (a resumed checkpoint).
  unsigned int
  ContactNodes::size() const
  {
    return w.size();
  }



  const ContactLaws &
  ContactNodes::laws() const
  {
    return contact_laws;
  }



  unsigned int
  ContactNodes::zone(const unsigned int i) const
  {
    return node_zones[i];
  }



  double
  ContactNodes::weight(const unsigned int i) const
  {
    return w[i];
  }



  unsigned int
  ContactNodes::piece(const unsigned int i) const
  {
    return node_pieces[i];
  }



  void
  ContactNodes::set_piece(const unsigned int i, const unsigned int piece)
  {
    Assert(contact_laws.zone_of_piece(piece) == node_zones[i],
           ExcInternalError());
    node_pieces[i] = piece;
  }



  const ContactLawPiece &
  ContactNodes::current_piece(const unsigned int i) const
  {
    return contact_laws.piece(node_pieces[i]);
  }



  const std::vector<unsigned int> &
  ContactNodes::pieces() const
  {
    return node_pieces;
  }



  // @sect4{ContactNodes::status}
  //
  // The contact state of a node as the output reports it: 2 at the rigid
  // limit (on the rigid piece), 1 in normal-compliance contact (penetrating
  // the layer, r > 0, or pressed by it, z > 0), 0 out of contact.
  unsigned int
  ContactNodes::status(const unsigned int i) const
  {
    if (current_piece(i).rigid)
      return 2;
    if (r[i] > 0 || z[i] > 0)
      return 1;
    return 0;
  }



  // @sect4{Contact pressures}
  //
  // The total pressure z_i / w_i, and the part the layer carries: p(g-) at
  // the rigid limit, where the foundation carries the rest, and the whole
  // pressure on every other piece, where the foundation carries nothing.
  double
  ContactNodes::contact_pressure(const unsigned int i) const
  {
    return z[i] / w[i];
  }



  double
  ContactNodes::compliance_pressure(const unsigned int i) const
  {
    const ContactLawPiece &current = current_piece(i);
    return current.rigid ? current.p_lower : contact_pressure(i);
  }



  // @sect4{ContactNodes::count_states and total_force}
  //
  // Over all ranks: the nodes at the rigid limit, in normal-compliance
  // contact and out of contact (in this order, status 2, 1, 0), and the
  // total contact force sum_i z_i (per unit thickness in 2D). Both are
  // collective.
  std::array<unsigned int, 3>
  ContactNodes::count_states(const MPI_Comm communicator) const
  {
    std::array<unsigned int, 3> counts = {{0, 0, 0}};
    for (unsigned int i = 0; i < size(); ++i)
      ++counts[2 - status(i)];
    return sum_over_ranks(counts, communicator);
  }



  double
  ContactNodes::total_force(const MPI_Comm communicator) const
  {
    double sum = 0;
    for (const double force : z)
      sum += force;
    return Utilities::MPI::sum(sum, communicator);
  }



  std::vector<double>
  ContactNodes::zone_forces(const MPI_Comm communicator) const
  {
    std::vector<double> forces(contact_laws.n_zones(), 0.);
    for (unsigned int i = 0; i < size(); ++i)
      forces[node_zones[i]] += z[i];
    std::vector<double> sums(forces.size());
    Utilities::MPI::sum(ArrayView<const double>(forces.data(), forces.size()),
                        communicator,
                        ArrayView<double>(sums.data(), sums.size()));
    return sums;
  }



  // @sect4{ContactNodes::contact_area and peak_pressure}
  //
  // Over all ranks: the weights of the nodes in contact (status 1 or 2)
  // summed, which is the contact width in 2D and the contact area in 3D to
  // within the weight of the nodes at the edge of the zone, and the largest
  // nodal pressure z_i / w_i. Both are collective.
  double
  ContactNodes::contact_area(const MPI_Comm communicator) const
  {
    double sum = 0;
    for (unsigned int i = 0; i < size(); ++i)
      if (status(i) > 0)
        sum += w[i];
    return Utilities::MPI::sum(sum, communicator);
  }



  double
  ContactNodes::peak_pressure(const MPI_Comm communicator) const
  {
    double peak = 0;
    for (unsigned int i = 0; i < size(); ++i)
      peak = std::max(peak, contact_pressure(i));
    return Utilities::MPI::max(peak, communicator);
  }
} // namespace ViscoContact
