#ifndef viscoplastic_contact_contact_nodes_h
#define viscoplastic_contact_contact_nodes_h

#include <deal.II/base/mpi.h>

#include "contact_law.h"

#include <array>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace ViscoContact
{
  using namespace dealii;

  // @sect3{The primal-dual active set method on the pieces of the contact law}
  //
  // At each contact node i the point (r_i, z_i / w_i) must lie on the graph
  // of the contact law (r_i = u.nu_i the normal displacement, z_i the nodal
  // normal force of layer and foundation, w_i the lumped weight). The graph
  // is made of pieces (contact_law.h). The semismooth Newton / primal-dual
  // active set method of doc/model.md, section 2, keeps every node on one
  // piece; for fixed pieces the step problem is linear, and a back end
  // (contact_solver.h) solves it and returns the new (r, z). Each node then
  // moves to the piece that q_i = z_i / w_i + c_i r_i names, and the
  // iteration stops when no node moves (on any MPI rank) and the last linear
  // solve met its tolerance.
  //
  // ContactNodes holds that state for the contact nodes this rank owns and
  // runs the iteration; the back ends write r and z (through
  // store_solution() where a node has friction), nothing else.

  // What one linear solve for fixed pieces did.
  struct LinearSolveReport
  {
    bool         converged        = true;
    double       residual         = 0; // relative, as the back end measures it
    unsigned int inner_iterations = 0; // CG/GMRES iterations; 0 if direct
    std::string  failure;              // why it did not converge
  };

  // What the active-set iteration asks of one linear solve: the relative
  // accuracy at which it may stop and, for an early solve while the pieces
  // still change (ContactNodes::solve()), how it may go on without a
  // restart. A Krylov method that supports this stores (r, z) of its first
  // iterate that meets accuracy in the nodes and asks pieces_stay(); if no
  // node would move, it goes on to settled_accuracy instead of stopping.
  // Other back ends stop at accuracy (a direct solve is exact anyway).
  struct LinearSolveRequest
  {
    double                accuracy         = 0;
    double                settled_accuracy = 0;
    std::function<bool()> pieces_stay; // empty: no going on
  };

  // What the active-set iteration of one step problem did.
  struct ActiveSetResult
  {
    struct IterationRecord
    {
      unsigned int changed_nodes; // moved to another piece or stick/slip
      unsigned int rigid_nodes;
      double       linear_residual;
      unsigned int inner_iterations;
      // Slipping nodes whose slip direction turned by more than the
      // friction tolerance resolves (3D, ContactNodes::update_friction()).
      unsigned int adjusted_nodes = 0;
    };

    bool                         converged = false;
    std::vector<IterationRecord> history;
    // Iterations of earlier active-set runs of the same time step (the
    // implicit scheme runs one per Newton iteration).
    unsigned int earlier_iterations = 0;
    // Krylov iterations outside history (earlier runs, a solve without
    // contact).
    unsigned int earlier_inner_iterations = 0;
    std::string  failure; // why it failed, if it did

    unsigned int
    iterations() const;
    unsigned int
    inner_iterations() const;
    std::string
    describe() const;
  };

  // One direction of a node's equations for fixed pieces and friction
  // states, in the node's frame (its normal, then its tangential
  // directions; ContactSet::frame_row() gives their rows in the dofs). The
  // directions of a node are orthonormal, and the first is the normal.
  // Along a fixed direction a the displacement a . y is prescribed (value)
  // and the force along it is unknown; along a free one the force is
  // value + stiffness a . y + coupling z, z the node's normal force (the
  // coupling is mu along a Coulomb node's slip direction). Here y is the
  // node's displacement in the frame (y_0 = u.nu, before the gap is
  // subtracted).
  struct NodeDirection
  {
    std::array<double, 3> frame     = {{0, 0, 0}};
    bool                  fixed     = false;
    double                value     = 0;
    double                stiffness = 0;
    double                coupling  = 0;
  };

  struct NodeDirections
  {
    unsigned int                 size = 0;
    std::array<NodeDirection, 3> direction;
  };

  class ContactNodes
  {
  public:
    // The tangential displacement and force of a node in its frame (up to
    // two tangential directions).
    using Tangential = std::array<double, 2>;

    // The stick/slip state of a node of a frictional zone: free (a zero
    // bound: Coulomb out of contact), stick, or slip.
    enum FrictionState : unsigned int
    {
      free_tangential = 0,
      stick           = 1,
      slip            = 2
    };

    // The laws of the contact zones, and the zone and the lumped weight of
    // every locally owned contact node; every node starts at r = z = 0 (on
    // the piece of that state once the parameters c are set).
    void
    reinit(const ContactLaws               &laws,
           const std::vector<unsigned int> &zones,
           const std::vector<double>       &weights);

    // Friction: the tangential law of every zone, the number of tangential
    // directions of every node (0 in a frictionless zone, fewer than dim - 1
    // where a plane of symmetry takes one) and the Tresca bound g_i of every
    // node (a nodal force; ignored elsewhere). Every frictional node starts
    // stuck, with no slip since the start.
    void
    set_friction(const std::vector<FrictionLaw>  &zone_laws,
                 const std::vector<unsigned int> &tangential_directions,
                 const std::vector<double>       &tresca_bounds);

    // The memory pressure m_i of every node for the step being solved (the
    // explicit history term of the normal law, normal_memory.h): node i's
    // graph is the law's moved up by m_i. Without a call there is none
    // (has_memory() is false on every rank).
    void
    set_history_pressure(const std::vector<double> &pressures);
    bool
    has_memory() const;
    double
    history_pressure(const unsigned int i) const;
    const std::vector<double> &
    history_pressures() const;

    // The bonding beta_i in [0, 1] of every node for the step being solved
    // (bonding_field.h): node i's adhesive pieces are the law's scaled by
    // its adhesive scale beta_i^2 (ContactLawPiece::scaled()). Without a
    // call every beta_i is 1 (has_adhesion() is false on every rank).
    void
    set_bonding(const std::vector<double> &bonding);
    bool
    has_adhesion() const;
    double
    bonding(const unsigned int i) const;
    const std::vector<double> &
    bondings() const;

    // The largest opening m_i every node of a cohesive interface has reached
    // before the step being solved (cohesive_damage.h): below it, the node's
    // tension is on the secant (ContactLaw::piece()). Without a call every
    // m_i is 0 (has_cohesion() is false on every rank).
    void
    set_reached_openings(const std::vector<double> &openings);
    bool
    has_cohesion() const;
    double
    reached_opening(const unsigned int i) const;
    const std::vector<double> &
    reached_openings() const;

    // What node i's history changes in its law: its adhesive scale
    // beta_i^2 and its reached opening.
    NodeLawState
    law_state(const unsigned int i) const;
    // Whether every node's law, with its history, holds with no force at
    // r_i = -gaps[i], as it does for a body at rest (u = 0) before its
    // obstacles: the point (r_i, 0) lies on node i's graph, which its
    // memory pressure moves up. On every rank (collective).
    bool
    rests_at_gaps(const std::vector<double> &gaps,
                  const MPI_Comm             communicator) const;
    // The damage of node i's cohesive interface at its reached opening
    // (ContactLaw::damage(); 0 elsewhere).
    double
    damage(const unsigned int i) const;

    // The worn depth w_i of every node (archard_wear.h): its obstacle is w_i
    // further away (ContactSet::gap() adds it). Without a call every w_i is
    // 0 (has_wear() is false on every rank).
    void
    set_wear(const std::vector<double> &depths);
    bool
    has_wear() const;
    double
    wear(const unsigned int i) const;

    // The parameter c_i of the update rule, one per node: it must exceed
    // the steepest softening of the law, so that q = p + c r increases
    // strictly along the graph. If the nodes have not been placed yet, each
    // goes to the piece of r = z = 0.
    void
    set_parameters(const std::vector<double> &c);

    // One step of the update rule on this rank: every node to the piece
    // q_i names (ContactLaw::next_piece keeps a node within rounding of its
    // piece), every frictional node to stick or slip (update_friction()).
    // Returns the number of nodes that moved (to another piece, or between
    // stick and slip), of nodes on the rigid piece afterwards, and of
    // slipping nodes whose slip direction turned. Without friction
    // (with_friction = false: the predicted start of a step, whose slip is
    // not predicted) the friction states stay as they are.
    std::array<unsigned int, 3>
    update_pieces(const bool with_friction = true);
    // update_pieces() on every rank of the communicator, the counts summed,
    // with the rounding of q measured against the largest |r| and that of
    // the slips against the largest displacement of a frictional node, of
    // all ranks (collective).
    std::array<unsigned int, 3>
    update_all_pieces(const MPI_Comm communicator);

    // The equations of node i for its piece and friction state (gap: the
    // node's obstacle gap s_i), and the solution of the back end stored
    // back: the displacement a . y along every direction and, for the fixed
    // ones, the force (the free ones' force follows from their law). Sets
    // r, z, s and t of the node.
    NodeDirections
    directions(const unsigned int i, const double gap) const;
    void
    store_solution(const unsigned int    i,
                   const double          gap,
                   const NodeDirections &directions,
                   const double         *displacements,
                   const double         *fixed_forces);

    // After an accepted step, with the tangential displacements of its
    // final u (from the caller): the slip of the next step is measured from
    // them, and a slipping node's bound and direction are those of its
    // forces. After a new mesh or a restored checkpoint: the tangential
    // displacements s of u are the reference, the forces t as given.
    // The step's length (0: no step, as after a new mesh or a restored
    // checkpoint) gives the slip rates of a rate-weakening law.
    void
    accept_slip(const std::vector<Tangential> &tangential_displacements,
                const double                   step_length = 0);
    // The tangential displacement of each node's obstacle over the step
    // being solved (a moving obstacle): a sticking node moves with it, and
    // the slip is measured relative to it. Zero after accept_slip() and
    // reset_slip().
    void
    set_obstacle_slip(const std::vector<Tangential> &obstacle_step);
    void
    reset_slip(const std::vector<Tangential> &tangential_displacements,
               const std::vector<Tangential> &tangential_forces);

    // The iteration: solve_for_pieces(request) solves the linear problem
    // of the current pieces to the requested relative accuracy and writes r
    // and z; repeat until no node moves on any rank of the communicator and
    // the solve met the tolerance, or until max_iterations. Solves before the
    // pieces settle are asked for sqrt(tolerance) only (contact_nodes.cc).
    ActiveSetResult
    solve(const std::function<LinearSolveReport(const LinearSolveRequest &)>
                            &solve_for_pieces,
          const unsigned int max_iterations,
          const double       tolerance,
          const MPI_Comm     communicator);
    // Whether update_all_pieces() would move no node to another piece or
    // between stick and slip, for the (r, z) the nodes hold now; changes
    // nothing (collective).
    bool
    pieces_stay(const MPI_Comm communicator);

    // The pieces, the last (r, z) and the friction state: what a retried
    // time step restores.
    struct State
    {
      std::vector<unsigned int> pieces;
      std::vector<double>       r, z;
      std::vector<Tangential>   s, t, slip_reference, slip_direction, last_slip;
      std::vector<unsigned int> friction_states;
      std::vector<double>       bounds, transverse_stiffness;
    };
    State
    state() const;
    void
    set_state(const State &state);

    unsigned int
    size() const;
    // The laws of all zones; the pieces are indices into their table.
    const ContactLaws &
    laws() const;
    unsigned int
    zone(const unsigned int i) const;
    double
    weight(const unsigned int i) const;
    unsigned int
    piece(const unsigned int i) const;
    // Node i's piece as its history makes it (ContactLaw::piece()).
    ContactLawPiece
    current_piece(const unsigned int i) const;
    void
    set_piece(const unsigned int i, const unsigned int piece);
    const std::vector<unsigned int> &
    pieces() const;

    // r_i = u.nu - gap_i and z_i, written by the back end of the current
    // solve.
    std::vector<double> r, z;
    // The tangential displacement s_i and force t_i of the frictional nodes
    // in their frames (the force the foundation exerts is -t_i, as it is
    // -z_i along the normal).
    std::vector<Tangential> s, t;

    // Friction: whether any zone has it, the tangential directions of node
    // i, its state, the slip increment of the step in its frame, and the
    // bound of its last update.
    bool
    has_friction() const;
    unsigned int
    n_tangential(const unsigned int i) const;
    FrictionState
    friction_state(const unsigned int i) const;
    // For a restored checkpoint (ignored at frictionless nodes).
    void
    set_friction_state(const unsigned int i, const FrictionState state);
    // The slip increment of the last accepted step, s_n - s_{n-1}.
    Tangential
    step_slip(const unsigned int i) const;
    // The variable a weakening law follows: the slip accumulated since the
    // start (the sum of the steps' |slip| while not free), or the slip rate
    // of the last step; settable for a restored checkpoint or a new mesh.
    double
    weakening_variable(const unsigned int i) const;
    void
    set_weakening_variable(const unsigned int i, const double value);
    // Whether a zone's law weakens with the slip or its rate.
    bool
    has_slip_weakening() const;
    double
    slip_bound(const unsigned int i) const;
    // The friction states over all ranks: stick, slip.
    std::array<unsigned int, 2>
    count_friction_states(const MPI_Comm communicator) const;

    // 2 at the rigid limit (u.nu = g), 1 in normal-compliance contact
    // (penetrating the layer, pressed by it or held by adhesion), 0 out of
    // contact.
    unsigned int
    status(const unsigned int i) const;
    // The pressure of the layer, p(u_nu) with its memory pressure (p(g-) and
    // the memory at the rigid limit), and the total pressure z / w; the
    // foundation carries the difference.
    double
    compliance_pressure(const unsigned int i) const;
    double
    contact_pressure(const unsigned int i) const;

    // Over all ranks: the nodes at the rigid limit, in normal-compliance
    // contact, and out of contact; the total contact force sum_i z_i.
    std::array<unsigned int, 3>
    count_states(const MPI_Comm communicator) const;
    double
    total_force(const MPI_Comm communicator) const;
    // Over all ranks: sum_i z_i over the nodes of each zone.
    std::vector<double>
    zone_forces(const MPI_Comm communicator) const;
    // Over all ranks: the sum of the weights of the nodes in contact with a
    // positive pressure (the contact width in 2D, the area in 3D) and the
    // largest pressure z / w.
    double
    contact_area(const MPI_Comm communicator) const;
    double
    peak_pressure(const MPI_Comm communicator) const;
    // The same per zone: {contact area, peak pressure} of each.
    std::vector<std::array<double, 2>>
    zone_areas_and_peaks(const MPI_Comm communicator) const;

  private:
    ContactLaws               contact_laws;
    std::vector<unsigned int> node_zones;
    std::vector<double>       w, c;
    std::vector<unsigned int> node_pieces;
    bool                      placed = false;
    // The largest |r| over all ranks after the last solve of the
    // iteration: the scale of the rounding in q = p + c r, which
    // next_piece()'s slack absorbs.
    double displacement_scale = 0;
    // The largest displacement |(u.nu, s)| of a frictional node over all
    // ranks after the last solve: the scale of the rounding of the slips
    // (update_friction()), with the obstacle gap of every node at its last
    // solve (u.nu = r + gap).
    double              slip_scale = 0;
    std::vector<double> node_gaps;
    // Values per node that a law with a history gives for each step (the
    // memory pressures, the bonding, the worn depths): none until given,
    // then the fallback at every node. Whether they were given is the same
    // on every rank, also on one without contact nodes.
    struct StepValues
    {
      explicit StepValues(const double fallback)
        : fallback(fallback)
      {}

      double              fallback;
      std::vector<double> values;
      bool                given = false;

      void
      set(const std::vector<double>          &new_values,
          [[maybe_unused]] const unsigned int n)
      {
        AssertDimension(new_values.size(), n);
        values = new_values;
        given  = true;
      }
      double
      operator()(const unsigned int i) const
      {
        return given ? values[i] : fallback;
      }
    };
    StepValues memory_pressures{0.}, node_bonding{1.}, worn_depths{0.},
      node_openings{0.};

    // Friction, per zone and per node (see set_friction(), update_friction()).
    std::vector<FrictionLaw>  zone_friction;
    std::vector<unsigned int> tangential_directions;
    std::vector<double>       tresca_bound;
    std::vector<Tangential>   slip_reference, slip_direction, last_slip;
    // The obstacle's tangential displacement over the step (empty: none).
    std::vector<Tangential> obstacle_slip;
    // The weakening variable of every node at the last accepted step.
    std::vector<double> weakening_state;
    // Where node i sticks in the step: its tangential displacement at the
    // last step moved with its obstacle.
    Tangential
                              stick_position(const unsigned int i) const;
    std::vector<unsigned int> friction_states;
    std::vector<double>       bounds, transverse_stiffness;
    double                    friction_tolerance = 1e-7;

    // The stick/slip update of one frictional node: returns whether its
    // state changed, and whether its bound or direction did.
    std::array<bool, 2>
    update_friction(const unsigned int i);
    // Node i's bound now, and its slip direction q / |q| with the
    // transverse stiffness for the bound g.
    double
    bound_of(const unsigned int i) const;
    void
    set_slip_direction(const unsigned int i,
                       const Tangential  &q,
                       const double       g);
    // A hash of the pieces and friction states of all ranks' nodes
    // (collective), by which solve() recognises a cycle.
    std::uint64_t
    active_set_signature(const MPI_Comm communicator) const;
  };
} // namespace ViscoContact

#endif
