// The contact nodes of Gamma_3: where they are, their weights, normals and
// active-set parameters, and their output (profiles and nodal fields).
//
// The contact integral is lumped to the vertices of Gamma_3 (doc/model.md,
// section 2, "Lumping"): node i carries the weight w_i = int_Gamma3 phi_i
// and the normal nu_i, the normalised int_Gamma3 phi_i nu. Both are
// assembled like a right-hand side, so they do not depend on how the mesh is
// partitioned, and the normal is the mesh's own, so a contact boundary need
// not be axis-aligned.

#include <deal.II/base/exceptions.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/partitioner.h>

#include <deal.II/fe/fe_values.h>

#include <deal.II/lac/full_matrix.h>

#include <deal.II/hp/fe_values.h>

#include "contact_pairs/contact_pairs.h"
#include "contact_set.h"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <map>
#include <set>
#include <sstream>

namespace ViscoContact
{
  // @sect4{pass_on_hanging_values}
  //
  // A vertex of Gamma_3 may be hanging (on adapted 3D meshes: the middle
  // of an edge between a refined and an unrefined contact face). It is no
  // contact node, since its displacement is the average of its parents';
  // its weight and weighted normal go to those parents with the weights of
  // its constraint. The result is the row sums of the boundary mass matrix
  // of the conforming (constrained) space, C^T M C 1 = C^T M 1, as without
  // hanging vertices. Each rank passes on the values of the hanging dofs
  // it owns (the parents are locally relevant: they lie on the same
  // cells); on meshes without hanging vertices on Gamma_3 nothing is
  // added. Collective.
  void
  pass_on_hanging_values(VectorType                      &vector,
                         const AffineConstraints<double> &constraints,
                         const VectorType                &layout)
  {
    const auto &partitioner = *layout.get_partitioner();
    VectorType  passed_on(layout);
    passed_on = 0;
    for (types::global_dof_index dof = partitioner.local_range().first;
         dof < partitioner.local_range().second;
         ++dof)
      if (vector(dof) != 0 && constraints.is_constrained(dof))
        if (const auto *entries = constraints.get_constraint_entries(dof))
          for (const auto &[parent, coefficient] : *entries)
            passed_on(parent) += coefficient * vector(dof);
    passed_on.compress(VectorOperation::add);
    vector += passed_on;
  }



  // @sect4{assemble_lumped_weights}
  //
  // Like a right-hand side: each rank integrates phi_i and phi_i nu over its
  // own faces of the boundary parts, adds into the (ghosted) entries of the
  // cell's dofs, and compress() sends the ghost contributions to the owners.
  // Every face is integrated by exactly one rank, the owner of its cell, so
  // the sums do not depend on the partition (up to the order of the
  // additions).
  //
  // The displacement element is a system of dim equal scalar elements, so
  // the shape function of component c at a vertex is the scalar hat function
  // phi times e_c: the weight is collected at the vertex's x-dof only, the
  // weighted normal component by component at its dim dofs.
  template <int dim>
  void
  assemble_lumped_weights(const hp::MappingCollection<dim> &mapping,
                          const DoFHandler<dim>            &dof_handler,
                          const hp::QCollection<dim - 1>   &face_quadrature,
                          const std::vector<types::boundary_id> &boundary_ids,
                          VectorType                            &weights,
                          VectorType &weighted_normals)
  {
    // Values, JxW and normals on the faces; the mapping is the run's
    // (linear) one.
    hp::FEFaceValues<dim>                hp_face_values(mapping,
                                         dof_handler.get_fe_collection(),
                                         face_quadrature,
                                         update_values | update_JxW_values
                                           | update_normal_vectors);
    std::vector<types::global_dof_index> local_dof_indices;
    weights          = 0;
    weighted_normals = 0;
    // Only faces on the named boundary parts of locally owned cells.
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
        for (const unsigned int f : cell->face_indices())
          if (cell->face(f)->at_boundary()
              && is_one_of(cell->face(f)->boundary_id(), boundary_ids))
            {
              const FiniteElement<dim> &fe = cell->get_fe();
              hp_face_values.reinit(cell, f);
              const FEFaceValues<dim> &fe_face_values
                = hp_face_values.get_present_fe_values();
              local_dof_indices.resize(fe.n_dofs_per_cell());
              cell->get_dof_indices(local_dof_indices);
              // phi_i(x_q) JxW_q, for the weight (component 0) and for each
              // component of the weighted normal.
              for (const unsigned int q :
                   fe_face_values.quadrature_point_indices())
                for (unsigned int i = 0; i < fe.n_dofs_per_cell(); ++i)
                  {
                    const unsigned int c
                      = fe.system_to_component_index(i).first;
                    const double phi_JxW = fe_face_values.shape_value(i, q)
                                           * fe_face_values.JxW(q);
                    if (c == 0)
                      weights(local_dof_indices[i]) += phi_JxW;
                    weighted_normals(local_dof_indices[i])
                      += phi_JxW * fe_face_values.normal_vector(q)[c];
                  }
            }
    // Contributions to ghost entries go to the owners of those dofs.
    weights.compress(VectorOperation::add);
    weighted_normals.compress(VectorOperation::add);
  }



  template <int dim>
  Tensor<1, dim>
  free_direction(const typename ContactSet<dim>::NodeGeometry &node,
                 const AffineConstraints<double>              &constraints);



  // @sect4{ContactSet::couple_pairs}
  template <int dim>
  IndexSet
  ContactSet<dim>::couple_pairs(
    const std::vector<ContactZoneDescription<dim>> &zones,
    const DoFHandler<dim>                          &dof_handler,
    const AffineConstraints<double>                &constraints)
  {
    pairs.reset();
    if (std::all_of(zones.begin(), zones.end(), [](const auto &zone) {
          return zone.opposite_ids.empty();
        }))
      return IndexSet(dof_handler.n_dofs());
    auto coupled = std::make_shared<ContactPairs<dim>>();
    coupled->reinit(zones,
                    dof_handler,
                    constraints,
                    dof_handler.get_communicator());
    pairs = coupled;
    return pairs->ghost_dofs();
  }



