#include <deal.II/base/exceptions.h>
#include <deal.II/base/utilities.h>

#include "parameters.h"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <iomanip>
#include <limits>
#include <sstream>

namespace ViscoContact
{
  namespace Parameters
  {
    namespace
    {
      // One place that formats the message of a rejected entry, so that every
      // error names the subsection, the entry, the value and what is accepted.
      void
      require(const bool         condition,
              const std::string &subsection,
              const std::string &entry,
              const std::string &value,
              const std::string &accepted)
      {
        AssertThrow(condition,
                    ExcMessage("Invalid parameter <" + entry
                               + "> in subsection <" + subsection + ">: value <"
                               + value + ">; accepted: " + accepted + "."));
      }

      std::string
      to_string(const double value)
      {
        std::ostringstream s;
        s << value;
        return s.str();
      }

      std::vector<types::boundary_id>
      get_boundary_ids(ParameterHandler &prm, const std::string &entry)
      {
        std::vector<types::boundary_id> ids;
        for (const int id : Utilities::string_to_int(
               Utilities::split_string_list(prm.get(entry))))
          ids.push_back(static_cast<types::boundary_id>(id));
        return ids;
      }
    } // namespace



    // Every number of a list (separated by ',' or ';') printed with the
    // fewest digits (15 to 17) that give it back, every other item trimmed, the
    // items joined by the separator and one space: "0.1" and "1e-1", "1,1" and
    // "1, 1" are the same value. An expression stays as it is written
    // (trimmed).
    std::string
    canonical_value(const std::string &value)
    {
      const char  separator = value.find(';') != std::string::npos ? ';' : ',';
      std::string result;
      for (const std::string &item :
           Utilities::split_string_list(value, separator))
        {
          const char *begin   = item.c_str();
          char       *end     = nullptr;
          errno               = 0;
          const double number = std::strtod(begin, &end);
          std::string  text   = item;
          if (!item.empty() && end == begin + item.size() && errno == 0)
            {
              // The shortest of 15 to 17 digits that gives the number back.
              for (int digits = 15; digits <= 17; ++digits)
                {
                  std::ostringstream printed;
                  printed << std::setprecision(digits) << number;
                  text = printed.str();
                  if (std::strtod(text.c_str(), nullptr) == number)
                    break;
                }
            }
          result
            += (result.empty() ? "" : std::string(1, separator) + " ") + text;
        }
      return result;
    }



    void
    Geometry::declare_parameters(ParameterHandler &prm)
    {
      prm.declare_entry("Dimension",
                        "2",
                        Patterns::Integer(2, 3),
                        "Space dimension: 2 (plane stress) or 3.");
      prm.enter_subsection("Geometry");
      {
        prm.declare_entry(
          "Lengths",
          "1, 1",
          Patterns::List(Patterns::Double(0), 2, 3),
          "Edge lengths L1, L2 (, L3) of the rectangular body "
          "(0,L1)x(0,L2)(x(0,L3)), one per dimension, each > 0.");
        prm.declare_entry("Subdivisions",
                          "32",
                          Patterns::Integer(1, 100000),
                          "Number of squares (cubes) along each edge; the mesh "
                          "size is h = L_i / Subdivisions. An integer in [1, "
                          "100000]; a mesh whose estimated memory exceeds "
                          "the memory of the machine is refused.");
        prm.declare_entry(
          "Cell type",
          "simplex",
          Patterns::Selection("simplex|hypercube"),
          "simplex: triangles/tetrahedra (see Simplex pattern), P1 "
          "displacement, piecewise-constant stress; hypercube: "
          "quadrilaterals/hexahedra, Q1 displacement, stresses at the 2^dim "
          "Gauss points.");
        prm.declare_entry(
          "Simplex pattern",
          "/",
          Patterns::Selection("/|backslash|union jack|crossed|five tetrahedra"),
          "How the generated box is cut into simplices. 2D: / splits each "
          "square [x_i,x_i+1]x[y_j,y_j+1] by the diagonal from (x_i,y_j) to "
          "(x_i+1,y_j+1) (the published benchmark); backslash by the other "
          "diagonal (written as a word: a parameter line ending in a "
          "backslash continues on the next line); union jack by alternating "
          "diagonals that meet at every second vertex; crossed by both "
          "diagonals around a new vertex at the centre (4 triangles). 3D: / "
          "cuts each cube into the 6 tetrahedra around its diagonal from "
          "(x_i,y_j,z_k) to (x_i+1,y_j+1,z_k+1); five tetrahedra is "
          "deal.II's generator (5 per cube, alternating). Every pattern but "
          "five tetrahedra gives nested meshes when Subdivisions doubles. "
          "Ignored for hypercube cells and Gmsh meshes.");
        prm.declare_entry(
          "Mesh file",
          "",
          Patterns::Anything(),
          "A Gmsh .msh file (format 2 or 4, ASCII) instead of the generated "
          "box; its physical groups on boundary faces are the boundary ids of "
          "subsection Boundary, and its cells must be of the Cell type. "
          "A relative path is relative to the directory of the parameter "
          "file. Faces without a physical group get boundary id 0. Empty: the "
          "box of Lengths and Subdivisions.");
        prm.declare_entry("Global refinements",
                          "0",
                          Patterns::Integer(0, 20),
                          "Uniform refinements of the generated or read mesh; "
                          "an integer in [0, 20].");
        prm.declare_entry(
          "Contact refinement levels",
          "0",
          Patterns::Integer(0, 20),
          "Extra refinements of the cells that touch Gamma_3, repeated this "
          "many times (a mesh graded toward the contact boundary; hanging "
          "nodes are constrained). An integer in [0, 20]; 0 for simplex "
          "cells.");
      }
      prm.leave_subsection();
    }

