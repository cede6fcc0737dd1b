// Contact pairs: the mortar coupling of a zone's nodes to the opposite side
// (contact_pairs.h), in parallel.

#include <deal.II/base/bounding_box.h>
#include <deal.II/base/mpi.h>

#include "contact_pairs/contact_pairs.h"
#include "contact_pairs/mortar.h"
#include "robustness/file_output.h"
#include "robustness/mpi_tools.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <sstream>

namespace ViscoContact
{
  namespace
  {
    std::string
    pair_problem(const std::string &subsection, const std::string &what)
    {
      return "Invalid parameter <Opposite boundary ids> in subsection <"
             + subsection + ">: " + what;
    }

    // A vertex of the opposite side as it travels between ranks: its
    // location, its x-dof (which names it), and each component's dof
    // expanded through its constraint, (dof, weight) pairs.
    template <int dim>
    struct MasterVertex
    {
      Point<dim>              location;
      types::global_dof_index x_dof;
      std::array<std::vector<std::pair<types::global_dof_index, double>>, dim>
        components;
    };
    template <int dim>
    using MasterFace = std::vector<MasterVertex<dim>>;

    // The vertices of face f of cell in the order of Mortar::Side: in 2D
    // the tangent turned clockwise, in 3D the normal of the cyclic order
    // (0, 1, 2) or (0, 1, 3, 2) by the right hand, points out of the cell.
    template <int dim>
    std::vector<unsigned int>
    outward_order(const typename DoFHandler<dim>::active_cell_iterator &cell,
                  const unsigned int                                    f)
    {
      const auto                face = cell->face(f);
      std::vector<unsigned int> order{0, 1};
      Tensor<1, dim>            normal;
      if constexpr (dim == 2)
        {
          const Tensor<1, 2> t = face->vertex(1) - face->vertex(0);
          normal               = Tensor<1, 2>({t[1], -t[0]});
        }
      else
        {
          order = face->n_vertices() == 3
                    ? std::vector<unsigned int>{0, 1, 2}
                    : std::vector<unsigned int>{0, 1, 3, 2};
          normal
            = cross_product_3d(face->vertex(order[1]) - face->vertex(order[0]),
                               face->vertex(order[2]) - face->vertex(order[0]));
        }
      if (normal * (face->center() - cell->center()) < 0)
        std::reverse(order.begin(), order.end());
      return order;
    }

    // Doubles in and out of a message: the number of vertices, locations,
    // dof numbers (exact below 2^53) and weights.
    template <int dim>
    void
    pack(const MasterFace<dim> &face, std::vector<double> &message)
    {
      message.push_back(face.size());
      for (const MasterVertex<dim> &vertex : face)
        {
          for (unsigned int d = 0; d < dim; ++d)
            message.push_back(vertex.location[d]);
          message.push_back(double(vertex.x_dof));
          for (const auto &entries : vertex.components)
            {
              message.push_back(entries.size());
              for (const auto &[dof, weight] : entries)
                message.insert(message.end(), {double(dof), weight});
            }
        }
    }

    template <int dim>
    std::vector<MasterFace<dim>>
    unpack(const std::vector<double> &message)
    {
      std::vector<MasterFace<dim>> faces;
      std::size_t                  k = 0;
      while (k < message.size())
        {
          MasterFace<dim> face(static_cast<std::size_t>(message[k++]));
          for (MasterVertex<dim> &vertex : face)
            {
              for (unsigned int d = 0; d < dim; ++d)
                vertex.location[d] = message[k++];
              vertex.x_dof = types::global_dof_index(message[k++]);
              for (auto &entries : vertex.components)
                {
                  const std::size_t n = message[k++];
                  for (std::size_t e = 0; e < n; ++e, k += 2)
                    entries.emplace_back(types::global_dof_index(message[k]),
                                         message[k + 1]);
                }
            }
          faces.push_back(std::move(face));
        }
      return faces;
    }

    // The pieces of one pair zone on this rank: the zone's faces around its
    // nodes (own and ghost cells), the opposite faces of its own cells, and
    // the longest face (diameter in 3D) of both among its own cells.
    template <int dim>
    struct ZoneFaces
    {
      Mortar::Side<dim>                               slave;
      std::map<types::global_dof_index, unsigned int> slave_vertex_of_dof;
      std::vector<MasterFace<dim>>                    own_master_faces;
      double                                          longest_face = 0;
    };

