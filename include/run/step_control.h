#ifndef viscoplastic_contact_step_control_h
#define viscoplastic_contact_step_control_h

#include "back_ends/linear_algebra.h"
#include "contact_nodes.h"
#include "material.h"

#include <string>
#include <vector>

namespace ViscoContact
{
  template <int dim>
  class ViscoplasticContact;

  // The state at the start of a step that a failed or rejected attempt is
  // undone with: u_{n-1}, the contact state, and with adaptive steps the
  // stress-point records and the step length their history was advanced
  // for.
  template <int dim>
  struct StepStart
  {
    VectorType                               solution;
    ContactNodes::State                      contact;
    std::vector<QuadraturePointHistory<dim>> stress_point_records;
    double                                   step_length;
  };

  // @sect3{The control of a time step}
  //
  // What ViscoplasticContact::do_time_step() decides around the solve of a
  // step (doc/algorithm.md, "Failed solves"; doc/adaptivity.md): the state
  // a failed or rejected attempt is undone with, whether a failed step is
  // cut, and the error test of an adaptive step. Every decision uses only
  // data every rank has alike, so all ranks take it together. The functions
  // read and set the state of a ViscoplasticContact (the problem), whose
  // friend this class is.
  template <int dim>
  class StepControl
  {
  public:
    static StepStart<dim>
    save_start(const ViscoplasticContact<dim> &problem);
    // u_{n-1} and the contact state (the stress points are restored apart,
    // where needed).
    static void
    restore_start(ViscoplasticContact<dim> &problem,
                  const StepStart<dim>     &start);
    // The step halved (TimeSchedule::cut_step()), if On solver failure =
    // cut time step and not below Minimum time step; false otherwise.
    static bool
    cut_failed_step(ViscoplasticContact<dim> &problem,
                    const std::string        &failure);
    // Accepted (true, with the step the controller proposes next), or
    // rejected and the state at the start restored for a shorter step.
    static bool
    accept_adaptive_step(ViscoplasticContact<dim> &problem,
                         const StepStart<dim>     &start,
                         double                   &proposed_step);
  };
} // namespace ViscoContact

#endif
