// The condensed back end: the operator factorised by a sparse direct solver,
// the contact problem of fixed pieces solved on the contact nodes.
//
// This file implements option (a) of doc/model.md, section 2 ("Two ways to
// solve the linear problem of fixed pieces"). The bulk unknowns are
// eliminated once per operator: with the contact compliance S = N A^{-1} N^T
// and the free normal displacements d = N A^{-1} b, the active-set iteration
// only ever sees the small dense problem r = d - S z of
// CondensedContactSystem (condensed_system.cc), and the displacement is
// assembled once, at the end of the step problem, as u = A^{-1} (b - N^T z).

#include <deal.II/base/exceptions.h>
#include <deal.II/base/mpi.h>

#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/lapack_full_matrix.h>

#include "back_ends/condensed_system.h"
#include "back_ends/contact_solver.h"
#include "back_ends/direct_solver.h"

#include <algorithm>
#include <map>
#include <set>

namespace ViscoContact
{
  namespace
  {
    // The values of all ranks, one after the other (rank order): what each
    // rank needs of the small, node-sized vectors of the condensed problem.
    // Since the contact nodes are numbered rank by rank (contact_set.cc),
    // the concatenation in rank order is exactly the global node order, so
    // the result can be indexed by global node number on every rank.
    template <typename T>
    std::vector<T>
    gather_on_all_ranks(const std::vector<T> &local,
                        const MPI_Comm        communicator)
    {
      const int        n_ranks = Utilities::MPI::n_mpi_processes(communicator);
      const int        size    = local.size();
      std::vector<int> sizes(n_ranks), offsets(n_ranks + 1, 0);
      // First every rank learns how many entries each rank contributes ...
      int error = MPI_Allgather(&size,
                                1,
                                MPI_INT,
                                sizes.data(),
                                1,
                                MPI_INT,
                                communicator);
      AssertThrowMPI(error);
      // ... which gives, by a prefix sum, where each rank's block starts ...
      for (int p = 0; p < n_ranks; ++p)
        offsets[p + 1] = offsets[p] + sizes[p];
      std::vector<T> all(offsets[n_ranks]);
      // ... and one collective call then hands every rank all blocks.
      error = MPI_Allgatherv(local.data(),
                             size,
                             Utilities::MPI::mpi_type_id_for_type<T>,
                             all.data(),
                             sizes.data(),
                             offsets.data(),
                             Utilities::MPI::mpi_type_id_for_type<T>,
                             communicator);
      AssertThrowMPI(error);
      return all;
    }
  } // namespace



  // @sect3{The condensed back end}
  //
  // With A factorised, the displacement of fixed nodal forces z is
  // u = A^{-1} (b - N^T z), and the contact problem of fixed pieces is the
  // dense m x m problem of CondensedContactSystem on the contact compliance
  // S = N A^{-1} N^T and the free normal displacements d = N A^{-1} b. How
  // S and d are found depends on what the factorisation offers.
  //
  // On one rank CHOLMOD factorises P A P^T = L L^T with an elimination order
  // that ends with the contact dofs (direct_solver.cc). The last block L_c
  // of the factor is then the Cholesky factor of the Schur complement of A
  // on the contact dofs, and everything the contact problem needs follows
  // from the dense matrix X = L_c^{-1} N_c^T (N_c: the normals at the
  // contact dofs, one column per node):
  //  - S = X^T X, without a single sparse solve;
  //  - d = X^T y_c, where y = L^{-1} P b is the forward half of the solve
  //    with b;
  //  - u from the backward half, after y_c -= X z: the force only changes
  //    the last block of the forward solve.
  // A step then costs one forward and one backward solve, as a solve
  // without contact does, plus products with the small X.
  //
  // Otherwise (UMFPACK's LU of an unsymmetric tangent, MUMPS on several
  // ranks) S is computed column by column: column j is N A^{-1} N^T e_j, the
  // normal displacements caused by a unit force at contact node j, from
  // solves in blocks of 64 right-hand sides, and a step costs two solves:
  // A^{-1} b before the active-set iteration and A^{-1} N^T z after it.
  //
  // With friction the contact nodes of frictional zones add their
  // tangential rows t_j to N (dim rows per node, ContactSet::row()):
  // S is the compliance of all rows, and the dense problem of the pieces and
  // friction states (solve_frictional()) is factorised afresh in every
  // active-set iteration, (m dim)^3 / 3 operations: its rows change with the
  // slip directions, which the row updates of CondensedContactSystem do not
  // follow.
  //
  // For the explicit stress update the operator is the elastic K for the
  // whole run, so this set-up is paid once; for the implicit update it is
  // paid again in every Newton iteration, with the new tangent.
  //
  // On several ranks S (m^2 doubles) is held by every rank, which solves the
  // small dense problem itself. Replicating S is what makes the active-set
  // iteration free of communication beyond a few gathers of node-sized
  // vectors: every rank has the same S, the same d and the same pieces, does
  // the same arithmetic and thus reaches the same forces and the same
  // decisions, so no rank has to wait for another's answer. The price is
  // memory that does not shrink with the number of ranks. That is why
  // Method = auto chooses this back end only on one rank and for small
  // contact surfaces.
  template <int dim>
  class CondensedContactSolver : public ContactSolver<dim>
  {
  public:
    CondensedContactSolver(const Parameters::AllParameters &parameters,
                           const VectorType                &layout);

