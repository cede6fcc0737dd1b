// The set-up phase of ViscoplasticContact<dim>: the distributed mesh, the
// dofs and their ownership, the elastic operator (assembled once), the
// stress points, the contact set, the back end, and the limits of the
// scheme reported before the time loop.

#include <deal.II/base/exceptions.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/utilities.h>

#include <deal.II/dofs/dof_tools.h>

#include <deal.II/fe/fe_values.h>

#include <deal.II/hp/fe_values.h>

#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/sparsity_tools.h>

#include <deal.II/numerics/vector_tools.h>

#include "constraints.h"
#include "elastic_operator.h"
#include "lanczos.h"
#include "mesh/mesh.h"
#include "robustness/file_output.h"
#include "viscoplastic_contact.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <sstream>
#include <unordered_map>
#include <vector>

namespace ViscoContact
{
  // @sect4{ViscoplasticContact::make_grid}
  //
  // The distributed mesh of mesh.cc: p4est for hypercubes, fully distributed
  // for simplices, on any number of ranks. It is built from the parameter file
  // alone (the generated box or a Gmsh file, then the uniform refinements and
  // those toward Gamma_3), so that every run of the same file has the same mesh
  // with the same cell ids, on any number of ranks; the checkpoints rely on
  // this. The boundary ids the parameter file names are checked there as well,
  // across all ranks.
  //
  // With Initial cycles and Initial refinement = global, the mesh of the
  // parameter file is the last one of the cycles: the run starts on it
  // coarsened Initial cycles times (fewer Global refinements, then half the
  // Subdivisions of a generated box), whose refinement the cycles do
  // (InitialCycles::solve()). On p4est both give the same cells with the
  // same ids; simplex meshes are built anew for each cycle.
  template <int dim>
  void
  ViscoplasticContact<dim>::make_grid()
  {
    TimerOutput::Scope        t(report.timer(), "Setup: mesh");
    Parameters::AllParameters first_mesh = parameters;
    if (parameters.initial_refinement == Parameters::InitialRefinement::global)
      first_mesh = parameters.coarsened(plan.initial_cycles());
    Timer timer;
    triangulation = create_distributed_mesh<dim>(first_mesh, mpi_communicator);
    if (parameters.print_timing_summary)
      {
        const unsigned int group_size
          = mesh_group_size(parameters, mpi_communicator);
        pcout << "Mesh built in " << timer.wall_time() << " s";
        if (parameters.cell_type != Parameters::CellType::hypercube)
          pcout << " (one rank in every " << group_size
                << " builds the whole mesh and hands out the parts)";
        pcout << std::endl;
        report.record_peak_memory("after the mesh");
      }
  }



  // @sect4{ViscoplasticContact::setup_on_mesh}
  //
  // Everything that depends on the mesh, in the order of the dependencies: the
  // dofs need the mesh; the stress-point geometry needs the dofs and the
  // partition of the vectors; the contact nodes need K for their parameters
  // c_i; the back end needs the number of contact nodes to choose its method
  // and, if condensed, the nodes themselves. The state it leaves is the
  // initial one (u = 0, zero stresses and history, every contact node at
  // r = z = 0): run() starts from it, and after a change of the mesh the
  // caller carries the state over (MeshAdaptation::adapt(),
  // Checkpoints::resume()). The start of the previous step is not carried over,
  // so the first step on a new mesh starts from u_{n-1}
  // (acceleration/predicted_start.h).
  //
  // The back end of the previous mesh goes first: a factorisation may refer
  // to the matrix it was set up with (Amesos' MUMPS asks it for its
  // communicator when it is destroyed), and setup_system() replaces that
  // matrix.
  template <int dim>
  void
  ViscoplasticContact<dim>::setup_on_mesh()
  {
    predicted_start.forget();
    step_cycles.forget();
    contact_solver.reset();
    // The peak memory after each phase, on the first set-up.
    const bool report_memory = report.reports_set_up_memory();
    report.set_up_done();
    setup_system();
    if (report_memory)
      report.record_peak_memory("after the operator");
    setup_stress_points();
    prescribed.reinit(discretisation.mapping,
                      dof_handler,
                      locally_relevant_dofs,
                      stress_points,
                      solution);
    prescribed.check_rigid_motions(discretisation.mapping,
                                   dof_handler,
                                   constraints);
    setup_contact();
    if (report_memory)
      report.record_peak_memory("after the stress points and contact nodes");
    setup_back_end();
    if (report_memory)
      report.record_peak_memory("after the back end");
  }



