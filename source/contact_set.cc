// The contact nodes of Gamma_3: where they are, their weights, normals and
// active-set parameters, and their output (profiles and nodal fields).

#include <deal.II/base/exceptions.h>
#include <deal.II/base/mpi.h>

#include <deal.II/fe/fe_values.h>

#include "contact_set.h"
#include "mpi_tools.h"

#include <algorithm>
#include <iomanip>
#include <set>
#include <sstream>

namespace ViscoContact
{
  namespace
  {
    bool
    is_one_of(const types::boundary_id               id,
              const std::vector<types::boundary_id> &ids)
    {
      return std::find(ids.begin(), ids.end(), id) != ids.end();
    }
  } // namespace



  // @sect4{assemble_lumped_weights}
  //
  // Like a right-hand side: each rank integrates phi_i and phi_i nu over
  // its own faces of the boundary parts, adds into the (ghosted) entries of
  // the cell's dofs, and compress() sends the ghost contributions to the
  // owners.
  template <int dim>
  void
  assemble_lumped_weights(const Mapping<dim>        &mapping,
                          const DoFHandler<dim>     &dof_handler,
                          const Quadrature<dim - 1> &face_quadrature,
                          const std::vector<types::boundary_id> &boundary_ids,
                          VectorType                            &weights,
                          VectorType &weighted_normals)
  {
    const FiniteElement<dim>            &fe = dof_handler.get_fe();
    FEFaceValues<dim>                    fe_face_values(mapping,
                                     fe,
                                     face_quadrature,
                                     update_values | update_JxW_values
                                       | update_normal_vectors);
    std::vector<types::global_dof_index> local_dof_indices(
      fe.n_dofs_per_cell());
    weights          = 0;
    weighted_normals = 0;
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
        for (const unsigned int f : cell->face_indices())
          if (cell->face(f)->at_boundary()
              && is_one_of(cell->face(f)->boundary_id(), boundary_ids))
            {
              fe_face_values.reinit(cell, f);
              cell->get_dof_indices(local_dof_indices);
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
    weights.compress(VectorOperation::add);
    weighted_normals.compress(VectorOperation::add);
  }



  // @sect4{ContactSet::setup}
  //
  // A vertex of Gamma_3 whose faces all belong to other ranks' cells is
  // still seen through the ghost cells, so every locally owned contact
  // vertex is found. Vertices of hanging or clamped dofs are left out.
  template <int dim>
  void
  ContactSet<dim>::setup(const ContactLaw          &law,
                         const Mapping<dim>        &mapping,
                         const DoFHandler<dim>     &dof_handler,
                         const DoFHandler<dim>     &scalar_dof_handler,
                         const Quadrature<dim - 1> &face_quadrature,
                         const std::vector<types::boundary_id> &contact_ids,
                         const AffineConstraints<double>       &constraints,
                         const VectorType                      &layout)
  {
    communicator = layout.get_mpi_communicator();
    VectorType weights(layout), weighted_normals(layout);
    assemble_lumped_weights(mapping,
                            dof_handler,
                            face_quadrature,
                            contact_ids,
                            weights,
                            weighted_normals);

    const auto &partitioner = *layout.get_partitioner();
    geometry.clear();
    std::set<types::global_dof_index> seen;
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (!cell->is_artificial())
        for (const unsigned int f : cell->face_indices())
          if (cell->face(f)->at_boundary()
              && is_one_of(cell->face(f)->boundary_id(), contact_ids))
            for (const unsigned int v : cell->face(f)->vertex_indices())
              {
                NodeGeometry node;
                for (unsigned int c = 0; c < dim; ++c)
                  node.dofs[c] = cell->face(f)->vertex_dof_index(v, c);
                bool usable = partitioner.in_local_range(node.dofs[0])
                              && seen.insert(node.dofs[0]).second;
                for (unsigned int c = 0; c < dim; ++c)
                  usable = usable && !constraints.is_constrained(node.dofs[c]);
                if (!usable)
                  continue;
                node.location = cell->face(f)->vertex(v);
                for (unsigned int c = 0; c < dim; ++c)
                  {
                    node.local_dofs[c]
                      = partitioner.global_to_local(node.dofs[c]);
                    node.normal[c] = weighted_normals(node.dofs[c]);
                  }
                node.normal /= node.normal.norm();
                const typename DoFHandler<dim>::active_cell_iterator
                  scalar_cell(&dof_handler.get_triangulation(),
                              cell->level(),
                              cell->index(),
                              &scalar_dof_handler);
                node.scalar_dof = scalar_cell->face(f)->vertex_dof_index(v, 0);
                geometry.push_back(node);
              }

    // Along Gamma_3: the order of the contact profiles.
    std::sort(geometry.begin(),
              geometry.end(),
              [](const NodeGeometry &a, const NodeGeometry &b) {
                for (unsigned int d = 0; d < dim; ++d)
                  if (std::abs(a.location[d] - b.location[d]) > 1e-12)
                    return a.location[d] < b.location[d];
                return false;
              });
    std::vector<double> node_weights(geometry.size());
    for (unsigned int i = 0; i < geometry.size(); ++i)
      node_weights[i] = weights(geometry[i].dofs[0]);
    reinit(law, node_weights);

    const types::global_dof_index n_local = geometry.size();
    n_global        = Utilities::MPI::sum(n_local, communicator);
    first_global    = 0;
    const int error = MPI_Exscan(
      &n_local,
      &first_global,
      1,
      Utilities::MPI::mpi_type_id_for_type<types::global_dof_index>,
      MPI_SUM,
      communicator);
    AssertThrowMPI(error);
    if (Utilities::MPI::this_mpi_process(communicator) == 0)
      first_global = 0;
    AssertThrow(n_global > 0,
                ExcMessage("Invalid parameter <Contact boundary ids> in "
                           "subsection <Boundary>: Gamma_3 has no node that "
                           "is free to move (all its nodes are clamped); "
                           "accepted: ids of boundary parts with at least one "
                           "node off Gamma_1."));
  }



  template <int dim>
  void
  ContactSet<dim>::set_operator(const MatrixType &A)
  {
    const double        softening = law().steepest_softening();
    std::vector<double> c(size());
    for (unsigned int i = 0; i < size(); ++i)
      {
        const NodeGeometry &n                = geometry[i];
        double              normal_stiffness = 0;
        for (unsigned int a = 0; a < dim; ++a)
          for (unsigned int b = 0; b < dim; ++b)
            normal_stiffness
              += n.normal[a] * n.normal[b] * A.el(n.dofs[a], n.dofs[b]);
        c[i] = std::max(normal_stiffness / weight(i), 2 * softening);
      }
    set_parameters(c);
  }



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



  template <int dim>
  MPI_Comm
  ContactSet<dim>::get_communicator() const
  {
    return communicator;
  }



  template <int dim>
  double
  ContactSet<dim>::normal_component(const VectorType  &u,
                                    const unsigned int i) const
  {
    double value = 0;
    for (unsigned int c = 0; c < dim; ++c)
      value
        += geometry[i].normal[c] * u.local_element(geometry[i].local_dofs[c]);
    return value;
  }



  template <int dim>
  void
  ContactSet<dim>::add_normal(VectorType        &v,
                              const unsigned int i,
                              const double       value) const
  {
    for (unsigned int c = 0; c < dim; ++c)
      v.local_element(geometry[i].local_dofs[c])
        += value * geometry[i].normal[c];
  }



  // @sect4{ContactSet::write_profile}
  //
  // Each rank formats its own nodes; rank 0 adds the header. On one rank
  // the lines follow Gamma_3; on several, each rank's block does.
  template <int dim>
  void
  ContactSet<dim>::write_profile(const std::string &file,
                                 const double       time) const
  {
    std::ostringstream out;
    out << std::setprecision(10);
    if (Utilities::MPI::this_mpi_process(communicator) == 0)
      {
        const char *coordinates[3] = {"x", "y", "z"};
        for (unsigned int d = 0; d < dim; ++d)
          out << coordinates[d] << ',';
        out << "time,u_nu,compliance_pressure,foundation_pressure,"
               "contact_pressure,nodal_force,weight,status\n";
      }
    for (unsigned int i = 0; i < size(); ++i)
      {
        for (unsigned int d = 0; d < dim; ++d)
          out << geometry[i].location[d] << ',';
        out << time << ',' << r[i] << ',' << compliance_pressure(i) << ','
            << contact_pressure(i) - compliance_pressure(i) << ','
            << contact_pressure(i) << ',' << z[i] << ',' << weight(i) << ','
            << status(i) << '\n';
      }
    MPITools::write_text_collectively(file, out.str(), communicator);
  }



  template <int dim>
  void
  ContactSet<dim>::fill_output_fields(VectorType &contact_pressure_field,
                                      VectorType &compliance_pressure_field,
                                      VectorType &foundation_pressure_field,
                                      VectorType &contact_status_field) const
  {
    for (VectorType *field : {&contact_pressure_field,
                              &compliance_pressure_field,
                              &foundation_pressure_field,
                              &contact_status_field})
      *field = 0;
    for (unsigned int i = 0; i < size(); ++i)
      {
        const types::global_dof_index dof = geometry[i].scalar_dof;
        contact_pressure_field(dof)       = contact_pressure(i);
        compliance_pressure_field(dof)    = compliance_pressure(i);
        foundation_pressure_field(dof)
          = contact_pressure(i) - compliance_pressure(i);
        contact_status_field(dof) = status(i);
      }
  }



  template void
  assemble_lumped_weights(const Mapping<2> &,
                          const DoFHandler<2> &,
                          const Quadrature<1> &,
                          const std::vector<types::boundary_id> &,
                          VectorType &,
                          VectorType &);
  template void
  assemble_lumped_weights(const Mapping<3> &,
                          const DoFHandler<3> &,
                          const Quadrature<2> &,
                          const std::vector<types::boundary_id> &,
                          VectorType &,
                          VectorType &);
  template class ContactSet<2>;
  template class ContactSet<3>;
} // namespace ViscoContact