    template <int dim>
    ZoneFaces<dim>
    collect_faces(const ContactZoneDescription<dim> &zone,
                  const DoFHandler<dim>             &dof_handler,
                  const AffineConstraints<double>   &constraints)
    {
      ZoneFaces<dim> faces;
      for (const auto &cell : dof_handler.active_cell_iterators())
        if (!cell->is_artificial())
          for (const unsigned int f : cell->face_indices())
            {
              if (!cell->face(f)->at_boundary())
                continue;
              const types::boundary_id id    = cell->face(f)->boundary_id();
              const bool               slave = is_one_of(id, zone.boundary_ids);
              if (!slave
                  && !(cell->is_locally_owned()
                       && is_one_of(id, zone.opposite_ids)))
                continue;
              const std::vector<unsigned int> order
                = outward_order<dim>(cell, f);
              if (cell->is_locally_owned())
                faces.longest_face
                  = std::max(faces.longest_face, cell->face(f)->diameter());
              if (slave)
                {
                  std::vector<unsigned int> vertices;
                  for (const unsigned int v : order)
                    {
                      const auto [it, inserted]
                        = faces.slave_vertex_of_dof.emplace(
                          cell->face(f)
                            ->vertex_dof_index(v, 0, cell->active_fe_index()),
                          faces.slave.vertices.size());
                      if (inserted)
                        faces.slave.vertices.push_back(
                          cell->face(f)->vertex(v));
                      vertices.push_back(it->second);
                    }
                  faces.slave.faces.push_back(vertices);
                }
              else
                {
                  MasterFace<dim> face(order.size());
                  for (unsigned int n = 0; n < order.size(); ++n)
                    {
                      const unsigned int v = order[n];
                      face[n].location     = cell->face(f)->vertex(v);
                      face[n].x_dof
                        = cell->face(f)
                            ->vertex_dof_index(v, 0, cell->active_fe_index());
                      for (unsigned int c = 0; c < dim; ++c)
                        {
                          const types::global_dof_index dof
                            = cell->face(f)->vertex_dof_index(
                              v,
                              c,
                              cell->active_fe_index());
                          if (!constraints.is_constrained(dof))
                            face[n].components[c] = {{dof, 1.}};
                          else if (const auto *entries
                                   = constraints.get_constraint_entries(dof))
                            face[n].components[c] = *entries;
                        }
                    }
                  faces.own_master_faces.push_back(face);
                }
            }
      return faces;
    }

    // The opposite faces near this rank's part of the zone: each rank's own
    // opposite faces go to every rank whose zone faces, widened by the
    // search distance, they meet.
    template <int dim>
    std::vector<MasterFace<dim>>
    exchange_master_faces(const ZoneFaces<dim> &faces,
                          const double          search_distance,
                          const MPI_Comm        communicator)
    {
      // This rank's box: lower and upper corner, or empty (lower > upper).
      std::vector<double> box(2 * dim, 0.);
      for (unsigned int d = 0; d < dim; ++d)
        box[d] = 1;
      if (!faces.slave.vertices.empty())
        {
          const BoundingBox<dim> slave_box(faces.slave.vertices);
          for (unsigned int d = 0; d < dim; ++d)
            {
              box[d]
                = slave_box.get_boundary_points().first[d] - search_distance;
              box[dim + d]
                = slave_box.get_boundary_points().second[d] + search_distance;
            }
        }
      const std::vector<std::vector<double>> boxes
        = Utilities::MPI::all_gather(communicator, box);
      const unsigned int my_rank
        = Utilities::MPI::this_mpi_process(communicator);
      std::map<unsigned int, std::vector<double>> messages;
      std::vector<MasterFace<dim>>                near;
      for (const MasterFace<dim> &face : faces.own_master_faces)
        for (unsigned int rank = 0; rank < boxes.size(); ++rank)
          {
            const std::vector<double> &b     = boxes[rank];
            bool                       meets = true;
            for (unsigned int d = 0; d < dim && meets; ++d)
              {
                double low  = std::numeric_limits<double>::max(),
                       high = std::numeric_limits<double>::lowest();
                for (const MasterVertex<dim> &vertex : face)
                  {
                    low  = std::min(low, vertex.location[d]);
                    high = std::max(high, vertex.location[d]);
                  }
                meets = b[d] <= b[dim + d] && high >= b[d] && low <= b[dim + d];
              }
            if (!meets)
              continue;
            if (rank == my_rank)
              near.push_back(face);
            else
              pack(face, messages[rank]);
          }
      for (const auto &[rank, message] :
           Utilities::MPI::some_to_some(communicator, messages))
        {
          const std::vector<MasterFace<dim>> received = unpack<dim>(message);
          near.insert(near.end(), received.begin(), received.end());
        }
      return near;
    }
  } // namespace