    // Set-up: the factorisation of A, and S, from its last block or from
    // one solve per contact node.
    void
    set_operator(const MatrixType      &A,
                 const bool             symmetric,
                 const ContactSet<dim> &contact) override;
    std::string
    description() const override;
    // Per step problem: d = N A^{-1} b; per active-set iteration: the dense
    // problem on the contact nodes; at the end: u = A^{-1} (b - N^T z).
    void
    set_right_hand_side(const VectorType      &b,
                        const ContactSet<dim> &contact) override;
    LinearSolveReport
    solve_for_pieces(ContactSet<dim>          &contact,
                     VectorType               &u,
                     const LinearSolveRequest &request) override;
    void
    finish(const ContactSet<dim> &contact, VectorType &u) override;
    // S x, and a solve with the factorisation.
    void
    apply_compliance(const ContactSet<dim> &contact,
                     const Vector<double>  &x,
                     Vector<double>        &y) override;
    LinearSolveReport
    solve_without_contact(const VectorType &b, VectorType &u) override;
    void
    apply_operator(VectorType &dst, const VectorType &src) const override
    {
      A->vmult(dst, src);
    }

    void
    forget_kept_state() override;

  private:
    // The operator of the last set_operator().
    const MatrixType *A = nullptr;

    // The two ways to S (see above).
    FullMatrix<double>
    compliance_from_last_block(const ContactSet<dim> &contact);
    FullMatrix<double>
    compliance_by_solves(const ContactSet<dim> &contact);
    // The dense problem of the pieces and friction states of all nodes,
    // factorised and solved; writes the nodes' solutions and returns the
    // backward error of the dense solve.
    double
    solve_frictional(ContactSet<dim> &contact);

    // The rows of this rank's node i in the global numbering of rows.
    unsigned int
    first_row(const ContactSet<dim> &contact, const unsigned int i) const;

    // Whether any zone has friction (then S and d cover the tangential rows
    // too and solve_frictional() solves), and the first global row of every
    // node (the rows of the nodes, rank by rank, node by node) and the
    // total.
    bool                      friction = false;
    std::vector<unsigned int> row_start;

    const MPI_Comm         communicator;
    SparseDirectSolver     factorization;
    CondensedContactSystem condensed_system;

    // The contact dofs of this rank's nodes (the dofs on which a row of N
    // has an entry), as local indices.
    std::vector<unsigned int> contact_dofs;

    // With the last block: X = L_c^{-1} N_c^T (one row per contact dof, in
    // the factor's order, one column per node) and the last block y_c of
    // the forward solve of the current step problem.
    LAPACKFullMatrix<double> normal_responses;
    Vector<double>           forward_last;

    // Without it: A^{-1} b of the current step problem.
    VectorType free_displacement;

    // The free displacements d along the rows (normal ones less the gap
    // without friction), and the normal displacements r and forces z of all
    // contact nodes (with friction: the forces along all rows).
    Vector<double> d, r_all, z_all;
    // The memory pressures, the bonding and the reached cohesive openings
    // of all contact nodes for the step (empty without memory, adhesion, a
    // cohesive interface), gathered with d.
    std::vector<double> memory_all, adhesion_all, openings_all;
    // With friction: S, kept for the dense problems.
    FullMatrix<double> frictional_compliance;
  };



