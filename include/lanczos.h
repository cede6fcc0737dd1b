#ifndef viscoplastic_contact_lanczos_h
#define viscoplastic_contact_lanczos_h

#include <deal.II/base/mpi.h>
#include <deal.II/base/types.h>

#include <deal.II/lac/vector.h>

#include <functional>

namespace ViscoContact
{
  using namespace dealii;

  // @sect3{The largest eigenvalue of a small distributed operator}
  //
  // The uniqueness check (doc/model.md, section 4) needs lambda_max of D^{1/2}
  // S D^{1/2} on the contact nodes: S the compliance, which a back end can
  // only apply, D the nodes' weights. This is the Lanczos iteration with full
  // reorthogonalisation (the vectors live on the contact nodes, so keeping
  // the basis is cheap), whose extreme Ritz values converge fast. Written
  // here because deal.II's eigensolvers want a matrix-sized vector type and
  // SLEPc's need PETSc objects; these vectors are a rank's own entries, with
  // n_global entries over all ranks.
  //
  // apply(x, y) sets y = A x (collective); A must be symmetric positive
  // semidefinite. Every rank sees the same scalars (only inner products are
  // reduced), so all take the same decisions and call apply() equally
  // often. At most min(n_global, max_iterations) products; the iteration
  // stops when the largest Ritz value changes by at most 1e-8 relative,
  // or when the Krylov space is invariant (then the value is exact).
  // Collective.
  double
  largest_eigenvalue(
    const std::function<void(const Vector<double> &, Vector<double> &)> &apply,
    const unsigned int            n_local,
    const types::global_dof_index n_global,
    const MPI_Comm                communicator,
    const unsigned int            max_iterations = 60);
} // namespace ViscoContact

#endif
