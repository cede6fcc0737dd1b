// ViscoplasticContact<dim>: the Dirichlet parts of the boundary (clamped, or
// a displacement prescribed in some components as a function of x and t),
// and the forces they exert on the body.
//
// A prescribed displacement g_n does not change which dofs are constrained,
// only their values. So K is assembled and factorised once, with the
// homogeneous constraints (u_D = 0), and every step splits u_n = u_0 + g_n:
// g_n carries the prescribed values (and the hanging nodes and symmetry
// constraints that depend on them), u_0 solves the step problem with the
// right-hand side b_n - K g_n. K assembled with the constraints has lost
// its columns of the Dirichlet dofs, so K g_n is not a product with K: it
// is the lifting load (E eps(g_n), eps(v)), integrated over the cells
// where g_n is not zero, at the stress points (the quadrature K was
// assembled with, so that the two are the same bilinear form).

#include <deal.II/base/exceptions.h>
#include <deal.II/base/mpi.h>

#include <deal.II/dofs/dof_tools.h>

#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/vector.h>

#include "constraints.h"
#include "rigid_motions.h"
#include "robustness/file_output.h"
#include "time_schedule.h"
#include "viscoplastic_contact.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>
#include <sstream>

namespace ViscoContact
{
  // @sect4{ViscoplasticContact::setup_dirichlet_dofs}
  //
  // The dofs of each part, found as interpolate_boundary_values() finds them
  // when it makes the constraints: the vertex dofs of the boundary faces of
  // the part, in the part's components, unless an earlier part or a hanging
  // node constrains them already. Then the owned cells the per-step loops
  // visit: those with a dof where g_n may be nonzero (the lifting), and
  // those with a Dirichlet dof (the reactions).
  template <int dim>
  void
  ViscoplasticContact<dim>::setup_dirichlet_dofs()
  {
    dirichlet_dofs.clear();
    lifting_cells.clear();
    reaction_cells.clear();
    // The values of the old mesh (set_dirichlet_values() sets them anew).
    current_constraints.clear();
    dirichlet_values.reinit(solution);
    if (dirichlet.has_values())
      lifting_load.reinit(solution);
    const std::vector<DirichletPart>  &parts = dirichlet.parts();
    const Utilities::MPI::Partitioner &partitioner
      = *solution.get_partitioner();
    std::vector<bool> taken(partitioner.locally_owned_size()
                            + partitioner.n_ghost_indices());
    // The hanging nodes, which keep their constraints (made first): the
    // closed constraints cannot tell them apart from Dirichlet dofs where
    // all their parents are Dirichlet dofs too.
    hanging_node_constraints.reinit(locally_relevant_dofs);
    DoFTools::make_hanging_node_constraints(dof_handler,
                                            hanging_node_constraints);
    hanging_node_constraints.close();
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
                      = face->vertex_dof_index(v, c);
                    if (!partitioner.in_local_range(index)
                        && !partitioner.is_ghost_entry(index))
                      continue;
                    const unsigned int local
                      = partitioner.global_to_local(index);
                    if (taken[local])
                      continue;
                    taken[local] = true;
                    if (hanging_node_constraints.is_constrained(index))
                      continue;
                    dirichlet_dofs.push_back({index,
                                              local,
                                              partitioner.in_local_range(index),
                                              p,
                                              c,
                                              face->vertex(v)});
                  }

    setup_roller_vertices(taken);

    // The owned cells with a dof where a marker is not zero.
    const auto cells_touching = [&](const VectorType &marker) {
      std::vector<unsigned int> cells;
      const unsigned int        n_local = n_cell_vertices * dim;
      for (unsigned int k = 0; k < owned_cells.size(); ++k)
        for (unsigned int i = 0; i < n_local; ++i)
          if (marker.local_element(
                cell_local_dofs[std::size_t(k) * n_local + i])
              != 0)
            {
              cells.push_back(k);
              break;
            }
      return cells;
    };
    // The reactions need the residual at the Dirichlet dofs, at the
    // vertices of the planes of symmetry, and at the hanging nodes that pass
    // theirs on to them.
    VectorType marker(solution);
    marker = 0;
    for (const DirichletDof &dof : dirichlet_dofs)
      marker.local_element(dof.local_index) = 1;
    for (const RollerVertex &vertex : roller_vertices)
      for (const unsigned int local : vertex.local_dofs)
        marker.local_element(local) = 1;
    marker.update_ghost_values();
    for (const auto &line : hanging_node_constraints.get_lines())
      if (partitioner.in_local_range(line.index))
        for (const auto &[parent, weight] : line.entries)
          if (marker(parent) != 0)
            marker(line.index) = 1;
    marker.update_ghost_values();
    reaction_cells = cells_touching(marker);
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



