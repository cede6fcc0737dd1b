// Forward and backward solves with a supernodal Cholesky factor, with the
// independent subtrees of its elimination tree on threads (the header,
// supernodal_solve.h, says why and how).

#include <deal.II/base/parallel.h>

#include "back_ends/supernodal_solve.h"

#include <algorithm>
#include <queue>
#include <utility>

// GCC on x86-64 compiles the solve's two kernels for two instruction sets
// (see below); elsewhere, and under AddressSanitizer (whose start-up may come
// after the loader's choice of version), they are compiled once.
#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__) \
  && !defined(__SANITIZE_ADDRESS__)
#  define VC_KERNEL_CLONES \
    __attribute__((target_clones("arch=x86-64-v3", "default")))
#else
#  define VC_KERNEL_CLONES
#endif

namespace ViscoContact
{
  // @sect4{Cutting the elimination tree}
  //
  // The parent of a supernode is the supernode of its first off-diagonal
  // row; a supernode without one is a root. The cut starts from the roots
  // and moves the heaviest subtree's root into the top part until no
  // subtree holds more than a 1/32 of the factor's entries: enough pieces
  // to balance two or more threads, while in the usual trees the top part
  // stays a few separators. Then the top part is cut again (stages).
  namespace
  {
    // The number of columns and of rows of supernode s's block.
    std::size_t
    n_columns(const SupernodalSolve::Factor &factor, const std::size_t s)
    {
      return std::size_t(factor.super[s + 1] - factor.super[s]);
    }

    std::size_t
    n_rows(const SupernodalSolve::Factor &factor, const std::size_t s)
    {
      return std::size_t(factor.pi[s + 1] - factor.pi[s]);
    }

    // The parent of a root: none.
    constexpr std::size_t no_parent = std::size_t(-1);

    // The elimination tree of a factor, with what the cut measures: the
    // work of the whole factor (the entries of its blocks) and its tallest
    // block (the size of the solves' work arrays).
    struct EliminationTree
    {
      std::vector<std::size_t>              supernode_of_column;
      std::vector<std::size_t>              parent;
      std::vector<std::vector<std::size_t>> children;
      double                                total_work = 0;
      std::size_t                           max_rows   = 0;
    };

    // The parents and children of the supernodes, in one pass that also
    // adds up the work.
    EliminationTree
    elimination_tree(const SupernodalSolve::Factor &factor)
    {
      const std::size_t ns = factor.n_super;
      EliminationTree   tree;
      tree.supernode_of_column.resize(factor.n);
      for (std::size_t s = 0; s < ns; ++s)
        for (auto j = factor.super[s]; j < factor.super[s + 1]; ++j)
          tree.supernode_of_column[j] = s;
      tree.parent.assign(ns, no_parent);
      tree.children.resize(ns);
      // The parents, the children, and the work: entries of the blocks.
      for (std::size_t s = 0; s < ns; ++s)
        {
          const double work = double(n_rows(factor, s)) * n_columns(factor, s);
          tree.total_work += work;
          tree.max_rows = std::max(tree.max_rows, n_rows(factor, s));
          if (n_rows(factor, s) > n_columns(factor, s))
            {
              tree.parent[s]
                = tree.supernode_of_column[factor.rows[factor.pi[s]
                                                       + n_columns(factor, s)]];
              tree.children[tree.parent[s]].push_back(s);
            }
        }
      return tree;
    }

    // One cut of the top part: which of its supernodes stay in it, their
    // work, and the roots of the subtrees cut off, heaviest first.
    struct TopPartCut
    {
      std::vector<char>        stays_in_top;
      double                   work_staying = 0;
      std::vector<std::size_t> subtree_roots;
    };