  // @sect4{ViscoplasticContact::setup_system}
  //
  // Dofs and their ownership (as in step-40), the clamping of Gamma_1 and
  // the hanging nodes of a graded mesh as constraints, the distributed
  // sparsity pattern, the vectors, and then the elastic operator K, which
  // the explicit scheme never changes. The scalar DoFHandler only carries
  // the nodal contact fields of the output.
  template <int dim>
  void
  ViscoplasticContact<dim>::setup_system()
  {
    {
      TimerOutput::Scope t(report.timer(), "Setup: dofs and constraints");
      // Two DoFHandlers on the same mesh: the vector-valued one of the
      // displacement, and a scalar one with one dof per vertex for the nodal
      // contact fields of the output.
      dof_handler.reinit(*triangulation);
      discretisation.distribute_dofs(dof_handler, discretisation.fe);
      scalar_dof_handler.reinit(*triangulation);
      discretisation.distribute_dofs(scalar_dof_handler,
                                     discretisation.scalar_fe);
      IndexSet scalar_relevant;
      DoFTools::extract_locally_relevant_dofs(scalar_dof_handler,
                                              scalar_relevant);
      scalar_partitioner = std::make_shared<Utilities::MPI::Partitioner>(
        scalar_dof_handler.locally_owned_dofs(),
        scalar_relevant,
        mpi_communicator);
      // Each rank owns a contiguous range of dofs (locally_owned_dofs) and also
      // sees the dofs of its ghost cells (locally_relevant_dofs): the ghost
      // entries of its vectors.
      locally_owned_dofs = dof_handler.locally_owned_dofs();
      DoFTools::extract_locally_relevant_dofs(dof_handler,
                                              locally_relevant_dofs);

      // The constraints are stored for all locally relevant dofs, not only the
      // owned ones: the cell loops write into every dof of an owned cell, and
      // some of those are ghosts owned by another rank. The Dirichlet parts
      // (clamped Gamma_1, prescribed displacements) get u_c = 0 here, which
      // is homogeneous, so the same constraints serve every displacement and
      // every right-hand side of the run; the prescribed values enter each
      // step as a lifting (set_dirichlet_values()). Hanging nodes appear
      // where the mesh is refined toward Gamma_3.
      prescribed.make_constraints(discretisation.mapping,
                                  dof_handler,
                                  locally_relevant_dofs,
                                  constraints);

      choose_back_end();

      // The sparsity pattern of the owned cells, without the entries that the
      // constraints eliminate (distribute_local_to_global() never writes them).
      // A rank's cells also couple ghost dofs; distribute_sparsity_pattern()
      // sends those rows to the ranks that own them, so that each rank ends
      // with the complete rows of its owned dofs, which is how the Trilinos
      // matrices are partitioned. Without a matrix (Method = matrix free) there
      // is nothing to lay out.
      if (!plan.matrix_free())
        {
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
          // The tangent of the implicit update has the same couplings as K;
          // the explicit update never needs it.
          if (parameters.implicit_update())
            tangent_matrix.reinit(locally_owned_dofs,
                                  locally_owned_dofs,
                                  dsp,
                                  mpi_communicator);
        }

      // All displacement-sized vectors share one partition: owned entries and
      // the ghosts of the locally relevant dofs. Sharing one partitioner also
      // means that a local index (owned entries first, then ghosts) means the
      // same dof in every one of them, which the stored stress-point geometry
      // relies on.
      // The dofs of the opposite side of a contact pair that the rows of
      // this rank's nodes use are ghosts too.
      IndexSet ghosts = locally_relevant_dofs;
      if (!contact_zones.empty())
        ghosts.add_indices(
          contact_set.couple_pairs(contact_zones.descriptions(),
                                   dof_handler,
                                   constraints));
      solution.reinit(locally_owned_dofs, ghosts, mpi_communicator);
      for (VectorType *vector :
           {&external_load, &history_load, &system_rhs, &internal_force})
        vector->reinit(solution);
      solution.update_ghost_values(); // u_0 = 0, readable at the ghosts
    }
    if (!plan.matrix_free())
      assemble_elastic_operator();
  }



