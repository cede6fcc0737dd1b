#ifndef viscoplastic_contact_dirichlet_parts_h
#define viscoplastic_contact_dirichlet_parts_h

#include <deal.II/base/function_parser.h>
#include <deal.II/base/point.h>

#include "constraints.h"
#include "parameters.h"

#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace ViscoContact
{
  using namespace dealii;

  // @sect3{The Dirichlet parts of a scene}
  //
  // The parts of the boundary whose displacement is prescribed, built from
  // the parameters once, in the order their constraints are made: the
  // Clamped boundary ids (all components, u = 0) first, then every
  // Prescribed displacement N with its components and its function of x
  // and t (a bad expression stops the run here, naming the entry). Their
  // names ("clamped", "prescribed_N") head the reaction columns of the
  // time series.
  template <int dim>
  class DirichletParts
  {
  public:
    explicit DirichletParts(const Parameters::AllParameters &parameters);

    unsigned int
    size() const;
    // The boundary ids and components of every part, for the constraints.
    const std::vector<DirichletPart> &
    parts() const;
    const std::string &
    name(const unsigned int part) const;
    const std::vector<unsigned int> &
    components(const unsigned int part) const;

    // Whether a part prescribes a function (clamped parts do not), whether
    // any part prescribes a value that is not the literal zero (else the
    // prescribed displacement needs no lifting), and whether any value
    // depends on t.
    bool
    prescribes_function(const unsigned int part) const;
    bool
    has_values() const;
    bool
    depend_on_time() const;

    // Component c of the displacement part prescribes at a point and a time,
    // and the message naming the entry if it is not finite (else empty).
    std::pair<double, std::string>
    value(const unsigned int part,
          const unsigned int component,
          const Point<dim>  &point,
          const double       time) const;

  private:
    std::vector<DirichletPart>                        boundary_parts;
    std::vector<std::string>                          names;
    std::vector<std::vector<unsigned int>>            part_components;
    std::vector<std::unique_ptr<FunctionParser<dim>>> functions;
    bool                                              nonzero_values = false;
    bool                                              time_dependent = false;
  };
} // namespace ViscoContact

#endif
