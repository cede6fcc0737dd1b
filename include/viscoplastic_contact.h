#ifndef viscoplastic_contact_viscoplastic_contact_h
#define viscoplastic_contact_viscoplastic_contact_h

#include <deal.II/base/array_view.h>
#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/function_parser.h>
#include <deal.II/base/index_set.h>
#include <deal.II/base/partitioner.h>
#include <deal.II/base/quadrature.h>
#include <deal.II/base/symmetric_tensor.h>
#include <deal.II/base/timer.h>

#include <deal.II/distributed/tria_base.h>

#include <deal.II/grid/cell_id.h>

#include <deal.II/dofs/dof_handler.h>

#include <deal.II/fe/fe.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/fe/mapping.h>

#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/vector.h>

#include <deal.II/numerics/data_out.h>

#include "acceleration/initial_cycles.h"
#include "acceleration/predicted_start.h"
#include "acceleration/step_cycles.h"
#include "back_ends/contact_solver.h"
#include "back_ends/linear_algebra.h"
#include "constraints.h"
#include "contact_nodes.h"
#include "contact_set.h"
#include "discretisation.h"
#include "scene/contact_zones.h"
#include "scene/loads.h"
#include "elastic_operator.h"
#include "material.h"
#include "materials.h"
#include "mesh/mesh_adaptation.h"
#include "contact_histories.h"
#include "parameters.h"
#include "scene/prescribed_displacements.h"
#include "robustness/checkpoint_file.h"
#include "robustness/output_folder.h"
#include "run/checkpoints.h"
#include "run/run_output.h"
#include "run/run_plan.h"
#include "run/run_report.h"
#include "run/step_control.h"
#include "step_report.h"
#include "stress_points.h"
#include "time_schedule.h"

#include <array>
#include <fstream>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <utility>
#include <vector>

namespace ViscoContact
{
  using namespace dealii;

  // @sect3{The ViscoplasticContact class}
  //
  // The program, in the structure of step-18 (a quasistatic time loop with
  // history at the stress points), step-40 (one code for one or many MPI ranks:
  // distributed meshes, locally owned cells and dofs, Trilinos) and step-41/42
  // (an active set on the contact nodes). run() reads as the algorithm of
  // doc/model.md, section 2:
  //   set up; while the schedule is not at its end: do one time step
  //   (assemble the right-hand side, solve the step's contact problem by the
  //   active-set method, update the stresses and the history), then finish
  //   it (write the results, adapt the mesh, write a checkpoint).
  //
  // One class runs every scene: dim = 2 and 3, simplices (P1) and hypercubes
  // (Q1), the explicit and the implicit stress update, one MPI rank or many.
  // The cell type is decided once, in the constructor; a one-rank run is the
  // one-rank case of the distributed data structures, not a separate code path.
  //
  // How the linear problem of fixed pieces is solved is the business of a back
  // end (contact_solver.h): condensed to the contact nodes through a factorised
  // operator, or in the full space by a preconditioned Krylov method. The class
  // owns one back end through that interface and never asks which one it is;
  // the active-set iteration around it (active_set.h) is the same for both. The
  // explicit (the paper's) and the implicit (backward Euler) stress updates run
  // on either: the explicit one keeps the elastic operator K for the whole run
  // and moves all of the plasticity into the right-hand side, the implicit one
  // solves each step by Newton's method, with a new tangent (and a new set-up
  // of the back end) per Newton iteration.
  //
  // The parallel data layout: every rank works on its locally owned cells and
  // on the contact nodes it owns; displacement-sized vectors hold the owned
  // entries and, as ghosts, the other locally relevant dofs (those of the owned
  // cells and of the layer of ghost cells around them, as in step-40). Nothing
  // global is gathered on one rank: only scalars (iteration decisions, counts,
  // forces, norms) are reduced over the ranks.
  template <int dim>
  class ViscoplasticContact
  {
  public:
    // The constructor stores the parameters and makes the choices that depend
    // on the cell type (mapping, element, quadratures); everything that needs
    // the mesh happens in run().
    ViscoplasticContact(const Parameters::AllParameters &parameters,
                        const MPI_Comm communicator = MPI_COMM_WORLD);
    // Releases the DoFHandlers before the triangulation they point to.
    ~ViscoplasticContact();