  // @sect4{ViscoplasticContact::assemble_elastic_operator}
  //
  // K_ij = (E eps(phi_j), eps(phi_i)) on the locally owned cells, with the
  // constrained rows and columns condensed (their diagonal stays positive,
  // so K is symmetric positive definite on all dofs). The count is printed
  // in the run summary: a change that re-assembles per step shows up there.
  //
  // The integral is taken with the stress quadrature, the same points at which
  // the stresses live and the history load is integrated, so that K and the
  // history load are consistent: (E eps(u) + H, eps(v)) at the stress points is
  // exactly K u + (H, eps(v)). This runs once, before the stress-point geometry
  // exists, so it uses FEValues like any deal.II assembly loop.
  template <int dim>
  void
  ViscoplasticContact<dim>::assemble_elastic_operator()
  {
    TimerOutput::Scope t(report.timer(), "Setup: assemble elastic operator");
    ViscoContact::assemble_elastic_operator(discretisation.mapping,
                                            dof_handler,
                                            discretisation.stress_quadrature,
                                            materials.cell_elasticity(),
                                            constraints,
                                            stiffness_matrix);
    report.count_operator_assembly();
  }



  // @sect4{ViscoplasticContact::setup_stress_points}
  //
  // The stress-point geometry the time loop uses instead of FEValues
  // (stress_points.h): the stress update, the history load and the tangent
  // visit every stress point in every step, and the mesh does not move. Then
  // one record per stress point of the locally owned cells, in a flat array
  // (as step-18 does); sigma_0 = 0 and u_0 = 0, so H_1 = 0.
  template <int dim>
  void
  ViscoplasticContact<dim>::setup_stress_points()
  {
    TimerOutput::Scope t(report.timer(), "Setup: stress points");
    stress_points.reinit(discretisation.mapping,
                         dof_handler,
                         discretisation.stress_quadrature,
                         *solution.get_partitioner(),
                         constraints);
    materials.set_cells(stress_points.cells());
    quadrature_point_history.assign(std::size_t(stress_points.n_cells())
                                      * discretisation.n_stress_points(),
                                    QuadraturePointHistory<dim>());
  }



  // @sect4{ViscoplasticContact::setup_contact}
  //
  // The contact set of contact_set.h, and its active-set parameters from K.
  // Without Gamma_3 or with a law that is zero everywhere and has no rigid
  // limit, contact is skipped altogether.
  //
  // ContactSet::setup() finds the contact nodes this rank owns (the owned
  // vertices of Gamma_3 that are not constrained), assembles their lumped
  // weights w_i and normals nu_i like a right-hand side (so that they do not
  // depend on the partition), and puts every node on the piece of the state
  // r = z = 0. The parameters c_i = max(nu_i^T K_ii nu_i / w_i,
  // 2 * steepest softening) come from the diagonal blocks of K (doc/model.md,
  // section 2); the implicit update recomputes them from each tangent.
  template <int dim>
  void
  ViscoplasticContact<dim>::setup_contact()
  {
    contact_enabled = !contact_zones.empty();
    if (!contact_enabled)
      return;
    TimerOutput::Scope t(report.timer(), "Setup: contact nodes");
    contact_set.setup(contact_zones.descriptions(),
                      discretisation.mapping,
                      dof_handler,
                      scalar_dof_handler,
                      discretisation.face_quadrature,
                      constraints,
                      prescribed.hanging_node_constraints(),
                      solution);
    set_gaps(schedule.current_time());
    // The laws with a history start from the initial state: the memory
    // empty, the bonding at its initial values, no opening reached, each
    // with the penetrations of the initial state for the first step.
    {
      std::vector<unsigned int> zones;
      std::vector<double>       penetrations;
      for (unsigned int i = 0; i < contact_set.size(); ++i)
        {
          zones.push_back(contact_set.zone(i));
          penetrations.push_back(contact_set.normal_component(solution, i)
                                 - contact_set.gap(i));
        }
      contact_histories.memory.reinit(contact_zones.memory_kernels(), zones);
      contact_histories.bonding.reinit(
        contact_zones.bonding_laws(),
        zones,
        contact_zones.initial_bonding(contact_set, mpi_communicator));
      contact_histories.wear.reinit(contact_zones.wear_coefficients(), zones);
      contact_histories.damage.reinit(contact_zones.cohesive_zones(), zones);
      contact_set.r = penetrations;
      for (ContactHistory *history : contact_histories.all())
        if (history->active())
          {
            history->accept_step(contact_set);
            history->apply_accepted(contact_set);
          }
    }
    // Tresca's bounds at the nodes (collective: a negative or infinite
    // value stops all ranks, naming the entry).
    FileOutput::agree_on_problem(contact_set.set_slip_bounds(
                                   contact_zones.slip_bounds()),
                                 mpi_communicator);
    if (!plan.matrix_free())
      contact_set.set_operator(stiffness_matrix);
    else
      {
        std::vector<std::array<types::global_dof_index, dim>> node_dofs;
        for (unsigned int i = 0; i < contact_set.size(); ++i)
          node_dofs.push_back(contact_set.node(i).dofs);
        contact_set.set_operator(
          elastic_node_blocks<dim>(discretisation.mapping,
                                   dof_handler,
                                   discretisation.stress_quadrature,
                                   materials.cell_elasticity(),
                                   node_dofs));
      }
  }



