// PrescribedDisplacements<dim>: the Dirichlet parts and planes of symmetry
// per mesh and per step, and the forces they exert on the body
// (prescribed_displacements.h).

#include <deal.II/base/exceptions.h>
#include <deal.II/base/mpi.h>

#include <deal.II/dofs/dof_tools.h>

#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/vector.h>

#include "constraints.h"
#include "scene/prescribed_displacements.h"
#include "rigid_motions.h"
#include "robustness/file_output.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>
#include <sstream>

namespace ViscoContact
{
  template <int dim>
  PrescribedDisplacements<dim>::PrescribedDisplacements(
    const Parameters::AllParameters &parameters,
    const MPI_Comm                   communicator)
    : communicator(communicator)
    , dirichlet(parameters)
    , symmetry_ids(parameters.symmetry_ids)
  {}



  // The Dirichlet parts get u_c = 0 here, which is homogeneous, so the same
  // constraints serve every displacement and every right-hand side of the
  // run; the prescribed values enter each step as a lifting (set_time()).
  template <int dim>
  void
  PrescribedDisplacements<dim>::make_constraints(
    const hp::MappingCollection<dim> &mapping,
    const DoFHandler<dim>            &dof_handler,
    const IndexSet                   &locally_relevant_dofs,
    AffineConstraints<double>        &constraints)
  {
    make_displacement_constraints(mapping,
                                  dof_handler,
                                  dirichlet.parts(),
                                  symmetry_ids,
                                  locally_relevant_dofs,
                                  constraints,
                                  dirichlet.has_values() ? &open_constraints
                                                         : nullptr);
  }



  // @sect4{PrescribedDisplacements::check_rigid_motions}
  //
  // The contact zones only push, and only where the body touches the
  // obstacle: they cannot hold a body that the Dirichlet and symmetry
  // conditions leave free to move rigidly, and K would be singular. Such a
  // scene is refused before anything is written, naming the motions.
  template <int dim>
  void
  PrescribedDisplacements<dim>::check_rigid_motions(
    const hp::MappingCollection<dim> &mapping,
    const DoFHandler<dim>            &dof_handler,
    const AffineConstraints<double>  &constraints) const
  {
    const std::vector<FreeBody<dim>> free
      = free_rigid_motions(mapping, dof_handler, constraints, communicator);
    if (free.empty())
      return;
    // Each body by its number and bounding box where the mesh has several.
    std::ostringstream which;
    for (const FreeBody<dim> &body : free)
      {
        which << (&body == &free.front() ? "" : ", and ") << "the body";
        if (body.n_bodies > 1)
          {
            which << " " << body.number << " of the mesh's " << body.n_bodies
                  << " bodies (the one in [" << body.lower[0] << ", "
                  << body.upper[0] << "]";
            for (unsigned int d = 1; d < dim; ++d)
              which << " x [" << body.lower[d] << ", " << body.upper[d] << "]";
            which << ")";
          }
        which << " free to move rigidly (";
        for (const std::string &motion : body.motions)
          which << (&motion == &body.motions.front() ? "" : "; ") << motion;
        which << ")";
      }
    AssertThrow(false,
                ExcMessage(
                  "The boundary conditions leave " + which.str()
                  + ": the elastic operator is singular. Stop these motions "
                    "with <Clamped boundary ids>, <Symmetry boundary ids> or a "
                    "<Prescribed displacement N> in subsection <Boundary> (a "
                    "contact zone, also one between two bodies, does not hold "
                    "a body); accepted: boundary conditions that leave no "
                    "rigid motion of any body free."));
  }



