#ifndef viscoplastic_contact_contact_zones_h
#define viscoplastic_contact_contact_zones_h

#include <deal.II/base/function.h>
#include <deal.II/base/function_parser.h>

#include <deal.II/dofs/dof_handler.h>

#include "bonding_field.h"
#include "contact_set.h"
#include "normal_memory.h"
#include "parameters.h"

#include <memory>
#include <vector>

namespace ViscoContact
{
  using namespace dealii;

  // @sect3{The contact zones of a scene}
  //
  // The contact zones (subsection Contact and the numbered Contact zone N
  // that name boundary parts), built from the parameters once: each with
  // its normal law (ContactLaw::from_parameters()), its direction (a unit
  // vector from the body into the obstacle, or the boundary's normals),
  // its tangential law (TangentialLaw::from_parameters()), its memory
  // kernel (NormalMemory::Kernel::from_parameters()), the obstacle's gap
  // s(x, t) along the direction and its rigid motion (a translation o(t),
  // a rotation about a moving center), and
  // Tresca's slip bound as functions of x (and t) where they are given. A zone
  // whose law does nothing (no layer, no rigid limit) has no contact nodes and
  // is left out. A bad expression stops the run here, naming the zone's
  // subsection and the entry.
  template <int dim>
  class ContactZones
  {
  public:
    explicit ContactZones(const Parameters::AllParameters &parameters);

    bool
    empty() const;
    const std::vector<ContactZoneDescription<dim>> &
    descriptions() const;
    // The zone numbers (1 for subsection Contact, N for Contact zone N), of
    // all zones and of those with friction.
    std::vector<unsigned int>
    numbers() const;
    std::vector<unsigned int>
    frictional_numbers() const;
    // The numbers of the zones that meet another body (contact pairs).
    std::vector<unsigned int>
    pair_numbers() const;

    // The memory kernel of each zone (normal_memory.h; no terms: none).
    const std::vector<NormalMemory::Kernel> &
    memory_kernels() const;
    // The adhesion of each zone (bonding_field.h; stiffness 0: none), and
    // the bonding at t = 0 of the contact nodes (Initial bonding; 1 in the
    // zones without adhesion; collective: a value outside [0, 1] stops all
    // ranks, naming the entry).
    const std::vector<BondingField::Law> &
    bonding_laws() const;
    std::vector<double>
    initial_bonding(const ContactSet<dim> &contact_set,
                    const MPI_Comm         communicator) const;
    // The wear coefficient of each zone (archard_wear.h; 0: none).
    const std::vector<double> &
    wear_coefficients() const;
    // Whether each zone's law has a cohesive interface (cohesive_damage.h).
    std::vector<bool>
    cohesive_zones() const;

    // The gap function of each zone (nullptr where it is zero: the nodes
    // keep s = 0), and Tresca's slip bound of each zone (nullptr in the
    // others).
    std::vector<Function<dim> *>
    gaps() const;
    std::vector<const Function<dim> *>
    slip_bounds() const;
    // Whether some zone's obstacle moves (Obstacle motion, Obstacle
    // rotation), and each zone's displacement of the obstacle's points
    // from the time start to the time end (an affine map of the place; zero
    // where it does not move). A moving zone's gap function is that of the
    // moved obstacle, s(x - o(t), t), or with a rotation R(t) about the
    // point c, s(c + R(t)^T (x - c - o(t)), t).
    bool
    has_obstacle_motion() const;
    std::vector<ObstacleStep<dim>>
    obstacle_steps(const double start, const double end) const;
    // Whether some zone has a gap, and whether a gap depends on t.
    bool
    has_gap() const;
    bool
    gap_depends_on_time() const;

    // The share of the contact vertices that are expected to touch their
    // obstacle at one time, the most over the given times: in a zone whose
    // obstacle drives the contact (it moves, or its gap depends on t), the
    // vertices of the undeformed body that the obstacle overlaps (s <= 0);
    // every vertex of the other zones (a body pushed by its loads, a
    // contact pair, a bonded zone). An estimate for the cost model
    // (SceneSize::contact_fraction): on an elastic body a Hertzian zone is
    // about half the overlap. Collective.
    double
    expected_contact_fraction(const DoFHandler<dim>     &dof_handler,
                              const std::vector<double> &times,
                              const MPI_Comm             communicator) const;

  private:
    std::vector<ContactZoneDescription<dim>>          zones;
    std::vector<NormalMemory::Kernel>                 kernels;
    std::vector<BondingField::Law>                    adhesion;
    std::vector<double>                               wear;
    std::vector<std::unique_ptr<FunctionParser<dim>>> initial_bonding_functions;
    std::vector<std::unique_ptr<FunctionParser<dim>>> gap_functions;
    std::vector<std::unique_ptr<FunctionParser<dim>>> slip_bound_functions;
    std::vector<std::unique_ptr<FunctionParser<dim>>> motion_functions;
    std::vector<std::unique_ptr<FunctionParser<dim>>> rotation_functions;
    std::vector<Point<dim>>                           rotation_centers;
    std::vector<std::unique_ptr<Function<dim>>>       moved_gap_functions;
    // Per zone: whether its obstacle drives the contact
    // (expected_contact_fraction()).
    std::vector<bool> obstacle_driven;
    bool              any_gap            = false;
    bool              any_motion         = false;
    bool              time_dependent_gap = false;
  };
} // namespace ViscoContact

#endif