  // @sect4{ContactSet::setup}
  //
  // Finds the contact nodes this rank owns, with their geometry, weights and
  // numbering across the ranks: the lumped weights and normals of all
  // vertices of Gamma_3, those of hanging vertices passed on to their
  // parents, the nodes themselves (find_nodes()), their order along
  // Gamma_3, and their global numbers.
  template <int dim>
  void
  ContactSet<dim>::setup(const std::vector<ContactZoneDescription<dim>> &zones,
                         const hp::MappingCollection<dim> &mapping,
                         const DoFHandler<dim>            &dof_handler,
                         const DoFHandler<dim>            &scalar_dof_handler,
                         const hp::QCollection<dim - 1>   &face_quadrature,
                         const AffineConstraints<double>  &constraints,
                         const AffineConstraints<double>  &hanging_constraints,
                         const VectorType                 &layout)
  {
    // The lumped weights and weighted normals of all vertices of Gamma_3 (of
    // every zone), in the displacement layout, with the values of hanging
    // vertices passed on to their parents.
    communicator = layout.get_mpi_communicator();
    std::vector<types::boundary_id> contact_ids;
    zone_subsections.clear();
    zone_numbers.clear();
    std::vector<ContactLaw> laws;
    for (const ContactZoneDescription<dim> &zone : zones)
      {
        contact_ids.insert(contact_ids.end(),
                           zone.boundary_ids.begin(),
                           zone.boundary_ids.end());
        zone_subsections.push_back(zone.subsection);
        zone_numbers.push_back(zone.number);
        laws.push_back(zone.law);
      }
    VectorType weights(layout), weighted_normals(layout);
    assemble_lumped_weights(mapping,
                            dof_handler,
                            face_quadrature,
                            contact_ids,
                            weights,
                            weighted_normals);
    // Only the hanging vertices pass their values on: an oblique plane of
    // symmetry also constrains a component, by the other components of the
    // same vertex, which keeps its weight and normal.
    for (VectorType *vector : {&weights, &weighted_normals})
      pass_on_hanging_values(*vector, hanging_constraints, layout);

    gaps.clear();
    find_nodes(zones,
               dof_handler,
               scalar_dof_handler,
               constraints,
               *layout.get_partitioner(),
               weighted_normals);

    // Along Gamma_3: the order of the contact profiles.
    std::sort(geometry.begin(),
              geometry.end(),
              [](const NodeGeometry &a, const NodeGeometry &b) {
                return precedes_in_profile(a.location, b.location);
              });
    // The weight of a node sits at its x-dof; the nodes start at r = z = 0,
    // stuck where the zone has friction, with a zero Tresca bound until
    // set_slip_bounds().
    std::vector<double> node_weights(geometry.size());
    for (unsigned int i = 0; i < geometry.size(); ++i)
      node_weights[i] = weights(geometry[i].dofs[0]);
    // The nodes of contact pairs take the weights and rows of the mortar
    // coupling with the opposite side.
    if (pairs)
      pairs->couple_nodes(geometry, node_weights, *layout.get_partitioner());
    opposite.setup(zones,
                   mapping,
                   dof_handler,
                   scalar_dof_handler,
                   face_quadrature,
                   hanging_constraints,
                   layout);
    std::vector<unsigned int> node_zones(geometry.size());
    for (unsigned int i = 0; i < geometry.size(); ++i)
      node_zones[i] = geometry[i].zone;
    reinit(ContactLaws(laws), node_zones, node_weights);
    zone_friction.clear();
    for (const ContactZoneDescription<dim> &zone : zones)
      zone_friction.push_back(zone.friction);
    make_rows();
    const unsigned int n_owned = layout.locally_owned_size();
    rows_reach_ghost_dofs      = Utilities::MPI::logical_or(
      std::any_of(row_entries.begin(),
                  row_entries.end(),
                  [n_owned](const RowEntry &entry) {
                    return entry.local_dof >= n_owned;
                  }),
      communicator);
    std::vector<unsigned int> tangents(geometry.size());
    for (unsigned int i = 0; i < geometry.size(); ++i)
      tangents[i] = geometry[i].n_tangents;
    set_friction(zone_friction,
                 tangents,
                 std::vector<double>(geometry.size(), 0.));

    // Numbering across ranks: rank p's nodes come after those of ranks
    // 0, ..., p - 1, which is how deal.II's Partitioner numbers a vector
    // whose ranks each hold a contiguous block (a prefix sum of the sizes).
    // The condensed back end relies on this numbering: gathering node
    // vectors in rank order yields them in global order.
    const Utilities::MPI::Partitioner numbering(geometry.size(),
                                                0,
                                                communicator);
    n_global     = numbering.size();
    first_global = numbering.local_range().first;
    // A contact zone whose nodes are all clamped has nothing to solve; say
    // so in the terms of the parameter file.
    std::vector<unsigned int> zone_sizes(zones.size(), 0);
    for (const unsigned int zone : node_zones)
      ++zone_sizes[zone];
    const std::vector<unsigned int> local_sizes = zone_sizes;
    Utilities::MPI::sum(
      ArrayView<const unsigned int>(local_sizes.data(), local_sizes.size()),
      communicator,
      ArrayView<unsigned int>(zone_sizes.data(), zone_sizes.size()));
    for (unsigned int z = 0; z < zones.size(); ++z)
      AssertThrow(zone_sizes[z] > 0,
                  ExcMessage(
                    (zones[z].subsection == "Contact"
                       ? std::string("Invalid parameter <Contact boundary "
                                     "ids> in subsection <Boundary>")
                       : "Invalid parameter <Boundary ids> in subsection <"
                           + zones[z].subsection + ">")
                    + ": the contact zone has no node that is free to move "
                      "(all its nodes are clamped or belong to a zone "
                      "listed before it); accepted: ids of boundary parts "
                      "with at least one node of their own off Gamma_1."));
  }