  // @sect4{ViscoplasticContact::choose_back_end}
  //
  // The plan's choice for this mesh (run/run_plan.h), from its dofs, the
  // vertices of the contact boundary (the contact nodes to be), and once the
  // schedule exists (a later mesh) the steps it has left. A coarser mesh of
  // the initial cycles solves the first step only.
  template <int dim>
  void
  ViscoplasticContact<dim>::choose_back_end()
  {
    double                                contact_nodes = 0;
    const std::vector<types::boundary_id> contact_ids
      = parameters.all_contact_ids();
    if (!contact_ids.empty())
      {
        const IndexSet on_contact
          = DoFTools::extract_boundary_dofs(
              dof_handler,
              discretisation.fe.component_mask(FEValuesExtractors::Scalar(0)),
              std::set<types::boundary_id>(contact_ids.begin(),
                                           contact_ids.end()))
            & locally_owned_dofs;
        contact_nodes
          = Utilities::MPI::sum(on_contact.n_elements(), mpi_communicator);
      }
    double steps_left = 0;
    if (schedule.end_time() > 0)
      steps_left
        = std::max(1.,
                   std::round((schedule.end_time() - schedule.current_time())
                              / std::max(schedule.step_length(), 1e-300)));
    const bool cycle_mesh = !parameters.resume
                            && report.n_initial_cycles() < plan.initial_cycles()
                            && parameters.initial_refinement
                                 == Parameters::InitialRefinement::global;
    // With friction the condensed back end's dense problem holds the nodes
    // in contact: from the obstacles' overlap at up to 64 times of the steps
    // this mesh solves (before the schedule is set, on the first mesh or a
    // resumed run, of the whole run from t = 0: an estimate of the cost).
    double contact_fraction = 1;
    if (!contact_zones.frictional_numbers().empty())
      {
        const bool   scheduled = schedule.end_time() > 0;
        const double start     = scheduled ? schedule.current_time() : 0.;
        const double end
          = cycle_mesh
              ? start
                  + (scheduled ? schedule.step_length() : parameters.time_step)
              : (scheduled ? schedule.end_time() : parameters.end_time);
        const unsigned int n_times
          = cycle_mesh ? 1
                       : static_cast<unsigned int>(
                         std::clamp((end - start)
                                      / std::max(parameters.time_step, 1e-300),
                                    1.,
                                    64.));
        std::vector<double> times;
        for (unsigned int k = 1; k <= n_times; ++k)
          times.push_back(start + (end - start) * k / n_times);
        contact_fraction
          = contact_zones.expected_contact_fraction(dof_handler,
                                                    times,
                                                    mpi_communicator);
      }
    plan.choose_back_end(dof_handler.n_dofs(),
                         contact_nodes,
                         contact_fraction,
                         steps_left,
                         cycle_mesh,
                         report.n_initial_cycles());
  }



