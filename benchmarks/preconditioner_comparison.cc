// benchmarks/preconditioner_comparison.cc: one elastic solve K u = b of a
// scene of the program, by CG to the scene's Tolerance, with each of several
// preconditioners in turn: ML's smoothed aggregation (as the full space back
// end configures it, and with other settings), hypre's BoomerAMG through
// PETSc (with and without its options for systems of PDEs), and the
// matrix-free back end's geometric multigrid (global coarsening of the
// p4est hexahedral mesh, matrix_free_elasticity.h). For each it
// reports the set-up time, the solve time, the CG iterations and the memory
// the preconditioner took, and checks that every preconditioner gives the
// same solution.
//
//   preconditioner_comparison SCENE.prm N VARIANT [VARIANT...]
//
// SCENE.prm is a parameter file of the program (its mesh, material, boundary
// parts, loads and Tolerance are used; Subdivisions is replaced by N), and
// each VARIANT is a preconditioner written as "ml:KEY=VALUE,...",
// "hypre:KEY=VALUE,..." or "gmg:KEY=VALUE,..." (the keys are listed at
// solve_with_ml(), solve_with_hypre() and solve_with_gmg() below). One line per
// variant starts with "RESULT" and has tab-separated fields;
// benchmarks/run_preconditioner_comparison.py runs the program and writes
// doc/performance/preconditioners.md from them.
//
// The mesh, the element and the quadrature are those of the program
// (create_distributed_mesh() of the project's library, Q1 or P1, the stress
// quadrature), and so is the operator: K_ij = (E eps(phi_j), eps(phi_i)) with
// the clamped dofs condensed, assembled by the program's own
// assemble_elastic_operator() (elastic_operator.h). The right-hand side is
// the external load of the scene at t = 0 (the surface traction on the
// loaded boundary and the body force).

#include <deal.II/base/function_parser.h>
#include <deal.II/base/index_set.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/quadrature.h>
#include <deal.II/base/timer.h>
#include <deal.II/base/utilities.h>

#include <deal.II/distributed/tria_base.h>

#include <deal.II/dofs/dof_handler.h>
#include <deal.II/dofs/dof_tools.h>

#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_simplex_p.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/fe/mapping.h>

#include <deal.II/grid/reference_cell.h>

#include <deal.II/distributed/tria.h>

#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/diagonal_matrix.h>
#include <deal.II/lac/precondition.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/la_parallel_vector.h>
#include <deal.II/lac/petsc_vector.h>
#include <deal.II/lac/solver_cg.h>
#include <deal.II/lac/solver_control.h>
#include <deal.II/lac/sparsity_tools.h>
#include <deal.II/lac/trilinos_precondition.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>



#include <deal.II/numerics/vector_tools.h>

#include "back_ends/blas_threads.h"
#include "back_ends/rigid_body_modes.h"
#include "constraints.h"
#include "elastic_operator.h"
#include "scene/loads.h"
#include "back_ends/matrix_free_elasticity.h"
#include "material.h"
#include "mesh/mesh.h"
#include "parameters.h"

#include <Epetra_CrsMatrix.h>
#include <Epetra_Map.h>
#include <Epetra_MultiVector.h>
#include <Teuchos_ParameterList.hpp>
#include <malloc.h>
#include <petscmat.h>
#include <petscpc.h>

#include <fstream>
#include <iomanip>
#include <iostream>
#include <map>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

namespace PreconditionerComparison
{
  using namespace dealii;
  using namespace ViscoContact;

  using VectorType      = LinearAlgebra::distributed::Vector<double>;
  using PETScVectorType = PETScWrappers::MPI::Vector;

  // @sect3{Small tools}
  //
  // The memory of the process now, in MB (resident pages), and the largest
  // it has been (VmHWM). The memory of a preconditioner is the growth of the
  // resident set over its set-up; malloc_trim() first returns what earlier
  // variants freed, so that the growth is not hidden by reused heap.
  double
  resident_mb()
  {
    malloc_trim(0);
    std::ifstream statm("/proc/self/statm");
    long          size = 0, resident = 0;
    statm >> size >> resident;
    return resident * (sysconf(_SC_PAGESIZE) / 1048576.);
  }

  double
  peak_mb()
  {
    std::ifstream in("/proc/self/status");
    std::string   line;
    while (std::getline(in, line))
      if (line.rfind("VmHWM:", 0) == 0)
        return std::stod(line.substr(6)) / 1024.;
    return 0;
  }

  // A variant "kind:key=value,key=value" as its kind and its map of keys.
  struct Variant
  {
    std::string                        name; // as given on the command line
    std::string                        kind; // ml, hypre or gmg
    std::map<std::string, std::string> keys;

    std::string
    get(const std::string &key, const std::string &fallback) const
    {
      const auto it = keys.find(key);
      return it == keys.end() ? fallback : it->second;
    }
  };

