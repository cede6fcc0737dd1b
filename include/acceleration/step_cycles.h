#ifndef viscoplastic_contact_step_cycles_h
#define viscoplastic_contact_step_cycles_h

#include "back_ends/linear_algebra.h"
#include "contact_nodes.h"

#include <memory>

namespace ViscoContact
{
  template <int dim>
  class ViscoplasticContact;

  // @sect3{Step cycles: nested iteration in every time step}
  //
  // (doc/algorithm.md, "Step cycles".)
  //
  // At a fixed time step the front of the rigid zone crosses more rows of
  // nodes per step on a finer mesh, and the active-set iteration finds them a
  // batch per iteration, so the iterations per step grow with the mesh
  // (doc/performance.md, "Active-set iterations, the mesh and the time step").
  // The same step problem on the mesh coarsened once has half as many rows to
  // cross and an eighth of the dofs (in 3D); its contact zone, prolongated, is
  // wrong only within a coarse cell of the front, so the iteration on the fine
  // mesh starts next to its end. Where the step's own start was already right
  // at the coarser resolution, it is kept (start_from_coarser_mesh()).
  //
  // The coarser problem is the step problem restricted to the coarser space:
  // its operator is K of the coarser mesh (for Q1 on nested meshes the
  // Galerkin product P^T K P), its external load and prescribed values are its
  // own, and its history load is P^T of this mesh's, so the viscoplastic
  // history of this mesh, not a coarser one's, drives it. It starts from this
  // step's start (after the prediction), injected into the coarser space. So
  // the coarser problem keeps no state between steps: a cut, rejected or
  // resumed step has the same coarser solve as an uninterrupted one.
  //
  // The transfers are deal.II's MGTwoLevelTransfer between the two meshes
  // (the global-coarsening transfer of step-75), on any partition of either:
  // the prolongation P and the restriction P^T. They need the meshes nested
  // with the same coarse cells: on p4est by construction, and for simplices,
  // which are built whole and handed out, by building both from the same
  // coarse box (AllParameters::nested_coarsened()). Written here rather than
  // taken from deal.II as it is: in deal.II 9.4 the geometric transfer of a
  // vector-valued P1 element on simplices and its injection (interpolate())
  // on simplices are wrong (a linear field is not reproduced; checked by
  // hand), while the scalar P1 and Q1 prolongations are exact. So every field
  // is transferred component by component with the scalar element of the
  // nodal output fields, and the injection of a fine field f into the
  // coarser mesh is P^T applied to f kept at the fine vertices that are
  // vertices of the coarser mesh and zeroed elsewhere: there the rows of P
  // are unit vectors, so P^T gives f at each coarser vertex.
  //
  // The object belongs to a ViscoplasticContact (the problem), whose state it
  // reads and whose step start it sets: it is the problem's friend. The
  // coarser problem and the transfer are built at their first use and
  // dropped with every new mesh (forget()).
  template <int dim>
  class StepCycles
  {
  public:
    StepCycles();
    ~StepCycles();

    // Whether the coarser meshes start this step of problem: with contact,
    // on every step but one that the initial cycles start, and not where
    // the uniqueness check found that the step problem may have several
    // solutions (there the nodes keep the pieces of the branch the run is
    // on, PredictedStart).
    bool
    due(const ViscoplasticContact<dim> &problem) const;
    // Called once the step's right-hand side is assembled and its start
    // predicted: the coarser problem is solved from the injected start, and
    // its u and contact pressure are prolongated into problem's start where
    // the coarser iteration found the start off (three iterations or more).
    // A coarser solve that fails leaves the start as it was. step_start is
    // u_{n-1}, where the slip of the step is measured from.
    void
    start_from_coarser_mesh(ViscoplasticContact<dim> &problem,
                            const VectorType         &step_start);
    // A new mesh (or the end of the problem): the coarser problem goes,
    // before the DoFHandlers its transfer refers to.
    void
    forget();
    // The active-set iterations on the coarser meshes of the last step (for
    // the iteration history); empty once taken.
    ActiveSetResult
    take_last_result();

  private:
    struct CoarserProblem;
    void
    set_up(ViscoplasticContact<dim> &problem);
    void
    inject_contact_state(const ViscoplasticContact<dim> &problem,
                         const VectorType               &coarse_step_start);

    std::unique_ptr<CoarserProblem> coarser;
    ActiveSetResult                 last_result;
  };
} // namespace ViscoContact

#endif