    void
    Geometry::parse_parameters(ParameterHandler &prm)
    {
      dimension = prm.get_integer("Dimension");
      prm.enter_subsection("Geometry");
      {
        lengths = Utilities::string_to_double(
          Utilities::split_string_list(prm.get("Lengths")));
        require(lengths.size() == dimension,
                "Geometry",
                "Lengths",
                prm.get("Lengths"),
                "exactly one length per space dimension ("
                  + std::to_string(dimension) + " values)");
        for (const double l : lengths)
          require(l > 0,
                  "Geometry",
                  "Lengths",
                  prm.get("Lengths"),
                  "strictly positive lengths");
        subdivisions = prm.get_integer("Subdivisions");
        cell_type    = (prm.get("Cell type") == "simplex" ? CellType::simplex
                                                          : CellType::hypercube);
        const std::string pattern = prm.get("Simplex pattern");
        simplex_pattern
          = (pattern == "/"            ? SimplexPattern::slash
             : pattern == "backslash"  ? SimplexPattern::backslash
             : pattern == "union jack" ? SimplexPattern::union_jack
             : pattern == "crossed"    ? SimplexPattern::crossed
                                       : SimplexPattern::five_tetrahedra);
        if (cell_type == CellType::simplex)
          require(dimension == 2
                    ? simplex_pattern != SimplexPattern::five_tetrahedra
                    : (simplex_pattern == SimplexPattern::slash
                       || simplex_pattern == SimplexPattern::five_tetrahedra),
                  "Geometry",
                  "Simplex pattern",
                  pattern,
                  dimension == 2 ? "/, backslash, union jack or crossed in 2D"
                                 : "/ or five tetrahedra in 3D");
        mesh_file           = prm.get("Mesh file");
        global_refinements  = prm.get_integer("Global refinements");
        contact_refinements = prm.get_integer("Contact refinement levels");
        require(contact_refinements == 0 || cell_type == CellType::hypercube,
                "Geometry",
                "Contact refinement levels",
                prm.get("Contact refinement levels"),
                "0 for Cell type = simplex (deal.II 9.4 has no hanging-node "
                "constraints on simplices); any number up to 20 for "
                "hypercube meshes");
      }
      prm.leave_subsection();
    }



    void
    BoundaryParts::declare_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Boundary");
      {
        prm.declare_entry(
          "Clamped boundary ids",
          "0",
          Patterns::List(Patterns::Integer(0, 255), 1),
          "Boundary ids of Gamma_1 (u = 0). The generated box numbers its "
          "faces as deal.II's colorize does: 0/1 at x = 0/L1, 2/3 at y = 0/L2, "
          "4/5 at z = 0/L3. At least one id; ids are integers in [0, 255] "
          "and must be on the mesh.");
        prm.declare_entry("Contact boundary ids",
                          "2",
                          Patterns::List(Patterns::Integer(0, 255)),
                          "Boundary ids of Gamma_3 (contact with the "
                          "foundation). Every other boundary part is Gamma_2. "
                          "Integers in [0, 255], none of them clamped.");
        prm.declare_entry("Loaded boundary ids",
                          "3",
                          Patterns::List(Patterns::Integer(0, 255)),
                          "Parts of Gamma_2 that carry the surface traction of "
                          "subsection Loads; the rest of Gamma_2 is "
                          "traction-free. Integers in [0, 255], none of them "
                          "clamped.");
      }
      prm.leave_subsection();
    }