  Variant
  parse_variant(const std::string &text)
  {
    Variant    v;
    const auto colon = text.find(':');
    v.name           = text;
    v.kind           = text.substr(0, colon);
    AssertThrow(v.kind == "ml" || v.kind == "hypre" || v.kind == "gmg",
                ExcMessage("unknown preconditioner kind in <" + text + ">"));
    if (colon != std::string::npos)
      for (const std::string &pair :
           Utilities::split_string_list(text.substr(colon + 1), ','))
        {
          const auto equal = pair.find('=');
          AssertThrow(equal != std::string::npos,
                      ExcMessage("expected key=value, got <" + pair + ">"));
          v.keys[pair.substr(0, equal)] = pair.substr(equal + 1);
        }
    return v;
  }



  // @sect3{The elastic problem of a scene}
  //
  // Everything the preconditioners need: the operator K as a Trilinos matrix
  // (what the program's back end has), the right-hand side, the support
  // point of every locally owned dof and its vector component (for the
  // rigid-body modes and PETSc's coordinates), and the solution of the first
  // variant, against which the others are checked.
  template <int dim>
  class ElasticProblem
  {
  public:
    ElasticProblem(const Parameters::AllParameters &parameters,
                   const MPI_Comm                   communicator);

    void
    run(const std::vector<Variant> &variants,
        const std::string          &mesh_name,
        const unsigned int          N);

  private:
    void
    setup_and_assemble();
    // The rigid-body modes as ML wants them (the same construction as
    // FullSpaceContactSolver::build_amg()): translations, then rotations.
    void
    compute_rigid_body_modes();

    // One CG solve with ML (TrilinosWrappers) or hypre (PETSc) as
    // preconditioner; each returns set-up and solve time, iterations,
    // memory and the solution.
    struct Result
    {
      double       setup_time = 0, solve_time = 0, memory = 0;
      unsigned int iterations = 0;
      bool         converged  = true;
      std::string  note;
    };
    Result
    solve_with_ml(const Variant &variant, VectorType &u);
    Result
    solve_with_hypre(const Variant &variant, VectorType &u);
    Result
    solve_with_gmg(const Variant &variant, VectorType &u);
    // K copied into a PETSc matrix with the block size dim (a node's dim
    // dofs are consecutive in deal.II's numbering of a vector-valued Q1 or
    // P1 element), made once when the first hypre variant asks for it.
    void
    make_petsc_matrix();

    const Parameters::AllParameters &parameters;
    const MPI_Comm                   communicator;
    ConditionalOStream               pcout;

    std::unique_ptr<parallel::DistributedTriangulationBase<dim>> triangulation;
    ReferenceCell                                                reference_cell;
    const Mapping<dim>                                          &mapping;
    std::unique_ptr<FESystem<dim>>                               fe;
    DoFHandler<dim>                                              dof_handler;
    IndexSet                       locally_owned_dofs, locally_relevant_dofs;
    AffineConstraints<double>      constraints;
    TrilinosWrappers::SparseMatrix K;
    VectorType                     b;
    std::vector<Point<dim>>        owned_support_points; // per owned dof
    std::vector<unsigned int>      owned_components;     // per owned dof
    std::unique_ptr<Epetra_MultiVector> rigid_body_modes;
    double                              setup_time = 0, modes_time = 0;

    Mat    petsc_matrix      = nullptr;
    Vec    petsc_coordinates = nullptr; // for MatNullSpaceCreateRigidBody
    double petsc_copy_time   = 0;
  };



  template <int dim>
  ElasticProblem<dim>::ElasticProblem(
    const Parameters::AllParameters &parameters,
    const MPI_Comm                   communicator)
    : parameters(parameters)
    , communicator(communicator)
    , pcout(std::cout, Utilities::MPI::this_mpi_process(communicator) == 0)
    , reference_cell(parameters.cell_type == Parameters::CellType::simplex
                       ? ReferenceCells::get_simplex<dim>()
                       : ReferenceCells::get_hypercube<dim>())
    , mapping(reference_cell.template get_default_linear_mapping<dim>())
  {
    if (reference_cell.is_simplex())
      fe = std::make_unique<FESystem<dim>>(FE_SimplexP<dim>(1), dim);
    else
      fe = std::make_unique<FESystem<dim>>(FE_Q<dim>(1), dim);
  }