    // The top part (marked by in_top, holding work_in_top) is closed under
    // taking parents, so its subtrees hang off its roots. The heaviest
    // subtree's root stays in the top part and its children become roots,
    // until no subtree holds more than a 1/32 of work_in_top.
    TopPartCut
    cut_top_part(const SupernodalSolve::Factor &factor,
                 const EliminationTree         &tree,
                 const std::vector<char>       &in_top,
                 const double                   work_in_top)
    {
      const std::size_t ns = factor.n_super;
      // The work of each subtree of the top part (children come before
      // their parents).
      std::vector<double> work_below(ns, 0.);
      for (std::size_t s = 0; s < ns; ++s)
        if (in_top[s])
          {
            work_below[s] += double(n_rows(factor, s)) * n_columns(factor, s);
            if (tree.parent[s] != no_parent)
              work_below[tree.parent[s]] += work_below[s];
          }
      std::priority_queue<std::pair<double, std::size_t>> heaviest;
      for (std::size_t s = 0; s < ns; ++s)
        if (in_top[s] && tree.parent[s] == no_parent)
          heaviest.emplace(work_below[s], s);
      TopPartCut cut;
      cut.stays_in_top.assign(ns, 0);
      while (!heaviest.empty() && heaviest.top().first > work_in_top / 32)
        {
          const std::size_t s = heaviest.top().second;
          heaviest.pop();
          cut.stays_in_top[s] = 1;
          cut.work_staying += double(n_rows(factor, s)) * n_columns(factor, s);
          for (const std::size_t child : tree.children[s])
            if (in_top[child])
              heaviest.emplace(work_below[child], child);
        }
      // What is left in the queue are the roots of the subtrees cut off.
      while (!heaviest.empty())
        {
          cut.subtree_roots.push_back(heaviest.top().second);
          heaviest.pop();
        }
      return cut;
    }
  } // namespace



  // @sect4{SupernodalSolve::initialize}
  //
  // The elimination tree, its cut stage by stage (cut_top_part(),
  // add_subtrees()), then the places of the updates each subtree owes rows
  // further up (set_up_update_targets()).
  void
  SupernodalSolve::initialize(const Factor &factor_in)
  {
    factor                     = factor_in;
    const std::size_t     ns   = factor.n_super;
    const EliminationTree tree = elimination_tree(factor);
    max_rows                   = tree.max_rows;

    // The cut into stages: the first cuts the whole tree, each further one
    // the top part the previous left, as long as that gives at least two
    // subtrees with a tenth of what is left (in 2D the top part is a few
    // chains of separators that branch). A supernode's subtree, -1 while it
    // is in the top part.
    std::vector<char>         in_top(ns, 1);
    std::vector<std::int64_t> subtree_of(ns, -1);
    double                    work_in_top = tree.total_work;
    subtree_supernodes.clear();
    stage_begin.assign(1, 0);
    for (unsigned int stage = 0; stage < 8; ++stage)
      {
        TopPartCut cut = cut_top_part(factor, tree, in_top, work_in_top);
        // A top part of more than half the factor after the first cut (3D
        // meshes, whose separators are large dense blocks) leaves too little
        // to share: CHOLMOD's own solve, with its BLAS kernels, is faster
        // there. The solver stays empty.
        if (stage == 0 && cut.work_staying > tree.total_work / 2)
          {
            *this = SupernodalSolve();
            return;
          }
        if (cut.subtree_roots.size() < 2
            || work_in_top - cut.work_staying < work_in_top / 10)
          break;
        add_subtrees(cut.subtree_roots,
                     tree.parent,
                     in_top,
                     cut.stays_in_top,
                     subtree_of);
        in_top.swap(cut.stays_in_top);
        work_in_top = cut.work_staying;
        stage_begin.push_back(subtree_supernodes.size());
      }
    top_supernodes.clear();
    for (std::size_t s = 0; s < ns; ++s)
      if (in_top[s])
        top_supernodes.push_back(s);

    set_up_update_targets(tree.supernode_of_column, subtree_of);
  }



  // @sect4{SupernodalSolve::add_subtrees}
  //
  // The subtrees of one cut, numbered after those of the earlier stages in
  // the order of their roots (heaviest first, so that threads start with
  // the large pieces); each supernode that leaves the top part joins its
  // parent's subtree (descending, parents first), and each subtree lists
  // its supernodes ascending.
  void
  SupernodalSolve::add_subtrees(const std::vector<std::size_t> &roots,
                                const std::vector<std::size_t> &parent,
                                const std::vector<char>        &in_top,
                                const std::vector<char>        &stays_in_top,
                                std::vector<std::int64_t>      &subtree_of)
  {
    for (const std::size_t root : roots)
      {
        subtree_of[root] = subtree_supernodes.size();
        subtree_supernodes.emplace_back();
      }
    const std::size_t ns = parent.size();
    for (std::size_t s = ns; s-- > 0;)
      if (in_top[s] && !stays_in_top[s] && subtree_of[s] < 0)
        subtree_of[s] = subtree_of[parent[s]];
    for (std::size_t s = 0; s < ns; ++s)
      if (in_top[s] && !stays_in_top[s])
        subtree_supernodes[subtree_of[s]].push_back(s);
  }



