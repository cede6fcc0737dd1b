// Parsing the expressions of subsection Loads and of the prescribed
// displacements.
//
// The body force f_0, the surface traction f_2 and the prescribed
// displacements are muparser expressions in x, y (, z) and t. Two properties of
// an expression let the program skip work: a load that does not mention t is
// assembled once, and a body force that is zero is not integrated at all.

#include <deal.II/base/exceptions.h>
#include <deal.II/base/utilities.h>

#include <deal.II/fe/fe_values.h>

#include <deal.II/hp/fe_values.h>

#include <deal.II/lac/vector.h>

#include "scene/loads.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>
#include <regex>
#include <sstream>

namespace ViscoContact
{
  // FunctionParser's variable names, plus time.
  template <int dim>
  static std::string
  load_variables()
  {
    return FunctionParser<dim>::default_variable_names() + ",t";
  }

  // A load expression is time dependent iff it mentions the variable t: a
  // "t" that is not part of a longer name (so "tan" or "t2" does not count).
  bool
  mentions_time(const std::string &expression)
  {
    static const std::regex t_variable("(^|[^A-Za-z0-9_])t($|[^A-Za-z0-9_])");
    return std::regex_search(expression, t_variable);
  }

  // Every component is the literal number zero. Anything that is not a
  // number (an expression, even one that evaluates to zero) counts as
  // nonzero, which only costs an unnecessary integration.
  bool
  is_zero_expression(const std::string &expression)
  {
    for (const std::string &part :
         Utilities::split_string_list(expression, ';'))
      {
        try
          {
            if (Utilities::string_to_double(part) != 0.)
              return false;
          }
        catch (...)
          {
            return false;
          }
      }
    return true;
  }

  std::map<std::string, double>
  expression_constants(const std::vector<double> &lengths)
  {
    std::map<std::string, double> constants;
    for (unsigned int d = 0; d < lengths.size(); ++d)
      constants["L" + std::to_string(d + 1)] = lengths[d];
    constants["pi"] = numbers::PI;
    return constants;
  }

  // Parse an expression with as many components as the function has; turn
  // muparser's messages into one that names the parameter. The expression
  // may use the box's edge lengths L1, L2 (, L3) and pi as constants.
  template <int dim>
  void
  initialize_load(FunctionParser<dim>       &function,
                  const std::string         &subsection,
                  const std::string         &entry,
                  const std::string         &expression,
                  const std::vector<double> &lengths,
                  const bool                 time_dependent)
  {
    const std::string variables
      = time_dependent ? load_variables<dim>()
                       : FunctionParser<dim>::default_variable_names();
    // One expression per component, separated by ';'.
    const unsigned int n_components = function.n_components;
    const unsigned int n_parts
      = Utilities::split_string_list(expression, ';').size();
    AssertThrow(n_parts == n_components,
                ExcMessage("Invalid parameter <" + entry + "> in subsection <"
                           + subsection + ">: value <" + expression
                           + ">; accepted: "
                           + (n_components == 1
                                ? std::string("one expression, without ';'.")
                                : std::to_string(n_components)
                                    + " expressions separated by ';', one per "
                                      "component.")));
    std::string parser_message;
    // Whatever the parser throws, its message becomes part of ours.
    try
      {
        function.initialize(variables,
                            expression,
                            expression_constants(lengths),
                            time_dependent);
        // muparser reports unknown variables only when evaluating.
        Vector<double> values(n_components);
        function.vector_value(Point<dim>(), values);
      }
    catch (const ExceptionBase &exc)
      {
        std::ostringstream info;
        exc.print_info(info);
        parser_message = info.str();
      }
    catch (const std::exception &exc)
      {
        parser_message = exc.what();
      }
    AssertThrow(parser_message.empty(),
                ExcMessage("Invalid parameter <" + entry + "> in subsection <"
                           + subsection + ">: value <" + expression
                           + ">; accepted: muparser expressions in " + variables
                           + " and the constants pi, L1, L2 (, L3). "
                           + parser_message));
  }


