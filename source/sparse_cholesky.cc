#include <deal.II/base/exceptions.h>

#include "sparse_cholesky.h"

#include <cholmod.h>

#include <algorithm>
#include <limits>
#include <string>
#include <utility>

namespace ViscoContact
{
  namespace
  {
    // CHOLMOD reports failures through Common->status; turn the code into
    // words for the exception messages (printing is switched off below).
    std::string
    cholmod_status_message(const int status)
    {
      switch (status)
        {
          case CHOLMOD_OK:
            return "no error";
          case CHOLMOD_NOT_INSTALLED:
            return "method not installed";
          case CHOLMOD_OUT_OF_MEMORY:
            return "out of memory";
          case CHOLMOD_TOO_LARGE:
            return "integer overflow (problem too large)";
          case CHOLMOD_INVALID:
            return "invalid input";
          case CHOLMOD_GPU_PROBLEM:
            return "GPU failure";
          case CHOLMOD_NOT_POSDEF:
            return "matrix not positive definite";
          case CHOLMOD_DSMALL:
            return "tiny diagonal entry in the factor";
          default:
            return "unknown status " + std::to_string(status);
        }
    }
  } // namespace



  // @sect4{SparseCholesky::Implementation}
  //
  // All CHOLMOD objects live here. We use the SuiteSparse_long interface
  // (cholmod_l_*) throughout, so that neither the size of the matrix nor
  // the number of entries of the factor, which can be much larger than that
  // of the matrix, can overflow an int. The cholmod_common holds CHOLMOD's
  // parameters, statistics and workspace; it is also written to by the
  // solves, which are const for the user of the class.
  struct SparseCholesky::Implementation
  {
    Implementation()
    {
      cholmod_l_start(&common);
      // Errors are turned into exceptions; CHOLMOD must not also print them.
      common.print = 0;
      // Always the supernodal method: dense kernels for the factorisation
      // and a BLAS-3 solve for blocks of right-hand sides.
      common.supernodal = CHOLMOD_SUPERNODAL;
      // Try AMD and METIS (nested dissection) and keep the ordering with the
      // least fill: on 2D meshes nested dissection wins clearly.
      common.nmethods           = 2;
      common.method[0].ordering = CHOLMOD_AMD;
      common.method[1].ordering = CHOLMOD_METIS;
      common.postorder          = 1;
    }

    ~Implementation()
    {
      free_factor();
      cholmod_l_finish(&common);
    }

    Implementation(const Implementation &) = delete;
    Implementation &
    operator=(const Implementation &)
      = delete;

    void
    free_factor()
    {
      if (factor != nullptr)
        cholmod_l_free_factor(&factor, &common);
      factor               = nullptr;
      n_nonzeros_in_factor = 0;
      cholmod_l_free_dense(&solution, &common);
      cholmod_l_free_dense(&workspace_y, &common);
      cholmod_l_free_dense(&workspace_e, &common);
    }

    void
    solve(double *values, const std::size_t size, const std::size_t n_columns);

    cholmod_common  common;
    cholmod_factor *factor               = nullptr;
    std::size_t     n_nonzeros_in_factor = 0;
    // Solution and workspaces of cholmod_l_solve2, kept between solves so
    // that a time step allocates nothing (a fresh allocation of this size
    // costs page faults comparable to the solve itself).
    cholmod_dense *solution    = nullptr;
    cholmod_dense *workspace_y = nullptr;
    cholmod_dense *workspace_e = nullptr;
  };