  // @sect4{CondensedContactSolver::CondensedContactSolver}
  //
  // The factorisation object is created here, the factorisation itself in
  // set_operator(). Direct solver = auto means CHOLMOD on one rank (a
  // symmetric operator is Cholesky-factorised; an unsymmetric tangent goes
  // to UMFPACK, see direct_solver.cc) and MUMPS on several, the only one of
  // the three that works on distributed matrices. free_displacement takes
  // the partition of the run's displacement vectors from layout.
  template <int dim>
  CondensedContactSolver<dim>::CondensedContactSolver(
    const Parameters::AllParameters &parameters,
    const VectorType                &layout)
    : communicator(layout.get_mpi_communicator())
    , factorization(parameters.direct_solver, communicator)
    , free_displacement(layout)
  {}



  // The line for the run's header names the factorisation (what it is and,
  // for CHOLMOD, the size of its factor), so that a run's log says which
  // library did the work.
  template <int dim>
  std::string
  CondensedContactSolver<dim>::description() const
  {
    return "condensed: the operator factorised (" + factorization.description()
           + "), the active set on the contact nodes";
  }



  // @sect4{CondensedContactSolver::set_operator}
  //
  // The set-up of the condensed problem for a new operator A: its sparse
  // factorisation, asked to eliminate the contact dofs last, and the
  // compliance S = N A^{-1} N^T. S(i, j) is the normal displacement at
  // contact node i caused by a unit normal force at node j.
  template <int dim>
  void
  CondensedContactSolver<dim>::set_operator(const MatrixType      &matrix,
                                            const bool             symmetric,
                                            const ContactSet<dim> &contact)
  {
    A = &matrix;
    // The rows of every node (the normal, and the tangents in a frictional
    // zone), numbered across ranks.
    friction = contact.has_friction();
    std::vector<unsigned int> own_rows(contact.size());
    for (unsigned int i = 0; i < contact.size(); ++i)
      own_rows[i] = 1 + contact.n_tangential(i);
    const std::vector<unsigned int> all_rows
      = gather_on_all_ranks(own_rows, communicator);
    row_start.assign(all_rows.size() + 1, 0);
    for (unsigned int n = 0; n < all_rows.size(); ++n)
      row_start[n + 1] = row_start[n] + all_rows[n];

    // The contact dofs: the owned dofs the rows have entries on, node by
    // node in increasing order, each once (a dof in which no row has an
    // entry does not enter N, so an axis-aligned frictionless contact
    // boundary needs one dof per node). The factor's last block needs them
    // (one rank, where every dof is owned); a row of a contact pair may
    // also reach dofs other ranks own (ghosts).
    const unsigned int n_owned = free_displacement.locally_owned_size();
    contact_dofs.clear();
    std::set<unsigned int> seen;
    for (unsigned int i = 0; i < contact.size(); ++i)
      {
        std::set<unsigned int> node_dofs;
        for (unsigned int j = 0; j < own_rows[i]; ++j)
          for (const auto &entry : contact.row(i, j))
            if (entry.local_dof < n_owned
                && seen.insert(entry.local_dof).second)
              node_dofs.insert(entry.local_dof);
        contact_dofs.insert(contact_dofs.end(),
                            node_dofs.begin(),
                            node_dofs.end());
      }

    // A new operator replaces the old factorisation (the implicit update
    // calls this once per Newton iteration).
    factorization.factorize(*A, symmetric, contact_dofs);
    ++this->counts.operator_setups;
    const unsigned int m = row_start.back();
    if (m == 0) // no contact: the factorisation is all there is to do
      return;

    FullMatrix<double> S = factorization.has_last_block()
                             ? compliance_from_last_block(contact)
                             : compliance_by_solves(contact);
    // S is symmetric in exact arithmetic when A is; make it so in floating
    // point. For an unsymmetric tangent S is left as computed, and the dense
    // problem is solved by LU anyway.
    if (symmetric)
      for (unsigned int i = 0; i < m; ++i)
        for (unsigned int j = 0; j < i; ++j)
          S(i, j) = S(j, i) = 0.5 * (S(i, j) + S(j, i));

    if (friction)
      {
        frictional_compliance = std::move(S);
        return;
      }
    // The dense problem also needs the weights w_i of all nodes. reinit()
    // discards the dense LU factorisation of the previous S, so the next
    // solve_for_pieces() factorises the dense matrix of the new S.
    std::vector<double> weights(contact.size());
    for (unsigned int i = 0; i < contact.size(); ++i)
      weights[i] = contact.weight(i);
    condensed_system.reinit(contact.laws(),
                            std::move(S),
                            gather_on_all_ranks(weights, communicator));
  }



