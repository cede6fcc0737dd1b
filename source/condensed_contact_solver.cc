// The condensed back end: the operator factorised by a sparse direct solver,
// the contact problem of fixed pieces solved on the contact nodes.
//
// This file implements option (a) of doc/model.md, section 2 ("Two ways to
// solve the linear problem of fixed pieces"). The bulk unknowns are
// eliminated once per operator: with the contact compliance S = N A^{-1} N^T
// and the free normal displacements d = N A^{-1} b, the active-set iteration
// only ever sees the small dense problem r = d - S z of
// CondensedContactSystem (condensed_system.cc), and the displacement is
// assembled once, at the end of the step problem, as u = A^{-1} b - W z.

#include <deal.II/base/exceptions.h>
#include <deal.II/base/mpi.h>

#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/lapack_full_matrix.h>

#include "condensed_system.h"
#include "contact_solver.h"
#include "direct_solver.h"

#include <algorithm>

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
  // u = A^{-1} b - W z, W = A^{-1} N^T, and the contact problem of fixed
  // pieces is the dense m x m problem of CondensedContactSystem on the
  // contact compliance S = N W. set_operator() pays for it: one
  // factorisation and one solve per contact node (in blocks of 64 right-hand
  // sides, which CHOLMOD solves with BLAS-3 kernels). After that, an
  // active-set iteration never touches the bulk unknowns, and a step costs
  // one solve with A plus the product W z.
  //
  // For the explicit stress update the operator is the elastic K for the
  // whole run, so this set-up is paid once; for the implicit update it is
  // paid again in every Newton iteration, with the new tangent.
  //
  // On several ranks the factorisation is MUMPS', each rank keeps the rows
  // of W of its own dofs, and S (m^2 doubles) is held by every rank, which
  // solves the small dense problem itself. Replicating S is what makes the
  // active-set iteration free of communication beyond a few gathers of
  // node-sized vectors: every rank has the same S, the same d and the same
  // pieces, does the same arithmetic and thus reaches the same forces and
  // the same decisions, so no rank has to wait for another's answer. The
  // price is memory that does not shrink with the number of ranks. That is
  // why Method = auto chooses this back end only on one rank and for small
  // contact surfaces.
  template <int dim>
  class CondensedContactSolver : public ContactSolver<dim>
  {
  public:
    CondensedContactSolver(const Parameters::AllParameters &parameters,
                           const VectorType                &layout);

    // Set-up: the factorisation of A, and W and S from one solve per
    // contact node.
    void
    set_operator(const MatrixType      &A,
                 const bool             symmetric,
                 const ContactSet<dim> &contact) override;
    std::string
    description() const override;
    // Per step problem: A^{-1} b and d = N A^{-1} b; per active-set
    // iteration: the dense problem on the contact nodes; at the end:
    // u = A^{-1} b - W z.
    void
    set_right_hand_side(const VectorType      &b,
                        const ContactSet<dim> &contact) override;
    LinearSolveReport
    solve_for_pieces(ContactSet<dim> &contact, VectorType &u) override;
    void
    finish(const ContactSet<dim> &contact, VectorType &u) override;
    // S x, and a solve with the factorisation.
    void
    apply_compliance(const ContactSet<dim> &contact,
                     const Vector<double>  &x,
                     Vector<double>        &y) override;
    LinearSolveReport
    solve_without_contact(const VectorType &b, VectorType &u) override;

  private:
    const MPI_Comm         communicator;
    SparseDirectSolver     factorization;
    CondensedContactSystem condensed_system;

    // W = A^{-1} N^T, the rows of the locally owned dofs, kept when it
    // takes less than 1 GiB on this rank (the product W z is then one BLAS
    // call); otherwise finish() solves once more.
    LAPACKFullMatrix<double> contact_responses;
    bool                     responses_stored = false;

    // A^{-1} b, the free normal displacements d = N A^{-1} b and the
    // forces z of all contact nodes.
    VectorType     free_displacement;
    Vector<double> d, r_all, z_all;
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
    , factorization(parameters.direct_solver
                        == Parameters::DirectSolver::automatic
                      ? (Utilities::MPI::n_mpi_processes(communicator) == 1
                           ? Parameters::DirectSolver::cholmod
                           : Parameters::DirectSolver::mumps)
                      : parameters.direct_solver,
                    communicator)
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
  // factorisation, the columns of W = A^{-1} N^T and the compliance S = N W.
  // Column j of W is the displacement caused by a unit normal force at
  // contact node j, and S(i, j) is the normal displacement this force causes
  // at node i.
  //
  // Columns of W are computed for 64 contact nodes at a time: each rank puts
  // the normals of its nodes of the block into the right-hand sides, all
  // ranks solve together, and each reads off the rows of S of its own nodes
  // (it can only evaluate nu_i . w at the dofs it owns). The rows are then
  // gathered on all ranks. Solving a block of right-hand sides at once lets
  // the direct solvers use dense matrix-matrix kernels instead of 64
  // separate triangular solves.
  template <int dim>
  void
  CondensedContactSolver<dim>::set_operator(const MatrixType      &A,
                                            const bool             symmetric,
                                            const ContactSet<dim> &contact)
  {
    // A new operator replaces the old factorisation (the implicit update
    // calls this once per Newton iteration).
    factorization.factorize(A, symmetric);
    ++this->counts.operator_setups;

    // The sizes involved: n_local displacement entries on this rank, m_local
    // contact nodes on this rank, m contact nodes in all.
    const unsigned int n_local = free_displacement.locally_owned_size();
    const unsigned int m_local = contact.size();
    const unsigned int m       = contact.n_global_nodes();
    if (m == 0) // no contact: the factorisation is all there is to do
      return;
    const types::global_dof_index first = contact.first_global_index();
    // Whether W is kept depends on its size: n_local x m doubles on each
    // rank. Below 1 GiB, finish() can form W z with one dense product;
    // above, W would be the largest object of the run, and finish() pays one
    // more solve instead. All ranks must take the same decision, since that
    // solve is collective: W is kept only if it fits on every rank.
    responses_stored
      = Utilities::MPI::min(8. * n_local * m < 1024. * 1024. * 1024. ? 1 : 0,
                            communicator)
        == 1;
    contact_responses.reinit(responses_stored ? n_local : 0,
                             responses_stored ? m : 0);

    // Row i of own_rows is row first + i of S, the row of this rank's i-th
    // node; the columns are filled block by block below.
    std::vector<double> own_rows(std::size_t(m_local) * m);
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
        for (unsigned int i = 0; i < m_local; ++i)
          if (first + i >= first_column && first + i < first_column + n_columns)
            for (unsigned int c = 0; c < dim; ++c)
              columns[std::size_t(first + i - first_column) * n_local
                      + contact.node(i).local_dofs[c]]
                = contact.node(i).normal[c];
        // One collective solve overwrites the columns with A^{-1} N^T e_j.
        factorization.solve(columns, n_columns);
        this->counts.solves += n_columns;
        // Read off, for every column, the normal displacements at this
        // rank's nodes: S(first + i,
        // first_column + j) = nu_i . (A^{-1} N^T e_j)_i.
        for (unsigned int j = 0; j < n_columns; ++j)
          {
            const double *response = &columns[std::size_t(j) * n_local];
            for (unsigned int i = 0; i < m_local; ++i)
              for (unsigned int c = 0; c < dim; ++c)
                own_rows[std::size_t(i) * m + first_column + j]
                  += contact.node(i).normal[c]
                     * response[contact.node(i).local_dofs[c]];
            // The same column, on the owned entries, is a column of W.
            if (responses_stored)
              for (unsigned int k = 0; k < n_local; ++k)
                contact_responses(k, first_column + j) = response[k];
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
    // S is symmetric in exact arithmetic when A is; make it so in floating
    // point. For an unsymmetric tangent S is left as computed, and the dense
    // problem is solved by LU anyway.
    if (symmetric)
      for (unsigned int i = 0; i < m; ++i)
        for (unsigned int j = 0; j < i; ++j)
          S(i, j) = S(j, i) = 0.5 * (S(i, j) + S(j, i));

    // The dense problem also needs the weights w_i of all nodes. reinit()
    // discards the dense LU factorisation of the previous S, so the next
    // solve_for_pieces() factorises the dense matrix of the new S.
    std::vector<double> weights(m_local);
    for (unsigned int i = 0; i < m_local; ++i)
      weights[i] = contact.weight(i);
    condensed_system.reinit(contact.law(),
                            S,
                            gather_on_all_ranks(weights, communicator));
  }



  // @sect4{CondensedContactSolver::set_right_hand_side}
  //
  // One solve per step problem gives A^{-1} b and with it the free normal
  // displacements d = N A^{-1} b, the normal displacements the contact nodes
  // would have without any contact force. This is the only sparse solve of a
  // step problem (besides the one in finish() when W is not stored): all
  // active-set iterations then work with d. d is needed on every rank, since
  // every rank solves the whole dense problem.
  template <int dim>
  void
  CondensedContactSolver<dim>::set_right_hand_side(
    const VectorType      &b,
    const ContactSet<dim> &contact)
  {
    factorization.solve(free_displacement, b);
    ++this->counts.solves;
    // Each rank evaluates d at its own nodes (their dofs are owned entries
    // of the solution), then the pieces are put together in global node
    // order.
    std::vector<double> own(contact.size());
    for (unsigned int i = 0; i < contact.size(); ++i)
      own[i] = contact.normal_component(free_displacement, i);
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
  // The solve is direct, so the report says "converged" with no inner
  // iterations; its residual is the defect the dense solve leaves in the
  // equations of the pieces, which ContactNodes::solve() compares with the
  // Tolerance.
  template <int dim>
  LinearSolveReport
  CondensedContactSolver<dim>::solve_for_pieces(ContactSet<dim> &contact,
                                                VectorType &)
  {
    // The dense problem couples all nodes, so every rank needs the pieces of
    // all of them. Every rank then solves the same problem and finds the
    // same r and z: this replicated arithmetic is what keeps the ranks'
    // decisions in step without further messages.
    const std::vector<unsigned int> pieces
      = gather_on_all_ranks(contact.pieces(), communicator);
    LinearSolveReport report;
    report.residual = condensed_system.solve(pieces, d, r_all, z_all);
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



  // @sect4{CondensedContactSolver::finish}
  //
  // u = A^{-1} b - W z once the active set has converged: a dense product
  // over the nodes with a force, or one more solve when W is not stored.
  template <int dim>
  void
  CondensedContactSolver<dim>::finish(const ContactSet<dim> &contact,
                                      VectorType            &u)
  {
    const unsigned int n_local = free_displacement.locally_owned_size();
    u                          = free_displacement;
    // Without any contact force the free displacement is the answer.
    if (z_all.size() == 0 || z_all.linfty_norm() == 0)
      return;
    // With W stored on this rank: W z as one matrix-vector product over the
    // owned rows (a BLAS call on the LAPACK matrix), subtracted from the
    // owned entries of u. The ghosts of u are updated by the caller.
    if (responses_stored)
      {
        Vector<double> response(n_local);
        contact_responses.vmult(response, z_all);
        for (unsigned int k = 0; k < n_local; ++k)
          u.local_element(k) -= response[k];
        return;
      }
    // Otherwise: assemble the nodal forces N^T z of this rank's nodes and
    // solve with the factorisation once more. This is the same displacement,
    // at the cost of one solve instead of n_local m doubles of storage.
    VectorType forces(free_displacement), response(free_displacement);
    forces = 0;
    for (unsigned int i = 0; i < contact.size(); ++i)
      contact.add_normal(forces, i, contact.z[i]);
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
    const FullMatrix<double>     &S     = condensed_system.compliance();
    const types::global_dof_index first = contact.first_global_index();
    // Only the rows of this rank's nodes are formed: the entries of y that
    // belong to other ranks are computed there.
    y.reinit(contact.size());
    for (unsigned int i = 0; i < contact.size(); ++i)
      for (unsigned int j = 0; j < x_all.size(); ++j)
        y[i] += S(first + i, j) * x_all[j];
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
