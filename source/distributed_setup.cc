// The set-up phase of DistributedViscoplasticContact<dim>: the distributed
// mesh, the dofs with their ownership, the elastic operator and its
// preconditioner (both built once), the contact nodes and the stress points.

#include <deal.II/base/exceptions.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/utilities.h>

#include <deal.II/distributed/fully_distributed_tria.h>
#include <deal.II/distributed/tria.h>

#include <deal.II/dofs/dof_tools.h>

#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_simplex_p.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/fe/fe_values.h>

#include <deal.II/grid/grid_tools.h>
#include <deal.II/grid/tria_description.h>

#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/sparsity_tools.h>

#include <deal.II/numerics/vector_tools.h>

#include "distributed_viscoplastic_contact.h"
#include "loads.h"
#include "mesh.h"

#include <Epetra_Map.h>
#include <Epetra_MultiVector.h>
#include <Teuchos_ParameterList.hpp>

#include <algorithm>
#include <set>

namespace ViscoContact
{
  // @sect4{DistributedViscoplasticContact::DistributedViscoplasticContact}
  //
  // As in the serial program, the reference cell fixes the finite element
  // (P1 on simplices, Q1 on hypercubes), the stress points and the
  // quadratures; here it also fixes the kind of distributed mesh.
  template <int dim>
  DistributedViscoplasticContact<dim>::DistributedViscoplasticContact(
    const Parameters::AllParameters &parameters)
    : mpi_communicator(MPI_COMM_WORLD)
    , parameters(parameters)
    , pcout(std::cout, Utilities::MPI::this_mpi_process(mpi_communicator) == 0)
    , computing_timer(mpi_communicator,
                      pcout,
                      TimerOutput::never,
                      TimerOutput::wall_times)
    , reference_cell(parameters.cell_type == "simplex"
                       ? ReferenceCells::get_simplex<dim>()
                       : ReferenceCells::get_hypercube<dim>())
    , mapping(&reference_cell.template get_default_linear_mapping<dim>())
    , fe(reference_cell.is_simplex()
           ? std::make_unique<FESystem<dim>>(FE_SimplexP<dim>(1), dim)
           : std::make_unique<FESystem<dim>>(FE_Q<dim>(1), dim))
    , stress_quadrature(reference_cell.template get_gauss_type_quadrature<dim>(
        reference_cell.is_simplex() ? 1 : 2))
    , load_quadrature(reference_cell.template get_gauss_type_quadrature<dim>(2))
    , face_quadrature(reference_cell.face_reference_cell(0)
                        .template get_gauss_type_quadrature<dim - 1>(2))
    , material(parameters.young_modulus,
               parameters.poisson_ratio,
               parameters.viscosity,
               parameters.yield_stress)
    , body_force(dim)
    , surface_traction(dim)
  {
    AssertThrow(parameters.dimension == dim, ExcInternalError());
    initialize_load(body_force,
                    "Body force",
                    parameters.body_force,
                    parameters.lengths);
    initialize_load(surface_traction,
                    "Surface traction",
                    parameters.surface_traction,
                    parameters.lengths);
    loads_depend_on_time = mentions_time(parameters.body_force)
                           || mentions_time(parameters.surface_traction);
  }



  template <int dim>
  DistributedViscoplasticContact<dim>::~DistributedViscoplasticContact()
  {
    // The DoFHandler refers to the triangulation: release it first.
    dof_handler.clear();
  }



