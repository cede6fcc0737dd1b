// The near-null space of elasticity and ML's settings for it, shared by the
// full space back end's AMG and the coarse level of the matrix-free back
// end's multigrid.

#include <deal.II/base/exceptions.h>

#include <deal.II/dofs/dof_tools.h>

#include <deal.II/fe/fe.h>
#include <deal.II/fe/fe_values_extractors.h>

#include "back_ends/elasticity_amg.h"
#include "back_ends/rigid_body_modes.h"
#include "rigid_motions.h"

#include <Teuchos_ParameterList.hpp>

#include <map>
#include <vector>

namespace ViscoContact
{
  // @sect4{compute_rigid_body_modes}
  //
  // Elasticity needs the near-null space of the operator without Dirichlet
  // conditions, the dim translations and the dim(dim-1)/2 infinitesimal
  // rotations, given to ML per locally owned dof (deal.II 9.4's
  // AdditionalData only takes translations, so the parameter list is
  // completed by hand in build_elasticity_amg()). Smoothed aggregation builds
  // its coarse spaces from these modes; with the translations alone they
  // could not represent the rotations of parts of the body, the low-energy
  // modes of elasticity. The modes depend on the mesh and the dofs only, not
  // on the operator, so they are computed once per mesh.
  //
  // With per_body, each body of the mesh (its connected components) has
  // modes of its own, zero on the other bodies: two bodies in contact
  // along a pair slide along each other at little cost, a low-energy mode
  // of the coupled operator that the modes of the whole mesh cannot give an
  // aggregate spanning both sides. On the 3D two-block patch test (172k
  // dofs, full space back end) CG took 96 iterations over the run against
  // 214 with the modes of the whole mesh, each 15% dearer (ML keeps the
  // zero columns of the other body's modes in its coarse spaces).
  template <int dim>
  RigidBodyModes
  compute_rigid_body_modes(const hp::MappingCollection<dim> &mapping,
                           const DoFHandler<dim>            &dof_handler,
                           const Epetra_Map                 &row_map,
                           const MPI_Comm                    communicator,
                           const bool                        per_body)
  {
    // The location of every dof, and which vector component each locally
    // owned dof belongs to.
    std::map<types::global_dof_index, Point<dim>> support_points;
    DoFTools::map_dofs_to_support_points(mapping, dof_handler, support_points);
    std::vector<IndexSet> component_dofs(dim);
    for (unsigned int c = 0; c < dim; ++c)
      component_dofs[c]
        = DoFTools::extract_dofs(dof_handler,
                                 dof_handler.get_fe_collection().component_mask(
                                   FEValuesExtractors::Scalar(c)));
    // Three modes in 2D (two translations, one rotation), six in 3D, laid
    // out like the rows of the matrix, so that ML can read them next to it.
    const unsigned int n_modes = (dim == 2 ? 3 : 6);
    // The body of every locally owned row (0 without per_body).
    unsigned int                                    n_bodies = 1;
    std::map<types::global_dof_index, unsigned int> body_of_dof;
    if (per_body)
      {
        const std::vector<unsigned int> body_of_cell
          = body_of_cells(dof_handler.get_triangulation(),
                          communicator,
                          n_bodies);
        std::vector<types::global_dof_index> dofs;
        for (const auto &cell : dof_handler.active_cell_iterators())
          if (!cell->is_artificial())
            {
              dofs.resize(cell->get_fe().n_dofs_per_cell());
              cell->get_dof_indices(dofs);
              for (const auto dof : dofs)
                body_of_dof[dof] = body_of_cell[cell->active_cell_index()];
            }
      }
    RigidBodyModes result;
    result.modes
      = std::make_unique<Epetra_MultiVector>(row_map, n_bodies * n_modes);
    // Per locally owned row: find its component c, then write component c
    // of each mode at the row's support point x.
    for (int local = 0; local < row_map.NumMyElements(); ++local)
      {
        const types::global_dof_index dof = row_map.GID64(local);
        unsigned int                  c   = 0;
        while (c < dim && !component_dofs[c].is_element(dof))
          ++c;
        Assert(c < dim, ExcInternalError());
        const Point<dim>  &x     = support_points.at(dof);
        const auto         modes = rigid_body_mode_components(c, x);
        const unsigned int first = per_body ? body_of_dof.at(dof) * n_modes : 0;
        for (unsigned int mode = 0; mode < modes.size(); ++mode)
          (*result.modes)[first + mode][local] = modes[mode];
        // Rows in blocks of dim, one block per vertex, in component order.
        if (c != static_cast<unsigned int>(local) % dim)
          result.node_blocks = false;
      }
    // Every rank must give ML the same number of PDE equations.
    result.node_blocks
      = (Utilities::MPI::min(result.node_blocks ? 1 : 0, communicator) == 1);
    return result;
  }