  // @sect4{PrescribedDisplacements::reinit}
  //
  // The dofs of each part, found as interpolate_boundary_values() finds them
  // when it makes the constraints: the vertex dofs of the boundary faces of
  // the part, in the part's components, unless an earlier part or a hanging
  // node constrains them already. Then the owned cells the per-step loops
  // visit: those with a dof where g_n may be nonzero (the lifting), and
  // those with a Dirichlet dof (the reactions).
  template <int dim>
  void
  PrescribedDisplacements<dim>::reinit(
    const hp::MappingCollection<dim> &mapping,
    const DoFHandler<dim>            &dof_handler,
    const IndexSet                   &locally_relevant_dofs,
    const StressPointGeometry<dim>   &stress_points,
    const VectorType                 &layout)
  {
    this->stress_points = &stress_points;
    dirichlet_dofs.clear();
    lifting_cells.clear();
    reaction_cells_.clear();
    // The values of the old mesh (set_time() sets them anew).
    current_constraints.clear();
    values_set = false;
    dirichlet_values.reinit(layout);
    if (dirichlet.has_values())
      lifting.reinit(layout);
    const std::vector<DirichletPart>  &parts       = dirichlet.parts();
    const Utilities::MPI::Partitioner &partitioner = *layout.get_partitioner();
    std::vector<bool>                  taken(partitioner.locally_owned_size()
                            + partitioner.n_ghost_indices());
    // The hanging nodes, which keep their constraints (made first): the
    // closed constraints cannot tell them apart from Dirichlet dofs where
    // all their parents are Dirichlet dofs too.
    hanging_nodes.reinit(locally_relevant_dofs);
    DoFTools::make_hanging_node_constraints(dof_handler, hanging_nodes);
    hanging_nodes.close();
    for (unsigned int p = 0; p < parts.size(); ++p)
      for (const auto &cell : dof_handler.active_cell_iterators())
        if (!cell->is_artificial())
          for (const auto &face : cell->face_iterators())
            if (face->at_boundary()
                && std::find(parts[p].boundary_ids.begin(),
                             parts[p].boundary_ids.end(),
                             face->boundary_id())
                     != parts[p].boundary_ids.end())
              for (const unsigned int v : face->vertex_indices())
                for (const unsigned int c : dirichlet.components(p))
                  {
                    const types::global_dof_index index
                      = face->vertex_dof_index(v, c, cell->active_fe_index());
                    if (!partitioner.in_local_range(index)
                        && !partitioner.is_ghost_entry(index))
                      continue;
                    const unsigned int local
                      = partitioner.global_to_local(index);
                    if (taken[local])
                      continue;
                    taken[local] = true;
                    if (hanging_nodes.is_constrained(index))
                      continue;
                    dirichlet_dofs.push_back({index,
                                              local,
                                              partitioner.in_local_range(index),
                                              p,
                                              c,
                                              face->vertex(v)});
                  }

    setup_roller_vertices(mapping, dof_handler, taken, partitioner);

    // The owned cells with a dof where a marker is not zero.
    const auto cells_touching = [&](const VectorType &marker) {
      std::vector<unsigned int> cells;
      const unsigned int        n_local = stress_points.n_vertices() * dim;
      for (unsigned int k = 0; k < stress_points.n_cells(); ++k)
        for (unsigned int i = 0; i < n_local; ++i)
          if (marker.local_element(stress_points.local_dofs(k)[i]) != 0)
            {
              cells.push_back(k);
              break;
            }
      return cells;
    };
    // The reactions need the residual at the Dirichlet dofs, at the
    // vertices of the planes of symmetry, and at the hanging nodes that pass
    // theirs on to them.
    VectorType marker(layout);
    marker = 0;
    for (const DirichletDof &dof : dirichlet_dofs)
      marker.local_element(dof.local_index) = 1;
    for (const RollerVertex &vertex : roller_vertices)
      for (const unsigned int local : vertex.local_dofs)
        marker.local_element(local) = 1;
    marker.update_ghost_values();
    for (const auto &line : hanging_nodes.get_lines())
      if (partitioner.in_local_range(line.index))
        for (const auto &[parent, weight] : line.entries)
          if (marker(parent) != 0)
            marker(line.index) = 1;
    marker.update_ghost_values();
    reaction_cells_ = cells_touching(marker);
    // The lifting needs the cells where g_n may be nonzero: the constraints
    // with the value 1 at every prescribed dof, closed and distributed,
    // mark them (hanging nodes and symmetry constraints included).
    if (dirichlet.has_values())
      {
        AffineConstraints<double> ones;
        ones.copy_from(open_constraints);
        for (const DirichletDof &dof : dirichlet_dofs)
          if (dirichlet.prescribes_function(dof.part))
            ones.set_inhomogeneity(dof.index, 1.);
        ones.close();
        marker = 0;
        ones.distribute(marker);
        marker.update_ghost_values();
        lifting_cells = cells_touching(marker);
      }
  }



