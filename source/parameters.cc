#include <deal.II/base/exceptions.h>
#include <deal.II/base/utilities.h>

#include "parameters.h"
#include "time_schedule.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iomanip>
#include <limits>
#include <map>
#include <tuple>
#include <regex>
#include <sstream>

namespace ViscoContact
{
  namespace Parameters
  {
    namespace
    {
      // One place that formats the message of a rejected entry, so that every
      // error names the subsection (none for an entry at the top level), the
      // entry, the value and what is accepted.
      void
      require(const bool         condition,
              const std::string &subsection,
              const std::string &entry,
              const std::string &value,
              const std::string &accepted)
      {
        AssertThrow(condition,
                    ExcMessage("Invalid parameter <" + entry
                               + (subsection.empty()
                                    ? ">"
                                    : "> in subsection <" + subsection + ">")
                               + ": value <" + value
                               + ">; accepted: " + accepted + "."));
      }

      std::string
      to_string(const double value)
      {
        std::ostringstream s;
        s << value;
        return s.str();
      }

      // The entries of a numbered list ("Prescribed displacement N", "Surface
      // load N") that name boundary ids, with their numbers N.
      template <typename Entry>
      std::vector<std::pair<unsigned int, const Entry *>>
      used_entries(const std::vector<Entry> &list)
      {
        std::vector<std::pair<unsigned int, const Entry *>> used;
        for (unsigned int n = 0; n < list.size(); ++n)
          if (!list[n].boundary_ids.empty())
            used.emplace_back(n + 1, &list[n]);
        return used;
      }

      // An entry whose text is one of the keys of choices, bound to an enum
      // member: the default is the key of the member's value.
      template <typename Enum>
      void
      add_selection(ParameterHandler                                &prm,
                    const std::string                               &entry,
                    Enum                                            &member,
                    const std::vector<std::pair<std::string, Enum>> &choices,
                    const std::string &documentation)
      {
        std::string keys, default_key;
        for (const auto &[key, value] : choices)
          {
            keys += (keys.empty() ? "" : "|") + key;
            if (value == member)
              default_key = key;
          }
        prm.declare_entry(entry,
                          default_key,
                          Patterns::Selection(keys),
                          documentation);
        prm.add_action(entry, [&member, choices](const std::string &text) {
          for (const auto &[key, value] : choices)
            if (key == text)
              member = value;
        });
      }

      // "auto", or an integer in [0, 20] (Initial cycles): the parser's
      // message for any other text names the file, the line and this
      // description.
      class AutoOrCount : public Patterns::PatternBase
      {
      public:
        bool
        match(const std::string &text) const override
        {
          return text == "auto" || count.match(text);
        }
        std::string
        description(const OutputStyle style = Machine) const override
        {
          return "auto or " + count.description(style);
        }
        std::unique_ptr<PatternBase>
        clone() const override
        {
          return std::make_unique<AutoOrCount>();
        }

      private:
        const Patterns::Integer count{0, 20};
      };

      // auto or a finite number > 0.
      class AutoOrPositive : public Patterns::PatternBase
      {
      public:
        bool
        match(const std::string &text) const override
        {
          if (text == "auto")
            return true;
          if (!Patterns::Double().match(text))
            return false;
          const double value = Patterns::Tools::Convert<double>::to_value(text);
          return std::isfinite(value) && value > 0;
        }
        std::string
        description(const OutputStyle = Machine) const override
        {
          return "auto or a number > 0";
        }
        std::unique_ptr<PatternBase>
        clone() const override
        {
          return std::make_unique<AutoOrPositive>();
        }
      };

      // A finite number in an interval whose ends may be open or infinite:
      // the range of an entry that is its own (a rule across entries stays
      // in check_parameters()). Written here because deal.II's
      // Patterns::Double has closed ends only, and "E > 0" is not [0, inf).
      // Its description is the range in words, which the message of a
      // rejected value quotes (parse_parameter_file()).
      class Interval : public Patterns::PatternBase
      {
      public:
        static constexpr double infinity
          = std::numeric_limits<double>::infinity();

        Interval(const double lower,
                 const bool   lower_open,
                 const double upper      = infinity,
                 const bool   upper_open = true)
          : lower(lower)
          , upper(upper)
          , lower_open(lower_open)
          , upper_open(upper_open)
        {}

        // A number as deal.II reads it (the syntax of Patterns::Double,
        // and the value Convert<double> gives the member), in the range.
        bool
        match(const std::string &text) const override
        {
          if (!Patterns::Double().match(text))
            return false;
          const double value = Patterns::Tools::Convert<double>::to_value(text);
          return std::isfinite(value)
                 && (lower_open ? value > lower : value >= lower)
                 && (upper_open ? value < upper : value <= upper);
        }
        std::string
        description(const OutputStyle = Machine) const override
        {
          const auto number = [](const double x) {
            std::ostringstream text;
            text << x;
            return text.str();
          };
          if (upper == infinity)
            return "[a number " + std::string(lower_open ? "> " : ">= ")
                   + number(lower) + "]";
          return "[a number in " + std::string(lower_open ? "(" : "[")
                 + number(lower) + ", " + number(upper)
                 + (upper_open ? ")" : "]") + "]";
        }
        std::unique_ptr<PatternBase>
        clone() const override
        {
          return std::make_unique<Interval>(lower,
                                            lower_open,
                                            upper,
                                            upper_open);
        }

      private:
        const double lower, upper;
        const bool   lower_open, upper_open;
      };

      const Interval positive(0, /*lower_open=*/true);
      const Interval non_negative(0, /*lower_open=*/false);
      const Interval fraction(0, false, 1, false);