  // @sect4{DistributedViscoplasticContact::make_grid}
  //
  // Hypercube meshes live on p4est: every rank holds the coarse mesh, p4est
  // distributes the refined cells, and the refinement toward Gamma_3 runs
  // in parallel. p4est cannot hold simplices; a simplex mesh is built and
  // refined as a serial mesh, partitioned by METIS, and each rank keeps its
  // part in a parallel::fullydistributed::Triangulation. (The serial mesh
  // exists on every rank during set-up only; for meshes beyond a few
  // million cells, create_description_from_triangulation_in_groups() would
  // build it once per node.)
  template <int dim>
  void
  DistributedViscoplasticContact<dim>::make_grid()
  {
    TimerOutput::Scope t(computing_timer, "Setup: mesh");
    if (reference_cell.is_simplex())
      {
        Triangulation<dim> serial_mesh;
        create_coarse_mesh(parameters, serial_mesh);
        refine_mesh(parameters, serial_mesh);
        GridTools::partition_triangulation(Utilities::MPI::n_mpi_processes(
                                             mpi_communicator),
                                           serial_mesh);
        const auto description = TriangulationDescription::Utilities::
          create_description_from_triangulation(serial_mesh, mpi_communicator);
        auto mesh
          = std::make_unique<parallel::fullydistributed::Triangulation<dim>>(
            mpi_communicator);
        mesh->create_triangulation(description);
        triangulation = std::move(mesh);
      }
    else
      {
        // Each coarse cell is a p4est tree, and trees are expensive (every
        // rank stores all of them): the generated box of Subdivisions =
        // m 2^j cubes per edge is made of m^dim coarse cells refined j times,
        // the same mesh.
        Parameters::AllParameters coarse_parameters = parameters;
        unsigned int              box_refinements   = 0;
        if (parameters.mesh_file.empty())
          while (coarse_parameters.subdivisions % 2 == 0)
            {
              coarse_parameters.subdivisions /= 2;
              ++box_refinements;
            }
        Triangulation<dim> coarse_mesh;
        create_coarse_mesh(coarse_parameters, coarse_mesh);
        auto mesh = std::make_unique<parallel::distributed::Triangulation<dim>>(
          mpi_communicator);
        mesh->copy_triangulation(coarse_mesh);
        if (box_refinements > 0)
          mesh->refine_global(box_refinements);
        refine_mesh(parameters, *mesh);
        triangulation = std::move(mesh);
      }
    check_boundary_ids(parameters, *triangulation, mpi_communicator);
  }



  // @sect4{DistributedViscoplasticContact::setup_system}
  //
  // Dofs and their ownership, the clamping of Gamma_1 and the hanging nodes
  // of a graded mesh as constraints, the distributed sparsity pattern, and
  // the vectors. K is then assembled once.
  template <int dim>
  void
  DistributedViscoplasticContact<dim>::setup_system()
  {
    {
      TimerOutput::Scope t(computing_timer, "Setup: dofs and constraints");
      dof_handler.reinit(*triangulation);
      dof_handler.distribute_dofs(*fe);
      locally_owned_dofs = dof_handler.locally_owned_dofs();
      DoFTools::extract_locally_relevant_dofs(dof_handler,
                                              locally_relevant_dofs);

      constraints.clear();
      constraints.reinit(locally_relevant_dofs);
      DoFTools::make_hanging_node_constraints(dof_handler, constraints);
      for (const auto id : parameters.clamped_ids)
        VectorTools::interpolate_boundary_values(*mapping,
                                                 dof_handler,
                                                 id,
                                                 Functions::ZeroFunction<dim>(
                                                   dim),
                                                 constraints);
      constraints.close();

      DynamicSparsityPattern dsp(locally_relevant_dofs);
      DoFTools::make_sparsity_pattern(dof_handler,
                                      dsp,
                                      constraints,
                                      /*keep_constrained_dofs=*/false);
      SparsityTools::distribute_sparsity_pattern(dsp,
                                                 locally_owned_dofs,
                                                 mpi_communicator,
                                                 locally_relevant_dofs);
      stiffness_matrix.reinit(locally_owned_dofs,
                              locally_owned_dofs,
                              dsp,
                              mpi_communicator);

      solution.reinit(locally_owned_dofs, mpi_communicator);
      ghosted_solution.reinit(locally_owned_dofs,
                              locally_relevant_dofs,
                              mpi_communicator);
      external_load.reinit(locally_owned_dofs, mpi_communicator);
      history_load.reinit(locally_owned_dofs, mpi_communicator);
      system_rhs.reinit(locally_owned_dofs, mpi_communicator);
    }
    assemble_elastic_operator();
  }



