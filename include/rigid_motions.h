// The rigid motions that the constraints of the displacement leave free: a
// check that K is not singular before it is assembled and factorised.

#ifndef viscoplastic_contact_rigid_motions_h
#define viscoplastic_contact_rigid_motions_h

#include <deal.II/base/mpi.h>

#include <deal.II/dofs/dof_handler.h>

#include <deal.II/fe/mapping.h>

#include <deal.II/lac/affine_constraints.h>

#include <string>
#include <vector>

namespace ViscoContact
{
  using namespace dealii;

  // @sect3{Free rigid motions}
  //
  // The rigid motions of the body that the constraints do not stop: K is
  // singular unless this is empty. Returns one line per free motion, e.g.
  // "translation in x", "rotation about z", or for a combination
  // "0.71 translation in x + 0.71 rotation about z". The rotations are
  // right-handed, about the centre of the mesh's bounding box. Collective.
  //
  // dof_handler: a primitive vector-valued element with dim components
  // (FESystem of P1 or Q1) on any (also distributed) mesh; constraints:
  // closed, stored at least on the locally relevant dofs (their
  // inhomogeneities do not matter). Every rank returns the same lines.
  template <int dim>
  std::vector<std::string>
  free_rigid_motions(const Mapping<dim>              &mapping,
                     const DoFHandler<dim>           &dof_handler,
                     const AffineConstraints<double> &constraints,
                     const MPI_Comm                   communicator);
} // namespace ViscoContact

#endif