      // A pattern's description as the message of a rejected value says
      // what is accepted: deal.II's "[Double 0...MAX_DOUBLE (inclusive)]"
      // becomes "a number >= 0", "[Selection a|b ]" "one of a|b", "[Bool]"
      // "true or false"; an Interval's is in words already; any other is
      // quoted.
      std::string
      accepted_by(const std::string &description)
      {
        std::smatch       match;
        const std::string trimmed = Utilities::trim(description);
        if (trimmed.rfind("auto or ", 0) == 0)
          return "auto or " + accepted_by(trimmed.substr(8));
        const std::regex range(
          "^\\[(Double|Integer range) (\\S+)\\.\\.\\.(\\S+) "
          "\\(inclusive\\)\\]$");
        if (std::regex_match(trimmed, match, range))
          {
            const std::string kind
              = match[1] == "Double" ? "a number" : "a whole number";
            const bool no_lower
              = match[2].str().find("MAX") != std::string::npos
                || match[2].str().find("2147483648") != std::string::npos;
            const bool no_upper
              = match[3].str().find("MAX") != std::string::npos
                || match[3].str().find("2147483647") != std::string::npos;
            if (no_lower && no_upper)
              return kind;
            if (no_upper)
              return kind + " >= " + match[2].str();
            if (no_lower)
              return kind + " <= " + match[3].str();
            return kind + " in [" + match[2].str() + ", " + match[3].str()
                   + "]";
          }
        if (std::regex_match(trimmed,
                             match,
                             std::regex("^\\[Selection (.*) \\]$")))
          return "one of " + match[1].str();
        if (trimmed == "[Bool]")
          return "true or false";
        if (trimmed == "[Double]")
          return "a number";
        if (trimmed == "[Integer]")
          return "a whole number";
        if (std::regex_match(trimmed,
                             match,
                             std::regex("^\\[(a number.*)\\]$")))
          return match[1].str();
        return trimmed;
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
    Geometry::add_parameters(ParameterHandler &prm)
    {
      prm.add_parameter("Dimension",
                        dimension,
                        "Space dimension: 2 (see Plane model) or 3.",
                        Patterns::Integer(2, 3));
      add_selection(prm,
                    "Plane model",
                    plane_model,
                    {{"plane stress", PlaneModel::plane_stress},
                     {"plane strain", PlaneModel::plane_strain}},
                    "In 2D: plane stress (sigma_zz = 0, a thin plate; the "
                    "paper's model) or plane strain (eps_zz = 0, a "
                    "cross-section of a long body; the out-of-plane stress "
                    "is written as stress_zz). Plane stress in 3D.");
      prm.enter_subsection("Geometry");
      {
        prm.add_parameter(
          "Lengths",
          lengths,
          "Edge lengths L1, L2 (, L3) of the rectangular body "
          "(0,L1)x(0,L2)(x(0,L3)), one per dimension, each > 0; the "
          "expressions of the file may use them as the constants L1, L2, L3. "
          "With a Mesh file the mesh gives the geometry: Lengths then only "
          "sets those constants (2 or 3 values, whatever the Dimension).",
          Patterns::List(positive, 2, 3));
        prm.add_parameter("Subdivisions",
                          subdivisions,
                          "Number of squares (cubes) along each edge; the mesh "
                          "size is h = L_i / Subdivisions. An integer in [1, "
                          "100000]; a mesh whose estimated memory exceeds "
                          "the memory of the machine is refused.",
                          Patterns::Integer(1, 100000));
        add_selection(
          prm,
          "Cell type",
          cell_type,
          {{"simplex", CellType::simplex},
           {"hypercube", CellType::hypercube},
           {"mixed", CellType::mixed}},
          "simplex: triangles/tetrahedra (see Simplex pattern), P1 "
          "displacement, piecewise-constant stress; hypercube: "
          "quadrilaterals/hexahedra, Q1 displacement, stresses at the 2^dim "
          "Gauss points; mixed: a Mesh file with both (say one body of "
          "each, joined by a contact pair), each cell with its element "
          "(every cell carries 2^dim stress points, a simplex as many copies "
          "of its one). Mixed meshes run on the condensed and full space "
          "back ends, with Global refinements, without adaptive meshes, "
          "initial or step cycles.");
        add_selection(
          prm,
          "Simplex pattern",
          simplex_pattern,
          {{"/", SimplexPattern::slash},
           {"backslash", SimplexPattern::backslash},
           {"union jack", SimplexPattern::union_jack},
           {"crossed", SimplexPattern::crossed},
           {"five tetrahedra", SimplexPattern::five_tetrahedra}},
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
        prm.add_parameter(
          "Mesh file",
          mesh_file,
          "A Gmsh .msh file (format 2 or 4, ASCII) instead of the generated "
          "box; its physical groups on boundary faces are the boundary ids of "
          "subsection Boundary, and its cells must be of the Cell type. "
          "A relative path is relative to the directory of the parameter "
          "file. Faces without a physical group get boundary id 0. Empty: the "
          "box of Lengths and Subdivisions.",
          Patterns::Anything());
        prm.add_parameter(
          "Box map",
          box_map,
          "The generated box moved point by point: muparser expressions "
          "x'; y'(; z') of the box point (x, y[, z]) and the constants L1, "
          "L2(, L3), pi, e.g. a mesh graded toward the corner (0, L2, 0): "
          "\"x^2/L1; L2 - (L2-y)^2/L2; z^2/L3\". Refinement places every "
          "new vertex where the map takes the point between its parents in "
          "the box (a deal.II FunctionManifold), so Subdivisions = 2n and n "
          "refined once give the same mesh, and the coarser meshes of "
          "multigrid and of the initial cycles are the box's coarser meshes "
          "moved by the map. The map must keep every cell's orientation. "
          "Empty: the box as generated. Not with a Mesh file.",
          Patterns::Anything());
        prm.add_parameter(
          "Box map inverse",
          box_map_inverse,
          "The inverse of Box map: the box point x; y(; z) of a moved point "
          "(x, y[, z]), e.g. \"sqrt(L1*x); L2 - sqrt(L2*(L2-y)); "
          "sqrt(L3*z)\" for the example there. Required with Box map and "
          "checked at every vertex of the box; empty without it.",
          Patterns::Anything());
        prm.add_parameter(
          "Material id function",
          material_id_function,
          "The material id of each cell as a muparser expression of x, y[, "
          "z] (and the constants L1, L2[, L3]), evaluated at the centre of "
          "every cell of the generated box (Subdivisions per edge) or of the "
          "Gmsh file, before any refinement; refined cells inherit it. Its "
          "value, an integer >= 0, selects the material (subsection Material "
          "and Material N). Example: \"y > 0.8 ? 1 : 0\" for a layer on top. "
          "Empty: the mesh's own ids (0 on the generated box, the physical "
          "groups of the cells of a Gmsh file).",
          Patterns::Anything());
        prm.add_parameter("Global refinements",
                          global_refinements,
                          "Uniform refinements of the generated or read mesh; "
                          "an integer in [0, 20].",
                          Patterns::Integer(0, 20));
        prm.add_parameter(
          "Contact refinement levels",
          contact_refinements,
          "Extra refinements of the cells that touch Gamma_3, repeated this "
          "many times (a mesh graded toward the contact boundary; hanging "
          "nodes are constrained). An integer in [0, 20]; 0 for simplex "
          "cells.",
          Patterns::Integer(0, 20));
        prm.add_parameter(
          "Mesh group size",
          mesh_group_size,
          "Simplex meshes (generated or read) are built whole, refined and "
          "partitioned by one rank in every group of this many consecutive "
          "ranks, which hands each member its part: the other ranks never "
          "hold or open the whole mesh. 0: the ranks of one compute node "
          "(the largest node of the run); 1: every rank builds the mesh  "
          "itself. A Gmsh file of hexahedra is read by every rank (p4est "
          "needs its cells on every rank). An integer >= 0.",
          Patterns::Integer(0));
      }
      prm.leave_subsection();
    }

    void
    Geometry::check_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Geometry");
      {
        // A mesh file gives the geometry itself: then Lengths only sets the
        // constants L1, L2(, L3) of the expressions, as many as it has.
        require(lengths.size() == dimension || !mesh_file.empty(),
                "Geometry",
                "Lengths",
                prm.get("Lengths"),
                "exactly one length per space dimension ("
                  + std::to_string(dimension)
                  + " values) for the generated box (with a Mesh file, "
                    "Lengths only sets the constants L1, L2, L3 of the "
                    "expressions and may have 2 or 3 values)");
        const std::string pattern = prm.get("Simplex pattern");
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
        require(contact_refinements == 0 || cell_type == CellType::hypercube,
                "Geometry",
                "Contact refinement levels",
                prm.get("Contact refinement levels"),
                "0 for Cell type = simplex or mixed (deal.II 9.4 has no "
                "hanging-node constraints on simplices); any number up to 20 "
                "for hypercube meshes");
        // The map moves the generated box only, and refinement needs its
        // inverse.
        if (!box_map.empty())
          require(mesh_file.empty(),
                  "Geometry",
                  "Box map",
                  box_map,
                  "empty with a Mesh file (the map moves the generated box)");
        require(box_map.empty() == box_map_inverse.empty(),
                "Geometry",
                "Box map inverse",
                box_map_inverse,
                box_map.empty()
                  ? "empty without a Box map"
                  : "the inverse of Box map, which refinement needs");
        // A mixed mesh comes from a file.
        if (cell_type == CellType::mixed)
          require(!mesh_file.empty(),
                  "Geometry",
                  "Cell type",
                  "mixed",
                  "simplex or hypercube for the generated box; mixed "
                  "needs a Mesh file with both kinds of cells");
      }
      prm.leave_subsection();
    }



    void
    PrescribedDisplacement::add_parameters(ParameterHandler  &prm,
                                           const unsigned int number)
    {
      prm.enter_subsection("Prescribed displacement " + std::to_string(number));
      {
        prm.add_parameter(
          "Boundary ids",
          boundary_ids,
          "The boundary parts whose displacement is prescribed (empty: this "
          "entry is not used). Integers in [0, 255], each named by one "
          "entry of subsection Boundary only.",
          Patterns::List(Patterns::Integer(0, 255)));
        prm.add_parameter("Components",
                          components,
                          "The components prescribed, e.g. \"y\" or "
                          "\"x, y\"; the others stay free.",
                          Patterns::List(Patterns::Selection("x|y|z"), 1, 3));
        prm.add_parameter(
          "Displacement",
          displacement,
          "One expression of x, y[, z] and t per component of Components, "
          "separated by ';' (muparser syntax, as the loads), e.g. "
          "\"-0.01 * t\" for Components = y, or \"0; -0.01 * min(t, 1)\" "
          "for Components = x, y. A value that depends on t is a "
          "displacement-controlled load (ramp, hold, unload); the operator "
          "is still factorised once per run.");
      }
      prm.leave_subsection();
    }

    std::vector<unsigned int>
    PrescribedDisplacement::component_indices() const
    {
      std::vector<unsigned int> indices;
      for (const std::string &c : components)
        indices.push_back(c == "x" ? 0 : c == "y" ? 1 : 2);
      return indices;
    }

    void
    PrescribedDisplacement::check_parameters(ParameterHandler  &prm,
                                             const unsigned int number,
                                             const unsigned int dim)
    {
      const std::string subsection
        = "Boundary/Prescribed displacement " + std::to_string(number);
      prm.enter_subsection("Prescribed displacement " + std::to_string(number));
      {
        const std::vector<unsigned int> indices = component_indices();
        for (unsigned int i = 0; i < indices.size(); ++i)
          {
            require(indices[i] < dim,
                    subsection,
                    "Components",
                    prm.get("Components"),
                    dim == 2 ? "x and y in 2D" : "x, y and z");
            for (unsigned int j = 0; j < i; ++j)
              require(indices[i] != indices[j],
                      subsection,
                      "Components",
                      prm.get("Components"),
                      "each component once");
          }
        require(Utilities::split_string_list(displacement, ';').size()
                  == components.size(),
                subsection,
                "Displacement",
                displacement,
                "one expression per component of Components ("
                  + std::to_string(components.size()) + "), separated by ';'");
      }
      prm.leave_subsection();
    }



    std::vector<double>
    Contact::direction_vector() const
    {
      std::vector<double> d;
      double              largest = 0;
      for (const std::string &x : Utilities::split_string_list(gap_direction))
        {
          char        *end   = nullptr;
          const double value = std::strtod(x.c_str(), &end);
          if (x.empty() || end != x.c_str() + x.size() || !std::isfinite(value))
            return {};
          d.push_back(value);
          largest = std::max(largest, std::abs(value));
        }
      if (!(largest > 0))
        return {};
      double length = 0;
      for (double &x : d)
        {
          x /= largest;
          length += x * x;
        }
      for (double &x : d)
        x /= std::sqrt(length);
      return d;
    }



    void
    BoundaryParts::add_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Boundary");
      {
        prm.add_parameter(
          "Clamped boundary ids",
          clamped_ids,
          "Boundary ids of Gamma_1 (u = 0). The generated box numbers its "
          "faces as deal.II's colorize does: 0/1 at x = 0/L1, 2/3 at y = 0/L2, "
          "4/5 at z = 0/L3. Integers in [0, 255] that are on the mesh; may be "
          "empty if the other boundary conditions stop every rigid motion of "
          "the body.",
          Patterns::List(Patterns::Integer(0, 255)));
        prm.add_parameter("Contact boundary ids",
                          contact_ids,
                          "Boundary ids of Gamma_3 (contact with the "
                          "foundation), the contact zone of subsection "
                          "Contact; further zones with laws of their own: "
                          "subsections \"Contact zone N\". Every other "
                          "boundary part is Gamma_2. Integers in [0, 255], "
                          "none of them clamped.",
                          Patterns::List(Patterns::Integer(0, 255)));
        prm.add_parameter("Loaded boundary ids",
                          loaded_ids,
                          "Parts of Gamma_2 that carry the surface traction of "
                          "subsection Loads; the rest of Gamma_2 is "
                          "traction-free. Integers in [0, 255], none of them "
                          "clamped.",
                          Patterns::List(Patterns::Integer(0, 255)));
        prm.add_parameter(
          "Symmetry boundary ids",
          symmetry_ids,
          "Planar boundary parts (of any orientation) on which the normal "
          "displacement is zero and the tangential one free: rollers and "
          "planes of symmetry. Integers in [0, 255].",
          Patterns::List(Patterns::Integer(0, 255)));
        for (unsigned int n = 0; n < prescribed_displacements.size(); ++n)
          prescribed_displacements[n].add_parameters(prm, n + 1);
      }
      prm.leave_subsection();
    }

    std::vector<std::pair<unsigned int, const PrescribedDisplacement *>>
    BoundaryParts::used_prescribed_displacements() const
    {
      return used_entries(prescribed_displacements);
    }

    void
    BoundaryParts::check_parameters(ParameterHandler  &prm,
                                    const unsigned int dim)
    {
      prm.enter_subsection("Boundary");
      {
        // Every boundary id belongs to one kind of part only: the entry
        // that names an id a second time is refused, naming the first.
        std::map<types::boundary_id, std::string> owner;
        const auto claim = [&](const std::vector<types::boundary_id> &ids,
                               const std::string &subsection,
                               const std::string &entry,
                               const std::string &value) {
          for (const auto id : ids)
            {
              const auto [it, inserted]
                = owner.emplace(id,
                                "<" + entry + "> of subsection <" + subsection
                                  + ">");
              require(inserted,
                      subsection,
                      entry,
                      value,
                      "ids that no other entry names (" + std::to_string(id)
                        + " is also in " + it->second + ")");
            }
        };
        claim(clamped_ids,
              "Boundary",
              "Clamped boundary ids",
              prm.get("Clamped boundary ids"));
        claim(contact_ids,
              "Boundary",
              "Contact boundary ids",
              prm.get("Contact boundary ids"));
        claim(loaded_ids,
              "Boundary",
              "Loaded boundary ids",
              prm.get("Loaded boundary ids"));
        claim(symmetry_ids,
              "Boundary",
              "Symmetry boundary ids",
              prm.get("Symmetry boundary ids"));
        for (auto &[number, entry] : used_prescribed_displacements())
          {
            const std::string name
              = "Prescribed displacement " + std::to_string(number);
            claim(entry->boundary_ids,
                  "Boundary/" + name,
                  "Boundary ids",
                  prm.get({"Prescribed displacement " + std::to_string(number)},
                          "Boundary ids"));
            prescribed_displacements[number - 1].check_parameters(prm,
                                                                  number,
                                                                  dim);
          }
      }
      prm.leave_subsection();
    }

    // @sect4{parse_parameter_file}
    //
    // ParameterHandler::parse_input(), with a value that its entry's pattern
    // rejects reported as every other rejected entry is: deal.II names the
    // file, the line, the entry and the pattern; the message names the
    // subsection (from the subsection lines of that file before that line:
    // in a file that another includes, the path below the include), the
    // entry, the value and, in words, what is accepted.
    void
    parse_parameter_file(ParameterHandler &prm, const std::string &file)
    {
      try
        {
          prm.parse_input(file);
        }
      catch (const ParameterHandler::ExcInvalidEntryForPattern &exc)
        {
          // The message's lines: "Line <N> of file <F>:", "The entry value",
          // the value, "for the entry named", the entry, "does not match
          // the given pattern:", the pattern.
          std::ostringstream info;
          exc.print_info(info);
          std::vector<std::string> lines;
          std::istringstream       text(info.str());
          for (std::string line; std::getline(text, line);)
            lines.push_back(Utilities::trim(line));
          std::smatch where;
          if (lines.size() < 7
              || !std::regex_match(lines[0],
                                   where,
                                   std::regex("^Line <([0-9]+)> of file "
                                              "<(.*)>:$")))
            throw;
          const unsigned int       line_number = std::stoul(where[1].str());
          const std::string        input       = where[2].str();
          std::vector<std::string> path;
          std::ifstream            in(input);
          std::string              line;
          for (unsigned int n = 1; n < line_number && std::getline(in, line);
               ++n)
            {
              const std::string statement
                = Utilities::trim(line.substr(0, line.find('#')));
              if (statement.rfind("subsection ", 0) == 0
                  || statement.rfind("SUBSECTION ", 0) == 0)
                path.push_back(Utilities::trim(statement.substr(11)));
              else if ((statement == "end" || statement == "END")
                       && !path.empty())
                path.pop_back();
            }
          std::string subsection;
          for (const std::string &section : path)
            subsection += (subsection.empty() ? "" : "/") + section;
          require(false,
                  subsection,
                  lines[4],
                  lines[2],
                  accepted_by(lines[6]) + " (line " + where[1].str() + " of "
                    + input + ")");
        }
    }



