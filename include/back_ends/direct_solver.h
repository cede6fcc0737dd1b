#ifndef viscoplastic_contact_direct_solver_h
#define viscoplastic_contact_direct_solver_h

#include <deal.II/base/mpi.h>

#include <deal.II/lac/lapack_full_matrix.h>
#include <deal.II/lac/vector.h>

#include "back_ends/linear_algebra.h"
#include "parameters.h"

#include <memory>
#include <string>
#include <vector>

namespace ViscoContact
{
  // @sect3{Sparse direct factorisations of the operator}
  //
  // The condensed back end factorises the operator of the step problem once
  // (the elastic operator K) or per Newton iteration (the implicit update's
  // tangent) and solves with it many times; the full space back end can use
  // the same factorisation as its preconditioner. Three factorisations are
  // available, chosen by the Direct solver entry:
  //  - cholmod: CHOLMOD's supernodal Cholesky factorisation K = L L^T, on
  //    one rank. It needs about half of the memory and work of an LU
  //    factorisation and solves many right-hand sides at once with dense
  //    (BLAS-3) kernels; a single right-hand side is solved on the
  //    rank's threads, subtree by subtree of the elimination tree
  //    (supernodal_solve.h). An unsymmetric operator (the tangent) is
  //    factorised by UMFPACK instead;
  //  - umfpack: UMFPACK's LU factorisation, on one rank;
  //  - mumps: MUMPS through Trilinos' Amesos, distributed over all ranks
  //    (LDL^T for symmetric operators, LU otherwise).
  // The libraries themselves stay in the implementation file.
  class SparseDirectSolver
  {
  public:
    // kind = automatic means cholmod on one rank, mumps on several.
    SparseDirectSolver(const Parameters::DirectSolver kind,
                       const MPI_Comm                 communicator);
    ~SparseDirectSolver();
    SparseDirectSolver(const SparseDirectSolver &) = delete;
    SparseDirectSolver &
    operator=(const SparseDirectSolver &)
      = delete;

    // Analyse and factorise A; symmetric says whether its values are (the
    // elastic operator) or not (a tangent). Replaces an earlier
    // factorisation. Throws an ExcMessage that names the solver and the
    // reason if the factorisation fails (e.g. a matrix that is not
    // positive definite for CHOLMOD).
    //
    // last_rows (local row indices, e.g. the contact dofs) asks for an
    // elimination order that ends with these rows. CHOLMOD can do this for
    // a symmetric operator: then has_last_block() is true, and the last
    // block L_c of the factor P A P^T = L L^T is the Cholesky factor of the
    // Schur complement of A on these rows, so (A^{-1}) on these rows is
    // L_c^{-T} L_c^{-1}, read off the factor without any further solve.
    void
    factorize(const MatrixType                &A,
              const bool                       symmetric,
              const std::vector<unsigned int> &last_rows = {});

    // Whether the last factorisation ends with last_rows (see above).
    bool
    has_last_block() const;

    // The lower triangular last block L_c of the factor (size of last_rows),
    // in the factor's order: its row k is last_rows[last_block_order()[k]].
    const LAPACKFullMatrix<double> &
    last_block_factor() const;
    const std::vector<unsigned int> &
    last_block_order() const;

    // A solve split at the last block, for a right-hand side that changes
    // in the last rows between the two halves: forward_solve() computes
    // y = L^{-1} P b, keeps it and returns its last block y_c (in the
    // factor's order); backward_solve() adds change to y_c and completes
    // x = P^T L^{-T} y. Together they cost one solve.
    void
    forward_solve(const VectorType &b, Vector<double> &last_block) const;
    void
    backward_solve(const Vector<double> &change, VectorType &x) const;

    // Solve A x = b (the locally owned entries of both).
    void
    solve(VectorType &x, const VectorType &b) const;

    // Solve for n_columns right-hand sides at once: columns holds the
    // locally owned rows of an n x n_columns block in column-major order
    // (column j starts at j * n_locally_owned) and is overwritten by the
    // solutions. Collective.
    void
    solve(std::vector<double> &columns, const unsigned int n_columns) const;

    // Single right-hand sides are solved with a CHOLMOD factor on threads,
    // subtree by subtree of its elimination tree (supernodal_solve.h): how
    // many subtrees the last factorisation gave (0: none, e.g. where
    // CHOLMOD's own solve is kept, or for other factorisations).
    std::size_t
    n_threaded_subtrees() const;

    // What was factorised, for the run's header and summary.
    std::string
    description() const;

  private:
    struct Implementation;
    std::unique_ptr<Implementation> implementation;
  };
} // namespace ViscoContact

#endif
