#ifndef viscoplastic_contact_supernodal_solve_h
#define viscoplastic_contact_supernodal_solve_h

#include <cstddef>
#include <cstdint>
#include <vector>

namespace ViscoContact
{
  // @sect3{Triangular solves with a supernodal factor, on threads}
  //
  // A time step of the condensed back end is one forward and one backward
  // solve with the Cholesky factor L of the operator; CHOLMOD does both on
  // one thread, and they are bound by the speed at which one core reads the
  // factor. The elimination tree says which columns are independent: two
  // subtrees that hang off the tree's top share nothing but the rows of the
  // top. So the tree is cut once, after the factorisation, into subtrees
  // of at most a 1/32 of the factor each and a top part, and the top part
  // again in the same way while that gives subtrees (stages), and:
  //  - forward (L y = b): stage by stage, the subtrees on threads, each
  //    adding what it owes rows further up into a buffer of its own, then
  //    the buffers in subtree order; last the top part;
  //  - backward (L^T x = y): the top part, then the stages in reverse, the
  //    subtrees on threads (each only reads values further up and writes
  //    its own);
  //  - in the top part, blocks with many off-diagonal entries share their
  //    rows (forward) or columns (backward) among the threads in pieces of
  //    a fixed size.
  // The cut depends on the factor only, and every sum is taken in the same
  // order whatever the number of threads, so results do not depend on it.
  //
  // The factor is given in CHOLMOD's supernodal format (cholmod_core.h):
  // supernode s holds the columns super[s] ... super[s+1]-1 as a dense
  // column-major block of pi[s+1]-pi[s] rows, whose row indices are
  // rows[pi[s]] ..., and whose values start at values[px[s]]; the first
  // rows of the block are its own columns (the diagonal block). The arrays
  // must outlive the solver.
  class SupernodalSolve
  {
  public:
    struct Factor
    {
      std::size_t         n       = 0; // columns
      std::size_t         n_super = 0; // supernodes
      const std::int64_t *super   = nullptr;
      const std::int64_t *pi      = nullptr;
      const std::int64_t *px      = nullptr;
      const std::int64_t *rows    = nullptr;
      const double       *values  = nullptr;
    };

    // Cuts the elimination tree of the factor (linear in its size). If the
    // top part would hold more than half of the factor's entries (as for 3D
    // meshes, whose separators are large dense blocks), too little is left
    // to share, and the solver stays empty: CHOLMOD's own solve is faster
    // there.
    void
    initialize(const Factor &factor);

    bool
    empty() const;

    // y := L^{-1} y and y := L^{-T} y, with y in the factor's order.
    void
    forward(double *y) const;
    void
    backward(double *y) const;

    // The number of subtrees of the cut.
    std::size_t
    n_subtrees() const;

  private:
    // The subtrees of one cut of the top part in_top, with the given roots
    // (heaviest first): their numbers in subtree_of and their supernodes in
    // subtree_supernodes.
    void
    add_subtrees(const std::vector<std::size_t> &roots,
                 const std::vector<std::size_t> &parent,
                 const std::vector<char>        &in_top,
                 const std::vector<char>        &stays_in_top,
                 std::vector<std::int64_t>      &subtree_of);
    // target, rows_above and buffers_above for the subtrees of the cut.
    void
    set_up_update_targets(const std::vector<std::size_t>  &supernode_of_column,
                          const std::vector<std::int64_t> &subtree_of);
    // One supernode of the forward and of the backward solve.
    void
    forward_supernode(const std::size_t s,
                      double           *y,
                      double           *buffer_above,
                      double           *work) const;
    void
    backward_supernode(const std::size_t s,
                       const bool        top,
                       double           *x,
                       double           *work) const;

    Factor factor;
    // The supernodes of each subtree and of the top part, ascending (a
    // parent comes after its children).
    std::vector<std::vector<std::size_t>> subtree_supernodes;
    // The subtrees of stage k are stage_begin[k] ... stage_begin[k+1]-1.
    std::vector<std::size_t> stage_begin;
    std::vector<std::size_t> top_supernodes;
    // Where the forward solve puts each off-diagonal entry's update: its row
    // (>= 0), or -1 - k for entry k of the subtree's buffer above. Indexed
    // like rows.
    std::vector<std::int64_t> target;
    // The rows further up (later stages, the top part) that each subtree
    // updates, and the buffers for them.
    std::vector<std::vector<std::int64_t>>   rows_above;
    mutable std::vector<std::vector<double>> buffers_above;
    std::size_t                              max_rows = 0;
  };
} // namespace ViscoContact

#endif
