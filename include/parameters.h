#ifndef viscoplastic_contact_parameters_h
#define viscoplastic_contact_parameters_h

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/types.h>

#include <string>
#include <vector>

namespace ViscoContact
{
  using namespace dealii;

  // @sect3{Run-time parameters}
  //
  // Every physical and numerical constant of a run comes from a parameter
  // file. As in step-44, each subsection of the file is one struct with a
  // static declare_parameters() and a parse_parameters() that reads the
  // values and checks what ParameterHandler's patterns cannot express
  // (strict positivity, consistency between entries). A violated check
  // throws an ExcMessage that names the subsection, the entry, the value
  // and the accepted range.
  //
  // Entries that select behaviour (cell types, laws, updates, solvers) are
  // turned into the enums below once, here; the rest of the program never
  // compares strings.
  namespace Parameters
  {
    enum class CellType
    {
      simplex,
      hypercube
    };

    // How the generated box is cut into simplices. In 2D each square
    // [x_i, x_i+1] x [y_j, y_j+1] is split by the diagonal "/" from
    // (x_i, y_j) to (x_i+1, y_j+1) (the published benchmark), by the other
    // one ("backslash"), by alternating diagonals that meet at every
    // second vertex ("union jack"), or by both diagonals around a vertex
    // at its centre ("crossed"). In 3D, "/" cuts every cube into the six
    // tetrahedra around its diagonal from (x_i, y_j, z_k) to
    // (x_i+1, y_j+1, z_k+1) (Kuhn's subdivision), "five tetrahedra" is
    // deal.II's generator. All but "five tetrahedra" give nested meshes
    // when the number of subdivisions is doubled.
    enum class SimplexPattern
    {
      slash,
      backslash,
      union_jack,
      crossed,
      five_tetrahedra
    };

    enum class ContactLawType
    {
      nonmonotone,
      piecewise_linear
    };

    enum class StressUpdate
    {
      explicit_euler, // the paper's scheme: the history from the past
      implicit_euler  // backward Euler with a Newton iteration per step
    };

    enum class FailurePolicy
    {
      stop,
      cut_time_step
    };

    // How the time steps are chosen: the schedule of Time step (cut only
    // when a solve fails), or a step-size controller on an estimate of the
    // local error of the history update (doc/adaptivity.md).
    enum class TimeStepControl
    {
      fixed,
      adaptive
    };

    // How the meshes of the initial cycles (nested iteration on the first
    // step, doc/adaptivity.md) are made: uniform refinement toward the mesh of
    // the parameter file, or the indicator of the adaptive meshes.
    enum class InitialRefinement
    {
      global,
      adaptive
    };

    // How a step's linear contact problem is solved (contact_solver.h).
    enum class Method
    {
      automatic,
      condensed,
      full_space
    };

    enum class Preconditioner
    {
      amg,
      direct
    };

    enum class DirectSolver
    {
      automatic,
      cholmod,
      umfpack,
      mumps
    };


    struct Geometry
    {
      unsigned int        dimension;
      std::vector<double> lengths;      // L1, L2 (, L3)
      unsigned int        subdivisions; // squares (cubes) along each edge
      CellType            cell_type;
      SimplexPattern      simplex_pattern;
      std::string         mesh_file;    // Gmsh .msh; empty: the generated box
      unsigned int global_refinements;  // uniform, after generation/reading
      unsigned int contact_refinements; // extra levels near Gamma_3

      static void
      declare_parameters(ParameterHandler &prm);
      void
      parse_parameters(ParameterHandler &prm);
    };

    struct BoundaryParts
    {
      std::vector<types::boundary_id> clamped_ids; // Gamma_1
      std::vector<types::boundary_id> contact_ids; // Gamma_3
      std::vector<types::boundary_id> loaded_ids;  // loaded part of Gamma_2

      static void
      declare_parameters(ParameterHandler &prm);
      void
      parse_parameters(ParameterHandler &prm);
    };

    struct Material
    {
      double young_modulus;
      double poisson_ratio;
      double viscosity;
      double yield_stress;
      bool   plasticity;

      static void
      declare_parameters(ParameterHandler &prm);
      void
      parse_parameters(ParameterHandler &prm, const unsigned int dim);
    };

    struct Loads
    {
      std::string body_force;       // FunctionParser expression, dim parts
      std::string surface_traction; // FunctionParser expression, dim parts

      static void
      declare_parameters(ParameterHandler &prm);
      void
      parse_parameters(ParameterHandler &prm);
    };

    struct Contact
    {
      bool                unilateral_constraint; // rigid foundation
      bool                normal_compliance;     // the deformable layer
      double              gap;                   // g, layer thickness
      ContactLawType      law_type;
      double              c1, c2, u1;  // the benchmark law
      std::vector<double> breakpoints; // a general piecewise-linear law
      std::vector<double> slopes;
      std::vector<double> jumps;
      bool                check_uniqueness;

      static void
      declare_parameters(ParameterHandler &prm);
      void
      parse_parameters(ParameterHandler &prm);
    };