  namespace
  {
    // The message of a load that is not finite at a point and a time: the
    // entry, its value, the point and the time, and what is accepted; empty
    // if every component is finite.
    template <int dim>
    std::string
    non_finite_load(const std::string    &subsection,
                    const std::string    &entry,
                    const std::string    &expression,
                    const Vector<double> &value,
                    const Point<dim>     &point,
                    const double          time)
    {
      bool finite = true;
      for (const double v : value)
        finite = finite && std::isfinite(v);
      if (finite)
        return "";
      const auto list = [](const auto &values, const unsigned int n) {
        std::ostringstream text;
        for (unsigned int d = 0; d < n; ++d)
          text << (d > 0 ? ", " : "") << values[d];
        return text.str();
      };
      return "Invalid parameter <" + entry + "> in subsection <" + subsection
             + ">: value <" + expression + "> is not finite at the point ("
             + list(point, dim)
             + ") at t = " + list(std::vector<double>{time}, 1) + " (it gives "
             + list(value, value.size())
             + "); accepted: expressions with a finite value at every load "
               "point of the mesh and every time of the run.";
    }
  } // namespace



  // @sect4{Loads::Loads}
  //
  // The parameters name each boundary id once, so a boundary id has at most
  // one part.
  template <int dim>
  Loads<dim>::Loads(const Parameters::AllParameters &parameters)
    : body(dim)
    , body_expression(parameters.body_force)
    , body_is_zero(is_zero_expression(parameters.body_force))
    , time_dependent(mentions_time(parameters.body_force))
  {
    initialize_load(body,
                    "Loads",
                    "Body force",
                    parameters.body_force,
                    parameters.lengths);
    const auto add_part = [&](const std::vector<types::boundary_id> &ids,
                              const bool                             pressure,
                              const std::string                     &subsection,
                              const std::string                     &entry,
                              const std::string &expression) {
      SurfacePart part{std::make_unique<FunctionParser<dim>>(pressure ? 1
                                                                      : dim),
                       pressure,
                       subsection,
                       entry,
                       expression};
      initialize_load(*part.function,
                      subsection,
                      entry,
                      expression,
                      parameters.lengths);
      time_dependent = time_dependent || mentions_time(expression);
      for (const auto id : ids)
        part_of_id[id] = surface_parts.size();
      surface_parts.push_back(std::move(part));
    };
    add_part(parameters.loaded_ids,
             false,
             "Loads",
             "Surface traction",
             parameters.surface_traction);
    for (const auto &[number, load] : parameters.used_surface_loads())
      add_part(load->boundary_ids,
               load->type == Parameters::SurfaceLoadType::pressure,
               "Loads/Surface load " + std::to_string(number),
               "Value",
               load->value);
  }



  template <int dim>
  void
  Loads<dim>::set_time(const double time)
  {
    body.set_time(time);
    for (SurfacePart &part : surface_parts)
      part.function->set_time(time);
  }



  template <int dim>
  double
  Loads<dim>::get_time() const
  {
    return body.get_time();
  }



  template <int dim>
  bool
  Loads<dim>::depend_on_time() const
  {
    return time_dependent;
  }



  template <int dim>
  bool
  Loads<dim>::body_force_is_zero() const
  {
    return body_is_zero;
  }



  template <int dim>
  unsigned int
  Loads<dim>::n_surface_parts() const
  {
    return surface_parts.size();
  }



  template <int dim>
  unsigned int
  Loads<dim>::surface_part_of(const types::boundary_id id) const
  {
    const auto part = part_of_id.find(id);
    return part == part_of_id.end() ? numbers::invalid_unsigned_int
                                    : part->second;
  }



  template <int dim>
  std::string
  Loads<dim>::body_force(const Point<dim> &point, Vector<double> &value) const
  {
    body.vector_value(point, value);
    return non_finite_load("Loads",
                           "Body force",
                           body_expression,
                           value,
                           point,
                           body.get_time());
  }