    unsigned int
    count_numbered_subsections(const std::string &parameter_file,
                               const std::string &name)
    {
      // The files an "include" line names are read as ParameterHandler
      // reads them (the name as given), to a depth that no sensible file
      // reaches (ParameterHandler itself reports a cycle). The name is
      // matched with any run of blanks between its words.
      const std::string pattern
        = std::regex_replace(name, std::regex(" "), "\\s+");
      const std::regex subsection("^\\s*subsection\\s+" + pattern
                                  + "\\s+([0-9]{1,3})\\s*(#.*)?$");
      const std::regex include("^\\s*include\\s+(\\S+)\\s*(#.*)?$");
      std::vector<std::pair<std::string, unsigned int>> files{
        {parameter_file, 0}};
      unsigned int highest = 1;
      while (!files.empty())
        {
          const auto [file, depth] = files.back();
          files.pop_back();
          std::ifstream in(file);
          std::string   line;
          while (std::getline(in, line))
            {
              std::smatch match;
              if (std::regex_match(line, match, subsection))
                highest = std::max(highest,
                                   static_cast<unsigned int>(
                                     std::stoul(match[1].str())));
              else if (depth < 16 && std::regex_match(line, match, include))
                files.emplace_back(match[1].str(), depth + 1);
            }
        }
      return highest;
    }



    void
    Material::add_parameters(ParameterHandler  &prm,
                             const std::string &subsection)
    {
      prm.enter_subsection(subsection);
      {
        prm.add_parameter(
          "Material ids",
          material_ids,
          subsection == "Material"
            ? "The material ids of the cells of this material: the "
              "physical groups of the cells of a Gmsh file, or the values "
              "of <Material id function> in subsection Geometry (the "
              "generated box has id 0). Empty: every cell, if the mesh has "
              "one material id only. Further materials are subsections "
              "\"Material 2\", \"Material 3\", ... with the same entries; "
              "each id of the mesh must be named by exactly one of them."
            : "The material ids of the cells of this material (empty: this "
              "material is not used). Each id is named by one material only.",
          Patterns::List(Patterns::Integer(0)));
        add_selection(
          prm,
          "Law",
          law,
          {{"Perzyna", MaterialLawType::perzyna},
           {"hardening plasticity", MaterialLawType::hardening_plasticity}},
          "How the material leaves the elastic range (with Plasticity = "
          "true): Perzyna, the viscoplastic law G = -(1/(2 lambda)) E "
          "(sigma - P_K sigma) of the paper (Viscosity, Yield stress); or "
          "hardening plasticity, rate-independent von Mises plasticity with "
          "linear isotropic hardening (Yield stress, Hardening modulus), "
          "which needs Stress update = implicit and, in 2D, Plane model = "
          "plane strain.");
        prm.add_parameter("Young's modulus",
                          young_modulus,
                          "E > 0 [N/m^2].",
                          positive);
        prm.add_parameter("Poisson ratio",
                          poisson_ratio,
                          "k: -1 < k < 1 in 2D (plane stress), -1 < k < 0.5 "
                          "in 3D.",
                          Interval(-1, true, 1, true));
        prm.add_parameter("Viscosity",
                          viscosity,
                          "lambda > 0 [N s/m^2] of the Perzyna law "
                          "G = -(1/(2 lambda)) E (sigma - P_K sigma).",
                          positive);
        prm.add_parameter("Yield stress",
                          yield_stress,
                          "sigma_Y > 0 [N/m^2] of the von Mises set K.",
                          positive);
        prm.add_parameter("Hardening modulus",
                          hardening_modulus,
                          "H >= 0 [N/m^2] of Law = hardening plasticity: the "
                          "yield stress grows to sigma_Y + H alpha with the "
                          "equivalent plastic strain alpha (0: perfect "
                          "plasticity, the limit of Perzyna's law as the "
                          "viscosity goes to 0).",
                          Patterns::Double(0));
        prm.add_parameter("Plasticity",
                          plasticity,
                          "false: linear elasticity (G = 0): the cells of "
                          "this material keep no history and cost no stress "
                          "update; without any viscoplastic material the "
                          "history terms are skipped altogether.",
                          Patterns::Bool());
      }
      prm.leave_subsection();
    }

    void
    Material::check_parameters(ParameterHandler  &prm,
                               const unsigned int dim,
                               const std::string &subsection) const
    {
      prm.enter_subsection(subsection);
      {
        const double k_max = (dim == 2 ? 1.0 : 0.5);
        require(poisson_ratio > -1 && poisson_ratio < k_max,
                subsection,
                "Poisson ratio",
                to_string(poisson_ratio),
                std::string("-1 < k < ")
                  + (dim == 2 ? "1 (2D plane stress)" : "0.5 (3D)"));
      }
      prm.leave_subsection();
    }



    void
    Loads::add_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Loads");
      {
        prm.add_parameter(
          "Body force",
          body_force,
          "f_0(x,t) [N/m^2 in 2D]: one muparser expression per component, "
          "separated by ';', in the variables x, y (, z) and t and the "
          "constants pi, L1, L2 (, L3). A load without the variable t is "
          "assembled once for the whole run. Every value at the load points "
          "of the mesh and the times of the run must be finite.",
          Patterns::Anything());
        prm.add_parameter(
          "Surface traction",
          surface_traction,
          "f_2(x,t) [N/m in 2D] on the Loaded boundary ids, same syntax as "
          "the body force; every value must be finite. Other loads on other "
          "parts: subsections \"Surface load N\".",
          Patterns::Anything());
        for (unsigned int n = 0; n < surface_loads.size(); ++n)
          surface_loads[n].add_parameters(prm, n + 1);
      }
      prm.leave_subsection();
    }

    std::vector<std::pair<unsigned int, const SurfaceLoad *>>
    Loads::used_surface_loads() const
    {
      return used_entries(surface_loads);
    }



    void
    SurfaceLoad::add_parameters(ParameterHandler  &prm,
                                const unsigned int number)
    {
      prm.enter_subsection("Surface load " + std::to_string(number));
      {
        prm.add_parameter(
          "Boundary ids",
          boundary_ids,
          "The boundary parts that carry this load (empty: this entry is not "
          "used). Integers in [0, 255], each named by one entry of "
          "subsections Boundary and Loads only.",
          Patterns::List(Patterns::Integer(0, 255)));
        add_selection(prm,
                      "Type",
                      type,
                      {{"traction", SurfaceLoadType::traction},
                       {"pressure", SurfaceLoadType::pressure}},
                      "traction: the force per area as a vector; pressure: "
                      "a force per area p along the inward normal, "
                      "-p n (positive p pushes into the body; also on curved "
                      "parts).");
        prm.add_parameter(
          "Value",
          value,
          "traction: one expression of x, y[, z] and t per component, "
          "separated by ';' (as Surface traction); pressure: one "
          "expression, e.g. \"2 * min(t, 1)\". Every value must be finite.",
          Patterns::Anything());
      }
      prm.leave_subsection();
    }

    void
    SurfaceLoad::check_parameters(const unsigned int number,
                                  const unsigned int dim) const
    {
      const unsigned int n_expressions
        = Utilities::split_string_list(value, ';').size();
      const unsigned int expected
        = (type == SurfaceLoadType::traction ? dim : 1);
      require(n_expressions == expected,
              "Loads/Surface load " + std::to_string(number),
              "Value",
              value,
              type == SurfaceLoadType::traction
                ? std::to_string(dim)
                    + " expressions separated by ';' for Type = traction"
                : std::string("one expression for Type = pressure"));
    }


    namespace
    {
      // Whether an expression is the number zero (an expression that only
      // evaluates to zero counts as a value), and whether every component
      // of a list separated by ';' is.
      bool
      is_zero_number(const std::string &expression)
      {
        try
          {
            return Utilities::string_to_double(expression) == 0;
          }
        catch (...)
          {
            return false;
          }
      }

      // Whether an expression mentions one of the variables (a regular
      // expression for the name: "t", "[xyz]"), not as part of a longer
      // name ("tan" does not mention t).
      bool
      mentions(const std::string &expression, const std::string &variables)
      {
        const std::regex variable("(^|[^A-Za-z0-9_])" + variables
                                  + "($|[^A-Za-z0-9_])");
        return std::regex_search(expression, variable);
      }

      bool
      is_zero_vector(const std::string &expression)
      {
        for (const std::string &part :
             Utilities::split_string_list(expression, ';'))
          if (!is_zero_number(part))
            return false;
        return true;
      }
    } // namespace

