// The output fields of the opposite side of a contact pair
// (opposite_side.h).

#include "contact_pairs/opposite_side.h"
#include "contact_set.h"

#include <algorithm>
#include <iomanip>
#include <set>
#include <sstream>

namespace ViscoContact
{
  // @sect4{OppositeSide::setup}
  //
  // The lumped weights and weighted normals of the opposite sides, as those
  // of the zones in ContactSet::setup(), and the owned vertices that carry
  // a weight.
  template <int dim>
  void
  OppositeSide<dim>::setup(
    const std::vector<ContactZoneDescription<dim>> &zones,
    const hp::MappingCollection<dim>               &mapping,
    const DoFHandler<dim>                          &dof_handler,
    const DoFHandler<dim>                          &scalar_dof_handler,
    const hp::QCollection<dim - 1>                 &face_quadrature,
    const AffineConstraints<double>                &hanging_constraints,
    const VectorType                               &layout)
  {
    vertices.clear();
    partitioner = layout.get_partitioner();
    std::vector<types::boundary_id> opposite_ids;
    for (const ContactZoneDescription<dim> &zone : zones)
      opposite_ids.insert(opposite_ids.end(),
                          zone.opposite_ids.begin(),
                          zone.opposite_ids.end());
    if (opposite_ids.empty())
      return;
    VectorType weights(layout), weighted_normals(layout);
    assemble_lumped_weights(mapping,
                            dof_handler,
                            face_quadrature,
                            opposite_ids,
                            weights,
                            weighted_normals);
    for (VectorType *vector : {&weights, &weighted_normals})
      pass_on_hanging_values(*vector, hanging_constraints, layout);
    std::set<types::global_dof_index> seen;
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
        for (const unsigned int f : cell->face_indices())
          if (cell->face(f)->at_boundary()
              && is_one_of(cell->face(f)->boundary_id(), opposite_ids))
            for (const unsigned int v : cell->face(f)->vertex_indices())
              {
                const types::global_dof_index x_dof
                  = cell->face(f)->vertex_dof_index(v,
                                                    0,
                                                    cell->active_fe_index());
                if (!partitioner->in_local_range(x_dof) || weights(x_dof) <= 0
                    || !seen.insert(x_dof).second)
                  continue;
                Vertex vertex;
                vertex.location = cell->face(f)->vertex(v);
                vertex.weight   = weights(x_dof);
                for (unsigned int c = 0; c < dim; ++c)
                  {
                    const types::global_dof_index dof
                      = cell->face(f)
                          ->vertex_dof_index(v, c, cell->active_fe_index());
                    vertex.local_dofs[c] = partitioner->global_to_local(dof);
                    vertex.normal[c]     = weighted_normals(dof);
                  }
                if (vertex.normal.norm() == 0)
                  continue;
                vertex.normal /= vertex.normal.norm();
                const typename DoFHandler<dim>::active_cell_iterator
                  scalar_cell(&dof_handler.get_triangulation(),
                              cell->level(),
                              cell->index(),
                              &scalar_dof_handler);
                vertex.scalar_dof
                  = scalar_cell->face(f)
                      ->vertex_dof_index(v, 0, scalar_cell->active_fe_index());
                vertices.push_back(vertex);
              }
    std::sort(vertices.begin(),
              vertices.end(),
              [](const Vertex &a, const Vertex &b) {
                return precedes_in_profile(a.location, b.location);
              });
  }