  // @sect4{CondensedContactSolver::compliance_from_last_block}
  //
  // S = X^T X with X = L_c^{-1} N_c^T: N_c^T has one row per contact dof, in
  // the order of the factor's last block, holding the entries of the rows
  // at that dof in their columns; one dense triangular solve with
  // m columns turns it into X, and one dense product gives S. The last
  // block exists on one rank only, so all nodes are this rank's.
  template <int dim>
  FullMatrix<double>
  CondensedContactSolver<dim>::compliance_from_last_block(
    const ContactSet<dim> &contact)
  {
    const unsigned int               m     = row_start.back();
    const std::vector<unsigned int> &order = factorization.last_block_order();
    // The position in the last block of every contact dof.
    std::map<unsigned int, unsigned int> position;
    for (unsigned int k = 0; k < order.size(); ++k)
      position[contact_dofs[order[k]]] = k;
    normal_responses.reinit(order.size(), m);
    for (unsigned int i = 0; i < contact.size(); ++i)
      for (unsigned int j = 0; j < row_start[i + 1] - row_start[i]; ++j)
        for (const auto &entry : contact.row(i, j))
          normal_responses(position.at(entry.local_dof), row_start[i] + j)
            = entry.value;
    factorization.last_block_factor().solve(normal_responses);
    LAPACKFullMatrix<double> S(m, m);
    normal_responses.Tmmult(S, normal_responses);
    FullMatrix<double> result(m, m);
    for (unsigned int i = 0; i < m; ++i)
      for (unsigned int j = 0; j < m; ++j)
        result(i, j) = S(i, j);
    return result;
  }



  // @sect4{CondensedContactSolver::compliance_by_solves}
  //
  // Columns of S are computed for 64 contact nodes at a time: each rank puts
  // the normals of its nodes of the block into the right-hand sides, all
  // ranks solve together, and each reads off the rows of S of its own nodes
  // (it can only evaluate nu_i . w at the dofs it owns). The rows are then
  // gathered on all ranks. Solving a block of right-hand sides at once lets
  // the direct solvers use dense matrix-matrix kernels instead of 64
  // separate triangular solves.
  template <int dim>
  FullMatrix<double>
  CondensedContactSolver<dim>::compliance_by_solves(
    const ContactSet<dim> &contact)
  {
    // The sizes involved: n_local displacement entries on this rank, m_local
    // contact nodes on this rank, m contact nodes in all.
    const unsigned int n_local = free_displacement.locally_owned_size();
    const unsigned int m       = row_start.back();
    const unsigned int first   = first_row(contact, 0);
    const unsigned int m_local = first_row(contact, contact.size()) - first;

    // Row i of own_rows is row first + i of S, the row of this rank's i-th
    // node; the columns are filled block by block below.
    std::vector<double> own_rows(std::size_t(m_local) * m);
    VectorType          column(free_displacement);
    const unsigned int  block = 64;
    std::vector<double> columns;
    for (unsigned int first_column = 0; first_column < m; first_column += block)
      {
        const unsigned int n_columns = std::min(block, m - first_column);
        // The right-hand sides of this block, column-major: column j holds
        // the normal nu of node first_column + j at that node's dofs, on the
        // rank that owns the node, and zeros everywhere else. A rank whose
        // nodes are all outside the block contributes zero columns but still
        // takes part in the collective solve.
        columns.assign(std::size_t(n_local) * n_columns, 0.);
        if (!contact.rows_reach_ghosts())
          {
            for (unsigned int i = 0; i < contact.size(); ++i)
              for (unsigned int row = first_row(contact, i);
                   row < first_row(contact, i + 1);
                   ++row)
                if (row >= first_column && row < first_column + n_columns)
                  for (const auto &entry :
                       contact.row(i, row - first_row(contact, i)))
                    columns[std::size_t(row - first_column) * n_local
                            + entry.local_dof]
                      = entry.value;
          }
        else
          // Rows with entries at ghosts (contact pairs): each column is
          // assembled in a vector and its ghost entries sent to their
          // owners.
          for (unsigned int j = 0; j < n_columns; ++j)
            {
              column = 0;
              for (unsigned int i = 0; i < contact.size(); ++i)
                for (unsigned int row = first_row(contact, i);
                     row < first_row(contact, i + 1);
                     ++row)
                  if (row == first_column + j)
                    contact.add_to_row(column,
                                       i,
                                       row - first_row(contact, i),
                                       1.);
              column.compress(VectorOperation::add);
              std::copy(column.begin(),
                        column.end(),
                        columns.begin() + std::size_t(j) * n_local);
            }
        // One collective solve overwrites the columns with A^{-1} N^T e_j.
        factorization.solve(columns, n_columns);
        this->counts.solves += n_columns;
        // Read off, for every column, the normal displacements at this
        // rank's nodes: S(first + i,
        // first_column + j) = nu_i . (A^{-1} N^T e_j)_i.
        for (unsigned int j = 0; j < n_columns; ++j)
          {
            const double *response = &columns[std::size_t(j) * n_local];
            if (contact.rows_reach_ghosts())
              {
                std::copy(response, response + n_local, column.begin());
                column.update_ghost_values();
              }
            for (unsigned int i = 0; i < contact.size(); ++i)
              for (unsigned int row = first_row(contact, i);
                   row < first_row(contact, i + 1);
                   ++row)
                own_rows[std::size_t(row - first) * m + first_column + j]
                  += contact.rows_reach_ghosts()
                       ? contact.row_component(column,
                                               i,
                                               row - first_row(contact, i))
                       : contact.row_component(response,
                                               i,
                                               row - first_row(contact, i));
          }
      }

    // Every rank now receives all rows; since nodes are numbered rank by
    // rank the gathered vector is S in row-major order.
    const std::vector<double> all_rows
      = gather_on_all_ranks(own_rows, communicator);
    FullMatrix<double> S(m, m);
    for (unsigned int i = 0; i < m; ++i)
      for (unsigned int j = 0; j < m; ++j)
        S(i, j) = all_rows[std::size_t(i) * m + j];
    return S;
  }



