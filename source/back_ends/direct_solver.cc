// Sparse direct factorisations of the operator: CHOLMOD and UMFPACK on one
// rank, MUMPS (through Amesos) on any number of ranks.
//
// The condensed back end reads the contact compliance off a CHOLMOD factor
// whose elimination order ends with the contact dofs and splits each step's
// solve around the contact problem; with the other libraries it solves once
// per contact node at set-up (many right-hand sides at once) and twice per
// step problem. The full space back end may use the same factorisation as
// its preconditioner. CHOLMOD and UMFPACK are called through
// their C interfaces, MUMPS through Trilinos' Amesos, all on the Trilinos
// matrix the program assembles; the rest of the program never sees them.

#include <deal.II/base/exceptions.h>
#include <deal.II/base/utilities.h>

#include "back_ends/blas_threads.h"
#include "back_ends/direct_solver.h"
#include "back_ends/supernodal_solve.h"

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
#include <optional>
#include <utility>

namespace ViscoContact
{
  // The rows of a matrix that lives on one rank in compressed sparse row
  // form with global column indices, sorted in each row: what CHOLMOD (read
  // as the columns of the symmetric matrix) and UMFPACK (as the columns of
  // the transpose) take. Not in the anonymous namespace: the solver's
  // implementation holds one.
  struct CompressedRows
  {
    std::vector<SuiteSparse_long> row_start;
    std::vector<SuiteSparse_long> column;
    std::vector<double>           value;
  };

  namespace
  {
    // CHOLMOD's status codes in words, for the messages of failed
    // factorisations and solves.
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