  // @sect4{free_direction}
  //
  // The direction of a contact node whose other components are constrained
  // (a node where the contact zone meets a roller, a plane of symmetry or a
  // part whose tangential displacement is prescribed). The node's
  // displacement lies in the span of the columns of C, u_node = C u_free,
  // u_free its unconstrained dofs (on a plane x_k = const, C drops
  // component k; on an oblique plane, the constrained component is a
  // combination of the others, setup.cc). Its direction nu is projected
  // onto that span and normalised, as the mirror image of the body would
  // make it (the weighted normal of a vertex on a plane of symmetry sees
  // only one side), and the node's vector is n = C^T nu on the free dofs:
  // then r = nu . u_node = n . u_free exactly, and n is the row of N (the
  // contact force n z acts on the free dofs). n has length 1 except where
  // the constraint couples components (an oblique plane). A vertex whose
  // direction lies in its constrained components gets the zero vector (it
  // is not a contact node, like a clamped corner); one constrained to
  // another vertex's dofs is refused, naming its location.
  //
  // The same construction gives the node's tangential frame: an
  // orthonormal basis tau_j of the span of C orthogonal to nu (from the
  // coordinate axes, dim - 1 directions on a free node, fewer where a
  // plane of symmetry takes one), and its rows t_j = C^T tau_j.
  template <int dim>
  struct FreeFrame
  {
    Tensor<1, dim>                      direction;
    Tensor<1, dim>                      normal_row;
    unsigned int                        n_tangents = 0;
    std::array<Tensor<1, dim>, dim - 1> tangent_rows, tangents;
  };

  template <int dim>
  FreeFrame<dim>
  free_frame(const typename ContactSet<dim>::NodeGeometry &node,
             const AffineConstraints<double>              &constraints)
  {
    FreeFrame<dim> frame;
    const double   length = node.normal.norm();
    // C: column f for free component f; constrained rows from their lines.
    // Coupling weights at rounding level (the edge of two planes of
    // symmetry along a coordinate axis) couple nothing.
    FullMatrix<double> C(dim, dim);
    std::vector<bool>  free(dim, true);
    for (unsigned int c = 0; c < dim; ++c)
      free[c] = !constraints.is_constrained(node.dofs[c]);
    for (unsigned int c = 0; c < dim; ++c)
      if (free[c])
        C(c, c) = 1;
      else if (const auto *entries
               = constraints.get_constraint_entries(node.dofs[c]))
        for (const auto &[dof, weight] : *entries)
          {
            if (std::abs(weight) <= 1e-10)
              continue;
            const auto own = std::find(node.dofs.begin(), node.dofs.end(), dof);
            const unsigned int f = own - node.dofs.begin();
            std::ostringstream where;
            where << node.location;
            AssertThrow(own != node.dofs.end() && free[f],
                        ExcMessage("The contact node at (" + where.str()
                                   + ") is constrained to the displacement "
                                     "of other nodes; accepted: contact "
                                     "nodes that are free, clamped or on "
                                     "planes of symmetry."));
            C(c, f) = weight;
          }
    // nu projected onto the span of C: C (C^T C)^+ C^T nu, with the
    // constrained components' empty columns left out of the inverse.
    Tensor<1, dim> n; // C^T nu
    for (unsigned int f = 0; f < dim; ++f)
      for (unsigned int c = 0; c < dim; ++c)
        n[f] += C(c, f) * node.normal[c];
    FullMatrix<double> gram(dim, dim); // C^T C, identity in constrained ones
    for (unsigned int f = 0; f < dim; ++f)
      for (unsigned int g = 0; g < dim; ++g)
        if (free[f] && free[g])
          for (unsigned int c = 0; c < dim; ++c)
            gram(f, g) += C(c, f) * C(c, g);
        else
          gram(f, g) = (f == g);
    gram.gauss_jordan();
    Tensor<1, dim> coefficients, direction;
    for (unsigned int f = 0; f < dim; ++f)
      for (unsigned int g = 0; g < dim; ++g)
        coefficients[f] += gram(f, g) * n[g];
    for (unsigned int c = 0; c < dim; ++c)
      for (unsigned int f = 0; f < dim; ++f)
        direction[c] += C(c, f) * coefficients[f];
    // Nothing left (the node where the contact zone meets a part that
    // prescribes its normal component): not a contact node.
    if (direction.norm() <= 1e-3 * length)
      return frame;
    direction /= direction.norm();
    frame.direction = direction;
    for (unsigned int f = 0; f < dim; ++f)
      for (unsigned int c = 0; c < dim; ++c)
        frame.normal_row[f] += C(c, f) * direction[c];
    // The tangents: the columns of C (coordinate axes on a free node),
    // orthogonalised against nu and each other.
    std::vector<Tensor<1, dim>> basis{direction};
    for (unsigned int f = 0; f < dim && frame.n_tangents < dim - 1; ++f)
      {
        if (!free[f])
          continue;
        Tensor<1, dim> column;
        for (unsigned int c = 0; c < dim; ++c)
          column[c] = C(c, f);
        const double column_length = column.norm();
        for (const Tensor<1, dim> &b : basis)
          column -= (column * b) * b;
        if (column.norm() <= 1e-6 * column_length)
          continue;
        column /= column.norm();
        basis.push_back(column);
        Tensor<1, dim> row; // C^T tau
        for (unsigned int g = 0; g < dim; ++g)
          for (unsigned int c = 0; c < dim; ++c)
            row[g] += C(c, g) * column[c];
        frame.tangents[frame.n_tangents]       = column;
        frame.tangent_rows[frame.n_tangents++] = row;
      }
    return frame;
  }