  // @sect4{DistributedViscoplasticContact::assemble_elastic_operator}
  //
  // K_ij = (E eps(phi_j), eps(phi_i)) on the locally owned cells, with the
  // constrained rows and columns condensed (their diagonal stays positive,
  // so K is SPD on all dofs).
  template <int dim>
  void
  DistributedViscoplasticContact<dim>::assemble_elastic_operator()
  {
    TimerOutput::Scope               t(computing_timer, "Setup: assemble K");
    const FEValuesExtractors::Vector displacements(0);
    FEValues<dim>                    fe_values(*mapping,
                            *fe,
                            stress_quadrature,
                            update_gradients | update_JxW_values);
    const unsigned int               dofs_per_cell = fe->n_dofs_per_cell();
    FullMatrix<double>               cell_matrix(dofs_per_cell, dofs_per_cell);
    std::vector<types::global_dof_index> local_dof_indices(dofs_per_cell);
    std::vector<SymmetricTensor<2, dim>> strains(dofs_per_cell);
    const SymmetricTensor<4, dim>       &E = material.elasticity_tensor();

    for (const auto &cell : dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          fe_values.reinit(cell);
          cell_matrix = 0;
          for (const unsigned int q : fe_values.quadrature_point_indices())
            {
              for (unsigned int i = 0; i < dofs_per_cell; ++i)
                strains[i] = fe_values[displacements].symmetric_gradient(i, q);
              for (unsigned int i = 0; i < dofs_per_cell; ++i)
                {
                  const SymmetricTensor<2, dim> stress_i
                    = E * strains[i] * fe_values.JxW(q);
                  for (unsigned int j = 0; j <= i; ++j)
                    cell_matrix(i, j) += stress_i * strains[j];
                }
            }
          for (unsigned int i = 0; i < dofs_per_cell; ++i)
            for (unsigned int j = i + 1; j < dofs_per_cell; ++j)
              cell_matrix(i, j) = cell_matrix(j, i);
          cell->get_dof_indices(local_dof_indices);
          constraints.distribute_local_to_global(cell_matrix,
                                                 local_dof_indices,
                                                 stiffness_matrix);
        }
    stiffness_matrix.compress(VectorOperation::add);
    ++n_operator_assemblies;
  }