    // keep(i, j): which entries to take (CHOLMOD reads one triangle only).
    // Each row is read through Epetra's local view, its column indices are
    // translated to global ones and sorted, as both libraries expect sorted
    // indices within a column. Both are only used on one rank, where global
    // and local indices coincide.
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
          // The row's entries, with column indices local to this rank's
          // column map.
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
          // row_start[i + 1] marks the end of row i: the usual compressed
          // format.
          rows.row_start.push_back(rows.column.size());
        }
      return rows;
    }
  } // namespace



  // @sect4{The implementations}
  //
  // One struct holds whichever factorisation was chosen; only one of its
  // parts is in use. It lives in this file only (the header declares it as
  // an opaque Implementation), so that no other file has to include
  // SuiteSparse or Amesos. in_use says which part holds the current
  // factorisation; it may differ from kind, because CHOLMOD hands an
  // unsymmetric operator to UMFPACK.
  struct SparseDirectSolver::Implementation
  {
    Implementation(const Parameters::DirectSolver kind,
                   const MPI_Comm                 communicator)
      : kind(kind)
      , communicator(communicator)
    {
      // CHOLMOD's settings, made once: no printing, always the supernodal
      // factorisation (dense kernels on blocks of columns with the same
      // structure), and the fill-reducing orderings to try.
      cholmod_l_start(&cholmod);
      cholmod.print      = 0;
      cholmod.supernodal = CHOLMOD_SUPERNODAL;
      // CHOLMOD's own strategy for the fill-reducing order (of the graph of
      // the nodes, see analyze()): AMD, and METIS's nested dissection only
      // when AMD leaves a factor with much fill and work.
      cholmod.nmethods  = 0;
      cholmod.postorder = 1;
    }

    // Everything clear() frees, then CHOLMOD's common block.
    ~Implementation()
    {
      clear();
      cholmod_l_finish(&cholmod);
    }

    // Frees whatever factorisation and workspace exist, before a new
    // factorisation or at the end. cholmod_l_free_dense() accepts null
    // pointers, so the work arrays are freed whether or not a solve has
    // allocated them.
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
      last_block = false;
      last_factor.reinit(0, 0);
      last_order.clear();
      threaded_solve = SupernodalSolve();
      in_use         = Parameters::DirectSolver::automatic;
    }

    // The three factorisations, and the solve with whichever is in use
    // (values: n_columns right-hand sides of n entries each, column by
    // column, overwritten by the solutions).
    void
    factorize_cholmod(const MatrixType                &A,
                      const std::vector<unsigned int> &last_rows);
    cholmod_factor *
    analyze(cholmod_sparse &matrix, const std::vector<unsigned int> &last_rows);
    void
    read_last_block(const std::vector<unsigned int> &last_rows);
    void
    solve_with_factor(const int         sys,
                      double           *values,
                      const std::size_t n_columns = 1) const;
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

    // CHOLMOD: its common block of settings and statistics, the factor, and
    // the solution and workspace that cholmod_l_solve2() reuses from one
    // solve to the next (hence mutable: solving does not change the
    // factorisation).
    mutable cholmod_common cholmod;
    cholmod_factor        *cholmod_factor_     = nullptr;
    mutable cholmod_dense *cholmod_solution    = nullptr;
    mutable cholmod_dense *cholmod_workspace_y = nullptr;
    mutable cholmod_dense *cholmod_workspace_e = nullptr;
    // The single right-hand side solves with CHOLMOD's factor, on threads
    // (supernodal_solve.h), and the permuted right-hand side of a whole
    // solve.
    SupernodalSolve             threaded_solve;
    mutable std::vector<double> permuted;

    // The last block of the CHOLMOD factor when the elimination order ends
    // with the requested rows (has_last_block()), the requested row of each
    // of its rows, and the forward half of a split solve, kept for the
    // backward half.
    bool                        last_block = false;
    LAPACKFullMatrix<double>    last_factor;
    std::vector<unsigned int>   last_order;
    mutable std::vector<double> forward;

    // UMFPACK: the matrix (its solve needs it again) and the numeric
    // factors.
    CompressedRows umfpack_rows;
    void          *umfpack_numeric = nullptr;

    // MUMPS: Amesos' linear problem, which points to the matrix and to the
    // vectors of a solve, the solver holding the factors, and the row map
    // that lays out the right-hand sides as the matrix's rows.
    std::unique_ptr<Epetra_LinearProblem> amesos_problem;
    std::unique_ptr<Amesos_BaseSolver>    amesos_solver;
    std::unique_ptr<Epetra_Map>           row_map;
  };



  // @sect4{The CHOLMOD factorisation}
  //
  // CHOLMOD reads the lower triangle, stored by columns: with symmetric
  // values that is the upper triangle of the rows. The rows are handed over
  // without copying them again: CHOLMOD's sparse matrix only points to the
  // arrays, which live until the end of this function (the factor does not
  // need them).
  void
  SparseDirectSolver::Implementation::factorize_cholmod(
    const MatrixType                &A,
    const std::vector<unsigned int> &last_rows)
  {
    CompressedRows rows
      = compressed_rows(A, [](const auto i, const auto j) { return j >= i; });
    cholmod_sparse matrix;
    matrix.nrow  = n;
    matrix.ncol  = n;
    matrix.nzmax = rows.value.size();
    matrix.p     = rows.row_start.data();
    matrix.i     = rows.column.data();
    matrix.nz    = nullptr;
    matrix.x     = rows.value.data();
    matrix.z     = nullptr;
    // stype = -1: the matrix is symmetric and only its lower triangle is
    // stored; long integer indices, real double values, sorted and packed
    // columns.
    matrix.stype  = -1;
    matrix.itype  = CHOLMOD_LONG;
    matrix.xtype  = CHOLMOD_REAL;
    matrix.dtype  = CHOLMOD_DOUBLE;
    matrix.sorted = 1;
    matrix.packed = 1;

    // The symbolic analysis (the ordering and the structure of the factor),
    // then the numeric factorisation.
    cholmod_factor_ = analyze(matrix, last_rows);
    AssertThrow(cholmod_factor_ != nullptr,
                ExcMessage("CHOLMOD's analysis of the operator failed: "
                           + cholmod_status_message(cholmod.status)));
    int ok = 0;
    {
      // The dense kernels of the supernodes on the rank's threads.
      const BlasThreadsOfRank threads;
      ok = cholmod_l_factorize(&matrix, cholmod_factor_, &cholmod);
    }
    // A pivot that is not positive stops CHOLMOD early: factor->minor is the
    // column where it stopped. For an elastic operator this means it has a
    // null space, most likely rigid motions that no clamped boundary
    // removes. The factorisation is freed before throwing, so the object is
    // left without one.
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
    // The description for the run's header: the size of the factor says how
    // much the fill cost.
    what = "CHOLMOD supernodal Cholesky, "
           + std::to_string(static_cast<std::size_t>(cholmod.lnz))
           + " nonzeros in the factor";
    // The elimination tree of the factor, cut for the threaded solves of
    // single right-hand sides (it stays empty where they would not pay).
    static_assert(sizeof(SuiteSparse_long) == sizeof(std::int64_t),
                  "CHOLMOD's long integers are 64 bits wide");
    const cholmod_factor &L = *cholmod_factor_;
    if (L.is_super && L.is_ll)
      {
        SupernodalSolve::Factor factor;
        factor.n       = L.n;
        factor.n_super = L.nsuper;
        factor.super   = static_cast<const std::int64_t *>(L.super);
        factor.pi      = static_cast<const std::int64_t *>(L.pi);
        factor.px      = static_cast<const std::int64_t *>(L.px);
        factor.rows    = static_cast<const std::int64_t *>(L.s);
        factor.values  = static_cast<const double *>(L.x);
        threaded_solve.initialize(factor);
      }
    if (last_block)
      {
        read_last_block(last_rows);
        what += ", contact dofs eliminated last";
      }
  }



  // @sect4{The elimination order}
  //
  // The order is found on the graph of the nodes rather than of the dofs:
  // the dofs of a node (the dim displacement components of a vertex) have
  // the same rows and columns in A, so they are best eliminated together,
  // and the graph of the nodes has a dim-th of the vertices and about a
  // dim^2-th of the edges. CHOLMOD's own strategy orders it: AMD, and METIS's
  // nested dissection as well where AMD leaves a factor with much work per
  // entry. Seen on the nodes, that test tries METIS in 3D, where it pays,
  // and not in 2D, where it does not (at 526k dofs METIS takes 0.9 s
  // longer than AMD and saves 0.3 s of the factorisation).
  //
  // The condensed back end also wants the contact dofs eliminated last:
  // then the last block of the factor is the Cholesky factor of the
  // operator's Schur complement on them, which is all the contact problem
  // needs. Their nodes are moved to the end of the order, in their relative
  // order; fill only grows by what the requested rows would have had anyway
  // as the last separator of the body.
  //
  // CHOLMOD analyses the matrix with the order given and post-orders the
  // elimination tree, which keeps the order as long as the requested rows
  // form its top (they do when the body is connected). The result is
  // checked; if the requested rows are not last, the analysis is repeated
  // without post-ordering, which takes the order exactly as given.
  namespace
  {
    // The nodes: maximal runs of consecutive rows with the same pattern in
    // the symmetric matrix (of which matrix holds the lower triangle,
    // column by column) and all requested or none. Returns the first row of
    // each node, and one past the last row at the end.
    std::vector<SuiteSparse_long>
    find_nodes(const cholmod_sparse &matrix, const std::vector<char> &is_last)
    {
      const auto  n     = static_cast<SuiteSparse_long>(matrix.ncol);
      const auto *start = static_cast<const SuiteSparse_long *>(matrix.p);
      const auto *row   = static_cast<const SuiteSparse_long *>(matrix.i);
      // Each row's entries up to its diagonal (the lower triangle read by
      // rows), as the columns where they are.
      std::vector<SuiteSparse_long> left_start(n + 1, 0);
      for (SuiteSparse_long k = 0; k < start[n]; ++k)
        ++left_start[row[k] + 1];
      for (SuiteSparse_long i = 0; i < n; ++i)
        left_start[i + 1] += left_start[i];
      std::vector<SuiteSparse_long> left(start[n]);
      std::vector<SuiteSparse_long> fill(left_start.begin(),
                                         left_start.end() - 1);
      for (SuiteSparse_long j = 0; j < n; ++j)
        for (SuiteSparse_long k = start[j]; k < start[j + 1]; ++k)
          left[fill[row[k]]++] = j;
      // Rows a and a + 1 have the same pattern if column a from its
      // diagonal down is a, a + 1, then column a + 1 below its diagonal,
      // and row a + 1 up to its diagonal is row a up to its diagonal, then
      // a + 1 (all in increasing order).
      const auto same_node = [&](const SuiteSparse_long a) {
        const SuiteSparse_long b = a + 1;
        return is_last[a] == is_last[b]
               && start[a + 1] - start[a] == start[b + 1] - start[b] + 1
               && row[start[a]] == a && row[start[a] + 1] == b
               && std::equal(row + start[a] + 1,
                             row + start[a + 1],
                             row + start[b])
               && left_start[b + 1] - left_start[b]
                    == left_start[a + 1] - left_start[a] + 1
               && std::equal(left.begin() + left_start[a],
                             left.begin() + left_start[a + 1],
                             left.begin() + left_start[b]);
      };
      std::vector<SuiteSparse_long> first_rows;
      for (SuiteSparse_long i = 0; i < n; ++i)
        if (i == 0 || !same_node(i - 1))
          first_rows.push_back(i);
      first_rows.push_back(n);
      return first_rows;
    }



    // The pattern of the graph of the nodes, as a symmetric CHOLMOD matrix
    // (the upper triangle with the diagonal, column by column), whose
    // arrays the two vectors hold.
    void
    node_graph(const cholmod_sparse                &matrix,
               const std::vector<SuiteSparse_long> &first_rows,
               std::vector<SuiteSparse_long>       &column_start,
               std::vector<SuiteSparse_long>       &rows,
               cholmod_sparse                      &graph)
    {
      const auto  n     = static_cast<SuiteSparse_long>(matrix.ncol);
      const auto *start = static_cast<const SuiteSparse_long *>(matrix.p);
      const auto *row   = static_cast<const SuiteSparse_long *>(matrix.i);
      const auto  nodes = static_cast<SuiteSparse_long>(first_rows.size() - 1);
      std::vector<SuiteSparse_long> node_of_row(n);
      for (SuiteSparse_long g = 0; g < nodes; ++g)
        std::fill(node_of_row.begin() + first_rows[g],
                  node_of_row.begin() + first_rows[g + 1],
                  g);
      // Each entry (i, j), i >= j, of A's lower triangle gives the entry
      // (node of j, node of i) of the graph's upper triangle (the node
      // order follows the row order);
      // the columns collect them with repetitions, then are sorted and made
      // unique.
      column_start.assign(nodes + 1, 0);
      for (SuiteSparse_long j = 0; j < n; ++j)
        for (SuiteSparse_long k = start[j]; k < start[j + 1]; ++k)
          ++column_start[node_of_row[row[k]] + 1];
      for (SuiteSparse_long g = 0; g < nodes; ++g)
        column_start[g + 1] += column_start[g];
      rows.resize(column_start[nodes]);
      std::vector<SuiteSparse_long> fill(column_start.begin(),
                                         column_start.end() - 1);
      for (SuiteSparse_long j = 0; j < n; ++j)
        for (SuiteSparse_long k = start[j]; k < start[j + 1]; ++k)
          rows[fill[node_of_row[row[k]]]++] = node_of_row[j];
      SuiteSparse_long kept = 0;
      for (SuiteSparse_long g = 0; g < nodes; ++g)
        {
          const auto first = rows.begin() + column_start[g];
          const auto last  = rows.begin() + column_start[g + 1];
          std::sort(first, last);
          const auto unique_end = std::unique(first, last);
          column_start[g]       = kept;
          kept
            = std::copy(first, unique_end, rows.begin() + kept) - rows.begin();
        }
      column_start[nodes] = kept;
      rows.resize(kept);

      graph.nrow   = nodes;
      graph.ncol   = nodes;
      graph.nzmax  = rows.size();
      graph.p      = column_start.data();
      graph.i      = rows.data();
      graph.nz     = nullptr;
      graph.x      = nullptr;
      graph.z      = nullptr;
      graph.stype  = 1;
      graph.itype  = CHOLMOD_LONG;
      graph.xtype  = CHOLMOD_PATTERN;
      graph.dtype  = CHOLMOD_DOUBLE;
      graph.sorted = 1;
      graph.packed = 1;
    }
  } // namespace



  cholmod_factor *
  SparseDirectSolver::Implementation::analyze(
    cholmod_sparse                  &matrix,
    const std::vector<unsigned int> &last_rows)
  {
    std::vector<char> is_last(n, 0);
    for (const unsigned int row : last_rows)
      is_last[row] = 1;

    // CHOLMOD's order of the nodes.
    const std::vector<SuiteSparse_long> first_rows
      = find_nodes(matrix, is_last);
    std::vector<SuiteSparse_long> graph_start, graph_rows;
    cholmod_sparse                graph;
    node_graph(matrix, first_rows, graph_start, graph_rows, graph);
    cholmod_factor *node_factor = cholmod_l_analyze(&graph, &cholmod);
    if (node_factor == nullptr)
      return nullptr;
    const auto *node_order
      = static_cast<const SuiteSparse_long *>(node_factor->Perm);

    // The order of the rows: the nodes without requested rows, then those
    // with, each in CHOLMOD's order, and each node's rows together.
    std::vector<SuiteSparse_long> order;
    order.reserve(n);
    for (const bool last : {false, true})
      for (std::size_t k = 0; k < graph.ncol; ++k)
        {
          const SuiteSparse_long node = node_order[k];
          if (bool(is_last[first_rows[node]]) == last)
            for (SuiteSparse_long i = first_rows[node];
                 i < first_rows[node + 1];
                 ++i)
              order.push_back(i);
        }
    cholmod_l_free_factor(&node_factor, &cholmod);

    // Analyse with the given order, with and then (if needed) without
    // post-ordering; the common block's settings are restored afterwards.
    const auto      saved_methods   = cholmod.nmethods;
    const auto      saved_ordering  = cholmod.method[0].ordering;
    const auto      saved_postorder = cholmod.postorder;
    cholmod_factor *factor          = nullptr;
    cholmod.nmethods                = 1;
    cholmod.method[0].ordering      = CHOLMOD_GIVEN;
    for (const int postorder : {1, 0})
      {
        cholmod.postorder = postorder;
        factor
          = cholmod_l_analyze_p(&matrix, order.data(), nullptr, 0, &cholmod);
        if (factor == nullptr || last_rows.empty())
          break;
        const auto *final_order
          = static_cast<const SuiteSparse_long *>(factor->Perm);
        bool ends_with_last_rows = true;
        for (std::size_t k = n - last_rows.size(); k < n; ++k)
          ends_with_last_rows = ends_with_last_rows && is_last[final_order[k]];
        if (ends_with_last_rows)
          {
            last_block = true;
            break;
          }
        cholmod_l_free_factor(&factor, &cholmod);
      }
    cholmod.nmethods           = saved_methods;
    cholmod.method[0].ordering = saved_ordering;
    cholmod.postorder          = saved_postorder;
    // Should neither work (it cannot, short of a CHOLMOD change), CHOLMOD
    // orders the whole matrix itself, without a last block.
    return factor != nullptr ? factor : cholmod_l_analyze(&matrix, &cholmod);
  }



  // @sect4{Reading the last block of the factor}
  //
  // A supernodal factor stores each supernode, a group of consecutive
  // columns with the same pattern below the diagonal, as a dense
  // column-major block: the columns super[s] ... super[s+1]-1, with the row
  // indices s[pi[s]] ... and the values from x[px[s]] (cholmod_core.h
  // documents the format). The entries of the last n_last rows and columns
  // are copied into last_factor, a dense lower triangular matrix;
  // last_order[k] is the position in the requested rows of the row at
  // position n - n_last + k of the elimination order.
  void
  SparseDirectSolver::Implementation::read_last_block(
    const std::vector<unsigned int> &last_rows)
  {
    const cholmod_factor &L      = *cholmod_factor_;
    const std::size_t     n_last = last_rows.size();
    const std::size_t     first  = n - n_last;
    // Which requested row each of the last positions of the order holds.
    std::vector<unsigned int> position_in_request(n);
    for (unsigned int q = 0; q < n_last; ++q)
      position_in_request[last_rows[q]] = q;
    const auto *order = static_cast<const SuiteSparse_long *>(L.Perm);
    last_order.resize(n_last);
    for (std::size_t k = 0; k < n_last; ++k)
      last_order[k] = position_in_request[order[first + k]];

    const auto *super  = static_cast<const SuiteSparse_long *>(L.super);
    const auto *pi     = static_cast<const SuiteSparse_long *>(L.pi);
    const auto *px     = static_cast<const SuiteSparse_long *>(L.px);
    const auto *rows   = static_cast<const SuiteSparse_long *>(L.s);
    const auto *values = static_cast<const double *>(L.x);
    last_factor.reinit(n_last, n_last);
    for (std::size_t s = 0; s < L.nsuper; ++s)
      {
        const std::size_t first_column = super[s], end_column = super[s + 1];
        if (end_column <= first)
          continue;
        const std::size_t n_rows = pi[s + 1] - pi[s];
        for (std::size_t j = std::max(first, first_column); j < end_column; ++j)
          for (std::size_t k = 0; k < n_rows; ++k)
            {
              const std::size_t row = rows[pi[s] + k];
              // Rows above the diagonal of a supernode's first block are
              // not part of L.
              if (row >= j)
                last_factor(row - first, j - first)
                  = values[px[s] + (j - first_column) * n_rows + k];
            }
      }
    last_factor.set_property(LAPACKSupport::lower_triangular);
  }



  // @sect4{The UMFPACK factorisation}
  //
  // UMFPACK takes columns; the rows of A are the columns of A^T, and solving
  // with the transpose of that (UMFPACK_At) is solving with A. This avoids
  // transposing the unsymmetric tangent. All entries are kept; the arrays
  // stay in umfpack_rows because every solve passes them again.
  void
  SparseDirectSolver::Implementation::factorize_umfpack(const MatrixType &A)
  {
    umfpack_rows
      = compressed_rows(A, [](const auto, const auto) { return true; });
    // The symbolic analysis (column ordering and structure) ...
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
    // ... and the numeric LU factorisation. The symbolic object is not
    // needed after it; a singular operator is reported by name.
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



  // @sect4{The MUMPS factorisation}
  //
  // Amesos copies the matrix into MUMPS' own distributed format; the solver
  // object keeps the factors. The matrix is used as it is distributed, rows
  // owned by each rank, so this is the factorisation for several ranks.
  void
  SparseDirectSolver::Implementation::factorize_mumps(const MatrixType &A,
                                                      const bool symmetric)
  {
    const Epetra_CrsMatrix &matrix = A.trilinos_matrix();
    // The row map lays out the right-hand sides of later solves like the
    // matrix's rows.
    row_map        = std::make_unique<Epetra_Map>(matrix.RowMap());
    amesos_problem = std::make_unique<Epetra_LinearProblem>();
    amesos_problem->SetOperator(const_cast<Epetra_CrsMatrix *>(&matrix));
    // MUMPS is optional in a Trilinos build; say so clearly instead of
    // failing in Amesos.
    Amesos factory;
    AssertThrow(factory.Query("Amesos_Mumps"),
                ExcMessage("MUMPS is not available in this Trilinos build; "
                           "choose Direct solver = cholmod or umfpack (one "
                           "MPI rank)."));
    amesos_solver.reset(factory.Create("Amesos_Mumps", *amesos_problem));
    // With symmetric values MUMPS is told the matrix is symmetric positive
    // definite, so that it factorises only one triangle (LDL^T); the tangent
    // gets a general LU factorisation.
    Teuchos::ParameterList list;
    list.set("MatrixProperty", symmetric ? "SPD" : "general");
    amesos_solver->SetParameters(list);
    // The analysis and the numeric factorisation; an error of either stops
    // the run with Amesos' code.
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



  // @sect4{SparseDirectSolver::Implementation::solve}
  //
  // Solves A x = b for n_columns right-hand sides, stored column by column
  // in values (n locally owned entries each) and overwritten by the
  // solutions. Each library gets the block in its own form; an empty block
  // returns at once on every rank.
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
            // CHOLMOD solves all columns in one call with its dense kernels.
            solve_with_factor(CHOLMOD_A, values, n_columns);
            break;
          }
        case Parameters::DirectSolver::umfpack:
          {
            // UMFPACK solves one right-hand side at a time: each column is
            // copied out as b, and the solution is written into the caller's
            // array in its place. Its default iterative refinement (up to
            // two residual corrections per solve) is switched off: the LU
            // factorisation with pivoting is backward stable for these
            // operators, and the refinement made each solve several times
            // as expensive (the condensed back end solves once per contact
            // node and tangent).
            std::vector<double> rhs(n);
            double              control[UMFPACK_CONTROL];
            umfpack_dl_defaults(control);
            control[UMFPACK_IRSTEP] = 0;
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
                                     control,
                                     nullptr);
                AssertThrow(status == UMFPACK_OK,
                            ExcMessage("UMFPACK's solve failed (status "
                                       + std::to_string(status) + ")."));
              }
            break;
          }
        case Parameters::DirectSolver::mumps:
          {
            // MUMPS: Amesos' multivectors are views of the arrays; only the
            // right-hand side is copied, since the solution overwrites the
            // caller's array. The problem only points to them during the
            // solve, so the pointers are reset afterwards. This is
            // collective: every rank passes its rows.
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
        // A solve before any factorisation is an error of the program, not
        // of the input.
        default:
          AssertThrow(false,
                      ExcMessage("SparseDirectSolver::solve() needs a "
                                 "factorisation first."));
      }
  }



  // @sect4{Solves with the CHOLMOD factor}
  //
  // values (n_columns right-hand sides of n entries, column by column) is
  // overwritten by A^{-1} values (sys = CHOLMOD_A), L^{-1} values
  // (CHOLMOD_L) or L^{-T} values (CHOLMOD_Lt): a whole solve, or the two
  // halves of one without the permutations, which the caller then applies
  // (values is in the elimination order). One right-hand side goes to the
  // threaded solves where the factor was cut for them (supernodal_solve.h).
  // Otherwise a dense-matrix header is put around the caller's array, and
  // cholmod_l_solve2() writes into the solution it keeps between calls,
  // which is copied back column by column.
  void
  SparseDirectSolver::Implementation::solve_with_factor(
    const int         sys,
    double           *values,
    const std::size_t n_columns) const
  {
    // One right-hand side: the threaded solves, and the permutations for a
    // whole solve, ((P b)_k = b_{Perm[k]}).
    if (n_columns == 1 && !threaded_solve.empty())
      {
        if (sys == CHOLMOD_L)
          threaded_solve.forward(values);
        else if (sys == CHOLMOD_Lt)
          threaded_solve.backward(values);
        else
          {
            Assert(sys == CHOLMOD_A, ExcNotImplemented());
            const auto *order
              = static_cast<const SuiteSparse_long *>(cholmod_factor_->Perm);
            permuted.resize(n);
            for (std::size_t k = 0; k < n; ++k)
              permuted[k] = values[order[k]];
            threaded_solve.forward(permuted.data());
            threaded_solve.backward(permuted.data());
            for (std::size_t k = 0; k < n; ++k)
              values[order[k]] = permuted[k];
          }
        return;
      }
    cholmod_dense rhs;
    rhs.nrow  = n;
    rhs.ncol  = n_columns;
    rhs.nzmax = n * n_columns;
    rhs.d     = n;
    rhs.x     = values;
    rhs.z     = nullptr;
    rhs.xtype = CHOLMOD_REAL;
    rhs.dtype = CHOLMOD_DOUBLE;
    // Many right-hand sides are solved with dense kernels, on the rank's
    // threads.
    std::optional<BlasThreadsOfRank> threads;
    if (n_columns > 1)
      threads.emplace();
    const int ok = cholmod_l_solve2(sys,
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
  }



  // @sect4{SparseDirectSolver}
  //
  // The public class only forwards to the implementation. Direct solver =
  // auto is resolved here: CHOLMOD on one rank, MUMPS (the only one of the
  // three that works on distributed matrices) on several.
  SparseDirectSolver::SparseDirectSolver(const Parameters::DirectSolver kind,
                                         const MPI_Comm communicator)
    : implementation(std::make_unique<Implementation>(
      kind != Parameters::DirectSolver::automatic
        ? kind
        : (Utilities::MPI::n_mpi_processes(communicator) == 1
             ? Parameters::DirectSolver::cholmod
             : Parameters::DirectSolver::mumps),
      communicator))
  {}



  // Defined here, where Implementation is a complete type, so that the
  // unique_ptr can delete it.
  SparseDirectSolver::~SparseDirectSolver() = default;



  // @sect4{SparseDirectSolver::factorize}
  //
  // Replaces any earlier factorisation by one of A. MUMPS works on any
  // number of ranks; CHOLMOD and UMFPACK only on one (the parameter check at
  // start-up already rejects them on several ranks, this is the safety net).
  // CHOLMOD only factorises symmetric operators; for an unsymmetric tangent
  // the same request silently becomes UMFPACK's LU, which description() then
  // reports.
  void
  SparseDirectSolver::factorize(const MatrixType                &A,
                                const bool                       symmetric,
                                const std::vector<unsigned int> &last_rows)
  {
    Implementation &impl = *implementation;
    impl.clear();
    // The number of locally owned rows, the length of every solve's
    // right-hand side on this rank.
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
        impl.factorize_cholmod(A, last_rows);
        impl.in_use = Parameters::DirectSolver::cholmod;
      }
    else
      {
        impl.factorize_umfpack(A);
        impl.in_use = Parameters::DirectSolver::umfpack;
      }
  }



  // @sect4{SparseDirectSolver::solve}
  //
  // One right-hand side: the solution overwrites a copy of b in the owned
  // entries of x (its ghost entries are left alone).
  void
  SparseDirectSolver::solve(VectorType &x, const VectorType &b) const
  {
    const unsigned int n = implementation->n;
    AssertDimension(b.locally_owned_size(), n);
    std::copy_n(b.begin(), n, x.begin());
    implementation->solve(x.begin(), 1);
  }



  // A block of right-hand sides, as the condensed back end uses at set-up.
  void
  SparseDirectSolver::solve(std::vector<double> &columns,
                            const unsigned int   n_columns) const
  {
    AssertDimension(columns.size(), std::size_t(implementation->n) * n_columns);
    implementation->solve(columns.data(), n_columns);
  }



  // @sect4{The last block and the split solve}
  //
  // Only a CHOLMOD factorisation asked for last rows has a last block; the
  // other libraries ignore the request (the condensed back end then
  // computes the compliance column by column).
  bool
  SparseDirectSolver::has_last_block() const
  {
    return implementation->last_block;
  }



  const LAPACKFullMatrix<double> &
  SparseDirectSolver::last_block_factor() const
  {
    Assert(has_last_block(), ExcInternalError());
    return implementation->last_factor;
  }



  const std::vector<unsigned int> &
  SparseDirectSolver::last_block_order() const
  {
    Assert(has_last_block(), ExcInternalError());
    return implementation->last_order;
  }



  // The forward half: y = L^{-1} P b, where (P b)_k = b_{Perm[k]}. y is kept
  // for backward_solve(); its last block is returned.
  void
  SparseDirectSolver::forward_solve(const VectorType &b,
                                    Vector<double>   &last_block) const
  {
    const Implementation &impl = *implementation;
    Assert(impl.last_block, ExcInternalError());
    const auto *order
      = static_cast<const SuiteSparse_long *>(impl.cholmod_factor_->Perm);
    impl.forward.resize(impl.n);
    for (std::size_t k = 0; k < impl.n; ++k)
      impl.forward[k] = b.local_element(order[k]);
    impl.solve_with_factor(CHOLMOD_L, impl.forward.data());
    const std::size_t n_last = impl.last_order.size();
    last_block.reinit(n_last);
    std::copy_n(impl.forward.end() - n_last, n_last, last_block.begin());
  }



  // The backward half: y_c += change, then x = P^T L^{-T} y, i.e.
  // x_{Perm[k]} = (L^{-T} y)_k, into the owned entries of x.
  void
  SparseDirectSolver::backward_solve(const Vector<double> &change,
                                     VectorType           &x) const
  {
    const Implementation &impl   = *implementation;
    const std::size_t     n_last = impl.last_order.size();
    AssertDimension(change.size(), n_last);
    AssertDimension(impl.forward.size(), impl.n);
    for (std::size_t k = 0; k < n_last; ++k)
      impl.forward[impl.n - n_last + k] += change[k];
    impl.solve_with_factor(CHOLMOD_Lt, impl.forward.data());
    const auto *order
      = static_cast<const SuiteSparse_long *>(impl.cholmod_factor_->Perm);
    for (std::size_t k = 0; k < impl.n; ++k)
      x.local_element(order[k]) = impl.forward[k];
  }



  std::size_t
  SparseDirectSolver::n_threaded_subtrees() const
  {
    return implementation->threaded_solve.n_subtrees();
  }



  // What was factorised, and how (set by the last factorize()).
  std::string
  SparseDirectSolver::description() const
  {
    return implementation->what;
  }
} // namespace ViscoContact