    // Set-up, the time loop and the run summary (viscoplastic_contact.cc).
    void
    run();

    // For studies that compare runs (the convergence study): a function
    // called after every accepted step with the step number and time, and
    // read access to the state it may inspect then, per locally owned cell k
    // (in the order of the stress points) and stress point q.
    void
    set_step_observer(
      const std::function<void(const unsigned int, const double)> &observer);
    struct StressPointState
    {
      const DoFHandler<dim>                          &dof_handler;
      const Quadrature<dim>                          &quadrature;
      const StressPointGeometry<dim>                 &geometry;
      const std::vector<QuadraturePointHistory<dim>> &records;
      const VectorType                               &displacement;

      const std::vector<typename DoFHandler<dim>::active_cell_iterator> &
      cells() const
      {
        return geometry.cells();
      }
      // sigma_n, grad u_n and JxW at stress point q of the k-th owned cell.
      const SymmetricTensor<2, dim> &
      stress(const unsigned int k, const unsigned int q) const
      {
        return records[std::size_t(k) * quadrature.size() + q].stress;
      }
      Tensor<2, dim>
      displacement_gradient(const unsigned int k, const unsigned int q) const
      {
        return geometry.displacement_gradient(displacement, k, q);
      }
      double
      JxW(const unsigned int k, const unsigned int q) const
      {
        return geometry.JxW(k, q);
      }
    };
    StressPointState
    stress_point_state() const
    {
      return {dof_handler,
              discretisation.stress_quadrature[0],
              stress_points,
              quadrature_point_history,
              solution};
    }

  private:
    // @sect4{Set-up}
    //
    // Called in this order by run(): the mesh; then, in setup_on_mesh(), dofs,
    // constraints and vectors, with K; the stress points and their geometry;
    // the contact nodes; the back end with K. Then the header and the limits of
    // the scheme (stability of the explicit update, the uniqueness margin) are
    // printed. setup_on_mesh() runs again whenever the mesh changes (an
    // adaptation, the mesh of a resumed adaptive run); it resets the state.
    void
    make_grid();
    void
    setup_on_mesh();
    void
    setup_system();
    void
    assemble_elastic_operator();
    // The back end of this mesh: Method as set, or for Method = auto the one
    // the cost model (cost_model.h) estimates fastest, from the dofs just
    // distributed and the vertices of the contact boundary.
    void
    choose_back_end();
    void
    setup_stress_points();
    void
    setup_contact();
    void
    setup_back_end();
    // The schedule of the run (or of the checkpoint it resumes), with every
    // load checked at the times it will be evaluated.
    void
    set_up_schedule();
    // The output folder prepared, the header and the limits of the scheme
    // printed, the initial state written.
    void
    prepare_output();
    void
    report_scheme_limits();

    // @sect4{One time step}
    //
    // do_time_step() is the time step as run() sees it: from the current time
    // of the schedule to the next, the step problem solved (with recovery
    // from failed solves), the stresses updated, the step control's decision
    // (adaptive steps: a rejected step is repeated with a shorter one), and
    // the schedule advanced. finish_time_step() is what follows an accepted
    // step; it returns false where the run stops early (Stop after step).
    ActiveSetResult
    do_time_step();
    bool
    finish_time_step(const ActiveSetResult &result, const double wall_time);
    // The step problem from the current time to the next, restarted with a
    // cut step if a solve fails and cutting is allowed; otherwise the run
    // stops with a report.
    ActiveSetResult
    solve_step_with_recovery(const StepStart<dim> &start);
    // b_n = (f_n, v) - (H_n, eps(v)) - (E eps(g_n), eps(v)), from its parts.
    void
    assemble_right_hand_side(const double time);
    void
    assemble_external_load(const double time);

