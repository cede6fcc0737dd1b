// ViscoplasticContact<dim>: the constructor, the algorithm (run), and the
// access the convergence study needs.

#include <deal.II/base/exceptions.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/utilities.h>

#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_simplex_p.h>
#include <deal.II/fe/fe_system.h>

#include "checkpoint.h"
#include "loads.h"
#include "robustness/stop_signals.h"
#include "time_loop.h"
#include "viscoplastic_contact.h"

#include <cmath>
#include <fstream>
#include <iomanip>
#include <limits>
#include <sstream>

namespace ViscoContact
{
  namespace
  {
    // The two helpers of the constructor's initialiser list, which must decide
    // before the body runs: the reference cell named by the parameter file's
    // Cell type, and the scalar linear Lagrange element on it (P1 on triangles
    // and tetrahedra, Q1 on quadrilaterals and hexahedra). The displacement
    // element is dim copies of the scalar one (FESystem); the scalar one alone
    // carries the nodal contact fields of the output.
    template <int dim>
    ReferenceCell
    reference_cell_of(const Parameters::AllParameters &parameters)
    {
      return parameters.cell_type == Parameters::CellType::simplex
               ? ReferenceCells::get_simplex<dim>()
               : ReferenceCells::get_hypercube<dim>();
    }

    template <int dim>
    std::unique_ptr<FiniteElement<dim>>
    linear_element(const ReferenceCell &cell)
    {
      if (cell.is_simplex())
        return std::make_unique<FE_SimplexP<dim>>(1);
      return std::make_unique<FE_Q<dim>>(1);
    }
  } // namespace



  // @sect4{ViscoplasticContact::ViscoplasticContact}
  //
  // The choice between simplices and hypercubes is made here, once: the
  // reference cell gives the mapping, the finite element (P1 or Q1) and the
  // quadratures, and everything else is written for either. On simplices the P1
  // strain is constant per cell and one stress point per cell is the
  // piecewise-constant stress space; on hypercubes the stresses live at the
  // 2^dim Gauss points (doc/model.md, section 2). The same stress quadrature is
  // used to assemble K, so that (sigma, eps(v)) summed over the stress points
  // is exactly (K u)(v) + (H, eps(v)): the operator and the history load are
  // integrated alike.
  //
  // The loads get a quadrature of their own (deal.II's Gauss-type rule of order
  // 2 for the cell type), and the face quadrature is built on the reference
  // face of the cell type (all faces of a cell have the same shape here).
  // Nothing is done with the mesh yet: the constructor creates the element and
  // the quadratures and parses the loads, and run() builds everything else.
  template <int dim>
  ViscoplasticContact<dim>::ViscoplasticContact(
    const Parameters::AllParameters &parameters,
    const MPI_Comm                   communicator)
    : parameters(parameters)
    , mpi_communicator(communicator)
    , pcout(std::cout, Utilities::MPI::this_mpi_process(communicator) == 0)
    , computing_timer(communicator,
                      pcout,
                      TimerOutput::never,
                      TimerOutput::wall_times)
    , reference_cell(reference_cell_of<dim>(parameters))
    , mapping(reference_cell.template get_default_linear_mapping<dim>())
    , fe(std::make_unique<FESystem<dim>>(*linear_element<dim>(reference_cell),
                                         dim))
    , scalar_fe(linear_element<dim>(reference_cell))
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
    // main() instantiates the class for the Dimension the parameter file names;
    // a mismatch is a programming error.
    AssertThrow(parameters.dimension == dim, ExcInternalError());
    // The load expressions of subsection Loads, parsed once (a bad expression
    // stops the run here, naming the entry). Two facts about them save work in
    // every step: a body force that is the literal zero is not integrated at
    // all, and loads that do not mention t are assembled only once
    // (assemble_right_hand_side()).
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



  // @sect4{ViscoplasticContact::~ViscoplasticContact}
  template <int dim>
  ViscoplasticContact<dim>::~ViscoplasticContact()
  {
    // The DoFHandlers refer to the triangulation: release them first.
    scalar_dof_handler.clear();
    dof_handler.clear();
  }



