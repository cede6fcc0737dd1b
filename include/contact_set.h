#ifndef viscoplastic_contact_contact_set_h
#define viscoplastic_contact_contact_set_h

#include <deal.II/base/array_view.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/point.h>
#include <deal.II/base/quadrature.h>
#include <deal.II/base/tensor.h>

#include <deal.II/dofs/dof_handler.h>

#include <deal.II/hp/mapping_collection.h>
#include <deal.II/hp/q_collection.h>

#include <deal.II/lac/affine_constraints.h>

#include "contact_nodes.h"
#include "contact_pairs/opposite_side.h"
#include "back_ends/linear_algebra.h"

#include <algorithm>
#include <cmath>
#include <array>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace ViscoContact
{
  using namespace dealii;

  // w_i = int_Gamma3 phi_i and int_Gamma3 phi_i nu at every vertex of the
  // given boundary parts, assembled like a right-hand side into the
  // displacement layout (the value of vertex i sits at its x-dof for the
  // weight, at its dim dofs for the weighted normal). Each rank adds its
  // faces and the owners receive the sums, so the result does not depend
  // on the partition. With an exact face quadrature these are the row sums
  // of the boundary mass matrix: the lumped contact terms of
  // doc/model.md, section 2, on any mesh.
  template <int dim>
  void
  assemble_lumped_weights(const hp::MappingCollection<dim> &mapping,
                          const DoFHandler<dim>            &dof_handler,
                          const hp::QCollection<dim - 1>   &face_quadrature,
                          const std::vector<types::boundary_id> &boundary_ids,
                          VectorType                            &weights,
                          VectorType &weighted_normals);

  // The values of the hanging vertices of Gamma_3 passed on to their
  // parents with the weights of their constraints (contact_set.cc).
  // Collective.
  void
  pass_on_hanging_values(VectorType                      &vector,
                         const AffineConstraints<double> &constraints,
                         const VectorType                &layout);

  // The order of the contact profiles along a boundary: lexicographic in
  // the coordinates (x first), with a tolerance for coordinates that differ
  // by rounding only; on the benchmark's bottom edge it is the order in x.
  template <int dim>
  inline bool
  precedes_in_profile(const Point<dim> &a, const Point<dim> &b)
  {
    for (unsigned int d = 0; d < dim; ++d)
      if (std::abs(a[d] - b[d]) > 1e-12)
        return a[d] < b[d];
    return false;
  }

  // Whether a boundary id is one of the given ones (a zone's faces, its
  // opposite side's).
  inline bool
  is_one_of(const types::boundary_id               id,
            const std::vector<types::boundary_id> &ids)
  {
    return std::find(ids.begin(), ids.end(), id) != ids.end();
  }

  // A contact zone as the contact set needs it: its number (1 for
  // subsection Contact, N for Contact zone N) and the subsection of the
  // parameter file that defines it (for outputs and messages), its law, its
  // boundary parts, and the direction in which its nodes meet the obstacle
  // (from the body into it; none: each node's outward normal), and its
  // tangential law.
  template <int dim>
  struct ContactZoneDescription
  {
    unsigned int                    number;
    std::string                     subsection;
    ContactLaw                      law;
    std::vector<types::boundary_id> boundary_ids;
    std::optional<Tensor<1, dim>>   direction;
    FrictionLaw                     friction = std::make_shared<Frictionless>();
    // A contact pair: the boundary parts of the body the zone meets (empty:
    // a rigid obstacle).
    std::vector<types::boundary_id> opposite_ids;
    // The largest distance between paired faces (0: the longest face of
    // the two sides).
    double search_distance = 0;
    // Whether the distance between the sides counts in the gap (else the
    // zone's Initial gap alone).
    bool measured_gap = true;
  };

  template <int dim>
  class ContactPairs;

  // The displacement of an obstacle's points over a time step: an affine
  // map of the place x, linear x + shift (a rigid motion less the
  // identity; linear = 0 for a translation).
  template <int dim>
  struct ObstacleStep
  {
    Tensor<2, dim> linear;
    Tensor<1, dim> shift;

    Tensor<1, dim>
    at(const Point<dim> &x) const
    {
      return linear * x + shift;
    }
  };

  // @sect3{The contact set}
  //
  // The contact nodes this MPI rank owns: the locally owned vertices of
  // Gamma_3 that are not constrained (the corner on Gamma_1 and hanging
  // nodes are not contact nodes), each with its outward normal nu_i (the
  // normalised int phi_i nu, so a contact boundary need not be
  // axis-aligned), its lumped weight w_i, its dofs, and (through
  // ContactNodes) its piece of the contact law and the last (r, z). The
  // nodes are sorted along Gamma_3 (lexicographically); across ranks they
  // are numbered rank by rank.
  template <int dim>
  class ContactSet : public ContactNodes
  {
  public:
    struct NodeGeometry
    {
      Point<dim> location;
      // The node's row n_i of N on its dofs, r_i = n_i . u: the normal (or
      // the zone's direction) without the constrained components, of
      // length 1 except on an oblique plane of symmetry (find_nodes()).
      Tensor<1, dim> normal;
      // The direction of the node's contact force in space (the unit
      // vector of which normal is the row; the same where no plane of
      // symmetry constrains the node): the force the obstacle exerts on
      // the body is -z_i direction - sum_j t_ij tangents_j.
      Tensor<1, dim>                           direction;
      std::array<types::global_dof_index, dim> dofs;
      // The same dofs as indices into the local storage of the
      // displacement vectors (owned entries first, then ghosts).
      std::array<unsigned int, dim> local_dofs;
      // The vertex's dof of the scalar output fields.
      types::global_dof_index scalar_dof;
      // The contact zone (index into the zones of setup()).
      unsigned int zone;
      // In a frictional zone: the tangential directions tau_j (unit vectors
      // of space, orthogonal to the normal) and their rows t_j on the dofs,
      // s_j = t_j . u (C^T tau_j where a plane of symmetry constrains the
      // node, find_nodes()); none in a frictionless zone.
      unsigned int                        n_tangents = 0;
      std::array<Tensor<1, dim>, dim - 1> tangents;
      std::array<Tensor<1, dim>, dim - 1> tangent_rows;
      // On a contact pair (contact_pairs/contact_pairs.h): component c of
      // the opposite side's displacement at the node as a sum of
      // coefficient * u[dof] over the entries of component c, and the
      // distance between the sides along the node's direction. The rows of
      // the node are then a . (u_node - u_opposite), a its direction or a
      // tangent; the gap adds to the zone's Initial gap.
      struct OppositeEntry
      {
        types::global_dof_index dof;
        unsigned int            local_dof;
        unsigned int            component;
        double                  coefficient;
      };
      std::vector<OppositeEntry> opposite;
      double                     opposite_gap = 0;
      // For the output (OppositeSide): the opposite vertices by their
      // x-dof (local in the layout) with the coefficients M_jk / D_j,
      // whatever constraints their components have.
      struct OppositeVertexShare
      {
        unsigned int x_local_dof;
        double       coefficient;
      };
      std::vector<OppositeVertexShare> opposite_vertices;
    };

    // Contact pairs (zones with Opposite boundary ids, contact_pairs.h),
    // before the vectors are laid out: the coupling of the pair nodes this
    // rank owns with the opposite sides, and the dofs of those sides that
    // their rows use and this rank does not own, which must be ghosts of
    // the layout setup() gets. Collective; refuses bad pairs on every rank.
    IndexSet
    couple_pairs(const std::vector<ContactZoneDescription<dim>> &zones,
                 const DoFHandler<dim>                          &dof_handler,
                 const AffineConstraints<double>                &constraints);

    // A vertex on the boundary parts of several zones belongs to the first
    // of them. constraints are all of the displacement's, hanging_constraints
    // those of the hanging nodes alone.
    void
    setup(const std::vector<ContactZoneDescription<dim>> &zones,
          const hp::MappingCollection<dim>               &mapping,
          const DoFHandler<dim>                          &dof_handler,
          const DoFHandler<dim>                          &scalar_dof_handler,
          const hp::QCollection<dim - 1>                 &face_quadrature,
          const AffineConstraints<double>                &constraints,
          const AffineConstraints<double>                &hanging_constraints,
          const VectorType                               &layout);

    // The obstacle: s_i = gap(x_i, time) at every node, gap the function of
    // the node's zone (nullptr: s = 0), the distance from the node to the
    // obstacle along its direction (negative where the obstacle has moved
    // into the body), so that the law acts on the penetration
    // r_i = nu_i . u_i - s_i. Returns the message naming the entry if a
    // value is not finite (else empty); not collective.
    std::string
    set_gaps(const std::vector<Function<dim> *> &zone_gaps, const double time);
    double
    gap(const unsigned int i) const;

    // The Tresca bounds g_i = w_i g(x_i) of the nodes of zones with Tresca
    // friction (zone_bounds: the Slip bound of each zone, nullptr for the
    // others). Returns the message naming the entry if a value is negative
    // or not finite (else empty); not collective.
    std::string
    set_slip_bounds(const std::vector<const Function<dim> *> &zone_bounds);

    // @sect4{Contact rows}
    //
    // Row j of node i (j = 0 the normal n_i, j = 1, ..., n_tangential(i)
    // the tangents t_ij): the row of N that the back ends see, a short
    // sparse vector over dofs, r_i = n_i . u as a sum over its entries.
    // Today every row lies on the node's own dofs (its nonzero components
    // in component order); contact between two bodies makes a row span
    // dofs of both sides, and a back end that only uses rows (the
    // condensed one) needs no change for it.
    struct RowEntry
    {
      types::global_dof_index dof;
      // The dof as an index into the local storage of the displacement
      // vectors (owned entries first, then ghosts).
      unsigned int local_dof;
      double       value;
    };
    ArrayView<const RowEntry>
    row(const unsigned int i, const unsigned int j) const;
    // Whether a row of any rank's nodes has an entry at a dof its rank
    // does not own (a contact pair whose opposite side lies on other
    // ranks): row . u then needs u's ghost values, and v += value row a
    // compress(add) of v afterwards.
    bool
    rows_reach_ghosts() const;
    // row(i, j) . u and v += value row(i, j), on the local entries.
    double
    row_component(const VectorType  &u,
                  const unsigned int i,
                  const unsigned int j) const;
    // The same on the owned entries of u as an array (every entry of the
    // row owned).
    double
    row_component(const double      *u,
                  const unsigned int i,
                  const unsigned int j) const;
    void
    add_to_row(VectorType        &v,
               const unsigned int i,
               const unsigned int j,
               const double       value) const;

    // The full space back end works in each node's frame on the node's own
    // dim dofs (NodeGeometry::dofs): the row of the frame direction a,
    // a_0 n_i + sum_j a_j t_ij, as a vector of the node's components, and
    // row . u_i and v_i += value row on the locally owned entries.
    Tensor<1, dim>
    frame_row(const unsigned int i, const std::array<double, 3> &a) const;
    double
    node_component(const VectorType     &u,
                   const unsigned int    i,
                   const Tensor<1, dim> &row) const;
    void
    add_to_node(VectorType           &v,
                const unsigned int    i,
                const Tensor<1, dim> &row,
                const double          value) const;
    // The tangential displacements s_ij = t_ij . u of every node (zero
    // where the zone is frictionless).
    std::vector<Tangential>
    tangential_displacements(const VectorType &u) const;
    // The weakening variable of every node
    // (ContactNodes::weakening_variable()) as a nodal field at its x-dof, with
    // the hanging-node constraints applied and the ghosts imported (for
    // checkpoints and transfers), and back from such a field at the nodes of
    // this rank.
    VectorType
    weakening_field(const VectorType                &layout,
                    const AffineConstraints<double> &hanging_constraints) const;
    void
    set_weakening_from(const VectorType &field);
    // A moving obstacle: each zone's displacement over the step at the
    // nodes' places, whose
    // tangential components at every frictional node become the node's
    // obstacle slip (ContactNodes::set_obstacle_slip()).
    void
    set_obstacle_steps(const std::vector<ObstacleStep<dim>> &zone_steps);
    // A vector of space from the tangential components of node i in its
    // frame, sum_j x_j tau_ij.
    Tensor<1, dim>
    tangential_vector(const unsigned int i, const Tangential &x) const;
    // Over all ranks: sum_i t_i (as vectors of space) over the nodes of each
    // zone, the tangential force the body exerts on the obstacle.
    std::vector<Tensor<1, dim>>
    zone_tangential_forces(const MPI_Comm communicator) const;
    // Over all ranks, per zone: the contact force on the zone's side (what
    // the other body or the obstacle exerts on it, normal and tangential)
    // and, on a contact pair, the force on the opposite side's free dofs
    // (from the entries of the rows there): the two balance, less what
    // constraints of the opposite side take (a plane of symmetry through
    // it).
    std::vector<std::array<Tensor<1, dim>, 2>>
    zone_side_forces(const MPI_Comm communicator) const;
    // The slip of the last step for the output: zero at a free node.
    Tensor<1, dim>
    output_slip(const unsigned int i) const;

    // The active-set parameter of every node from the operator A of the
    // step problem: c_i = max(nu^T A_ii nu / w_i, 2 * steepest softening),
    // A_ii the dim x dim block of node i, which scales c like the node's
    // stiffness per unit weight (step-41/42 scale it with the diagonal of
    // the matrix). One formula for every back end.
    void
    set_operator(const MatrixType &A);
    // The same from the blocks A_ii of this rank's nodes, for an operator
    // without a matrix.
    void
    set_operator(const std::vector<Tensor<2, dim>> &node_blocks);

    const NodeGeometry &
    node(const unsigned int i) const;
    types::global_dof_index
    n_global_nodes() const;
    // The global number of the first node of this rank.
    types::global_dof_index
    first_global_index() const;

    // nu_i . u_i, from the locally owned entries of u (the penetration is
    // this minus gap(i)).
    double
    normal_component(const VectorType &u, const unsigned int i) const;
    // v_i += value nu_i.
    void
    add_normal(VectorType &v, const unsigned int i, const double value) const;

    // This rank's block of the contact profile along Gamma_3 (rank 0's with
    // the header), one line per node: the coordinates, the time, u_nu, the
    // pressures of the layer, of the foundation and in all, the nodal force,
    // the weight and the status (and the zone number if there are several
    // zones).
    std::string
    profile_text(const double time) const;
    // The header of the profiles on rank 0 (empty on the others); the
    // opposite side of a pair has no columns of the contact side's own
    // variables (bonding, wear).
    std::string
    profile_header(const bool opposite_side = false) const;
    // With contact pairs: this rank's block of the profile of the opposite
    // sides, the same columns for the vertices the zones cover
    // (OppositeSide). Collective.
    bool
    has_pairs() const;
    std::string
    opposite_profile_text(const double time) const;
    // The number of a zone (1 for subsection Contact, N for Contact zone N).
    unsigned int
    zone_number(const unsigned int zone) const;

    // For a change of mesh: the contact pressure as a nodal field of the
    // displacement's layout, z_i / w_i at the first dof of each node and
    // zero elsewhere, with the hanging-node constraints and the ghosts (only
    // those: a Dirichlet constraint, a symmetry plane through Gamma_3, would
    // overwrite the pressure of its nodes). And back: each node's
    // r = nu.u - s and z = w p from u and such a field p, and the pieces
    // they name; the stick/slip states too only with_friction (the step
    // cycles leave them as the predicted start does).
    VectorType
    pressure_field(const VectorType                &layout,
                   const AffineConstraints<double> &hanging_constraints) const;
    void
    set_state_from(const VectorType &u,
                   const VectorType &pressure,
                   const bool        with_friction);
    // With friction, for the step cycles (uniformly refined meshes, no
    // hanging nodes): the tangential traction t_i / w_i as a vector at the
    // dofs of each node, zero elsewhere, with the ghosts. And back: each
    // node's tangential displacement s from u and its tangential force
    // t = w tau_j . f from such a field f, which set_state_from() with
    // friction then takes to stick or slip.
    VectorType
    tangential_traction_field(const VectorType &layout) const;
    void
    set_tangential_state_from(const VectorType &u, const VectorType &traction);

    // The nodal contact fields of the output (in the scalar layout) at the
    // contact nodes of this rank, zero elsewhere, named by
    // output_field_names(): the contact pressure z/w, its parts carried by
    // the layer and by the foundation, the status and the penetration r;
    // on the opposite side of a contact pair what its vertices receive
    // from the zone (OppositeSide). Collective where there are pairs.
    static std::vector<std::string>
    output_field_names();
    void
    fill_output_fields(std::vector<VectorType> &fields) const;
    // The friction fields, likewise: the tangential traction t / w and the
    // slip increment of the last step (output_slip()) as vectors (in the
    // displacement layout), and the friction state (0 free or frictionless,
    // 1 stick, 2 slip; scalar layout); on the opposite sides too.
    void
    fill_friction_fields(VectorType &tangential_traction,
                         VectorType &slip,
                         VectorType &friction_state) const;
    // With a memory term: the memory pressure of the last step (scalar
    // layout); on the opposite sides the mortar average of the zone's.
    void
    fill_memory_field(VectorType &memory_pressure) const;
    // With adhesion, wear, a cohesive interface: the bonding, the worn
    // depth and the damage of the last step (scalar layout; a field of
    // size 0 is left out).
    void
    fill_history_fields(VectorType &bonding,
                        VectorType &wear,
                        VectorType &damage) const;

  private:
    // A nodal field with value_of_node(i) at the x-dof of every node i
    // (pressure_field(), weakening_field()).
    template <typename NodeValue>
    VectorType
    x_dof_field(const VectorType                &layout,
                const AffineConstraints<double> &hanging_constraints,
                const NodeValue                 &value_of_node) const;

    // The contact nodes of this rank into geometry, in the order the zones
    // and the cells come (setup() sorts them): the locally owned vertices of
    // the faces on the boundary parts of each zone, each with its location,
    // its dofs (global, local in partitioner's numbering, and scalar), its
    // zone and its direction: the zone's or the weighted normal, without
    // the components that are constrained, normalised. A vertex whose
    // direction lies in its constrained components (a clamped corner, a
    // hanging node) is not a contact node. Not collective.
    void
    find_nodes(const std::vector<ContactZoneDescription<dim>> &zones,
               const DoFHandler<dim>                          &dof_handler,
               const DoFHandler<dim>             &scalar_dof_handler,
               const AffineConstraints<double>   &constraints,
               const Utilities::MPI::Partitioner &partitioner,
               const VectorType                  &weighted_normals);

    // The entries of the rows of all nodes from their geometry (after the
    // nodes are sorted).
    void
    make_rows();

    // The opposite sides of the pairs, for the output.
    OppositeSide<dim> opposite;

    std::vector<NodeGeometry> geometry;
    // Row j of node i: row_entries[row_begin[node_first_row[i] + j]] up to
    // row_begin[node_first_row[i] + j + 1].
    std::vector<RowEntry>     row_entries;
    std::vector<unsigned int> row_begin;
    std::vector<unsigned int> node_first_row;
    std::vector<std::string>  zone_subsections;
    std::vector<unsigned int> zone_numbers;
    std::vector<double>       gaps; // empty: no obstacle gap (s = 0)
    std::vector<FrictionLaw>  zone_friction;
    // The mortar coupling of the pair nodes (none without pairs).
    std::shared_ptr<const ContactPairs<dim>> pairs;
    bool                                     rows_reach_ghost_dofs = false;
    types::global_dof_index                  n_global              = 0;
    types::global_dof_index                  first_global          = 0;
    MPI_Comm                                 communicator = MPI_COMM_SELF;
  };
} // namespace ViscoContact

#endif