  // @sect4{SupernodalSolve::set_up_update_targets}
  //
  // Where each off-diagonal update goes: a row of the same subtree (or of
  // the top part, for the top's own supernodes), or, for a row further up
  // (a later stage or the top part), the subtree's buffer. A subtree's rows
  // further up are listed once, ascending, and entry k of its buffer
  // belongs to the k-th of them.
  void
  SupernodalSolve::set_up_update_targets(
    const std::vector<std::size_t>  &supernode_of_column,
    const std::vector<std::int64_t> &subtree_of)
  {
    const std::size_t ns         = factor.n_super;
    const std::size_t n_subtrees = subtree_supernodes.size();
    target.assign(factor.rows, factor.rows + factor.pi[ns]);
    rows_above.assign(n_subtrees, {});
    buffers_above.assign(n_subtrees, {});
    for (std::size_t t = 0; t < n_subtrees; ++t)
      {
        const auto outside = [&](const std::int64_t row) {
          return subtree_of[supernode_of_column[row]] != std::int64_t(t);
        };
        std::vector<std::int64_t> &rows = rows_above[t];
        for (const std::size_t s : subtree_supernodes[t])
          for (auto k = factor.pi[s] + std::int64_t(n_columns(factor, s));
               k < factor.pi[s + 1];
               ++k)
            if (outside(factor.rows[k]))
              rows.push_back(factor.rows[k]);
        std::sort(rows.begin(), rows.end());
        rows.erase(std::unique(rows.begin(), rows.end()), rows.end());
        for (const std::size_t s : subtree_supernodes[t])
          for (auto k = factor.pi[s] + std::int64_t(n_columns(factor, s));
               k < factor.pi[s + 1];
               ++k)
            if (outside(factor.rows[k]))
              target[k]
                = -1
                  - (std::lower_bound(rows.begin(), rows.end(), factor.rows[k])
                     - rows.begin());
        buffers_above[t].resize(rows.size());
      }
  }



  bool
  SupernodalSolve::empty() const
  {
    return factor.n_super == 0;
  }



  std::size_t
  SupernodalSolve::n_subtrees() const
  {
    return subtree_supernodes.size();
  }



  // @sect4{One supernode of the forward solve}
  //
  // The block's part of y and zeros for its off-diagonal rows go into work;
  // then the columns in groups of four: the group's triangle, and the rest
  // of the four columns times their solved values subtracted from the rows
  // below in one pass (one pass over the block, as it is stored, and work
  // read once per four columns). Then work's off-diagonal rows, -L_off x,
  // go to their rows, or to the subtree's buffer (which collects L_off x)
  // where the row lies further up (a later stage or the top part).
  namespace
  {
    constexpr std::size_t group = 4;

    // The two kernels below read most of the factor. Each is compiled
    // twice, for x86-64 and for x86-64-v3 (AVX2 and FMA), and the loader
    // picks the version the processor runs: 7% less time per solve on this
    // machine (doc/performance.md), while the program still runs on any
    // x86-64. On one machine the same version runs on every thread, so the
    // results still do not depend on the number of threads.
    //
    // work[i] -= sum_j column_j[i] work[j] for the rows i in [begin, end)
    // and the columns j in [j0, j_end) of a block with n_rows rows, four
    // columns at a time.
    VC_KERNEL_CLONES void
    subtract_columns(const double     *block,
                     const std::size_t n_rows,
                     const std::size_t j0,
                     const std::size_t j_end,
                     const std::size_t begin,
                     const std::size_t end,
                     double           *work)
    {
      if (j_end - j0 == group)
        {
          const double *c0 = block + j0 * n_rows, *c1 = c0 + n_rows,
                       *c2 = c1 + n_rows, *c3 = c2 + n_rows;
          const double x0 = work[j0], x1 = work[j0 + 1], x2 = work[j0 + 2],
                       x3 = work[j0 + 3];
          for (std::size_t i = begin; i < end; ++i)
            work[i] -= c0[i] * x0 + c1[i] * x1 + c2[i] * x2 + c3[i] * x3;
        }
      else
        for (std::size_t j = j0; j < j_end; ++j)
          {
            const double *column = block + j * n_rows;
            for (std::size_t i = begin; i < end; ++i)
              work[i] -= column[i] * work[j];
          }
    }

