#ifndef viscoplastic_contact_mesh_adaptation_h
#define viscoplastic_contact_mesh_adaptation_h

#include <deal.II/grid/cell_id.h>

#include <deal.II/lac/vector.h>

#include "back_ends/linear_algebra.h"

#include <set>

namespace ViscoContact
{
  using namespace dealii;

  template <int dim>
  class ViscoplasticContact;

  // @sect3{Changing the mesh of a run}
  //
  // Every Refinement interval steps (doc/adaptivity.md, "Adaptive meshes"):
  // the indicator (Kelly's estimator of the displacement, raised at the
  // contact front and at the boundary of the plastic zone), refinement and
  // coarsening of the p4est mesh, the set-up of the problem on the new mesh,
  // and its state carried over: the displacement, the stress-point data and
  // the contact pressures, from which the contact set is re-established. The
  // initial cycles (acceleration/initial_cycles.h) change the mesh with the
  // same functions: on p4est they mark cells and call refine_and_transfer()
  // without the stress-point data (every mesh starts from the initial
  // history); on simplices, which deal.II 9.4 cannot refine in a
  // distributed mesh, they call rebuild_and_transfer().
  //
  // The functions change the mesh and the state of a ViscoplasticContact
  // (the problem), whose friend this class is; it keeps no state of its own.
  template <int dim>
  class MeshAdaptation
  {
  public:
    // After every Refinement interval-th step but the last.
    static bool
    due(const ViscoplasticContact<dim> &problem);
    // Mark, refine and coarsen, set up, carry the state over, and assemble
    // the loads of the next step at time on the new mesh. If nothing is
    // marked the mesh and the state stay as they are.
    static void
    adapt(ViscoplasticContact<dim> &problem, const double time);
    // The marking by the indicators, within Maximum cells and Maximum
    // refinement level; returns whether any cell is marked.
    static bool
    mark_cells(ViscoplasticContact<dim> &problem);
    // The marked p4est mesh refined and coarsened, the problem set up on it
    // and u and the contact pressure carried over, and the stress-point data
    // if asked to. state_time: the time of the state carried over, whose
    // gaps name the contact nodes' pieces. The loads are left to the caller.
    static void
    refine_and_transfer(ViscoplasticContact<dim> &problem,
                        const bool                transfer_stress_points,
                        const double              state_time);
    // The next simplex mesh, the parameter file's coarsened coarsenings
    // times, built anew, the problem set up on it, and u and the contact
    // pressure interpolated to it from the current mesh.
    static void
    rebuild_and_transfer(ViscoplasticContact<dim> &problem,
                         const unsigned int        coarsenings,
                         const double              state_time);

  private:
    static Vector<float>
    refinement_indicators(const ViscoplasticContact<dim> &problem);
    // After a transfer: each contact node's (r, z) from u, the gaps at
    // state_time and the pressure field, the piece they name, friction from
    // stick.
    static void
    set_contact_state_from(ViscoplasticContact<dim> &problem,
                           const VectorType         &pressure,
                           const double              state_time);
    // Debug builds: the transferred stress points reproduce E eps(u) on the
    // children of refined_parents (implicit update).
    static void
    check_stress_point_transfer(const ViscoplasticContact<dim> &problem,
                                const std::set<CellId> &refined_parents);
  };
} // namespace ViscoContact

#endif