  // @sect4{CondensedContactSolver::set_right_hand_side}
  //
  // The free normal displacements d = N A^{-1} b - s, the penetrations the
  // contact nodes would have without any contact force (s the obstacle's
  // gaps): all active-set iterations of the step problem work with d. With the
  // factor's last block, d = X^T y_c needs only the forward half of the solve
  // with b; otherwise the whole solve A^{-1} b is done here (and kept for
  // finish()), and each rank evaluates d at its own nodes. d is needed on every
  // rank, since every rank solves the whole dense problem.
  template <int dim>
  void
  CondensedContactSolver<dim>::set_right_hand_side(
    const VectorType      &b,
    const ContactSet<dim> &contact)
  {
    ++this->counts.solves;
    memory_all.clear();
    adhesion_all.clear();
    openings_all.clear();
    if (contact.has_memory() && !friction)
      memory_all
        = gather_on_all_ranks(contact.history_pressures(), communicator);
    if (contact.has_adhesion() && !friction)
      adhesion_all = gather_on_all_ranks(contact.bondings(), communicator);
    if (contact.has_cohesion() && !friction)
      openings_all
        = gather_on_all_ranks(contact.reached_openings(), communicator);
    if (factorization.has_last_block())
      {
        factorization.forward_solve(b, forward_last);
        d.reinit(row_start.back());
        if (contact.size() > 0)
          normal_responses.Tvmult(d, forward_last);
        for (unsigned int i = 0; i < contact.size() && !friction; ++i)
          d[i] -= contact.gap(i);
        return;
      }
    factorization.solve(free_displacement, b);
    free_displacement.update_ghost_values();
    std::vector<double> own;
    for (unsigned int i = 0; i < contact.size(); ++i)
      for (unsigned int j = 0; j < 1 + contact.n_tangential(i); ++j)
        own.push_back(contact.row_component(free_displacement, i, j)
                      - (friction || j > 0 ? 0. : contact.gap(i)));
    const std::vector<double> all = gather_on_all_ranks(own, communicator);
    d.reinit(all.size());
    std::copy(all.begin(), all.end(), d.begin());
  }