    // work[j] -= sum_i column_j[i] work[i] for the columns j in [j0, j_end)
    // and the rows i in [begin, end), four columns at a time (each sum in
    // the order of the rows).
    VC_KERNEL_CLONES void
    subtract_dot_products(const double     *block,
                          const std::size_t n_rows,
                          const std::size_t j0,
                          const std::size_t j_end,
                          const std::size_t begin,
                          const std::size_t end,
                          double           *work)
    {
      if (j_end - j0 == group)
        {
          const double *c0 = block + j0 * n_rows, *c1 = c0 + n_rows,
                       *c2 = c1 + n_rows, *c3 = c2 + n_rows;
          double s0 = 0, s1 = 0, s2 = 0, s3 = 0;
          for (std::size_t i = begin; i < end; ++i)
            {
              s0 += c0[i] * work[i];
              s1 += c1[i] * work[i];
              s2 += c2[i] * work[i];
              s3 += c3[i] * work[i];
            }
          work[j0] -= s0;
          work[j0 + 1] -= s1;
          work[j0 + 2] -= s2;
          work[j0 + 3] -= s3;
        }
      else
        for (std::size_t j = j0; j < j_end; ++j)
          {
            const double *column = block + j * n_rows;
            double        sum    = 0;
            for (std::size_t i = begin; i < end; ++i)
              sum += column[i] * work[i];
            work[j] -= sum;
          }
    }

    // Blocks of the top part with at least this many off-diagonal entries
    // share their off-diagonal rows (forward) or columns (backward) among
    // the threads, in pieces of a fixed size.
    constexpr std::size_t shared_block_entries = 16384;
    constexpr std::size_t rows_per_piece       = 128;
    constexpr std::size_t columns_per_piece    = 8;
  } // namespace

  void
  SupernodalSolve::forward_supernode(const std::size_t s,
                                     double           *y,
                                     double           *buffer_above,
                                     double           *work) const
  {
    const std::size_t first  = factor.super[s];
    const std::size_t n_cols = factor.super[s + 1] - first;
    const std::size_t n_rows = factor.pi[s + 1] - factor.pi[s];
    const double     *block  = factor.values + factor.px[s];
    std::copy_n(y + first, n_cols, work);
    std::fill(work + n_cols, work + n_rows, 0.);
    // A large block of the top part: its triangle first, then the
    // off-diagonal rows in pieces on threads. Each row sees the same
    // operations in the same order either way.
    const bool shared = buffer_above == nullptr
                        && (n_rows - n_cols) * n_cols >= shared_block_entries;
    const std::size_t rows_now = shared ? n_cols : n_rows;
    for (std::size_t j0 = 0; j0 < n_cols; j0 += group)
      {
        const std::size_t j_end = std::min(j0 + group, n_cols);
        for (std::size_t j = j0; j < j_end; ++j)
          {
            const double *column = block + j * n_rows;
            work[j] /= column[j];
            for (std::size_t i = j + 1; i < j_end; ++i)
              work[i] -= column[i] * work[j];
          }
        subtract_columns(block, n_rows, j0, j_end, j_end, rows_now, work);
      }
    if (shared)
      dealii::parallel::apply_to_subranges(
        std::size_t(0),
        (n_rows - n_cols + rows_per_piece - 1) / rows_per_piece,
        [&](const std::size_t begin, const std::size_t end) {
          for (std::size_t piece = begin; piece < end; ++piece)
            {
              const std::size_t i0 = n_cols + piece * rows_per_piece,
                                i1 = std::min(i0 + rows_per_piece, n_rows);
              for (std::size_t j0 = 0; j0 < n_cols; j0 += group)
                subtract_columns(block,
                                 n_rows,
                                 j0,
                                 std::min(j0 + group, n_cols),
                                 i0,
                                 i1,
                                 work);
            }
        },
        1);
    std::copy_n(work, n_cols, y + first);
    const std::int64_t *to = target.data() + factor.pi[s];
    for (std::size_t i = n_cols; i < n_rows; ++i)
      if (to[i] >= 0)
        y[to[i]] += work[i];
      else
        buffer_above[-1 - to[i]] -= work[i];
  }



