#ifndef viscoplastic_contact_loads_h
#define viscoplastic_contact_loads_h

#include <deal.II/base/function_parser.h>

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

  // Parse an expression (of subsection Loads, or of a prescribed
  // displacement) with as many components as function has, in x, y (, z),
  // t and the constants L1, L2 (, L3); a bad expression gives a message
  // that names the subsection and the entry.
  template <int dim>
  void
  initialize_load(FunctionParser<dim>       &function,
                  const std::string         &subsection,
                  const std::string         &entry,
                  const std::string         &expression,
                  const std::vector<double> &lengths);
} // namespace ViscoContact

#endif
