// The contact zones of a scene (contact_zones.h), built from the
// parameters.

#include <deal.II/base/symmetric_tensor.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/tensor.h>

#include "scene/contact_zones.h"
#include "scene/loads.h"
#include "robustness/file_output.h"

#include <algorithm>
#include <set>
#include <sstream>

namespace ViscoContact
{
  namespace
  {
    // The rotation R(t) of an obstacle: the angle theta (2D) or the
    // rotation vector theta n (3D, Rodrigues' formula) at the function's
    // time; the identity without a rotation.
    template <int dim>
    Tensor<2, dim>
    rotation_matrix(const Function<dim> *rotation)
    {
      Tensor<2, dim> R = unit_symmetric_tensor<dim>();
      if (rotation == nullptr)
        return R;
      if constexpr (dim == 2)
        {
          const double theta = rotation->value(Point<dim>(), 0);
          R[0][0] = R[1][1] = std::cos(theta);
          R[1][0]           = std::sin(theta);
          R[0][1]           = -std::sin(theta);
        }
      else
        {
          Tensor<1, dim> axis;
          for (unsigned int c = 0; c < dim; ++c)
            axis[c] = rotation->value(Point<dim>(), c);
          const double theta = axis.norm();
          if (theta > 0)
            {
              axis /= theta;
              Tensor<2, dim> K; // the cross product with the axis
              K[0][1] = -axis[2];
              K[0][2] = axis[1];
              K[1][0] = axis[2];
              K[1][2] = -axis[0];
              K[2][0] = -axis[1];
              K[2][1] = axis[0];
              R += std::sin(theta) * K + (1 - std::cos(theta)) * (K * K);
            }
        }
      return R;
    }



    // Where the obstacle is at a time: a point X of it at t = 0 is at
    // c + o + R (X - c).
    template <int dim>
    struct Placement
    {
      Tensor<2, dim> rotation;
      Tensor<1, dim> translation;
      Point<dim>     center;

      Placement(Function<dim>    *motion,
                Function<dim>    *rotation_function,
                const Point<dim> &center,
                const double      time)
        : center(center)
      {
        for (Function<dim> *f : {motion, rotation_function})
          if (f)
            f->set_time(time);
        rotation = rotation_matrix<dim>(rotation_function);
        if (motion)
          for (unsigned int c = 0; c < dim; ++c)
            translation[c] = motion->value(Point<dim>(), c);
      }

      Point<dim>
      place(const Point<dim> &X) const
      {
        return center + translation + rotation * (X - center);
      }
      // The point X of the obstacle at t = 0 that is at x now.
      Point<dim>
      origin_of(const Point<dim> &x) const
      {
        return center + transpose(rotation) * (x - center - translation);
      }
    };



    // The gap of an obstacle that moves rigidly: s(X(x, t), t) with X the
    // obstacle's point at t = 0 that is at x at t.
    template <int dim>
    class MovedObstacleGap : public Function<dim>
    {
    public:
      MovedObstacleGap(Function<dim>    &gap,
                       Function<dim>    *motion,
                       Function<dim>    *rotation,
                       const Point<dim> &center)
        : Function<dim>(1)
        , gap(gap)
        , motion(motion)
        , rotation(rotation)
        , placement(motion, rotation, center, 0.)
      {
        set_time(0.);
      }

      // The placement is evaluated once per time, not per node.
      void
      set_time(const double time) override
      {
        Function<dim>::set_time(time);
        gap.set_time(time);
        placement = Placement<dim>(motion, rotation, placement.center, time);
      }

      double
      value(const Point<dim> &p, const unsigned int = 0) const override
      {
        return gap.value(placement.origin_of(p));
      }

    private:
      Function<dim> &gap;
      Function<dim> *motion;
      Function<dim> *rotation;
      Placement<dim> placement;
    };
  } // namespace



