#ifndef viscoplastic_contact_parameters_h
#define viscoplastic_contact_parameters_h

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/types.h>

#include <optional>
#include <string>
#include <vector>

namespace ViscoContact
{
  using namespace dealii;

  // @sect3{Run-time parameters}
  //
  // Every physical and numerical constant of a run comes from a parameter
  // file. Each subsection of the file is one struct whose members hold the
  // values, initialised with the defaults; add_parameters() binds each entry
  // to its member in one line (ParameterHandler::add_parameter(), with the
  // range in the pattern where a pattern can state it), so that
  // ParameterHandler::parse_input() fills the members, and
  // check_parameters() (where there is anything to check) checks what the
  // patterns cannot express (strict
  // positivity, consistency between entries). A violated check throws an
  // ExcMessage that names the subsection, the entry, the value and the
  // accepted range. A list of parts (several materials or boundary
  // conditions, say) is one such struct per numbered subsection.
  //
  // Entries that select behaviour (cell types, laws, updates, solvers) are
  // turned into the enums below once, here; the rest of the program never
  // compares strings.
  namespace Parameters
  {
    enum class CellType
    {
      simplex,
      hypercube,
      mixed
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

    enum class TangentialLawType
    {
      frictionless,
      tresca,
      coulomb
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
      full_space,
      matrix_free
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


    // What a 2D body is: a thin plate (sigma_zz = 0, the paper's model) or
    // a cross-section of a long body (eps_zz = 0).
    enum class PlaneModel
    {
      plane_stress,
      plane_strain
    };

    struct Geometry
    {
      unsigned int        dimension    = 2;
      PlaneModel          plane_model  = PlaneModel::plane_stress;
      std::vector<double> lengths      = {1, 1}; // L1, L2 (, L3)
      unsigned int        subdivisions = 32; // squares (cubes) along each edge
      CellType            cell_type    = CellType::simplex;
      SimplexPattern      simplex_pattern = SimplexPattern::slash;
      std::string         mesh_file; // Gmsh .msh; empty: the generated box
      // The generated box's points moved by a map and its inverse (empty:
      // the box as generated); refinement follows the map (mesh.cc).
      std::string box_map;
      std::string box_map_inverse;
      // The material id of each cell of the coarse mesh as a function of
      // its centre (empty: the mesh's own ids).
      std::string  material_id_function;
      unsigned int global_refinements  = 0; // uniform, after generation/reading
      unsigned int contact_refinements = 0; // extra levels near Gamma_3
      // Simplex meshes are built by one rank per group of this many
      // consecutive ranks (0: the ranks of one compute node).
      unsigned int mesh_group_size = 0;
      // Not an entry: a simplex box of Subdivisions = m 2^j is built as the
      // box of m 2^(j - b) refined b = min(j, box_refinement_limit) times
      // (mesh.cc). The coarser meshes of the step cycles lower it, so that
      // they refine the same coarse box and are nested in the mesh of the
      // run.
      unsigned int box_refinement_limit = 4;

      void
      add_parameters(ParameterHandler &prm);
      void
      check_parameters(ParameterHandler &prm);
    };

    // A displacement prescribed on some boundary parts, for some of its
    // components, as a function of (x, y[, z], t): one numbered subsection
    // "Prescribed displacement N" of subsection Boundary each.
    struct PrescribedDisplacement
    {
      std::vector<types::boundary_id> boundary_ids;       // empty: not used
      std::vector<std::string>        components = {"y"}; // x, y, z
      std::string displacement = "0"; // one expression per component

      void
      add_parameters(ParameterHandler &prm, const unsigned int number);
      void
      check_parameters(ParameterHandler  &prm,
                       const unsigned int number,
                       const unsigned int dim);
      // The component numbers (x = 0, y = 1, z = 2), in the order given.
      std::vector<unsigned int>
      component_indices() const;
    };

