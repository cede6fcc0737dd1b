#ifndef viscoplastic_contact_contact_pairs_h
#define viscoplastic_contact_contact_pairs_h

#include <deal.II/base/index_set.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/partitioner.h>
#include <deal.II/base/point.h>

#include <deal.II/dofs/dof_handler.h>

#include <deal.II/lac/affine_constraints.h>

#include "contact_set.h"

#include <map>
#include <string>
#include <utility>
#include <vector>

namespace ViscoContact
{
  using namespace dealii;

  // @sect3{Contact pairs: zones that meet another body}
  //
  // A contact zone with Opposite boundary ids meets a boundary part of
  // another body of the mesh instead of a rigid obstacle. Its nodes (the
  // zone's side, the slave side of the mortar method) keep their place in
  // the contact set; ContactPairs couples each of them to the opposite
  // (master) side by the mortar integrals of mortar.h: the node's weight
  // becomes D_j, the opposite side's displacement at the node
  // sum_k (M_jk / D_j) u_k (each master dof expanded through its
  // constraint: hanging nodes, planes of symmetry), and the distance of the
  // sides along the node's direction its gap.
  //
  // In parallel, each rank couples the zone's nodes it owns. It needs every
  // face of the zone around them (its own and its ghost cells have them)
  // and the faces of the opposite side near them, wherever they are: each
  // rank sends the opposite faces of its own cells to every rank whose zone
  // faces they come within the search distance of (a bounding box per rank,
  // gathered on all ranks: 2 dim numbers each), so no rank holds more of
  // the opposite side than lies across its part of the zone. The dofs of
  // the opposite side that a rank's rows use and that it does not own
  // become ghosts of the displacement vectors (ghost_dofs()).
  template <int dim>
  class ContactPairs
  {
  public:
    // Collective. Refuses on every rank, naming the entry: an opposite
    // side that shares nodes with the zone, or that lies within the search
    // distance of no node of the zone (with the distance of the nearest
    // facing face).
    void
    reinit(const std::vector<ContactZoneDescription<dim>> &zones,
           const DoFHandler<dim>                          &dof_handler,
           const AffineConstraints<double>                &constraints,
           const MPI_Comm                                  communicator);

    // The dofs the rows of this rank's pair nodes use that it does not own.
    const IndexSet &
    ghost_dofs() const;

    // The nodes of pair zones among nodes (ContactSet::find_nodes()): their
    // weights, opposite entries (local indices from partitioner, which must
    // have ghost_dofs() among its ghosts) and gaps. A node the opposite side
    // does not cover (D_j = 0) is not a contact node and is removed from
    // nodes and weights.
    void
    couple_nodes(std::vector<typename ContactSet<dim>::NodeGeometry> &nodes,
                 std::vector<double>                                 &weights,
                 const Utilities::MPI::Partitioner &partitioner) const;

    // What the coupling gives a node: its weight D_j, the opposite side's
    // point sum_k (M_jk / D_j) x_k, the opposite displacement's components
    // as (dof, component, coefficient), and the opposite vertices as
    // (x-dof, M_jk / D_j), for the output.
    struct NodeCoupling
    {
      double     weight = 0;
      Point<dim> opposite_point;
      std::vector<std::tuple<types::global_dof_index, unsigned int, double>>
                                                              entries;
      std::vector<std::pair<types::global_dof_index, double>> vertices;
    };

  private:
    // By zone index and the node's x-dof.
    std::map<std::pair<unsigned int, types::global_dof_index>, NodeCoupling>
                      couplings;
    std::vector<bool> zone_is_pair, zone_measures_gap;
    IndexSet          ghosts;
  };
} // namespace ViscoContact

#endif
