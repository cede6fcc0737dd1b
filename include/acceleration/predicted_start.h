#ifndef viscoplastic_contact_predicted_start_h
#define viscoplastic_contact_predicted_start_h

#include "back_ends/linear_algebra.h"
#include "contact_set.h"

#include <optional>
#include <vector>

namespace ViscoContact
{
  using namespace dealii;

  // @sect3{The predicted start of a step}
  //
  // With Predicted start, step n starts from the linear extrapolation of the
  // last two steps instead of from u_{n-1}: u = u_{n-1} + (k_n / k_{n-1})
  // (u_{n-1} - u_{n-2}) is the first guess of the full space back end's
  // Krylov solves and of the implicit update's Newton iteration, and every
  // contact node goes to the piece that the extrapolated r = u.nu_i - s_i
  // and z_{n-1} + (k_n / k_{n-1}) (z_{n-1} - z_{n-2}) name. While the front
  // of the rigid zone moves, the nodes it reaches in this step are then on
  // the rigid piece from the first active-set iteration on, instead of being
  // found one batch per iteration.
  //
  // The start changes the iterations, not the result, as long as the step
  // problem has one solution (doc/model.md, section 4). Where the uniqueness
  // check found that it may have several, the nodes keep the previous step's
  // pieces (pieces_predictable false), which keeps the run on the branch it
  // is on; the displacement is still extrapolated, which only changes where
  // the Krylov solves start.
  //
  // The object keeps u_{n-2} and z_{n-2} (the start of the last accepted
  // step) between steps; a new mesh forgets them, and a checkpoint stores
  // them (has_start(), displacement(), contact_forces(), remember()).
  template <int dim>
  class PredictedStart
  {
  public:
    // A new mesh or a new run: nothing to extrapolate from.
    void
    forget();
    // After an accepted step: the state it started from, u with its ghosts
    // and z of this rank's contact nodes. Not after the first step, unless
    // the run starts at rest: a load already present at t = 0 makes the
    // first step a jump, not a piece of a smooth path.
    void
    remember(VectorType &&displacement, std::vector<double> &&contact_forces);
    // Whether the run starts at rest: u_0 = 0 solves the problem at t_0,
    // because the displacements prescribed at t_0 are 0 (prescribed_start:
    // 0 with them distributed), the right-hand side at t_0 (the loads, the
    // lifting of the prescribed displacements, the history) is 0, and every
    // contact node's law holds with no force at u = 0 (ContactNodes::
    // rests_at_gaps(), at the gaps set for t_0). The first step then is a
    // piece of a smooth path from u_0 = 0, z_0 = 0, which the second step
    // may extrapolate. Collective.
    static bool
    starts_at_rest(const VectorType      &prescribed_start,
                   const VectorType      &right_hand_side,
                   const ContactSet<dim> *contact,
                   const MPI_Comm         communicator);
    bool
    has_start() const;
    const VectorType &
    displacement() const;
    const std::vector<double> &
    contact_forces() const;

    // Whether the contact nodes may take the pieces of the prediction.
    void
    set_pieces_predictable(const bool predictable);
    bool
    pieces_predictable() const;

    // u (with its ghosts updated) and, with contact and predictable pieces,
    // the contact nodes' (r, z) and pieces extrapolated with ratio = k_n /
    // k_{n-1} from the state they hold, the start of the step. The slip is
    // not predicted: a node starts the step in the stick/slip state it
    // ended the last one in (with the extrapolated normal force, a node
    // slipping at its bound would look stuck). Nothing without a start.
    void
    predict(const double ratio, VectorType &u, ContactSet<dim> *contact) const;

  private:
    struct Start
    {
      VectorType          displacement;
      std::vector<double> contact_forces;
    };
    std::optional<Start> start;
    bool                 predictable = true;
  };
} // namespace ViscoContact

#endif
