// The set-up phase of ViscoplasticContact<dim>: mesh, finite element,
// constraints, the elastic operator (assembled and factorised once), the
// contact nodes with their condensed compliance, and the stress points.

#include <deal.II/base/exceptions.h>
#include <deal.II/base/utilities.h>

#include <deal.II/dofs/dof_tools.h>

#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_simplex_p.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/fe/fe_values.h>

#include <deal.II/grid/grid_generator.h>

#include <deal.II/lac/dynamic_sparsity_pattern.h>

#include <deal.II/numerics/vector_tools.h>

#include "loads.h"
#include "mesh.h"
#include "viscoplastic_contact.h"

#include <algorithm>
#include <regex>
#include <sstream>

namespace ViscoContact
{



  // @sect4{ViscoplasticContact::ViscoplasticContact}
  //
  // The choice between simplices and hypercubes is made here, once: the
  // reference cell gives the mapping and the quadratures, and everything
  // else in the program is written for either. On simplices the P1 strain
  // is constant per cell and one stress point per cell is the piecewise-
  // constant stress space Q^h; on hypercubes the stresses live at the
  // 2^dim Gauss points.
  template <int dim>
  ViscoplasticContact<dim>::ViscoplasticContact(
    const Parameters::AllParameters &parameters)
    : parameters(parameters)
    , pcout(std::cout)
    , computing_timer(pcout, TimerOutput::never, TimerOutput::wall_times)
    , reference_cell(parameters.cell_type == "simplex"
                       ? ReferenceCells::get_simplex<dim>()
                       : ReferenceCells::get_hypercube<dim>())
    , mapping(&reference_cell.template get_default_linear_mapping<dim>())
    , fe(reference_cell.is_simplex()
           ? std::make_unique<FESystem<dim>>(FE_SimplexP<dim>(1), dim)
           : std::make_unique<FESystem<dim>>(FE_Q<dim>(1), dim))
    , scalar_fe(
        reference_cell.is_simplex()
          ? std::unique_ptr<FiniteElement<dim>>(
            std::make_unique<FE_SimplexP<dim>>(1))
          : std::unique_ptr<FiniteElement<dim>>(std::make_unique<FE_Q<dim>>(1)))
    , dof_handler(triangulation)
    , scalar_dof_handler(triangulation)
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
    , contact_enabled(false)
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
    body_force_is_zero   = is_zero_expression(parameters.body_force);
    loads_depend_on_time = mentions_time(parameters.body_force)
                           || mentions_time(parameters.surface_traction);
  }



  // @sect4{ViscoplasticContact::make_grid}
  //
  // The mesh of mesh.cc (the generated box or a Gmsh file, refined as the
  // parameter file says), with the named boundary parts checked.
  template <int dim>
  void
  ViscoplasticContact<dim>::make_grid()
  {
    TimerOutput::Scope t(computing_timer, "Setup: mesh");
    create_coarse_mesh(parameters, triangulation);
    refine_mesh(parameters, triangulation);
    check_boundary_ids(parameters, triangulation, MPI_COMM_SELF);
  }



  // @sect4{ViscoplasticContact::setup_system}
  //
  // Degrees of freedom, the clamping of Gamma_1 as constraints, the sparsity
  // pattern, and then the elastic operator, which the explicit scheme never
  // changes.
  template <int dim>
  void
  ViscoplasticContact<dim>::setup_system()
  {
    {
      TimerOutput::Scope t(computing_timer, "Setup: dofs and constraints");
      dof_handler.distribute_dofs(*fe);
      scalar_dof_handler.distribute_dofs(*scalar_fe);

      constraints.clear();
      DoFTools::make_hanging_node_constraints(dof_handler, constraints);
      for (const auto id : parameters.clamped_ids)
        VectorTools::interpolate_boundary_values(*mapping,
                                                 dof_handler,
                                                 id,
                                                 Functions::ZeroFunction<dim>(
                                                   dim),
                                                 constraints);
      constraints.close();

      DynamicSparsityPattern dsp(dof_handler.n_dofs());
      DoFTools::make_sparsity_pattern(dof_handler,
                                      dsp,
                                      constraints,
                                      /*keep_constrained_dofs=*/false);
      sparsity_pattern.copy_from(dsp);
      stiffness_matrix.reinit(sparsity_pattern);
      if (parameters.stress_update == "implicit")
        {
          tangent_matrix.reinit(sparsity_pattern);
          internal_force.reinit(dof_handler.n_dofs());
        }

      solution.reinit(dof_handler.n_dofs());
      external_load.reinit(dof_handler.n_dofs());
      history_load.reinit(dof_handler.n_dofs());
      system_rhs.reinit(dof_handler.n_dofs());
      contact_response.reinit(dof_handler.n_dofs());
    }
    assemble_elastic_operator();
  }



  // @sect4{ViscoplasticContact::assemble_elastic_operator}
  //
  // K_ij = (E eps(phi_j), eps(phi_i)), with the Dirichlet rows condensed,
  // followed by the one LU factorisation of the run. Both counts are kept
  // and printed, so that a change that re-assembles or re-factorises per
  // step shows up in the run summary (and fails a test).
  template <int dim>
  void
  ViscoplasticContact<dim>::assemble_elastic_operator()
  {
    {
      TimerOutput::Scope t(computing_timer, "Setup: assemble elastic operator");
      FEValues<dim>      fe_values(*mapping,
                              *fe,
                              stress_quadrature,
                              update_gradients | update_JxW_values);
      const FEValuesExtractors::Vector displacement(0);
      const unsigned int               dofs_per_cell = fe->n_dofs_per_cell();
      FullMatrix<double> cell_matrix(dofs_per_cell, dofs_per_cell);
      std::vector<types::global_dof_index> local_dof_indices(dofs_per_cell);
      std::vector<SymmetricTensor<2, dim>> strain(dofs_per_cell);
      const SymmetricTensor<4, dim>       &E = material.elasticity_tensor();

      for (const auto &cell : dof_handler.active_cell_iterators())
        {
          fe_values.reinit(cell);
          cell_matrix = 0;
          for (const unsigned int q : fe_values.quadrature_point_indices())
            {
              for (unsigned int i = 0; i < dofs_per_cell; ++i)
                strain[i] = fe_values[displacement].symmetric_gradient(i, q);
              for (unsigned int i = 0; i < dofs_per_cell; ++i)
                {
                  const SymmetricTensor<2, dim> E_strain_i = E * strain[i];
                  for (unsigned int j = 0; j <= i; ++j)
                    cell_matrix(i, j)
                      += (E_strain_i * strain[j]) * fe_values.JxW(q);
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
      ++n_operator_assemblies;
    }
    {
      TimerOutput::Scope t(computing_timer,
                           "Setup: factorise elastic operator");
      if (parameters.direct_solver == "cholmod")
        cholesky_factorization.factorize(stiffness_matrix);
      else
        lu_factorization.initialize(stiffness_matrix);
      ++n_operator_factorizations;
    }
  }



  // @sect4{ViscoplasticContact::solve_elastic}
  //
  // K^{-1} applied to one or several right-hand sides with the factorisation
  // of the run; every solve is counted.
  template <int dim>
  void
  ViscoplasticContact<dim>::solve_elastic(Vector<double> &rhs_and_solution)
  {
    if (parameters.direct_solver == "cholmod")
      cholesky_factorization.solve(rhs_and_solution);
    else
      lu_factorization.solve(rhs_and_solution);
    ++n_elastic_solves;
  }



  template <int dim>
  void
  ViscoplasticContact<dim>::solve_elastic(std::vector<double> &columns,
                                          const unsigned int   n_columns)
  {
    const unsigned int n = dof_handler.n_dofs();
    if (parameters.direct_solver == "cholmod")
      {
        cholesky_factorization.solve(columns, n_columns);
        n_elastic_solves += n_columns;
      }
    else
      for (unsigned int j = 0; j < n_columns; ++j)
        {
          Vector<double> column(columns.begin() + std::size_t(j) * n,
                                columns.begin() + std::size_t(j + 1) * n);
          solve_elastic(column);
          std::copy(column.begin(),
                    column.end(),
                    columns.begin() + std::size_t(j) * n);
        }
  }



  // @sect4{lumped_boundary_weights}
  //
  // w_i = int_Gamma3 phi_i and the mean outward normal
  // int_Gamma3 phi_i nu / |int_Gamma3 phi_i nu| of every vertex on the given
  // boundary parts. With an exact face quadrature these are the row sums of
  // the boundary mass matrix, i.e. the lumped contact terms of model.md,
  // section 2, on any mesh; the normal is what makes a contact boundary that
  // is not axis-aligned work.
  template <int dim>
  std::map<unsigned int, BoundaryVertexData<dim>>
  lumped_boundary_weights(const Mapping<dim>        &mapping,
                          const DoFHandler<dim>     &dof_handler,
                          const Quadrature<dim - 1> &face_quadrature,
                          const std::vector<types::boundary_id> &boundary_ids)
  {
    const FiniteElement<dim>                       &fe = dof_handler.get_fe();
    FEFaceValues<dim>                               fe_face_values(mapping,
                                     fe,
                                     face_quadrature,
                                     update_values | update_JxW_values
                                       | update_normal_vectors);
    std::map<unsigned int, BoundaryVertexData<dim>> vertices;
    for (const auto &cell : dof_handler.active_cell_iterators())
      for (const unsigned int f : cell->face_indices())
        if (cell->face(f)->at_boundary()
            && std::find(boundary_ids.begin(),
                         boundary_ids.end(),
                         cell->face(f)->boundary_id())
                 != boundary_ids.end())
          {
            fe_face_values.reinit(cell, f);
            for (const unsigned int v : cell->face(f)->vertex_indices())
              {
                const unsigned int vertex      = cell->face(f)->vertex_index(v);
                unsigned int       cell_vertex = numbers::invalid_unsigned_int;
                for (const unsigned int cv : cell->vertex_indices())
                  if (cell->vertex_index(cv) == vertex)
                    cell_vertex = cv;
                Assert(cell_vertex != numbers::invalid_unsigned_int,
                       ExcInternalError());
                // The x-component shape function of this vertex (P1 and Q1
                // number their dofs vertex by vertex).
                const unsigned int i
                  = fe.component_to_system_index(0, cell_vertex);

                BoundaryVertexData<dim> &data = vertices[vertex];
                data.location                 = cell->vertex(cell_vertex);
                for (const unsigned int q :
                     fe_face_values.quadrature_point_indices())
                  {
                    const double phi_JxW = fe_face_values.shape_value(i, q)
                                           * fe_face_values.JxW(q);
                    data.weight += phi_JxW;
                    data.normal += phi_JxW * fe_face_values.normal_vector(q);
                  }
              }
          }
    for (auto &vertex : vertices)
      vertex.second.normal /= vertex.second.normal.norm();
    return vertices;
  }



  // @sect4{ViscoplasticContact::setup_contact}
  //
  // The contact nodes are the vertices of Gamma_3 that are not clamped (the
  // corner shared with Gamma_1 is not one). The condensed contact compliance
  // S_ij = nu_i . (K^{-1} N^T e_j)_i costs one solve with the factorised
  // operator per contact node, once per run; afterwards a contact iteration
  // never touches the bulk unknowns.
  template <int dim>
  void
  ViscoplasticContact<dim>::setup_contact()
  {
    const ContactLaw law = ContactLaw::from_parameters(parameters);
    contact_enabled      = !parameters.contact_ids.empty() && !law.is_void();
    if (!contact_enabled)
      return;

    {
      TimerOutput::Scope t(computing_timer, "Setup: contact nodes");
      const auto         vertices = lumped_boundary_weights(*mapping,
                                                    dof_handler,
                                                    face_quadrature,
                                                    parameters.contact_ids);

      // Each vertex's dofs, found through any cell that has it.
      std::map<unsigned int, std::array<types::global_dof_index, dim>> dofs;
      std::map<unsigned int, types::global_dof_index> scalar_dofs;
      auto scalar_cell = scalar_dof_handler.begin_active();
      for (const auto &cell : dof_handler.active_cell_iterators())
        {
          for (const unsigned int v : cell->vertex_indices())
            if (vertices.count(cell->vertex_index(v)) == 1)
              {
                for (unsigned int c = 0; c < dim; ++c)
                  dofs[cell->vertex_index(v)][c] = cell->vertex_dof_index(v, c);
                scalar_dofs[cell->vertex_index(v)]
                  = scalar_cell->vertex_dof_index(v, 0);
              }
          ++scalar_cell;
        }

      contact_nodes.clear();
      for (const auto &vertex : vertices)
        {
          const auto &node_dofs = dofs.at(vertex.first);
          bool        clamped   = false;
          for (const auto dof : node_dofs)
            clamped = clamped || constraints.is_constrained(dof);
          if (clamped)
            continue;
          contact_nodes.push_back({vertex.second.location,
                                   vertex.second.normal,
                                   vertex.second.weight,
                                   node_dofs,
                                   scalar_dofs.at(vertex.first)});
        }
      // Order the nodes along Gamma_3 (lexicographically), which is the order
      // of the contact profiles.
      std::sort(contact_nodes.begin(),
                contact_nodes.end(),
                [](const ContactNode<dim> &a, const ContactNode<dim> &b) {
                  for (unsigned int d = 0; d < dim; ++d)
                    if (std::abs(a.location[d] - b.location[d]) > 1e-12)
                      return a.location[d] < b.location[d];
                  return false;
                });
      AssertThrow(!contact_nodes.empty(),
                  ExcMessage(
                    "Gamma_3 (Contact boundary ids) has no node that "
                    "is free to move: every contact node is clamped."));
    }

    {
      TimerOutput::Scope t(computing_timer, "Setup: contact compliance");
      const unsigned int m = contact_nodes.size();
      const unsigned int n = dof_handler.n_dofs();
      // Keep W = K^{-1} N^T if it takes less than 1 GiB.
      // (The implicit scheme recomputes its own per Newton iteration.)
      contact_responses_stored = parameters.stress_update == "explicit"
                                 && (8. * n * m < 1024. * 1024. * 1024.);
      if (contact_responses_stored)
        contact_responses.reinit(n, m);

      // Columns of W = K^{-1} N^T in blocks of up to 64 right-hand sides.
      FullMatrix<double>  compliance(m, m);
      const unsigned int  block = 64;
      std::vector<double> columns;
      for (unsigned int first = 0; first < m; first += block)
        {
          const unsigned int n_columns = std::min(block, m - first);
          columns.assign(std::size_t(n) * n_columns, 0.);
          for (unsigned int j = 0; j < n_columns; ++j)
            for (unsigned int c = 0; c < dim; ++c)
              columns[std::size_t(j) * n + contact_nodes[first + j].dofs[c]]
                = contact_nodes[first + j].normal[c];
          solve_elastic(columns, n_columns);
          for (unsigned int j = 0; j < n_columns; ++j)
            {
              const double *response = &columns[std::size_t(j) * n];
              for (unsigned int i = 0; i < m; ++i)
                for (unsigned int c = 0; c < dim; ++c)
                  compliance(i, first + j)
                    += contact_nodes[i].normal[c]
                       * response[contact_nodes[i].dofs[c]];
              if (contact_responses_stored)
                for (unsigned int k = 0; k < n; ++k)
                  contact_responses(k, first + j) = response[k];
            }
        }
      // S is symmetric in exact arithmetic; make it so in floating point.
      for (unsigned int i = 0; i < m; ++i)
        for (unsigned int j = 0; j < i; ++j)
          compliance(i, j) = compliance(j, i)
            = 0.5 * (compliance(i, j) + compliance(j, i));

      std::vector<double> weights(m);
      for (unsigned int i = 0; i < m; ++i)
        weights[i] = contact_nodes[i].weight;
      active_set_solver.reinit(law, compliance, weights);

      // min_v a(v,v) / sum_i w_i (v . nu_i)^2: for given normal displacements
      // r the smallest energy is r^T S^{-1} r (the harmonic extension), so
      // the minimum is 1 / lambda_max(W^{1/2} S W^{1/2}), W = diag(w).
      LAPACKFullMatrix<double> scaled(m, m);
      for (unsigned int i = 0; i < m; ++i)
        for (unsigned int j = 0; j < m; ++j)
          scaled(i, j) = std::sqrt(weights[i] * weights[j]) * compliance(i, j);
      scaled.compute_eigenvalues();
      double largest = 0;
      for (unsigned int i = 0; i < m; ++i)
        largest = std::max(largest, scaled.eigenvalue(i).real());
      uniqueness_eigenvalue = 1. / largest;
    }
  }



  // @sect4{ViscoplasticContact::report_scheme_limits}
  //
  // Where the method may fail, said before the run starts (model.md,
  // sections 3 and 4): the explicit history update is forward Euler on a
  // relaxation with rate up to lambda_max(E)/(2 lambda), stable for
  // k < 4 lambda / lambda_max(E); and the step problem has a unique solution
  // (its energy is strongly convex) iff the smallest generalised eigenvalue
  // of stiffness against the lumped normal boundary mass exceeds the
  // steepest softening of the contact law.
  template <int dim>
  void
  ViscoplasticContact<dim>::report_scheme_limits() const
  {
    if (parameters.plasticity && parameters.stress_update == "implicit")
      pcout << "Implicit (backward-Euler) history update: no stability limit "
               "on k (model.md, section 3); k = "
            << parameters.time_step << " s\n";
    else if (parameters.plasticity)
      {
        const double bound
          = 4 * material.viscosity() / material.largest_elastic_eigenvalue();
        pcout << "Explicit history update: stable for k < 4 lambda / "
                 "lambda_max(E) = "
              << bound << " s; k = " << parameters.time_step << " s\n";
        if (parameters.time_step >= bound)
          pcout << "WARNING: the time step exceeds the stability limit of the "
                   "explicit history update (model.md, section 3): the "
                   "stresses may oscillate or blow up.\n";
      }
    if (contact_enabled)
      {
        const double softening = active_set_solver.law().steepest_softening();
        pcout << "Uniqueness: smallest eigenvalue of (stiffness, lumped "
                 "normal boundary mass) = "
              << uniqueness_eigenvalue
              << ", steepest softening of the contact law = " << softening
              << '\n';
        if (uniqueness_eigenvalue <= softening)
          pcout << "WARNING: the contact law softens more than the body can "
                   "carry (model.md, section 4): the step problem may have "
                   "several solutions and the active-set iteration may "
                   "cycle.\n";
      }
  }



  // @sect4{ViscoplasticContact::setup_quadrature_point_history}
  //
  // One record per stress point, in a flat array indexed by the active cell
  // index, as step-18 does; sigma_0 = 0 and u_0 = 0, so H_1 = 0. Alongside,
  // the stress-point geometry the time loop uses instead of FEValues.
  template <int dim>
  void
  ViscoplasticContact<dim>::setup_quadrature_point_history()
  {
    TimerOutput::Scope t(computing_timer, "Setup: stress points");
    const unsigned int n_cells = triangulation.n_active_cells();
    const unsigned int n_q     = stress_quadrature.size();
    quadrature_point_history.assign(n_cells * n_q,
                                    QuadraturePointHistory<dim>());

    n_cell_vertices = scalar_fe->n_dofs_per_cell();
    cell_dof_indices.resize(std::size_t(n_cells) * n_cell_vertices * dim);
    stress_point_gradients.resize(std::size_t(n_cells) * n_q * n_cell_vertices);
    stress_point_JxW.resize(std::size_t(n_cells) * n_q);

    FEValues<dim>                        fe_values(*mapping,
                            *fe,
                            stress_quadrature,
                            update_gradients | update_JxW_values);
    std::vector<types::global_dof_index> local_dof_indices(
      fe->n_dofs_per_cell());
    for (const auto &cell : dof_handler.active_cell_iterators())
      {
        const std::size_t c = cell->active_cell_index();
        fe_values.reinit(cell);
        cell->get_dof_indices(local_dof_indices);
        for (unsigned int a = 0; a < n_cell_vertices; ++a)
          for (unsigned int d = 0; d < dim; ++d)
            cell_dof_indices[(c * n_cell_vertices + a) * dim + d]
              = local_dof_indices[fe->component_to_system_index(d, a)];
        for (unsigned int q = 0; q < n_q; ++q)
          {
            stress_point_JxW[c * n_q + q] = fe_values.JxW(q);
            for (unsigned int a = 0; a < n_cell_vertices; ++a)
              stress_point_gradients[(c * n_q + q) * n_cell_vertices + a]
                = fe_values.shape_grad_component(
                  fe->component_to_system_index(0, a),
                  q,
                  0);
          }
      }
  }



  template std::map<unsigned int, BoundaryVertexData<2>>
  lumped_boundary_weights(const Mapping<2> &,
                          const DoFHandler<2> &,
                          const Quadrature<1> &,
                          const std::vector<types::boundary_id> &);
  template std::map<unsigned int, BoundaryVertexData<3>>
  lumped_boundary_weights(const Mapping<3> &,
                          const DoFHandler<3> &,
                          const Quadrature<2> &,
                          const std::vector<types::boundary_id> &);
  template class ViscoplasticContact<2>;
  template class ViscoplasticContact<3>;
} // namespace ViscoContact