  // @sect4{ContactSet::find_nodes}
  //
  // A vertex of Gamma_3 whose faces all belong to other ranks' cells is
  // still seen through the ghost cells, so every locally owned contact
  // vertex is found. Vertices of hanging or clamped dofs are left out: their
  // displacement is not free, so they cannot carry a contact condition of
  // their own (the corner of Gamma_3 on Gamma_1; hanging nodes, which the
  // refinement toward Gamma_3 in refine_mesh() keeps off it).
  template <int dim>
  void
  ContactSet<dim>::find_nodes(
    const std::vector<ContactZoneDescription<dim>> &zones,
    const DoFHandler<dim>                          &dof_handler,
    const DoFHandler<dim>                          &scalar_dof_handler,
    const AffineConstraints<double>                &constraints,
    const Utilities::MPI::Partitioner              &partitioner,
    const VectorType                               &weighted_normals)
  {
    geometry.clear();
    std::set<types::global_dof_index> seen;
    // Every vertex of every contact face of the owned and ghost cells, once
    // (the set seen remembers the x-dofs taken), zone by zone: a vertex of
    // two zones goes to the first, on every partition (its owner sees all
    // the faces around it).
    for (unsigned int zone = 0; zone < zones.size(); ++zone)
      for (const auto &cell : dof_handler.active_cell_iterators())
        if (!cell->is_artificial())
          for (const unsigned int f : cell->face_indices())
            if (cell->face(f)->at_boundary()
                && is_one_of(cell->face(f)->boundary_id(),
                             zones[zone].boundary_ids))
              for (const unsigned int v : cell->face(f)->vertex_indices())
                {
                  NodeGeometry node;
                  for (unsigned int c = 0; c < dim; ++c)
                    node.dofs[c]
                      = cell->face(f)
                          ->vertex_dof_index(v, c, cell->active_fe_index());
                  // A vertex becomes a node of this rank if this rank owns it
                  // (its dim dofs have the same owner, so the x-dof decides),
                  // it has not been taken already, and not all of its
                  // components are constrained (a clamped corner, a hanging
                  // node).
                  if (!partitioner.in_local_range(node.dofs[0])
                      || !seen.insert(node.dofs[0]).second)
                    continue;
                  unsigned int n_constrained = 0;
                  for (unsigned int c = 0; c < dim; ++c)
                    n_constrained += constraints.is_constrained(node.dofs[c]);
                  if (n_constrained == dim)
                    continue;
                  // Its location, the local indices of its dofs (owned
                  // entries, so no ghost lookup is ever needed), and the
                  // normal: the weighted normal, normalised.
                  node.location = cell->face(f)->vertex(v);
                  for (unsigned int c = 0; c < dim; ++c)
                    {
                      node.local_dofs[c]
                        = partitioner.global_to_local(node.dofs[c]);
                      node.normal[c] = weighted_normals(node.dofs[c]);
                    }
                  // The zone's direction replaces the normal.
                  node.zone = zone;
                  if (zones[zone].direction)
                    node.normal = *zones[zone].direction;
                  const FreeFrame<dim> frame
                    = free_frame<dim>(node, constraints);
                  node.normal    = frame.normal_row;
                  node.direction = frame.direction;
                  if (node.normal.norm() == 0)
                    continue;
                  // The tangential frame, in a frictional zone only. On an
                  // oblique plane of symmetry its rows are not orthonormal
                  // on the dofs; the back ends read the forces along them
                  // with the dual rows.
                  if (zones[zone].friction->has_friction())
                    {
                      node.n_tangents   = frame.n_tangents;
                      node.tangent_rows = frame.tangent_rows;
                      node.tangents     = frame.tangents;
                    }
                  // The same vertex's dof in the scalar dof handler of the
                  // output fields, through the same cell of the common
                  // triangulation.
                  const typename DoFHandler<dim>::active_cell_iterator
                    scalar_cell(&dof_handler.get_triangulation(),
                                cell->level(),
                                cell->index(),
                                &scalar_dof_handler);
                  node.scalar_dof = scalar_cell->face(f)->vertex_dof_index(
                    v,
                    0,
                    scalar_cell->active_fe_index());
                  geometry.push_back(node);
                }
  }



  // @sect4{ContactSet::set_operator}
  //
  // The parameter c_i of every node from the operator A of the step problem
  // (doc/model.md, section 2, "The parameter c_i"): the node's normal
  // stiffness nu_i^T A_ii nu_i per unit weight, at least twice the steepest
  // softening of the law. Called for K at set-up and for every tangent of
  // the implicit update. The entries A_ii are read from rows this rank owns.
  template <int dim>
  void
  ContactSet<dim>::set_operator(const MatrixType &A)
  {
    std::vector<Tensor<2, dim>> node_blocks(size());
    for (unsigned int i = 0; i < size(); ++i)
      for (unsigned int a = 0; a < dim; ++a)
        for (unsigned int b = 0; b < dim; ++b)
          node_blocks[i][a][b] = A.el(geometry[i].dofs[a], geometry[i].dofs[b]);
    set_operator(node_blocks);
  }



  template <int dim>
  void
  ContactSet<dim>::set_operator(const std::vector<Tensor<2, dim>> &node_blocks)
  {
    std::vector<double> c(size());
    for (unsigned int i = 0; i < size(); ++i)
      {
        const double softening = laws().zone_law(zone(i)).steepest_softening();
        const NodeGeometry &n  = geometry[i];
        const double normal_stiffness = n.normal * (node_blocks[i] * n.normal);
        // The factor 2 keeps the growth of q along the softest piece at
        // least c_i / 2, even where the node's own stiffness is small.
        c[i] = std::max(normal_stiffness / weight(i), 2 * softening);
      }
    set_parameters(c);
  }



  // @sect4{Access to the nodes}
  //
  // The geometry of node i, the number of nodes of all ranks, this rank's
  // first global node number.
  template <int dim>
  const typename ContactSet<dim>::NodeGeometry &
  ContactSet<dim>::node(const unsigned int i) const
  {
    return geometry[i];
  }



  template <int dim>
  types::global_dof_index
  ContactSet<dim>::n_global_nodes() const
  {
    return n_global;
  }



  template <int dim>
  types::global_dof_index
  ContactSet<dim>::first_global_index() const
  {
    return first_global;
  }



