#ifndef viscoplastic_contact_elasticity_amg_h
#define viscoplastic_contact_elasticity_amg_h

#include <deal.II/base/mpi.h>

#include <deal.II/dofs/dof_handler.h>

#include <deal.II/hp/mapping_collection.h>

#include <deal.II/lac/trilinos_precondition.h>

#include <Epetra_CrsMatrix.h>
#include <Epetra_Map.h>
#include <Epetra_MultiVector.h>

#include <memory>

namespace ViscoContact
{
  using namespace dealii;

  // @sect3{Smoothed aggregation for elasticity}
  //
  // What the full space back end's AMG and the coarse level of the matrix-free
  // back end's multigrid share: the near-null space of elasticity and ML's
  // settings for it.

  // The rigid-body modes at the rows of row_map (locally owned dofs of
  // dof_handler), and whether every rank's rows come in blocks of dim, one
  // block per vertex in component order (what ML's "PDE equations" = dim
  // assumes). Collective.
  struct RigidBodyModes
  {
    std::unique_ptr<Epetra_MultiVector> modes;
    bool                                node_blocks = true;
  };

  template <int dim>
  RigidBodyModes
  compute_rigid_body_modes(const hp::MappingCollection<dim> &mapping,
                           const DoFHandler<dim>            &dof_handler,
                           const Epetra_Map                 &row_map,
                           const MPI_Comm                    communicator,
                           const bool                        per_body = false);

  // ML's smoothed aggregation on matrix with the given near-null space:
  // elliptic settings when symmetric, nonsymmetric ones otherwise.
  void
  build_elasticity_amg(const Epetra_CrsMatrix            &matrix,
                       const Epetra_MultiVector          &null_space,
                       const bool                         node_blocks,
                       const unsigned int                 dim,
                       const bool                         symmetric,
                       TrilinosWrappers::PreconditionAMG &amg,
                       const bool fine_level_smoothing = true);
} // namespace ViscoContact

#endif