    struct BoundaryParts
    {
      std::vector<types::boundary_id> clamped_ids = {0}; // Gamma_1
      std::vector<types::boundary_id> contact_ids = {2}; // Gamma_3
      std::vector<types::boundary_id> loaded_ids
        = {3}; // loaded part of Gamma_2
      // Planar parts with zero normal displacement (rollers, planes of
      // symmetry).
      std::vector<types::boundary_id> symmetry_ids;
      // Sized before add_parameters() to the highest N of the subsections
      // "Prescribed displacement N" of the parameter file (at least one, so
      // that --print-parameters documents the list).
      std::vector<PrescribedDisplacement> prescribed_displacements
        = std::vector<PrescribedDisplacement>(1);

      void
      add_parameters(ParameterHandler &prm);
      void
      check_parameters(ParameterHandler &prm, const unsigned int dim);
      // The entries that are used (with boundary ids), in their order.
      std::vector<std::pair<unsigned int, const PrescribedDisplacement *>>
      used_prescribed_displacements() const;
    };

    // ParameterHandler::parse_input() of a parameter file, with a value that
    // does not match its entry's pattern reported as any rejected entry is:
    // the subsection, the entry, the value and what is accepted.
    void
    parse_parameter_file(ParameterHandler &prm, const std::string &file);

    // The highest N of the subsections "<name> N" in a parameter file (and
    // in the files it includes), at least 1: how many such subsections to
    // declare before the file is parsed.
    unsigned int
    count_numbered_subsections(const std::string &parameter_file,
                               const std::string &name);

    // A list of ids (boundary or material ids, any container) as the
    // parameter file writes it, "1, 2, 3": how the messages quote them.
    template <typename Ids>
    std::string
    id_list(const Ids &ids)
    {
      std::string text;
      for (const auto id : ids)
        text += (text.empty() ? "" : ", ") + std::to_string(id);
      return text;
    }

    // The material of the cells with the given material ids: subsection
    // "Material" (whose empty list means every cell of a mesh with one
    // material id) and the numbered "Material N", N >= 2 (empty: not used).
    // How a material leaves the elastic range (material_law.h): Perzyna's
    // viscoplastic law (the paper's), or rate-independent von Mises
    // plasticity with linear isotropic hardening.
    enum class MaterialLawType
    {
      perzyna,
      hardening_plasticity
    };

    struct Material
    {
      std::vector<types::material_id> material_ids;
      MaterialLawType                 law           = MaterialLawType::perzyna;
      double                          young_modulus = 1000;
      double                          poisson_ratio = 0.4;
      double                          viscosity     = 50;
      double                          yield_stress  = 2;
      double                          hardening_modulus = 0;
      bool                            plasticity        = true;

      void
      add_parameters(ParameterHandler &prm, const std::string &subsection);
      void
      check_parameters(ParameterHandler  &prm,
                       const unsigned int dim,
                       const std::string &subsection) const;
    };

    enum class SurfaceLoadType
    {
      traction, // a vector
      pressure  // along the inward normal
    };

    // A load on some boundary parts, a traction vector or a normal pressure
    // as a function of (x, y[, z], t): one numbered subsection
    // "Surface load N" of subsection Loads each.
    struct SurfaceLoad
    {
      std::vector<types::boundary_id> boundary_ids; // empty: not used
      SurfaceLoadType                 type  = SurfaceLoadType::pressure;
      std::string                     value = "0";

      void
      add_parameters(ParameterHandler &prm, const unsigned int number);
      void
      check_parameters(const unsigned int number, const unsigned int dim) const;
    };

    struct Loads
    {
      std::string body_force = "0; 0"; // FunctionParser expression, dim parts
      std::string surface_traction = "0; -5"; // the same
      // Sized before add_parameters() to the highest N of the subsections
      // "Surface load N" (at least one, to document the list).
      std::vector<SurfaceLoad> surface_loads = std::vector<SurfaceLoad>(1);

      void
      add_parameters(ParameterHandler &prm);
      // The entries that are used (with boundary ids), with their numbers.
      std::vector<std::pair<unsigned int, const SurfaceLoad *>>
      used_surface_loads() const;
    };