  // @sect4{SparseCholesky::Implementation::solve}
  //
  // CHOLMOD only reads the right-hand side, so instead of copying the user's
  // data into a CHOLMOD-allocated matrix we describe it by a cholmod_dense
  // header pointing to it. cholmod_l_solve2 writes the solution into a
  // matrix it reuses between calls, which we copy back. The sizes are checked
  // also in release mode: a wrong size would make CHOLMOD read and write
  // out of bounds.
  void
  SparseCholesky::Implementation::solve(double           *values,
                                        const std::size_t size,
                                        const std::size_t n_columns)
  {
    AssertThrow(factor != nullptr,
                dealii::ExcMessage("SparseCholesky::solve() needs a "
                                   "successful call of factorize() first."));
    const std::size_t n = factor->n;
    AssertThrow(size == n * n_columns,
                dealii::ExcDimensionMismatch(size, n * n_columns));
    if (n_columns == 0)
      return;

    cholmod_dense rhs;
    rhs.nrow  = n;
    rhs.ncol  = n_columns;
    rhs.nzmax = n * n_columns;
    rhs.d     = n;
    rhs.x     = values;
    rhs.z     = nullptr;
    rhs.xtype = CHOLMOD_REAL;
    rhs.dtype = CHOLMOD_DOUBLE;

    const int ok = cholmod_l_solve2(CHOLMOD_A,
                                    factor,
                                    &rhs,
                                    nullptr,
                                    &solution,
                                    nullptr,
                                    &workspace_y,
                                    &workspace_e,
                                    &common);
    AssertThrow(ok && solution != nullptr,
                dealii::ExcMessage("CHOLMOD's solve failed: "
                                   + cholmod_status_message(common.status)));

    const double *x = static_cast<const double *>(solution->x);
    for (std::size_t j = 0; j < n_columns; ++j)
      std::copy_n(x + j * solution->d, n, values + j * n);
  }



  SparseCholesky::SparseCholesky()
    : implementation(std::make_unique<Implementation>())
  {}



  SparseCholesky::~SparseCholesky() = default;