    void
    Contact::add_parameters(ParameterHandler  &prm,
                            const std::string &subsection)
    {
      const bool first_zone = (subsection == "Contact");
      prm.enter_subsection(subsection);
      {
        if (!first_zone)
          prm.add_parameter(
            "Boundary ids",
            boundary_ids,
            "The boundary ids of this contact zone (empty: the subsection is "
            "not used); the law, layer and obstacle entries below mean what "
            "they mean in subsection Contact. A vertex shared with a zone of "
            "a lower number belongs to that zone.",
            Patterns::List(Patterns::Integer(0, 255)));
        prm.add_parameter(
          "Opposite boundary ids",
          opposite_ids,
          "A contact pair: the boundary parts of another body of the mesh "
          "that this zone meets (empty: the zone meets a rigid obstacle). "
          "The law acts on the relative displacement of the two sides, "
          "coupled by mortar integrals on non-matching meshes; the gap is "
          "their distance along the zone's normal plus Initial gap (2D; "
          "doc/model.md, section 8).",
          Patterns::List(Patterns::Integer(0, 255)));
        prm.add_parameter(
          "Search distance",
          search_distance,
          "A contact pair: the largest distance along the zone's normal "
          "(in front of the zone or behind it) at which a face of the "
          "opposite side is paired with a face of the zone [m]; auto: the "
          "longest face of the two sides.",
          AutoOrPositive());
        prm.add_parameter(
          "Geometric gap",
          geometric_gap,
          "A contact pair: measured: the gap of a node is the distance "
          "between the two sides along its normal (on the mesh's faces) "
          "plus Initial gap; ignored: Initial gap alone, for two sides that "
          "discretise the same curve with different nodes (a curved "
          "interface whose polygons would otherwise show gaps of the order "
          "of h^2 / radius between them).",
          Patterns::Selection("measured|ignored"));
        prm.add_parameter("Unilateral constraint",
                          unilateral_constraint,
                          "Rigid foundation under the layer: u_nu <= g.",
                          Patterns::Bool());
        prm.add_parameter("Normal compliance",
                          normal_compliance,
                          "Deformable layer: -sigma_nu = p(u_nu).",
                          Patterns::Bool());
        prm.add_parameter("Layer thickness",
                          gap,
                          "g > 0 [m], the thickness of the deformable layer "
                          "(g >= 0 is accepted without normal compliance: "
                          "Signorini with gap g).",
                          non_negative);
        add_selection(
          prm,
          "Law",
          law_type,
          {{"nonmonotone", ContactLawType::nonmonotone},
           {"piecewise linear", ContactLawType::piecewise_linear}},
          "nonmonotone: the benchmark law p(r) = 0 (r < 0), c1 r (0 <= r <= "
          "u1), c1 u1 + c2 (r - u1) (r > u1); piecewise linear: any law given "
          "by Breakpoints, Slopes and Jumps.");
        prm.add_parameter("c1",
                          c1,
                          "Stiffness of the layer up to u1 [N/m^3], c1 >= 0.",
                          Patterns::Double());
        prm.add_parameter("c2",
                          c2,
                          "Slope beyond u1 [N/m^3]; negative = softening.",
                          Patterns::Double());
        prm.add_parameter("u1",
                          u1,
                          "Penetration where the slope changes [m], u1 >= 0.",
                          Patterns::Double());
        prm.add_parameter(
          "Breakpoints",
          breakpoints,
          "Piecewise-linear law: increasing breakpoints b_1 < ... < b_K.",
          Patterns::List(Patterns::Double()));
        prm.add_parameter("Slopes",
                          slopes,
                          "Piecewise-linear law: K+1 slopes, on (-inf,b_1), "
                          "(b_1,b_2), ..., (b_K,inf); p(b_1-) = 0.",
                          Patterns::List(Patterns::Double()));
        prm.add_parameter(
          "Jumps",
          jumps,
          "Piecewise-linear law: K jumps p(b_k+) - p(b_k-) >= 0 (empty: all "
          "zero). A jump makes the Clarke subdifferential an interval (an "
          "upward jump is a vertical piece of the graph; a downward one has no "
          "such piece).",
          Patterns::List(Patterns::Double()));
        if (first_zone)
          prm.add_parameter(
            "Check uniqueness",
            check_uniqueness,
            "At set-up, compute the smallest generalised eigenvalue of "
            "(stiffness, lumped normal boundary mass) by a Lanczos iteration "
            "and "
            "compare it with the steepest softening of the law (doc/model.md, "
            "section 4): a dense product per iteration on the condensed back "
            "end, one elastic solve per iteration (about 10 to 20) on the full "
            "space back end.",
            Patterns::Bool());
        prm.add_parameter(
          "Initial gap",
          initial_gap,
          "s(x, t): the distance from a point x of Gamma_3 to the obstacle, "
          "measured along Gap direction; a muparser expression in x, y (, z), "
          "t (and pi, L1, L2 (, L3)). The law acts on the penetration "
          "r = u.d - s (0: the paper's foundation along the contact "
          "boundary). A rigid plane y = 0 under a body above it: \"y\" with "
          "Gap direction 0, -1; an indenter that moves into the body by "
          "0.01 t: \"... - 0.01 * t\".");
        prm.add_parameter(
          "Obstacle motion",
          obstacle_motion,
          "o(t): the rigid translation of the obstacle since t = 0, dim "
          "muparser expressions in t separated by ';' (0: the obstacle does "
          "not move). Initial gap describes the obstacle where it is at t = "
          "0: the gap at x is s(x - o(t), t); friction acts on the slip "
          "relative to the obstacle. A rigid support moving sideways under "
          "a body: \"-0.01 * t; 0\"; a punch dragged along x: \"0.1 * t; 0\". "
          "Not on a contact pair (Opposite boundary ids).",
          Patterns::Anything());
        prm.add_parameter(
          "Obstacle rotation",
          obstacle_rotation,
          "theta(t): the rigid rotation of the obstacle since t = 0 about the "
          "point that is at Rotation center at t = 0 and moves with Obstacle "
          "motion: the angle in radians, counterclockwise (2D, one "
          "expression), or the rotation vector, its direction the axis and "
          "its length the angle (3D, three expressions separated by ';'), in "
          "t (0: the obstacle does not turn). A point X of the obstacle at "
          "t = 0 is at c + o(t) + R(t) (X - c); the gap at x is s(c + R(t)^T "
          "(x - c - o(t)), t), so Initial gap must be a distance the rotation "
          "leaves as it is: for a cylinder of radius 2, its axis at x = 1, "
          "y = 3, the distance \"sqrt((x - 1)^2 + (y - 3)^2) - 2\" (a gap "
          "measured along a fixed direction would turn with the obstacle). A "
          "wheel of radius 2 rolling along x at speed V: Obstacle motion = "
          "\"V * t; 0\", Obstacle rotation = \"-V * t / 2\", Rotation center "
          "= \"1; 3\". Not on a contact pair.",
          Patterns::Anything());
        prm.add_parameter(
          "Rotation center",
          rotation_center,
          "c: the point the obstacle turns about at t = 0 (dim numbers "
          "separated by ';'), needed with Obstacle rotation.",
          Patterns::Anything());
        prm.add_parameter(
          "Gap direction",
          gap_direction,
          "d: normal (each node's outward normal, the paper's model) or a "
          "vector of dim numbers, the direction from the body into the "
          "obstacle (minus the obstacle's normal), e.g. 0, -1.");
        add_selection(
          prm,
          "Tangential law",
          tangential_law,
          {{"frictionless", TangentialLawType::frictionless},
           {"Tresca", TangentialLawType::tresca},
           {"Coulomb", TangentialLawType::coulomb}},
          "Friction on the zone (doc/model.md, section 7), acting on the "
          "slip of each time step with exact stick: frictionless (the "
          "paper's model); Tresca: the tangential traction is at most Slip "
          "bound, on every node of the zone; Coulomb: at most Friction "
          "coefficient times the contact pressure.");
        prm.add_parameter(
          "Slip bound",
          slip_bound,
          "Tresca's bound g(x) >= 0 on the tangential traction [N/m^2 in "
          "3D, N/m in 2D]: a muparser expression in x, y (, z) (and pi, L1, "
          "L2 (, L3)), not in t.",
          Patterns::Anything());
        prm.add_parameter("Friction coefficient",
                          friction_coefficient,
                          "Coulomb's coefficient mu >= 0.",
                          non_negative);
        prm.add_parameter(
          "Weakening slips",
          weakening_slips,
          "Slip weakening of the tangential law (doc/model.md, section 7): "
          "the bound (Slip bound, or Friction coefficient times the "
          "pressure) times f(S), S the node's accumulated slip up to the "
          "last step, f piecewise linear through the points (S_k, f_k) and "
          "constant beyond them. These are S_1 < ... < S_K >= 0 [m] (empty: "
          "no weakening).",
          Patterns::List(Patterns::Double()));
        prm.add_parameter(
          "Weakening slip rates",
          weakening_rates,
          "Instead of Weakening slips: the bound times f(v), v the node's "
          "slip rate in the last step (|slip| / time step), f piecewise "
          "linear through the points (v_k, f_k): v_1 < ... < v_K >= 0 "
          "[m/s] (empty: none).",
          Patterns::List(Patterns::Double()));
        prm.add_parameter("Weakening factors",
                          weakening_factors,
                          "The factors f_k >= 0 at the Weakening slips (or "
                          "slip rates), one per point (e.g. 1, 0.6: a "
                          "coefficient that falls to 60% of its value).",
                          Patterns::List(Patterns::Double()));
        prm.add_parameter(
          "Memory weights",
          memory_weights,
          "The memory term of the normal law (doc/model.md, section 9): the "
          "pressure gets int_0^t b(t - s) r+(s) ds with the kernel b(t) = "
          "sum_k a_k exp(-lambda_k t); these are the a_k [N/m^3/s in 2D "
          "and 3D], one per term (empty: no memory). Needs Normal "
          "compliance = true.",
          Patterns::List(Patterns::Double()));
        prm.add_parameter(
          "Memory rates",
          memory_rates,
          "The lambda_k >= 0 of the memory kernel [1/s], one per Memory "
          "weight (0: a constant term, the kernel's integral grows as a_k t).",
          Patterns::List(Patterns::Double()));
        prm.add_parameter(
          "Adhesion stiffness",
          adhesion_stiffness,
          "Adhesion with a bonding field (doc/model.md, section 10): where the "
          "body separates from the obstacle (r < 0) it is pulled back by the "
          "tension gamma beta^2 R(r), R(r) = max(-L, r), beta in [0, 1] the "
          "node's bonding. This is gamma >= 0 [Pa/m] (0: no adhesion).",
          Patterns::Double());
        prm.add_parameter("Adhesion length",
                          adhesion_length,
                          "L > 0 [m]: the separation beyond which the "
                          "tension stays at gamma beta^2 L (needed with "
                          "Adhesion stiffness > 0).",
                          Patterns::Double());
        prm.add_parameter(
          "Adhesion energy",
          adhesion_energy,
          "epsilon >= 0 [J/m^2] in the bonding's evolution beta' = -kappa "
          "(beta gamma R(r)^2 - epsilon)+: below this energy the bond holds; "
          "beta only decreases (debonding is irreversible).",
          Patterns::Double());
        prm.add_parameter("Debonding rate",
                          debonding_rate,
                          "kappa >= 0 [m^2/(J s)] in the bonding's evolution "
                          "(1: the form of the literature, beta' = -(beta "
                          "gamma R^2 - epsilon)+).",
                          Patterns::Double());
        prm.add_parameter(
          "Wear coefficient",
          wear_coefficient,
          "Archard's wear (doc/model.md, section 11): where a node slips under "
          "the pressure p its surface wears away at the rate w' = k_w p "
          "|slip rate|, and the obstacle of the next step is w further away. "
          "This is k_w >= 0 [1/Pa] (0: no wear). Needs friction.",
          Patterns::Double());
        prm.add_parameter("Initial bonding",
                          initial_bonding,
                          "beta_0(x, y, z) in [0, 1]: the bonding at t = 0 "
                          "(1: fully bonded; 0 where the surfaces are not "
                          "glued).",
                          Patterns::Anything());
        prm.add_parameter(
          "Cohesive strength",
          cohesive_strength,
          "A cohesive interface with damage (doc/model.md, section 12): "
          "where the body opens from the obstacle by delta = -r > 0 the "
          "interface pulls it back with a tension that rises with the "
          "Cohesive stiffness K to this strength T_c at delta_0 = T_c / K and "
          "falls linearly to 0 at delta_f = 2 G_c / T_c; below the largest "
          "opening a node has reached it unloads and reloads on the secant "
          "(the damage never heals). This is T_c >= 0 [Pa] (0: none).",
          Patterns::Double());
        prm.add_parameter("Cohesive stiffness",
                          cohesive_stiffness,
                          "K > 0 [Pa/m]: the interface's stiffness before it "
                          "is damaged (needed with Cohesive strength > 0).",
                          Patterns::Double());
        prm.add_parameter("Fracture energy",
                          fracture_energy,
                          "G_c > T_c^2 / (2 K) [J/m^2]: the work to open the "
                          "interface completely (needed with Cohesive "
                          "strength > 0).",
                          Patterns::Double());
        prm.add_parameter(
          "Cohesive damage",
          cohesive_damage,
          "How a time step treats an opening beyond the largest one reached "
          "before it (doc/model.md, section 12). implicit: on the envelope, "
          "which softens within the step; exact for every time step, but the "
          "step problem is unique only where the body is stiffer than the "
          "softening (the start-up check), and the active set may cycle "
          "where it is not (a slender strip peeled off). explicit: on a "
          "plateau at the tension reached before the step, the damage "
          "taken from the last step as the other histories are; a monotone "
          "law, so always one solution, with a tension that lags the "
          "envelope by one step (first order in the time step).",
          Patterns::Selection("implicit|explicit"));
        prm.add_parameter(
          "Cohesive softening",
          cohesive_softening,
          "How the tension falls after its peak T_c at delta_0 = T_c / K "
          "(doc/model.md, section 12). linear: to 0 at delta_f = 2 G_c / "
          "T_c (Code_Aster's CZM_LIN_REG). exponential: as T_c exp(-(delta - "
          "delta_0) / lambda), lambda = (G_c - T_c delta_0 / 2) / T_c "
          "(Code_Aster's CZM_EXP_REG), in 16 linear pieces down to T_c / "
          "1000 and then to 0, stretched so that the work of separation is "
          "G_c exactly.",
          Patterns::Selection("linear|exponential"));
      }
      prm.leave_subsection();
    }