  // @sect4{ContactPairs::reinit}
  template <int dim>
  void
  ContactPairs<dim>::reinit(
    const std::vector<ContactZoneDescription<dim>> &zones,
    const DoFHandler<dim>                          &dof_handler,
    const AffineConstraints<double>                &constraints,
    const MPI_Comm                                  communicator)
  {
    couplings.clear();
    zone_is_pair.assign(zones.size(), false);
    zone_measures_gap.clear();
    for (const auto &zone : zones)
      zone_measures_gap.push_back(zone.measured_gap);
    ghosts = IndexSet(dof_handler.n_dofs());
    for (unsigned int z = 0; z < zones.size(); ++z)
      {
        zone_is_pair[z] = !zones[z].opposite_ids.empty();
        if (!zone_is_pair[z])
          continue;
        const ZoneFaces<dim> faces
          = collect_faces(zones[z], dof_handler, constraints);
        const double search_distance
          = zones[z].search_distance > 0
              ? zones[z].search_distance
              : Utilities::MPI::max(faces.longest_face, communicator);
        const std::vector<MasterFace<dim>> near
          = exchange_master_faces(faces, search_distance, communicator);

        // The opposite side near this rank, each vertex once.
        Mortar::Side<dim>                               master;
        std::vector<const MasterVertex<dim> *>          master_vertices;
        std::map<types::global_dof_index, unsigned int> vertex_of_dof;
        std::string                                     problem;
        for (const MasterFace<dim> &face : near)
          {
            std::vector<unsigned int> vertices;
            for (unsigned int n = 0; n < face.size(); ++n)
              {
                const auto [it, inserted]
                  = vertex_of_dof.emplace(face[n].x_dof,
                                          master.vertices.size());
                if (inserted)
                  {
                    master.vertices.push_back(face[n].location);
                    master_vertices.push_back(&face[n]);
                  }
                vertices.push_back(it->second);
                if (problem.empty()
                    && faces.slave_vertex_of_dof.count(face[n].x_dof) == 1)
                  {
                    std::ostringstream message;
                    message << "the opposite side shares the node at ("
                            << face[n].location
                            << ") with the zone; accepted: boundary "
                               "parts of another body, which share no "
                               "node with the zone (a Gmsh mesh whose "
                               "bodies are separate components).";
                    problem = pair_problem(zones[z].subsection, message.str());
                  }
              }
            master.faces.push_back(vertices);
          }
        FileOutput::agree_on_problem(problem, communicator);

        // The coupling of the nodes this rank owns. The mortar refuses
        // faces it cannot integrate on (collapsed, or too warped seen along
        // the other side's normal); the ranks where that happens stop
        // every rank with the entry named, rather than leave the others
        // waiting in the collective calls below.
        Mortar::Coupling<dim>    coupling;
        const Mortar::Side<dim> &slave   = faces.slave;
        std::string              failure = MPITools::failure_of(
          [&]() { coupling = Mortar::couple(slave, master, search_distance); });
        if (!failure.empty())
          {
            const auto first = failure.find_first_not_of(" \n");
            const auto last  = failure.find_last_not_of(" \n");
            failure          = pair_problem(
              zones[z].subsection,
              "the mortar coupling of the zone with the opposite side "
                       "failed: "
                + failure.substr(first, last - first + 1)
                + " Accepted: boundary parts whose faces are not collapsed "
                           "and nearly planar.");
          }
        FileOutput::agree_on_problem(failure, communicator);
        const IndexSet &owned   = dof_handler.locally_owned_dofs();
        unsigned int    covered = 0;
        for (const auto &[x_dof, j] : faces.slave_vertex_of_dof)
          {
            AssertThrow(std::isfinite(coupling.D[j]), ExcInternalError());
            if (!owned.is_element(x_dof) || !(coupling.D[j] > 0))
              continue;
            ++covered;
            NodeCoupling &node = couplings[{z, x_dof}];
            node.weight        = coupling.D[j];
            for (const auto &[k, M] : coupling.M[j])
              {
                const double coefficient = M / coupling.D[j];
                node.opposite_point += coefficient * master.vertices[k];
                node.vertices.emplace_back(master_vertices[k]->x_dof,
                                           coefficient);
                if (!owned.is_element(master_vertices[k]->x_dof))
                  ghosts.add_index(master_vertices[k]->x_dof);
                for (unsigned int c = 0; c < dim; ++c)
                  for (const auto &[dof, weight] :
                       master_vertices[k]->components[c])
                    {
                      node.entries.emplace_back(dof, c, coefficient * weight);
                      if (!owned.is_element(dof))
                        ghosts.add_index(dof);
                    }
              }
          }
        if (Utilities::MPI::sum(covered, communicator) == 0)
          {
            // Refused: how far the nearest facing face lies, from all
            // of the opposite side (gathered on this path only).
            const double      unlimited = std::numeric_limits<double>::max();
            Mortar::Side<dim> everything;
            for (const MasterFace<dim> &face :
                 exchange_master_faces(faces, unlimited, communicator))
              {
                everything.faces.emplace_back();
                for (const MasterVertex<dim> &vertex : face)
                  {
                    everything.faces.back().push_back(
                      everything.vertices.size());
                    everything.vertices.push_back(vertex.location);
                  }
              }
            // (A face the mortar cannot integrate on counts as none here,
            // on the ranks that meet it, so that all reach the minimum.)
            double nearest = std::numeric_limits<double>::infinity();
            const Mortar::Side<dim> &zone_side = faces.slave;
            MPITools::failure_of([&]() {
              nearest = Mortar::couple(zone_side, everything).closest_distance;
            });
            const double closest = Utilities::MPI::min(nearest, communicator);
            std::ostringstream message;
            message << "no node of the zone has a face of the opposite "
                       "side within the Search distance "
                    << search_distance << " along its normal (";
            if (std::isfinite(closest))
              message << "the nearest facing one lies " << closest
                      << " from the zone";
            else
              message << "no face of the opposite side faces the zone";
            message << "); accepted: ids of boundary parts that face "
                       "the zone within the Search distance.";
            AssertThrow(false,
                        ExcMessage(
                          pair_problem(zones[z].subsection, message.str())));
          }
      }
    ghosts.compress();
  }



