// The constraints of the displacement: hanging nodes, the Dirichlet parts
// (clamped, or a prescribed displacement of some components) and the
// planes of symmetry. The program's set-up and the preconditioner benchmark
// use the same function, so that the benchmark solves the program's K.

#ifndef viscoplastic_contact_constraints_h
#define viscoplastic_contact_constraints_h

#include <deal.II/base/index_set.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/tensor.h>
#include <deal.II/base/types.h>

#include <deal.II/dofs/dof_handler.h>

#include <deal.II/fe/component_mask.h>
#include <deal.II/hp/mapping_collection.h>

#include <deal.II/lac/affine_constraints.h>

#include <vector>

namespace ViscoContact
{
  using namespace dealii;

  // Boundary parts whose displacement is prescribed in the components of
  // the mask (all of them if the mask is empty).
  struct DirichletPart
  {
    std::vector<types::boundary_id> boundary_ids;
    ComponentMask                   components;
  };

  // Fills constraints (reinitialised on locally_relevant_dofs) with the
  // hanging nodes, then u_c = 0 on each Dirichlet part in the order given
  // (a dof keeps the first constraint it gets), then u.n = 0 on the
  // symmetry parts, and closes it. The constraints are homogeneous: the
  // values of prescribed displacements enter each step as a lifting
  // (ViscoplasticContact::set_dirichlet_values()), so that K and its
  // factorisation serve the whole run. If open_constraints is given, it
  // gets a copy before closing, into which the values of a time can be
  // set (AffineConstraints::set_inhomogeneity()) before it is closed.
  template <int dim>
  void
  make_displacement_constraints(
    const hp::MappingCollection<dim>      &mapping,
    const DoFHandler<dim>                 &dof_handler,
    const std::vector<DirichletPart>      &dirichlet_parts,
    const std::vector<types::boundary_id> &symmetry_ids,
    const IndexSet                        &locally_relevant_dofs,
    AffineConstraints<double>             &constraints,
    AffineConstraints<double>             *open_constraints = nullptr);

  // The unit outward normal of the planar boundary part id (a plane of
  // symmetry): the mean of its faces' normals over all ranks, components
  // at rounding level set to zero. A part that is not planar is refused on
  // every rank, naming the entry. Collective.
  template <int dim>
  Tensor<1, dim>
  symmetry_plane_normal(const hp::MappingCollection<dim> &mapping,
                        const DoFHandler<dim>            &dof_handler,
                        const types::boundary_id          id,
                        const MPI_Comm                    communicator);
} // namespace ViscoContact

#endif
