#ifndef viscoplastic_contact_mesh_h
#define viscoplastic_contact_mesh_h

#include <deal.II/base/mpi.h>

#include <deal.II/grid/tria.h>

#include "parameters.h"

namespace ViscoContact
{
  using namespace dealii;

  // @sect3{Meshes}
  //
  // Every mesh of the program is made in two stages, so that the serial and
  // the distributed solvers see the same cells:
  //  - create_coarse_mesh(): the generated box or a Gmsh file, with the
  //    boundary ids of subsection Boundary, on a serial Triangulation (p4est
  //    meshes copy it, fully distributed meshes are partitioned from it);
  //  - refine_mesh(): the uniform refinements and the refinement toward
  //    Gamma_3, on any triangulation (only locally owned cells are flagged).
  // check_boundary_ids() then makes sure that the boundary parts the
  // parameter file names exist, across all MPI ranks.
  template <int dim>
  void
  create_coarse_mesh(const Parameters::AllParameters &parameters,
                     Triangulation<dim>              &triangulation);

  template <int dim>
  void
  refine_mesh(const Parameters::AllParameters &parameters,
              Triangulation<dim>              &triangulation);

  template <int dim>
  void
  check_boundary_ids(const Parameters::AllParameters &parameters,
                     const Triangulation<dim>        &triangulation,
                     const MPI_Comm                   communicator);
} // namespace ViscoContact

#endif