  template <int dim>
  const IndexSet &
  ContactPairs<dim>::ghost_dofs() const
  {
    return ghosts;
  }



  // @sect4{ContactPairs::couple_nodes}
  template <int dim>
  void
  ContactPairs<dim>::couple_nodes(
    std::vector<typename ContactSet<dim>::NodeGeometry> &nodes,
    std::vector<double>                                 &weights,
    const Utilities::MPI::Partitioner                   &partitioner) const
  {
    unsigned int kept = 0;
    for (unsigned int i = 0; i < nodes.size(); ++i)
      {
        auto      &node     = nodes[i];
        const auto coupling = couplings.find({node.zone, node.dofs[0]});
        if (zone_is_pair[node.zone] && coupling == couplings.end())
          continue; // not covered by the opposite side
        if (coupling != couplings.end())
          {
            weights[i] = coupling->second.weight;
            node.opposite.clear();
            for (const auto &[dof, component, coefficient] :
                 coupling->second.entries)
              node.opposite.push_back(
                {dof,
                 static_cast<unsigned int>(partitioner.global_to_local(dof)),
                 component,
                 coefficient});
            node.opposite_vertices.clear();
            for (const auto &[x_dof, coefficient] : coupling->second.vertices)
              node.opposite_vertices.push_back(
                {static_cast<unsigned int>(partitioner.global_to_local(x_dof)),
                 coefficient});
            node.opposite_gap
              = zone_measures_gap[node.zone]
                  ? node.direction
                      * (coupling->second.opposite_point - node.location)
                  : 0.;
          }
        if (kept != i)
          {
            nodes[kept]   = std::move(nodes[i]);
            weights[kept] = weights[i];
          }
        ++kept;
      }
    nodes.resize(kept);
    weights.resize(kept);
  }



  template class ContactPairs<2>;
  template class ContactPairs<3>;
} // namespace ViscoContact