  // @sect4{One supernode of the backward solve}
  //
  // The rows below the block are already solved (they are later in the
  // order) and are gathered into work with the block's own part of y. Then
  // the groups of four columns from the last one: the dot products of the
  // four columns with the solved values below the group in one pass, then
  // the group's triangle from its last column.
  void
  SupernodalSolve::backward_supernode(const std::size_t s,
                                      const bool        top,
                                      double           *x,
                                      double           *work) const
  {
    const std::size_t   first  = factor.super[s];
    const std::size_t   n_cols = factor.super[s + 1] - first;
    const std::size_t   n_rows = factor.pi[s + 1] - factor.pi[s];
    const double       *block  = factor.values + factor.px[s];
    const std::int64_t *rows   = factor.rows + factor.pi[s];
    std::copy_n(x + first, n_cols, work);
    for (std::size_t i = n_cols; i < n_rows; ++i)
      work[i] = x[rows[i]];
    // A large block of the top part: the off-diagonal rows' share of every
    // column first, pieces of columns on threads (each column's sum in the
    // same order either way), then the triangle.
    const bool shared
      = top && (n_rows - n_cols) * n_cols >= shared_block_entries;
    const std::size_t rows_now = shared ? n_cols : n_rows;
    if (shared)
      dealii::parallel::apply_to_subranges(
        std::size_t(0),
        (n_cols + columns_per_piece - 1) / columns_per_piece,
        [&](const std::size_t begin, const std::size_t end) {
          const std::size_t j_end = std::min(end * columns_per_piece, n_cols);
          for (std::size_t j0 = begin * columns_per_piece; j0 < j_end;
               j0 += group)
            subtract_dot_products(block,
                                  n_rows,
                                  j0,
                                  std::min(j0 + group, j_end),
                                  n_cols,
                                  n_rows,
                                  work);
        },
        1);
    const std::size_t n_groups = (n_cols + group - 1) / group;
    for (std::size_t g = n_groups; g-- > 0;)
      {
        const std::size_t j0 = g * group, j_end = std::min(j0 + group, n_cols);
        subtract_dot_products(block, n_rows, j0, j_end, j_end, rows_now, work);
        for (std::size_t j = j_end; j-- > j0;)
          {
            const double *column = block + j * n_rows;
            double        sum    = work[j];
            for (std::size_t i = j + 1; i < j_end; ++i)
              sum -= column[i] * work[i];
            work[j] = sum / column[j];
          }
      }
    std::copy_n(work, n_cols, x + first);
  }



  // @sect4{The two solves}
  void
  SupernodalSolve::forward(double *y) const
  {
    for (std::size_t stage = 0; stage + 1 < stage_begin.size(); ++stage)
      {
        dealii::parallel::apply_to_subranges(
          stage_begin[stage],
          stage_begin[stage + 1],
          [&](const std::size_t begin, const std::size_t end) {
            std::vector<double> work(max_rows);
            for (std::size_t t = begin; t < end; ++t)
              {
                std::vector<double> &buffer = buffers_above[t];
                std::fill(buffer.begin(), buffer.end(), 0.);
                for (const std::size_t s : subtree_supernodes[t])
                  forward_supernode(s, y, buffer.data(), work.data());
              }
          },
          1);
        // The subtrees' updates of the rows further up, in subtree order.
        for (std::size_t t = stage_begin[stage]; t < stage_begin[stage + 1];
             ++t)
          for (std::size_t k = 0; k < rows_above[t].size(); ++k)
            y[rows_above[t][k]] -= buffers_above[t][k];
      }
    // The top part, which only updates its own rows.
    std::vector<double> work(max_rows);
    for (const std::size_t s : top_supernodes)
      forward_supernode(s, y, nullptr, work.data());
  }



  void
  SupernodalSolve::backward(double *x) const
  {
    std::vector<double> work(max_rows);
    for (auto s = top_supernodes.rbegin(); s != top_supernodes.rend(); ++s)
      backward_supernode(*s, true, x, work.data());
    for (std::size_t stage = stage_begin.size() - 1; stage-- > 0;)
      dealii::parallel::apply_to_subranges(
        stage_begin[stage],
        stage_begin[stage + 1],
        [&](const std::size_t begin, const std::size_t end) {
          std::vector<double> work(max_rows);
          for (std::size_t t = begin; t < end; ++t)
            for (auto s = subtree_supernodes[t].rbegin();
                 s != subtree_supernodes[t].rend();
                 ++s)
              backward_supernode(*s, false, x, work.data());
        },
        1);
  }
} // namespace ViscoContact
