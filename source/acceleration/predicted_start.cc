// PredictedStart<dim>: the start of a step extrapolated from the two steps
// before it (acceleration/predicted_start.h).

#include <deal.II/base/exceptions.h>

#include "acceleration/predicted_start.h"

#include <utility>

namespace ViscoContact
{
  template <int dim>
  void
  PredictedStart<dim>::forget()
  {
    start.reset();
  }



  template <int dim>
  void
  PredictedStart<dim>::remember(VectorType          &&displacement,
                                std::vector<double> &&contact_forces)
  {
    start = Start{std::move(displacement), std::move(contact_forces)};
  }



  template <int dim>
  bool
  PredictedStart<dim>::starts_at_rest(const VectorType      &prescribed_start,
                                      const VectorType      &right_hand_side,
                                      const ContactSet<dim> *contact,
                                      const MPI_Comm         communicator)
  {
    if (prescribed_start.linfty_norm() != 0
        || right_hand_side.linfty_norm() != 0)
      return false;
    if (contact == nullptr)
      return true;
    std::vector<double> gaps(contact->size());
    for (unsigned int i = 0; i < gaps.size(); ++i)
      gaps[i] = contact->gap(i);
    return contact->rests_at_gaps(gaps, communicator);
  }



  template <int dim>
  bool
  PredictedStart<dim>::has_start() const
  {
    return start.has_value();
  }



  template <int dim>
  const VectorType &
  PredictedStart<dim>::displacement() const
  {
    Assert(start, ExcMessage("No start to predict from."));
    return start->displacement;
  }



  template <int dim>
  const std::vector<double> &
  PredictedStart<dim>::contact_forces() const
  {
    Assert(start, ExcMessage("No start to predict from."));
    return start->contact_forces;
  }



  template <int dim>
  void
  PredictedStart<dim>::set_pieces_predictable(const bool predictable)
  {
    this->predictable = predictable;
  }



  template <int dim>
  bool
  PredictedStart<dim>::pieces_predictable() const
  {
    return predictable;
  }



  template <int dim>
  void
  PredictedStart<dim>::predict(const double     ratio,
                               VectorType      &u,
                               ContactSet<dim> *contact) const
  {
    if (!start)
      return;
    u.zero_out_ghost_values();
    u.sadd(1 + ratio, -ratio, start->displacement);
    u.update_ghost_values();
    if (contact == nullptr || !predictable)
      return;
    const std::vector<double> &earlier_forces = start->contact_forces;
    for (unsigned int i = 0; i < contact->size(); ++i)
      {
        contact->r[i] = contact->normal_component(u, i) - contact->gap(i);
        contact->z[i] += ratio * (contact->z[i] - earlier_forces[i]);
      }
    contact->update_pieces(/*with_friction=*/false);
  }



  template class PredictedStart<2>;
  template class PredictedStart<3>;
} // namespace ViscoContact
