#ifndef viscoplastic_contact_loads_h
#define viscoplastic_contact_loads_h

#include <deal.II/base/function_parser.h>
#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>
#include <deal.II/base/types.h>

#include <deal.II/base/quadrature.h>

#include <deal.II/dofs/dof_handler.h>

#include <deal.II/fe/fe.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/fe/mapping.h>

#include <deal.II/hp/fe_collection.h>
#include <deal.II/hp/fe_values.h>
#include <deal.II/hp/mapping_collection.h>
#include <deal.II/hp/q_collection.h>

#include <deal.II/lac/vector.h>

#include "parameters.h"
#include "time_schedule.h"

#include <map>
#include <memory>
#include <string>
#include <vector>

namespace ViscoContact
{
  using namespace dealii;

  // A load expression is time dependent iff it mentions the variable t.
  bool
  mentions_time(const std::string &expression);

  // Every component is the literal number zero.
  bool
  is_zero_expression(const std::string &expression);

  // The constants every expression of a parameter file may use: the box's
  // edge lengths L1, L2 (, L3) and pi.
  std::map<std::string, double>
  expression_constants(const std::vector<double> &lengths);

  // Parse an expression (of subsection Loads, or of a prescribed
  // displacement) with as many components as function has, in x, y (, z),
  // t (unless time_dependent is false) and the expression_constants(); a
  // bad expression gives a message that names the subsection and the
  // entry.
  template <int dim>
  void
  initialize_load(FunctionParser<dim>       &function,
                  const std::string         &subsection,
                  const std::string         &entry,
                  const std::string         &expression,
                  const std::vector<double> &lengths,
                  const bool                 time_dependent = true);

  // @sect3{The loads of a scene}
  //
  // The body force f_0 and the loads on parts of the boundary (the Surface
  // traction of subsection Loads on the Loaded boundary ids first, then
  // each Surface load N on its own ids: a traction, or a pressure acting as
  // -p n along the outward normal n), built from the parameters once (a bad
  // expression stops the run here, naming the entry). Two facts save work
  // in every step: a body force that is the literal zero is not integrated
  // at all, and loads that do not mention t are assembled once.
  template <int dim>
  class Loads
  {
  public:
    explicit Loads(const Parameters::AllParameters &parameters);

    // The time at which the values are taken.
    void
    set_time(const double time);
    double
    get_time() const;
    bool
    depend_on_time() const;
    bool
    body_force_is_zero() const;

    // The surface load parts, and the part of a boundary id
    // (numbers::invalid_unsigned_int if the id carries no load).
    unsigned int
    n_surface_parts() const;
    unsigned int
    surface_part_of(const types::boundary_id id) const;

    // The body force at a point, and the traction of a surface part at a
    // point with outward normal: an empty string, or the message naming the
    // entry, its value, the point and the time if a value is not finite.
    std::string
    body_force(const Point<dim> &point, Vector<double> &value) const;
    std::string
    surface_load(const unsigned int    part,
                 const Point<dim>     &point,
                 const Tensor<1, dim> &normal,
                 Vector<double>       &value) const;

    // The loads of one cell at the time set, (f_0, v) + (f_2, v)_Gamma2 into
    // cell_rhs (the dofs of fe_values' element); false if the cell carries
    // no load. problem gets the first value that is not finite.
    bool
    cell_load(const typename DoFHandler<dim>::active_cell_iterator &cell,
              hp::FEValues<dim>                                    &fe_values,
              hp::FEFaceValues<dim> &fe_face_values,
              Vector<double>        &cell_rhs,
              std::string           &problem) const;
    // Every load at the points of the cells the assembly evaluates, at the
    // time levels of the schedule's grid: the message for the first value
    // that is not finite, or an empty string (not collective).
    std::string
    first_non_finite_value(
      const std::vector<typename DoFHandler<dim>::active_cell_iterator> &cells,
      const hp::MappingCollection<dim> &mapping,
      const hp::FECollection<dim>      &fe,
      const hp::QCollection<dim>       &load_quadrature,
      const hp::QCollection<dim - 1>   &face_quadrature,
      const TimeSchedule               &schedule);

  private:
    struct SurfacePart
    {
      std::unique_ptr<FunctionParser<dim>> function;
      bool                                 pressure;
      std::string                          subsection, entry, expression;
    };
    FunctionParser<dim>                        body;
    std::string                                body_expression;
    bool                                       body_is_zero;
    bool                                       time_dependent;
    std::vector<SurfacePart>                   surface_parts;
    std::map<types::boundary_id, unsigned int> part_of_id;
  };
} // namespace ViscoContact

#endif