    void
    Contact::check_parameters(ParameterHandler  &prm,
                              const unsigned int dim,
                              const std::string &subsection) const
    {
      prm.enter_subsection(subsection);
      {
        if (gap_direction != "normal")
          {
            require(direction_vector().size() == dim,
                    subsection,
                    "Gap direction",
                    gap_direction,
                    "normal, or " + std::to_string(dim)
                      + " numbers separated by ',' that are not all zero");
          }
        if (tangential_law != TangentialLawType::frictionless)
          require(unilateral_constraint || normal_compliance,
                  subsection,
                  "Tangential law",
                  prm.get("Tangential law"),
                  "frictionless on a zone without a normal law (Unilateral "
                  "constraint = false and Normal compliance = false)");
        if (tangential_law == TangentialLawType::tresca)
          {
            require(!mentions(slip_bound, "t"),
                    subsection,
                    "Slip bound",
                    slip_bound,
                    "an expression of the position x, y (, z) alone, not of "
                    "the time t");
            double constant  = 0;
            bool   is_number = true;
            try
              {
                constant = Utilities::string_to_double(slip_bound);
              }
            catch (...)
              {
                is_number = false;
              }
            require(!is_number || (constant >= 0 && std::isfinite(constant)),
                    subsection,
                    "Slip bound",
                    slip_bound,
                    "a finite bound g >= 0");
          }
        // The obstacle's rigid motion: functions of t alone, and none on a
        // contact pair.
        for (const auto &[entry, value, kind] :
             {std::tuple{"Obstacle motion", &obstacle_motion, "translation"},
              std::tuple{"Obstacle rotation", &obstacle_rotation, "rotation"}})
          if (!is_zero_vector(*value))
            {
              require(!mentions(*value, "[xyz]"),
                      subsection,
                      entry,
                      *value,
                      std::string("expressions of the time t alone (a rigid ")
                        + kind + "), not of the position x, y (, z)");
              require(opposite_ids.empty(),
                      subsection,
                      entry,
                      *value,
                      "0 on a contact pair (Opposite boundary ids): the other "
                      "body moves by its own boundary conditions");
            }
        require(!mentions(rotation_center, "[xyzt]"),
                subsection,
                "Rotation center",
                rotation_center,
                "numbers (a fixed point at t = 0; it moves with Obstacle "
                "motion)");
        if (!opposite_ids.empty())
          require(gap_direction == "normal",
                  subsection,
                  "Gap direction",
                  gap_direction,
                  "normal on a contact pair (Opposite boundary ids): the "
                  "gap is measured along the zone's normals");
        if (normal_compliance)
          require(gap > 0,
                  subsection,
                  "Layer thickness",
                  to_string(gap),
                  "g > 0 with Normal compliance = true");
        require(weakening_slips.empty() || weakening_rates.empty(),
                subsection,
                "Weakening slip rates",
                prm.get("Weakening slip rates"),
                "empty when Weakening slips are given (a law weakens with "
                "the slip or with its rate)");
        const bool                 of_rate = !weakening_rates.empty();
        const std::vector<double> &points
          = of_rate ? weakening_rates : weakening_slips;
        const std::string points_entry
          = of_rate ? "Weakening slip rates" : "Weakening slips";
        require(weakening_factors.size() == points.size(),
                subsection,
                "Weakening factors",
                prm.get("Weakening factors"),
                "one factor per point of " + points_entry + " ("
                  + std::to_string(points.size()) + " values)");
        for (unsigned int k = 0; k < points.size(); ++k)
          require(std::isfinite(points[k])
                    && (k == 0 ? points[k] >= 0 : points[k] > points[k - 1]),
                  subsection,
                  points_entry,
                  prm.get(points_entry),
                  "finite values 0 <= x_1 < ... < x_K");
        for (const double factor : weakening_factors)
          require(factor >= 0 && std::isfinite(factor),
                  subsection,
                  "Weakening factors",
                  prm.get("Weakening factors"),
                  "finite factors f_k >= 0");
        if (!points.empty())
          require(tangential_law != TangentialLawType::frictionless,
                  subsection,
                  points_entry,
                  prm.get(points_entry),
                  "empty with Tangential law = frictionless");
        require(memory_rates.size() == memory_weights.size(),
                subsection,
                "Memory rates",
                prm.get("Memory rates"),
                "one rate per Memory weight ("
                  + std::to_string(memory_weights.size()) + " values)");
        for (const double weight : memory_weights)
          require(std::isfinite(weight),
                  subsection,
                  "Memory weights",
                  prm.get("Memory weights"),
                  "finite numbers");
        for (const double rate : memory_rates)
          require(rate >= 0 && std::isfinite(rate),
                  subsection,
                  "Memory rates",
                  prm.get("Memory rates"),
                  "finite rates lambda_k >= 0");
        if (!memory_weights.empty())
          require(normal_compliance,
                  subsection,
                  "Memory weights",
                  prm.get("Memory weights"),
                  "empty with Normal compliance = false (the memory term "
                  "acts on the penetration of the layer)");
        require(adhesion_stiffness >= 0 && std::isfinite(adhesion_stiffness),
                subsection,
                "Adhesion stiffness",
                to_string(adhesion_stiffness),
                "a finite gamma >= 0");
        if (adhesion_stiffness > 0)
          {
            require(adhesion_length > 0 && std::isfinite(adhesion_length),
                    subsection,
                    "Adhesion length",
                    to_string(adhesion_length),
                    "a finite L > 0 with Adhesion stiffness > 0");
            require(adhesion_energy >= 0 && std::isfinite(adhesion_energy),
                    subsection,
                    "Adhesion energy",
                    to_string(adhesion_energy),
                    "a finite epsilon >= 0");
            require(debonding_rate >= 0 && std::isfinite(debonding_rate),
                    subsection,
                    "Debonding rate",
                    to_string(debonding_rate),
                    "a finite kappa >= 0");
          }
        require(cohesive_strength >= 0 && std::isfinite(cohesive_strength),
                subsection,
                "Cohesive strength",
                to_string(cohesive_strength),
                "a finite T_c >= 0");
        if (cohesive_strength > 0)
          {
            require(adhesion_stiffness == 0,
                    subsection,
                    "Cohesive strength",
                    to_string(cohesive_strength),
                    "0 with Adhesion stiffness > 0 (a zone is glued by "
                    "adhesion or by a cohesive interface, not both)");
            require(cohesive_stiffness > 0 && std::isfinite(cohesive_stiffness),
                    subsection,
                    "Cohesive stiffness",
                    to_string(cohesive_stiffness),
                    "a finite K > 0 with Cohesive strength > 0");
            require(std::isfinite(fracture_energy)
                      && std::isfinite(2 * fracture_energy / cohesive_strength)
                      && fracture_energy > cohesive_strength * cohesive_strength
                                             / (2 * cohesive_stiffness),
                    subsection,
                    "Fracture energy",
                    to_string(fracture_energy),
                    "a finite G_c > T_c^2 / (2 K) = "
                      + to_string(cohesive_strength * cohesive_strength
                                  / (2 * cohesive_stiffness))
                      + " (the energy of the elastic part alone: the "
                        "tension must soften after its peak)");
          }
        if (adhesion_stiffness > 0 || cohesive_strength > 0)
          {
            const std::string entry = adhesion_stiffness > 0
                                        ? "Adhesion stiffness"
                                        : "Cohesive strength";
            require(gap >= 0,
                    subsection,
                    "Layer thickness",
                    to_string(gap),
                    "g >= 0 with " + entry
                      + " > 0 (the tension acts for r < 0, below the rigid "
                        "limit)");
            const bool tension_in_law
              = normal_compliance
                && law_type == ContactLawType::piecewise_linear
                && !slopes.empty()
                && (slopes[0] != 0
                    || (!breakpoints.empty() && breakpoints[0] < 0));
            require(!tension_in_law,
                    subsection,
                    "Breakpoints",
                    prm.get("Breakpoints"),
                    "a law that is zero for r < 0 with " + entry
                      + " > 0 (first breakpoint >= 0 and first slope 0: the "
                        "tension of the glue is the law there)");
          }
        require(wear_coefficient >= 0 && std::isfinite(wear_coefficient),
                subsection,
                "Wear coefficient",
                to_string(wear_coefficient),
                "a finite k_w >= 0");
        if (wear_coefficient > 0)
          require(cohesive_strength == 0,
                  subsection,
                  "Wear coefficient",
                  to_string(wear_coefficient),
                  "0 with Cohesive strength > 0 (the worn depth would count "
                  "as an opening of the interface)");
        if (wear_coefficient > 0)
          require(tangential_law != TangentialLawType::frictionless,
                  subsection,
                  "Wear coefficient",
                  to_string(wear_coefficient),
                  "0 with Tangential law = frictionless (the wear grows with "
                  "the slip, which a frictionless zone does not measure)");
        // The ranges of the laws' entries hold only for the law that uses
        // them.
        if (normal_compliance && law_type == ContactLawType::nonmonotone)
          {
            require(c1 >= 0, subsection, "c1", to_string(c1), "c1 >= 0");
            require(u1 >= 0, subsection, "u1", to_string(u1), "u1 >= 0");
          }
        if (normal_compliance && law_type == ContactLawType::piecewise_linear)
          {
            require(breakpoints.size() >= 1,
                    subsection,
                    "Breakpoints",
                    prm.get("Breakpoints"),
                    "at least one breakpoint for Law = piecewise linear");
            for (unsigned int k = 1; k < breakpoints.size(); ++k)
              require(breakpoints[k] > breakpoints[k - 1],
                      subsection,
                      "Breakpoints",
                      prm.get("Breakpoints"),
                      "strictly increasing values");
            require(slopes.size() == breakpoints.size() + 1,
                    subsection,
                    "Slopes",
                    prm.get("Slopes"),
                    "one more slope than breakpoints ("
                      + std::to_string(breakpoints.size() + 1) + " values)");
            require(jumps.empty() || jumps.size() == breakpoints.size(),
                    subsection,
                    "Jumps",
                    prm.get("Jumps"),
                    "empty or one jump per breakpoint ("
                      + std::to_string(breakpoints.size()) + " values)");
            for (const double jump : jumps)
              require(jump >= 0,
                      subsection,
                      "Jumps",
                      prm.get("Jumps"),
                      "non-negative jumps (an upward jump is a vertical piece "
                      "of the graph; a downward one has no such piece)");
          }
      }
      prm.leave_subsection();
    }



