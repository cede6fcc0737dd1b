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

#include "acceleration/predicted_start.h"
#include "acceleration/step_cycles.h"
#include "back_ends/contact_solver.h"
#include "back_ends/linear_algebra.h"
#include "constraints.h"
#include "contact_nodes.h"
#include "contact_set.h"
#include "scene/contact_zones.h"
#include "scene/loads.h"
#include "elastic_operator.h"
#include "material.h"
#include "parameters.h"
#include "scene/prescribed_displacements.h"
#include "robustness/checkpoint_file.h"
#include "robustness/output_folder.h"
#include "run/run_plan.h"
#include "run/run_report.h"
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
    // called after every time step with the step number and time, and read
    // access to the state it may inspect then.
    void
    set_step_observer(
      const std::function<void(const unsigned int, const double)> &observer);
    const DoFHandler<dim> &
    get_dof_handler() const;
    const Quadrature<dim> &
    get_stress_quadrature() const;
    // The locally owned cells, in the order of the stress-point data.
    const std::vector<typename DoFHandler<dim>::active_cell_iterator> &
    get_owned_cells() const;
    // sigma_n and grad u_n at stress point q of the k-th locally owned cell.
    const SymmetricTensor<2, dim> &
    get_stress(const unsigned int k, const unsigned int q) const;
    Tensor<2, dim>
    get_displacement_gradient(const unsigned int k, const unsigned int q) const;
    // JxW of stress point q of the k-th locally owned cell.
    double
    get_stress_point_weight(const unsigned int k, const unsigned int q) const;

  private:
    // Which history update the steps run. Without plasticity the history
    // stays zero and both updates are the elastic problem, so the implicit
    // update's Newton iteration only runs with plasticity on.
    bool
    implicit_update() const;
    bool
    explicit_history_update() const;

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
    // The matrix-free back end: no matrix of K is assembled; the back end
    // applies it cell by cell.
    bool
    matrix_free() const
    {
      return plan.back_end().method == Parameters::Method::matrix_free;
    }
    // The elasticity tensor of a cell's material.
    ElasticityOfCell<dim>
    cell_elasticity() const;
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
    print_header(const unsigned int n_steps) const;
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
    // The state at the start of a step that a failed or rejected attempt is
    // undone with: u_{n-1}, the contact state, and with adaptive steps the
    // stress-point records and the step length their history was advanced
    // for.
    struct StepStartState
    {
      VectorType                               solution;
      ContactNodes::State                      contact;
      std::vector<QuadraturePointHistory<dim>> stress_point_records;
      double                                   step_length;
    };
    StepStartState
    save_step_start() const;
    // u_{n-1} and the contact state (the stress points are restored apart,
    // where needed).
    void
    restore_step_start(const StepStartState &start);
    // The step problem from the current time to the next, restarted with a
    // cut step if a solve fails and cutting is allowed; otherwise the run
    // stops with a report.
    ActiveSetResult
    solve_step_with_recovery(const StepStartState &start);
    bool
    cut_failed_step(const std::string &failure);
    // b_n = (f_n, v) - (H_n, eps(v)) - (E eps(g_n), eps(v)), from its parts.
    void
    assemble_right_hand_side(const double time);
    void
    assemble_external_load(const double time);
    // (f, v) + (f_2, v)_Gamma2 of one cell into cell_rhs (dofs ordered
    // (vertex, component)) at the time the load functions are set to; false
    // if the cell carries no load. problem gets the first value that is not
    // finite.
    bool
    cell_external_load(
      const typename DoFHandler<dim>::active_cell_iterator &cell,
      FEValues<dim>                                        &fe_values,
      FEFaceValues<dim>                                    &fe_face_values,
      Vector<double>                                       &cell_rhs,
      std::string                                          &problem);

    // @sect4{Prescribed displacements (boundary_conditions.cc)}
    //
    // The values g_n of the step (with the lifting load of the explicit
    // update), a check that every prescribed value and gap of the run is
    // finite (all ranks stop with a message naming the entry, before
    // anything is written), and the forces every Dirichlet part and then
    // every plane of symmetry exert on the body at time t_n (collective).
    void
    set_dirichlet_values(const double time);
    void
    check_prescribed_values();
    std::vector<Tensor<1, dim>>
    reaction_forces(const double time);
    // Every load value at the load points and the times of the run is
    // finite, or all ranks stop with a message naming the entry.
    void
    check_loads();
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
    // What update_stresses() does at every stress point of a step: which
    // update, whether the history of the next step and the error estimate
    // are computed, and the two step lengths.
    struct StressUpdateStep
    {
      bool   implicit;
      bool   update_history;
      bool   estimate;
      double current_time_step;
      double next_time_step;
    };
    StressUpdateStep
    stress_update_step(const double current_time_step,
                       const double next_time_step) const;
    void
    stop_on_non_finite_stresses() const;
    // One stress point q of the k-th owned cell: sigma_n, the history and
    // its load into cell_vector, the largest von Mises stress of the cell
    // so far, and the point's terms of the error estimate.
    void
    update_stress_point(const StressUpdateStep  &step,
                        const unsigned int       k,
                        const unsigned int       q,
                        const ArrayView<double> &cell_vector,
                        double                  &max_von_mises_of_cell,
                        std::array<double, 3>   &estimate_sums);
    // The step's relative error estimate from the sums over the rank's
    // stress points (doc/adaptivity.md); collective.
    double
    step_error_estimate(const std::array<double, 3> &local_sums,
                        const double                 time_step) const;
    // With adaptive steps: H_{n+1} = H_n + k_{n+1} G(sigma_n) and its load,
    // once k_{n+1} is known (explicit update only).
    void
    advance_history(const double next_time_step);

    // @sect4{Adaptive time steps}
    //
    // The controller's side of the time step (doc/adaptivity.md): the
    // controller, the times the steps must land on (Profile times, End
    // time), and the error test of a solved step: accepted (with the step
    // the controller proposes next), or rejected and the state at its start
    // restored for a shorter step.
    TimeStepController
    time_step_controller() const;
    std::vector<double>
    landing_targets() const;
    bool
    accept_adaptive_step(const StepStartState &start, double &proposed_step);

    // @sect4{Output}
    //
    // .pvtu records with their .pvd list, one CSV row per step, contact
    // profiles, and the run summary with its cost measurements. What is written
    // is either reduced over the ranks (counts, forces, norms: written by rank
    // 0) or each rank's own part of one file (written collectively).
    void
    check_output_directory();
    void
    prepare_output_directory(const unsigned int resume_step);
    void
    output_results(const unsigned int step,
                   const double       time,
                   const std::string &stem = "solution");
    // The fields of a record: per cell (an entry per active cell, set on the
    // owned ones; material_id and stress_zz empty where not written) and at
    // the vertices (the contact fields, and with friction the friction
    // fields; friction_state empty without), with their ghosts.
    struct OutputFields
    {
      std::vector<Vector<float>> stress, viscoplastic;
      Vector<float>              von_mises, subdomain, material_id, stress_zz;
      std::vector<VectorType>    contact;
      VectorType                 tangential_traction, slip, friction_state;

      void
      add_to(DataOut<dim>          &data_out,
             const DoFHandler<dim> &dof_handler,
             const DoFHandler<dim> &scalar_dof_handler) const;
    };
    OutputFields
    compute_output_fields() const;
    void
    write_time_series_row(const unsigned int     step,
                          const double           time,
                          const double           time_step,
                          const ActiveSetResult &result,
                          const double           wall_time);
    void
    write_contact_profile(const unsigned int step, const double time);
    void
    print_run_summary();
    // The reference costs of the run summary, measured after the run: one
    // solve with the step operator and no contact, one stress update.
    RunReport::CostMeasurement
    measure_reference_costs();

    // @sect4{Mesh adaptation}
    //
    // Every Refinement interval steps (mesh_adaptation.cc, doc/adaptivity.md):
    // the indicator (Kelly's estimator of the displacement, raised at the
    // contact front and at the boundary of the plastic zone), refinement and
    // coarsening of the p4est mesh with the displacement, the stress-point data
    // and the contact pressures carried over, the set-up on the new mesh and
    // the contact set re-established. A resumed adaptive run first rebuilds
    // the checkpoint's mesh.
    //
    // Both the adaptation during the run and the initial cycles (nested
    // iteration on the first step) on p4est mark cells and then call
    // refine_and_transfer(), which changes the mesh, sets everything up on it
    // and carries u and the contact pressure over, and the stress-point data
    // if asked to (the initial cycles start every mesh from the initial
    // history instead); on simplices the initial cycles call
    // rebuild_and_transfer().
    bool
    adaptation_due() const;
    void
    adapt_mesh(const double time);
    Vector<float>
    refinement_indicators() const;
    bool
    mark_cells_by_indicators();
    void
    refine_and_transfer(const bool transfer_stress_points);
    // The initial cycles on a simplex mesh (deal.II 9.4's fully distributed
    // triangulation cannot refine): the next mesh, the parameter file's
    // coarsened coarsenings times, is built anew, and u and the contact
    // pressure are interpolated to it from the current mesh.
    void
    rebuild_and_transfer(const unsigned int coarsenings);
    // The contact pressure as a nodal field of the displacement's layout
    // (at the x-dof of each contact node), for the transfer.
    VectorType
    contact_pressure_field() const;
    // After a transfer: each contact node's (r, z) from u and the pressure
    // field, the piece they name, friction from stick.
    void
    set_contact_state_from(const VectorType &pressure);
    // Debug builds: the transferred stress points reproduce E eps(u) on the
    // children of refined_parents (implicit update).
    void
    check_stress_point_transfer(const std::set<CellId> &refined_parents) const;
    void
    solve_initial_cycles();
    void
    restore_checkpoint_mesh();

    // The contact state of this rank's nodes from u and a nodal pressure
    // field; their stick/slip states only with_friction.
    void
    set_pieces_from(const VectorType &pressure,
                    const bool        with_friction = false);

    // @sect4{Checkpoints}
    //
    // One file per checkpoint with one record per cell, keyed by the cell's id,
    // so that a run can be resumed on any number of ranks (checkpoint.h).
    void
    write_checkpoint(const double wall_time);
    // The header of a checkpoint file (the same on every rank; rank 0's is
    // written); the vectors the records hold besides u, with their ghost
    // values; and the records of stress_points.cells()[first, end).
    ByteWriter
    checkpoint_header(const double wall_time) const;
    std::array<VectorType, 4>
    checkpoint_vectors() const;
    void
    write_cell_records(const std::array<VectorType, 4> &vectors,
                       const std::size_t                first,
                       const std::size_t                end,
                       char                            *out) const;
    // A scheduler's signal received on any rank: all ranks stop after this
    // step, with a checkpoint of it (unless one was just written).
    void
    stop_if_signalled(const bool checkpoint_written, const double wall_time);
    // Collective. Resumes from the last checkpoint: the mesh, the header
    // (schedule, counters, .pvd list), the records of the owned cells, and
    // what the time loop derives from them.
    void
    resume_from_checkpoint();
    struct CheckpointFlags
    {
      bool has_step_start;
    };
    CheckpointFlags
    read_checkpoint_header(ByteReader &header, const unsigned int step);
    // The schedule after the checkpoint for this run's End time; returns the
    // next step's length before and after.
    std::pair<double, double>
    continue_schedule_after_checkpoint();
    // The values a checkpoint stores at the dofs of every cell besides u
    // (restored into solution): the contact state, the start of the step,
    // the nodes' history and their friction state.
    struct CellRecordVectors
    {
      VectorType contact_state;
      VectorType start_displacement;
      VectorType node_history;
      VectorType friction_state;
    };
    // The records of this rank's share of the file sent to the owners of
    // their cells and restored on the owned dofs and stress points, after
    // check_header() has read the header; false on a rank that did not find
    // all its cells.
    bool
    restore_cell_records(const std::string           &file,
                         std::vector<char>           &header,
                         CellRecordVectors           &vectors,
                         const std::function<void()> &check_header);
    void
    restore_contact_nodes(const CellRecordVectors &vectors,
                          const ByteReader        &header);
    void
    restore_prediction_start(const CellRecordVectors &vectors,
                             const CheckpointFlags   &flags);
    // The bytes of a cell's record in a checkpoint file: the cell id, the
    // values of the vectors at the cell's dofs, its stress-point records.
    std::size_t
    checkpoint_record_size() const;


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


    // Mesh, finite elements, quadratures, degrees of freedom. The reference
    // cell (simplex or hypercube) decides the mapping, the element (P1 or Q1)
    // and the quadratures; fe is the vector-valued element of the displacement.
    // The stress quadrature holds the stress points (one per simplex, 2^dim
    // Gauss points per hypercube), the load quadrature integrates the external
    // loads. locally_relevant_dofs are those of the owned and the ghost cells:
    // the owned ones and the ghosts of every displacement vector.
    std::unique_ptr<parallel::DistributedTriangulationBase<dim>> triangulation;
    const ReferenceCell                                          reference_cell;
    const Mapping<dim>                                          &mapping;
    const std::unique_ptr<FiniteElement<dim>>                    fe;
    const std::unique_ptr<FiniteElement<dim>> scalar_fe; // nodal output
    DoFHandler<dim>                           dof_handler;
    DoFHandler<dim>                           scalar_dof_handler;
    // The layout (owned entries and ghosts) of the nodal output fields.
    std::shared_ptr<const Utilities::MPI::Partitioner> scalar_partitioner;
    const Quadrature<dim>                              stress_quadrature;
    const Quadrature<dim>                              load_quadrature;
    const Quadrature<dim - 1>                          face_quadrature;
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
    // The smallest eigenvalue of the uniqueness check, once computed (on the
    // first mesh of the run, the coarsest of the initial cycles); a resumed
    // run takes it from the checkpoint, so that it decides as the
    // uninterrupted run did and skips the Lanczos iteration on the fine mesh
    // (567 s of a resume at 10.7M dofs on one rank).
    std::optional<double> uniqueness_eigenvalue;

    // Materials, loads, and the state at the stress points of the locally
    // owned cells. materials holds the laws (material_law.h) of subsection
    // Material and of the numbered ones that are used, in that order;
    // material_index the index of each material id (empty with one material
    // for every cell), cell_material that of each owned cell k
    // (material_of(k)). quadrature_point_history is a flat array: the record
    // of stress point q of the k-th owned cell is entry k * n_q + q, with n_q
    // = stress_quadrature.size(), holding sigma_n, the history H_{n+1} of
    // the next step and the law's internal variable. max_von_mises is the
    // maximum over all ranks of the last stress update.
    std::vector<std::unique_ptr<const MaterialLaw<dim>>> materials;
    std::map<types::material_id, unsigned int>           material_index;
    std::vector<unsigned int>                            cell_material;
    unsigned int
    material_number(const types::material_id id) const
    {
      return material_index.empty() ? 0 : material_index.at(id);
    }
    const MaterialLaw<dim> &
    material_of(const unsigned int k) const
    {
      return *materials[cell_material[k]];
    }
    // The von Mises stress of a record of the k-th owned cell (with its
    // sigma_zz in 2D plane strain).
    double
    von_mises_stress(const unsigned int                 k,
                     const QuadraturePointHistory<dim> &state) const
    {
      double stress_zz = 0;
      if constexpr (dim == 2)
        stress_zz = state.stress_zz;
      return material_of(k).equivalent_stress(state.stress, stress_zz);
    }
    // The largest step of the explicit history update that is stable: the
    // smallest of the materials' (4 lambda / lambda_max(E) for Perzyna's).
    double
    explicit_stability_limit() const;

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
    // The gaps of the contact nodes at the given time (collective: a value
    // that is not finite stops all ranks, naming the entry).
    void
    set_gaps(const double time);

    // Called after every accepted step (set_step_observer()).
    std::function<void(const unsigned int, const double)> step_observer;

    // The time levels of the run, the steps taken and the step controller's
    // state: what a checkpoint stores and a resumed run restores.
    TimeSchedule schedule;

    // The output folder (created by run() before the set-up, which checks
    // and locks it), the .pvd list (kept on rank 0), and the step of the
    // last checkpoint.
    std::unique_ptr<OutputFolder>               output_folder;
    std::vector<std::pair<double, std::string>> times_and_names;
    unsigned int last_checkpoint_step = numbers::invalid_unsigned_int;
  };
} // namespace ViscoContact

#endif