  // @sect4{SparseCholesky::factorize}
  //
  // CHOLMOD wants a column-compressed (CSC) matrix of which, for a symmetric
  // matrix, one triangle suffices. deal.II stores A row by row (CSR), and
  // row i of A restricted to the columns j >= i is, read as a column, the
  // column i of the lower triangle of A^T = A. So we pass the entries with
  // j >= i of each row as column i of a matrix with stype = -1 ("lower
  // triangle stored"), and only the upper triangle of A is ever read.
  //
  // CHOLMOD expects sorted row indices within a column. deal.II stores the
  // diagonal entry first in each row of a square matrix and the others in
  // ascending order, so the kept entries are in fact already sorted; since
  // this is an implementation detail of deal.II we sort anyway, which costs
  // nothing compared to the factorisation.
  //
  // cholmod_l_analyze computes the fill-reducing ordering (CHOLMOD's
  // default strategy: AMD, and METIS as well if AMD gives much fill) and the
  // supernodal structure; cholmod_l_factorize computes the numbers. A matrix
  // that is not positive definite is not an error for CHOLMOD: it stops at
  // the first non-positive pivot, sets status to CHOLMOD_NOT_POSDEF and
  // records the column in L->minor (< n), which we check and report.
  void
  SparseCholesky::factorize(const dealii::SparseMatrix<double> &A)
  {
    AssertThrow(A.m() == A.n(),
                dealii::ExcMessage("SparseCholesky::factorize() needs a "
                                   "square matrix, but the matrix has "
                                   + std::to_string(A.m()) + " rows and "
                                   + std::to_string(A.n()) + " columns."));
    AssertThrow(A.m() <= std::numeric_limits<unsigned int>::max(),
                dealii::ExcMessage("SparseCholesky::factorize(): the matrix "
                                   "is too large."));

    implementation->free_factor();
    cholmod_common &common = implementation->common;
    const auto      n      = static_cast<std::size_t>(A.m());

    std::size_t n_entries = 0;
    for (std::size_t i = 0; i < n; ++i)
      for (auto entry = A.begin(i); entry != A.end(i); ++entry)
        if (entry->column() >= i)
          ++n_entries;

    // The CHOLMOD matrix is freed at the end of this function, also when an
    // exception leaves it.
    const auto free_sparse = [&common](cholmod_sparse *matrix) {
      cholmod_l_free_sparse(&matrix, &common);
    };
    std::unique_ptr<cholmod_sparse, decltype(free_sparse)> matrix(
      cholmod_l_allocate_sparse(n,
                                n,
                                n_entries,
                                /*sorted=*/1,
                                /*packed=*/1,
                                /*stype=*/-1,
                                CHOLMOD_REAL,
                                &common),
      free_sparse);
    AssertThrow(matrix != nullptr,
                dealii::ExcMessage("CHOLMOD could not allocate the matrix: "
                                   + cholmod_status_message(common.status)));

    auto *const column_start = static_cast<SuiteSparse_long *>(matrix->p);
    auto *const row_index    = static_cast<SuiteSparse_long *>(matrix->i);
    auto *const value        = static_cast<double *>(matrix->x);

    std::vector<std::pair<SuiteSparse_long, double>> column;
    SuiteSparse_long                                 k = 0;
    for (std::size_t i = 0; i < n; ++i)
      {
        column.clear();
        for (auto entry = A.begin(i); entry != A.end(i); ++entry)
          if (entry->column() >= i)
            column.emplace_back(entry->column(), entry->value());
        std::sort(column.begin(), column.end());

        column_start[i] = k;
        for (const auto &[row, v] : column)
          {
            row_index[k] = row;
            value[k]     = v;
            ++k;
          }
      }
    column_start[n] = k;

    implementation->factor = cholmod_l_analyze(matrix.get(), &common);
    AssertThrow(implementation->factor != nullptr,
                dealii::ExcMessage("CHOLMOD's analysis failed: "
                                   + cholmod_status_message(common.status)));
    // common.lnz is the number of nonzeros of L for the chosen ordering.
    implementation->n_nonzeros_in_factor = static_cast<std::size_t>(common.lnz);

    const int ok
      = cholmod_l_factorize(matrix.get(), implementation->factor, &common);
    cholmod_factor *const L = implementation->factor;

    if (common.status == CHOLMOD_NOT_POSDEF || L->minor < L->n)
      {
        // L->minor counts in the permuted ordering; report the row of A.
        const std::size_t step = L->minor;
        const std::size_t row
          = (L->Perm != nullptr)
              ? static_cast<const SuiteSparse_long *>(L->Perm)[step]
              : step;
        implementation->free_factor();
        AssertThrow(false,
                    dealii::ExcMessage(
                      "SparseCholesky::factorize(): the matrix is not "
                      "positive definite (non-positive pivot at row "
                      + std::to_string(row) + " of " + std::to_string(n)
                      + ", elimination step " + std::to_string(step) + ")."));
      }
    if (!ok || common.status < CHOLMOD_OK)
      {
        const int status = common.status;
        implementation->free_factor();
        AssertThrow(false,
                    dealii::ExcMessage("CHOLMOD's factorisation failed: "
                                       + cholmod_status_message(status)));
      }
  }



  void
  SparseCholesky::solve(dealii::Vector<double> &rhs_and_solution) const
  {
    implementation->solve(rhs_and_solution.data(), rhs_and_solution.size(), 1);
  }



  // @sect4{SparseCholesky::solve for a block of right-hand sides}
  //
  // All columns go to CHOLMOD in one call: the supernodal triangular solves
  // then work on n x n_columns blocks with BLAS-3 kernels instead of
  // repeating the BLAS-2 sweep through L for every column.
  void
  SparseCholesky::solve(std::vector<double> &columns,
                        const unsigned int   n_columns) const
  {
    implementation->solve(columns.data(), columns.size(), n_columns);
  }



  std::size_t
  SparseCholesky::n_nonzeros_in_factor() const
  {
    return implementation->n_nonzeros_in_factor;
  }



  unsigned int
  SparseCholesky::m() const
  {
    return (implementation->factor != nullptr)
             ? static_cast<unsigned int>(implementation->factor->n)
             : 0;
  }
} // namespace ViscoContact