  // @sect4{ContactSet::make_rows and the rows}
  //
  // The rows of every node on its own dofs: the normal, then the tangents,
  // each with the components in which it is not zero (a component
  // constrained by a plane of symmetry has none).
  template <int dim>
  void
  ContactSet<dim>::make_rows()
  {
    row_entries.clear();
    row_begin.assign(1, 0);
    node_first_row.assign(1, 0);
    for (const NodeGeometry &node : geometry)
      {
        for (unsigned int j = 0; j < 1 + node.n_tangents; ++j)
          {
            const Tensor<1, dim> &vector
              = (j == 0 ? node.normal : node.tangent_rows[j - 1]);
            for (unsigned int c = 0; c < dim; ++c)
              if (vector[c] != 0.)
                row_entries.push_back(
                  RowEntry{node.dofs[c], node.local_dofs[c], vector[c]});
            // On a pair, minus the opposite side's displacement along the
            // row's direction in space, each dof once.
            const Tensor<1, dim> &direction
              = (j == 0 ? node.direction : node.tangents[j - 1]);
            std::map<types::global_dof_index, RowEntry> opposite;
            for (const auto &entry : node.opposite)
              {
                RowEntry &row_entry
                  = opposite
                      .emplace(entry.dof,
                               RowEntry{entry.dof, entry.local_dof, 0.})
                      .first->second;
                row_entry.value
                  -= entry.coefficient * direction[entry.component];
              }
            for (const auto &[dof, entry] : opposite)
              if (entry.value != 0.)
                row_entries.push_back(entry);
            row_begin.push_back(row_entries.size());
          }
        node_first_row.push_back(node_first_row.back() + 1 + node.n_tangents);
      }
  }



  template <int dim>
  ArrayView<const typename ContactSet<dim>::RowEntry>
  ContactSet<dim>::row(const unsigned int i, const unsigned int j) const
  {
    AssertIndexRange(j, node_first_row[i + 1] - node_first_row[i]);
    const unsigned int k = node_first_row[i] + j;
    return make_array_view(row_entries.data() + row_begin[k],
                           row_entries.data() + row_begin[k + 1]);
  }



  // The two operations that connect a row to the displacement vectors:
  // row . u, and v += value row (with the forces z this assembles N^T z).
  // Both use local indices; no communication is involved.
  template <int dim>
  double
  ContactSet<dim>::row_component(const VectorType  &u,
                                 const unsigned int i,
                                 const unsigned int j) const
  {
    double value = 0;
    for (const RowEntry &entry : row(i, j))
      value += entry.value * u.local_element(entry.local_dof);
    return value;
  }



  template <int dim>
  double
  ContactSet<dim>::row_component(const double      *u,
                                 const unsigned int i,
                                 const unsigned int j) const
  {
    double value = 0;
    for (const RowEntry &entry : row(i, j))
      value += entry.value * u[entry.local_dof];
    return value;
  }



  template <int dim>
  bool
  ContactSet<dim>::rows_reach_ghosts() const
  {
    return rows_reach_ghost_dofs;
  }



  template <int dim>
  void
  ContactSet<dim>::add_to_row(VectorType        &v,
                              const unsigned int i,
                              const unsigned int j,
                              const double       value) const
  {
    for (const RowEntry &entry : row(i, j))
      v.local_element(entry.local_dof) += value * entry.value;
  }



  // r_i = n_i . u and v += value n_i: the rows j = 0.
  template <int dim>
  double
  ContactSet<dim>::normal_component(const VectorType  &u,
                                    const unsigned int i) const
  {
    return row_component(u, i, 0);
  }



  template <int dim>
  void
  ContactSet<dim>::add_normal(VectorType        &v,
                              const unsigned int i,
                              const double       value) const
  {
    add_to_row(v, i, 0, value);
  }



  // @sect4{ContactSet::write_profile}
  //
  // Each rank formats its own nodes; rank 0 adds the header. On one rank the
  // lines follow Gamma_3; on several, each rank's block does. One line per
  // node: its coordinates, the time, u_nu, the pressures of the layer, of
  // the foundation and in all, the nodal force, the weight and the status.
  // The caller writes the blocks collectively, so no rank collects the
  // others' lines.
  template <int dim>
  std::string
  ContactSet<dim>::profile_text(const double time) const
  {
    std::ostringstream out;
    out << std::setprecision(10) << profile_header();
    // The foundation's pressure is what the layer does not carry.
    for (unsigned int i = 0; i < size(); ++i)
      {
        for (unsigned int d = 0; d < dim; ++d)
          out << geometry[i].location[d] << ',';
        out << time << ',' << r[i] << ',' << compliance_pressure(i) << ','
            << contact_pressure(i) - compliance_pressure(i) << ','
            << contact_pressure(i) << ',' << z[i] << ',' << weight(i) << ','
            << status(i);
        if (laws().n_zones() > 1)
          out << ',' << zone_numbers[zone(i)];
        if (has_friction())
          {
            const Tensor<1, dim> traction
              = tangential_vector(i, t[i]) / weight(i);
            const Tensor<1, dim> slip = output_slip(i);
            out << ',' << friction_state(i);
            for (unsigned int d = 0; d < dim; ++d)
              out << ',' << traction[d];
            for (unsigned int d = 0; d < dim; ++d)
              out << ',' << slip[d];
          }
        if (has_memory())
          out << ',' << history_pressure(i);
        if (has_adhesion())
          out << ',' << bonding(i);
        if (has_wear())
          out << ',' << this->wear(i);
        if (has_cohesion())
          out << ',' << damage(i);
        out << '\n';
      }
    return out.str();
  }