    struct Time
    {
      double        end_time;
      double        time_step;
      StressUpdate  stress_update;
      FailurePolicy on_failure;
      double        minimum_time_step;
      // Adaptive time steps: Time step is the first step, the steps stay in
      // [Minimum time step, maximum_time_step] (maximum_time_step is End time
      // if the entry is 0), and the relative error estimate of each step at
      // most error_tolerance.
      TimeStepControl time_step_control;
      double          error_tolerance;
      double          maximum_time_step;
      // The bound on the number of steps of a run (and of each run of a
      // convergence study): a schedule beyond it is refused before anything
      // is written.
      unsigned int max_steps;

      static void
      declare_parameters(ParameterHandler &prm);
      void
      parse_parameters(ParameterHandler &prm);
    };

    struct ActiveSetSolver
    {
      unsigned int max_iterations;
      double       tolerance; // of every linear solve for fixed pieces
      // Start each step from the state extrapolated from the last two steps
      // (ViscoplasticContact::predict_step_start()).
      bool predicted_start;

      static void
      declare_parameters(ParameterHandler &prm);
      void
      parse_parameters(ParameterHandler &prm);
    };

    struct LinearSolver
    {
      Method         method;
      Preconditioner preconditioner; // full space back end
      DirectSolver   direct_solver;  // the factorisations of the operator

      static void
      declare_parameters(ParameterHandler &prm);
      void
      parse_parameters(ParameterHandler &prm);
    };

    // The canonical text of an entry's value (the numbers of a list parsed
    // and printed again): what a resumed run compares.
    std::string
    canonical_value(const std::string &value);

    // The most .vtu records a run writes (each a .pvtu file with its
    // pieces, listed in solution.pvd): beyond it the schedule is refused.
    constexpr unsigned int max_output_records = 10000;

    struct Output
    {
      std::string         directory;
      bool                write_vtu;
      unsigned int        interval;
      std::vector<double> profile_times;
      bool                print_timing_summary;
      bool                verbose;
      bool                overwrite; // remove an earlier run's files
      // The parameter file being run (set by main(), not an entry): a run
      // never removes or replaces it.
      std::string parameter_file;
      std::string parsed_parameters; // the complete parsed file
      // Every entry that changes the result, as "Subsection/Entry = value":
      // all but the Output and Checkpoint entries and End time (a resumed
      // run may go further). Stored with a checkpoint and compared on resume.
      std::vector<std::string> result_entries;

      static void
      declare_parameters(ParameterHandler &prm);
      void
      parse_parameters(ParameterHandler &prm);
    };

    struct Checkpoint
    {
      unsigned int checkpoint_interval; // 0: never
      bool         resume;
      unsigned int stop_after_step; // 0: never
      // Not an entry: false for the runs of a convergence study, which
      // cannot be resumed one by one (a signal then writes no checkpoint).
      bool resumable = true;

      static void
      declare_parameters(ParameterHandler &prm);
      void
      parse_parameters(ParameterHandler &prm);
    };

    // Adaptive meshes during the run (mesh_adaptation.cc): every Refinement
    // interval steps the mesh is refined and coarsened by the indicator of
    // doc/adaptivity.md, the state is carried over, and the step problem is
    // set up again. Hypercube meshes only (p4est).
    struct MeshAdaptation
    {
      bool         adaptive_refinement;
      unsigned int refinement_interval;
      double       refine_fraction;
      double       coarsen_fraction;
      unsigned int maximum_cells;
      unsigned int maximum_refinement_level;
      // Nested iteration on the first step: solved on initial_cycles coarser
      // meshes first, each solution the warm start of the next mesh.
      unsigned int      initial_cycles;
      InitialRefinement initial_refinement;

      static void
      declare_parameters(ParameterHandler &prm);
      void
      parse_parameters(ParameterHandler &prm);
    };

    struct ConvergenceStudy
    {
      bool                      study_enabled;
      std::vector<unsigned int> study_subdivisions;
      std::vector<double>       study_time_steps;
      unsigned int              reference_subdivisions;
      double                    reference_time_step;

      static void
      declare_parameters(ParameterHandler &prm);
      void
      parse_parameters(ParameterHandler &prm);
    };

    struct AllParameters : public Geometry,
                           public BoundaryParts,
                           public Material,
                           public Loads,
                           public Contact,
                           public Time,
                           public ActiveSetSolver,
                           public LinearSolver,
                           public MeshAdaptation,
                           public ConvergenceStudy,
                           public Output,
                           public Checkpoint
    {
      static void
      declare_parameters(ParameterHandler &prm);
      void
      parse_parameters(ParameterHandler &prm);
      // The checks between subsections, after every subsection is parsed.
      void
      check_study_entries() const;
      void
      check_mesh_adaptation_entries() const;
      void
      check_schedule_size(const ParameterHandler &prm) const;
      void
      check_unused_entries(const ParameterHandler &prm) const;

      // Checks between subsections that depend on how the program is run
      // (the number of MPI ranks).
      void
      check_run_configuration(const unsigned int n_mpi_ranks) const;
    };
  } // namespace Parameters
} // namespace ViscoContact

#endif