  template <int dim>
  ContactZones<dim>::ContactZones(const Parameters::AllParameters &parameters)
  {
    for (const Parameters::ContactZone &zone : parameters.used_contact_zones())
      {
        const Parameters::Contact  &entries = *zone.contact;
        ContactZoneDescription<dim> description{
          zone.number,
          zone.subsection,
          ContactLaw::from_parameters(entries),
          zone.boundary_ids,
          {},
          TangentialLaw::from_parameters(entries),
          entries.opposite_ids,
          entries.search_distance == "auto"
            ? 0.
            : Utilities::string_to_double(entries.search_distance),
          entries.geometric_gap == "measured"};
        if (description.law.is_void())
          continue;
        if (entries.gap_direction != "normal")
          {
            const std::vector<double> d = entries.direction_vector();
            Tensor<1, dim>            direction;
            for (unsigned int c = 0; c < dim; ++c)
              direction[c] = d[c];
            description.direction = direction;
          }
        std::unique_ptr<FunctionParser<dim>> gap;
        if (!is_zero_expression(entries.initial_gap))
          {
            gap = std::make_unique<FunctionParser<dim>>(1);
            initialize_load(*gap,
                            zone.subsection,
                            "Initial gap",
                            entries.initial_gap,
                            parameters.lengths);
            any_gap = true;
            time_dependent_gap
              = time_dependent_gap || mentions_time(entries.initial_gap);
          }
        std::unique_ptr<FunctionParser<dim>> slip_bound;
        if (description.friction->uses_node_bounds())
          {
            slip_bound = std::make_unique<FunctionParser<dim>>(1);
            initialize_load(*slip_bound,
                            zone.subsection,
                            "Slip bound",
                            entries.slip_bound,
                            parameters.lengths);
          }
        // A rigid motion of the obstacle: a translation o(t), a rotation
        // about c + o(t).
        std::unique_ptr<FunctionParser<dim>> motion, rotation;
        std::unique_ptr<Function<dim>>       moved_gap;
        Point<dim>                           center;
        if (!is_zero_expression(entries.obstacle_motion))
          {
            motion = std::make_unique<FunctionParser<dim>>(dim);
            initialize_load(*motion,
                            zone.subsection,
                            "Obstacle motion",
                            entries.obstacle_motion,
                            parameters.lengths);
          }
        if (!is_zero_expression(entries.obstacle_rotation))
          {
            rotation = std::make_unique<FunctionParser<dim>>(dim == 2 ? 1 : 3);
            initialize_load(*rotation,
                            zone.subsection,
                            "Obstacle rotation",
                            entries.obstacle_rotation,
                            parameters.lengths);
            FunctionParser<dim> center_function(dim);
            initialize_load(center_function,
                            zone.subsection,
                            "Rotation center",
                            entries.rotation_center,
                            parameters.lengths);
            for (unsigned int c = 0; c < dim; ++c)
              center[c] = center_function.value(Point<dim>(), c);
          }
        if (motion || rotation)
          {
            any_motion = true;
            if (gap)
              {
                moved_gap
                  = std::make_unique<MovedObstacleGap<dim>>(*gap,
                                                            motion.get(),
                                                            rotation.get(),
                                                            center);
                time_dependent_gap = true;
              }
          }
        std::unique_ptr<FunctionParser<dim>> bonding;
        if (entries.adhesion_stiffness > 0)
          {
            bonding = std::make_unique<FunctionParser<dim>>(1);
            initialize_load(*bonding,
                            zone.subsection,
                            "Initial bonding",
                            entries.initial_bonding,
                            parameters.lengths);
          }
        obstacle_driven.push_back(
          (moved_gap || mentions_time(entries.initial_gap))
          && description.opposite_ids.empty() && entries.adhesion_stiffness == 0
          && entries.cohesive_strength == 0);
        zones.push_back(std::move(description));
        kernels.push_back(NormalMemory::Kernel::from_parameters(entries));
        adhesion.push_back(BondingField::Law::from_parameters(entries));
        wear.push_back(entries.wear_coefficient);
        initial_bonding_functions.push_back(std::move(bonding));
        gap_functions.push_back(std::move(gap));
        moved_gap_functions.push_back(std::move(moved_gap));
        motion_functions.push_back(std::move(motion));
        rotation_functions.push_back(std::move(rotation));
        rotation_centers.push_back(center);
        slip_bound_functions.push_back(std::move(slip_bound));
      }
  }