  template <int dim>
  std::string
  ContactSet<dim>::profile_header(const bool opposite_side) const
  {
    if (Utilities::MPI::this_mpi_process(communicator) != 0)
      return "";
    std::ostringstream out;
    const char        *coordinates[3] = {"x", "y", "z"};
    for (unsigned int d = 0; d < dim; ++d)
      out << coordinates[d] << ',';
    out << "time,u_nu,compliance_pressure,foundation_pressure,"
           "contact_pressure,nodal_force,weight,status"
        << (laws().n_zones() > 1 ? ",zone" : "");
    // With friction: the stick/slip state, the tangential traction t / w
    // and the slip increment of the last step, as vectors of space.
    if (has_friction())
      {
        out << ",friction_state";
        for (const std::string field : {"tangential_traction_", "slip_"})
          for (unsigned int d = 0; d < dim; ++d)
            out << ',' << field << coordinates[d];
      }
    // With a memory term: the memory pressure of the last step (part of
    // compliance_pressure).
    if (has_memory())
      out << ",memory_pressure";
    // With adhesion: the bonding beta of the last step; with wear: the worn
    // depth after it; with a cohesive interface: the damage after it (the
    // contact side's nodes only).
    if (has_adhesion() && !opposite_side)
      out << ",bonding";
    if (has_wear() && !opposite_side)
      out << ",wear";
    if (has_cohesion() && !opposite_side)
      out << ",damage";
    out << '\n';
    return out.str();
  }



  template <int dim>
  bool
  ContactSet<dim>::has_pairs() const
  {
    return pairs != nullptr;
  }



  template <int dim>
  std::string
  ContactSet<dim>::opposite_profile_text(const double time) const
  {
    return OppositeSide<dim>::profile_text(opposite.states(*this), *this, time);
  }



  template <int dim>
  unsigned int
  ContactSet<dim>::zone_number(const unsigned int zone) const
  {
    return zone_numbers[zone];
  }



  // @sect4{ContactSet::pressure_field and weakening_field}
  //
  // A value per node at its x-dof, zero elsewhere, as a finite element
  // function of the mesh (the hanging-node constraints applied), with its
  // ghosts: what SolutionTransfer and the checkpoints read.
  template <int dim>
  template <typename NodeValue>
  VectorType
  ContactSet<dim>::x_dof_field(
    const VectorType                &layout,
    const AffineConstraints<double> &hanging_constraints,
    const NodeValue                 &value_of_node) const
  {
    VectorType field(layout);
    field = 0;
    for (unsigned int i = 0; i < size(); ++i)
      field.local_element(node(i).local_dofs[0]) = value_of_node(i);
    field.zero_out_ghost_values();
    hanging_constraints.distribute(field);
    field.update_ghost_values();
    return field;
  }



  template <int dim>
  VectorType
  ContactSet<dim>::pressure_field(
    const VectorType                &layout,
    const AffineConstraints<double> &hanging_constraints) const
  {
    return x_dof_field(layout, hanging_constraints, [this](unsigned int i) {
      return contact_pressure(i);
    });
  }



  template <int dim>
  VectorType
  ContactSet<dim>::weakening_field(
    const VectorType                &layout,
    const AffineConstraints<double> &hanging_constraints) const
  {
    return x_dof_field(layout, hanging_constraints, [this](unsigned int i) {
      return weakening_variable(i);
    });
  }



  template <int dim>
  void
  ContactSet<dim>::set_weakening_from(const VectorType &field)
  {
    for (unsigned int i = 0; i < size(); ++i)
      set_weakening_variable(i, field.local_element(node(i).local_dofs[0]));
  }



  // @sect4{ContactSet::set_state_from}
  template <int dim>
  void
  ContactSet<dim>::set_state_from(const VectorType &u,
                                  const VectorType &pressure,
                                  const bool        with_friction)
  {
    for (unsigned int i = 0; i < size(); ++i)
      {
        this->r[i] = normal_component(u, i) - gap(i);
        this->z[i] = weight(i) * pressure.local_element(node(i).local_dofs[0]);
      }
    update_pieces(with_friction);
  }



  template <int dim>
  VectorType
  ContactSet<dim>::tangential_traction_field(const VectorType &layout) const
  {
    VectorType field(layout);
    field = 0;
    for (unsigned int i = 0; i < size(); ++i)
      {
        const Tensor<1, dim> traction = tangential_vector(i, t[i]) / weight(i);
        for (unsigned int c = 0; c < dim; ++c)
          field.local_element(node(i).local_dofs[c]) = traction[c];
      }
    field.update_ghost_values();
    return field;
  }



  template <int dim>
  void
  ContactSet<dim>::set_tangential_state_from(const VectorType &u,
                                             const VectorType &traction)
  {
    s = tangential_displacements(u);
    for (unsigned int i = 0; i < size(); ++i)
      {
        Tensor<1, dim> f;
        for (unsigned int c = 0; c < dim; ++c)
          f[c] = traction.local_element(node(i).local_dofs[c]);
        for (unsigned int j = 0; j < geometry[i].n_tangents; ++j)
          t[i][j] = weight(i) * (geometry[i].tangents[j] * f);
      }
  }



  // @sect4{ContactSet::fill_output_fields}
  //
  // The nodal contact fields of the graphical output, in the layout of the
  // scalar dof handler: zero everywhere, the values of the nodes at their
  // scalar dofs, and on the opposite sides of pairs those the vertices
  // receive (OppositeSide). The caller updates the ghost entries before
  // writing.
  template <int dim>
  std::vector<std::string>
  ContactSet<dim>::output_field_names()
  {
    return {"contact_pressure",
            "compliance_pressure",
            "foundation_pressure",
            "contact_status",
            "penetration"};
  }



  template <int dim>
  void
  ContactSet<dim>::fill_output_fields(std::vector<VectorType> &fields) const
  {
    AssertDimension(fields.size(), output_field_names().size());
    for (VectorType &field : fields)
      field = 0;
    const auto set = [&fields](const types::global_dof_index dof,
                               const double                  pressure,
                               const double                  compliance,
                               const double                  status,
                               const double                  penetration) {
      fields[0](dof) = pressure;
      fields[1](dof) = compliance;
      fields[2](dof) = pressure - compliance;
      fields[3](dof) = status;
      fields[4](dof) = penetration;
    };
    if (pairs)
      for (const auto &vertex : opposite.states(*this))
        set(vertex.scalar_dof,
            vertex.contact_pressure,
            vertex.compliance_pressure,
            vertex.status,
            vertex.penetration);
    for (unsigned int i = 0; i < size(); ++i)
      set(geometry[i].scalar_dof,
          contact_pressure(i),
          compliance_pressure(i),
          status(i),
          r[i]);
  }