  // @sect4{ElasticProblem::setup_and_assemble}
  //
  // The mesh of the program, its dofs and constraints (clamped parts and
  // hanging nodes), and K and b, as setup.cc and assembly.cc build them.
  template <int dim>
  void
  ElasticProblem<dim>::setup_and_assemble()
  {
    Timer timer;
    // The program's mesh; on p4est with the level hierarchy that the
    // geometric multigrid needs (the active cells are the program's).
    triangulation = create_distributed_mesh<dim>(parameters,
                                                 communicator,
                                                 /*multigrid_hierarchy=*/true);
    dof_handler.reinit(*triangulation);
    dof_handler.distribute_dofs(*fe);
    locally_owned_dofs = dof_handler.locally_owned_dofs();
    DoFTools::extract_locally_relevant_dofs(dof_handler, locally_relevant_dofs);
    // The benchmark's scenes are clamped and loaded: no prescribed
    // displacements or symmetry planes.
    make_displacement_constraints(hp::MappingCollection<dim>(mapping),
                                  dof_handler,
                                  {DirichletPart{parameters.clamped_ids, {}}},
                                  {},
                                  locally_relevant_dofs,
                                  constraints);

    DynamicSparsityPattern dsp(locally_relevant_dofs);
    DoFTools::make_sparsity_pattern(dof_handler, dsp, constraints, false);
    SparsityTools::distribute_sparsity_pattern(dsp,
                                               locally_owned_dofs,
                                               communicator,
                                               locally_relevant_dofs);
    K.reinit(locally_owned_dofs, locally_owned_dofs, dsp, communicator);
    b.reinit(locally_owned_dofs, locally_relevant_dofs, communicator);

    // The operator with the stress quadrature, the loads with the load and
    // face quadratures of the program (ViscoplasticContact's constructor).
    const Quadrature<dim> stress_quadrature
      = reference_cell.template get_gauss_type_quadrature<dim>(
        reference_cell.is_simplex() ? 1 : 2);
    const Quadrature<dim> load_quadrature
      = reference_cell.template get_gauss_type_quadrature<dim>(2);
    const Quadrature<dim - 1> face_quadrature
      = reference_cell.face_reference_cell(0)
          .template get_gauss_type_quadrature<dim - 1>(2);
    FEValues<dim>       load_values(mapping,
                              *fe,
                              load_quadrature,
                              update_values | update_quadrature_points
                                | update_JxW_values);
    FEFaceValues<dim>   face_values(mapping,
                                  *fe,
                                  face_quadrature,
                                  update_values | update_quadrature_points
                                    | update_JxW_values);
    FunctionParser<dim> body_force(dim), traction(dim);
    initialize_load(body_force,
                    "Loads",
                    "Body force",
                    parameters.body_force,
                    parameters.lengths);
    initialize_load(traction,
                    "Loads",
                    "Surface traction",
                    parameters.surface_traction,
                    parameters.lengths);
    body_force.set_time(0);
    traction.set_time(0);
    const PerzynaMaterial<dim> material(parameters.young_modulus,
                                        parameters.poisson_ratio,
                                        parameters.viscosity,
                                        parameters.yield_stress);
    // K as the program assembles it; b by the loop below.
    assemble_elastic_operator<dim>(
      hp::MappingCollection<dim>(mapping),
      dof_handler,
      hp::QCollection<dim>(stress_quadrature),
      [&](const auto &) -> const auto & {
        return material.elasticity_tensor();
      },
      constraints,
      K);
    const unsigned int                   n = fe->n_dofs_per_cell();
    Vector<double>                       cell_rhs(n);
    std::vector<types::global_dof_index> dof_indices(n);
    Vector<double>                       load(dim);
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          cell_rhs = 0;
          load_values.reinit(cell);
          for (const unsigned int q : load_values.quadrature_point_indices())
            {
              body_force.vector_value(load_values.quadrature_point(q), load);
              for (unsigned int i = 0; i < n; ++i)
                cell_rhs(i) += load(fe->system_to_component_index(i).first)
                               * load_values.shape_value(i, q)
                               * load_values.JxW(q);
            }
          for (const auto &face : cell->face_iterators())
            if (face->at_boundary()
                && std::find(parameters.loaded_ids.begin(),
                             parameters.loaded_ids.end(),
                             face->boundary_id())
                     != parameters.loaded_ids.end())
              {
                face_values.reinit(cell, face);
                for (const unsigned int q :
                     face_values.quadrature_point_indices())
                  {
                    traction.vector_value(face_values.quadrature_point(q),
                                          load);
                    for (unsigned int i = 0; i < n; ++i)
                      cell_rhs(i)
                        += load(fe->system_to_component_index(i).first)
                           * face_values.shape_value(i, q) * face_values.JxW(q);
                  }
              }
          cell->get_dof_indices(dof_indices);
          constraints.distribute_local_to_global(cell_rhs, dof_indices, b);
        }
    b.compress(VectorOperation::add);