    // A contact zone: the law of its layer and foundation, and its
    // obstacle. Subsection "Contact" is zone 1 (its boundary parts are
    // Contact boundary ids of subsection Boundary); the numbered
    // "Contact zone N", N >= 2, name their own boundary ids (empty: not
    // used).
    struct Contact
    {
      std::vector<types::boundary_id> boundary_ids; // zones N >= 2 only
      // A contact pair: the boundary part of the other body that the zone
      // meets (empty: a rigid obstacle).
      std::vector<types::boundary_id> opposite_ids;
      std::string                     search_distance = "auto";
      std::string                     geometric_gap   = "measured";
      bool                unilateral_constraint = true; // rigid foundation
      bool                normal_compliance     = true; // the deformable layer
      double              gap                   = 0.01; // g, layer thickness
      ContactLawType      law_type              = ContactLawType::nonmonotone;
      double              c1 = 300, c2 = -100, u1 = 0.006; // the benchmark law
      std::vector<double> breakpoints; // a general piecewise-linear law
      std::vector<double> slopes;
      std::vector<double> jumps;
      bool                check_uniqueness = true;
      // The obstacle: the gap s(x, t) along the direction d (doc/model.md).
      std::string initial_gap   = "0";
      std::string gap_direction = "normal";
      // The obstacle's rigid translation o(t) since t = 0 (dim expressions
      // in t; "0": it does not move).
      std::string obstacle_motion = "0";
      // Its rigid rotation since t = 0 about the point that is at
      // Rotation center at t = 0 and moves with the translation: the angle
      // (counterclockwise, 2D) or the rotation vector (3D) as expressions
      // in t ("0": it does not turn).
      std::string obstacle_rotation = "0";
      std::string rotation_center   = "0";
      // Friction (doc/model.md, section 7): the law, Tresca's bound g(x),
      // Coulomb's coefficient mu.
      TangentialLawType tangential_law       = TangentialLawType::frictionless;
      std::string       slip_bound           = "0";
      double            friction_coefficient = 0;
      // Slip weakening: the bound times f(x), piecewise linear through
      // (x_k, f_k), x the accumulated slip or the slip rate (empty: f = 1).
      std::vector<double> weakening_slips;
      std::vector<double> weakening_rates; // or of the slip rate
      std::vector<double> weakening_factors;
      // The memory term of the normal law (doc/model.md, section 9): the
      // kernel b(t) = sum_k a_k exp(-lambda_k t), weights a_k and rates
      // lambda_k (empty: no memory).
      std::vector<double> memory_weights;
      std::vector<double> memory_rates;
      // Adhesion (doc/model.md, section 10): the tension gamma beta^2 R(r)
      // for r < 0, R(r) = max(-L, r), and the bonding beta's evolution
      // beta' = -kappa (beta gamma R(r)^2 - epsilon)+ from beta_0(x)
      // (gamma = 0: no adhesion).
      double      adhesion_stiffness = 0; // gamma
      double      adhesion_length    = 0; // L
      double      adhesion_energy    = 0; // epsilon
      double      debonding_rate     = 1; // kappa
      std::string initial_bonding    = "1";
      // A cohesive interface (doc/model.md, section 12): the tension
      // rises with K to T_c, softens linearly to 0 with the work G_c, and
      // unloads on the secant (strength 0: none).
      double cohesive_strength  = 0; // T_c
      double cohesive_stiffness = 0; // K
      double fracture_energy    = 0; // G_c
      // implicit: the step's opening beyond the reached one follows the
      // envelope; explicit: a plateau at the reached tension (the damage
      // from the last step).
      std::string cohesive_damage = "implicit";
      // linear: the tension falls linearly from T_c to 0; exponential: as
      // T_c exp(-(delta - delta_0) / lambda), in pieces.
      std::string cohesive_softening = "linear";
      // Archard's wear (doc/model.md, section 11): w' = k_w p |slip'|
      // (0: no wear).
      double wear_coefficient = 0;

      void
      add_parameters(ParameterHandler  &prm,
                     const std::string &subsection = "Contact");
      void
      check_parameters(ParameterHandler  &prm,
                       const unsigned int dim,
                       const std::string &subsection = "Contact") const;
      // Gap direction as a unit vector (empty if it is "normal", not a list
      // of finite numbers, or all zero). Scaled by its largest entry before
      // it is normalised, so that neither 1e300 nor 1e-300 overflows.
      std::vector<double>
      direction_vector() const;
    };