  template <int dim>
  void
  ContactSet<dim>::fill_memory_field(VectorType &memory_pressure) const
  {
    memory_pressure = 0;
    if (pairs)
      for (const auto &vertex : opposite.states(*this))
        memory_pressure(vertex.scalar_dof) = vertex.memory_pressure;
    for (unsigned int i = 0; i < size(); ++i)
      memory_pressure(geometry[i].scalar_dof) = history_pressure(i);
  }



  // The bonding, the worn depth and the damage of the contact nodes (the
  // contact side of a pair only: the opposite side has no variables of its
  // own).
  template <int dim>
  void
  ContactSet<dim>::fill_history_fields(VectorType &bonding_field,
                                       VectorType &wear_field,
                                       VectorType &damage_field) const
  {
    for (VectorType *field : {&bonding_field, &wear_field, &damage_field})
      if (field->size() > 0)
        *field = 0;
    for (unsigned int i = 0; i < size(); ++i)
      {
        if (bonding_field.size() > 0)
          bonding_field(geometry[i].scalar_dof) = bonding(i);
        if (wear_field.size() > 0)
          wear_field(geometry[i].scalar_dof) = this->wear(i);
        if (damage_field.size() > 0)
          damage_field(geometry[i].scalar_dof) = damage(i);
      }
  }



  template <int dim>
  void
  ContactSet<dim>::fill_friction_fields(VectorType &tangential_traction,
                                        VectorType &slip,
                                        VectorType &friction_state_field) const
  {
    for (VectorType *field :
         {&tangential_traction, &slip, &friction_state_field})
      *field = 0;
    const auto set = [&](const std::array<unsigned int, dim> &local_dofs,
                         const types::global_dof_index        scalar_dof,
                         const Tensor<1, dim>                &traction,
                         const Tensor<1, dim>                &step,
                         const unsigned int                   state) {
      for (unsigned int c = 0; c < dim; ++c)
        {
          tangential_traction.local_element(local_dofs[c]) = traction[c];
          slip.local_element(local_dofs[c])                = step[c];
        }
      friction_state_field(scalar_dof) = state;
    };
    if (pairs)
      for (const auto &vertex : opposite.states(*this))
        set(vertex.local_dofs,
            vertex.scalar_dof,
            vertex.tangential_traction,
            vertex.slip,
            vertex.friction_state);
    for (unsigned int i = 0; i < size(); ++i)
      set(geometry[i].local_dofs,
          geometry[i].scalar_dof,
          tangential_vector(i, t[i]) / weight(i),
          output_slip(i),
          friction_state(i));
  }



  // @sect4{ContactSet::frame_row, node_component and add_to_node}
  //
  // The rows of a node's frame directions on its own dofs, and the two
  // operations that connect them to the displacement vectors (on the owned
  // entries; no communication), for the full space back end.
  template <int dim>
  Tensor<1, dim>
  ContactSet<dim>::frame_row(const unsigned int           i,
                             const std::array<double, 3> &a) const
  {
    Tensor<1, dim> row = a[0] * geometry[i].normal;
    for (unsigned int j = 0; j < geometry[i].n_tangents; ++j)
      row += a[1 + j] * geometry[i].tangent_rows[j];
    return row;
  }



  template <int dim>
  double
  ContactSet<dim>::node_component(const VectorType     &u,
                                  const unsigned int    i,
                                  const Tensor<1, dim> &row) const
  {
    double value = 0;
    for (unsigned int c = 0; c < dim; ++c)
      value += row[c] * u.local_element(geometry[i].local_dofs[c]);
    return value;
  }



  template <int dim>
  void
  ContactSet<dim>::add_to_node(VectorType           &v,
                               const unsigned int    i,
                               const Tensor<1, dim> &row,
                               const double          value) const
  {
    for (unsigned int c = 0; c < dim; ++c)
      v.local_element(geometry[i].local_dofs[c]) += value * row[c];
  }



  // The slip of the last step as the output shows it: zero at a free node
  // (out of contact under Coulomb's law), whose tangential motion is no
  // slip against the obstacle.
  template <int dim>
  Tensor<1, dim>
  ContactSet<dim>::output_slip(const unsigned int i) const
  {
    if (friction_state(i) == free_tangential)
      return Tensor<1, dim>();
    return tangential_vector(i, step_slip(i));
  }



  // @sect4{ContactSet: tangential quantities}
  template <int dim>
  std::vector<ContactNodes::Tangential>
  ContactSet<dim>::tangential_displacements(const VectorType &u) const
  {
    std::vector<Tangential> result(size(), Tangential{{0, 0}});
    for (unsigned int i = 0; i < size(); ++i)
      for (unsigned int j = 0; j < geometry[i].n_tangents; ++j)
        result[i][j] = row_component(u, i, 1 + j);
    return result;
  }



  template <int dim>
  void
  ContactSet<dim>::set_obstacle_steps(
    const std::vector<ObstacleStep<dim>> &zone_steps)
  {
    std::vector<Tangential> steps(size(), Tangential{{0, 0}});
    for (unsigned int i = 0; i < size(); ++i)
      {
        const Tensor<1, dim> step
          = zone_steps[zone(i)].at(geometry[i].location);
        for (unsigned int j = 0; j < geometry[i].n_tangents; ++j)
          steps[i][j] = geometry[i].tangents[j] * step;
      }
    set_obstacle_slip(steps);
  }



