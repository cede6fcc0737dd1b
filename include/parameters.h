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
  namespace Parameters
  {
    struct Geometry
    {
      unsigned int        dimension;
      std::vector<double> lengths;      // L1, L2 (, L3)
      unsigned int        subdivisions; // squares (cubes) along each edge
      std::string         cell_type;    // "simplex" or "hypercube"
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
      bool        unilateral_constraint; // rigid foundation below the layer
      bool        normal_compliance;     // the deformable layer
      double      gap;                   // g, thickness of the layer
      std::string law_type;              // "nonmonotone" or "piecewise linear"
      double      c1, c2, u1;            // the benchmark law
      std::vector<double> breakpoints;   // a general piecewise-linear law
      std::vector<double> slopes;
      std::vector<double> jumps;

      static void
      declare_parameters(ParameterHandler &prm);
      void
      parse_parameters(ParameterHandler &prm);
    };

    struct Time
    {
      double      end_time;
      double      time_step;
      std::string stress_update; // "explicit" or "implicit"
      std::string on_failure;    // "stop" or "cut time step"
      double      minimum_time_step;

      static void
      declare_parameters(ParameterHandler &prm);
      void
      parse_parameters(ParameterHandler &prm);
    };

    struct ActiveSetSolver
    {
      unsigned int max_iterations;
      double       tolerance;

      static void
      declare_parameters(ParameterHandler &prm);
      void
      parse_parameters(ParameterHandler &prm);
    };

    struct LinearSolver
    {
      std::string method;             // "condensed" (serial) or "distributed"
      std::string direct_solver;      // condensed: "cholmod" or "umfpack"
      std::string preconditioner;     // distributed: "amg" or "direct"
      double      relative_tolerance; // distributed: of the CG solves

      static void
      declare_parameters(ParameterHandler &prm);
      void
      parse_parameters(ParameterHandler &prm);
    };

    struct Output
    {
      std::string         directory;
      bool                write_vtu;
      unsigned int        interval;
      std::vector<double> profile_times;
      bool                print_timing_summary;
      bool                verbose;
      std::string         parsed_parameters; // the complete parsed file

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
      parse_parameters(ParameterHandler &prm, const std::string &cell_type);
    };

    struct AllParameters : public Geometry,
                           public BoundaryParts,
                           public Material,
                           public Loads,
                           public Contact,
                           public Time,
                           public ActiveSetSolver,
                           public LinearSolver,
                           public ConvergenceStudy,
                           public Output,
                           public Checkpoint
    {
      static void
      declare_parameters(ParameterHandler &prm);
      void
      parse_parameters(ParameterHandler &prm);

      // Checks between subsections that depend on how the program is run
      // (the number of MPI ranks).
      void
      check_run_configuration(const unsigned int n_mpi_ranks) const;
    };
  } // namespace Parameters
} // namespace ViscoContact

#endif