  // @sect4{PrescribedDisplacements::setup_roller_vertices}
  //
  // The owned vertices of the faces on each plane of symmetry that are not
  // hanging nodes, with the planes each lies on (a vertex on an edge or a
  // corner lies on several) and the components a Dirichlet part takes
  // (dirichlet_dof[local]: reinit()).
  template <int dim>
  void
  PrescribedDisplacements<dim>::setup_roller_vertices(
    const hp::MappingCollection<dim>  &mapping,
    const DoFHandler<dim>             &dof_handler,
    const std::vector<bool>           &dirichlet_dof,
    const Utilities::MPI::Partitioner &partitioner)
  {
    roller_vertices.clear();
    symmetry_normals.clear();
    for (const auto id : symmetry_ids)
      symmetry_normals.push_back(
        symmetry_plane_normal(mapping, dof_handler, id, communicator));
    std::map<types::global_dof_index, unsigned int> vertex_of_x_dof;
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
        for (const auto &face : cell->face_iterators())
          if (face->at_boundary())
            for (unsigned int p = 0; p < symmetry_ids.size(); ++p)
              if (face->boundary_id() == symmetry_ids[p])
                for (const unsigned int v : face->vertex_indices())
                  {
                    const unsigned int element = cell->active_fe_index();
                    const types::global_dof_index x_dof
                      = face->vertex_dof_index(v, 0, element);
                    if (!partitioner.in_local_range(x_dof)
                        || hanging_nodes.is_constrained(x_dof))
                      continue;
                    const auto [entry, is_new]
                      = vertex_of_x_dof.emplace(x_dof, roller_vertices.size());
                    if (is_new)
                      {
                        RollerVertex vertex;
                        for (unsigned int c = 0; c < dim; ++c)
                          {
                            vertex.local_dofs[c] = partitioner.global_to_local(
                              face->vertex_dof_index(v, c, element));
                            vertex.dirichlet[c]
                              = dirichlet_dof[vertex.local_dofs[c]];
                          }
                        roller_vertices.push_back(vertex);
                      }
                    std::vector<unsigned int> &planes
                      = roller_vertices[entry->second].planes;
                    if (std::find(planes.begin(), planes.end(), p)
                        == planes.end())
                      planes.push_back(p);
                  }
  }



  // @sect4{PrescribedDisplacements::first_non_finite_value}
  //
  // Before anything is written: every prescribed value is finite at the
  // dofs of its part at the times of the run (the levels of Time step and
  // End time; at a stride beyond about 2e7 evaluations per rank).
  template <int dim>
  std::string
  PrescribedDisplacements<dim>::first_non_finite_value(
    const TimeSchedule &schedule) const
  {
    if (!dirichlet.has_values())
      return "";
    // The levels of the schedule's grid t_m = m k, m < N, and t_N = T.
    const std::uint64_t n_levels
      = dirichlet.depend_on_time() ? schedule.n_grid_levels() : 1;
    const std::size_t stride
      = std::max<std::size_t>(1,
                              std::size_t(double(dirichlet_dofs.size())
                                          * n_levels / 2e7));
    for (std::uint64_t m = 0; m < n_levels; ++m)
      for (std::size_t d = 0; d < dirichlet_dofs.size(); d += stride)
        {
          const DirichletDof &dof = dirichlet_dofs[d];
          // A clamped part has no expression (its value is zero).
          if (!dirichlet.prescribes_function(dof.part))
            continue;
          std::string problem = dirichlet
                                  .value(dof.part,
                                         dof.component,
                                         dof.location,
                                         schedule.grid_level(m))
                                  .second;
          if (!problem.empty())
            return problem;
        }
    return "";
  }