  // @sect4{ViscoplasticContact::implicit_update}
  //
  // The two ways of updating the history (doc/model.md, sections 2 and 3),
  // decided from the parameters in one place: the implicit update runs only
  // with plasticity on; the explicit one adds a history load only then.
  template <int dim>
  bool
  ViscoplasticContact<dim>::implicit_update() const
  {
    return parameters.plasticity
           && parameters.stress_update
                == Parameters::StressUpdate::implicit_euler;
  }



  template <int dim>
  bool
  ViscoplasticContact<dim>::explicit_history_update() const
  {
    return parameters.plasticity && !implicit_update();
  }



  // @sect4{ViscoplasticContact::check_memory_estimate}
  //
  // The size of a generated box follows from the parameters alone: (N 2^r +
  // 1)^dim vertices for N Subdivisions and r Global refinements (plus a centre
  // vertex per square for the crossed pattern), dim dofs per vertex. The
  // memory per dof was measured on the benchmark scenes (peak resident memory
  // of runs of 10^4 to 10^5 dofs on one rank, both back ends): about 2 kB per
  // dof in 2D and 13 kB in 3D, where the direct factorisations fill in more,
  // plus some 150 MB for the libraries. Both are lower estimates (the fill-in
  // of a factorisation grows faster than the dofs), so a mesh is refused only
  // if it certainly does not fit: if the estimate exceeds the physical memory
  // of the ranks' nodes (MemTotal of /proc/meminfo, shared among the ranks of
  // a node). A Gmsh mesh is only known once read; it is not estimated here.
  template <int dim>
  void
  ViscoplasticContact<dim>::check_memory_estimate() const
  {
    if (!parameters.mesh_file.empty())
      return;
    const double edge
      = parameters.subdivisions * std::pow(2., parameters.global_refinements);
    double vertices = std::pow(edge + 1, dim);
    if (parameters.cell_type == Parameters::CellType::simplex
        && parameters.simplex_pattern == Parameters::SimplexPattern::crossed)
      vertices += std::pow(edge, dim);
    const double dofs  = dim * vertices;
    const double bytes = 150e6 + dofs * (dim == 2 ? 2e3 : 13e3);

    // The memory of this rank's node, shared by the ranks on it; summed over
    // the ranks, the memory of all nodes of the run.
    double node_memory = 0;
    {
      std::ifstream meminfo("/proc/meminfo");
      std::string   key;
      double        kilobytes = 0;
      while (meminfo >> key >> kilobytes)
        {
          if (key == "MemTotal:")
            {
              node_memory = kilobytes * 1024;
              break;
            }
          meminfo.ignore(std::numeric_limits<std::streamsize>::max(), '\n');
        }
    }
    MPI_Comm node_communicator;
    MPI_Comm_split_type(mpi_communicator,
                        MPI_COMM_TYPE_SHARED,
                        0,
                        MPI_INFO_NULL,
                        &node_communicator);
    const unsigned int ranks_on_node
      = Utilities::MPI::n_mpi_processes(node_communicator);
    MPI_Comm_free(&node_communicator);
    const double available
      = Utilities::MPI::sum(node_memory / ranks_on_node, mpi_communicator);
    // Without /proc/meminfo (not Linux) the check is skipped.
    if (available <= 0 || bytes <= available)
      return;

    std::ostringstream message;
    message << std::setprecision(3) << "Invalid parameter <Subdivisions> in "
            << "subsection <Geometry>: value <" << parameters.subdivisions
            << ">";
    if (parameters.global_refinements > 0)
      message << " with <Global refinements> = "
              << parameters.global_refinements;
    message << "; the mesh would have about " << dofs
            << " displacement dofs and need at least " << bytes / 1e9
            << " GB of memory, but the nodes of this run have "
            << available / 1e9
            << " GB; accepted: a mesh that fits (fewer Subdivisions or "
               "Global refinements, or more nodes).";
    AssertThrow(false, ExcMessage(message.str()));
  }



