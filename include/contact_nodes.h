#ifndef viscoplastic_contact_contact_nodes_h
#define viscoplastic_contact_contact_nodes_h

#include <deal.II/base/mpi.h>

#include "contact_law.h"

#include <array>
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
  // runs the iteration; the back ends write r and z, nothing else.

  // What one linear solve for fixed pieces did.
  struct LinearSolveReport
  {
    bool         converged        = true;
    double       residual         = 0; // relative, as the back end measures it
    unsigned int inner_iterations = 0; // CG/GMRES iterations; 0 if direct
    std::string  failure;              // why it did not converge
  };

  // What the active-set iteration of one step problem did.
  struct ActiveSetResult
  {
    struct IterationRecord
    {
      unsigned int changed_nodes;
      unsigned int rigid_nodes;
      double       linear_residual;
      unsigned int inner_iterations;
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

  class ContactNodes
  {
  public:
    // The laws of the contact zones, and the zone and the lumped weight of
    // every locally owned contact node; every node starts at r = z = 0 (on
    // the piece of that state once the parameters c are set).
    void
    reinit(const ContactLaws               &laws,
           const std::vector<unsigned int> &zones,
           const std::vector<double>       &weights);

    // The parameter c_i of the update rule, one per node: it must exceed
    // the steepest softening of the law, so that q = p + c r increases
    // strictly along the graph. If the nodes have not been placed yet, each
    // goes to the piece of r = z = 0.
    void
    set_parameters(const std::vector<double> &c);

    // One step of the update rule on this rank: every node to the piece
    // q_i names (ContactLaw::next_piece keeps a node within rounding of its
    // piece). Returns the number of nodes that moved and of nodes on the
    // rigid piece afterwards.
    std::array<unsigned int, 2>
    update_pieces();

    // The iteration: solve_for_pieces(accuracy) solves the linear problem
    // of the current pieces to the given relative accuracy and writes r and
    // z; repeat until no node moves on any rank of the communicator and the
    // solve met the tolerance, or until max_iterations. Solves before the
    // pieces settle are asked for sqrt(tolerance) only (contact_nodes.cc).
    ActiveSetResult
    solve(const std::function<LinearSolveReport(double)> &solve_for_pieces,
          const unsigned int                              max_iterations,
          const double                                    tolerance,
          const MPI_Comm                                  communicator);

    // The pieces and the last (r, z): what a retried time step restores.
    struct State
    {
      std::vector<unsigned int> pieces;
      std::vector<double>       r, z;
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
    const ContactLawPiece &
    current_piece(const unsigned int i) const;
    void
    set_piece(const unsigned int i, const unsigned int piece);
    const std::vector<unsigned int> &
    pieces() const;

    // r_i = u.nu and z_i, written by the back end of the current solve.
    std::vector<double> r, z;

    // 2 at the rigid limit (u.nu = g), 1 in normal-compliance contact
    // (penetrating the layer, or pressed by it), 0 out of contact.
    unsigned int
    status(const unsigned int i) const;
    // The pressure of the layer, p(u_nu) (p(g-) at the rigid limit), and
    // the total pressure z / w; the foundation carries the difference.
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
    // Over all ranks: the sum of the weights of the nodes in contact (the
    // contact width in 2D, the area in 3D) and the largest pressure z / w.
    double
    contact_area(const MPI_Comm communicator) const;
    double
    peak_pressure(const MPI_Comm communicator) const;

  private:
    ContactLaws               contact_laws;
    std::vector<unsigned int> node_zones;
    std::vector<double>       w, c;
    std::vector<unsigned int> node_pieces;
    bool                      placed = false;
  };
} // namespace ViscoContact

#endif