  // @sect4{CondensedContactSolver::solve_for_pieces}
  //
  // One active-set iteration's linear solve: for the pieces the nodes sit on
  // now, solve the dense problem of CondensedContactSystem and hand the
  // forces z and normal displacements r = d - S z back to the nodes of this
  // rank. The displacement u is not touched here; it is formed once, in
  // finish(), when the pieces are final.
  //
  // The solve is direct, so the accuracy asked for does not matter and the
  // report says "converged" with no inner iterations; its residual is the
  // defect the dense solve leaves in the equations of the pieces, which
  // ContactNodes::solve() compares with the Tolerance.
  template <int dim>
  LinearSolveReport
  CondensedContactSolver<dim>::solve_for_pieces(ContactSet<dim> &contact,
                                                VectorType &,
                                                const LinearSolveRequest &)
  {
    if (friction)
      {
        LinearSolveReport report;
        report.residual = solve_frictional(contact);
        return report;
      }
    // The dense problem couples all nodes, so every rank needs the pieces of
    // all of them. Every rank then solves the same problem and finds the
    // same r and z: this replicated arithmetic is what keeps the ranks'
    // decisions in step without further messages.
    // Each node's piece as it acts there: scaled by its bonding, cut at its
    // reached opening, moved up by its memory pressure.
    const std::vector<unsigned int> pieces
      = gather_on_all_ranks(contact.pieces(), communicator);
    std::vector<ContactLawPiece> node_pieces(pieces.size());
    for (unsigned int i = 0; i < pieces.size(); ++i)
      {
        const double beta = adhesion_all.empty() ? 1. : adhesion_all[i];
        node_pieces[i]
          = contact.laws().piece(pieces[i],
                                 {beta * beta,
                                  openings_all.empty() ? 0. : openings_all[i]});
        if (!memory_all.empty() && !node_pieces[i].vertical)
          node_pieces[i].intercept += memory_all[i];
      }
    LinearSolveReport report;
    report.residual = condensed_system.solve(node_pieces, d, r_all, z_all);
    // Of the global result, this rank keeps the entries of its own nodes,
    // which is what ContactNodes::update_pieces() reads.
    const types::global_dof_index first = contact.first_global_index();
    for (unsigned int i = 0; i < contact.size(); ++i)
      {
        contact.r[i] = r_all[first + i];
        contact.z[i] = z_all[first + i];
      }
    return report;
  }