  // @sect4{DistributedViscoplasticContact::setup_preconditioner}
  //
  // The preconditioner of the constant elastic operator, built once per run
  // and used by every CG solve of every active-set iteration.
  //  - amg: ML smoothed aggregation. Elasticity needs the near-null space of
  //    K without Dirichlet conditions, the dim translations and the
  //    dim(dim-1)/2 infinitesimal rotations, given to ML per locally owned
  //    dof (deal.II 9.4's AdditionalData only takes translations, so the
  //    parameter list is completed by hand).
  //  - direct: a MUMPS factorisation of K (distributed), for small runs.
  template <int dim>
  void
  DistributedViscoplasticContact<dim>::setup_preconditioner()
  {
    TimerOutput::Scope t(computing_timer, "Setup: preconditioner");
    if (parameters.preconditioner == "direct")
      {
        direct_solver = std::make_unique<TrilinosWrappers::SolverDirect>(
          direct_solver_control,
          TrilinosWrappers::SolverDirect::AdditionalData(false,
                                                         "Amesos_Mumps"));
        direct_solver->initialize(stiffness_matrix);
        ++n_preconditioner_setups;
        return;
      }

    // Support point and component of every locally owned dof.
    std::map<types::global_dof_index, Point<dim>> support_points;
    DoFTools::map_dofs_to_support_points(*mapping, dof_handler, support_points);
    std::vector<IndexSet> component_dofs(dim);
    for (unsigned int c = 0; c < dim; ++c)
      component_dofs[c]
        = DoFTools::extract_dofs(dof_handler,
                                 fe->component_mask(
                                   FEValuesExtractors::Scalar(c)));

    const unsigned int n_modes = (dim == 2 ? 3 : 6);
    const Epetra_Map  &row_map = stiffness_matrix.trilinos_matrix().RowMap();
    rigid_body_modes = std::make_unique<Epetra_MultiVector>(row_map, n_modes);
    for (int local = 0; local < row_map.NumMyElements(); ++local)
      {
        const types::global_dof_index dof = row_map.GID64(local);
        unsigned int                  c   = 0;
        while (c < dim && !component_dofs[c].is_element(dof))
          ++c;
        Assert(c < dim, ExcInternalError());
        const Point<dim> &x           = support_points[dof];
        (*rigid_body_modes)[c][local] = 1.; // translation in direction c
        if (dim == 2)
          (*rigid_body_modes)[2][local] = (c == 0 ? -x[1] : x[0]);
        else
          {
            // Rotations about the x, y and z axes: e_d x x, component c.
            const unsigned int c1 = (c + 1) % 3, c2 = (c + 2) % 3;
            for (unsigned int d = 0; d < 3; ++d)
              (*rigid_body_modes)[3 + d][local]
                = (d == c2 ? x[c1] : (d == c1 ? -x[c2] : 0.));
          }
      }

    TrilinosWrappers::PreconditionAMG::AdditionalData data;
    data.elliptic              = true;
    data.higher_order_elements = false;
    data.smoother_sweeps       = 2;
    data.aggregation_threshold = 0.02;
    Teuchos::ParameterList              ml_parameters;
    std::unique_ptr<Epetra_MultiVector> unused_constant_modes;
    data.set_parameters(ml_parameters, unused_constant_modes, stiffness_matrix);
    ml_parameters.set("null space: type", "pre-computed");
    ml_parameters.set("null space: dimension", int(n_modes));
    ml_parameters.set("null space: vectors", rigid_body_modes->Values());
    amg_preconditioner.initialize(stiffness_matrix, ml_parameters);
    ++n_preconditioner_setups;
  }



