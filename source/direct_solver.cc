// Sparse direct factorisations of the operator: CHOLMOD and UMFPACK on one
// rank, MUMPS (through Amesos) on any number of ranks.

#include <deal.II/base/exceptions.h>
#include <deal.II/base/utilities.h>

#include "direct_solver.h"

#include <Amesos.h>
#include <Amesos_BaseSolver.h>
#include <Epetra_CrsMatrix.h>
#include <Epetra_LinearProblem.h>
#include <Epetra_Map.h>
#include <Epetra_MultiVector.h>
#include <Teuchos_ParameterList.hpp>
#include <cholmod.h>
#include <umfpack.h>

#include <algorithm>
#include <utility>

namespace ViscoContact
{
  namespace
  {
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
          case CHOLMOD_NOT_POSDEF:
            return "matrix not positive definite";
          case CHOLMOD_DSMALL:
            return "tiny diagonal entry in the factor";
          default:
            return "status " + std::to_string(status);
        }
    }



    // The rows of a matrix that lives on one rank in compressed sparse row
    // form with global column indices, sorted in each row: what CHOLMOD
    // (read as the columns of the symmetric matrix) and UMFPACK (as the
    // columns of the transpose) take.
    struct CompressedRows
    {
      std::vector<SuiteSparse_long> row_start;
      std::vector<SuiteSparse_long> column;
      std::vector<double>           value;
    };

    // keep(i, j): which entries to take (CHOLMOD reads one triangle only).
    template <typename Predicate>
    CompressedRows
    compressed_rows(const MatrixType &A, const Predicate &keep)
    {
      const Epetra_CrsMatrix &matrix = A.trilinos_matrix();
      const int               n      = matrix.NumMyRows();
      CompressedRows          rows;
      rows.row_start.reserve(n + 1);
      rows.row_start.push_back(0);
      std::vector<std::pair<SuiteSparse_long, double>> row;
      for (int i = 0; i < n; ++i)
        {
          int     n_entries = 0;
          double *values    = nullptr;
          int    *indices   = nullptr;
          matrix.ExtractMyRowView(i, n_entries, values, indices);
          const SuiteSparse_long global_row = matrix.RowMap().GID64(i);
          row.clear();
          for (int k = 0; k < n_entries; ++k)
            {
              const SuiteSparse_long global_column
                = matrix.ColMap().GID64(indices[k]);
              if (keep(global_row, global_column))
                row.emplace_back(global_column, values[k]);
            }
          std::sort(row.begin(), row.end());
          for (const auto &[j, v] : row)
            {
              rows.column.push_back(j);
              rows.value.push_back(v);
            }
          rows.row_start.push_back(rows.column.size());
        }
      return rows;
    }
  } // namespace



  // @sect4{The implementations}
  //
  // One struct holds whichever factorisation was chosen; only one of its
  // parts is in use.
  struct SparseDirectSolver::Implementation
  {
    Implementation(const Parameters::DirectSolver kind,
                   const MPI_Comm                 communicator)
      : kind(kind)
      , communicator(communicator)
    {
      cholmod_l_start(&cholmod);
      cholmod.print      = 0;
      cholmod.supernodal = CHOLMOD_SUPERNODAL;
      // Let CHOLMOD pick the better of AMD and METIS orderings.
      cholmod.nmethods           = 2;
      cholmod.method[0].ordering = CHOLMOD_AMD;
      cholmod.method[1].ordering = CHOLMOD_METIS;
      cholmod.postorder          = 1;
    }

    ~Implementation()
    {
      clear();
      cholmod_l_finish(&cholmod);
    }

    void
    clear()
    {
      if (cholmod_factor_ != nullptr)
        cholmod_l_free_factor(&cholmod_factor_, &cholmod);
      cholmod_l_free_dense(&cholmod_solution, &cholmod);
      cholmod_l_free_dense(&cholmod_workspace_y, &cholmod);
      cholmod_l_free_dense(&cholmod_workspace_e, &cholmod);
      if (umfpack_numeric != nullptr)
        umfpack_dl_free_numeric(&umfpack_numeric);
      umfpack_numeric = nullptr;
      amesos_solver.reset();
      amesos_problem.reset();
      in_use = Parameters::DirectSolver::automatic;
    }

    void
    factorize_cholmod(const MatrixType &A);
    void
    factorize_umfpack(const MatrixType &A);
    void
    factorize_mumps(const MatrixType &A, const bool symmetric);
    void
    solve(double *values, const std::size_t n_columns) const;

    const Parameters::DirectSolver kind;
    const MPI_Comm                 communicator;
    // What the current factorisation is (umfpack when cholmod was asked for
    // an unsymmetric matrix); automatic: none.
    Parameters::DirectSolver in_use = Parameters::DirectSolver::automatic;
    std::size_t              n      = 0; // locally owned rows
    std::string              what;

    mutable cholmod_common cholmod;
    cholmod_factor        *cholmod_factor_     = nullptr;
    mutable cholmod_dense *cholmod_solution    = nullptr;
    mutable cholmod_dense *cholmod_workspace_y = nullptr;
    mutable cholmod_dense *cholmod_workspace_e = nullptr;

    CompressedRows umfpack_rows;
    void          *umfpack_numeric = nullptr;

    std::unique_ptr<Epetra_LinearProblem> amesos_problem;
    std::unique_ptr<Amesos_BaseSolver>    amesos_solver;
    std::unique_ptr<Epetra_Map>           row_map;
  };



  // CHOLMOD reads the lower triangle, stored by columns: with symmetric
  // values that is the upper triangle of the rows.
  void
  SparseDirectSolver::Implementation::factorize_cholmod(const MatrixType &A)
  {
    CompressedRows rows
      = compressed_rows(A, [](const auto i, const auto j) { return j >= i; });
    cholmod_sparse matrix;
    matrix.nrow   = n;
    matrix.ncol   = n;
    matrix.nzmax  = rows.value.size();
    matrix.p      = rows.row_start.data();
    matrix.i      = rows.column.data();
    matrix.nz     = nullptr;
    matrix.x      = rows.value.data();
    matrix.z      = nullptr;
    matrix.stype  = -1;
    matrix.itype  = CHOLMOD_LONG;
    matrix.xtype  = CHOLMOD_REAL;
    matrix.dtype  = CHOLMOD_DOUBLE;
    matrix.sorted = 1;
    matrix.packed = 1;

    cholmod_factor_ = cholmod_l_analyze(&matrix, &cholmod);
    AssertThrow(cholmod_factor_ != nullptr,
                ExcMessage("CHOLMOD's analysis of the operator failed: "
                           + cholmod_status_message(cholmod.status)));
    const int ok = cholmod_l_factorize(&matrix, cholmod_factor_, &cholmod);
    if (cholmod.status == CHOLMOD_NOT_POSDEF
        || cholmod_factor_->minor < cholmod_factor_->n)
      {
        const std::size_t step = cholmod_factor_->minor;
        clear();
        AssertThrow(false,
                    ExcMessage(
                      "CHOLMOD: the operator is not positive "
                      "definite (non-positive pivot in elimination "
                      "step "
                      + std::to_string(step) + " of " + std::to_string(n)
                      + "); is Gamma_1 (Clamped boundary ids) empty?"));
      }
    AssertThrow(ok && cholmod.status >= CHOLMOD_OK,
                ExcMessage("CHOLMOD's factorisation failed: "
                           + cholmod_status_message(cholmod.status)));
    what = "CHOLMOD supernodal Cholesky, "
           + std::to_string(static_cast<std::size_t>(cholmod.lnz))
           + " nonzeros in the factor";
  }



  // UMFPACK takes columns; the rows of A are the columns of A^T, and
  // solving with the transpose of that (UMFPACK_At) is solving with A.
  void
  SparseDirectSolver::Implementation::factorize_umfpack(const MatrixType &A)
  {
    umfpack_rows
      = compressed_rows(A, [](const auto, const auto) { return true; });
    const SuiteSparse_long size     = n;
    void                  *symbolic = nullptr;
    int                    status   = umfpack_dl_symbolic(size,
                                     size,
                                     umfpack_rows.row_start.data(),
                                     umfpack_rows.column.data(),
                                     umfpack_rows.value.data(),
                                     &symbolic,
                                     nullptr,
                                     nullptr);
    AssertThrow(status == UMFPACK_OK,
                ExcMessage("UMFPACK's analysis of the operator failed (status "
                           + std::to_string(status) + ")."));
    status = umfpack_dl_numeric(umfpack_rows.row_start.data(),
                                umfpack_rows.column.data(),
                                umfpack_rows.value.data(),
                                symbolic,
                                &umfpack_numeric,
                                nullptr,
                                nullptr);
    umfpack_dl_free_symbolic(&symbolic);
    AssertThrow(status == UMFPACK_OK,
                ExcMessage("UMFPACK's factorisation of the operator failed "
                           "(status "
                           + std::to_string(status)
                           + (status == UMFPACK_WARNING_singular_matrix
                                ? ", the operator is singular"
                                : "")
                           + ")."));
    what = "UMFPACK LU";
  }



  // Amesos copies the matrix into MUMPS' own distributed format; the
  // solver object keeps the factors.
  void
  SparseDirectSolver::Implementation::factorize_mumps(const MatrixType &A,
                                                      const bool symmetric)
  {
    const Epetra_CrsMatrix &matrix = A.trilinos_matrix();
    row_map        = std::make_unique<Epetra_Map>(matrix.RowMap());
    amesos_problem = std::make_unique<Epetra_LinearProblem>();
    amesos_problem->SetOperator(const_cast<Epetra_CrsMatrix *>(&matrix));
    Amesos factory;
    AssertThrow(factory.Query("Amesos_Mumps"),
                ExcMessage("MUMPS is not available in this Trilinos build; "
                           "choose Direct solver = cholmod or umfpack (one "
                           "MPI rank)."));
    amesos_solver.reset(factory.Create("Amesos_Mumps", *amesos_problem));
    Teuchos::ParameterList list;
    list.set("MatrixProperty", symmetric ? "SPD" : "general");
    amesos_solver->SetParameters(list);
    int error = amesos_solver->SymbolicFactorization();
    if (error == 0)
      error = amesos_solver->NumericFactorization();
    AssertThrow(error == 0,
                ExcMessage("MUMPS' factorisation of the operator failed "
                           "(Amesos error "
                           + std::to_string(error) + ")."));
    what = std::string("MUMPS ") + (symmetric ? "LDL^T" : "LU") + " on "
           + std::to_string(Utilities::MPI::n_mpi_processes(communicator))
           + " rank(s)";
  }



  void
  SparseDirectSolver::Implementation::solve(double           *values,
                                            const std::size_t n_columns) const
  {
    if (n_columns == 0)
      return;
    switch (in_use)
      {
        case Parameters::DirectSolver::cholmod:
          {
            cholmod_dense rhs;
            rhs.nrow     = n;
            rhs.ncol     = n_columns;
            rhs.nzmax    = n * n_columns;
            rhs.d        = n;
            rhs.x        = values;
            rhs.z        = nullptr;
            rhs.xtype    = CHOLMOD_REAL;
            rhs.dtype    = CHOLMOD_DOUBLE;
            const int ok = cholmod_l_solve2(CHOLMOD_A,
                                            cholmod_factor_,
                                            &rhs,
                                            nullptr,
                                            &cholmod_solution,
                                            nullptr,
                                            &cholmod_workspace_y,
                                            &cholmod_workspace_e,
                                            &cholmod);
            AssertThrow(ok && cholmod_solution != nullptr,
                        ExcMessage("CHOLMOD's solve failed: "
                                   + cholmod_status_message(cholmod.status)));
            const double *x = static_cast<const double *>(cholmod_solution->x);
            for (std::size_t j = 0; j < n_columns; ++j)
              std::copy_n(x + j * cholmod_solution->d, n, values + j * n);
            break;
          }
        case Parameters::DirectSolver::umfpack:
          {
            std::vector<double> rhs(n);
            for (std::size_t j = 0; j < n_columns; ++j)
              {
                std::copy_n(values + j * n, n, rhs.begin());
                const int status
                  = umfpack_dl_solve(UMFPACK_At,
                                     umfpack_rows.row_start.data(),
                                     umfpack_rows.column.data(),
                                     umfpack_rows.value.data(),
                                     values + j * n,
                                     rhs.data(),
                                     umfpack_numeric,
                                     nullptr,
                                     nullptr);
                AssertThrow(status == UMFPACK_OK,
                            ExcMessage("UMFPACK's solve failed (status "
                                       + std::to_string(status) + ")."));
              }
            break;
          }
        case Parameters::DirectSolver::mumps:
          {
            std::vector<double> rhs(values, values + n * n_columns);
            Epetra_MultiVector  b(View, *row_map, rhs.data(), n, n_columns);
            Epetra_MultiVector  x(View, *row_map, values, n, n_columns);
            amesos_problem->SetLHS(&x);
            amesos_problem->SetRHS(&b);
            const int error = amesos_solver->Solve();
            amesos_problem->SetLHS(nullptr);
            amesos_problem->SetRHS(nullptr);
            AssertThrow(error == 0,
                        ExcMessage("MUMPS' solve failed (Amesos error "
                                   + std::to_string(error) + ")."));
            break;
          }
        default:
          AssertThrow(false,
                      ExcMessage("SparseDirectSolver::solve() needs a "
                                 "factorisation first."));
      }
  }



  SparseDirectSolver::SparseDirectSolver(const Parameters::DirectSolver kind,
                                         const MPI_Comm communicator)
    : implementation(std::make_unique<Implementation>(kind, communicator))
  {
    Assert(kind != Parameters::DirectSolver::automatic, ExcInternalError());
  }



  SparseDirectSolver::~SparseDirectSolver() = default;



  void
  SparseDirectSolver::factorize(const MatrixType &A, const bool symmetric)
  {
    Implementation &impl = *implementation;
    impl.clear();
    impl.n = A.local_size();
    if (impl.kind == Parameters::DirectSolver::mumps)
      {
        impl.factorize_mumps(A, symmetric);
        impl.in_use = Parameters::DirectSolver::mumps;
        return;
      }
    AssertThrow(Utilities::MPI::n_mpi_processes(impl.communicator) == 1,
                ExcMessage("CHOLMOD and UMFPACK factorise on one MPI rank "
                           "only: choose Direct solver = mumps or auto."));
    if (impl.kind == Parameters::DirectSolver::cholmod && symmetric)
      {
        impl.factorize_cholmod(A);
        impl.in_use = Parameters::DirectSolver::cholmod;
      }
    else
      {
        impl.factorize_umfpack(A);
        impl.in_use = Parameters::DirectSolver::umfpack;
      }
  }



  void
  SparseDirectSolver::solve(VectorType &x, const VectorType &b) const
  {
    const unsigned int n = implementation->n;
    AssertDimension(b.locally_owned_size(), n);
    std::copy_n(b.begin(), n, x.begin());
    implementation->solve(x.begin(), 1);
  }



  void
  SparseDirectSolver::solve(std::vector<double> &columns,
                            const unsigned int   n_columns) const
  {
    AssertDimension(columns.size(), std::size_t(implementation->n) * n_columns);
    implementation->solve(columns.data(), n_columns);
  }



  std::string
  SparseDirectSolver::description() const
  {
    return implementation->what;
  }
} // namespace ViscoContact