    // A contact zone that is used: its subsection, its boundary ids and its
    // law and obstacle.
    struct ContactZone
    {
      unsigned int                    number; // 1: subsection Contact
      std::string                     subsection;
      std::vector<types::boundary_id> boundary_ids;
      const Contact                  *contact;
    };

    struct Time
    {
      double        end_time          = 1;
      double        time_step         = 0.015625;
      StressUpdate  stress_update     = StressUpdate::explicit_euler;
      FailurePolicy on_failure        = FailurePolicy::stop;
      double        minimum_time_step = 1e-6;
      // Adaptive time steps: Time step is the first step, the steps stay in
      // [Minimum time step, maximum_time_step] (maximum_time_step is End time
      // if the entry is 0), and the relative error estimate of each step at
      // most error_tolerance.
      TimeStepControl time_step_control = TimeStepControl::fixed;
      double          error_tolerance   = 1e-3;
      double          maximum_time_step = 0;
      // The bound on the number of steps of a run (and of each run of a
      // convergence study): a schedule beyond it is refused before anything
      // is written.
      unsigned int max_steps = 1000000;

      void
      add_parameters(ParameterHandler &prm);
      void
      check_parameters(ParameterHandler &prm);
    };

    struct ActiveSetSolver
    {
      unsigned int max_iterations = 50;
      double       tolerance = 1e-10; // of every linear solve for fixed pieces
      // Start each step from the state extrapolated from the last two steps
      // (acceleration/predicted_start.h).
      bool predicted_start = true;

      void
      add_parameters(ParameterHandler &prm);
    };

    struct LinearSolver
    {
      Method         method         = Method::automatic;
      Preconditioner preconditioner = Preconditioner::amg;     // full space
      DirectSolver   direct_solver  = DirectSolver::automatic; // factorisations

      void
      add_parameters(ParameterHandler &prm);
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
      std::string         directory               = "output/default";
      bool                write_vtu               = true;
      unsigned int        interval                = 1;
      std::vector<double> profile_times           = {0.015625, 0.5, 1};
      bool                print_timing_summary    = true;
      bool                measure_cost_ratios     = false;
      bool                verbose                 = true;
      bool                print_iteration_history = false;
      bool                overwrite = false; // remove an earlier run's files
      // The parameter file being run (set by main(), not an entry): a run
      // never removes or replaces it.
      std::string parameter_file;
      std::string parsed_parameters; // the complete parsed file
      // Every entry that changes the result, as "Subsection/Entry = value":
      // all but the Output and Checkpoint entries and End time (a resumed
      // run may go further). Stored with a checkpoint and compared on resume.
      std::vector<std::string> result_entries;

      void
      add_parameters(ParameterHandler &prm);
      void
      check_parameters(ParameterHandler &prm);
    };

    struct Checkpoint
    {
      unsigned int checkpoint_interval = 0; // 0: never
      bool         resume              = false;
      unsigned int stop_after_step     = 0; // 0: never
      // Not an entry: false for the runs of a convergence study, which
      // cannot be resumed one by one (a signal then writes no checkpoint).
      bool resumable = true;

      void
      add_parameters(ParameterHandler &prm);
    };

    // Adaptive meshes during the run (mesh/mesh_adaptation.cc): every
    // Refinement interval steps the mesh is refined and coarsened by the
    // indicator of doc/adaptivity.md, the state is carried over, and the step
    // problem is set up again. Hypercube meshes only (p4est).
    struct MeshAdaptation
    {
      bool         adaptive_refinement      = false;
      unsigned int refinement_interval      = 1;
      double       refine_fraction          = 0.3;
      double       coarsen_fraction         = 0.03;
      unsigned int maximum_cells            = 20000;
      unsigned int maximum_refinement_level = 8;
      // Nested iteration on the first step: solved on L coarser meshes
      // first, each solution the warm start of the next mesh. The entry is
      // "auto" (the program chooses L) or L; initial_cycles() reads it.
      std::string       initial_cycles_entry = "auto";
      InitialRefinement initial_refinement   = InitialRefinement::global;
      // Nested iteration in every later step: each step problem is solved on
      // L coarser meshes first (its history load restricted to them), whose
      // contact zone starts the solve on the run's mesh. "auto" or L, read
      // by step_cycles().
      std::string step_cycles_entry = "auto";