  // @sect4{ViscoplasticContact::setup_back_end}
  //
  // Method = auto picks the back end from the scene (contact_solver.cc);
  // the back end then factorises or preconditions K, which for the explicit
  // update is the operator of every step problem of the run.
  //
  // The choice depends only on numbers every rank knows (ranks, dofs, global
  // number of contact nodes), so all ranks create the same back end. From here
  // on the class speaks to it only through the ContactSolver interface: the
  // time loop below is the same for both.
  template <int dim>
  void
  ViscoplasticContact<dim>::setup_back_end()
  {
    // What the matrix-free back end builds its operator and multigrid
    // from: the coarser meshes get the constraints of the same boundary
    // parts.
    const ElasticOperatorData<dim> operator_data{
      discretisation.mapping[0],
      dof_handler,
      constraints,
      [this](const types::material_id id) -> const SymmetricTensor<4, dim> & {
        return materials.of_id(id).elasticity_tensor();
      },
      [this](const DoFHandler<dim>     &level_dofs,
             const IndexSet            &relevant,
             AffineConstraints<double> &level_constraints) {
        make_displacement_constraints(discretisation.mapping,
                                      level_dofs,
                                      prescribed.parts().parts(),
                                      parameters.symmetry_ids,
                                      relevant,
                                      level_constraints);
      }};
    contact_solver = create_contact_solver<dim>(plan.back_end().method,
                                                parameters,
                                                discretisation.mapping,
                                                dof_handler,
                                                solution,
                                                operator_data,
                                                constraints);
    // Only the set-up of the operator is timed: the factorisation and the
    // compliance S (from the factor's last block) of the condensed back end, or
    // the AMG hierarchy of the full space one. K is symmetric (the argument
    // true), so the back end may use CG and a symmetric factorisation.
    TimerOutput::Scope t(report.timer(), "Setup: back end for K");
    contact_solver->set_operator(stiffness_matrix, true, contact_set);
  }



  namespace
  {
    // A cohesive envelope that softens more than the body carries (its
    // smallest eigenvalue) need not soften within a step: the entry that
    // takes its damage from the last step.
    template <int dim>
    std::string
    cohesive_remedy(const ContactZones<dim> &contact_zones,
                    const double             eigenvalue)
    {
      std::string remedy;
      for (const ContactZoneDescription<dim> &zone :
           contact_zones.descriptions())
        if (zone.law.has_cohesion()
            && zone.law.steepest_softening() >= eigenvalue)
          remedy += " <Cohesive damage> = explicit in subsection <"
                    + zone.subsection
                    + "> takes the damage from the last step: no softening "
                      "within a step.";
      return remedy;
    }
  } // namespace



