#ifndef viscoplastic_contact_sparse_cholesky_h
#define viscoplastic_contact_sparse_cholesky_h

#include <deal.II/lac/sparse_matrix.h>
#include <deal.II/lac/vector.h>

#include <cstddef>
#include <memory>
#include <vector>

namespace ViscoContact
{
  // @sect3{A sparse Cholesky factorisation with CHOLMOD}
  //
  // The elastic stiffness matrix K is symmetric positive definite and is
  // factorised once and then used for many solves (the free displacements
  // and the columns of the contact compliance N K^{-1} N^T). UMFPACK, which
  // deal.II wraps in SparseDirectUMFPACK, computes an LU factorisation that
  // ignores the symmetry; CHOLMOD's supernodal Cholesky factorisation
  // K = L L^T needs about half the memory and work and solves many
  // right-hand sides at once with dense (BLAS-3) kernels.
  //
  // This class is a thin wrapper: factorize() takes the upper triangle of
  // the matrix (the values are assumed to be symmetric, which is not
  // checked), lets CHOLMOD choose the fill-reducing ordering (AMD, or METIS
  // if that is clearly better) and factorises; solve() then solves with the
  // factor. CHOLMOD itself is hidden in the implementation file, so users of
  // this header neither see nor need its headers.
  //
  // solve() is logically const but uses CHOLMOD's workspace, so one object
  // must not be used for solves from several threads at the same time.
  class SparseCholesky
  {
  public:
    SparseCholesky();
    ~SparseCholesky();
    SparseCholesky(const SparseCholesky &) = delete;
    SparseCholesky &
    operator=(const SparseCholesky &)
      = delete;

    // Analyse (fill-reducing ordering chosen by CHOLMOD) and factorise
    // A = L L^T, replacing any previous factorisation. A must be square with
    // symmetric values; only its upper triangle is read. Throws
    // dealii::ExcMessage if A is not positive definite or CHOLMOD fails; the
    // object is then left without a factorisation.
    void
    factorize(const dealii::SparseMatrix<double> &A);

    // Solve A x = b in place.
    void
    solve(dealii::Vector<double> &rhs_and_solution) const;

    // Solve for n_columns right-hand sides at once: `columns` holds an
    // n x n_columns dense block in column-major order (column j starts at
    // j*n) and is overwritten by the solutions.
    void
    solve(std::vector<double> &columns, const unsigned int n_columns) const;

    // Number of nonzeros of the factor L (diagonal included, without the
    // explicit zeros of the supernodal storage), for reporting.
    std::size_t
    n_nonzeros_in_factor() const;

    // The size of the factorised matrix, zero without a factorisation.
    unsigned int
    m() const;

  private:
    struct Implementation;
    std::unique_ptr<Implementation> implementation;
  };
} // namespace ViscoContact

#endif
