#ifndef viscoplastic_contact_active_set_solver_h
#define viscoplastic_contact_active_set_solver_h

#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/lapack_full_matrix.h>
#include <deal.II/lac/vector.h>

#include "contact_law.h"

#include <optional>
#include <string>
#include <vector>

namespace ViscoContact
{
  using namespace dealii;

  // @sect3{The primal-dual active set method on the contact nodes}
  //
  // With the elastic operator K factorised once, the displacement of a time
  // step is u = K^{-1} (b - N^T z), where N takes u to its normal components
  // r = N u at the m contact nodes and z are the nodal normal contact forces
  // (compliance plus foundation). Hence
  //   r = d - S z,   d = N K^{-1} b,   S = N K^{-1} N^T (m x m, SPD),
  // and the contact conditions only involve the contact nodes: at node i
  // the point (r_i, z_i / w_i) must lie on the graph of the contact law
  // (w_i the lumped weight of the node). This class solves that condensed
  // problem with the semismooth Newton / primal-dual active set method of
  // model.md, sections 2 and 5: each node sits on one piece of the graph;
  // the pieces fix a linear system for z; its solution moves the nodes to new
  // pieces; stop when no node moves. The pieces persist between calls (warm
  // start from the previous time step).
  //
  // The condensation is exact, so this is the active-set iteration of
  // step-41/step-42 in which every linear solve with the modified stiffness
  // matrix is replaced by a dense solve of the size of the contact set.
  class ContactActiveSetSolver
  {
  public:
    struct IterationRecord
    {
      unsigned int changed_nodes;
      unsigned int rigid_nodes;
      double       linear_residual;
    };

    struct Result
    {
      bool                         converged;
      std::vector<IterationRecord> history;
      // Iterations of earlier solves in the same time step (the implicit
      // scheme solves one contact problem per Newton iteration).
      unsigned int earlier_iterations = 0;
      // Why the solve failed, if it did (for the report).
      std::string failure;
      unsigned int
      iterations() const
      {
        return earlier_iterations + history.size();
      }
      std::string
      describe() const;
    };

    // The contact compliance S, the lumped weights w_i and the law. Puts
    // every node on the piece of the undeformed, unloaded state (r = z = 0).
    void
    reinit(const ContactLaw          &law,
           const FullMatrix<double>  &compliance,
           const std::vector<double> &weights);

    // A new compliance S (the implicit scheme's tangent changes per Newton
    // iteration), keeping every node on its piece as warm start.
    void
    update_compliance(const FullMatrix<double> &compliance);

    // Solve for given free normal displacements d = N K^{-1} b.
    Result
    solve(const Vector<double> &free_normal_displacement,
          const unsigned int    max_iterations,
          const double          tolerance);

    // The pieces and the last (r, z): what a retried time step restores and
    // a checkpoint stores.
    struct State
    {
      std::vector<unsigned int> pieces;
      Vector<double>            r, z;
    };
    State
    state() const;
    void
    set_state(const State &state);

    unsigned int
    n_nodes() const;
    const std::vector<unsigned int> &
    pieces() const;
    const ContactLaw &
    law() const;
    // r_i = u_nu at the contact nodes, z_i = nodal normal forces.
    const Vector<double> &
    normal_displacements() const;
    const Vector<double> &
    normal_forces() const;
    // The number of LU factorisations of the condensed matrix so far (they
    // are reused while the pieces stay the same).
    unsigned int
    n_factorizations() const;

  private:
    double
    update_forces(const Vector<double> &free_normal_displacement);

    std::optional<ContactLaw> contact_law;
    FullMatrix<double>        S;
    std::vector<double>       w;
    std::vector<double> c; // active-set parameter per node (pressure/length)
    std::vector<unsigned int> node_pieces;
    Vector<double>            r, z;

    // The factorised matrix of the current pieces, and which unknowns it is
    // for, so that an unchanged active set is not factorised again.
    LAPACKFullMatrix<double>  system_matrix;
    std::vector<unsigned int> factorized_pieces;
    std::vector<unsigned int> unknown_nodes;
    unsigned int              factorization_count = 0;
  };
} // namespace ViscoContact

#endif
