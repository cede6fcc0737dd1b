// The active-set iteration on the pieces of the contact law, and the state
// of the contact nodes it moves.

#include <deal.II/base/exceptions.h>
#include <deal.II/base/mpi.h>

#include "active_set.h"

#include <cmath>
#include <iomanip>
#include <sstream>

namespace ViscoContact
{
  namespace
  {
    template <std::size_t N>
    std::array<unsigned int, N>
    sum_over_ranks(const std::array<unsigned int, N> &local,
                   const MPI_Comm                     communicator)
    {
      std::array<unsigned int, N> sums;
      const int                   error = MPI_Allreduce(local.data(),
                                      sums.data(),
                                      N,
                                      MPI_UNSIGNED,
                                      MPI_SUM,
                                      communicator);
      AssertThrowMPI(error);
      return sums;
    }
  } // namespace



  unsigned int
  ActiveSetResult::iterations() const
  {
    return earlier_iterations + history.size();
  }



  unsigned int
  ActiveSetResult::inner_iterations() const
  {
    unsigned int sum = earlier_inner_iterations;
    for (const IterationRecord &record : history)
      sum += record.inner_iterations;
    return sum;
  }



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



  void
  ContactNodes::reinit(const ContactLaw          &law,
                       const std::vector<double> &weights)
  {
    contact_law.emplace(law);
    w = weights;
    c.assign(w.size(), 0.);
    r.assign(w.size(), 0.);
    z.assign(w.size(), 0.);
    node_pieces.assign(w.size(), 0);
    placed = false;
  }



  // @sect4{ContactNodes::set_parameters}
  //
  // The parameter c_i scales the normal displacement into a pressure; it
  // changes with the operator (the implicit scheme's tangent), the pieces
  // do not: they are the warm start of the next solve.
  void
  ContactNodes::set_parameters(const std::vector<double> &parameters)
  {
    AssertDimension(parameters.size(), size());
    for (const double value : parameters)
      AssertThrow(value > contact_law->steepest_softening(),
                  ExcInternalError());
    c = parameters;
    if (!placed)
      for (unsigned int i = 0; i < size(); ++i)
        node_pieces[i] = contact_law->find_piece(0., c[i]);
    placed = true;
  }



  std::array<unsigned int, 2>
  ContactNodes::update_pieces()
  {
    unsigned int changed = 0, rigid = 0;
    for (unsigned int i = 0; i < size(); ++i)
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
    return {{changed, rigid}};
  }



  // @sect4{ContactNodes::solve}
  //
  // The iteration itself, the same for every back end and rank count: the
  // decision to stop depends on sums over all ranks only, so every rank
  // takes it at the same iteration.
  ActiveSetResult
  ContactNodes::solve(
    const std::function<LinearSolveReport()> &solve_for_pieces,
    const unsigned int                        max_iterations,
    const double                              tolerance,
    const MPI_Comm                            communicator)
  {
    ActiveSetResult result;
    for (unsigned int iteration = 0; iteration < max_iterations; ++iteration)
      {
        const LinearSolveReport report = solve_for_pieces();
        if (!report.converged)
          {
            result.failure = report.failure;
            return result;
          }
        const std::array<unsigned int, 2> moved
          = sum_over_ranks(update_pieces(), communicator);
        result.history.push_back(
          {moved[0], moved[1], report.residual, report.inner_iterations});
        if (moved[0] == 0 && report.residual <= tolerance)
          {
            result.converged = true;
            return result;
          }
      }
    std::ostringstream reason;
    reason << "The active-set iteration did not converge within "
           << max_iterations
           << " iterations (Maximum iterations = " << max_iterations
           << ", Tolerance = " << tolerance
           << " in subsection <Active set solver>).";
    result.failure = reason.str();
    return result;
  }



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



  unsigned int
  ContactNodes::size() const
  {
    return w.size();
  }



  const ContactLaw &
  ContactNodes::law() const
  {
    return *contact_law;
  }



  double
  ContactNodes::weight(const unsigned int i) const
  {
    return w[i];
  }



  double
  ContactNodes::parameter(const unsigned int i) const
  {
    return c[i];
  }



  unsigned int
  ContactNodes::piece(const unsigned int i) const
  {
    return node_pieces[i];
  }



  void
  ContactNodes::set_piece(const unsigned int i, const unsigned int piece)
  {
    AssertIndexRange(piece, contact_law->n_pieces());
    node_pieces[i] = piece;
  }



  const std::vector<unsigned int> &
  ContactNodes::pieces() const
  {
    return node_pieces;
  }



  unsigned int
  ContactNodes::status(const unsigned int i) const
  {
    if (contact_law->piece(node_pieces[i]).rigid)
      return 2;
    if (r[i] > 0 || z[i] > 0)
      return 1;
    return 0;
  }



  double
  ContactNodes::contact_pressure(const unsigned int i) const
  {
    return z[i] / w[i];
  }



  double
  ContactNodes::compliance_pressure(const unsigned int i) const
  {
    const ContactLawPiece &current = contact_law->piece(node_pieces[i]);
    return current.rigid ? current.p_lower : contact_pressure(i);
  }



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
} // namespace ViscoContact