  // @sect4{ViscoplasticContact::report_scheme_limits}
  //
  // Where the method may fail, said before the run starts (doc/model.md,
  // sections 3 and 4): the explicit history update is forward Euler on a
  // relaxation with rate up to lambda_max(E)/(2 lambda), stable for
  // k < 4 lambda / lambda_max(E); and the step problem has a unique
  // solution (its energy is strongly convex) iff the smallest generalised
  // eigenvalue of stiffness against the lumped normal boundary mass
  // exceeds the steepest softening of the contact law.
  template <int dim>
  void
  ViscoplasticContact<dim>::report_scheme_limits()
  {
    // The implicit update is unconditionally stable (doc/model.md, section 3);
    // the explicit one has the limit of forward Euler on the relaxation.
    if (parameters.implicit_update())
      pcout << "Implicit (backward-Euler) history update: no stability limit "
               "on k (doc/model.md, section 3); k = "
            << schedule.grid_step_length() << " s\n";
    else if (parameters.explicit_history_update())
      {
        const double bound = materials.explicit_stability_limit();
        pcout << "Explicit history update: stable for k < 4 lambda / "
                 "lambda_max(E) = "
              << bound << " s; k = " << schedule.grid_step_length() << " s\n";
        if (schedule.grid_step_length() >= bound
            && parameters.time_step_control
                 == Parameters::TimeStepControl::fixed)
          pcout << "WARNING: the time step exceeds the stability limit of the "
                   "explicit history update (doc/model.md, section 3): the "
                   "stresses may oscillate or blow up.\n";
      }
    // Adaptive steps: the controller's tolerance and range, with the cap of
    // the explicit update (make_time_step_controller()).
    if (parameters.time_step_control == Parameters::TimeStepControl::adaptive)
      {
        const TimeStepController &controller = step_controller;
        pcout << "Adaptive time steps: Error tolerance = "
              << controller.tolerance << ", k in [" << controller.minimum_step
              << ", " << controller.maximum_step << "] s";
        if (parameters.explicit_history_update())
          pcout << " (at most 0.9 x the stability limit)";
        pcout << (parameters.resume ? ", next step " : ", first step ")
              << schedule.proposed_step() << " s\n";
        if (parameters.explicit_history_update()
            && controller.maximum_step >= materials.explicit_stability_limit())
          pcout << "WARNING: Minimum time step exceeds the stability limit of "
                   "the explicit history update (doc/model.md, section 3).\n";
      }
    // The uniqueness margin needs products with the compliance S, i.e. the back
    // end for K; Check uniqueness = false skips it. It is collective: every
    // rank takes part in the Lanczos iteration and prints (on rank 0) the same
    // number. A law that does not soften (the rigid limit, a monotone layer)
    // needs no margin: K is positive definite, so the step problem has one
    // solution, and the Lanczos iteration (one solve with K per product on
    // the full space back end) would cost more than the run's first steps.
    if (!contact_enabled || !parameters.check_uniqueness)
      return;
    const double softening = contact_set.laws().steepest_softening();
    if (softening <= 0)
      pcout << "Uniqueness: the contact law"
            << (contact_zones.descriptions().size() > 1 ? "s do" : " does")
            << " not soften, so the step problem has one solution\n";
    else
      {
        const bool from_checkpoint = uniqueness_eigenvalue.has_value();
        if (!from_checkpoint)
          {
            TimerOutput::Scope t(report.timer(), "Setup: uniqueness margin");
            // min_v a(v,v) / sum_i w_i (v . nu_i)^2: for given normal
            // displacements r the smallest energy is r^T S^{-1} r (the
            // harmonic extension), so the minimum is 1 / lambda_max(D^{1/2}
            // S D^{1/2}), D = diag(w_i). A product with S is the back end's
            // apply_compliance(): a dense product on the condensed back end,
            // one elastic solve on the full space back end.
            const auto apply
              = [this](const Vector<double> &x, Vector<double> &y) {
                  Vector<double> scaled(x);
                  for (unsigned int i = 0; i < contact_set.size(); ++i)
                    scaled[i] *= std::sqrt(contact_set.weight(i));
                  contact_solver->apply_compliance(contact_set, scaled, y);
                  for (unsigned int i = 0; i < contact_set.size(); ++i)
                    y[i] *= std::sqrt(contact_set.weight(i));
                };
            uniqueness_eigenvalue
              = 1.
                / largest_eigenvalue(apply,
                                     contact_set.size(),
                                     contact_set.n_global_nodes(),
                                     mpi_communicator);
          }
        const double eigenvalue = *uniqueness_eigenvalue;
        pcout << "Uniqueness: smallest eigenvalue of (stiffness, lumped "
                 "normal boundary mass) = "
              << eigenvalue << (from_checkpoint ? " (from the checkpoint)" : "")
              << ", steepest softening of the contact law"
              << (contact_zones.descriptions().size() > 1 ? "s" : "") << " = "
              << softening << '\n';
        // Several solutions possible: a predicted start must not move the
        // run to another branch (acceleration/predicted_start.h).
        predicted_start.set_pieces_predictable(eigenvalue > softening);
        if (eigenvalue <= softening)
          pcout << "WARNING: the contact law softens more than the body can "
                   "carry (doc/model.md, section 4): the step problem may "
                   "have several solutions and the active-set iteration may "
                   "cycle."
                << cohesive_remedy(contact_zones, eigenvalue) << '\n';
      }
  }



  // @sect4{symmetry_plane_normal}
  //
  // The mean of the part's faces' normals, weighted by their areas. A face
  // whose normal differs from the mean by more than 1e-8 makes the part
  // not planar.
  template <int dim>
  Tensor<1, dim>
  symmetry_plane_normal(const hp::MappingCollection<dim> &mapping,
                        const DoFHandler<dim>            &dof_handler,
                        const types::boundary_id          id,
                        const MPI_Comm                    communicator)
  {
    // The midpoint rule of each element's faces.
    hp::QCollection<dim - 1> midpoints;
    for (const auto &element : dof_handler.get_fe_collection())
      midpoints.push_back(element.reference_cell()
                            .face_reference_cell(0)
                            .template get_gauss_type_quadrature<dim - 1>(1));
    hp::FEFaceValues<dim>                              hp_face_values(mapping,
                                         dof_handler.get_fe_collection(),
                                         midpoints,
                                         update_normal_vectors
                                           | update_JxW_values
                                           | update_quadrature_points);
    std::vector<std::pair<Tensor<1, dim>, Point<dim>>> faces;
    Tensor<1, dim>                                     sum;
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
        for (const unsigned int f : cell->face_indices())
          if (cell->face(f)->at_boundary()
              && cell->face(f)->boundary_id() == id)
            {
              hp_face_values.reinit(cell, f);
              const FEFaceValues<dim> &face_values
                = hp_face_values.get_present_fe_values();
              sum += face_values.normal_vector(0) * face_values.JxW(0);
              faces.emplace_back(face_values.normal_vector(0),
                                 face_values.quadrature_point(0));
            }
    Tensor<1, dim> normal = Utilities::MPI::sum(sum, communicator);
    normal /= normal.norm();
    for (unsigned int c = 0; c < dim; ++c)
      if (std::abs(normal[c]) < 1e-12)
        normal[c] = 0;
    normal /= normal.norm();
    std::string problem;
    for (const auto &[face_normal, center] : faces)
      if (problem.empty() && (face_normal - normal).norm() > 1e-8)
        {
          std::ostringstream message;
          message << "Invalid parameter <Symmetry boundary ids> in "
                     "subsection <Boundary>: boundary id "
                  << int(id) << " is not planar (its face at (" << center
                  << ") has the normal (" << face_normal
                  << "), the part's mean normal is (" << normal
                  << ")); accepted: planar boundary parts.";
          problem = message.str();
        }
    FileOutput::agree_on_problem(problem, communicator);
    return normal;
  }



