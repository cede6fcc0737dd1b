#ifndef viscoplastic_contact_linear_algebra_h
#define viscoplastic_contact_linear_algebra_h

#include <deal.II/lac/la_parallel_vector.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>

namespace ViscoContact
{
  using namespace dealii;

  // @sect3{Linear algebra types}
  //
  // One set of types for every run, on one MPI rank or many (as step-42
  // uses Trilinos throughout): the operators are Trilinos matrices, which
  // ML's algebraic multigrid and Amesos' direct solvers take as they are,
  // and the vectors are deal.II's own distributed vectors, whose entries
  // (owned ones first, then the ghosts) the cell loops of the time loop
  // address by local index without a hash lookup. Trilinos' matrices,
  // preconditioners and the direct solvers accept these vectors directly.
  using VectorType = LinearAlgebra::distributed::Vector<double>;
  using MatrixType = TrilinosWrappers::SparseMatrix;
} // namespace ViscoContact

#endif
