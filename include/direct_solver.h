#ifndef viscoplastic_contact_direct_solver_h
#define viscoplastic_contact_direct_solver_h

#include <deal.II/base/mpi.h>

#include "linear_algebra.h"
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
  //    (BLAS-3) kernels. An unsymmetric operator (the tangent) is
  //    factorised by UMFPACK instead;
  //  - umfpack: UMFPACK's LU factorisation, on one rank;
  //  - mumps: MUMPS through Trilinos' Amesos, distributed over all ranks
  //    (LDL^T for symmetric operators, LU otherwise).
  // The libraries themselves stay in the implementation file.
  class SparseDirectSolver
  {
  public:
    // kind must not be automatic: the caller resolves it (cholmod on one
    // rank, mumps on several).
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
    void
    factorize(const MatrixType &A, const bool symmetric);

    // Solve A x = b (the locally owned entries of both).
    void
    solve(VectorType &x, const VectorType &b) const;

    // Solve for n_columns right-hand sides at once: columns holds the
    // locally owned rows of an n x n_columns block in column-major order
    // (column j starts at j * n_locally_owned) and is overwritten by the
    // solutions. Collective.
    void
    solve(std::vector<double> &columns, const unsigned int n_columns) const;

    // What was factorised, for the run's header and summary.
    std::string
    description() const;

  private:
    struct Implementation;
    std::unique_ptr<Implementation> implementation;
  };
} // namespace ViscoContact

#endif