  // A pressure p acts along the inward normal: the traction is -p n with the
  // outward normal n of the face, on curved parts too.
  template <int dim>
  std::string
  Loads<dim>::surface_load(const unsigned int    part_number,
                           const Point<dim>     &point,
                           const Tensor<1, dim> &normal,
                           Vector<double>       &value) const
  {
    const SurfacePart &part = surface_parts[part_number];
    if (part.pressure)
      {
        const double p = part.function->value(point);
        for (unsigned int d = 0; d < dim; ++d)
          value(d) = -p * normal[d];
      }
    else
      part.function->vector_value(point, value);
    return non_finite_load(part.subsection,
                           part.entry,
                           part.expression,
                           value,
                           point,
                           part.function->get_time());
  }



  // @sect4{Loads::first_non_finite_value}
  //
  // A load that is not finite somewhere (1/0, sqrt(t - 0.5) at t = 0) would
  // only show as a displacement that is not finite in some step, after files
  // have been written and without naming the entry. So the loads are
  // evaluated here, before the output directory is touched: the surface
  // traction at the face quadrature points of the loaded boundary, the body
  // force at the load quadrature points of the cells, each at every time
  // level of the fixed schedule of Time step (at t = 0 only, if the loads do
  // not mention t). These are the points and times the assembly evaluates
  // (adaptive and cut steps add levels between them).
  //
  // The body force of a large time-dependent 3D run would make this as
  // expensive as assembling it in every step; beyond a budget of evaluations,
  // the cells are checked at a stride, and the assembly itself checks every
  // value it computes (cell_load()).
  template <int dim>
  std::string
  Loads<dim>::first_non_finite_value(
    const std::vector<typename DoFHandler<dim>::active_cell_iterator> &cells,
    const hp::MappingCollection<dim>                                  &mapping,
    const hp::FECollection<dim>                                       &fe,
    const hp::QCollection<dim>     &load_quadrature,
    const hp::QCollection<dim - 1> &face_quadrature,
    const TimeSchedule             &schedule)
  {
    // The levels of the schedule's grid t_m = m k, m < N, and t_N = T.
    const std::uint64_t n_levels
      = time_dependent ? schedule.n_grid_levels() : 1;
    const auto level
      = [&](const std::uint64_t m) { return schedule.grid_level(m); };
    // The points first, once: the geometry does not change with time. The
    // points of each surface load come with their normals.
    std::vector<Point<dim>> body_points;
    std::vector<std::vector<std::pair<Point<dim>, Tensor<1, dim>>>>
                          surface_points(n_surface_parts());
    hp::FEValues<dim>     hp_fe_values(mapping,
                                   fe,
                                   load_quadrature,
                                   update_quadrature_points);
    hp::FEFaceValues<dim> hp_face_values(mapping,
                                         fe,
                                         face_quadrature,
                                         update_quadrature_points
                                           | update_normal_vectors);
    for (const auto &cell : cells)
      {
        if (!body_is_zero)
          {
            hp_fe_values.reinit(cell);
            const FEValues<dim> &fe_values
              = hp_fe_values.get_present_fe_values();
            for (const unsigned int q : fe_values.quadrature_point_indices())
              body_points.push_back(fe_values.quadrature_point(q));
          }
        for (const unsigned int f : cell->face_indices())
          if (cell->face(f)->at_boundary())
            {
              const unsigned int part
                = surface_part_of(cell->face(f)->boundary_id());
              if (part == numbers::invalid_unsigned_int)
                continue;
              hp_face_values.reinit(cell, f);
              const FEFaceValues<dim> &fe_face_values
                = hp_face_values.get_present_fe_values();
              for (const unsigned int q :
                   fe_face_values.quadrature_point_indices())
                surface_points[part].emplace_back(
                  fe_face_values.quadrature_point(q),
                  fe_face_values.normal_vector(q));
            }
      }

    // At most about 2e7 evaluations per rank and load: every point if that
    // suffices, otherwise every stride-th point.
    const auto stride_of = [&](const std::size_t n_points) {
      const double evaluations = double(n_points) * n_levels;
      return std::max<std::size_t>(1, std::size_t(evaluations / 2e7));
    };
    std::string    problem;
    Vector<double> value(dim);
    for (unsigned int l = 0; l < n_surface_parts(); ++l)
      {
        const auto       &points = surface_points[l];
        const std::size_t stride = stride_of(points.size());
        for (std::uint64_t m = 0; m < n_levels && problem.empty(); ++m)
          {
            set_time(level(m));
            for (std::size_t i = 0; i < points.size() && problem.empty();
                 i += stride)
              problem
                = surface_load(l, points[i].first, points[i].second, value);
          }
      }
    const std::size_t stride = stride_of(body_points.size());
    for (std::uint64_t m = 0; m < n_levels && problem.empty(); ++m)
      {
        set_time(level(m));
        for (std::size_t i = 0; i < body_points.size() && problem.empty();
             i += stride)
          problem = body_force(body_points[i], value);
      }
    return problem;
  }