  // @sect4{ViscoplasticContact::run}
  //
  // The algorithm of doc/model.md, section 2, as the reader would write it
  // down: set up, then for each time step assemble the right-hand side,
  // solve the step's variational-hemivariational inequality by the
  // active-set method (for the implicit update: a Newton iteration of such
  // solves), update the stresses and the history, and write the results.
  // Around it: a resumed run starts after the step of its checkpoint, a
  // checkpoint is written every Checkpoint interval steps, and a run may be
  // told to stop after a given step (as if it had been killed).
  //
  // The schedule, times, is a vector that may grow during the run: a step whose
  // solve fails may be cut in half, which inserts a new time level
  // (solve_step_with_recovery()). That is why the loop runs to times.size() and
  // recomputes the number of steps after every step, and why "the next step" is
  // read off the schedule only after the current one was accepted.
  template <int dim>
  void
  ViscoplasticContact<dim>::run()
  {
    // Set-up: the mesh, then everything that depends on it (setup_on_mesh()).
    // A folder with another run's files is refused before any work is done
    // (or, with Overwrite = true, cleared later by prepare_output_directory()).
    check_output_directory();
    // A generated mesh far too large for the machine is refused before it is
    // built, with the estimate, instead of ending in std::bad_alloc.
    check_memory_estimate();
    make_grid();
    // A scheduler's signal during the set-up stops the run between its
    // phases (there is no step to save yet).
    StopSignals::stop_if_received(mpi_communicator, "after the mesh");
    setup_on_mesh();
    StopSignals::stop_if_received(mpi_communicator,
                                  "after the operator and the back end");

    // t_n = n k with the last step shortened to end at T. A resumed run
    // replaces the schedule by the one of its checkpoint (with the cut steps of
    // the interrupted run), restores the state, and continues after the
    // checkpoint's step. This happens before the output directory is prepared,
    // so that a damaged or mismatched checkpoint stops the run before the
    // output directory is modified.
    std::vector<double> times
      = time_levels(parameters.end_time, parameters.time_step);
    // The loads at every point and time they will be evaluated: a load that
    // is not finite stops the run here, naming the entry, the point and the
    // time, before anything is read or written. (Adaptive steps are checked
    // at the levels of Time step; the assembly checks every value it
    // computes.)
    check_loads(times);
    // With adaptive steps the schedule holds the accepted levels and the next
    // one: t_0 = 0 and t_1 after the first step, Time step within the
    // controller's range and fitted to the targets. Each accepted step
    // appends the next level (doc/adaptivity.md).
    const bool adaptive
      = parameters.time_step_control == Parameters::TimeStepControl::adaptive;
    if (adaptive)
      {
        const TimeStepController controller = time_step_controller();
        desired_time_step
          = std::min(std::max(parameters.time_step, controller.minimum_step),
                     controller.maximum_step);
        times = {0., next_time_level(0., desired_time_step, landing_targets())};
      }
    unsigned int first_step = 1;
    if (parameters.resume)
      first_step = resume_from_checkpoint(times) + 1;
    // The output volume: the .vtu records must fit on the disk.
    check_output_volume(times.size() - 1);
    StopSignals::stop_if_received(mpi_communicator,
                                  "before the output folder was prepared");
    prepare_output_directory(first_step - 1);
    // The header and the limits of the scheme go to the console before the
    // first step, so that a user sees a warning (unstable time step, several
    // solutions possible) at once and not after the run.
    n_time_steps = times.size() - 1;
    print_header(n_time_steps);
    report_scheme_limits();

    // The step whose contact profile is written for a requested time is the
    // one closest to it in the schedule (which a cut step refines).
    const auto is_profile_step = [&](const unsigned int n) {
      for (const double target : parameters.profile_times)
        {
          unsigned int closest = 0;
          for (unsigned int m = 1; m < times.size(); ++m)
            if (std::abs(times[m] - target) < std::abs(times[closest] - target))
              closest = m;
          if (closest == n)
            return true;
        }
      return false;
    };

    // The initial state u_0 = 0, sigma_0 = 0 as record 0; a resumed run has it
    // already.
    if (parameters.write_vtu && first_step == 1)
      output_results(0, 0.);

    // The time loop. The wall time written per step counts from the start of
    // the original run: a resumed run adds the time the interrupted run had
    // spent up to its checkpoint (loop_time_offset), so that the time series
    // reads as one run.
    Timer loop_timer;
    for (unsigned int n = first_step; n < times.size(); ++n)
      {
        // Adaptive and cut steps are not counted before the run: their number
        // is bounded here (fixed schedules were checked with the parameters).
        check_step_count(n, times[n - 1]);
        // One step: solve for u_n (retrying with cut steps if necessary), then
        // the stresses sigma_n at every stress point and the history of the
        // next step, whose length is the distance to the next time level (0
        // after the last step, where no history is needed). Only this part
        // counts as compute time; output is timed apart.
        //
        // With adaptive steps the step comes with its error test
        // (solve_adaptive_step(), which also updates the stresses), and only
        // then is the next level known: the controller's step fitted to the
        // targets, with the history advanced for it.
        Timer step_timer;
        // With Initial cycles, step 1 is first solved on coarser meshes, each
        // solution the start of the next (nested iteration,
        // solve_initial_cycles()); the step below is then the solve on the
        // last mesh, and its time includes the cycles.
        if (n == 1 && parameters.initial_cycles > 0)
          solve_initial_cycles(times);
        // u_{n-1} and z_{n-1}: once step n is accepted, the start the next
        // step's prediction extrapolates from (predict_step_start()), copied
        // only if there is a prediction. Not the initial state u_0 = 0: a
        // load already present at t = 0 makes the first step a jump, not a
        // piece of a smooth path to extrapolate.
        const bool keep_step_start = parameters.predicted_start && n > 1;
        StepStart  step_start;
        if (keep_step_start)
          step_start = {solution, contact_set.z};
        const ActiveSetResult result = adaptive
                                         ? solve_adaptive_step(n, times)
                                         : solve_step_with_recovery(n, times);
        if (keep_step_start)
          previous_step_start = std::move(step_start);
        if (!adaptive)
          update_stresses(times[n] - times[n - 1],
                          n + 1 < times.size() ? times[n + 1] - times[n] : 0.);
        else
          {
            times.resize(n + 1);
            if (times[n] < parameters.end_time * (1 - 1e-12))
              {
                times.push_back(next_time_level(times[n],
                                                desired_time_step,
                                                landing_targets()));
                if (explicit_history_update())
                  advance_history(times[n + 1] - times[n]);
              }
          }
        time_loop_compute_time += step_timer.wall_time();
        // A cut step has inserted a level: the number of steps is that of the
        // current schedule (with adaptive steps: those taken so far).
        n_time_steps = adaptive ? n : times.size() - 1;
        n_steps_done = n;
        if (step_observer)
          step_observer(n, times[n]);

        // What is written per step. The time-series row and the step line
        // contain sums over the ranks: every rank calls count_contact_states()
        // and total_contact_force(), which are collective, and rank 0 prints.
        // The contact profile and the .pvtu record are written by all ranks
        // into shared files.
        const double wall_time = loop_time_offset + loop_timer.wall_time();
        write_time_series_row(n,
                              times[n],
                              times[n] - times[n - 1],
                              result,
                              wall_time);
        if (parameters.verbose && !adaptive)
          print_step_line(pcout,
                          n,
                          times[n],
                          result.iterations(),
                          count_contact_states(),
                          total_contact_force());
        if (parameters.verbose && adaptive)
          print_adaptive_step_line(pcout,
                                   n,
                                   times[n],
                                   result.iterations(),
                                   count_contact_states(),
                                   total_contact_force(),
                                   times[n] - times[n - 1],
                                   error_estimate);
        if (contact_enabled && is_profile_step(n))
          write_contact_profile(n, times[n]);
        if (parameters.write_vtu
            && (n % parameters.interval == 0 || n + 1 == times.size()))
          output_results(n, times[n]);
        // With Adaptive refinement, the mesh of the next steps: after the
        // output of step n (which shows the mesh step n was computed on) and
        // before its checkpoint (which stores the adapted mesh and state).
        if (adaptation_due(n, times.size() - 1))
          adapt_mesh(times[n]);
        // The checkpoint comes after the output of the step, so that a run
        // resumed from it has everything of step n on disk, and the .pvd list
        // the checkpoint stores includes step n.
        const bool checkpoint_due = parameters.checkpoint_interval > 0
                                    && n % parameters.checkpoint_interval == 0;
        if (checkpoint_due)
          write_checkpoint(n, times, wall_time);
        // A scheduler's signal (SIGTERM, SIGINT, SIGUSR1) on any rank: every
        // rank learns of it here, once per step, through the maximum over the
        // ranks, so that all stop after this same step. The step is complete
        // and written; a checkpoint of it is written if none is due, and the
        // run ends with status 128 + signal (main()). After the last step
        // there is nothing left to save the run for: it ends normally.
        const int signal
          = Utilities::MPI::max(StopSignals::received(), mpi_communicator);
        if (signal != 0 && n + 1 < times.size() && !parameters.resumable)
          {
            pcout << "Stopped after step " << n << " (t = " << times[n]
                  << ") on " << StopSignals::name(signal)
                  << "; a convergence study cannot be resumed: run it "
                     "again."
                  << std::endl;
            throw StopSignals::Stopped{signal};
          }
        if (signal != 0 && n + 1 < times.size())
          {
            if (!checkpoint_due)
              write_checkpoint(n, times, wall_time);
            pcout << "Stopped after step " << n << " (t = " << times[n]
                  << ") on " << StopSignals::name(signal)
                  << "; the checkpoint of step " << n << " is in "
                  << output_folder->path(checkpoint_folder)
                  << ".\nTo continue the run, set Resume = true in "
                     "subsection <Checkpoint> and run the same parameter "
                     "file again (on any number of MPI ranks)."
                  << std::endl;
            throw StopSignals::Stopped{signal};
          }
        // For tests of the checkpoints: end the loop here as if the run had
        // been killed after the checkpoint; the summary is still printed.
        if (n == parameters.stop_after_step)
          {
            pcout << "Stopped after step " << n
                  << " as requested (Stop after step, subsection "
                     "<Checkpoint>).\n";
            break;
          }
      }

    print_run_summary();
  }