  template <int dim>
  Tensor<1, dim>
  ContactSet<dim>::tangential_vector(const unsigned int i,
                                     const Tangential  &x) const
  {
    Tensor<1, dim> vector;
    for (unsigned int j = 0; j < geometry[i].n_tangents; ++j)
      vector += x[j] * geometry[i].tangents[j];
    return vector;
  }



  template <int dim>
  std::vector<Tensor<1, dim>>
  ContactSet<dim>::zone_tangential_forces(const MPI_Comm communicator) const
  {
    std::vector<double> sums(laws().n_zones() * dim, 0.);
    for (unsigned int i = 0; i < size(); ++i)
      {
        const Tensor<1, dim> force = tangential_vector(i, t[i]);
        for (unsigned int c = 0; c < dim; ++c)
          sums[zone(i) * dim + c] += force[c];
      }
    const std::vector<double> local = sums;
    Utilities::MPI::sum(ArrayView<const double>(local.data(), local.size()),
                        communicator,
                        ArrayView<double>(sums.data(), sums.size()));
    std::vector<Tensor<1, dim>> forces(laws().n_zones());
    for (unsigned int zone = 0; zone < forces.size(); ++zone)
      for (unsigned int c = 0; c < dim; ++c)
        forces[zone][c] = sums[zone * dim + c];
    return forces;
  }



  template <int dim>
  std::vector<std::array<Tensor<1, dim>, 2>>
  ContactSet<dim>::zone_side_forces(const MPI_Comm communicator) const
  {
    std::vector<double> sums(laws().n_zones() * 2 * dim, 0.);
    for (unsigned int i = 0; i < size(); ++i)
      {
        const NodeGeometry &node = geometry[i];
        // The force of node i on the other side, in space.
        Tensor<1, dim> force = z[i] * node.direction;
        if (node.n_tangents > 0)
          force += tangential_vector(i, t[i]);
        double *zone_sums = &sums[zone(i) * 2 * dim];
        for (unsigned int c = 0; c < dim; ++c)
          zone_sums[c] -= force[c];
        for (const auto &entry : node.opposite)
          zone_sums[dim + entry.component]
            += entry.coefficient * force[entry.component];
      }
    const std::vector<double> local = sums;
    Utilities::MPI::sum(ArrayView<const double>(local.data(), local.size()),
                        communicator,
                        ArrayView<double>(sums.data(), sums.size()));
    std::vector<std::array<Tensor<1, dim>, 2>> forces(laws().n_zones());
    for (unsigned int zone = 0; zone < forces.size(); ++zone)
      for (unsigned int side = 0; side < 2; ++side)
        for (unsigned int c = 0; c < dim; ++c)
          forces[zone][side][c] = sums[(zone * 2 + side) * dim + c];
    return forces;
  }



  // The instantiations for 2D and 3D.
  template void
  assemble_lumped_weights(const hp::MappingCollection<2> &,
                          const DoFHandler<2> &,
                          const hp::QCollection<1> &,
                          const std::vector<types::boundary_id> &,
                          VectorType &,
                          VectorType &);
  template void
  assemble_lumped_weights(const hp::MappingCollection<3> &,
                          const DoFHandler<3> &,
                          const hp::QCollection<2> &,
                          const std::vector<types::boundary_id> &,
                          VectorType &,
                          VectorType &);
  // @sect4{ContactSet::set_gaps}
  //
  // The gap of every node at its location, at the given time.
  template <int dim>
  std::string
  ContactSet<dim>::set_gaps(const std::vector<Function<dim> *> &zone_gaps,
                            const double                        time)
  {
    AssertDimension(zone_gaps.size(), zone_subsections.size());
    for (Function<dim> *gap_function : zone_gaps)
      if (gap_function != nullptr)
        gap_function->set_time(time);
    gaps.resize(geometry.size());
    for (unsigned int i = 0; i < geometry.size(); ++i)
      {
        Function<dim> *gap_function = zone_gaps[zone(i)];
        gaps[i] = gap_function ? gap_function->value(geometry[i].location) : 0.;
        if (!std::isfinite(gaps[i]))
          {
            std::ostringstream message;
            message << "Invalid parameter <Initial gap> in subsection <"
                    << zone_subsections[zone(i)]
                    << ">: the gap is not finite at the contact node ("
                    << geometry[i].location << ") at t = " << time
                    << "; accepted: expressions with a finite value at every "
                       "contact node and every time of the run.";
            return message.str();
          }
      }
    return "";
  }



  template <int dim>
  double
  ContactSet<dim>::gap(const unsigned int i) const
  {
    return (gaps.empty() ? 0. : gaps[i]) + geometry[i].opposite_gap
           + this->wear(i);
  }



  // @sect4{ContactSet::set_slip_bounds}
  //
  // g_i = w_i g(x_i) at the nodes of the Tresca zones: the bound is a
  // traction, the node's share of it a force.
  template <int dim>
  std::string
  ContactSet<dim>::set_slip_bounds(
    const std::vector<const Function<dim> *> &zone_bounds)
  {
    AssertDimension(zone_bounds.size(), zone_subsections.size());
    std::vector<double>       bounds(size(), 0.);
    std::vector<unsigned int> tangents(size());
    for (unsigned int i = 0; i < size(); ++i)
      {
        tangents[i]                = geometry[i].n_tangents;
        const Function<dim> *bound = zone_bounds[zone(i)];
        if (bound == nullptr || !zone_friction[zone(i)]->uses_node_bounds())
          continue;
        const double value = bound->value(geometry[i].location);
        if (!(value >= 0) || !std::isfinite(value))
          {
            std::ostringstream message;
            message << "Invalid parameter <Slip bound> in subsection <"
                    << zone_subsections[zone(i)] << ">: the bound is " << value
                    << " at the contact node (" << geometry[i].location
                    << "); accepted: expressions with a finite value >= 0 at "
                       "every contact node.";
            return message.str();
          }
        bounds[i] = weight(i) * value;
      }
    set_friction(zone_friction, tangents, bounds);
    return "";
  }



  template class ContactSet<2>;
  template class ContactSet<3>;
} // namespace ViscoContact