  namespace
  {
    // u.n = 0 at every vertex of the symmetry parts, from the normals n of
    // the planes the vertex lies on: on one plane, the component k with the
    // largest |n_k| is constrained, u_k = -sum_{j != k} n_j / n_k u_j (just
    // u_k = 0 on a plane x_k = const); on two planes in 3D (an edge) u is
    // along the edge t = n_1 x n_2; on more (2D corners, 3D vertices) u = 0.
    // Components constrained already (hanging nodes, Dirichlet parts) keep
    // their constraints; on one plane the largest free component takes the
    // plane's constraint instead. Only the owner of a vertex, which sees all of
    // the cells around it, makes its lines (another rank may not see every
    // plane there); make_consistent_in_parallel() gives them to the ranks
    // that have the vertex as a ghost.
    template <int dim>
    void
    make_symmetry_constraints(
      const hp::MappingCollection<dim>      &mapping,
      const DoFHandler<dim>                 &dof_handler,
      const std::vector<types::boundary_id> &symmetry_ids,
      AffineConstraints<double>             &constraints)
    {
      const MPI_Comm              communicator = dof_handler.get_communicator();
      std::vector<Tensor<1, dim>> normals;
      for (const auto id : symmetry_ids)
        normals.push_back(
          symmetry_plane_normal(mapping, dof_handler, id, communicator));
      // The planes of every vertex (by its x-dof): parallel parts count once.
      std::map<types::global_dof_index,
               std::pair<std::array<types::global_dof_index, dim>,
                         std::vector<Tensor<1, dim>>>>
        vertices;
      for (const auto &cell : dof_handler.active_cell_iterators())
        if (!cell->is_artificial())
          for (const auto &face : cell->face_iterators())
            if (face->at_boundary())
              for (unsigned int p = 0; p < symmetry_ids.size(); ++p)
                if (face->boundary_id() == symmetry_ids[p])
                  for (const unsigned int v : face->vertex_indices())
                    {
                      const unsigned int element = cell->active_fe_index();
                      auto &[dofs, planes]
                        = vertices[face->vertex_dof_index(v, 0, element)];
                      for (unsigned int c = 0; c < dim; ++c)
                        dofs[c] = face->vertex_dof_index(v, c, element);
                      bool known = false;
                      for (const auto &n : planes)
                        known
                          = known
                            || std::abs(std::abs(n * normals[p]) - 1) < 1e-12;
                      if (!known)
                        planes.push_back(normals[p]);
                    }
      const auto largest = [](const Tensor<1, dim> &t) {
        unsigned int k = 0;
        for (unsigned int c = 1; c < dim; ++c)
          if (std::abs(t[c]) > std::abs(t[k]))
            k = c;
        return k;
      };
      const IndexSet &owned = dof_handler.locally_owned_dofs();
      for (const auto &[x_dof, vertex] : vertices)
        {
          const auto &[dofs, planes] = vertex;
          if (!owned.is_element(x_dof))
            continue;
          if (planes.size() == 1)
            {
              // A component prescribed already stays prescribed: the plane
              // constrains the free component with the largest |n_k| in
              // terms of the others (close() resolves the prescribed ones'
              // values into it). None free with n_k != 0: u.n is held.
              const Tensor<1, dim> &n         = planes[0];
              Tensor<1, dim>        free_part = n;
              for (unsigned int c = 0; c < dim; ++c)
                if (constraints.is_constrained(dofs[c]))
                  free_part[c] = 0;
              const unsigned int k = largest(free_part);
              if (free_part[k] == 0)
                continue;
              constraints.add_line(dofs[k]);
              for (unsigned int j = 0; j < dim; ++j)
                if (j != k && n[j] != 0)
                  constraints.add_entry(dofs[k], dofs[j], -n[j] / n[k]);
            }
          else if (dim == 3 && planes.size() == 2)
            {
              Tensor<1, dim> t;
              t[0] = planes[0][1] * planes[1][2] - planes[0][2] * planes[1][1];
              t[1] = planes[0][2] * planes[1][0] - planes[0][0] * planes[1][2];
              t[2] = planes[0][0] * planes[1][1] - planes[0][1] * planes[1][0];
              for (unsigned int c = 0; c < dim; ++c)
                if (std::abs(t[c]) < 1e-12 * t.norm())
                  t[c] = 0;
              const unsigned int k = largest(t);
              for (unsigned int j = 0; j < dim; ++j)
                if (j != k && !constraints.is_constrained(dofs[j]))
                  {
                    constraints.add_line(dofs[j]);
                    if (t[j] != 0)
                      constraints.add_entry(dofs[j], dofs[k], t[j] / t[k]);
                  }
            }
          else
            for (unsigned int c = 0; c < dim; ++c)
              if (!constraints.is_constrained(dofs[c]))
                constraints.add_line(dofs[c]);
        }
    }
  } // namespace