    // @sect4{Prescribed displacements (boundary_conditions.cc)}
    //
    // The values g_n of the step (with the lifting load of the explicit
    // update), a check that every load, prescribed value and gap of the run
    // is finite (all ranks stop with a message naming the entry, before
    // anything is written), and the forces every Dirichlet part and then
    // every plane of symmetry exert on the body at time t_n (collective).
    void
    set_dirichlet_values(const double time);
    void
    check_scene_values();
    std::vector<Tensor<1, dim>>
    reaction_forces(const double time);
    void
    assemble_history_load();
    // The active set around the back end's solves, for the operator it holds.
    ActiveSetResult
    solve_contact_problem(const VectorType &rhs);
    ActiveSetResult
    solve_explicit_step();
    ActiveSetResult
    solve_implicit_step(const double time_step);
    // Newton's method for the implicit step with the step length k in the
    // viscous parameters a = k/(2 lambda) of the materials; the continuation
    // of solve_implicit_step() calls it with k/J, 2k/J, ..., k.
    bool
    implicit_newton(const double     time_step,
                    VectorType      &iterate,
                    ActiveSetResult &result);
    void
    assemble_tangent_system(const VectorType &displacement,
                            const double      time_step);
    // After a cut step: H_n with the new step length (explicit update only).
    void
    rescale_history_increment(const double old_step, const double new_step);
    // sigma_n from u_n at every stress point, and the history of the next step
    // with its load.
    // It also computes error_estimate, the relative estimate of the local
    // error of the step's history update (doc/adaptivity.md).
    void
    update_stresses(const double current_time_step,
                    const double next_time_step);
    // With adaptive steps: H_{n+1} = H_n + k_{n+1} G(sigma_n) and its load,
    // once k_{n+1} is known (explicit update only).
    void
    advance_history(const double next_time_step);

    // Run control, console (pcout prints on rank 0 only) and the report of
    // the run (counts, timers, progress, summary: run/run_report.h).
    const Parameters::AllParameters parameters;
    const MPI_Comm                  mpi_communicator;
    // Whether this rank builds the whole mesh for its group (simplex
    // meshes, mesh_group_size()).
    const bool         mesh_group_root;
    ConditionalOStream pcout;
    RunReport          report;
    // The plan of the run: memory, nested iteration and back end
    // (run/run_plan.h).
    RunPlan<dim> plan;


    // Mesh, finite elements, quadratures, degrees of freedom. The cell types
    // decide the mappings, the elements (P1 or Q1) and the quadratures
    // (discretisation.h); locally_relevant_dofs are those of the owned and
    // the ghost cells: the owned ones and the ghosts of every displacement
    // vector.
    std::unique_ptr<parallel::DistributedTriangulationBase<dim>> triangulation;
    const Discretisation<dim>                                    discretisation;
    DoFHandler<dim>                                              dof_handler;
    DoFHandler<dim> scalar_dof_handler; // nodal output
    // The layout (owned entries and ghosts) of the nodal output fields.
    std::shared_ptr<const Utilities::MPI::Partitioner> scalar_partitioner;
    IndexSet                                           locally_owned_dofs;
    IndexSet                                           locally_relevant_dofs;
    AffineConstraints<double>                          constraints;

    // The elastic operator K (assembled once per run) and, for the implicit
    // update, the tangent and internal force of the current Newton iterate.
    // The report counts the assemblies: the run summary shows a change that
    // re-assembles more often than intended.
    MatrixType stiffness_matrix;
    MatrixType tangent_matrix;
    VectorType internal_force;

    // The back end that solves the step problems (the plan chose it).
    std::unique_ptr<ContactSolver<dim>> contact_solver;

    // u_n (with ghost entries), f_n, -(H_n, eps(v)), their sum. All four share
    // the partition of solution; the three loads are assembled on the owned
    // cells and compressed, so they hold owned entries only.
    VectorType solution;
    VectorType external_load;
    VectorType history_load;
    VectorType system_rhs;

