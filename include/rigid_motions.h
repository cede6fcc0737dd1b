// The rigid motions that the constraints of the displacement leave free: a
// check that K is not singular before it is assembled and factorised.

#ifndef viscoplastic_contact_rigid_motions_h
#define viscoplastic_contact_rigid_motions_h

#include <deal.II/base/mpi.h>
#include <deal.II/base/point.h>

#include <deal.II/dofs/dof_handler.h>

#include <deal.II/hp/mapping_collection.h>

#include <deal.II/grid/tria.h>

#include <deal.II/lac/affine_constraints.h>

#include <string>
#include <vector>

namespace ViscoContact
{
  using namespace dealii;

  // @sect3{Free rigid motions}
  //
  // The rigid motions of the bodies of the mesh (its connected components)
  // that the constraints do not stop: K is singular unless this is empty.
  // One entry per body with a free motion: its number (from 1, in the order
  // of the coarse cells), the number of bodies, its bounding box, and one
  // line per free motion, e.g. "translation in x", "rotation about z", or
  // for a combination "0.71 translation in x + 0.71 rotation about z". The
  // rotations are right-handed, about the centre of the body's bounding
  // box. Collective.
  //
  // dof_handler: a primitive vector-valued element with dim components
  // (FESystem of P1 or Q1) on any (also distributed) mesh; constraints:
  // closed, stored at least on the locally relevant dofs (their
  // inhomogeneities do not matter). Every rank returns the same lines.
  template <int dim>
  struct FreeBody
  {
    unsigned int             number;
    unsigned int             n_bodies;
    Point<dim>               lower, upper;
    std::vector<std::string> motions;
  };

  // The bodies of the mesh: the body number (from 0, in the order of the
  // coarse cells) of every active cell this rank knows, by
  // active_cell_index() (artificial cells: numbers::invalid_unsigned_int),
  // and in n_bodies their number. Collective.
  template <int dim>
  std::vector<unsigned int>
  body_of_cells(const Triangulation<dim> &triangulation,
                const MPI_Comm            communicator,
                unsigned int             &n_bodies);

  template <int dim>
  std::vector<FreeBody<dim>>
  free_rigid_motions(const hp::MappingCollection<dim> &mapping,
                     const DoFHandler<dim>            &dof_handler,
                     const AffineConstraints<double>  &constraints,
                     const MPI_Comm                    communicator);
} // namespace ViscoContact

#endif