  // @sect4{build_elasticity_amg}
  //
  // The AMG settings: ML's defaults for elliptic (symmetric) or for
  // nonsymmetric problems, linear elements, Chebyshev smoothing of degree 2,
  // Amesos-KLU on the coarsest level, and two more settings that make the
  // iteration counts (nearly) independent of the mesh, measured by
  // benchmarks/run_preconditioner_comparison.py (doc/performance.md,
  // "Preconditioners"):
  //  - aggregation threshold 0 (it was 0.02): every matrix entry counts as a
  //    connection when ML forms its aggregates. With 0.02 CG took 18, 32, 45
  //    iterations for the cube's elastic solve on hexahedra at 15k, 108k,
  //    824k dofs (23, 34, 53 on tetrahedra); with these two settings 16, 20,
  //    21 (24, 33, 36);
  //  - "PDE equations" = dim: ML aggregates nodes, the dim dofs of a vertex
  //    together, as the rigid-body modes need (deal.II 9.4's AdditionalData
  //    leaves ML's default, 1: every dof its own node). A vertex's dofs are
  //    consecutive in deal.II's numbering of the vector-valued Q1/P1
  //    element; node_blocks, computed with the modes, checks it, and if it
  //    did not hold ML would aggregate dofs.
  // Chebyshev degree 3 or 4 and symmetric Gauss-Seidel took fewer iterations
  // but not less time, a smoother as coarse solver more iterations.
  // Without fine_level_smoothing the finest level is not smoothed (ML's
  // "do-nothing"): for a caller that smooths it itself around the cycle
  // (the full space back end's smoothing of the projected step operator).
  void
  build_elasticity_amg(const Epetra_CrsMatrix            &matrix,
                       const Epetra_MultiVector          &null_space,
                       const bool                         node_blocks,
                       const unsigned int                 dim,
                       const bool                         symmetric,
                       TrilinosWrappers::PreconditionAMG &amg,
                       const bool                         fine_level_smoothing)
  {
    TrilinosWrappers::PreconditionAMG::AdditionalData data;
    data.elliptic              = symmetric;
    data.higher_order_elements = false;
    data.smoother_sweeps       = 2;
    data.aggregation_threshold = 0.;
    // Let deal.II translate these settings into ML's parameter list (its
    // constant-mode output is not needed), then replace the null space by
    // the given modes and build the hierarchy.
    Teuchos::ParameterList              ml_parameters;
    std::unique_ptr<Epetra_MultiVector> unused_constant_modes;
    data.set_parameters(ml_parameters, unused_constant_modes, matrix);
    ml_parameters.set("PDE equations", node_blocks ? static_cast<int>(dim) : 1);
    ml_parameters.set("null space: type", "pre-computed");
    ml_parameters.set("null space: dimension", null_space.NumVectors());
    // A rank without rows (a small coarse mesh on many ranks) has no
    // values; ML takes a null pointer for no null space at all.
    static double no_rows = 0;
    ml_parameters.set("null space: vectors",
                      null_space.MyLength() > 0 ? null_space.Values()
                                                : &no_rows);
    if (!fine_level_smoothing)
      ml_parameters.set("smoother: type (level 0)", "do-nothing");
    amg.initialize(matrix, ml_parameters);
  }



  template RigidBodyModes
  compute_rigid_body_modes(const hp::MappingCollection<2> &,
                           const DoFHandler<2> &,
                           const Epetra_Map &,
                           const MPI_Comm,
                           const bool);
  template RigidBodyModes
  compute_rigid_body_modes(const hp::MappingCollection<3> &,
                           const DoFHandler<3> &,
                           const Epetra_Map &,
                           const MPI_Comm,
                           const bool);
} // namespace ViscoContact
