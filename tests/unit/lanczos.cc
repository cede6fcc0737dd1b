// Unit tests of largest_eigenvalue() (the Lanczos iteration of the
// uniqueness check) on operators whose largest eigenvalue is known, with
// the vector's entries spread over the ranks as the contact nodes are:
// diag(1, ..., m) (lambda_max = m, reached in at most m products: the
// Krylov space becomes invariant) and I + c c^T (lambda_max = 1 + |c|^2,
// exact after two products), both to 1e-12 relative.

#include <deal.II/base/mpi.h>

#include <gtest/gtest.h>

#include "lanczos.h"

#include <cmath>

using namespace dealii;
using namespace ViscoContact;

namespace
{
  // This rank's share of m entries and the global index of its first.
  std::pair<unsigned int, unsigned int>
  share(const unsigned int m)
  {
    const unsigned int rank  = Utilities::MPI::this_mpi_process(MPI_COMM_WORLD);
    const unsigned int n     = Utilities::MPI::n_mpi_processes(MPI_COMM_WORLD);
    const unsigned int first = m * rank / n, end = m * (rank + 1) / n;
    return {end - first, first};
  }
} // namespace

TEST(Lanczos, DiagonalOperator)
{
  for (const unsigned int m : {1u, 7u, 40u})
    {
      const auto [n_local, first] = share(m);
      unsigned int products       = 0;
      const auto   apply
        = [&, first = first](const Vector<double> &x, Vector<double> &y) {
            ++products;
            for (unsigned int i = 0; i < x.size(); ++i)
              y[i] = (first + i + 1.) * x[i];
          };
      const double lambda
        = largest_eigenvalue(apply, n_local, m, MPI_COMM_WORLD);
      // The iteration stops once the estimate changes by at most 1e-8
      // relative, which bounds its error: observed 2.03e-9 at m = 40 (whose
      // two largest eigenvalues are close), exact for m = 1 and 7. The
      // bound is 1.5 times the observed error.
      EXPECT_NEAR(lambda, m, 3e-9 * m) << "m = " << m;
      EXPECT_LE(products, m);
    }
}

TEST(Lanczos, RankOneUpdate)
{
  const unsigned int m        = 25;
  const auto [n_local, first] = share(m);
  double c_norm2              = 0;
  for (unsigned int g = 0; g < m; ++g)
    c_norm2 += std::pow(std::sin(1. + g), 2);
  unsigned int products = 0;
  const auto   apply
    = [&, first = first](const Vector<double> &x, Vector<double> &y) {
        ++products;
        double c_dot_x = 0;
        for (unsigned int i = 0; i < x.size(); ++i)
          c_dot_x += std::sin(1. + first + i) * x[i];
        c_dot_x = Utilities::MPI::sum(c_dot_x, MPI_COMM_WORLD);
        for (unsigned int i = 0; i < x.size(); ++i)
          y[i] = x[i] + std::sin(1. + first + i) * c_dot_x;
      };
  const double lambda = largest_eigenvalue(apply, n_local, m, MPI_COMM_WORLD);
  EXPECT_NEAR(lambda, 1. + c_norm2, 1e-12 * (1. + c_norm2));
  EXPECT_LE(products, 3u);
}