    void
    Time::add_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Time");
      {
        prm.add_parameter("End time", end_time, "T > 0 [s].", positive);
        prm.add_parameter("Time step",
                          time_step,
                          "k with 0 < k <= T [s]; if T/k is not an integer the "
                          "last step is shortened to end at T.",
                          positive);
        add_selection(
          prm,
          "Stress update",
          stress_update,
          {{"explicit", StressUpdate::explicit_euler},
           {"implicit", StressUpdate::implicit_euler}},
          "explicit: the paper's scheme, H_n from the previous stresses "
          "(doc/model.md, section 2; stable for k < 4 lambda/lambda_max(E)); "
          "implicit: backward Euler, sigma_n from a local equation at each "
          "stress point and a Newton iteration with the consistent tangent "
          "per step (doc/model.md, section 3; unconditionally stable; the "
          "back end sets up the tangent in every Newton iteration).");
        add_selection(
          prm,
          "On solver failure",
          on_failure,
          {{"stop", FailurePolicy::stop},
           {"cut time step", FailurePolicy::cut_time_step}},
          "When a step's solve fails (the active-set or Newton iteration "
          "reaches its limit, CG fails, or the displacement is not finite): "
          "stop (write the last accepted state as failed_step_NNNN.pvtu, "
          "report, exit status 1), or cut time step (retry the step with half "
          "the time step, down to Minimum time step; the remainder of the "
          "step follows as the next step).");
        prm.add_parameter("Minimum time step",
                          minimum_time_step,
                          "The smallest time step a cut may reach [s], and "
                          "with Time step control = adaptive the smallest "
                          "step the controller takes; in (0, Time step].",
                          positive);
        add_selection(
          prm,
          "Time step control",
          time_step_control,
          {{"fixed", TimeStepControl::fixed},
           {"adaptive", TimeStepControl::adaptive}},
          "fixed: the steps of Time step (cut only when a solve fails); "
          "adaptive: Time step is the first step, and each step's length "
          "follows from an estimate of the local error of the history update "
          "(the difference between the Euler and the trapezoidal history "
          "increment, doc/adaptivity.md); a step whose estimate exceeds Error "
          "tolerance is repeated with a shorter one. The steps land on End "
          "time and on the Profile times.");
        prm.add_parameter(
          "Error tolerance",
          error_tolerance,
          "With Time step control = adaptive: the bound on each step's "
          "estimated local error of the history, relative to the stress "
          "(both in the energy norm of E^-1 over the body); in (0, 1].",
          Interval(0, true, 1, false));
        prm.add_parameter(
          "Maximum time step",
          maximum_time_step,
          "With Time step control = adaptive: the largest step [s]; 0: End "
          "time. The explicit history update never takes more than 0.9 times "
          "its stability limit 4 lambda / lambda_max(E). 0, or in [Minimum "
          "time step, End time].",
          non_negative);
        prm.add_parameter(
          "Maximum number of steps",
          max_steps,
          "The most time steps a run may take: a schedule of more steps "
          "(End time / Time step; for each run of a convergence study too) "
          "is refused before anything is written, and adaptive steps stop "
          "with an error there. An integer in [1, 1e7].",
          Patterns::Integer(1, 10000000));
      }
      prm.leave_subsection();
    }