  // @sect4{PrescribedDisplacements::set_time}
  //
  // The values of the prescribed parts at their dofs, set as the
  // inhomogeneities of a copy of the open constraints, which closing
  // resolves into the hanging nodes and symmetry constraints that depend on
  // them; distributing them into a zero vector gives g_n.
  template <int dim>
  void
  PrescribedDisplacements<dim>::set_time(
    const double time,
    const bool   with_lifting,
    const std::function<const SymmetricTensor<4, dim> &(const unsigned int k)>
      &elasticity)
  {
    // Values that do not depend on time are set once per mesh. The flag is
    // the same on every rank (a rank without prescribed dofs has no
    // constraints to count, and would otherwise enter the collective
    // operations below alone).
    if (!dirichlet.has_values() || (!dirichlet.depend_on_time() && values_set))
      return;
    values_set = true;
    current_constraints.copy_from(open_constraints);
    std::string problem;
    for (const DirichletDof &dof : dirichlet_dofs)
      if (dirichlet.prescribes_function(dof.part))
        {
          const auto [value, message]
            = dirichlet.value(dof.part, dof.component, dof.location, time);
          if (problem.empty())
            problem = message;
          current_constraints.set_inhomogeneity(dof.index, value);
        }
    FileOutput::agree_on_problem(problem, communicator);
    current_constraints.close();
    dirichlet_values = 0;
    current_constraints.distribute(dirichlet_values);
    dirichlet_values.update_ghost_values();

    if (!with_lifting)
      return;
    lifting                 = 0;
    const unsigned int  n_q = stress_points->n_points();
    std::vector<double> cell_vector(stress_points->n_vertices() * dim);
    for (const unsigned int k : lifting_cells)
      {
        std::fill(cell_vector.begin(), cell_vector.end(), 0.);
        for (unsigned int q = 0; q < n_q; ++q)
          stress_points->add_load(
            -(elasticity(k)
              * symmetrize(
                stress_points->displacement_gradient(dirichlet_values, k, q))),
            k,
            q,
            make_array_view(cell_vector));
        stress_points->distribute(k, make_array_view(cell_vector), lifting);
      }
    lifting.compress(VectorOperation::add);
  }



  template <int dim>
  void
  PrescribedDisplacements<dim>::distribute(
    VectorType                      &u,
    const AffineConstraints<double> &homogeneous) const
  {
    if (dirichlet.has_values())
      current_constraints.distribute(u);
    else
      homogeneous.distribute(u);
  }



  template <int dim>
  std::vector<std::string>
  PrescribedDisplacements<dim>::reaction_names() const
  {
    std::vector<std::string> names;
    for (unsigned int part = 0; part < dirichlet.size(); ++part)
      names.push_back(dirichlet.name(part));
    for (const auto id : symmetry_ids)
      names.push_back("symmetry_" + std::to_string(id));
    return names;
  }