    // Support point and component of every owned dof.
    std::map<types::global_dof_index, Point<dim>> support_points;
    DoFTools::map_dofs_to_support_points(mapping, dof_handler, support_points);
    owned_support_points.resize(locally_owned_dofs.n_elements());
    owned_components.resize(locally_owned_dofs.n_elements(), dim);
    for (unsigned int c = 0; c < dim; ++c)
      {
        const IndexSet dofs
          = DoFTools::extract_dofs(dof_handler,
                                   fe->component_mask(
                                     FEValuesExtractors::Scalar(c)));
        for (const auto dof : dofs)
          if (locally_owned_dofs.is_element(dof))
            owned_components[locally_owned_dofs.index_within_set(dof)] = c;
      }
    for (unsigned int i = 0; i < owned_support_points.size(); ++i)
      owned_support_points[i]
        = support_points.at(locally_owned_dofs.nth_index_in_set(i));
    setup_time = timer.wall_time();
  }



  // @sect4{ElasticProblem::compute_rigid_body_modes}
  template <int dim>
  void
  ElasticProblem<dim>::compute_rigid_body_modes()
  {
    Timer              timer;
    const unsigned int n_modes = (dim == 2 ? 3 : 6);
    const Epetra_Map  &row_map = K.trilinos_matrix().RowMap();
    rigid_body_modes = std::make_unique<Epetra_MultiVector>(row_map, n_modes);
    for (int local = 0; local < row_map.NumMyElements(); ++local)
      {
        const unsigned int index
          = locally_owned_dofs.index_within_set(row_map.GID64(local));
        const unsigned int c     = owned_components[index];
        const Point<dim>  &x     = owned_support_points[index];
        const auto         modes = rigid_body_mode_components(c, x);
        for (unsigned int mode = 0; mode < modes.size(); ++mode)
          (*rigid_body_modes)[mode][local] = modes[mode];
      }
    modes_time = timer.wall_time();
  }



  // @sect4{ElasticProblem::solve_with_ml}
  //
  // The keys of an ML variant (the defaults are the settings of the
  // program's full space back end before this comparison):
  //  - thr: aggregation threshold (0.02);
  //  - smoother: cheb (Chebyshev, deal.II's default for elliptic problems),
  //    sgs (symmetric Gauss-Seidel) or ilu (cheb);
  //  - sweeps: the smoother's sweeps, the polynomial degree for Chebyshev
  //    (2);
  //  - coarse: klu (Amesos-KLU, deal.II's default) or smoother (a few
  //    smoother sweeps on the coarsest level) (klu);
  //  - modes: 6 (3 in 2D), the rigid-body modes, or 0: ML's default null
  //    space, the constant of every one of the "PDE equations" (6);
  //  - pde: ML's "PDE equations", the unknowns per node that ML amalgamates
  //    into one node of its aggregation graph (1: ML's default, every dof
  //    its own node, which is what deal.II 9.4's AdditionalData leaves);
  //  - agg: the aggregation scheme (ML's default for "SA", Uncoupled-MIS,
  //    or uncoupled, mis);
  //  - maxcoarse: "coarse: max size" (2000, deal.II's choice);
  //  - damping: "aggregation: damping factor" (ML: 4/3).
  template <int dim>
  typename ElasticProblem<dim>::Result
  ElasticProblem<dim>::solve_with_ml(const Variant &variant, VectorType &u)
  {
    TrilinosWrappers::PreconditionAMG::AdditionalData data;
    data.elliptic              = true;
    data.higher_order_elements = false;
    data.smoother_sweeps       = std::stoi(variant.get("sweeps", "2"));
    data.aggregation_threshold = std::stod(variant.get("thr", "0.02"));
    const std::string smoother = variant.get("smoother", "cheb");
    data.smoother_type         = (smoother == "cheb"  ? "Chebyshev"
                                  : smoother == "sgs" ? "symmetric Gauss-Seidel"
                                  : smoother == "ilu" ? "ILU"
                                                      : smoother.c_str());
    const std::string coarse   = variant.get("coarse", "klu");
    data.coarse_type = (coarse == "klu" ? "Amesos-KLU" : data.smoother_type);

    Teuchos::ParameterList              ml_parameters;
    std::unique_ptr<Epetra_MultiVector> unused_constant_modes;
    data.set_parameters(ml_parameters, unused_constant_modes, K);
    const int pde = std::stoi(variant.get("pde", "1"));
    ml_parameters.set("PDE equations", pde);
    if (variant.get("modes", "6") != "0")
      {
        ml_parameters.set("null space: type", "pre-computed");
        ml_parameters.set("null space: dimension",
                          rigid_body_modes->NumVectors());
        ml_parameters.set("null space: vectors", rigid_body_modes->Values());
      }
    if (variant.keys.count("agg"))
      ml_parameters.set("aggregation: type",
                        variant.get("agg", "") == "mis" ? "MIS" : "Uncoupled");
    if (variant.keys.count("maxcoarse"))
      ml_parameters.set("coarse: max size",
                        std::stoi(variant.get("maxcoarse", "")));
    if (variant.keys.count("damping"))
      ml_parameters.set("aggregation: damping factor",
                        std::stod(variant.get("damping", "")));
    if (coarse != "klu")
      ml_parameters.set("coarse: sweeps",
                        std::stoi(variant.get("coarsesweeps", "4")));

    Result                            result;
    const double                      before = resident_mb();
    Timer                             timer;
    TrilinosWrappers::PreconditionAMG amg;
    amg.initialize(K, ml_parameters);
    result.setup_time = timer.wall_time();
    result.memory     = resident_mb() - before;

    SolverControl control(10000, parameters.tolerance * b.l2_norm());
    u = 0;
    timer.restart();
    try
      {
        SolverCG<VectorType>(control).solve(K, u, b, amg);
      }
    catch (const SolverControl::NoConvergence &)
      {
        result.converged = false;
      }
    result.solve_time = timer.wall_time();
    result.iterations = control.last_step();
    {
      VectorType y(u);
      Timer      product_timer;
      for (unsigned int i = 0; i < 5; ++i)
        K.vmult(y, b);
      const double product = product_timer.wall_time() / 5;
      product_timer.restart();
      for (unsigned int i = 0; i < 5; ++i)
        amg.vmult(y, b);
      result.note = "K " + std::to_string(1e3 * product) + " ms, cycle "
                    + std::to_string(1e3 * product_timer.wall_time() / 5)
                    + " ms";
    }
    return result;
  }



  // @sect4{ElasticProblem::make_petsc_matrix}
  //
  // PETSc's AIJ matrix with the rows of K, preallocated from them, and block
  // size dim, which PCHYPRE passes to BoomerAMG as its number of functions
  // (the unknown-based approach for systems). deal.II 9.4's PETSc matrix
  // cannot be given a block size before its preallocation, so the Mat is
  // made here with PETSc's C interface. The coordinates of the dofs, laid out
  // like the rows with block size dim, give MatNullSpaceCreateRigidBody().
  template <int dim>
  void
  ElasticProblem<dim>::make_petsc_matrix()
  {
    Timer                   timer;
    const Epetra_CrsMatrix &A       = K.trilinos_matrix();
    const PetscInt          n_local = A.NumMyRows();
    const PetscInt          first   = locally_owned_dofs.nth_index_in_set(0),
                   last             = first + n_local;
    AssertThrow(locally_owned_dofs.is_contiguous() && n_local % dim == 0,
                ExcMessage("hypre needs contiguous node-wise blocks"));
    std::vector<PetscInt> diagonal_nnz(n_local), off_nnz(n_local);
    for (PetscInt row = 0; row < n_local; ++row)
      {
        int     n_entries;
        double *values;
        int    *columns;
        A.ExtractMyRowView(row, n_entries, values, columns);
        for (int k = 0; k < n_entries; ++k)
          {
            const PetscInt col = A.ColMap().GID64(columns[k]);
            ++((col >= first && col < last) ? diagonal_nnz : off_nnz)[row];
          }
      }
    PetscErrorCode ierr = MatCreate(communicator, &petsc_matrix);
    ierr |= MatSetSizes(petsc_matrix,
                        n_local,
                        n_local,
                        PETSC_DETERMINE,
                        PETSC_DETERMINE);
    ierr |= MatSetBlockSize(petsc_matrix, dim);
    ierr |= MatSetType(petsc_matrix, MATAIJ);
    ierr |= MatSeqAIJSetPreallocation(petsc_matrix, 0, diagonal_nnz.data());
    ierr |= MatMPIAIJSetPreallocation(petsc_matrix,
                                      0,
                                      diagonal_nnz.data(),
                                      0,
                                      off_nnz.data());
    std::vector<PetscInt> global_columns;
    for (PetscInt row = 0; row < n_local; ++row)
      {
        int     n_entries;
        double *values;
        int    *columns;
        A.ExtractMyRowView(row, n_entries, values, columns);
        global_columns.resize(n_entries);
        for (int k = 0; k < n_entries; ++k)
          global_columns[k] = A.ColMap().GID64(columns[k]);
        const PetscInt global_row = first + row;
        ierr |= MatSetValues(petsc_matrix,
                             1,
                             &global_row,
                             n_entries,
                             global_columns.data(),
                             values,
                             INSERT_VALUES);
      }
    ierr |= MatAssemblyBegin(petsc_matrix, MAT_FINAL_ASSEMBLY);
    ierr |= MatAssemblyEnd(petsc_matrix, MAT_FINAL_ASSEMBLY);

    ierr |= VecCreateMPI(communicator,
                         n_local,
                         PETSC_DETERMINE,
                         &petsc_coordinates);
    ierr |= VecSetBlockSize(petsc_coordinates, dim);
    PetscScalar *x;
    ierr |= VecGetArray(petsc_coordinates, &x);
    for (PetscInt i = 0; i < n_local; ++i)
      {
        // The coordinates of node i / dim: its dofs are consecutive, in
        // component order.
        AssertThrow(owned_components[i] == static_cast<unsigned int>(i % dim),
                    ExcMessage("dofs are not numbered node by node"));
        x[i] = owned_support_points[i - i % dim][i % dim];
      }
    ierr |= VecRestoreArray(petsc_coordinates, &x);
    AssertThrow(ierr == 0, ExcMessage("PETSc error while copying K"));
    petsc_copy_time = timer.wall_time();
  }



  // @sect4{ElasticProblem::solve_with_hypre}
  //
  // BoomerAMG through PETSc's PCHYPRE, set by PETSc options under a prefix of
  // its own per variant. The keys:
  //  - theta: strong threshold (0.5; hypre recommends 0.5 or more in 3D);
  //  - agg: levels of aggressive coarsening (0);
  //  - coarsen: coarsening (PETSc's default Falgout, or HMIS, PMIS);
  //  - interp: interpolation (classical, or ext+i);
  //  - pmax: largest number of interpolation entries per row (0: no limit);
  //  - relax: smoother (symmetric-SOR/Jacobi, or l1scaled-SOR/Jacobi,
  //    Chebyshev);
  //  - bs: the block size given to hypre (dim, the unknown approach; 1: all
  //    dofs alike);
  //  - nodal: nodal coarsening, hypre's SetNodal (0: none; 1-6, 4 is the
  //    row-sum norm hypre suggests for elasticity);
  //  - vec: the interpolation variant that fits the rigid-body modes (0:
  //    none, 1-3 hypre's GM-1/GM-2/LN), with the rigid-body modes as the
  //    matrix's near null space;
  //  - print: 1 prints hypre's statistics of the hierarchy (0).
  template <int dim>
  typename ElasticProblem<dim>::Result
  ElasticProblem<dim>::solve_with_hypre(const Variant &variant, VectorType &u)
  {
    if (petsc_matrix == nullptr)
      make_petsc_matrix();
    static unsigned int counter = 0;
    const std::string   prefix  = "v" + std::to_string(counter++) + "_";
    const auto option = [&](const std::string &key, const std::string &value) {
      const std::string name = "-" + prefix + "pc_hypre_boomeramg_" + key;
      PetscOptionsSetValue(nullptr, name.c_str(), value.c_str());
    };
    option("strong_threshold", variant.get("theta", "0.5"));
    option("agg_nl", variant.get("agg", "0"));
    option("max_row_sum", "1.0");
    if (variant.keys.count("coarsen"))
      option("coarsen_type", variant.get("coarsen", ""));
    if (variant.keys.count("interp"))
      option("interp_type", variant.get("interp", ""));
    if (variant.keys.count("pmax"))
      option("P_max", variant.get("pmax", ""));
    const std::string relax = variant.get("relax", "symmetric-SOR/Jacobi");
    option("relax_type_down", relax);
    option("relax_type_up", relax);
    option("relax_type_coarse", "Gaussian-elimination");
    if (variant.get("nodal", "0") != "0")
      option("nodal_coarsen", variant.get("nodal", ""));
    if (variant.get("print", "0") != "0")
      option("print_statistics", "1");
    const bool use_modes = variant.get("vec", "0") != "0";
    if (use_modes)
      option("vec_interp_variant", variant.get("vec", ""));

    // The block size: set on the matrix (hypre reads it in PCSetUp), and
    // the rigid-body modes as its near null space when asked for.
    const PetscInt bs   = std::stoi(variant.get("bs", std::to_string(dim)));
    PetscErrorCode ierr = 0;
    ierr |= MatSetBlockSize(petsc_matrix, bs);
    MatNullSpace near_null_space = nullptr;
    if (use_modes)
      {
        ierr
          |= MatNullSpaceCreateRigidBody(petsc_coordinates, &near_null_space);
        ierr |= MatSetNearNullSpace(petsc_matrix, near_null_space);
      }
    else
      ierr |= MatSetNearNullSpace(petsc_matrix, nullptr);
    AssertThrow(ierr == 0, ExcMessage("PETSc error setting up the matrix"));

    Result       result;
    const double before = resident_mb();
    Timer        timer;
    PC           pc;
    ierr |= PCCreate(communicator, &pc);
    ierr |= PCSetOptionsPrefix(pc, prefix.c_str());
    ierr |= PCSetOperators(pc, petsc_matrix, petsc_matrix);
    ierr |= PCSetType(pc, PCHYPRE);
    ierr |= PCHYPRESetType(pc, "boomeramg");
    ierr |= PCSetFromOptions(pc);
    ierr |= PCSetUp(pc);
    AssertThrow(ierr == 0, ExcMessage("PETSc error in BoomerAMG's set-up"));
    result.setup_time = timer.wall_time();
    result.memory     = resident_mb() - before;

    // CG on PETSc vectors: deal.II's SolverCG, with K and BoomerAMG applied
    // by MatMult() and PCApply().
    struct PetscOperator
    {
      Mat A;
      void
      vmult(PETScVectorType &dst, const PETScVectorType &src) const
      {
        MatMult(A, src, dst);
      }
    };
    struct PetscPreconditioner
    {
      PC pc;
      void
      vmult(PETScVectorType &dst, const PETScVectorType &src) const
      {
        PCApply(pc, src, dst);
      }
    };
    PETScVectorType petsc_b(locally_owned_dofs, communicator),
      petsc_u(locally_owned_dofs, communicator);
    {
      PetscScalar *values;
      VecGetArray(petsc_b, &values);
      for (unsigned int i = 0; i < b.locally_owned_size(); ++i)
        values[i] = b.local_element(i);
      VecRestoreArray(petsc_b, &values);
    }
    SolverControl control(10000, parameters.tolerance * b.l2_norm());
    timer.restart();
    try
      {
        SolverCG<PETScVectorType>(control).solve(PetscOperator{petsc_matrix},
                                                 petsc_u,
                                                 petsc_b,
                                                 PetscPreconditioner{pc});
      }
    catch (const SolverControl::NoConvergence &)
      {
        result.converged = false;
      }
    result.solve_time = timer.wall_time();
    result.iterations = control.last_step();
    // Where a CG iteration's time goes: one product with K and one
    // application of BoomerAMG, each the average of 5 (into a scratch
    // vector: petsc_u is the solution).
    {
      PETScVectorType scratch(locally_owned_dofs, communicator);
      Timer           product_timer;
      for (unsigned int i = 0; i < 5; ++i)
        MatMult(petsc_matrix, petsc_b, scratch);
      const double product = product_timer.wall_time() / 5;
      product_timer.restart();
      for (unsigned int i = 0; i < 5; ++i)
        PCApply(pc, petsc_b, scratch);
      result.note = "K " + std::to_string(1e3 * product) + " ms, cycle "
                    + std::to_string(1e3 * product_timer.wall_time() / 5)
                    + " ms";
    }
    {
      const PetscScalar *values;
      VecGetArrayRead(petsc_u, &values);
      for (unsigned int i = 0; i < u.locally_owned_size(); ++i)
        u.local_element(i) = values[i];
      VecRestoreArrayRead(petsc_u, &values);
    }
    PCDestroy(&pc);
    if (near_null_space != nullptr)
      MatNullSpaceDestroy(&near_null_space);
    return result;
  }



  // @sect4{ElasticProblem::solve_with_gmg}
  //
  // The matrix-free back end's operator and multigrid
  // (matrix_free_elasticity.h): K applied cell by cell, a V-cycle on the
  // meshes of global coarsening with Chebyshev smoothing and ML's AMG on
  // the coarse mesh. CG runs on the matrix-free operator (outer=mf) or on
  // the assembled K (outer=matrix). The keys:
  //  - degree: the Chebyshev degree of the smoother (4);
  //  - range: its smoothing range, the part of the spectrum it damps (15);
  //  - outer: mf or matrix (mf).
  // Hexahedra only.
  template <int dim>
  typename ElasticProblem<dim>::Result
  ElasticProblem<dim>::solve_with_gmg(const Variant &variant, VectorType &u)
  {
    AssertThrow(!reference_cell.is_simplex(),
                ExcMessage("gmg: hexahedra only"));
    const PerzynaMaterial<dim> material(parameters.young_modulus,
                                        parameters.poisson_ratio,
                                        parameters.viscosity,
                                        parameters.yield_stress);
    ElasticOperatorData<dim>   data{
      mapping,
      dof_handler,
      constraints,
      [&](const types::material_id) -> const SymmetricTensor<4, dim>   &{
        return material.elasticity_tensor();
      },
      [&](const DoFHandler<dim>     &level_dofs,
          const IndexSet            &relevant,
          AffineConstraints<double> &level_constraints) {
        make_displacement_constraints(hp::MappingCollection<dim>(mapping),
                                      level_dofs,
                                      {DirichletPart{parameters.clamped_ids,
                                                     {}}},
                                      {},
                                      relevant,
                                      level_constraints);
      }};
    data.smoother_degree = std::stoi(variant.get("degree", "4"));
    data.smoothing_range = std::stod(variant.get("range", "15"));

    Result       result;
    const double before = resident_mb();
    Timer        timer;
    // The set-up ends with one V-cycle, in which the Chebyshev smoothers
    // estimate their eigenvalues.
    const MatrixFreeElasticity<dim> gmg(data, b);
    result.setup_time = timer.wall_time();
    result.memory     = resident_mb() - before;
    struct Operator
    {
      std::function<void(VectorType &, const VectorType &)> apply;
      void
      vmult(VectorType &dst, const VectorType &src) const
      {
        apply(dst, src);
      }
    };
    const Operator mf{
      [&](VectorType &dst, const VectorType &src) { gmg.vmult(dst, src); }};
    const Operator preconditioner{[&](VectorType &dst, const VectorType &src) {
      gmg.precondition(dst, src);
    }};

    VectorType solution(b);
    solution = 0;
    SolverControl control(10000, parameters.tolerance * b.l2_norm());
    timer.restart();
    try
      {
        if (variant.get("outer", "mf") == "matrix")
          SolverCG<VectorType>(control).solve(K, solution, b, preconditioner);
        else
          SolverCG<VectorType>(control).solve(mf, solution, b, preconditioner);
      }
    catch (const SolverControl::NoConvergence &)
      {
        result.converged = false;
      }
    result.solve_time = timer.wall_time();
    result.iterations = control.last_step();
    {
      VectorType y(b);
      Timer      product_timer;
      for (unsigned int i = 0; i < 5; ++i)
        gmg.vmult(y, b);
      const double product = product_timer.wall_time() / 5;
      product_timer.restart();
      for (unsigned int i = 0; i < 5; ++i)
        gmg.precondition(y, b);
      result.note = "K " + std::to_string(1e3 * product) + " ms, cycle "
                    + std::to_string(1e3 * product_timer.wall_time() / 5)
                    + " ms";
    }
    u = solution;
    return result;
  }



  // @sect4{ElasticProblem::run}
  //
  // Set up once, then every variant in the order given; the first one's
  // solution is the reference of the others.
  template <int dim>
  void
  ElasticProblem<dim>::run(const std::vector<Variant> &variants,
                           const std::string          &mesh_name,
                           const unsigned int          N)
  {
    setup_and_assemble();
    compute_rigid_body_modes();
    pcout << "# " << mesh_name << " N = " << N << ": " << dof_handler.n_dofs()
          << " dofs, " << K.n_nonzero_elements() << " nonzeros; mesh, dofs "
          << "and assembly " << setup_time << " s, rigid-body modes "
          << modes_time << " s" << std::endl;
    VectorType reference, u(b);
    for (const Variant &variant : variants)
      {
        const Result result
          = (variant.kind == "ml"      ? solve_with_ml(variant, u)
             : variant.kind == "hypre" ? solve_with_hypre(variant, u)
                                       : solve_with_gmg(variant, u));
        double difference = 0;
        if (reference.size() == 0)
          reference = u;
        else
          {
            VectorType d(u);
            d -= reference;
            difference = d.l2_norm() / reference.l2_norm();
          }
        pcout << "RESULT\t" << mesh_name << '\t' << N << '\t'
              << dof_handler.n_dofs() << '\t' << variant.name << '\t'
              << result.setup_time << '\t' << result.solve_time << '\t'
              << result.iterations << '\t' << result.memory << '\t'
              << difference << '\t' << (result.converged ? "yes" : "no") << '\t'
              << result.note << std::endl;
      }
    if (petsc_matrix != nullptr)
      pcout << "# PETSc copy of K: " << petsc_copy_time << " s" << std::endl;
    pcout << "# peak memory of the process: " << peak_mb() << " MB"
          << std::endl;
    if (petsc_matrix != nullptr)
      {
        MatDestroy(&petsc_matrix);
        VecDestroy(&petsc_coordinates);
      }
  }
} // namespace PreconditionerComparison