    void
    Time::check_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Time");
      {
        require(time_step <= end_time,
                "Time",
                "Time step",
                to_string(time_step),
                "0 < k <= T = " + to_string(end_time));
        require(minimum_time_step <= time_step,
                "Time",
                "Minimum time step",
                to_string(minimum_time_step),
                "0 < Minimum time step <= Time step = " + to_string(time_step));
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
      }
      prm.leave_subsection();
    }



    void
    Checkpoint::add_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Checkpoint");
      {
        prm.add_parameter(
          "Checkpoint interval",
          checkpoint_interval,
          "Write a checkpoint (everything a resumed run needs) into "
          "<Output directory>/checkpoint every n-th step; 0: never (an "
          "integer >= 0). Only the last complete checkpoint is kept. A "
          "signal (SIGTERM, SIGINT, SIGUSR1) always writes one.",
          Patterns::Integer(0));
        prm.add_parameter(
          "Resume",
          resume,
          "Continue from the last complete checkpoint in the Output "
          "directory (same scene; any number of MPI ranks) instead of "
          "starting at t = 0. The time series and the .pvd record continue.",
          Patterns::Bool());
        prm.add_parameter(
          "Stop after step",
          stop_after_step,
          "End the run after this step as if it had been "
          "killed (for tests of Resume); 0: never. An integer in [0, "
          "number of time steps].",
          Patterns::Integer(0));
      }
      prm.leave_subsection();
    }



    void
    ActiveSetSolver::add_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Active set solver");
      {
        prm.add_parameter("Maximum iterations",
                          max_iterations,
                          "Limit of the primal-dual active set (semismooth "
                          "Newton) iterations per time step; reaching it stops "
                          "the run with a report. An integer in [1, 10000].",
                          Patterns::Integer(1, 10000));
        prm.add_parameter(
          "Tolerance",
          tolerance,
          "Relative accuracy of every linear solve for fixed pieces: the "
          "residual of CG/GMRES relative to the right-hand side (full space "
          "back end), the defect of the condensed equations relative to the "
          "normal displacements (condensed back end). The iteration stops "
          "when no contact node changes its piece and the last solve met "
          "this tolerance; in (0, 1e-2].",
          Interval(0, true, 1e-2, false));
        prm.add_parameter(
          "Predicted start",
          predicted_start,
          "Start each time step from the state extrapolated from the last two "
          "steps: the displacement u_{n-1} + (k_n/k_{n-1}) (u_{n-1} - u_{n-2}) "
          "as the first guess of the Krylov solves (full space back end) and "
          "of Newton's iteration (implicit update), and every contact node on "
          "the piece of its extrapolated (r, z), from step 2 on if the run "
          "starts at rest (u_0 = 0 solves the problem at the start time: no "
          "load, no prescribed displacement and no contact force there), else "
          "from step 3 on. The result is the same as "
          "from u_{n-1} and the previous pieces; only the iterations are "
          "fewer. Where the uniqueness check found that the step problem may "
          "have several solutions, the nodes keep the previous step's pieces "
          "(the branch the run is on). false: every step starts from u_{n-1} "
          "and the previous step's pieces.",
          Patterns::Bool());
      }
      prm.leave_subsection();
    }



    void
    LinearSolver::add_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Linear solver");
      {
        add_selection(
          prm,
          "Method",
          method,
          {{"auto", Method::automatic},
           {"condensed", Method::condensed},
           {"full space", Method::full_space},
           {"matrix free", Method::matrix_free}},
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
          "large 3D meshes and many ranks. matrix free: the full space "
          "back end without any matrix of the mesh, the operator applied "
          "cell by cell and preconditioned by geometric multigrid on the "
          "meshes of global coarsening (the least memory per unknown; "
          "hypercube cells and the explicit stress update). auto: condensed "
          "on one rank when "
          "the contact surface and the mesh are small enough (printed at "
          "start-up with the reason), full space otherwise.");
        add_selection(
          prm,
          "Preconditioner",
          preconditioner,
          {{"amg", Preconditioner::amg}, {"direct", Preconditioner::direct}},
          "Full space back end: amg (Trilinos ML smoothed aggregation with "
          "the rigid-body modes as near-null space; for large runs) or direct "
          "(the factorisation of the Direct solver; for small runs).");
        add_selection(
          prm,
          "Direct solver",
          direct_solver,
          {{"auto", DirectSolver::automatic},
           {"cholmod", DirectSolver::cholmod},
           {"umfpack", DirectSolver::umfpack},
           {"mumps", DirectSolver::mumps}},
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
    Output::add_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Output");
      {
        prm.add_parameter(
          "Output directory",
          directory,
          "Where the run writes parameters.prm, solution.pvd with its .vtu "
          "files, time_series.csv, the contact profiles and checkpoint/. "
          "Created if missing; must not be empty. The run lists every file it "
          "writes in the folder's manifest (.viscoplastic_contact.manifest) "
          "and holds a lock on the folder while it runs: a second run into a "
          "folder in use is refused, and so is a folder with files under the "
          "program's names that no manifest lists (they are never replaced). "
          "A '#' cannot be part of the value (it starts a comment).",
          Patterns::DirectoryName());
        prm.add_parameter(
          "Overwrite",
          overwrite,
          "A new run never mixes its files with those of an earlier run: "
          "false refuses an Output directory that holds another run's files; "
          "true removes exactly the files and folders the earlier run's "
          "manifest lists, once the new run's set-up has succeeded (nothing "
          "else, never the parameter file being run). A resumed run continues "
          "its own files.",
          Patterns::Bool());
        prm.add_parameter("Write vtu",
                          write_vtu,
                          "Write a .vtu file per output step and the .pvd "
                          "record.",
                          Patterns::Bool());
        prm.add_parameter("Output interval",
                          interval,
                          "Write a .vtu file every n-th time step (and always "
                          "the last one; with adaptive time steps every n-th "
                          "accepted step); an integer >= 1.",
                          Patterns::Integer(1));
        prm.add_parameter(
          "Profile times",
          profile_times,
          "Times at which the contact profile along Gamma_3 is written to "
          "contact_profile_NNNN.csv (the step closest to each time; adaptive "
          "time steps land on these times). Each in [0, End time]; of the "
          "default ones, those after End time are left out.",
          Patterns::List(Patterns::Double(0)));
        prm.add_parameter("Print timing summary",
                          print_timing_summary,
                          "Print the TimerOutput table at the end of the run, "
                          "and the wall time of the mesh and the peak memory "
                          "of the ranks (the sum, the largest rank, group "
                          "root and member) after each set-up phase and over "
                          "the run.",
                          Patterns::Bool());
        prm.add_parameter(
          "Measure cost ratios",
          measure_cost_ratios,
          "After the run, time one solve with the step operator, one "
          "operator application and one stress update, and print the cost "
          "of a step in these units (the Cost measurement block: ratio step "
          "/ solve and others). The measurement takes two elastic solves "
          "and a stress update (on small meshes four and three): on a large "
          "or graded mesh as long as several steps.",
          Patterns::Bool());
        prm.add_parameter("Verbose",
                          verbose,
                          "Print one line per time step.",
                          Patterns::Bool());
        prm.add_parameter(
          "Print iteration history",
          print_iteration_history,
          "After every step (and every solve of the Initial cycles), print "
          "its line (as Verbose does) and under it one line per active-set "
          "iteration: the nodes that changed their "
          "piece of the law, the nodes at the rigid limit, the relative "
          "residual of the linear solve and its Krylov iterations (with the "
          "implicit update: those of the step's last Newton iteration). "
          "Shows where a step's iterations go (doc/performance.md).",
          Patterns::Bool());
      }
      prm.leave_subsection();
    }

    void
    Output::check_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Output");
      {
        // An empty directory would put every result into the working
        // directory, next to whatever is there; "." says so explicitly.
        require(!directory.empty(),
                "Output",
                "Output directory",
                "",
                "a directory name (\".\" for the working directory)");
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
    MeshAdaptation::add_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Mesh adaptation");
      {
        prm.add_parameter(
          "Adaptive refinement",
          adaptive_refinement,
          "Refine and coarsen the mesh during the run (doc/adaptivity.md, "
          "\"Adaptive meshes\"): every Refinement interval steps, by the "
          "Kelly estimator of the displacement plus the cells at the contact "
          "front and at the boundary of the plastic zone; the displacement, "
          "the stress-point history and the contact state are carried over. "
          "Hypercube meshes (Cell type = hypercube) only.",
          Patterns::Bool());
        prm.add_parameter("Refinement interval",
                          refinement_interval,
                          "Adapt the mesh after every n-th step (an integer "
                          ">= 1).",
                          Patterns::Integer(1, 1000000000));
        prm.add_parameter("Refine fraction",
                          refine_fraction,
                          "The fraction of the cells with the largest "
                          "indicators that is refined, in [0, 1].",
                          fraction);
        prm.add_parameter("Coarsen fraction",
                          coarsen_fraction,
                          "The fraction of the cells with the smallest "
                          "indicators that is coarsened, in [0, 1]; Refine "
                          "fraction + Coarsen fraction <= 1.",
                          fraction);
        prm.add_parameter("Maximum cells",
                          maximum_cells,
                          "A bound on the number of active cells: fewer "
                          "cells are refined when it would be exceeded (an "
                          "integer >= 1).",
                          Patterns::Integer(1, 2000000000));
        prm.add_parameter("Maximum refinement level",
                          maximum_refinement_level,
                          "No cell is refined beyond this level of the "
                          "p4est forest (the generated box of m 2^j "
                          "Subdivisions has m^dim trees); an integer in "
                          "[0, 20].",
                          Patterns::Integer(0, 20));
        prm.add_parameter(
          "Initial cycles",
          initial_cycles_entry,
          "Nested iteration on the first time step (doc/adaptivity.md, "
          "\"Initial cycles\"): step 1 is solved on L coarser meshes first, "
          "each solution (displacement and contact pressure) carried over to "
          "the next mesh as the starting point of its active-set iteration; "
          "only the solve on the last mesh is recorded. auto: the program "
          "chooses L (printed in the header; none where the back end is the "
          "condensed one, which solves a cold step in milliseconds once K is "
          "factorised); 0: none. auto or an integer in [0, 20], with "
          "Initial refinement = global at most the number of times the mesh "
          "can be coarsened (Global refinements, and the factors of 2 of a "
          "generated box's Subdivisions); simplex meshes are built anew for "
          "each cycle.",
          AutoOrCount());
        prm.add_parameter(
          "Step cycles",
          step_cycles_entry,
          "Nested iteration in every time step (doc/algorithm.md, \"Step "
          "cycles\"; not in a first step that Initial cycles start): each "
          "step problem is first solved "
          "on L coarser meshes (the mesh coarsened uniformly 1, ..., L times, "
          "with the step's history load restricted to them), and where that "
          "solve moved the contact zone further than the step's predicted "
          "start (three iterations or more there), its contact zone starts "
          "the active-set iteration on the mesh of the run. It changes where "
          "the iteration starts, not the solution. "
          "auto: the program chooses L (printed in the header: 1 on "
          "hypercubes where the back end is expected to be an iterative one "
          "and the coarser mesh keeps 40000 dofs or more, else none); 0: "
          "none (each step starts from the last one, extrapolated with "
          "Predicted start). auto or an "
          "integer in [0, 20]; more than 0 needs a mesh that is the uniform "
          "refinement of one coarsened L times (Global refinements, and the "
          "factors of 2 of a generated box's Subdivisions: of a box of "
          "hypercubes, or at most 4 of a box of triangles cut by / or "
          "backslash), no Contact refinement levels, no Adaptive "
          "refinement, no friction, and the explicit update (or no "
          "plasticity).",
          AutoOrCount());
        add_selection(
          prm,
          "Initial refinement",
          initial_refinement,
          {{"global", InitialRefinement::global},
           {"adaptive", InitialRefinement::adaptive}},
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
    MeshAdaptation::check_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Mesh adaptation");
      {
        require(coarsen_fraction <= 1 - refine_fraction,
                "Mesh adaptation",
                "Coarsen fraction",
                prm.get("Coarsen fraction"),
                "a number in [0, 1 - Refine fraction]");
      }
      prm.leave_subsection();
    }



    void
    ConvergenceStudy::add_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Convergence study");
      {
        prm.add_parameter(
          "Enabled",
          study_enabled,
          "Instead of one run: run the scene for each (Subdivisions, Time "
          "steps) pair and for the reference resolution, and tabulate "
          "max_n (||u_n - u_n^ref||_V + ||sigma_n - sigma_n^ref||_Q) with "
          "observed orders in convergence.csv. The meshes must be nested "
          "generated boxes (every Subdivisions entry divides Reference "
          "subdivisions; not with Simplex pattern = five tetrahedra).",
          Patterns::Bool());
        prm.add_parameter("Subdivisions",
                          study_subdivisions,
                          "Mesh of each run: squares along each edge; "
                          "integers >= 1.",
                          Patterns::List(Patterns::Integer(1)));
        prm.add_parameter("Time steps",
                          study_time_steps,
                          "Time step of each run (one per Subdivisions entry); "
                          "each must be a positive multiple of the reference "
                          "time step.",
                          Patterns::List(Patterns::Double(0)));
        prm.add_parameter("Reference subdivisions",
                          reference_subdivisions,
                          "Mesh of the reference run; a multiple of every "
                          "Subdivisions entry, so that the meshes are nested.",
                          Patterns::Integer(1));
        prm.add_parameter("Reference time step",
                          reference_time_step,
                          "Time step of the reference run; > 0.",
                          Patterns::Double(0));
      }
      prm.leave_subsection();
    }

    void
    ConvergenceStudy::check_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Convergence study");
      {
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
    AllParameters::add_parameters(ParameterHandler &prm)
    {
      Geometry::add_parameters(prm);
      BoundaryParts::add_parameters(prm);
      Material::add_parameters(prm, "Material");
      for (unsigned int n = 0; n < further_materials.size(); ++n)
        further_materials[n].add_parameters(prm,
                                            "Material "
                                              + std::to_string(n + 2));
      Loads::add_parameters(prm);
      Contact::add_parameters(prm);
      for (unsigned int n = 0; n < further_contact_zones.size(); ++n)
        further_contact_zones[n].add_parameters(prm,
                                                "Contact zone "
                                                  + std::to_string(n + 2));
      Time::add_parameters(prm);
      ActiveSetSolver::add_parameters(prm);
      LinearSolver::add_parameters(prm);
      MeshAdaptation::add_parameters(prm);
      ConvergenceStudy::add_parameters(prm);
      Output::add_parameters(prm);
      Checkpoint::add_parameters(prm);
    }

    void
    AllParameters::check_parameters(ParameterHandler &prm)
    {
      Geometry::check_parameters(prm);
      BoundaryParts::check_parameters(prm, dimension);
      for (const auto &[name, material] : used_materials())
        material->check_parameters(prm, dimension, name);
      check_material_entries();
      // Subsection Contact is checked even when no boundary part uses it.
      Contact::check_parameters(prm, dimension);
      for (const ContactZone &zone : used_contact_zones())
        if (zone.contact != this)
          zone.contact->check_parameters(prm, dimension, zone.subsection);
      check_boundary_id_claims();
      Time::check_parameters(prm);
      MeshAdaptation::check_parameters(prm);
      ConvergenceStudy::check_parameters(prm);
      Output::check_parameters(prm);
      check_study_entries();
      check_mesh_adaptation_entries();
      check_method_entries();
      // The default Profile times are the benchmark's (1/64, 1/2, 1): a
      // shorter run keeps those within it. Times a parameter file sets must
      // lie in the run (check_schedule_size()).
      if (profile_times == Output().profile_times)
        profile_times.erase(std::remove_if(profile_times.begin(),
                                           profile_times.end(),
                                           [this](const double t) {
                                             return t > end_time;
                                           }),
                            profile_times.end());
      check_schedule_size(prm);
      check_unused_entries(prm);
    }

    std::vector<std::pair<std::string, const Material *>>
    AllParameters::used_materials() const
    {
      std::vector<std::pair<std::string, const Material *>> used{
        {"Material", this}};
      for (unsigned int n = 0; n < further_materials.size(); ++n)
        if (!further_materials[n].material_ids.empty())
          used.emplace_back("Material " + std::to_string(n + 2),
                            &further_materials[n]);
      return used;
    }

    std::vector<ContactZone>
    AllParameters::used_contact_zones() const
    {
      std::vector<ContactZone> used;
      if (!contact_ids.empty())
        used.push_back({1, "Contact", contact_ids, this});
      for (unsigned int n = 0; n < further_contact_zones.size(); ++n)
        if (!further_contact_zones[n].boundary_ids.empty())
          used.push_back({n + 2,
                          "Contact zone " + std::to_string(n + 2),
                          further_contact_zones[n].boundary_ids,
                          &further_contact_zones[n]});
      return used;
    }

    std::vector<types::boundary_id>
    AllParameters::all_contact_ids() const
    {
      std::vector<types::boundary_id> ids;
      for (const ContactZone &zone : used_contact_zones())
        ids.insert(ids.end(),
                   zone.boundary_ids.begin(),
                   zone.boundary_ids.end());
      return ids;
    }

    bool
    AllParameters::any_plasticity() const
    {
      for (const auto &[name, material] : used_materials())
        if (material->plasticity)
          return true;
      return false;
    }

    bool
    AllParameters::implicit_update() const
    {
      return any_plasticity() && stress_update == StressUpdate::implicit_euler;
    }

    bool
    AllParameters::explicit_history_update() const
    {
      return any_plasticity() && !implicit_update();
    }

    // Each material id belongs to one material; with several materials,
    // subsection Material names its ids too (its empty list means "every
    // cell" only when it is the only material). Plane strain is a 2D model,
    // with k < 1/2.
    void
    AllParameters::check_material_entries() const
    {
      if (plane_model == PlaneModel::plane_strain)
        {
          require(dimension == 2,
                  "",
                  "Plane model",
                  "plane strain",
                  "plane stress (the default) when Dimension = 3, where the "
                  "body needs no plane model");
          for (const auto &[name, material] : used_materials())
            {
              require(material->poisson_ratio < 0.5,
                      name,
                      "Poisson ratio",
                      to_string(material->poisson_ratio),
                      "-1 < k < 0.5 in plane strain");
            }
        }
      const auto materials = used_materials();
      // A rate-independent law has no rate for the explicit history update,
      // and its return mapping is the radial one of 3D (plane strain).
      for (const auto &[name, material] : materials)
        if (material->plasticity
            && material->law == MaterialLawType::hardening_plasticity)
          {
            require(stress_update == StressUpdate::implicit_euler,
                    "Time",
                    "Stress update",
                    "explicit",
                    "implicit when subsection <" + name
                      + "> has Law = hardening plasticity (a "
                        "rate-independent law has no rate for the explicit "
                        "history update)");
            require(dimension == 3 || plane_model == PlaneModel::plane_strain,
                    "",
                    "Plane model",
                    "plane stress",
                    "plane strain in 2D when subsection <" + name
                      + "> has Law = hardening plasticity");
          }
      if (materials.size() > 1)
        require(!material_ids.empty(),
                "Material",
                "Material ids",
                "",
                "the material ids of subsection Material when subsection <"
                  + materials[1].first
                  + "> names some too (empty means every cell only for a "
                    "single material)");
      std::map<types::material_id, std::string> owner;
      for (const auto &[name, material] : materials)
        for (const auto id : material->material_ids)
          {
            const auto [it, inserted] = owner.emplace(id, name);
            require(inserted,
                    name,
                    "Material ids",
                    id_list(material->material_ids),
                    "ids that no other material names (" + std::to_string(id)
                      + " is also in subsection <" + it->second + ">)");
          }
    }

    // The boundary ids of the further contact zones and of the surface loads
    // are named by no other entry of subsections Boundary, Contact zone N and
    // Loads (those of subsection Boundary are checked among themselves by
    // BoundaryParts::check_parameters()); each surface load has the right
    // number of expressions.
    void
    AllParameters::check_boundary_id_claims() const
    {
      std::map<types::boundary_id, std::string> owner;
      const auto claim = [&](const std::vector<types::boundary_id> &ids,
                             const std::string                     &name) {
        for (const auto id : ids)
          owner.emplace(id, name);
      };
      claim(clamped_ids, "<Clamped boundary ids> of subsection <Boundary>");
      claim(contact_ids, "<Contact boundary ids> of subsection <Boundary>");
      claim(loaded_ids, "<Loaded boundary ids> of subsection <Boundary>");
      claim(symmetry_ids, "<Symmetry boundary ids> of subsection <Boundary>");
      for (const auto &[number, entry] : used_prescribed_displacements())
        claim(entry->boundary_ids,
              "<Boundary ids> of subsection <Boundary/Prescribed "
              "displacement "
                + std::to_string(number) + ">");
      // The ids of an entry "Boundary ids" of the given subsection, each
      // refused if an earlier entry names it.
      const auto claim_exclusively
        = [&](const std::vector<types::boundary_id> &ids,
              const std::string                     &subsection,
              const std::string                     &accepted,
              const std::string                     &entry = "Boundary ids") {
            for (const auto id : ids)
              {
                const auto [it, inserted]
                  = owner.emplace(id,
                                  "<" + entry + "> of subsection <" + subsection
                                    + ">");
                require(inserted,
                        subsection,
                        entry,
                        id_list(ids),
                        accepted + " (" + std::to_string(id) + " is also in "
                          + it->second + ")");
              }
          };
      for (const ContactZone &zone : used_contact_zones())
        if (zone.subsection != "Contact")
          claim_exclusively(zone.boundary_ids,
                            zone.subsection,
                            "ids that no other entry names");
      // The opposite side of a pair is a free part of another body: no
      // other entry may name it, and it is not the zone itself.
      for (const ContactZone &zone : used_contact_zones())
        claim_exclusively(zone.contact->opposite_ids,
                          zone.subsection,
                          "ids of boundary parts that no other entry names "
                          "(not the zone's own)",
                          "Opposite boundary ids");
      // A load may act on a roller or plane of symmetry (its tangential
      // part does work) and on a part whose displacement is prescribed in
      // some components only (a top pressed down by a prescribed u_y and
      // pushed sideways by a traction): the constrained components take no
      // load, and the reactions count the load's part on them. Not on a
      // part with every component prescribed, where it would do nothing.
      for (const auto id : symmetry_ids)
        owner.erase(id);
      for (const auto &[number, entry] : used_prescribed_displacements())
        if (entry->components.size() < dimension)
          for (const auto id : entry->boundary_ids)
            owner.erase(id);
      for (const auto &[number, load] : used_surface_loads())
        {
          claim_exclusively(load->boundary_ids,
                            "Loads/Surface load " + std::to_string(number),
                            "ids that no other entry names, except Symmetry "
                            "boundary ids and parts of a Prescribed "
                            "displacement that leaves a component free");
          load->check_parameters(number, dimension);
        }
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
    AllParameters::check_method_entries() const
    {
      // The matrix-free operator evaluates tensor-product elements
      // (deal.II 9.4 has no multigrid hierarchy for simplex meshes), and it
      // is the elastic K: the implicit update's tangent changes in every
      // Newton iteration and is assembled.
      if (method != Method::matrix_free)
        return;
      require(cell_type == CellType::hypercube,
              "Linear solver",
              "Method",
              "matrix free",
              "auto, condensed or full space when Cell type = simplex or "
              "mixed (subsection <Geometry>): the matrix-free back end's "
              "multigrid needs hypercube cells");
      require(stress_update == StressUpdate::explicit_euler,
              "Linear solver",
              "Method",
              "matrix free",
              "auto, condensed or full space when Stress update = implicit "
              "(subsection <Time>): the implicit update's tangent is "
              "assembled in every Newton iteration");
    }



    std::optional<unsigned int>
    MeshAdaptation::initial_cycles() const
    {
      if (initial_cycles_entry == "auto")
        return std::nullopt;
      return Utilities::string_to_int(initial_cycles_entry);
    }



    std::optional<unsigned int>
    MeshAdaptation::step_cycles() const
    {
      if (step_cycles_entry == "auto")
        return std::nullopt;
      return Utilities::string_to_int(step_cycles_entry);
    }



    unsigned int
    AllParameters::uniform_coarsenings() const
    {
      unsigned int coarsenings = global_refinements;
      if (mesh_file.empty() && subdivisions > 0
          && (cell_type == CellType::simplex || material_id_function.empty()))
        for (unsigned int n = subdivisions; n % 2 == 0; n /= 2)
          ++coarsenings;
      return coarsenings;
    }



    AllParameters
    AllParameters::coarsened(const unsigned int levels) const
    {
      AllParameters      coarse = *this;
      const unsigned int from_refinements
        = std::min(levels, global_refinements);
      coarse.global_refinements -= from_refinements;
      coarse.subdivisions >>= (levels - from_refinements);
      return coarse;
    }



    unsigned int
    AllParameters::nested_coarsenings() const
    {
      if (cell_type == CellType::hypercube)
        return uniform_coarsenings();
      // As mesh.cc's coarser_equivalent_box() builds simplex boxes.
      const bool box_refines
        = mesh_file.empty() && material_id_function.empty() && dimension == 2
          && (simplex_pattern == SimplexPattern::slash
              || simplex_pattern == SimplexPattern::backslash);
      unsigned int coarsenings = global_refinements;
      if (box_refines)
        for (unsigned int n = subdivisions, b = 0;
             n > 0 && n % 2 == 0 && b < box_refinement_limit;
             n /= 2, ++b)
          ++coarsenings;
      return coarsenings;
    }



    AllParameters
    AllParameters::nested_coarsened() const
    {
      AllParameters coarse = coarsened(1);
      // Subdivisions halved: one refinement of the same coarse box less.
      if (global_refinements == 0 && box_refinement_limit > 0)
        --coarse.box_refinement_limit;
      return coarse;
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
                "false when Cell type = simplex or mixed or a convergence "
                "study runs "
                "(adaptive meshes need hypercube cells on p4est: deal.II "
                "9.4's fully distributed triangulation of triangles and "
                "tetrahedra cannot refine)");
      // With global refinement the mesh of the parameter file is the finest,
      // reached from one coarsened Initial cycles times (by refinement on
      // p4est, built anew for simplices), and the contact refinements would
      // not be nested that way; adaptive initial refinement refines p4est
      // meshes. (Initial cycles = auto takes none where they do not apply.)
      const unsigned int cycles = initial_cycles().value_or(0);
      if (cycles > 0)
        require(!study_enabled,
                "Mesh adaptation",
                "Initial cycles",
                initial_cycles_entry,
                "auto or 0 when a convergence study runs (it builds its own "
                "meshes)");
      // The coarser meshes of the cycles are built and transferred with
      // one element (mesh_adaptation.cc, step_cycles.cc).
      if (cycles > 0)
        require(cell_type != CellType::mixed,
                "Mesh adaptation",
                "Initial cycles",
                initial_cycles_entry,
                "auto or 0 when Cell type = mixed (the coarser meshes of "
                "the cycles carry one element)");
      if (cycles > 0 && initial_refinement == InitialRefinement::adaptive)
        require(cell_type == CellType::hypercube,
                "Mesh adaptation",
                "Initial cycles",
                initial_cycles_entry,
                "auto or 0 when Cell type = simplex and Initial refinement = "
                "adaptive (adaptive meshes need hypercube cells on p4est: "
                "deal.II 9.4's fully distributed triangulation of triangles "
                "and tetrahedra cannot refine); or Initial refinement = "
                "global");
      if (cycles > 0 && initial_refinement == InitialRefinement::global)
        {
          require(cycles <= uniform_coarsenings(),
                  "Mesh adaptation",
                  "Initial cycles",
                  initial_cycles_entry,
                  "at most " + std::to_string(uniform_coarsenings())
                    + " (Global refinements = "
                    + std::to_string(global_refinements)
                    + ", and the factors of 2 of Subdivisions = "
                    + std::to_string(subdivisions)
                    + " of a generated box; subsection <Geometry>) with "
                      "Initial refinement = global: the first cycle's mesh "
                      "is the parameter file's coarsened Initial cycles "
                      "times");
          require(contact_refinements == 0,
                  "Mesh adaptation",
                  "Initial cycles",
                  initial_cycles_entry,
                  "0 when Contact refinement levels > 0 (subsection "
                  "<Geometry>) with Initial refinement = global (uniform "
                  "refinement of a graded mesh does not give the graded mesh "
                  "of the parameter file); or Initial refinement = adaptive");
        }
      check_step_cycles();
    }



    // Step cycles solve every step on coarser meshes of the same p4est
    // forest, made from the parameter file with fewer refinements: the mesh
    // of the run must be theirs refined uniformly (no graded or adapted
    // mesh), and the coarse problem must be the step problem restricted to
    // them, which holds for the explicit update's fixed operator K with its
    // history load (the laws' histories and the friction state are injected
    // into them every step, StepCycles::inject_contact_state()).
    void
    AllParameters::check_step_cycles() const
    {
      const unsigned int cycles = step_cycles().value_or(0);
      if (cycles == 0)
        return;
      const auto refuse_unless
        = [&](const bool condition, const std::string &accepted) {
            require(condition,
                    "Mesh adaptation",
                    "Step cycles",
                    step_cycles_entry,
                    "auto or " + accepted);
          };
      refuse_unless(!study_enabled,
                    "0 when a convergence study runs (it builds its own "
                    "meshes)");
      refuse_unless(cell_type != CellType::mixed,
                    "0 when Cell type = mixed (the coarser meshes of the "
                    "cycles carry one element)");
      refuse_unless(!adaptive_refinement,
                    "0 when Adaptive refinement = true (an adapted mesh is "
                    "not a uniform refinement of the coarser meshes)");
      refuse_unless(initial_refinement == InitialRefinement::global
                      || initial_cycles().value_or(0) == 0,
                    "0 when Initial refinement = adaptive with Initial "
                    "cycles (the cycles adapt the mesh of the run, which is "
                    "then not a uniform refinement of the coarser meshes)");
      refuse_unless(contact_refinements == 0,
                    "0 when Contact refinement levels > 0 (subsection "
                    "<Geometry>: a graded mesh is not a uniform refinement "
                    "of the coarser meshes)");
      // What the coarser meshes are made of: the global refinements, and of
      // a generated box the factors of 2 of its subdivisions (at most
      // box_refinement_limit for triangles, none for tetrahedra).
      const unsigned int most        = nested_coarsenings();
      const unsigned int box_factors = most - global_refinements;
      std::string        made_of
        = "Global refinements = " + std::to_string(global_refinements);
      if (box_factors > 0)
        made_of += ", and " + std::to_string(box_factors)
                   + " factor(s) of 2 of Subdivisions = "
                   + std::to_string(subdivisions) + " of a generated box";
      else if (cell_type == CellType::simplex && mesh_file.empty())
        made_of += "; a generated box of simplices is coarsened only as "
                   "triangles cut by / or backslash";
      refuse_unless(cycles <= most,
                    (most == 0 ? std::string("0")
                               : "at most " + std::to_string(most))
                      + " (" + made_of
                      + "; subsection <Geometry>: the coarser meshes must "
                        "refine to the mesh of the run)");
      refuse_unless(stress_update == StressUpdate::explicit_euler
                      || !any_plasticity(),
                    "0 with Stress update = implicit euler and a "
                    "viscoplastic material (the coarser meshes solve the "
                    "explicit update's step problem)");
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
        return fixed_step_count(end_time, time_step);
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
      std::vector<ContactZone> zones = used_contact_zones();
      if (contact_ids.empty())
        zones.insert(zones.begin(), {1, "Contact", {}, this});
      for (const ContactZone &zone : zones)
        if (zone.contact->law_type == ContactLawType::nonmonotone)
          for (const std::string entry : {"Breakpoints", "Slopes", "Jumps"})
            require(prm.get({zone.subsection}, entry).empty(),
                    zone.subsection,
                    entry,
                    prm.get({zone.subsection}, entry),
                    "empty when Law = nonmonotone (it is used by Law = "
                    "piecewise linear only)");
      // Likewise the entries of the tangential laws the zone does not have.
      for (const ContactZone &zone : zones)
        {
          const auto law = zone.contact->tangential_law;
          if (law != TangentialLawType::tresca)
            require(is_zero_number(zone.contact->slip_bound),
                    zone.subsection,
                    "Slip bound",
                    prm.get({zone.subsection}, "Slip bound"),
                    "0 (the default) unless Tangential law = Tresca");
          if (law != TangentialLawType::coulomb)
            require(zone.contact->friction_coefficient == 0,
                    zone.subsection,
                    "Friction coefficient",
                    prm.get({zone.subsection}, "Friction coefficient"),
                    "0 (the default) unless Tangential law = Coulomb");
        }
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
