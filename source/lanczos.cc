// largest_eigenvalue(): the Lanczos iteration of the uniqueness check
// (lanczos.h).

#include <deal.II/base/mpi.h>

#include <deal.II/lac/tridiagonal_matrix.h>

#include "lanczos.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace ViscoContact
{
  double
  largest_eigenvalue(
    const std::function<void(const Vector<double> &, Vector<double> &)> &apply,
    const unsigned int            n_local,
    const types::global_dof_index n_global,
    const MPI_Comm                communicator,
    const unsigned int            max_iterations)
  {
    // The inner product of two vectors over all ranks: only the scalar is
    // reduced.
    const auto dot = [&](const Vector<double> &a, const Vector<double> &b) {
      double sum = 0;
      for (unsigned int i = 0; i < n_local; ++i)
        sum += a[i] * b[i];
      return Utilities::MPI::sum(sum, communicator);
    };

    // The Lanczos basis (kept for the reorthogonalisation) and the recurrence
    // coefficients alpha_k (diagonal) and beta_k (off-diagonal) of the
    // tridiagonal matrix T. The start vector is the constant vector of unit
    // length over all ranks, which every rank sets up without communication.
    std::vector<Vector<double>> basis;
    std::vector<double>         alpha, beta;
    Vector<double>              v(n_local), w(n_local);
    for (unsigned int i = 0; i < n_local; ++i)
      v[i] = 1. / std::sqrt(double(n_global));
    double largest = 0;
    // At most n_global iterations (then the Krylov space is the whole space);
    // 4 on the 2D static scene at 526k dofs (doc/model.md, section 4).
    const unsigned int n_iterations
      = std::min<types::global_dof_index>(n_global, max_iterations);
    for (unsigned int k = 0; k < n_iterations; ++k)
      {
        basis.push_back(v);
        apply(v, w);
        alpha.push_back(dot(w, v));
        // w = A v and alpha_k = (A v, v). Then w is orthogonalised against
        // every earlier basis vector, not only the last two: in floating point
        // the three-term recurrence loses orthogonality and produces spurious
        // copies of converged Ritz values. This subtraction includes the
        // usual alpha_k v_k and beta_{k-1} v_{k-1}.
        for (const Vector<double> &b : basis)
          {
            const double projection = dot(w, b);
            for (unsigned int i = 0; i < n_local; ++i)
              w[i] -= projection * b[i];
          }
        // The norm of what remains is beta_k, the next off-diagonal entry.
        const double norm = std::sqrt(dot(w, w));

        // The Ritz values are the eigenvalues of T (LAPACK's symmetric
        // tridiagonal solver, in ascending order); the largest approximates
        // lambda_max from below.
        TridiagonalMatrix<double> T(alpha.size(), true);
        for (unsigned int i = 0; i < alpha.size(); ++i)
          {
            T(i, i) = alpha[i];
            if (i + 1 < alpha.size())
              T(i, i + 1) = T(i + 1, i) = beta[i];
          }
        T.compute_eigenvalues();
        const double ritz = T.eigenvalue(alpha.size() - 1);
        // Stop when the largest Ritz value changes by at most a relative
        // 1e-8, or when the Krylov space is invariant (w vanishes): then the
        // Ritz value is exact. The Ritz values converge faster than
        // geometrically, so the last change bounds the error; the margin is
        // printed with 6 digits. Each product is an elastic solve on the
        // full space back end: on the 2D static scene at 526k dofs the
        // iteration stopped after 4 products instead of 7 (1e-12), 3e-9
        // below the converged value.
        const bool converged
          = k > 0 && std::abs(ritz - largest) <= 1e-8 * std::abs(ritz);
        largest = ritz;
        if (converged || norm <= 1e-14 * std::abs(ritz))
          break;
        // Otherwise the normalised remainder is the next basis vector.
        beta.push_back(norm);
        for (unsigned int i = 0; i < n_local; ++i)
          v[i] = w[i] / norm;
      }
    return largest;
  }
} // namespace ViscoContact