  template <int dim>
  bool
  ContactZones<dim>::empty() const
  {
    return zones.empty();
  }



  template <int dim>
  const std::vector<ContactZoneDescription<dim>> &
  ContactZones<dim>::descriptions() const
  {
    return zones;
  }



  template <int dim>
  std::vector<unsigned int>
  ContactZones<dim>::numbers() const
  {
    std::vector<unsigned int> result;
    for (const auto &zone : zones)
      result.push_back(zone.number);
    return result;
  }



  template <int dim>
  std::vector<unsigned int>
  ContactZones<dim>::frictional_numbers() const
  {
    std::vector<unsigned int> result;
    for (const auto &zone : zones)
      if (zone.friction->has_friction())
        result.push_back(zone.number);
    return result;
  }



  template <int dim>
  std::vector<unsigned int>
  ContactZones<dim>::pair_numbers() const
  {
    std::vector<unsigned int> result;
    for (const auto &zone : zones)
      if (!zone.opposite_ids.empty())
        result.push_back(zone.number);
    return result;
  }



  template <int dim>
  const std::vector<NormalMemory::Kernel> &
  ContactZones<dim>::memory_kernels() const
  {
    return kernels;
  }



  template <int dim>
  const std::vector<BondingField::Law> &
  ContactZones<dim>::bonding_laws() const
  {
    return adhesion;
  }



  // The bonding at t = 0 of every contact node (1 outside the zones with
  // adhesion), collective: a value outside [0, 1] stops all ranks, naming
  // the zone's entry and the node.
  template <int dim>
  std::vector<double>
  ContactZones<dim>::initial_bonding(const ContactSet<dim> &contact_set,
                                     const MPI_Comm         communicator) const
  {
    std::vector<double> bonding(contact_set.size(), 1.);
    std::string         problem;
    for (unsigned int i = 0; i < contact_set.size(); ++i)
      if (const auto &beta_0 = initial_bonding_functions[contact_set.zone(i)])
        {
          bonding[i] = beta_0->value(contact_set.node(i).location);
          if (!(bonding[i] >= 0 && bonding[i] <= 1) && problem.empty())
            {
              std::ostringstream message;
              message << "Invalid parameter <Initial bonding> in subsection <"
                      << zones[contact_set.zone(i)].subsection
                      << ">: the bonding is " << bonding[i] << " at (";
              for (unsigned int d = 0; d < dim; ++d)
                message << (d > 0 ? ", " : "")
                        << contact_set.node(i).location[d];
              message << "); accepted are values in [0, 1].";
              problem = message.str();
            }
        }
    FileOutput::agree_on_problem(problem, communicator);
    return bonding;
  }



  template <int dim>
  const std::vector<double> &
  ContactZones<dim>::wear_coefficients() const
  {
    return wear;
  }



  template <int dim>
  std::vector<bool>
  ContactZones<dim>::cohesive_zones() const
  {
    std::vector<bool> cohesive;
    for (const ContactZoneDescription<dim> &zone : zones)
      cohesive.push_back(zone.law.has_cohesion());
    return cohesive;
  }



  template <int dim>
  std::vector<Function<dim> *>
  ContactZones<dim>::gaps() const
  {
    std::vector<Function<dim> *> result;
    for (unsigned int zone = 0; zone < gap_functions.size(); ++zone)
      if (moved_gap_functions[zone])
        result.push_back(moved_gap_functions[zone].get());
      else
        result.push_back(gap_functions[zone].get());
    return result;
  }



  template <int dim>
  bool
  ContactZones<dim>::has_obstacle_motion() const
  {
    return any_motion;
  }



