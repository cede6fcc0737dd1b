// Parsing the expressions of subsection Loads and of the prescribed
// displacements.
//
// The body force f_0, the surface traction f_2 and the prescribed
// displacements are muparser expressions in x, y (, z) and t. Two properties of
// an expression let the program skip work: a load that does not mention t is
// assembled once, and a body force that is zero is not integrated at all.

#include <deal.II/base/exceptions.h>
#include <deal.II/base/utilities.h>

#include <deal.II/lac/vector.h>

#include "loads.h"

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

  // Parse an expression with as many components as the function has; turn
  // muparser's messages into one that names the parameter. The expression
  // may use the box's edge lengths L1, L2 (, L3) and pi as constants.
  template <int dim>
  void
  initialize_load(FunctionParser<dim>       &function,
                  const std::string         &subsection,
                  const std::string         &entry,
                  const std::string         &expression,
                  const std::vector<double> &lengths)
  {
    // One expression per component, separated by ';'.
    const unsigned int n_components = function.n_components;
    const unsigned int n_parts
      = Utilities::split_string_list(expression, ';').size();
    AssertThrow(n_parts == n_components,
                ExcMessage(
                  "Invalid parameter <" + entry + "> in subsection <"
                  + subsection + ">: value <" + expression
                  + ">; accepted: " + std::to_string(n_components)
                  + (n_components == 1 ? " expression" : " expressions")
                  + " separated by ';' (one per displacement "
                    "component)."));
    // The constants every load expression may use.
    std::map<std::string, double> constants;
    for (unsigned int d = 0; d < lengths.size(); ++d)
      constants["L" + std::to_string(d + 1)] = lengths[d];
    constants["pi"] = numbers::PI;
    std::string parser_message;
    // Whatever the parser throws, its message becomes part of ours.
    try
      {
        function.initialize(load_variables<dim>(),
                            expression,
                            constants,
                            /*time_dependent=*/true);
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
                           + ">; accepted: muparser expressions in "
                           + load_variables<dim>()
                           + " and the constants pi, L1, L2 (, L3). "
                           + parser_message));
  }


  template void
  initialize_load(FunctionParser<2> &,
                  const std::string &,
                  const std::string &,
                  const std::string &,
                  const std::vector<double> &);
  template void
  initialize_load(FunctionParser<3> &,
                  const std::string &,
                  const std::string &,
                  const std::string &,
                  const std::vector<double> &);
} // namespace ViscoContact