int
main(int argc, char **argv)
{
  using namespace dealii;
  using namespace PreconditionerComparison;
  // One thread per process, the BLAS's too: the comparison is of the
  // preconditioners on one core, as the program's back end runs them per
  // MPI rank.
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  ViscoContact::set_blas_threads(1);
  try
    {
      AssertThrow(argc >= 4,
                  ExcMessage("usage: preconditioner_comparison SCENE.prm N "
                             "VARIANT [VARIANT...]"));
      ParameterHandler          prm;
      Parameters::AllParameters parameters;
      parameters.add_parameters(prm);
      prm.parse_input(argv[1]);
      prm.enter_subsection("Geometry");
      prm.set("Subdivisions", argv[2]);
      prm.leave_subsection();
      parameters.check_parameters(prm);
      std::vector<Variant> variants;
      for (int i = 3; i < argc; ++i)
        variants.push_back(parse_variant(argv[i]));
      const unsigned int N = std::stoi(argv[2]);
      const std::string  mesh_name
        = (parameters.cell_type == Parameters::CellType::simplex
             ? (parameters.dimension == 3 ? "tetrahedra" : "triangles")
             : (parameters.dimension == 3 ? "hexahedra" : "quadrilaterals"));
      if (parameters.dimension == 2)
        ElasticProblem<2>(parameters, MPI_COMM_WORLD)
          .run(variants, mesh_name, N);
      else
        ElasticProblem<3>(parameters, MPI_COMM_WORLD)
          .run(variants, mesh_name, N);
    }
  catch (const std::exception &e)
    {
      std::cerr << "preconditioner_comparison: " << e.what() << std::endl;
      return 1;
    }
  return 0;
}