  // @sect4{OppositeSide::states}
  //
  // The forces sum over the entries (j, k, c) of the zone's rows, entry
  // coefficient c_jk of component c of the opposite side's dof k (through
  // the constraints of k: the force on the free dofs); the states over the
  // opposite vertices of each node, at each vertex's x-dof, with the
  // weights D_j c_jk = M_jk (so that a vertex whose components are
  // constrained, on an oblique plane of symmetry, is averaged as any
  // other). Each rank adds its own nodes' terms, the owners of the dofs
  // receive the sums (compress(add)). The states of the node with the
  // largest weight take two passes: the largest weight per vertex first
  // (compress(max)), then the states of the nodes that reach it.
  template <int dim>
  std::vector<typename OppositeSide<dim>::VertexState>
  OppositeSide<dim>::states(const ContactSet<dim> &contact) const
  {
    std::vector<VertexState> result(vertices.size());
    for (unsigned int k = 0; k < vertices.size(); ++k)
      {
        result[k].location   = vertices[k].location;
        result[k].local_dofs = vertices[k].local_dofs;
        result[k].scalar_dof = vertices[k].scalar_dof;
        result[k].weight     = vertices[k].weight;
      }
    if (!partitioner)
      return result;
    VectorType force(partitioner), layer_force(partitioner),
      mortar_weight(partitioner), penetration(partitioner),
      memory_pressure(partitioner), largest_weight(partitioner),
      dominant_state(partitioner);
    std::vector<VectorType> slip(dim, VectorType(partitioner));
    const bool              friction = contact.has_friction();
    for (unsigned int j = 0; j < contact.size(); ++j)
      {
        const auto    &node       = contact.node(j);
        Tensor<1, dim> node_force = contact.z[j] * node.direction;
        if (node.n_tangents > 0)
          node_force += contact.tangential_vector(j, contact.t[j]);
        const Tensor<1, dim> node_layer_force
          = contact.compliance_pressure(j) * contact.weight(j) * node.direction;
        for (const auto &entry : node.opposite)
          {
            force.local_element(entry.local_dof)
              += entry.coefficient * node_force[entry.component];
            layer_force.local_element(entry.local_dof)
              += entry.coefficient * node_layer_force[entry.component];
          }
        const Tensor<1, dim> node_slip = contact.output_slip(j);
        for (const auto &share : node.opposite_vertices)
          {
            const unsigned int k    = share.x_local_dof;
            const double       M_jk = contact.weight(j) * share.coefficient;
            mortar_weight.local_element(k) += M_jk;
            penetration.local_element(k) += M_jk * contact.r[j];
            memory_pressure.local_element(k)
              += M_jk * contact.history_pressure(j);
            for (unsigned int c = 0; c < dim; ++c)
              slip[c].local_element(k) += M_jk * node_slip[c];
            double &largest = largest_weight.local_element(k);
            largest         = std::max(largest, M_jk);
          }
      }
    for (VectorType *sum :
         {&force, &layer_force, &mortar_weight, &penetration, &memory_pressure})
      sum->compress(VectorOperation::add);
    for (VectorType &sum : slip)
      sum.compress(VectorOperation::add);
    largest_weight.compress(VectorOperation::max);
    largest_weight.update_ghost_values();
    // The states of a node as one number (1 + status + 3 friction state +
    // 9 zone, zero where no node reaches the largest weight).
    for (unsigned int j = 0; j < contact.size(); ++j)
      {
        const double code
          = 1 + contact.status(j)
            + 3.
                * (friction
                     ? static_cast<unsigned int>(contact.friction_state(j))
                     : 0u)
            + 9 * contact.zone(j);
        for (const auto &share : contact.node(j).opposite_vertices)
          {
            const unsigned int k = share.x_local_dof;
            if (contact.weight(j) * share.coefficient
                >= largest_weight.local_element(k))
              dominant_state.local_element(k)
                = std::max(dominant_state.local_element(k), code);
          }
      }
    dominant_state.compress(VectorOperation::max);

    for (unsigned int k = 0; k < vertices.size(); ++k)
      {
        const Vertex      &vertex = vertices[k];
        VertexState       &state  = result[k];
        const unsigned int x_dof  = vertex.local_dofs[0];
        Tensor<1, dim>     vertex_force, vertex_layer_force;
        for (unsigned int c = 0; c < dim; ++c)
          {
            vertex_force[c] = force.local_element(vertex.local_dofs[c]);
            vertex_layer_force[c]
              = layer_force.local_element(vertex.local_dofs[c]);
          }
        const double covered_weight = mortar_weight.local_element(x_dof);
        // A vertex that the zone covers on a sliver only (round-off of the
        // clipping) keeps zero.
        state.covered = covered_weight > 1e-9 * vertex.weight;
        if (!state.covered)
          continue;
        // This side's slip relative to the zone, the zone's reversed.
        for (unsigned int c = 0; c < dim; ++c)
          state.slip[c] = 0. - slip[c].local_element(x_dof) / covered_weight;
        // The force the zone exerts on the vertex; minus its normal part
        // is the pressure on this side.
        // (0. - x: no negative zeros in the profile.)
        state.normal_force     = 0. - vertex_force * vertex.normal;
        state.contact_pressure = state.normal_force / vertex.weight;
        state.compliance_pressure
          = 0. - vertex_layer_force * vertex.normal / vertex.weight;
        state.penetration = penetration.local_element(x_dof) / covered_weight;
        state.memory_pressure
          = memory_pressure.local_element(x_dof) / covered_weight;
        // The tangential traction as on the zone: the one this body exerts
        // on the other, per unit area.
        state.tangential_traction
          = Tensor<1, dim>()
            - (vertex_force - (vertex_force * vertex.normal) * vertex.normal)
                / vertex.weight;
        if (const double code = dominant_state.local_element(x_dof); code > 0)
          {
            const unsigned int states = static_cast<unsigned int>(code) - 1;
            state.status              = states % 3;
            state.friction_state      = (states / 3) % 3;
            state.zone                = states / 9;
          }
      }
    return result;
  }



  // @sect4{OppositeSide::profile_text}
  template <int dim>
  std::string
  OppositeSide<dim>::profile_text(const std::vector<VertexState> &states,
                                  const ContactSet<dim>          &contact,
                                  const double                    time)
  {
    const bool         friction = contact.has_friction();
    const bool         zones    = contact.laws().n_zones() > 1;
    std::ostringstream out;
    out << std::setprecision(10);
    out << contact.profile_header(/*opposite_side=*/true);
    for (const VertexState &state : states)
      if (state.covered)
        {
          for (unsigned int d = 0; d < dim; ++d)
            out << state.location[d] << ',';
          out << time << ',' << state.penetration << ','
              << state.compliance_pressure << ','
              << state.contact_pressure - state.compliance_pressure << ','
              << state.contact_pressure << ',' << state.normal_force << ','
              << state.weight << ',' << state.status;
          if (zones)
            out << ',' << contact.zone_number(state.zone);
          if (friction)
            {
              out << ',' << state.friction_state;
              for (unsigned int d = 0; d < dim; ++d)
                out << ',' << state.tangential_traction[d];
              for (unsigned int d = 0; d < dim; ++d)
                out << ',' << state.slip[d];
            }
          if (contact.has_memory())
            out << ',' << state.memory_pressure;
          out << '\n';
        }
    return out.str();
  }



  template class OppositeSide<2>;
  template class OppositeSide<3>;
} // namespace ViscoContact