  // @sect4{ViscoplasticContact::setup_roller_vertices}
  //
  // The owned vertices of the faces on each plane of symmetry that are not
  // hanging nodes, with the planes each lies on (a vertex on an edge or a
  // corner lies on several) and the components a Dirichlet part takes
  // (dirichlet_dof[local]: setup_dirichlet_dofs()).
  template <int dim>
  void
  ViscoplasticContact<dim>::setup_roller_vertices(
    const std::vector<bool> &dirichlet_dof)
  {
    roller_vertices.clear();
    symmetry_normals.clear();
    for (const auto id : parameters.symmetry_ids)
      symmetry_normals.push_back(
        symmetry_plane_normal(mapping, dof_handler, id, mpi_communicator));
    const Utilities::MPI::Partitioner &partitioner
      = *solution.get_partitioner();
    std::map<types::global_dof_index, unsigned int> vertex_of_x_dof;
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
        for (const auto &face : cell->face_iterators())
          if (face->at_boundary())
            for (unsigned int p = 0; p < parameters.symmetry_ids.size(); ++p)
              if (face->boundary_id() == parameters.symmetry_ids[p])
                for (const unsigned int v : face->vertex_indices())
                  {
                    const types::global_dof_index x_dof
                      = face->vertex_dof_index(v, 0);
                    if (!partitioner.in_local_range(x_dof)
                        || hanging_node_constraints.is_constrained(x_dof))
                      continue;
                    const auto [entry, is_new]
                      = vertex_of_x_dof.emplace(x_dof, roller_vertices.size());
                    if (is_new)
                      {
                        RollerVertex vertex;
                        for (unsigned int c = 0; c < dim; ++c)
                          {
                            vertex.local_dofs[c] = partitioner.global_to_local(
                              face->vertex_dof_index(v, c));
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



  template <int dim>
  std::vector<std::string>
  ViscoplasticContact<dim>::reaction_part_names() const
  {
    std::vector<std::string> names;
    for (unsigned int part = 0; part < dirichlet.size(); ++part)
      names.push_back(dirichlet.name(part));
    for (const auto id : parameters.symmetry_ids)
      names.push_back("symmetry_" + std::to_string(id));
    return names;
  }



  // @sect4{ViscoplasticContact::check_rigid_motions}
  //
  // The contact zones only push, and only where the body touches the
  // obstacle: they cannot hold a body that the Dirichlet and symmetry
  // conditions leave free to move rigidly, and K would be singular. Such a
  // scene is refused before anything is written, naming the motions.
  template <int dim>
  void
  ViscoplasticContact<dim>::check_rigid_motions() const
  {
    const std::vector<std::string> free
      = free_rigid_motions(mapping, dof_handler, constraints, mpi_communicator);
    if (free.empty())
      return;
    std::string motions;
    for (const std::string &motion : free)
      motions += (motions.empty() ? "" : "; ") + motion;
    AssertThrow(false,
                ExcMessage(
                  "The boundary conditions leave the body free to move "
                  "rigidly ("
                  + motions
                  + "): the elastic operator is singular. Stop these motions "
                    "with <Clamped boundary ids>, <Symmetry boundary ids> or a "
                    "<Prescribed displacement N> in subsection <Boundary> (a "
                    "contact zone does not hold a body); accepted: boundary "
                    "conditions that leave no rigid motion free."));
  }



  // @sect4{ViscoplasticContact::check_prescribed_values}
  //
  // Before anything is written: every prescribed value is finite at the
  // dofs of its part, and the obstacle's gap at the contact nodes, at the
  // times of the run (the levels of Time step and End time; at a stride
  // beyond about 2e7 evaluations per rank). The message names the entry,
  // the point and the time, on every rank.
  template <int dim>
  void
  ViscoplasticContact<dim>::check_prescribed_values()
  {
    // The levels of the schedule's grid t_m = m k, m < N, and t_N = T.
    const std::uint64_t n_grid_levels = schedule.n_grid_levels();
    const std::uint64_t n_levels
      = dirichlet.depend_on_time() ? n_grid_levels : 1;
    const std::size_t stride
      = std::max<std::size_t>(1,
                              std::size_t(double(dirichlet_dofs.size())
                                          * n_levels / 2e7));
    const auto level
      = [&](const std::uint64_t m) { return schedule.grid_level(m); };
    std::string problem;
    if (dirichlet.has_values())
      for (std::uint64_t m = 0; m < n_levels && problem.empty(); ++m)
        for (std::size_t d = 0; d < dirichlet_dofs.size() && problem.empty();
             d += stride)
          problem = prescribed_value(dirichlet_dofs[d], level(m)).second;
    // The obstacle's gap at the contact nodes, at every level (or every
    // stride-th on long runs with many nodes), then again at the current
    // time.
    if (contact_zones.has_gap() && contact_enabled)
      {
        const std::uint64_t n_gap_levels
          = contact_zones.gap_depends_on_time() ? n_grid_levels : 1;
        const std::uint64_t gap_stride
          = std::max<std::uint64_t>(1,
                                    std::uint64_t(double(contact_set.size())
                                                  * n_gap_levels / 2e7));
        for (std::uint64_t m = 0; m < n_gap_levels && problem.empty();
             m += gap_stride)
          problem = contact_set.set_gaps(contact_zones.gaps(), level(m));
        if (problem.empty())
          problem = contact_set.set_gaps(contact_zones.gaps(),
                                         schedule.current_time());
      }
    FileOutput::agree_on_problem(problem, mpi_communicator);
  }



  // The value of a prescribed dof at a time, or the message that it is not
  // finite.
  template <int dim>
  std::pair<double, std::string>
  ViscoplasticContact<dim>::prescribed_value(const DirichletDof &dof,
                                             const double        time) const
  {
    return dirichlet.value(dof.part, dof.component, dof.location, time);
  }



  // @sect4{ViscoplasticContact::set_dirichlet_values}
  //
  // The values of the prescribed parts at their dofs, set as the
  // inhomogeneities of a copy of the open constraints, which closing
  // resolves into the hanging nodes and symmetry constraints that depend on
  // them; distributing them into a zero vector gives g_n. A value that is
  // not finite stops all ranks, naming the entry, the point and the time.
  // Values that do not depend on t are set once per mesh (the closed
  // constraints have lines from then on).
  template <int dim>
  void
  ViscoplasticContact<dim>::set_dirichlet_values(const double time)
  {
    if (!dirichlet.has_values()
        || (!dirichlet.depend_on_time()
            && current_constraints.n_constraints() > 0))
      return;
    TimerOutput::Scope t(report.timer(), "Assemble prescribed displacement");
    current_constraints.copy_from(open_constraints);
    std::string problem;
    for (const DirichletDof &dof : dirichlet_dofs)
      if (dirichlet.prescribes_function(dof.part))
        {
          const auto [value, message] = prescribed_value(dof, time);
          if (problem.empty())
            problem = message;
          current_constraints.set_inhomogeneity(dof.index, value);
        }
    FileOutput::agree_on_problem(problem, mpi_communicator);
    current_constraints.close();
    dirichlet_values = 0;
    current_constraints.distribute(dirichlet_values);
    dirichlet_values.update_ghost_values();

    // The implicit update's Newton iteration has g_n in its iterate, and so
    // in its internal force: it needs no lifting load.
    if (implicit_update())
      return;
    lifting_load            = 0;
    const unsigned int  n_q = stress_quadrature.size();
    std::vector<double> cell_vector(n_cell_vertices * dim);
    for (const unsigned int k : lifting_cells)
      {
        std::fill(cell_vector.begin(), cell_vector.end(), 0.);
        for (unsigned int q = 0; q < n_q; ++q)
          add_stress_point_load(
            -(material_of(k).elasticity_tensor()
              * symmetrize(displacement_gradient_at(dirichlet_values, k, q))),
            k,
            q,
            make_array_view(cell_vector));
        distribute_cell_vector(k, make_array_view(cell_vector), lifting_load);
      }
    lifting_load.compress(VectorOperation::add);
  }



  // The gap functions of the zones, nullptr where the gap is zero.



  // @sect4{ViscoplasticContact::set_gaps}
  template <int dim>
  void
  ViscoplasticContact<dim>::set_gaps(const double time)
  {
    if (!contact_zones.has_gap() || !contact_enabled)
      return;
    FileOutput::agree_on_problem(contact_set.set_gaps(contact_zones.gaps(),
                                                      time),
                                 mpi_communicator);
  }



  // @sect4{ViscoplasticContact::apply_constraints}
  //
  // The constrained entries of u from the free ones: hanging nodes and
  // symmetry constraints, and the values g_n of the Dirichlet parts. The
  // caller updates the ghosts.
  template <int dim>
  void
  ViscoplasticContact<dim>::apply_constraints(VectorType &u) const
  {
    if (dirichlet.has_values())
      current_constraints.distribute(u);
    else
      constraints.distribute(u);
  }



  // @sect4{ViscoplasticContact::reaction_forces}
  //
  // The force a Dirichlet part exerts on the body is the residual of the
  // equilibrium equations at its dofs, (sigma_n, eps(v)) - (f_n, v), summed
  // per component over the part's dofs. The residual of a hanging node
  // belongs to its parents, with the weights of its constraint (a hanging
  // node on a refined face next to the part, or on the part itself). The cells
  // around the Dirichlet dofs add their terms without the constraints (which
  // would drop exactly these rows), into the ghosts too; the owners sum them,
  // and the parts' sums are reduced over the ranks.
  template <int dim>
  std::vector<Tensor<1, dim>>
  ViscoplasticContact<dim>::reaction_forces(const double time)
  {
    std::vector<Tensor<1, dim>> forces(dirichlet.size()
                                       + parameters.symmetry_ids.size());
    if (forces.empty())
      return forces;
    VectorType residual(solution);
    residual                    = 0;
    const unsigned int  n_q     = stress_quadrature.size();
    const unsigned int  n_local = n_cell_vertices * dim;
    std::vector<double> cell_vector(n_local);
    Vector<double>      cell_load(n_local);
    FEValues<dim>       fe_values(mapping,
                            *fe,
                            load_quadrature,
                            update_values | update_quadrature_points
                              | update_JxW_values);
    FEFaceValues<dim>   fe_face_values(mapping,
                                     *fe,
                                     face_quadrature,
                                     update_values | update_quadrature_points
                                       | update_normal_vectors
                                       | update_JxW_values);
    loads.set_time(time);
    std::string problem;
    double     *values = residual.get_values(); // owned entries, then ghosts
    for (const unsigned int k : reaction_cells)
      {
        std::fill(cell_vector.begin(), cell_vector.end(), 0.);
        for (unsigned int q = 0; q < n_q; ++q)
          add_stress_point_load(
            quadrature_point_history[std::size_t(k) * n_q + q].stress,
            k,
            q,
            make_array_view(cell_vector));
        if (cell_external_load(owned_cells[k],
                               fe_values,
                               fe_face_values,
                               cell_load,
                               problem))
          for (unsigned int a = 0; a < n_cell_vertices; ++a)
            for (unsigned int c = 0; c < dim; ++c)
              cell_vector[a * dim + c]
                -= cell_load(fe->component_to_system_index(c, a));
        for (unsigned int i = 0; i < n_local; ++i)
          values[cell_local_dofs[std::size_t(k) * n_local + i]]
            += cell_vector[i];
      }
    residual.compress(VectorOperation::add);
    FileOutput::agree_on_problem(problem, mpi_communicator);
    // The residuals of the owned hanging nodes passed on to their parents
    // (those of ghost parents sent to their owners), on meshes that have
    // hanging nodes (the decision is the same on every rank).
    if (Utilities::MPI::max(static_cast<unsigned int>(
                              hanging_node_constraints.n_constraints()),
                            mpi_communicator)
        > 0)
      {
        VectorType condensed(residual);
        for (const auto &line : hanging_node_constraints.get_lines())
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
                         make_array_view(forces.begin() + dirichlet.size(),
                                         forces.end()));
    for (Tensor<1, dim> &force : forces)
      force = Utilities::MPI::sum(force, mpi_communicator);
    return forces;
  }



  // @sect4{ViscoplasticContact::add_roller_reactions}
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
  ViscoplasticContact<dim>::add_roller_reactions(
    VectorType                      &residual,
    const ArrayView<Tensor<1, dim>> &plane_forces) const
  {
    if (roller_vertices.empty())
      return;
    if (contact_enabled)
      for (unsigned int i = 0; i < contact_set.size(); ++i)
        {
          const auto    &node  = contact_set.node(i);
          Tensor<1, dim> force = contact_set.z[i] * node.direction;
          for (unsigned int j = 0; j < contact_set.n_tangential(i); ++j)
            force += contact_set.t[i][j] * node.tangents[j];
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



  template class ViscoplasticContact<2>;
  template class ViscoplasticContact<3>;
} // namespace ViscoContact