      // L as set in the parameter file; nothing for auto.
      std::optional<unsigned int>
      initial_cycles() const;
      std::optional<unsigned int>
      step_cycles() const;

      void
      add_parameters(ParameterHandler &prm);
      void
      check_parameters(ParameterHandler &prm);
    };

    struct ConvergenceStudy
    {
      bool                      study_enabled      = false;
      std::vector<unsigned int> study_subdivisions = {2, 4, 8, 16, 32};
      std::vector<double>       study_time_steps
        = {0.5, 0.25, 0.125, 0.0625, 0.03125};
      unsigned int reference_subdivisions = 64;
      double       reference_time_step    = 0.015625;

      void
      add_parameters(ParameterHandler &prm);
      void
      check_parameters(ParameterHandler &prm);
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
      // The materials "Material 2", "Material 3", ...: sized before
      // add_parameters() to the numbered subsections of the parameter file
      // (at least one, so that --print-parameters documents the list).
      std::vector<Material> further_materials = std::vector<Material>(1);
      // The materials that are used, with the names of their subsections:
      // subsection Material first, then those of further_materials with
      // material ids.
      std::vector<std::pair<std::string, const Material *>>
      used_materials() const;
      // Whether any material that is used is viscoplastic, and whether the
      // steps run the implicit (backward Euler) update: only with plasticity
      // (without it, both updates are the elastic problem).
      bool
      any_plasticity() const;
      bool
      implicit_update() const;
      // Whether the explicit update adds a history load: only with
      // plasticity.
      bool
      explicit_history_update() const;
      // The contact zones "Contact zone 2", "Contact zone 3", ...: sized like
      // further_materials.
      std::vector<Contact> further_contact_zones = std::vector<Contact>(1);
      // The zones that name boundary parts: subsection Contact with Contact
      // boundary ids first, then the numbered ones with ids, in order.
      std::vector<ContactZone>
      used_contact_zones() const;
      // Every boundary id of every contact zone.
      std::vector<types::boundary_id>
      all_contact_ids() const;
      // How many times the mesh of the parameter file can be coarsened
      // uniformly: its Global refinements, and for a generated box also the
      // factors of 2 of Subdivisions. (On p4est the box of m 2^j cells per
      // edge is the box of m refined j times, with the same cells, mesh.cc,
      // unless a Material id function decides on its cells; a simplex mesh
      // of the initial cycles is built anew for each cycle.)
      unsigned int
      uniform_coarsenings() const;
      // The parameters of the mesh coarsened levels times: fewer Global
      // refinements first, then Subdivisions halved.
      AllParameters
      coarsened(const unsigned int levels) const;
      // How many times the mesh of the parameter file is the uniform
      // refinement of a coarser mesh of the same coarse cells (the coarser
      // meshes of the step cycles): uniform_coarsenings() on hypercubes; on
      // simplices the Global refinements, and for a box of triangles cut
      // by "/" or backslash the refinements of its coarse box.
      unsigned int
      nested_coarsenings() const;
      // The parameters of the mesh the step cycles coarsen to: coarsened
      // once, a simplex box from the same coarse box.
      AllParameters
      nested_coarsened() const;

      // Every entry of the file, bound to the members of this object (which
      // must outlive the parsing); then the checks of every subsection and
      // those between subsections.
      void
      add_parameters(ParameterHandler &prm);
      void
      check_parameters(ParameterHandler &prm);
      // The checks between subsections, after every subsection is checked.
      void
      check_material_entries() const;
      void
      check_boundary_id_claims() const;
      void
      check_study_entries() const;
      void
      check_mesh_adaptation_entries() const;
      void
      check_step_cycles() const;
      // Method = matrix free: hypercube cells, the explicit update.
      void
      check_method_entries() const;
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