  // The point at x at the start goes to place_end(origin_start(x)): the
  // step is that less x, affine in x.
  template <int dim>
  std::vector<ObstacleStep<dim>>
  ContactZones<dim>::obstacle_steps(const double start, const double end) const
  {
    std::vector<ObstacleStep<dim>> steps(zones.size());
    for (unsigned int zone = 0; zone < zones.size(); ++zone)
      {
        Function<dim> *motion   = motion_functions[zone].get();
        Function<dim> *rotation = rotation_functions[zone].get();
        if (!motion && !rotation)
          continue;
        const Point<dim>    &center = rotation_centers[zone];
        const Placement<dim> before(motion, rotation, center, start);
        const Placement<dim> after(motion, rotation, center, end);
        const Tensor<2, dim> turn = after.rotation * transpose(before.rotation);
        steps[zone].linear        = turn - unit_symmetric_tensor<dim>();
        steps[zone].shift         = after.place(before.origin_of(Point<dim>()));
      }
    return steps;
  }



  template <int dim>
  std::vector<const Function<dim> *>
  ContactZones<dim>::slip_bounds() const
  {
    std::vector<const Function<dim> *> result;
    for (const auto &bound : slip_bound_functions)
      result.push_back(bound.get());
    return result;
  }



  template <int dim>
  bool
  ContactZones<dim>::has_gap() const
  {
    return any_gap;
  }



  template <int dim>
  bool
  ContactZones<dim>::gap_depends_on_time() const
  {
    return time_dependent_gap;
  }



  // Each vertex of a contact face is counted once, by the rank that owns
  // its first dof; ghost cells are looked at too, since that rank need not
  // own a contact face through the vertex. The gap functions are the
  // contact set's: their time is put back afterwards.
  template <int dim>
  double
  ContactZones<dim>::expected_contact_fraction(
    const DoFHandler<dim>     &dof_handler,
    const std::vector<double> &times,
    const MPI_Comm             communicator) const
  {
    const std::vector<Function<dim> *> gap                 = gaps();
    bool                               any_moving_obstacle = false;
    for (unsigned int zone = 0; zone < zones.size(); ++zone)
      any_moving_obstacle |= obstacle_driven[zone] && gap[zone] != nullptr;
    if (!any_moving_obstacle || times.empty())
      return 1;

    const auto zone_of = [&](const types::boundary_id id) -> int {
      for (unsigned int zone = 0; zone < zones.size(); ++zone)
        for (const types::boundary_id zone_id : zones[zone].boundary_ids)
          if (zone_id == id)
            return zone;
      return -1;
    };
    // The owned contact vertices of each zone.
    const IndexSet                   &owned = dof_handler.locally_owned_dofs();
    std::set<types::global_dof_index> seen;
    std::vector<std::vector<Point<dim>>> vertices(zones.size());
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (!cell->is_artificial())
        for (const auto &face : cell->face_iterators())
          if (face->at_boundary())
            {
              const int zone = zone_of(face->boundary_id());
              if (zone < 0)
                continue;
              for (const unsigned int v : face->vertex_indices())
                {
                  const types::global_dof_index dof
                    = face->vertex_dof_index(v, 0, cell->active_fe_index());
                  if (owned.is_element(dof) && seen.insert(dof).second)
                    vertices[zone].push_back(face->vertex(v));
                }
            }

    // counts[0]: contact vertices; counts[1 + k]: those touching at times[k].
    std::vector<double> counts(1 + times.size(), 0.);
    for (unsigned int zone = 0; zone < zones.size(); ++zone)
      {
        counts[0] += vertices[zone].size();
        if (!obstacle_driven[zone] || gap[zone] == nullptr)
          {
            for (unsigned int k = 0; k < times.size(); ++k)
              counts[1 + k] += vertices[zone].size();
            continue;
          }
        const double saved_time = gap[zone]->get_time();
        for (unsigned int k = 0; k < times.size(); ++k)
          {
            gap[zone]->set_time(times[k]);
            for (const Point<dim> &point : vertices[zone])
              counts[1 + k] += (gap[zone]->value(point) <= 0);
          }
        gap[zone]->set_time(saved_time);
      }

    Utilities::MPI::sum(counts, communicator, counts);
    if (counts[0] == 0)
      return 1;
    // At least one node, so that the dense problem is never priced at
    // nothing.
    double touching = 1;
    for (unsigned int k = 0; k < times.size(); ++k)
      touching = std::max(touching, counts[1 + k]);
    return touching / counts[0];
  }



  template class ContactZones<2>;
  template class ContactZones<3>;
} // namespace ViscoContact