  // @sect4{make_displacement_constraints}
  //
  // Hanging nodes first, then the Dirichlet parts (interpolate_boundary_values
  // leaves dofs already constrained as they are), then the planes of
  // symmetry. Each rank builds the constraints of its locally relevant dofs
  // from its own and its ghost cells; with symmetry planes (whose
  // constraints at a vertex depend on the faces a rank sees) they are made
  // the same on every rank that stores them before closing.
  template <int dim>
  void
  make_displacement_constraints(
    const hp::MappingCollection<dim>      &mapping,
    const DoFHandler<dim>                 &dof_handler,
    const std::vector<DirichletPart>      &dirichlet_parts,
    const std::vector<types::boundary_id> &symmetry_ids,
    const IndexSet                        &locally_relevant_dofs,
    AffineConstraints<double>             &constraints,
    AffineConstraints<double>             *open_constraints)
  {
    constraints.reinit(locally_relevant_dofs);
    DoFTools::make_hanging_node_constraints(dof_handler, constraints);
    const Functions::ZeroFunction<dim> zero(dim);
    for (const DirichletPart &part : dirichlet_parts)
      {
        std::map<types::boundary_id, const Function<dim> *> values;
        for (const auto id : part.boundary_ids)
          values[id] = &zero;
        VectorTools::interpolate_boundary_values(mapping,
                                                 dof_handler,
                                                 values,
                                                 constraints,
                                                 part.components);
      }
    if (!symmetry_ids.empty())
      {
        make_symmetry_constraints(mapping,
                                  dof_handler,
                                  symmetry_ids,
                                  constraints);
        constraints.make_consistent_in_parallel(
          dof_handler.locally_owned_dofs(),
          locally_relevant_dofs,
          dof_handler.get_communicator());
      }
    if (open_constraints != nullptr)
      open_constraints->copy_from(constraints);
    constraints.close();
  }



  template class ViscoplasticContact<2>;
  template class ViscoplasticContact<3>;
  template void
  make_displacement_constraints(const hp::MappingCollection<2> &,
                                const DoFHandler<2> &,
                                const std::vector<DirichletPart> &,
                                const std::vector<types::boundary_id> &,
                                const IndexSet &,
                                AffineConstraints<double> &,
                                AffineConstraints<double> *);
  template Tensor<1, 2>
  symmetry_plane_normal(const hp::MappingCollection<2> &,
                        const DoFHandler<2> &,
                        const types::boundary_id,
                        const MPI_Comm);
  template Tensor<1, 3>
  symmetry_plane_normal(const hp::MappingCollection<3> &,
                        const DoFHandler<3> &,
                        const types::boundary_id,
                        const MPI_Comm);
  template void
  make_displacement_constraints(const hp::MappingCollection<3> &,
                                const DoFHandler<3> &,
                                const std::vector<DirichletPart> &,
                                const std::vector<types::boundary_id> &,
                                const IndexSet &,
                                AffineConstraints<double> &,
                                AffineConstraints<double> *);
} // namespace ViscoContact