    void
    BoundaryParts::parse_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Boundary");
      {
        clamped_ids = get_boundary_ids(prm, "Clamped boundary ids");
        contact_ids = get_boundary_ids(prm, "Contact boundary ids");
        loaded_ids  = get_boundary_ids(prm, "Loaded boundary ids");
        for (const auto id : contact_ids)
          for (const auto c : clamped_ids)
            require(id != c,
                    "Boundary",
                    "Contact boundary ids",
                    prm.get("Contact boundary ids"),
                    "ids different from the Clamped boundary ids");
        for (const auto id : loaded_ids)
          for (const auto c : clamped_ids)
            require(id != c,
                    "Boundary",
                    "Loaded boundary ids",
                    prm.get("Loaded boundary ids"),
                    "ids different from the Clamped boundary ids");
      }
      prm.leave_subsection();
    }



    void
    Material::declare_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Material");
      {
        prm.declare_entry("Young's modulus",
                          "1000",
                          Patterns::Double(),
                          "E > 0 [N/m^2].");
        prm.declare_entry("Poisson ratio",
                          "0.4",
                          Patterns::Double(),
                          "k: -1 < k < 1 in 2D (plane stress), -1 < k < 0.5 "
                          "in 3D.");
        prm.declare_entry("Viscosity",
                          "50",
                          Patterns::Double(),
                          "lambda > 0 [N s/m^2] of the Perzyna law "
                          "G = -(1/(2 lambda)) E (sigma - P_K sigma).");
        prm.declare_entry("Yield stress",
                          "2",
                          Patterns::Double(),
                          "sigma_Y > 0 [N/m^2] of the von Mises set K.");
        prm.declare_entry("Plasticity",
                          "true",
                          Patterns::Bool(),
                          "false: linear elasticity (G = 0); the history "
                          "terms are then skipped altogether.");
      }
      prm.leave_subsection();
    }

    void
    Material::parse_parameters(ParameterHandler &prm, const unsigned int dim)
    {
      prm.enter_subsection("Material");
      {
        young_modulus = prm.get_double("Young's modulus");
        poisson_ratio = prm.get_double("Poisson ratio");
        viscosity     = prm.get_double("Viscosity");
        yield_stress  = prm.get_double("Yield stress");
        plasticity    = prm.get_bool("Plasticity");
        require(young_modulus > 0,
                "Material",
                "Young's modulus",
                to_string(young_modulus),
                "E > 0");
        const double k_max = (dim == 2 ? 1.0 : 0.5);
        require(poisson_ratio > -1 && poisson_ratio < k_max,
                "Material",
                "Poisson ratio",
                to_string(poisson_ratio),
                std::string("-1 < k < ")
                  + (dim == 2 ? "1 (2D plane stress)" : "0.5 (3D)"));
        require(viscosity > 0,
                "Material",
                "Viscosity",
                to_string(viscosity),
                "lambda > 0");
        require(yield_stress > 0,
                "Material",
                "Yield stress",
                to_string(yield_stress),
                "sigma_Y > 0");
      }
      prm.leave_subsection();
    }



    void
    Loads::declare_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Loads");
      {
        prm.declare_entry(
          "Body force",
          "0; 0",
          Patterns::Anything(),
          "f_0(x,t) [N/m^2 in 2D]: one muparser expression per component, "
          "separated by ';', in the variables x, y (, z) and t and the "
          "constants pi, L1, L2 (, L3). A load without the variable t is "
          "assembled once for the whole run. Every value at the load points "
          "of the mesh and the times of the run must be finite.");
        prm.declare_entry(
          "Surface traction",
          "0; -5",
          Patterns::Anything(),
          "f_2(x,t) [N/m in 2D] on the Loaded boundary ids, same syntax as "
          "the body force; every value must be finite.");
      }
      prm.leave_subsection();
    }

    void
    Loads::parse_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Loads");
      {
        body_force       = prm.get("Body force");
        surface_traction = prm.get("Surface traction");
      }
      prm.leave_subsection();
    }



    void
    Contact::declare_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Contact");
      {
        prm.declare_entry("Unilateral constraint",
                          "true",
                          Patterns::Bool(),
                          "Rigid foundation under the layer: u_nu <= g.");
        prm.declare_entry("Normal compliance",
                          "true",
                          Patterns::Bool(),
                          "Deformable layer: -sigma_nu = p(u_nu).");
        prm.declare_entry("Layer thickness",
                          "0.01",
                          Patterns::Double(),
                          "g > 0 [m], the thickness of the deformable layer "
                          "(g >= 0 is accepted without normal compliance: "
                          "Signorini with gap g).");
        prm.declare_entry(
          "Law",
          "nonmonotone",
          Patterns::Selection("nonmonotone|piecewise linear"),
          "nonmonotone: the benchmark law p(r) = 0 (r < 0), c1 r (0 <= r <= "
          "u1), c1 u1 + c2 (r - u1) (r > u1); piecewise linear: any law given "
          "by Breakpoints, Slopes and Jumps.");
        prm.declare_entry("c1",
                          "300",
                          Patterns::Double(),
                          "Stiffness of the layer up to u1 [N/m^3], c1 >= 0.");
        prm.declare_entry("c2",
                          "-100",
                          Patterns::Double(),
                          "Slope beyond u1 [N/m^3]; negative = softening.");
        prm.declare_entry("u1",
                          "0.006",
                          Patterns::Double(),
                          "Penetration where the slope changes [m], u1 >= 0.");
        prm.declare_entry(
          "Breakpoints",
          "",
          Patterns::List(Patterns::Double()),
          "Piecewise-linear law: increasing breakpoints b_1 < ... < b_K.");
        prm.declare_entry("Slopes",
                          "",
                          Patterns::List(Patterns::Double()),
                          "Piecewise-linear law: K+1 slopes, on (-inf,b_1), "
                          "(b_1,b_2), ..., (b_K,inf); p(b_1-) = 0.");
        prm.declare_entry(
          "Jumps",
          "",
          Patterns::List(Patterns::Double()),
          "Piecewise-linear law: K jumps p(b_k+) - p(b_k-) >= 0 (empty: all "
          "zero). A jump makes the Clarke subdifferential an interval.");
        prm.declare_entry(
          "Check uniqueness",
          "true",
          Patterns::Bool(),
          "At set-up, compute the smallest generalised eigenvalue of "
          "(stiffness, lumped normal boundary mass) by a Lanczos iteration and "
          "compare it with the steepest softening of the law (doc/model.md, "
          "section 4): a dense product per iteration on the condensed back "
          "end, one elastic solve per iteration (about 10 to 20) on the full "
          "space back end.");
      }
      prm.leave_subsection();
    }

    void
    Contact::parse_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Contact");
      {
        unilateral_constraint = prm.get_bool("Unilateral constraint");
        normal_compliance     = prm.get_bool("Normal compliance");
        gap                   = prm.get_double("Layer thickness");
        law_type              = (prm.get("Law") == "nonmonotone"
                                   ? ContactLawType::nonmonotone
                                   : ContactLawType::piecewise_linear);
        check_uniqueness      = prm.get_bool("Check uniqueness");
        c1                    = prm.get_double("c1");
        c2                    = prm.get_double("c2");
        u1                    = prm.get_double("u1");
        breakpoints           = Utilities::string_to_double(
          Utilities::split_string_list(prm.get("Breakpoints")));
        slopes = Utilities::string_to_double(
          Utilities::split_string_list(prm.get("Slopes")));
        jumps = Utilities::string_to_double(
          Utilities::split_string_list(prm.get("Jumps")));

        if (normal_compliance)
          require(gap > 0,
                  "Contact",
                  "Layer thickness",
                  to_string(gap),
                  "g > 0");
        else
          require(gap >= 0,
                  "Contact",
                  "Layer thickness",
                  to_string(gap),
                  "g >= 0");

        if (normal_compliance && law_type == ContactLawType::nonmonotone)
          {
            require(c1 >= 0, "Contact", "c1", to_string(c1), "c1 >= 0");
            require(u1 >= 0, "Contact", "u1", to_string(u1), "u1 >= 0");
          }
        if (normal_compliance && law_type == ContactLawType::piecewise_linear)
          {
            require(breakpoints.size() >= 1,
                    "Contact",
                    "Breakpoints",
                    prm.get("Breakpoints"),
                    "at least one breakpoint for Law = piecewise linear");
            for (unsigned int k = 1; k < breakpoints.size(); ++k)
              require(breakpoints[k] > breakpoints[k - 1],
                      "Contact",
                      "Breakpoints",
                      prm.get("Breakpoints"),
                      "strictly increasing values");
            require(slopes.size() == breakpoints.size() + 1,
                    "Contact",
                    "Slopes",
                    prm.get("Slopes"),
                    "one more slope than breakpoints ("
                      + std::to_string(breakpoints.size() + 1) + " values)");
            require(jumps.empty() || jumps.size() == breakpoints.size(),
                    "Contact",
                    "Jumps",
                    prm.get("Jumps"),
                    "empty or one jump per breakpoint ("
                      + std::to_string(breakpoints.size()) + " values)");
            for (const double jump : jumps)
              require(jump >= 0,
                      "Contact",
                      "Jumps",
                      prm.get("Jumps"),
                      "non-negative jumps (an upward jump is a vertical piece "
                      "of the graph; a downward one has no such piece)");
          }
      }
      prm.leave_subsection();
    }



    void
    Time::declare_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Time");
      {
        prm.declare_entry("End time", "1", Patterns::Double(), "T > 0 [s].");
        prm.declare_entry("Time step",
                          "0.015625",
                          Patterns::Double(),
                          "k with 0 < k <= T [s]; if T/k is not an integer the "
                          "last step is shortened to end at T.");
        prm.declare_entry(
          "Stress update",
          "explicit",
          Patterns::Selection("explicit|implicit"),
          "explicit: the paper's scheme, H_n from the previous stresses "
          "(doc/model.md, section 2; stable for k < 4 lambda/lambda_max(E)); "
          "implicit: backward Euler, sigma_n from a local equation at each "
          "stress point and a Newton iteration with the consistent tangent "
          "per step (doc/model.md, section 3; unconditionally stable; the "
          "back end sets up the tangent in every Newton iteration).");
        prm.declare_entry(
          "On solver failure",
          "stop",
          Patterns::Selection("stop|cut time step"),
          "When a step's solve fails (the active-set or Newton iteration "
          "reaches its limit, CG fails, or the displacement is not finite): "
          "stop (write the last accepted state as failed_step_NNNN.pvtu, "
          "report, exit status 1), or cut time step (retry the step with half "
          "the time step, down to Minimum time step; the remainder of the "
          "step follows as the next step).");
        prm.declare_entry("Minimum time step",
                          "1e-6",
                          Patterns::Double(),
                          "The smallest time step a cut may reach [s], and "
                          "with Time step control = adaptive the smallest "
                          "step the controller takes; in (0, Time step].");
        prm.declare_entry(
          "Time step control",
          "fixed",
          Patterns::Selection("fixed|adaptive"),
          "fixed: the steps of Time step (cut only when a solve fails); "
          "adaptive: Time step is the first step, and each step's length "
          "follows from an estimate of the local error of the history update "
          "(the difference between the Euler and the trapezoidal history "
          "increment, doc/adaptivity.md); a step whose estimate exceeds Error "
          "tolerance is repeated with a shorter one. The steps land on End "
          "time and on the Profile times.");
        prm.declare_entry(
          "Error tolerance",
          "1e-3",
          Patterns::Double(),
          "With Time step control = adaptive: the bound on each step's "
          "estimated local error of the history, relative to the stress "
          "(both in the energy norm of E^-1 over the body); in (0, 1].");
        prm.declare_entry(
          "Maximum time step",
          "0",
          Patterns::Double(),
          "With Time step control = adaptive: the largest step [s]; 0: End "
          "time. The explicit history update never takes more than 0.9 times "
          "its stability limit 4 lambda / lambda_max(E). 0, or in [Minimum "
          "time step, End time].");
        prm.declare_entry(
          "Maximum number of steps",
          "1000000",
          Patterns::Integer(1, 10000000),
          "The most time steps a run may take: a schedule of more steps "
          "(End time / Time step; for each run of a convergence study too) "
          "is refused before anything is written, and adaptive steps stop "
          "with an error there. An integer in [1, 1e7].");
      }
      prm.leave_subsection();
    }

    void
    Time::parse_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Time");
      {
        end_time      = prm.get_double("End time");
        time_step     = prm.get_double("Time step");
        stress_update = (prm.get("Stress update") == "explicit"
                           ? StressUpdate::explicit_euler
                           : StressUpdate::implicit_euler);
        require(end_time > 0, "Time", "End time", to_string(end_time), "T > 0");
        require(time_step > 0 && time_step <= end_time,
                "Time",
                "Time step",
                to_string(time_step),
                "0 < k <= T = " + to_string(end_time));
        on_failure        = (prm.get("On solver failure") == "stop"
                               ? FailurePolicy::stop
                               : FailurePolicy::cut_time_step);
        minimum_time_step = prm.get_double("Minimum time step");
        require(minimum_time_step > 0 && minimum_time_step <= time_step,
                "Time",
                "Minimum time step",
                to_string(minimum_time_step),
                "0 < Minimum time step <= Time step = " + to_string(time_step));
        time_step_control = (prm.get("Time step control") == "fixed"
                               ? TimeStepControl::fixed
                               : TimeStepControl::adaptive);
        error_tolerance   = prm.get_double("Error tolerance");
        require(error_tolerance > 0 && error_tolerance <= 1,
                "Time",
                "Error tolerance",
                to_string(error_tolerance),
                "0 < Error tolerance <= 1 (relative)");
        maximum_time_step = prm.get_double("Maximum time step");
        require(maximum_time_step == 0
                  || (maximum_time_step >= minimum_time_step
                      && maximum_time_step <= end_time),
                "Time",
                "Maximum time step",
                to_string(maximum_time_step),
                "0 (End time) or Minimum time step = "
                  + to_string(minimum_time_step)
                  + " <= Maximum time step <= End time = "
                  + to_string(end_time));
        if (maximum_time_step == 0)
          maximum_time_step = end_time;
        max_steps = prm.get_integer("Maximum number of steps");
      }
      prm.leave_subsection();
    }



    void
    Checkpoint::declare_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Checkpoint");
      {
        prm.declare_entry(
          "Checkpoint interval",
          "0",
          Patterns::Integer(0),
          "Write a checkpoint (everything a resumed run needs) into "
          "<Output directory>/checkpoint every n-th step; 0: never (an "
          "integer >= 0). Only the last complete checkpoint is kept. A "
          "signal (SIGTERM, SIGINT, SIGUSR1) always writes one.");
        prm.declare_entry(
          "Resume",
          "false",
          Patterns::Bool(),
          "Continue from the last complete checkpoint in the Output "
          "directory (same scene; any number of MPI ranks) instead of "
          "starting at t = 0. The time series and the .pvd record continue.");
        prm.declare_entry(
          "Stop after step",
          "0",
          Patterns::Integer(0),
          "End the run after this step as if it had been "
          "killed (for tests of Resume); 0: never. An integer in [0, "
          "number of time steps].");
      }
      prm.leave_subsection();
    }

    void
    Checkpoint::parse_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Checkpoint");
      checkpoint_interval = prm.get_integer("Checkpoint interval");
      resume              = prm.get_bool("Resume");
      stop_after_step     = prm.get_integer("Stop after step");
      prm.leave_subsection();
    }



    void
    ActiveSetSolver::declare_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Active set solver");
      {
        prm.declare_entry("Maximum iterations",
                          "50",
                          Patterns::Integer(1, 10000),
                          "Limit of the primal-dual active set (semismooth "
                          "Newton) iterations per time step; reaching it stops "
                          "the run with a report. An integer in [1, 10000].");
        prm.declare_entry(
          "Tolerance",
          "1e-10",
          Patterns::Double(0),
          "Relative accuracy of every linear solve for fixed pieces: the "
          "residual of CG/GMRES relative to the right-hand side (full space "
          "back end), the defect of the condensed equations relative to the "
          "normal displacements (condensed back end). The iteration stops "
          "when no contact node changes its piece and the last solve met "
          "this tolerance; in (0, 1e-2].");
        prm.declare_entry(
          "Predicted start",
          "true",
          Patterns::Bool(),
          "Start each time step from the state extrapolated from the last two "
          "steps: the displacement u_{n-1} + (k_n/k_{n-1}) (u_{n-1} - u_{n-2}) "
          "as the first guess of the Krylov solves (full space back end) and "
          "of Newton's iteration (implicit update), and every contact node on "
          "the piece of its extrapolated (r, z). The result is the same as "
          "from u_{n-1} and the previous pieces; only the iterations are "
          "fewer. Where the uniqueness check found that the step problem may "
          "have several solutions, the nodes keep the previous step's pieces "
          "(the branch the run is on). false: every step starts from u_{n-1} "
          "and the previous step's pieces.");
      }
      prm.leave_subsection();
    }

    void
    ActiveSetSolver::parse_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Active set solver");
      {
        max_iterations  = prm.get_integer("Maximum iterations");
        tolerance       = prm.get_double("Tolerance");
        predicted_start = prm.get_bool("Predicted start");
        require(tolerance > 0 && tolerance <= 1e-2,
                "Active set solver",
                "Tolerance",
                to_string(tolerance),
                "a number in (0, 1e-2]");
      }
      prm.leave_subsection();
    }



    void
    LinearSolver::declare_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Linear solver");
      {
        prm.declare_entry(
          "Method",
          "auto",
          Patterns::Selection("auto|condensed|full space"),
          "How a time step's linear contact problem is solved (doc/model.md, "
          "section 2). condensed: the operator is factorised (Direct solver) "
          "and the active set works on the contact nodes alone through the "
          "contact compliance S = N K^-1 N^T (m^2 doubles on every rank), "
          "read off the factor on one rank (CHOLMOD, contact dofs "
          "eliminated last) or computed with one solve per contact node "
          "(UMFPACK, MUMPS); fastest for 2D and for small contact surfaces. "
          "full space: the active set in "
          "the full space, CG (GMRES for the implicit update's tangent) "
          "preconditioned by the Preconditioner of the operator; scales to "
          "large 3D meshes and many ranks. auto: condensed on one rank when "
          "the contact surface and the mesh are small enough (printed at "
          "start-up with the reason), full space otherwise.");
        prm.declare_entry(
          "Preconditioner",
          "amg",
          Patterns::Selection("amg|direct"),
          "Full space back end: amg (Trilinos ML smoothed aggregation with "
          "the rigid-body modes as near-null space; for large runs) or direct "
          "(the factorisation of the Direct solver; for small runs).");
        prm.declare_entry(
          "Direct solver",
          "auto",
          Patterns::Selection("auto|cholmod|umfpack|mumps"),
          "Sparse direct factorisation of the operator (condensed back end, "
          "and the full space back end's direct preconditioner): cholmod "
          "(supernodal Cholesky of the symmetric elastic operator; one MPI "
          "rank; the implicit update's unsymmetric tangent then uses "
          "umfpack), umfpack (LU; one MPI rank), mumps (LU or LDL^T, "
          "distributed over all ranks). auto: cholmod on one rank, mumps on "
          "several.");
      }
      prm.leave_subsection();
    }

    void
    LinearSolver::parse_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Linear solver");
      {
        const std::string method_name = prm.get("Method");
        method = (method_name == "auto"        ? Method::automatic
                  : method_name == "condensed" ? Method::condensed
                                               : Method::full_space);
        preconditioner
          = (prm.get("Preconditioner") == "amg" ? Preconditioner::amg
                                                : Preconditioner::direct);
        const std::string solver_name = prm.get("Direct solver");
        direct_solver = (solver_name == "auto"      ? DirectSolver::automatic
                         : solver_name == "cholmod" ? DirectSolver::cholmod
                         : solver_name == "umfpack" ? DirectSolver::umfpack
                                                    : DirectSolver::mumps);
      }
      prm.leave_subsection();
    }



    void
    Output::declare_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Output");
      {
        prm.declare_entry(
          "Output directory",
          "output/default",
          Patterns::DirectoryName(),
          "Where the run writes parameters.prm, solution.pvd with its .vtu "
          "files, time_series.csv, the contact profiles and checkpoint/. "
          "Created if missing; must not be empty. The run lists every file it "
          "writes in the folder's manifest (.viscoplastic_contact.manifest) "
          "and holds a lock on the folder while it runs: a second run into a "
          "folder in use is refused, and so is a folder with files under the "
          "program's names that no manifest lists (they are never replaced). "
          "A '#' cannot be part of the value (it starts a comment).");
        prm.declare_entry(
          "Overwrite",
          "false",
          Patterns::Bool(),
          "A new run never mixes its files with those of an earlier run: "
          "false refuses an Output directory that holds another run's files; "
          "true removes exactly the files and folders the earlier run's "
          "manifest lists, once the new run's set-up has succeeded (nothing "
          "else, never the parameter file being run). A resumed run continues "
          "its own files.");
        prm.declare_entry("Write vtu",
                          "true",
                          Patterns::Bool(),
                          "Write a .vtu file per output step and the .pvd "
                          "record.");
        prm.declare_entry("Output interval",
                          "1",
                          Patterns::Integer(1),
                          "Write a .vtu file every n-th time step (and always "
                          "the last one; with adaptive time steps every n-th "
                          "accepted step); an integer >= 1.");
        prm.declare_entry(
          "Profile times",
          "0.015625, 0.5, 1",
          Patterns::List(Patterns::Double(0)),
          "Times at which the contact profile along Gamma_3 is written to "
          "contact_profile_NNNN.csv (the step closest to each time; adaptive "
          "time steps land on these times). Each in [0, End time].");
        prm.declare_entry("Print timing summary",
                          "true",
                          Patterns::Bool(),
                          "Print the TimerOutput table and the cost ratios at "
                          "the end of the run.");
        prm.declare_entry("Verbose",
                          "true",
                          Patterns::Bool(),
                          "Print one line per time step.");
      }
      prm.leave_subsection();
    }

    void
    Output::parse_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Output");
      {
        // An empty directory would put every result into the working
        // directory, next to whatever is there; "." says so explicitly.
        directory = prm.get("Output directory");
        require(!directory.empty(),
                "Output",
                "Output directory",
                "",
                "a directory name (\".\" for the working directory)");
        write_vtu     = prm.get_bool("Write vtu");
        interval      = prm.get_integer("Output interval");
        profile_times = Utilities::string_to_double(
          Utilities::split_string_list(prm.get("Profile times")));
        print_timing_summary = prm.get_bool("Print timing summary");
        verbose              = prm.get_bool("Verbose");
        overwrite            = prm.get_bool("Overwrite");
      }
      prm.leave_subsection();
      std::ostringstream parsed;
      prm.print_parameters(parsed, ParameterHandler::PRM);
      parsed_parameters = parsed.str();

      // The entries that change the result, from the short listing (one
      // "set" line per entry, inside "subsection" ... "end"), each value in
      // its canonical form, so that a resumed run compares what the values
      // mean, not how they were written.
      std::ostringstream short_listing;
      prm.print_parameters(short_listing, ParameterHandler::ShortPRM);
      std::istringstream       lines(short_listing.str());
      std::vector<std::string> path;
      std::string              line;
      result_entries.clear();
      while (std::getline(lines, line))
        {
          const std::string text = Utilities::trim(line);
          if (text.rfind("subsection ", 0) == 0)
            path.push_back(Utilities::trim(text.substr(11)));
          else if (text == "end" && !path.empty())
            path.pop_back();
          else if (text.rfind("set ", 0) == 0)
            {
              const std::size_t equals = text.find('=');
              const std::string name
                = Utilities::trim(text.substr(4, equals - 4));
              const std::string value
                = equals == std::string::npos
                    ? ""
                    : Utilities::trim(text.substr(equals + 1));
              std::string full_name;
              for (const std::string &section : path)
                full_name += section + "/";
              full_name += name;
              if (full_name.rfind("Output/", 0) == 0
                  || full_name.rfind("Checkpoint/", 0) == 0
                  || full_name == "Time/End time")
                continue;
              result_entries.push_back(full_name + " = "
                                       + canonical_value(value));
            }
        }
    }



    void
    MeshAdaptation::declare_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Mesh adaptation");
      {
        prm.declare_entry(
          "Adaptive refinement",
          "false",
          Patterns::Bool(),
          "Refine and coarsen the mesh during the run (doc/adaptivity.md, "
          "\"Adaptive meshes\"): every Refinement interval steps, by the "
          "Kelly estimator of the displacement plus the cells at the contact "
          "front and at the boundary of the plastic zone; the displacement, "
          "the stress-point history and the contact state are carried over. "
          "Hypercube meshes (Cell type = hypercube) only.");
        prm.declare_entry("Refinement interval",
                          "1",
                          Patterns::Integer(),
                          "Adapt the mesh after every n-th step (an integer "
                          ">= 1).");
        prm.declare_entry("Refine fraction",
                          "0.3",
                          Patterns::Double(),
                          "The fraction of the cells with the largest "
                          "indicators that is refined, in [0, 1].");
        prm.declare_entry("Coarsen fraction",
                          "0.03",
                          Patterns::Double(),
                          "The fraction of the cells with the smallest "
                          "indicators that is coarsened, in [0, 1]; Refine "
                          "fraction + Coarsen fraction <= 1.");
        prm.declare_entry("Maximum cells",
                          "20000",
                          Patterns::Integer(),
                          "A bound on the number of active cells: fewer "
                          "cells are refined when it would be exceeded (an "
                          "integer >= 1).");
        prm.declare_entry("Maximum refinement level",
                          "8",
                          Patterns::Integer(),
                          "No cell is refined beyond this level of the "
                          "p4est forest (the generated box of m 2^j "
                          "Subdivisions has m^dim trees); an integer in "
                          "[0, 20].");
        prm.declare_entry(
          "Initial cycles",
          "0",
          Patterns::Integer(),
          "Nested iteration on the first time step (doc/adaptivity.md, "
          "\"Initial cycles\"): step 1 is solved on L coarser meshes first, "
          "each solution (displacement and contact pressure) carried over to "
          "the next mesh as the starting point of its active-set iteration; "
          "only the solve on the last mesh is recorded. 0: none. Hypercube "
          "meshes only; an integer in [0, 20], with Initial refinement = "
          "global at most Global refinements.");
        prm.declare_entry(
          "Initial refinement",
          "global",
          Patterns::Selection("global|adaptive"),
          "How the meshes of the Initial cycles are made. global: the mesh "
          "of subsection Geometry is the last one; the first cycle runs on "
          "it with Global refinements - Initial cycles uniform refinements, "
          "and each cycle refines every cell (no Contact refinement levels). "
          "adaptive: the mesh of subsection Geometry is the first one, and "
          "each cycle refines and coarsens it by the indicator of Adaptive "
          "refinement, within Refine fraction, Coarsen fraction, Maximum "
          "cells and Maximum refinement level.");
      }
      prm.leave_subsection();
    }

    void
    MeshAdaptation::parse_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Mesh adaptation");
      {
        adaptive_refinement = prm.get_bool("Adaptive refinement");
        const long interval = prm.get_integer("Refinement interval");
        require(interval >= 1 && interval <= 1000000000,
                "Mesh adaptation",
                "Refinement interval",
                prm.get("Refinement interval"),
                "an integer >= 1");
        refinement_interval = interval;
        refine_fraction     = prm.get_double("Refine fraction");
        require(refine_fraction >= 0 && refine_fraction <= 1,
                "Mesh adaptation",
                "Refine fraction",
                prm.get("Refine fraction"),
                "a number in [0, 1]");
        coarsen_fraction = prm.get_double("Coarsen fraction");
        require(coarsen_fraction >= 0
                  && coarsen_fraction <= 1 - refine_fraction,
                "Mesh adaptation",
                "Coarsen fraction",
                prm.get("Coarsen fraction"),
                "a number in [0, 1 - Refine fraction]");
        const long cells = prm.get_integer("Maximum cells");
        require(cells >= 1 && cells <= 2000000000,
                "Mesh adaptation",
                "Maximum cells",
                prm.get("Maximum cells"),
                "an integer in [1, 2e9]");
        maximum_cells    = cells;
        const long level = prm.get_integer("Maximum refinement level");
        require(level >= 0 && level <= 20,
                "Mesh adaptation",
                "Maximum refinement level",
                prm.get("Maximum refinement level"),
                "an integer in [0, 20]");
        maximum_refinement_level = level;
        const long cycles        = prm.get_integer("Initial cycles");
        require(cycles >= 0 && cycles <= 20,
                "Mesh adaptation",
                "Initial cycles",
                prm.get("Initial cycles"),
                "an integer in [0, 20]");
        initial_cycles     = cycles;
        initial_refinement = prm.get("Initial refinement") == "global"
                               ? InitialRefinement::global
                               : InitialRefinement::adaptive;
      }
      prm.leave_subsection();
    }



    void
    ConvergenceStudy::declare_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Convergence study");
      {
        prm.declare_entry(
          "Enabled",
          "false",
          Patterns::Bool(),
          "Instead of one run: run the scene for each (Subdivisions, Time "
          "steps) pair and for the reference resolution, and tabulate "
          "max_n (||u_n - u_n^ref||_V + ||sigma_n - sigma_n^ref||_Q) with "
          "observed orders in convergence.csv. The meshes must be nested "
          "generated boxes (every Subdivisions entry divides Reference "
          "subdivisions; not with Simplex pattern = five tetrahedra).");
        prm.declare_entry("Subdivisions",
                          "2, 4, 8, 16, 32",
                          Patterns::List(Patterns::Integer(1)),
                          "Mesh of each run: squares along each edge; "
                          "integers >= 1.");
        prm.declare_entry("Time steps",
                          "0.5, 0.25, 0.125, 0.0625, 0.03125",
                          Patterns::List(Patterns::Double(0)),
                          "Time step of each run (one per Subdivisions entry); "
                          "each must be a positive multiple of the reference "
                          "time step.");
        prm.declare_entry("Reference subdivisions",
                          "64",
                          Patterns::Integer(1),
                          "Mesh of the reference run; a multiple of every "
                          "Subdivisions entry, so that the meshes are nested.");
        prm.declare_entry("Reference time step",
                          "0.015625",
                          Patterns::Double(0),
                          "Time step of the reference run; > 0.");
      }
      prm.leave_subsection();
    }

    void
    ConvergenceStudy::parse_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Convergence study");
      {
        study_enabled = prm.get_bool("Enabled");
        for (const int n : Utilities::string_to_int(
               Utilities::split_string_list(prm.get("Subdivisions"))))
          study_subdivisions.push_back(n);
        study_time_steps = Utilities::string_to_double(
          Utilities::split_string_list(prm.get("Time steps")));
        reference_subdivisions = prm.get_integer("Reference subdivisions");
        reference_time_step    = prm.get_double("Reference time step");
        if (study_enabled)
          {
            require(study_time_steps.size() == study_subdivisions.size(),
                    "Convergence study",
                    "Time steps",
                    prm.get("Time steps"),
                    "one time step per Subdivisions entry ("
                      + std::to_string(study_subdivisions.size()) + " values)");
            require(reference_time_step > 0,
                    "Convergence study",
                    "Reference time step",
                    prm.get("Reference time step"),
                    "a positive number");
            for (const unsigned int n : study_subdivisions)
              require(reference_subdivisions % n == 0,
                      "Convergence study",
                      "Subdivisions",
                      prm.get("Subdivisions"),
                      "divisors of Reference subdivisions = "
                        + std::to_string(reference_subdivisions)
                        + " (nested meshes)");
            for (const double k : study_time_steps)
              {
                const double ratio = k / reference_time_step;
                require(k > 0 && std::abs(ratio - std::round(ratio)) < 1e-9
                          && std::round(ratio) >= 1,
                        "Convergence study",
                        "Time steps",
                        prm.get("Time steps"),
                        "positive multiples of Reference time step = "
                          + prm.get("Reference time step"));
              }
          }
      }
      prm.leave_subsection();
    }



    void
    AllParameters::declare_parameters(ParameterHandler &prm)
    {
      Geometry::declare_parameters(prm);
      BoundaryParts::declare_parameters(prm);
      Material::declare_parameters(prm);
      Loads::declare_parameters(prm);
      Contact::declare_parameters(prm);
      Time::declare_parameters(prm);
      ActiveSetSolver::declare_parameters(prm);
      LinearSolver::declare_parameters(prm);
      MeshAdaptation::declare_parameters(prm);
      ConvergenceStudy::declare_parameters(prm);
      Output::declare_parameters(prm);
      Checkpoint::declare_parameters(prm);
    }

    void
    AllParameters::parse_parameters(ParameterHandler &prm)
    {
      Geometry::parse_parameters(prm);
      BoundaryParts::parse_parameters(prm);
      Material::parse_parameters(prm, dimension);
      Loads::parse_parameters(prm);
      Contact::parse_parameters(prm);
      Time::parse_parameters(prm);
      ActiveSetSolver::parse_parameters(prm);
      LinearSolver::parse_parameters(prm);
      MeshAdaptation::parse_parameters(prm);
      ConvergenceStudy::parse_parameters(prm);
      Output::parse_parameters(prm);
      Checkpoint::parse_parameters(prm);
      check_study_entries();
      check_mesh_adaptation_entries();
      check_schedule_size(prm);
      check_unused_entries(prm);
    }

    // What a convergence study needs of the other subsections.
    void
    AllParameters::check_study_entries() const
    {
      if (study_enabled)
        require(checkpoint_interval == 0 && !resume && stop_after_step == 0,
                "Checkpoint",
                "Checkpoint interval",
                std::to_string(checkpoint_interval),
                "0, and Resume = false, Stop after step = 0, when a "
                "convergence study runs");

      // A convergence study compares its runs at the levels of their fixed
      // steps (multiples of the reference step).
      if (study_enabled)
        require(time_step_control == TimeStepControl::fixed,
                "Time",
                "Time step control",
                "adaptive",
                "fixed when a convergence study runs (its runs are compared "
                "at the levels of their fixed time steps)");
      if (study_enabled)
        require(mesh_file.empty() && global_refinements == 0
                  && contact_refinements == 0,
                "Geometry",
                "Mesh file",
                mesh_file,
                "an empty Mesh file and no Global refinements or Contact "
                "refinement levels when a convergence study runs (it builds "
                "its own nested boxes)");
      if (study_enabled && cell_type == CellType::simplex)
        require(simplex_pattern != SimplexPattern::five_tetrahedra,
                "Geometry",
                "Simplex pattern",
                "five tetrahedra",
                "a pattern that gives nested meshes (/) when a convergence "
                "study runs");
    }

    void
    AllParameters::check_mesh_adaptation_entries() const
    {
      // Adaptivity refines p4est meshes; deal.II 9.4's fully distributed
      // triangulation of simplices cannot be refined during the run, and a
      // convergence study builds its own nested meshes.
      if (adaptive_refinement)
        require(cell_type == CellType::hypercube && !study_enabled,
                "Mesh adaptation",
                "Adaptive refinement",
                "true",
                "false when Cell type = simplex or a convergence study runs "
                "(adaptive meshes need hypercube cells on p4est: deal.II "
                "9.4's fully distributed triangulation of triangles and "
                "tetrahedra cannot refine)");
      // The initial cycles refine p4est meshes too; with global refinement
      // the mesh of the parameter file is the finest, reached from one with
      // Initial cycles fewer uniform refinements, and the contact refinements
      // would not be nested that way.
      if (initial_cycles > 0)
        require(cell_type == CellType::hypercube && !study_enabled,
                "Mesh adaptation",
                "Initial cycles",
                std::to_string(initial_cycles),
                "0 when Cell type = simplex or a convergence study runs "
                "(the initial cycles refine hypercube meshes on p4est)");
      if (initial_cycles > 0 && initial_refinement == InitialRefinement::global)
        {
          require(initial_cycles <= global_refinements,
                  "Mesh adaptation",
                  "Initial cycles",
                  std::to_string(initial_cycles),
                  "at most Global refinements = "
                    + std::to_string(global_refinements)
                    + " (subsection <Geometry>) with Initial refinement = "
                      "global: the first cycle's mesh has Global refinements "
                      "- Initial cycles uniform refinements");
          require(contact_refinements == 0,
                  "Mesh adaptation",
                  "Initial cycles",
                  std::to_string(initial_cycles),
                  "0 when Contact refinement levels > 0 (subsection "
                  "<Geometry>) with Initial refinement = global (uniform "
                  "refinement of a graded mesh does not give the graded mesh "
                  "of the parameter file); or Initial refinement = adaptive");
        }
    }

    // Profile times within the run, and schedules of a size the run can
    // take and write.
    void
    AllParameters::check_schedule_size(const ParameterHandler &prm) const
    {
      // A profile time outside [0, T] has no step near it (the closest step
      // would be the first or the last one, a profile nobody asked for).
      for (const double t : profile_times)
        require(t >= 0 && t <= end_time,
                "Output",
                "Profile times",
                prm.get({"Output"}, "Profile times"),
                "times in [0, End time = " + to_string(end_time) + "]");
      // Schedules beyond Maximum number of steps (or beyond the range of the
      // step counter, where t_n = n k no longer gives distinct times) and
      // more than max_output_records .vtu records are refused. The number of
      // steps is that of n_fixed_steps() (time_schedule.cc), computed in
      // floating point before it is converted; adaptive steps are not known
      // before the run, and neither is their number (the time loop bounds
      // them).
      const auto steps_of = [&](const double time_step) {
        return std::ceil(end_time / time_step * (1 - 1e-12));
      };
      const auto require_steps = [&](const double       steps,
                                     const std::string &subsection,
                                     const std::string &entry,
                                     const double       value) {
        std::ostringstream message;
        message << "a schedule of at most Maximum number of steps = "
                << max_steps
                << " (subsection <Time>) steps; with End time = " << end_time
                << " it has " << steps
                << " steps (a larger time step, an earlier End time, or a "
                   "larger Maximum number of steps if the run is meant to be "
                   "that long)";
        require(steps <= max_steps,
                subsection,
                entry,
                to_string(value),
                message.str());
      };
      if (time_step_control == TimeStepControl::fixed && !study_enabled)
        require_steps(steps_of(time_step), "Time", "Time step", time_step);
      if (study_enabled)
        {
          require_steps(steps_of(reference_time_step),
                        "Convergence study",
                        "Reference time step",
                        reference_time_step);
          for (const double k : study_time_steps)
            require_steps(steps_of(k), "Convergence study", "Time steps", k);
        }
      const unsigned int n_steps
        = time_step_control == TimeStepControl::adaptive || study_enabled
            ? std::numeric_limits<unsigned int>::max()
            : static_cast<unsigned int>(steps_of(time_step));
      if (write_vtu && time_step_control == TimeStepControl::fixed
          && !study_enabled)
        {
          const double records = 2 + std::floor(n_steps / double(interval));
          std::ostringstream message;
          message << "at most " << max_output_records
                  << " .vtu records in a run; Time step = " << time_step
                  << " and End time = " << end_time << " make " << n_steps
                  << " steps, and Output interval = " << interval << " writes "
                  << records
                  << " records (a larger Output interval, or Write vtu = "
                     "false)";
          require(records <= max_output_records,
                  "Output",
                  "Output interval",
                  std::to_string(interval),
                  message.str());
        }
      require(stop_after_step <= n_steps,
              "Checkpoint",
              "Stop after step",
              std::to_string(stop_after_step),
              "0 (never) or a step of the run, at most "
                + std::to_string(n_steps));
      require(checkpoint_interval <= n_steps,
              "Checkpoint",
              "Checkpoint interval",
              std::to_string(checkpoint_interval),
              "0 (never) or at most the number of steps, "
                + std::to_string(n_steps));
    }

    // Entries whose value the run would otherwise ignore without a word.
    void
    AllParameters::check_unused_entries(const ParameterHandler &prm) const
    {
      // The points of a piecewise-linear law mean nothing to the benchmark
      // law (their defaults are empty, so a value is a mistake, not a
      // leftover default).
      if (law_type == ContactLawType::nonmonotone)
        for (const std::string entry : {"Breakpoints", "Slopes", "Jumps"})
          require(prm.get({"Contact"}, entry).empty(),
                  "Contact",
                  entry,
                  prm.get({"Contact"}, entry),
                  "empty when Law = nonmonotone (it is used by Law = "
                  "piecewise linear only)");
    }

    void
    AllParameters::check_run_configuration(const unsigned int n_ranks) const
    {
      require(n_ranks == 1
                || (direct_solver != DirectSolver::cholmod
                    && direct_solver != DirectSolver::umfpack),
              "Linear solver",
              "Direct solver",
              direct_solver == DirectSolver::cholmod ? "cholmod" : "umfpack",
              "auto or mumps when the program runs on more than one MPI rank ("
                + std::to_string(n_ranks)
                + " here); cholmod and umfpack factorise on one rank");
    }
  } // namespace Parameters
} // namespace ViscoContact