  // @sect4{CondensedContactSolver::solve_frictional}
  //
  // With friction every node has one equation per row of its frame, along
  // its directions a_k (ContactNodes::directions()): with y = d - S f the
  // displacements and f the forces along the rows (f_i0 the normal force),
  //   fixed:  a_k . y_i = beta_k, i.e. -a_k . (S f)_i = beta_k - a_k . d_i;
  //   free:   a_k . f_i = value_k + k_k a_k . y_i + c_k f_i0, i.e.
  //           a_k . f_i - c_k f_i0 + k_k a_k . (S f)_i
  //             = value_k + k_k a_k . d_i.
  // The matrix of these rows is unsymmetric (a slipping node's force is
  // known along its direction), and every rank factorises the same one by
  // LU, from the directions of all nodes gathered on every rank.
  template <int dim>
  double
  CondensedContactSolver<dim>::solve_frictional(ContactSet<dim> &contact)
  {
    // Per node: the number of directions, then per direction its frame
    // vector, whether it is fixed, its value, its stiffness and its
    // coupling.
    constexpr unsigned int      record = 1 + 3 * 7;
    std::vector<double>         own;
    std::vector<NodeDirections> own_directions(contact.size());
    own.reserve(record * contact.size());
    for (unsigned int i = 0; i < contact.size(); ++i)
      {
        const NodeDirections &directions = own_directions[i]
          = contact.directions(i, contact.gap(i));
        own.push_back(directions.size);
        for (const NodeDirection &direction : directions.direction)
          {
            own.insert(own.end(),
                       direction.frame.begin(),
                       direction.frame.end());
            own.push_back(direction.fixed ? 1. : 0.);
            own.push_back(direction.value);
            own.push_back(direction.stiffness);
            own.push_back(direction.coupling);
          }
      }
    const std::vector<double> all = gather_on_all_ranks(own, communicator);

    // A node free along all its rows with no stiffness, value or coupling
    // (out of contact, not bonded) carries no force: its rows read
    // a_k . f_i = 0 in a full frame, so f_i = 0, and the dense problem is
    // that of the other nodes' rows alone. Only the nodes in or near
    // contact are left: on the Hertz sphere's ramp at N = 32 a few hundred
    // of 3267 rows, where factorising all of them took 3.9 s a step.
    const unsigned int        m = row_start.back();
    const FullMatrix<double> &S = frictional_compliance;
    std::vector<unsigned int> kept; // the rows of the problem
    kept.reserve(m);
    for (unsigned int n = 0; n + 1 < row_start.size(); ++n)
      {
        const double      *node  = &all[std::size_t(n) * record];
        const unsigned int rows  = row_start[n + 1] - row_start[n];
        bool               carry = (static_cast<unsigned int>(node[0]) != rows);
        for (unsigned int k = 0; k < static_cast<unsigned int>(node[0]); ++k)
          {
            const double *a = node + 1 + 7 * k;
            carry = carry || a[3] == 1. || a[4] != 0 || a[5] != 0 || a[6] != 0;
          }
        if (carry)
          for (unsigned int r = row_start[n]; r < row_start[n + 1]; ++r)
            kept.push_back(r);
      }
    const unsigned int        n_kept = kept.size();
    std::vector<unsigned int> position(m, numbers::invalid_unsigned_int);
    for (unsigned int j = 0; j < n_kept; ++j)
      position[kept[j]] = j;

    FullMatrix<double> M(n_kept, n_kept);
    Vector<double>     h(n_kept);
    for (unsigned int n = 0; n + 1 < row_start.size(); ++n)
      {
        const unsigned int base = row_start[n];
        if (position[base] == numbers::invalid_unsigned_int)
          continue;
        const double *node = &all[std::size_t(n) * record];
        for (unsigned int k = 0; k < static_cast<unsigned int>(node[0]); ++k)
          {
            const double      *a         = node + 1 + 7 * k;
            const bool         fixed     = (a[3] == 1.);
            const double       value     = a[4];
            const double       stiffness = a[5];
            const double       coupling  = a[6];
            const unsigned int row       = position[base + k];
            double             a_d       = 0;
            for (unsigned int r = 0; r < row_start[n + 1] - base; ++r)
              a_d += a[r] * d[base + r];
            const double scale = (fixed ? -1. : stiffness);
            for (unsigned int r = 0; r < row_start[n + 1] - base; ++r)
              if (a[r] != 0 && scale != 0)
                for (unsigned int column = 0; column < n_kept; ++column)
                  M(row, column) += scale * a[r] * S(base + r, kept[column]);
            if (fixed)
              h[row] = value - a_d;
            else
              {
                for (unsigned int r = 0; r < row_start[n + 1] - base; ++r)
                  M(row, position[base + r]) += a[r];
                M(row, position[base]) -= coupling;
                h[row] = value + stiffness * a_d;
              }
          }
      }
    // No node in contact or bonded: every force is zero, and the solve is
    // exact. Otherwise the backward error of the dense solve, which
    // ContactNodes::solve() compares with the Tolerance (the rows left out
    // hold exactly).
    Vector<double> f_kept(h);
    double         error = 0;
    if (n_kept > 0)
      {
        LAPACKFullMatrix<double> lu(n_kept, n_kept);
        lu = M;
        lu.compute_lu_factorization();
        lu.solve(f_kept);
        Vector<double> defect(n_kept);
        M.vmult(defect, f_kept);
        defect -= h;
        error
          = defect.linfty_norm()
            / std::max(M.linfty_norm() * f_kept.linfty_norm() + h.linfty_norm(),
                       1e-300);
      }
    Vector<double> f(m);
    for (unsigned int j = 0; j < n_kept; ++j)
      f[kept[j]] = f_kept[j];

    // y = d - S f, and every own node's displacements along its directions
    // and forces along the fixed ones.
    // Only the columns of the rows kept carry forces: S f reads those (a
    // product with all of S read 85 MB per iteration at 3267 rows).
    Vector<double> y(d);
    for (unsigned int row = 0; row < m; ++row)
      {
        double sum = 0;
        for (unsigned int j = 0; j < n_kept; ++j)
          sum += S(row, kept[j]) * f_kept[j];
        y[row] -= sum;
      }
    const unsigned int first_node = contact.first_global_index();
    for (unsigned int i = 0; i < contact.size(); ++i)
      {
        const NodeDirections &directions    = own_directions[i];
        const unsigned int    base          = row_start[first_node + i];
        std::array<double, 3> displacements = {{0, 0, 0}}, forces = {{0, 0, 0}};
        for (unsigned int k = 0; k < directions.size; ++k)
          for (unsigned int r = 0; r < directions.size; ++r)
            {
              displacements[k]
                += directions.direction[k].frame[r] * y[base + r];
              forces[k] += directions.direction[k].frame[r] * f[base + r];
            }
        contact.store_solution(i,
                               contact.gap(i),
                               directions,
                               displacements.data(),
                               forces.data());
      }
    z_all = f;
    return error;
  }



  // @sect4{CondensedContactSolver::first_row}
  template <int dim>
  unsigned int
  CondensedContactSolver<dim>::first_row(const ContactSet<dim> &contact,
                                         const unsigned int     i) const
  {
    return row_start[contact.first_global_index() + i];
  }



