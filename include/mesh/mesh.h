#ifndef viscoplastic_contact_mesh_h
#define viscoplastic_contact_mesh_h

#include <deal.II/base/mpi.h>

#include <deal.II/distributed/tria_base.h>

#include <deal.II/grid/tria.h>
#include <deal.II/grid/tria_description.h>

#include "parameters.h"

#include <memory>

namespace ViscoContact
{
  using namespace dealii;

  // @sect3{Meshes}
  //
  // Every mesh of the program is a distributed mesh, also on one MPI rank
  // (as in step-40): quadrilaterals and hexahedra live on p4est
  // (parallel::distributed::Triangulation), triangles and tetrahedra, which
  // p4est cannot hold, on a parallel::fullydistributed::Triangulation
  // partitioned by METIS, which one rank per group of Mesh group size ranks
  // (mesh_group_size()) builds whole and hands out in parts.
  // create_distributed_mesh() builds it in stages:
  //  - create_coarse_mesh(): the generated box (simplices cut by the
  //    Simplex pattern) or a Gmsh file, with the boundary ids of subsection
  //    Boundary, on a serial Triangulation;
  //  - refine_mesh(): the uniform refinements and the refinement toward
  //    Gamma_3 (only locally owned cells are flagged);
  //  - check_boundary_ids(), check_material_ids(): the boundary parts and
  //    the material ids the parameter file names exist, across all MPI
  //    ranks, and every material id of the mesh has its material.
  // multigrid_hierarchy: a p4est mesh with the level hierarchy (and the
  // level difference limited at vertices) that geometric multigrid needs;
  // the program's runs do not use it.
  template <int dim>
  std::unique_ptr<parallel::DistributedTriangulationBase<dim>>
  create_distributed_mesh(const Parameters::AllParameters &parameters,
                          const MPI_Comm                   communicator,
                          const bool multigrid_hierarchy = false);

  // The number of consecutive ranks that share one whole simplex mesh during
  // set-up: one of them builds it and hands out the parts (mesh.cc).
  // Collective.
  unsigned int
  mesh_group_size(const Parameters::AllParameters &parameters,
                  const MPI_Comm                   communicator);

  template <int dim>
  void
  create_coarse_mesh(const Parameters::AllParameters &parameters,
                     Triangulation<dim>              &triangulation);

  // The box (0,L1)x(0,L2)(x(0,L3)) with n squares (cubes) along each edge,
  // cut into simplices by the given pattern (parameters.h), with the
  // boundary ids deal.II's colorize gives hypercubes: 2d and 2d+1 at
  // x_d = 0 and x_d = L_d.
  template <int dim>
  void
  create_simplex_box(Triangulation<dim>              &triangulation,
                     const std::vector<double>       &lengths,
                     const unsigned int               n,
                     const Parameters::SimplexPattern pattern);
  template <>
  void
  create_simplex_box(Triangulation<2> &,
                     const std::vector<double> &,
                     const unsigned int,
                     const Parameters::SimplexPattern);
  template <>
  void
  create_simplex_box(Triangulation<3> &,
                     const std::vector<double> &,
                     const unsigned int,
                     const Parameters::SimplexPattern);

  template <int dim>
  void
  refine_mesh(const Parameters::AllParameters &parameters,
              Triangulation<dim>              &triangulation);

  template <int dim>
  void
  check_boundary_ids(const Parameters::AllParameters &parameters,
                     const Triangulation<dim>        &triangulation,
                     const MPI_Comm                   communicator);

  template <int dim>
  void
  check_material_ids(const Parameters::AllParameters &parameters,
                     const Triangulation<dim>        &triangulation,
                     const MPI_Comm                   communicator);
} // namespace ViscoContact

#endif