  // @sect4{Loads::cell_load}
  //
  // The body force at the load quadrature points and the surface load on
  // the faces of the cell that lie on a loaded part of the boundary (the
  // Surface traction on the Loaded boundary ids, each Surface load N on its
  // own ids); the component of shape function i picks the component of the
  // load it is tested with. The rest of the boundary that is neither
  // Dirichlet nor in contact is traction free.
  template <int dim>
  bool
  Loads<dim>::cell_load(
    const typename DoFHandler<dim>::active_cell_iterator &cell,
    hp::FEValues<dim>                                    &hp_fe_values,
    hp::FEFaceValues<dim>                                &hp_face_values,
    Vector<double>                                       &cell_rhs,
    std::string                                          &problem) const
  {
    const FiniteElement<dim> &fe            = cell->get_fe();
    const unsigned int        dofs_per_cell = fe.n_dofs_per_cell();
    Vector<double>            load_value(dim);
    cell_rhs.reinit(dofs_per_cell);
    bool has_loads = false;
    if (!body_is_zero)
      {
        hp_fe_values.reinit(cell);
        const FEValues<dim> &fe_values = hp_fe_values.get_present_fe_values();
        for (const unsigned int q : fe_values.quadrature_point_indices())
          {
            const std::string message
              = body_force(fe_values.quadrature_point(q), load_value);
            if (problem.empty())
              problem = message;
            for (unsigned int i = 0; i < dofs_per_cell; ++i)
              cell_rhs(i) += load_value(fe.system_to_component_index(i).first)
                             * fe_values.shape_value(i, q) * fe_values.JxW(q);
          }
        has_loads = true;
      }
    for (const unsigned int f : cell->face_indices())
      if (cell->face(f)->at_boundary())
        {
          const unsigned int part
            = surface_part_of(cell->face(f)->boundary_id());
          if (part == numbers::invalid_unsigned_int)
            continue;
          hp_face_values.reinit(cell, f);
          const FEFaceValues<dim> &fe_face_values
            = hp_face_values.get_present_fe_values();
          for (const unsigned int q : fe_face_values.quadrature_point_indices())
            {
              const std::string message
                = surface_load(part,
                               fe_face_values.quadrature_point(q),
                               fe_face_values.normal_vector(q),
                               load_value);
              if (problem.empty())
                problem = message;
              for (unsigned int i = 0; i < dofs_per_cell; ++i)
                cell_rhs(i) += load_value(fe.system_to_component_index(i).first)
                               * fe_face_values.shape_value(i, q)
                               * fe_face_values.JxW(q);
            }
          has_loads = true;
        }
    return has_loads;
  }



  template class Loads<2>;
  template class Loads<3>;

  template void
  initialize_load(FunctionParser<2> &,
                  const std::string &,
                  const std::string &,
                  const std::string &,
                  const std::vector<double> &,
                  const bool);
  template void
  initialize_load(FunctionParser<3> &,
                  const std::string &,
                  const std::string &,
                  const std::string &,
                  const std::vector<double> &,
                  const bool);
} // namespace ViscoContact