  // @sect4{CondensedContactSolver::finish}
  //
  // u = A^{-1} (b - N^T z) once the active-set iteration has converged.
  // With the last block, the force changes the forward solve's last block
  // by -X z, and the backward half of the solve completes u. Otherwise the
  // nodal forces N^T z of this rank's nodes are assembled and solved for,
  // and the response subtracted from A^{-1} b.
  template <int dim>
  void
  CondensedContactSolver<dim>::finish(const ContactSet<dim> &contact,
                                      VectorType            &u)
  {
    const bool has_force = (z_all.size() > 0 && z_all.linfty_norm() > 0);
    if (factorization.has_last_block())
      {
        Vector<double> change(forward_last.size());
        if (has_force)
          {
            normal_responses.vmult(change, z_all);
            change *= -1.;
          }
        factorization.backward_solve(change, u);
        return;
      }
    u = free_displacement;
    if (!has_force)
      return;
    VectorType forces(free_displacement), response(free_displacement);
    forces = 0;
    for (unsigned int i = 0; i < contact.size(); ++i)
      if (friction)
        for (unsigned int row = first_row(contact, i);
             row < first_row(contact, i + 1);
             ++row)
          contact.add_to_row(forces,
                             i,
                             row - first_row(contact, i),
                             z_all[row]);
      else
        contact.add_normal(forces, i, contact.z[i]);
    forces.compress(VectorOperation::add);
    factorization.solve(response, forces);
    ++this->counts.solves;
    u -= response;
  }



  // @sect4{CondensedContactSolver::solve_without_contact}
  //
  // A^{-1} b with the factorisation: the step problem when the scene has no
  // contact, and the reference solve of the run summary's cost measurements.
  // A direct solve has nothing to report but success.
  template <int dim>
  LinearSolveReport
  CondensedContactSolver<dim>::solve_without_contact(const VectorType &b,
                                                     VectorType       &u)
  {
    factorization.solve(u, b);
    ++this->counts.solves;
    return LinearSolveReport();
  }



  // @sect4{CondensedContactSolver::forget_kept_state}
  //
  // A resumed run factorises the dense problem of its first pieces afresh;
  // after a checkpoint the uninterrupted run does the same, so that both
  // continue with the same arithmetic (a kept factorisation corrected for
  // changed rows agrees with a new one to rounding only, which the error
  // estimate of the time series, a difference of nearly equal increments,
  // magnified to 1e-9 relative).
  template <int dim>
  void
  CondensedContactSolver<dim>::forget_kept_state()
  {
    condensed_system.forget_factorization();
  }



  // @sect4{CondensedContactSolver::apply_compliance}
  //
  // y = S x for the Lanczos iteration of the uniqueness test (doc/model.md,
  // section 4). x and y are indexed by this rank's contact nodes; the
  // product itself is a dense one with the rows of S that belong to them,
  // since S is available on every rank. It is collective because x has to be
  // gathered first.
  template <int dim>
  void
  CondensedContactSolver<dim>::apply_compliance(const ContactSet<dim> &contact,
                                                const Vector<double>  &x,
                                                Vector<double>        &y)
  {
    const std::vector<double> x_all
      = gather_on_all_ranks(std::vector<double>(x.begin(), x.end()),
                            communicator);
    const FullMatrix<double> &S
      = (friction ? frictional_compliance : condensed_system.compliance());
    const types::global_dof_index first = contact.first_global_index();
    // Only the rows of this rank's nodes are formed: the entries of y that
    // belong to other ranks are computed there. With friction, the normal
    // rows of S.
    y.reinit(contact.size());
    for (unsigned int i = 0; i < contact.size(); ++i)
      for (unsigned int j = 0; j < x_all.size(); ++j)
        y[i] += S(row_start[first + i], row_start[j]) * x_all[j];
  }



  // @sect4{Instantiations and the factory}
  //
  // The class is only known in this file; the rest of the program sees it
  // through the ContactSolver interface, and create_contact_solver()
  // (contact_solver.cc) reaches its constructor through this function.
  template class CondensedContactSolver<2>;
  template class CondensedContactSolver<3>;

  template <int dim>
  std::unique_ptr<ContactSolver<dim>>
  create_condensed_contact_solver(const Parameters::AllParameters &parameters,
                                  const VectorType                &layout)
  {
    return std::make_unique<CondensedContactSolver<dim>>(parameters, layout);
  }

  template std::unique_ptr<ContactSolver<2>>
  create_condensed_contact_solver(const Parameters::AllParameters &,
                                  const VectorType &);
  template std::unique_ptr<ContactSolver<3>>
  create_condensed_contact_solver(const Parameters::AllParameters &,
                                  const VectorType &);
} // namespace ViscoContact