  // @sect4{DistributedViscoplasticContact::setup_contact}
  //
  // The lumped weights w_i = int_Gamma3 phi_i and the mean outward normals
  // are assembled like a right-hand side (each rank adds its faces, the
  // owners of the dofs receive the sums), so a node shared by faces of
  // several ranks gets the same weight and normal on any number of ranks.
  // The contact nodes of this rank are the locally owned, unconstrained
  // vertices of Gamma_3 (the clamped corner and hanging nodes are not
  // contact nodes); a vertex whose Gamma_3 faces all belong to ghost cells
  // is found through those ghost cells.
  template <int dim>
  void
  DistributedViscoplasticContact<dim>::setup_contact()
  {
    contact_law.emplace(ContactLaw::from_parameters(parameters));
    contact_enabled
      = !parameters.contact_ids.empty() && !contact_law->is_void();
    if (!contact_enabled)
      return;
    TimerOutput::Scope t(computing_timer, "Setup: contact nodes");

    const auto on_contact_boundary = [&](const auto &face) {
      return face->at_boundary()
             && std::find(parameters.contact_ids.begin(),
                          parameters.contact_ids.end(),
                          face->boundary_id())
                  != parameters.contact_ids.end();
    };

    TrilinosWrappers::MPI::Vector weights(locally_owned_dofs, mpi_communicator);
    TrilinosWrappers::MPI::Vector weighted_normals(locally_owned_dofs,
                                                   mpi_communicator);
    FEFaceValues<dim>             fe_face_values(*mapping,
                                     *fe,
                                     face_quadrature,
                                     update_values | update_JxW_values
                                       | update_normal_vectors);
    const unsigned int            dofs_per_cell = fe->n_dofs_per_cell();
    std::vector<types::global_dof_index> local_dof_indices(dofs_per_cell);
    Vector<double>                       cell_weights(dofs_per_cell);
    Vector<double>                       cell_normals(dofs_per_cell);
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
        for (const unsigned int f : cell->face_indices())
          if (on_contact_boundary(cell->face(f)))
            {
              fe_face_values.reinit(cell, f);
              cell_weights = 0;
              cell_normals = 0;
              for (const unsigned int q :
                   fe_face_values.quadrature_point_indices())
                for (unsigned int i = 0; i < dofs_per_cell; ++i)
                  {
                    const unsigned int c
                      = fe->system_to_component_index(i).first;
                    const double phi_JxW = fe_face_values.shape_value(i, q)
                                           * fe_face_values.JxW(q);
                    cell_weights(i) += phi_JxW;
                    cell_normals(i)
                      += phi_JxW * fe_face_values.normal_vector(q)[c];
                  }
              cell->get_dof_indices(local_dof_indices);
              weights.add(local_dof_indices, cell_weights);
              weighted_normals.add(local_dof_indices, cell_normals);
            }
    weights.compress(VectorOperation::add);
    weighted_normals.compress(VectorOperation::add);

    const double softening = contact_law->steepest_softening();
    std::set<types::global_dof_index> seen;
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (!cell->is_artificial())
        for (const unsigned int f : cell->face_indices())
          if (on_contact_boundary(cell->face(f)))
            for (const unsigned int v : cell->face(f)->vertex_indices())
              {
                DistributedContactNode<dim> node;
                for (unsigned int c = 0; c < dim; ++c)
                  node.dofs[c] = cell->face(f)->vertex_dof_index(v, c);
                bool usable = locally_owned_dofs.is_element(node.dofs[0])
                              && seen.insert(node.dofs[0]).second;
                for (unsigned int c = 0; c < dim; ++c)
                  usable = usable && !constraints.is_constrained(node.dofs[c]);
                if (!usable)
                  continue;
                node.location = cell->face(f)->vertex(v);
                node.weight   = weights[node.dofs[0]];
                for (unsigned int c = 0; c < dim; ++c)
                  node.normal[c] = weighted_normals[node.dofs[c]];
                node.normal /= node.normal.norm();
                // c scaled like the normal stiffness of the node per unit
                // weight, as step-41/42 scale it with the diagonal of K.
                double normal_stiffness = 0;
                for (unsigned int a = 0; a < dim; ++a)
                  for (unsigned int b = 0; b < dim; ++b)
                    normal_stiffness
                      += node.normal[a] * node.normal[b]
                         * stiffness_matrix.el(node.dofs[a], node.dofs[b]);
                node.c
                  = std::max(normal_stiffness / node.weight, 2 * softening);
                node.piece = contact_law->find_piece(0., node.c);
                contact_nodes.push_back(node);
              }
    n_global_contact_nodes
      = Utilities::MPI::sum<types::global_dof_index>(contact_nodes.size(),
                                                     mpi_communicator);
    AssertThrow(n_global_contact_nodes > 0,
                ExcMessage("Invalid parameter <Contact boundary ids> in "
                           "subsection <Boundary>: Gamma_3 has no node that "
                           "is free to move (all its nodes are clamped); "
                           "accepted: ids of boundary parts with at least "
                           "one node off Gamma_1."));
  }



  // @sect4{DistributedViscoplasticContact::setup_stress_points}
  //
  // sigma_0 = 0, H_1 = 0 at the stress points of the locally owned cells.
  template <int dim>
  void
  DistributedViscoplasticContact<dim>::setup_stress_points()
  {
    quadrature_point_history.assign(std::size_t(triangulation->n_active_cells())
                                      * stress_quadrature.size(),
                                    QuadraturePointHistory<dim>());
  }



  template class DistributedViscoplasticContact<2>;
  template class DistributedViscoplasticContact<3>;
} // namespace ViscoContact