  // @sect4{PrescribedDisplacements::reactions}
  //
  // The force a Dirichlet part exerts on the body is the residual of the
  // equilibrium equations at its dofs, summed per component over the part's
  // dofs. The residual of a hanging node belongs to its parents, with the
  // weights of its constraint (a hanging node on a refined face next to the
  // part, or on the part itself). The parts' sums are reduced over the
  // ranks.
  template <int dim>
  std::vector<Tensor<1, dim>>
  PrescribedDisplacements<dim>::reactions(VectorType            &residual,
                                          const ContactSet<dim> *contact) const
  {
    std::vector<Tensor<1, dim>> forces(n_reactions());
    if (forces.empty())
      return forces;
    // The residuals of the owned hanging nodes passed on to their parents
    // (those of ghost parents sent to their owners), on meshes that have
    // hanging nodes (the decision is the same on every rank).
    if (Utilities::MPI::max(static_cast<unsigned int>(
                              hanging_nodes.n_constraints()),
                            communicator)
        > 0)
      {
        VectorType condensed(residual);
        for (const auto &line : hanging_nodes.get_lines())
          if (residual.get_partitioner()->in_local_range(line.index))
            for (const auto &[parent, weight] : line.entries)
              condensed(parent) += weight * residual(line.index);
        condensed.compress(VectorOperation::add);
        residual = condensed;
      }
    for (const DirichletDof &dof : dirichlet_dofs)
      if (dof.owned)
        forces[dof.part][dof.component]
          += residual.local_element(dof.local_index);
    add_roller_reactions(residual,
                         contact,
                         make_array_view(forces.begin() + dirichlet.size(),
                                         forces.end()));
    for (Tensor<1, dim> &force : forces)
      force = Utilities::MPI::sum(force, communicator);
    return forces;
  }
  // @sect4{PrescribedDisplacements::add_roller_reactions}
  //
  // A vertex on a plane of symmetry holds the plane's reaction, and where it
  // is a contact node also the contact force: the contact force is taken
  // out first (the residual plus z_i d_i and t_ij tau_ij, its direction and
  // tangents in space: zero at the free components of the vertex then, by
  // equilibrium), and what is left, apart from the components a Dirichlet
  // part takes, lies in the span of the normals of the planes at the
  // vertex. One plane: its
  // force is all of it; an edge or a corner: the least-squares split over
  // the planes' normals (exact for independent normals, which the
  // constraints need). Adds this rank's vertices to the planes' forces.
  template <int dim>
  void
  PrescribedDisplacements<dim>::add_roller_reactions(
    VectorType                      &residual,
    const ContactSet<dim>           *contact,
    const ArrayView<Tensor<1, dim>> &plane_forces) const
  {
    if (roller_vertices.empty())
      return;
    if (contact != nullptr)
      for (unsigned int i = 0; i < contact->size(); ++i)
        {
          const auto    &node  = contact->node(i);
          Tensor<1, dim> force = contact->z[i] * node.direction;
          for (unsigned int j = 0; j < contact->n_tangential(i); ++j)
            force += contact->t[i][j] * node.tangents[j];
          for (unsigned int c = 0; c < dim; ++c)
            residual.local_element(node.local_dofs[c]) += force[c];
        }
    for (const RollerVertex &vertex : roller_vertices)
      {
        Tensor<1, dim> force;
        for (unsigned int c = 0; c < dim; ++c)
          if (!vertex.dirichlet[c])
            force[c] = residual.local_element(vertex.local_dofs[c]);
        const unsigned int          m = vertex.planes.size();
        std::vector<Tensor<1, dim>> normals(m);
        for (unsigned int a = 0; a < m; ++a)
          for (unsigned int c = 0; c < dim; ++c)
            if (!vertex.dirichlet[c])
              normals[a][c] = symmetry_normals[vertex.planes[a]][c];
        // The normal equations G alpha = N^T force of the split.
        FullMatrix<double> gram(m, m);
        Vector<double>     alpha(m), projection(m);
        for (unsigned int a = 0; a < m; ++a)
          {
            projection(a) = normals[a] * force;
            for (unsigned int b = 0; b < m; ++b)
              gram(a, b) = normals[a] * normals[b];
          }
        if (m == 1)
          alpha(0) = gram(0, 0) > 0 ? projection(0) / gram(0, 0) : 0.;
        else if (std::abs(gram.determinant()) > 1e-12)
          {
            gram.gauss_jordan();
            gram.vmult(alpha, projection);
          }
        for (unsigned int a = 0; a < m; ++a)
          plane_forces[vertex.planes[a]] += alpha(a) * normals[a];
      }
  }


  template class PrescribedDisplacements<2>;
  template class PrescribedDisplacements<3>;
} // namespace ViscoContact
