#ifndef viscoplastic_contact_opposite_side_h
#define viscoplastic_contact_opposite_side_h

#include <deal.II/base/point.h>
#include <deal.II/base/quadrature.h>
#include <deal.II/base/tensor.h>

#include <deal.II/dofs/dof_handler.h>

#include <deal.II/hp/mapping_collection.h>
#include <deal.II/hp/q_collection.h>

#include <deal.II/lac/affine_constraints.h>

#include "back_ends/linear_algebra.h"

#include <array>
#include <memory>
#include <string>
#include <vector>

namespace ViscoContact
{
  using namespace dealii;

  template <int dim>
  class ContactSet;

  template <int dim>
  struct ContactZoneDescription;

  // @sect3{The opposite side of a contact pair, for the output}
  //
  // The contact nodes of a pair lie on its zone; the opposite side has no
  // nodes of its own, but a user wants pressure, gap, slip and state on
  // both bodies. The rows of the zone's nodes carry the mortar
  // coefficients c_jk = M_jk / D_j of the opposite side's dofs k
  // (contact_pairs.h), and they transfer both kinds of field:
  // - forces by action and reaction: vertex k receives sum_j c_jk f_j, f_j
  //   the force of node j (the transpose of the mortar map, so the forces
  //   on the two sides balance exactly), over its lumped weight: the
  //   contact pressure, the layer's part of it and the tangential traction;
  // - states by the mortar average: a value at vertex k is
  //   sum_j D_j c_jk a_j / sum_j D_j c_jk (the weights M_jk are the
  //   integrals of the zone's dual functions against vertex k's shape
  //   function, so a constant is kept exactly): the penetration and the
  //   slip (with the sign of this side's motion relative to the other);
  //   the contact and friction states and the zone are those of the node
  //   with the largest weight M_jk at the vertex.
  // Only the vertices that the zone covers (sum_j M_jk > 0) get values.
  template <int dim>
  class OppositeSide
  {
  public:
    // The owned vertices of the opposite sides of the zones with lumped
    // weight and normal (as the zone's nodes get them); their order is
    // lexicographic in the coordinates, as the profile's. Collective.
    void
    setup(const std::vector<ContactZoneDescription<dim>> &zones,
          const hp::MappingCollection<dim>               &mapping,
          const DoFHandler<dim>                          &dof_handler,
          const DoFHandler<dim>                          &scalar_dof_handler,
          const hp::QCollection<dim - 1>                 &face_quadrature,
          const AffineConstraints<double>                &hanging_constraints,
          const VectorType                               &layout);

    // What a vertex of the opposite side receives from the zone.
    struct VertexState
    {
      Point<dim> location;
      // The displacement's dofs (local in the layout) and the scalar dof.
      std::array<unsigned int, dim> local_dofs;
      types::global_dof_index       scalar_dof;
      double                        weight;
      // Whether the zone covers the vertex; the rest are zero if not.
      bool           covered             = false;
      double         normal_force        = 0;
      double         contact_pressure    = 0;
      double         compliance_pressure = 0;
      double         penetration         = 0;
      double         memory_pressure     = 0;
      unsigned int   status              = 0;
      unsigned int   friction_state      = 0;
      unsigned int   zone                = 0;
      Tensor<1, dim> tangential_traction;
      Tensor<1, dim> slip;
    };
    // The state of every vertex of this rank from the zone's nodes.
    // Collective.
    std::vector<VertexState>
    states(const ContactSet<dim> &contact) const;

    // This rank's block of the opposite sides' profile: one line per
    // covered vertex, the columns of the zone's profile
    // (ContactSet::profile_text()).
    static std::string
    profile_text(const std::vector<VertexState> &states,
                 const ContactSet<dim>          &contact,
                 const double                    time);

  private:
    struct Vertex
    {
      Point<dim>                    location;
      std::array<unsigned int, dim> local_dofs;
      types::global_dof_index       scalar_dof;
      double                        weight;
      Tensor<1, dim>                normal; // unit, outward
    };
    std::vector<Vertex>                                vertices;
    std::shared_ptr<const Utilities::MPI::Partitioner> partitioner;
  };
} // namespace ViscoContact

#endif