    // The start of each step extrapolated from the two before it, with what
    // it extrapolates from (acceleration/predicted_start.h), and the step
    // solved first on the mesh coarsened once (Step cycles,
    // acceleration/step_cycles.h), which reads this object's state.
    PredictedStart<dim> predicted_start;
    StepCycles<dim>     step_cycles;
    friend class StepCycles<dim>;
    // The initial cycles (acceleration/initial_cycles.h) and the mesh
    // adaptation (mesh/mesh_adaptation.h) change the mesh of this object and
    // carry its state over.
    friend class InitialCycles<dim>;
    friend class MeshAdaptation<dim>;
    // The saved start of a step, cuts and the error test of adaptive steps
    // (run/step_control.h).
    friend class StepControl<dim>;
    // The smallest eigenvalue of the uniqueness check, once computed (on the
    // first mesh of the run, the coarsest of the initial cycles); a resumed
    // run takes it from the checkpoint, so that it decides as the
    // uninterrupted run did and skips the Lanczos iteration on the fine mesh
    // (567 s of a resume at 10.7M dofs on one rank).
    std::optional<double> uniqueness_eigenvalue;

    // The materials (materials.h) and the state at the stress points of the
    // locally owned cells. quadrature_point_history is a flat array: the
    // record of stress point q of the k-th owned cell is entry k * n_q + q,
    // with n_q = stress_quadrature.size(), holding sigma_n, the history
    // H_{n+1} of the next step and the law's internal variable.
    // max_von_mises is the maximum over all ranks of the last stress update.
    Materials<dim>                           materials;
    std::vector<QuadraturePointHistory<dim>> quadrature_point_history;
    double                                   max_von_mises = 0;
    // The relative error estimate of the last stress update.
    double error_estimate = 0;

    // The loads of the scene (scene/loads.h).
    Loads<dim> loads;

    // The owned cells, their dofs and the geometry of their stress points
    // (stress_points.h), for the cell loops of the time loop.
    StressPointGeometry<dim> stress_points;
    // The Dirichlet parts and planes of symmetry: constraints, values g_n,
    // lifting load and reactions (scene/prescribed_displacements.h).
    PrescribedDisplacements<dim> prescribed;

    // Contact: the nodes of Gamma_3 this rank owns, with their pieces, their
    // last (r, z) and their active-set parameters c_i. contact_enabled is false
    // without Gamma_3 or with a law that is void (zero and no rigid limit);
    // then the step problem is a single linear solve.
    bool            contact_enabled = false;
    ContactSet<dim> contact_set;
    // The contact zones of the scene, with their laws and obstacles
    // (scene/contact_zones.h).
    ContactZones<dim> contact_zones;
    // The laws with a history at the contact nodes (contact_histories.h):
    // each step's memory pressures, adhesive scales, worn gaps and reached
    // cohesive openings come from them, each accepted step adds to them.
    ContactHistories contact_histories;
    // The gaps of the contact nodes at the given time (collective: a value
    // that is not finite stops all ranks, naming the entry).
    void
    set_gaps(const double time);

    // Called after every accepted step (set_step_observer()).
    std::function<void(const unsigned int, const double)> step_observer;

    // The time levels of the run, the steps taken and the step controller's
    // state: what a checkpoint stores and a resumed run restores.
    TimeSchedule schedule;
    // The controller of adaptive steps, with the cap of the explicit update
    // (set with the schedule).
    TimeStepController step_controller;

    // What the run writes: the output folder (opened by run() before the
    // set-up, which checks and locks it), the records, the time series, the
    // profiles and the summary (run/run_output.h).
    RunOutput<dim> output;
    friend class RunOutput<dim>;
    // What a checkpoint stores and a resumed run restores
    // (run/checkpoints.h), which reads and sets this object's state.
    Checkpoints<dim> checkpoints;
    friend class Checkpoints<dim>;
  };
} // namespace ViscoContact

#endif
