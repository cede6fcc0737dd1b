#ifndef viscoplastic_contact_cost_model_h
#define viscoplastic_contact_cost_model_h

#include "parameters.h"

#include <string>
#include <vector>

namespace ViscoContact
{
  // @sect3{The cost of each back end}
  //
  // One estimator of what a back end costs on a scene, before it is built:
  // the memory each rank needs at its peak and the time of the run (set-up
  // and steps). It serves two decisions:
  //  - Method = auto takes the back end of least estimated time among those
  //    it may take (automatic_may_take()) that fit in the memory of a rank
  //    (choose_method());
  //  - before the mesh is built, a run is refused if the back end it will
  //    use, or with Method = auto every back end it could use, needs more
  //    memory than a compute node has
  //    (ViscoplasticContact::check_memory_estimate()).
  // The formulas and the measurements behind their constants are in
  // cost_model.cc and doc/performance.md ("Method = auto").

  // The libraries and MPI of one rank (peak resident memory of a run on a
  // tiny mesh).
  constexpr double library_bytes_per_rank = 150e6;

  // The part of a rank's memory a back end may take: a quarter stays for the
  // system, the output and the model's own error (its memory estimates were
  // within 20% of the measured peaks).
  constexpr double usable_memory_fraction = 0.75;

  // What the estimate depends on. Contact nodes count vertices of the contact
  // boundary (0 when not known yet: the estimate is then a lower one).
  struct SceneSize
  {
    unsigned int dim             = 2;
    bool         simplex         = false;
    bool         implicit_update = false;
    double       dofs            = 0;
    double       contact_nodes   = 0;
    // Unknowns per contact node in the dense problem of the condensed back
    // end: 1 without friction, dim with it.
    unsigned int node_unknowns = 1;
    // The share of the contact nodes expected in contact at one time
    // (ContactZones::expected_contact_fraction()): with friction the dense
    // problem the condensed back end factorises in every active-set
    // iteration holds the rows of those nodes only.
    double       contact_fraction = 1;
    unsigned int ranks            = 1;
    // The steps left in the run (at least one).
    double steps = 1;
    // Whether the first step runs initial cycles (nested iteration), so
    // that its cold start on this mesh takes few active-set iterations.
    bool nested_iteration = false;
    // The coarser meshes every step is solved on first (Step cycles), each
    // with 2^-dim of the dofs of the one above and the same back end, held
    // beside this mesh's for the whole run.
    unsigned int step_cycles = 0;
    // Whether the mesh has coarser meshes inside it: a coarse mesh refined
    // (a generated box with even Subdivisions, Global or Contact refinement
    // levels, adaptive refinement). Without them (a Gmsh file used as it
    // is, a box with odd Subdivisions) the matrix-free back end's
    // multigrid is one level, the AMG of the assembled K with smoothing
    // around it: the full space back end's preconditioner and more.
    bool coarser_meshes = true;
    // Whether the cells differ in shape (a Box map moves every vertex): the
    // matrix-free operator then evaluates every cell by sum factorisation,
    // where the cells of a box or of a refined Gmsh mesh share the dense
    // matrices of a few shapes.
    bool distinct_cells = false;
    // Whether a contact zone is bonded from the start (adhesion or a
    // cohesive interface): springs on the whole zone, often stiffer than the
    // body, which the coarser levels of the matrix-free multigrid do not hold.
    bool bonded_interface = false;
    // The bytes available to each rank: its compute node's memory divided by
    // the ranks on the node, the least over the nodes (0: unknown, every back
    // end fits).
    double memory_per_rank = 0;
    // A lower estimate of the memory (the check before a run): the condensed
    // back end's factor no fuller per dof than at the largest measured size.
    bool lower_estimate = false;
  };

  struct BackEndCost
  {
    Parameters::Method method;
    // Why the back end cannot run the scene; empty if it can.
    std::string unavailable;
    // Why Method = auto does not take a back end that can run the scene
    // (named in the parameter file, it still runs); empty if auto may.
    std::string not_taken;
    // Peak resident memory of one rank, the libraries included.
    double bytes_per_rank = 0;
    // The back end's set-up, and the steps left in the run.
    double setup_seconds = 0;
    double steps_seconds = 0;

    double
    run_seconds() const
    {
      return setup_seconds + steps_seconds;
    }
    // Whether the back end fits in the part of a rank's memory it may take.
    bool
    fits(const SceneSize &scene) const;
    bool
    automatic_may_take() const
    {
      return unavailable.empty() && not_taken.empty();
    }
  };

  // The three back ends' costs on a scene (method condensed, full space,
  // matrix free, in this order).
  std::vector<BackEndCost>
  estimate_costs(const SceneSize &scene);

  // The cost of one back end.
  BackEndCost
  estimate_cost(const Parameters::Method method, const SceneSize &scene);

  // What Method = auto picks, and why (printed at start-up).
  struct MethodChoice
  {
    Parameters::Method method;
    std::string        reason;
  };

  // Resolves Method = auto: the back end it may take of least estimated run
  // time among those that fit in a rank's memory, or the one of least
  // memory if none fits; the reason names every estimate. A method set in
  // the parameter file is returned as it is.
  MethodChoice
  choose_method(const Parameters::Method requested, const SceneSize &scene);
} // namespace ViscoContact

#endif