  // @sect4{Access for studies}
  //
  // The convergence study runs several ViscoplasticContact objects and compares
  // their states at every time level. It installs an observer that run() calls
  // after every accepted step and reads, per locally owned cell k and stress
  // point q, the stress, the displacement gradient and the weight JxW: the same
  // (k, q) indexing as the stress-point arrays, so it needs no FEValues either.
  // All of this is local to a rank; the study itself sends the cells where they
  // are needed.
  template <int dim>
  void
  ViscoplasticContact<dim>::set_step_observer(
    const std::function<void(const unsigned int, const double)> &observer)
  {
    step_observer = observer;
  }



  template <int dim>
  const DoFHandler<dim> &
  ViscoplasticContact<dim>::get_dof_handler() const
  {
    return dof_handler;
  }



  template <int dim>
  const Quadrature<dim> &
  ViscoplasticContact<dim>::get_stress_quadrature() const
  {
    return stress_quadrature;
  }



  template <int dim>
  const std::vector<typename DoFHandler<dim>::active_cell_iterator> &
  ViscoplasticContact<dim>::get_owned_cells() const
  {
    return owned_cells;
  }



  template <int dim>
  const SymmetricTensor<2, dim> &
  ViscoplasticContact<dim>::get_stress(const unsigned int k,
                                       const unsigned int q) const
  {
    // The record of (k, q) in the flat stress-point array.
    return quadrature_point_history[std::size_t(k) * stress_quadrature.size()
                                    + q]
      .stress;
  }



  template <int dim>
  Tensor<2, dim>
  ViscoplasticContact<dim>::get_displacement_gradient(
    const unsigned int k,
    const unsigned int q) const
  {
    // grad u_n at the stress point, from the ghosted solution (it is called
    // between time steps, when solution holds u_n with its ghosts).
    return displacement_gradient_at(solution, k, q);
  }



  template <int dim>
  double
  ViscoplasticContact<dim>::get_stress_point_weight(const unsigned int k,
                                                    const unsigned int q) const
  {
    return stress_point_JxW[std::size_t(k) * stress_quadrature.size() + q];
  }



  // Both dimensions are compiled into the library; main() and the convergence
  // study pick one at run time.
  template class ViscoplasticContact<2>;
  template class ViscoplasticContact<3>;
} // namespace ViscoContact
