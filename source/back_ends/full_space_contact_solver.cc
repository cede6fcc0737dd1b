// The full space back end: a Krylov method on the projected operator of the
// step problem, preconditioned by AMG or a factorisation of the operator,
// both built once per operator.
//
// This file implements option (b) of doc/model.md, section 2 ("Two ways to
// solve the linear problem of fixed pieces"). Nothing here costs m^2 or n m
// (m contact nodes, n unknowns): every active-set iteration is one Krylov
// solve in the space of all displacement unknowns, and every node-wise
// operation touches only the rank's own entries. This is the back end for
// large 3D meshes and for several MPI ranks.

#include <deal.II/base/exceptions.h>
#include <deal.II/base/mpi.h>

#include <deal.II/dofs/dof_tools.h>

#include <deal.II/fe/fe.h>
#include <deal.II/fe/fe_values_extractors.h>

#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/solver_cg.h>
#include <deal.II/lac/solver_control.h>
#include <deal.II/lac/solver_gmres.h>
#include <deal.II/lac/trilinos_precondition.h>

#include "back_ends/contact_solver.h"
#include "back_ends/direct_solver.h"
#include "back_ends/constrained_smoothing.h"
#include "back_ends/elasticity_amg.h"
#include "back_ends/matrix_free_elasticity.h"

#include <Epetra_CrsMatrix.h>
#include <Epetra_Import.h>
#include <Epetra_Map.h>
#include <Epetra_MultiVector.h>
#include <Epetra_Vector.h>
#include <Teuchos_ParameterList.hpp>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <optional>
#include <sstream>
#include <utility>
#include <vector>

namespace ViscoContact
{
  namespace
  {
    // The fixed directions of a node that the AMG of the step operator
    // removes: its normal when it is fixed (the first vector of the node's
    // basis then), not the tangents of a sticking node. Stick and slip
    // change from iteration to iteration at the edge of a stick zone, and
    // an AMG rebuilt for each change cost more than it saved: the projected
    // preconditioner P M^{-1} P keeps the tangents fixed anyway.
    template <typename Terms>
    unsigned int
    amg_fixed(const Terms &node)
    {
      return node.directions.size > 0 && node.directions.direction[0].fixed ? 1
                                                                            : 0;
    }
  } // namespace



  // @sect3{The full space back end}
  //
  // For fixed pieces and friction states, every contact node has up to dim
  // orthonormal directions a in its frame (ContactNodes::directions(), with
  // rows v on its dofs, ContactSet::frame_row()): along a fixed one the
  // displacement v . u = beta is prescribed (a vertical piece of the normal
  // law, a sticking tangential direction), along a free one the force is
  // f + k v . u (a sloped piece: f = w o, k = w s; a slipping direction:
  // f = g). With u = u_0 + y, u_0 a displacement with the prescribed
  // values (collect_node_terms()), y solves
  //   (P (A + sum k v v^T) P + (I - P)) y = P (b - sum f v - A u_0),
  // P the orthogonal projection that removes the fixed rows of every node
  // (a constraint among the components of a node, for any directions). The
  // operator is applied around A, which never changes within a step problem;
  // the preconditioner P M^{-1} P + (I - P) uses an AMG cycle of the step
  // operator (its matrix with the fixed nodes' normal directions removed,
  // rebuilt when enough nodes have changed, update_contact_amg()) or the
  // factorisation M^{-1} of A built by set_operator(). Both are symmetric when
  // A is, and positive definite as long as the uniqueness condition
  // (doc/model.md, section 4) holds: CG then; GMRES for the implicit update's
  // unsymmetric tangent. The forces along the fixed directions of a node are
  // read off the residual (b - A u)_i = sum_k f_k v_k with the dual rows,
  // f_k = w_k . (b - A u)_i, W = (V V^T)^{-1} V for the rows V of all its
  // directions: W = V where the rows are orthonormal, not on an oblique
  // plane of symmetry, whose rows are neither unit vectors nor orthogonal
  // (doc/model.md, section 2).
  //
  // Why this form: the sloped pieces only add a rank-one term per direction
  // and the fixed directions only remove directions per node, so neither the
  // matrix A nor its preconditioner has to be rebuilt when a node changes
  // its piece. The contact terms are applied on the fly, and the block I - P
  // keeps the operator nonsingular while leaving the removed components of y
  // at zero.
  template <int dim>
  class FullSpaceContactSolver : public ContactSolver<dim>
  {
  public:
    FullSpaceContactSolver(const Parameters::AllParameters  &parameters,
                           const hp::MappingCollection<dim> &mapping,
                           const DoFHandler<dim>            &dof_handler,
                           const VectorType                 &layout,
                           const ElasticOperatorData<dim>   *matrix_free_data);

    std::string
    description() const override;
    // Set-up: the AMG hierarchy (or the factorisation) of A.
    void
    set_operator(const MatrixType      &A,
                 const bool             symmetric,
                 const ContactSet<dim> &contact) override;
    // A Krylov solve with A alone, and N A^{-1} N^T x through one.
    LinearSolveReport
    solve_without_contact(const VectorType &b, VectorType &u) override;
    void
    apply_compliance(const ContactSet<dim> &contact,
                     const Vector<double>  &x,
                     Vector<double>        &y) override;
    // Per active-set iteration: a Krylov solve on the projected operator
    // with the right-hand side b that set_right_hand_side() keeps per step
    // problem. Its solution is u itself, so finish() has nothing to do.
    LinearSolveReport
    solve_for_pieces(ContactSet<dim>          &contact,
                     VectorType               &u,
                     const LinearSolveRequest &request) override;
    void
    set_right_hand_side(const VectorType      &b,
                        const ContactSet<dim> &contact) override;
    void
    finish(const ContactSet<dim> &contact, VectorType &u) override;
    void
    apply_operator(VectorType &dst, const VectorType &src) const override;
    // After a checkpoint: the AMG of the step operator is built anew at the
    // next solve, as a resumed run builds it.
    void
    forget_kept_state() override;
    // Contact pairs (dual_mortar_basis.h): without a matrix, apply
    // T^T A T and precondition with T^{-1} M^{-1} T^{-T} (T^{-1} = 2 I - T);
    // with one (T^T A T, formed by the caller), give the AMG the rigid-body
    // modes of each body in the basis, T^{-1} r.
    void
    work_in_basis(const MatrixType &T) override;

  private:
    using Apply = std::function<void(VectorType &, const VectorType &)>;

    // What one node contributes for the current pieces and friction states:
    // its directions, their rows on the dofs, and for its fixed rows R an
    // orthonormal basis (what P removes) and (R R^T)^{-1} (for u_0 and the
    // forces along them).
    struct NodeTerms
    {
      NodeDirections                  directions;
      std::array<Tensor<1, dim>, dim> rows;
      unsigned int                    n_fixed = 0;
      std::array<unsigned int, dim>   fixed_directions;
      std::array<Tensor<1, dim>, dim> fixed_basis;
      // The dual rows of all directions, w_k . v_l = delta_kl: a nodal
      // force sum_l f_l v_l has f_k = w_k . force along direction k. On an
      // oblique plane of symmetry the rows are not orthogonal, and w_k is
      // not v_k.
      std::array<Tensor<1, dim>, dim> duals;
    };

    // ML's smoothed aggregation of matrix with the null space (a
    // projection of) the rigid-body modes.
    void
    build_amg(const Epetra_CrsMatrix            &matrix,
              const Epetra_MultiVector          &null_space,
              TrilinosWrappers::PreconditionAMG &amg,
              const bool                         fine_level_smoothing = true)
    {
      build_elasticity_amg(matrix,
                           null_space,
                           rigid_body_modes.node_blocks,
                           dim,
                           symmetric,
                           amg,
                           fine_level_smoothing);
    }
    // The AMG of the step operator of the current terms, rebuilt when
    // enough nodes have changed their fixed directions since it was last
    // built, or the solves since have paid for a new one.
    void
    update_contact_amg(const ContactSet<dim> &contact);
    // Whether the AMG built last still serves the current terms: no node has
    // changed its fixed normal since, or at most 10% of the contact nodes
    // (over all ranks) have and the solves with it have not yet lost the
    // iterations of a set-up. Collective.
    bool
    contact_amg_fits(const ContactSet<dim> &contact) const;
    // What a solve with the AMG of the step operator tells about its age:
    // its convergence factor (last_log_factor) against the one of the first
    // solve after the set-up.
    void
    record_contact_amg_solve(const LinearSolveReport &report);
    // The matrix of the step operator of the current terms, the fixed rows
    // removed, into contact_matrix (after releasing the AMG built on the
    // previous one).
    void
    assemble_contact_matrix(const ContactSet<dim> &contact);
    // The last step of that matrix: the rows of the nodes lose their fixed
    // directions, which come back on their diagonal blocks.
    void
    project_fixed_rows(Epetra_CrsMatrix      &matrix,
                       const ContactSet<dim> &contact) const;
    // The rigid-body modes without their fixed components, into
    // contact_modes.
    void
    project_rigid_body_modes(const ContactSet<dim> &contact);

    // The terms of this rank's nodes for their pieces and friction states
    // (into terms), the prescribed displacement u0 and the loads, into
    // step_rhs.
    void
    collect_node_terms(const ContactSet<dim> &contact,
                       VectorType            &u0,
                       VectorType            &step_rhs);
    // P v: v without its fixed rows at every node.
    void
    remove_fixed_rows(const ContactSet<dim> &contact, VectorType &v) const;
    // The free directions stiffer than the body that the coarse correction
    // does not know (into stiff_rows), and v without its components along
    // them: what the coarse correction leaves to the smoothing
    // (constrained_operator()).
    void
    collect_stiff_rows(const ContactSet<dim> &contact);
    void
    remove_stiff_rows(const ContactSet<dim> &contact, VectorType &v) const;
    // A's diagonal (locally owned entries), computed at the first call after
    // set_operator(); collective then.
    const VectorType &
    diagonal();
    // v -> P inner(P v) + (I - P) v, with the work vector projected_src.
    // The function refers to all arguments but inner, which it copies.
    Apply
    projected(const Apply           &inner,
              VectorType            &projected_src,
              const ContactSet<dim> &contact) const;
    // v -> (A + sum k v v^T) v over the free directions; refers to its
    // arguments.
    Apply
    step_operator(const ContactSet<dim> &contact) const;
    // The factorisation of A, or the AMG of the step operator of these
    // terms, updated here (collective).
    Apply
    step_preconditioner(const ContactSet<dim> &contact);
    // The projected step operator of the current terms, for the smoothing
    // of the preconditioners; refers to contact and this.
    ConstrainedOperator
    constrained_operator(const ContactSet<dim> &contact);
    // The displacement along every direction, and the force along the
    // fixed ones, from the solution u and the residual b - A u.
    void
    read_off_contact(ContactSet<dim>  &contact,
                     const VectorType &u,
                     const VectorType &residual) const;
    // How CG may go on past its accuracy (LinearSolveRequest): to
    // settled_accuracy if pieces_stay(y) holds for its first iterate y that
    // meets the accuracy.
    struct Continuation
    {
      double                                  settled_accuracy = 0;
      std::function<bool(const VectorType &)> pieces_stay;
    };
    // Solves op y = rhs from the initial y with the preconditioner prec:
    // CG (symmetric_operator) or GMRES to the relative accuracy (Tolerance
    // unless the active-set iteration asks for less) times reference_norm.
    LinearSolveReport
    krylov_solve(const Apply        &op,
                 const Apply        &prec,
                 VectorType         &y,
                 const VectorType   &rhs,
                 const double        reference_norm,
                 const double        accuracy,
                 const bool          symmetric_operator,
                 const Continuation &continuation = {});
    // Whether a node of this rank has a direction coupled to its normal
    // force (a slipping Coulomb node), and the coupled directions k of node
    // i whose normal is fixed.
    bool
    has_coupling() const;
    template <typename Function>
    void
    for_each_coupled_fixed_normal(const unsigned int i, const Function &f) const
    {
      if (!terms[i].directions.direction[0].fixed)
        return;
      for (unsigned int k = 1; k < terms[i].directions.size; ++k)
        if (!terms[i].directions.direction[k].fixed
            && terms[i].directions.direction[k].coupling != 0)
          f(k);
    }
    // The free directions k of node i with a stiffness.
    template <typename Function>
    void
    for_each_stiff_direction(const unsigned int i, const Function &f) const
    {
      for (unsigned int k = 0; k < terms[i].directions.size; ++k)
        if (!terms[i].directions.direction[k].fixed
            && terms[i].directions.direction[k].stiffness != 0)
          f(k);
    }

    // Preconditioner (subsection Linear solver), Tolerance (subsection
    // Active set solver), and what the AMG needs to build the rigid-body
    // modes.
    const Parameters::Preconditioner  preconditioner_type;
    const double                      tolerance;
    const MPI_Comm                    communicator;
    const hp::MappingCollection<dim> &mapping;
    const DoFHandler<dim>            &dof_handler;

    // The operator of the current step problems (owned by the caller: the
    // elastic matrix or the current tangent), whether it is symmetric (which
    // decides between CG and GMRES), the factorisation when Preconditioner =
    // direct, and the right-hand side of the current step problem.
    const MatrixType *A = nullptr;
    // Method = matrix free: what its operator is built from, and the
    // operator with its multigrid, built by the first set_operator().
    std::optional<ElasticOperatorData<dim>>    matrix_free_data;
    std::unique_ptr<MatrixFreeElasticity<dim>> matrix_free;
    bool                                       symmetric = true;
    RigidBodyModes                             rigid_body_modes;
    std::optional<SparseDirectSolver>          factorization;
    VectorType                                 b;
    double                                     b_norm = 0;

    // The two AMG preconditioners, each built when first needed after
    // set_operator(): one of A alone, for the solves without contact, and
    // one of the step operator of the pieces the nodes were on when it was
    // built (update_contact_amg()), held in contact_matrix with its near-null
    // space contact_modes. contact_amg_fixed keeps the number of fixed
    // directions of this rank's nodes it was built for, to tell how many
    // nodes have changed since, and contact_amg_stiffness the sum of k v v^T
    // over each node's free directions that its matrix holds.
    TrilinosWrappers::PreconditionAMG   operator_amg, contact_amg;
    bool                                operator_amg_built = false;
    bool                                contact_amg_built  = false;
    std::unique_ptr<Epetra_CrsMatrix>   contact_matrix;
    std::unique_ptr<Epetra_MultiVector> contact_modes;
    std::vector<unsigned int>           contact_amg_fixed;
    std::vector<Tensor<2, dim>>         contact_amg_stiffness;
    // The log of the convergence factor per iteration of the first solve
    // with the AMG (0: none yet), and the iterations that the later ones
    // took beyond that factor (record_contact_amg_solve()).
    double contact_amg_first_log_factor = 0;
    double contact_amg_lost_iterations  = 0;
    // The log of the last Krylov solve's convergence factor per iteration
    // (0 if it took no iteration).
    double last_log_factor = 0;

    // The terms of this rank's nodes in the current solve.
    std::vector<NodeTerms> terms;

    // Work vectors of the projected operator and preconditioner, which the
    // Krylov method applies once per iteration each: allocated once here
    // instead of once per application.
    VectorType operator_scratch, preconditioner_scratch;
    // And of the projected operator that the preconditioners smooth
    // (allocated with its first use).
    VectorType smoother_scratch;
    // The smoothing around the AMG of the step operator, and whether it has
    // its eigenvalue bound for the current A.
    ConstrainedSmoothing smoothing{2, 15.};
    bool                 smoothing_ready = false;
    // A's diagonal (diagonal(); empty until needed), and the stiff free
    // directions of this rank's nodes as (node, unit row orthogonal to its
    // fixed rows), collect_stiff_rows().
    VectorType                                           diagonal_of_A;
    std::vector<std::pair<unsigned int, Tensor<1, dim>>> stiff_rows;

    // With contact pairs: the basis T of the step problem, work vectors of
    // its products (without a matrix), and the rigid-body modes in the
    // basis (with one).
    const MatrixType                   *basis = nullptr;
    mutable VectorType                  basis_scratch, basis_result;
    std::unique_ptr<Epetra_MultiVector> basis_modes;
    // The near-null space of the operator in the basis of the step problem.
    const Epetra_MultiVector &
    near_null_space() const;
    // M^{-1} of the matrix-free multigrid, in the basis if there is one.
    void
    precondition_matrix_free(VectorType &dst, const VectorType &src) const;
  };



  // @sect4{FullSpaceContactSolver::FullSpaceContactSolver}
  //
  // Only the choice of the preconditioner is made here. With Preconditioner
  // = direct, a sparse direct solver is created (with the same rule for
  // Direct solver = auto as on the condensed back end: CHOLMOD on one rank,
  // MUMPS on several); otherwise the AMG is built by set_operator(). The
  // vector b takes its partition from layout.
  template <int dim>
  FullSpaceContactSolver<dim>::FullSpaceContactSolver(
    const Parameters::AllParameters  &parameters,
    const hp::MappingCollection<dim> &mapping,
    const DoFHandler<dim>            &dof_handler,
    const VectorType                 &layout,
    const ElasticOperatorData<dim>   *matrix_free_data)
    : preconditioner_type(parameters.preconditioner)
    , tolerance(parameters.tolerance)
    , communicator(layout.get_mpi_communicator())
    , mapping(mapping)
    , dof_handler(dof_handler)
    , b(layout)
    , operator_scratch(layout)
    , preconditioner_scratch(layout)
  {
    if (matrix_free_data != nullptr)
      this->matrix_free_data.emplace(*matrix_free_data);
    else if (preconditioner_type == Parameters::Preconditioner::direct)
      factorization.emplace(parameters.direct_solver, communicator);
  }



  // The line for the run's header: the Krylov method and its preconditioner.
  template <int dim>
  std::string
  FullSpaceContactSolver<dim>::description() const
  {
    if (matrix_free_data)
      return "matrix free: CG on the projected operator, K applied cell by "
             "cell, preconditioned by "
             + (matrix_free ? matrix_free->description()
                            : std::string("a geometric multigrid V-cycle"));
    return std::string("full space: CG (GMRES for the implicit update's "
                       "tangent) on the projected operator, preconditioned by ")
           + (factorization ? factorization->description()
                            : "ML AMG of the step operator with the "
                              "rigid-body modes");
  }



  // @sect4{FullSpaceContactSolver::set_operator}
  //
  // Remember the operator: once per run for the elastic K, once per Newton
  // iteration for the implicit update's tangent. With Preconditioner =
  // direct, A is factorised here. The AMG preconditioners are built when a
  // solve first needs them (a scene with contact rarely solves with A alone,
  // one without contact never needs the step operator's), so each Newton
  // iteration builds one AMG, not two. The parameters c_i of the active set
  // are set by ContactSet::set_operator(), not here.
  template <int dim>
  void
  FullSpaceContactSolver<dim>::set_operator(const MatrixType &matrix,
                                            const bool        is_symmetric,
                                            const ContactSet<dim> &)
  {
    symmetric = is_symmetric;
    // Without a matrix: the operator and its multigrid are built once, for
    // K (the implicit update's tangent is refused when the parameters are
    // read).
    if (matrix_free_data)
      {
        AssertThrow(is_symmetric, ExcInternalError());
        if (!matrix_free)
          {
            matrix_free
              = std::make_unique<MatrixFreeElasticity<dim>>(*matrix_free_data,
                                                            b);
            ++this->counts.operator_setups;
          }
        return;
      }
    A                  = &matrix;
    operator_amg_built = false;
    contact_amg_built  = false;
    smoothing_ready    = false;
    diagonal_of_A.reinit(0);
    if (!factorization && !rigid_body_modes.modes)
      rigid_body_modes
        = compute_rigid_body_modes(mapping,
                                   dof_handler,
                                   matrix.trilinos_matrix().RowMap(),
                                   communicator,
                                   /*per_body=*/basis != nullptr);
    if (!factorization && basis && !basis_modes)
      {
        // T^{-1} r = 2 r - T r.
        basis_modes
          = std::make_unique<Epetra_MultiVector>(*rigid_body_modes.modes);
        const int error
          = basis->trilinos_matrix().Multiply(false,
                                              *rigid_body_modes.modes,
                                              *basis_modes);
        AssertThrow(error == 0, ExcTrilinosError(error));
        basis_modes->Update(2., *rigid_body_modes.modes, -1.);
      }
    if (factorization)
      {
        factorization->factorize(matrix, is_symmetric);
        ++this->counts.operator_setups;
      }
  }



  // @sect4{FullSpaceContactSolver::update_contact_amg}
  //
  // The step operator differs from A by the stiffness of the free
  // directions (sloped pieces, a slipping node's transverse stiffness) and,
  // above all, by the fixed directions (the normal of a node on a vertical
  // piece, the tangents of a sticking node). A preconditioner of A alone
  // treats those as free: with a few hundred fixed nodes, CG needs about
  // twice as many iterations per digit as for A (measured in
  // doc/performance.md). So the AMG is built for the matrix of the
  // projected operator itself,
  //   P (A + sum k v v^T) P + sum_{fixed q} d_q q q^T,
  // d_q = q^T A_ii q, q the node's fixed normal (amg_fixed(): the tangents
  // of a sticking node stay in the AMG's matrix): at a node its fixed
  // normal is removed from its rows and columns, as a Dirichlet condition
  // would be, and comes back only on the node's own diagonal block, with
  // the node's stiffness as scale. Its near-null space
  // is P applied to the rigid-body modes, which the constrained operator no
  // longer has in its null space. (Earlier, a penalty 1000 nu^T A_ii nu at
  // the fixed nodes with the unprojected modes took 30% more CG iterations
  // on tetrahedra: the coarse spaces carried the fixed normal components,
  // and the AMG settings had to differ on simplices; doc/performance.md.)
  // Every change touches only entries in the pattern of A: the node's
  // dim x dim blocks, and the columns of its dofs.
  //
  // When to build it again is a trade: a set-up costs about 30 CG
  // iterations, while an AMG built for other pieces makes each solve slower.
  // The nodes that changed since are handled by the smoothing of the
  // projected step operator around the AMG's cycle (step_preconditioner()),
  // which knows every fixed direction, a sticking node's tangents too; how
  // much a stale AMG costs then depends on the mesh. On the uniform cube
  // (cube_3d.prm, 108k dofs, 8 steps) rebuilt whenever a quarter of the
  // nodes in contact had changed, the AMG took 153 CG iterations and 10
  // set-ups against 190 and 2 for a rebuild at 10% of the contact nodes: a
  // rebuild did not pay. On the Hertz sphere's mesh, graded toward a zone
  // in contact of a tenth of the contact boundary, that rule built the AMG
  // twice in the whole run, and the solves slowed down from step to step
  // (601 CG iterations in 4 steps at 353k dofs). So the solves also measure
  // what staleness costs (record_contact_amg_solve()): each one after the first
  // with this AMG counts the iterations it took beyond the convergence
  // factor of the first, and the AMG is rebuilt once these lost iterations
  // reach the cost of a set-up (rent or buy), or once 10% of the contact
  // nodes have changed (which keeps the cold starts and the small scenes
  // as they were). On the Hertz sphere that took 451 iterations and 4
  // set-ups, on the cube 190 and 3 (doc/performance.md, "The full space
  // back end"). These counts, and the 30 iterations a set-up is taken to
  // cost, were measured while the AMG smoothed its finest level too, whose
  // iterations took nine products with A instead of five. Iterations and
  // residuals are the same on every rank, so all ranks decide alike.
  // contact_amg_fits() decides, then assemble_contact_matrix() and
  // project_rigid_body_modes() give the AMG its matrix and near-null space.
  template <int dim>
  void
  FullSpaceContactSolver<dim>::update_contact_amg(
    const ContactSet<dim> &contact)
  {
    if (contact_amg_fits(contact))
      return;
    assemble_contact_matrix(contact);
    project_rigid_body_modes(contact);
    // A symmetric operator gets the AMG inside the smoothing of the
    // projected operator (step_preconditioner()), which smooths the finest
    // level: ML then only does the coarse levels.
    build_amg(*contact_matrix,
              *contact_modes,
              contact_amg,
              /*fine_level_smoothing=*/!symmetric);
    contact_amg_fixed.resize(contact.size());
    for (unsigned int i = 0; i < contact.size(); ++i)
      contact_amg_fixed[i] = amg_fixed(terms[i]);
    contact_amg_built            = true;
    contact_amg_first_log_factor = 0;
    contact_amg_lost_iterations  = 0;
    ++this->counts.operator_setups;
  }



  // @sect4{FullSpaceContactSolver::contact_amg_fits}
  //
  // A node has changed if it has become fixed or free along its normal
  // (amg_fixed()); a changed slope or stick/slip state does not count. Every
  // rank takes part in the sum, whether an AMG has been built or not.
  // An operator that fits ML's coarsest level (2000 rows, deal.II's setting)
  // makes the AMG one sparse factorisation: a set-up then costs little, and
  // rebuilt for every change the AMG solves each set of pieces exactly.
  template <int dim>
  bool
  FullSpaceContactSolver<dim>::contact_amg_fits(
    const ContactSet<dim> &contact) const
  {
    unsigned int changed = 0;
    if (contact_amg_built)
      for (unsigned int i = 0; i < contact.size(); ++i)
        changed += (amg_fixed(terms[i]) != contact_amg_fixed[i]);
    changed = Utilities::MPI::sum(changed, communicator);
    if (A->m() <= 2000)
      return contact_amg_built && changed == 0;
    // A set-up costs about 30 CG iterations (with the smoothing,
    // cube_3d.prm at 108k dofs).
    return contact_amg_built
           && (changed == 0
               || (changed <= 0.1 * contact.n_global_nodes()
                   && contact_amg_lost_iterations < 30));
  }



  // @sect4{FullSpaceContactSolver::record_contact_amg_solve}
  //
  // A solve whose factor per iteration rho is worse than the first one's,
  // rho_1, would have taken n log(rho) / log(rho_1) iterations with an AMG
  // as good as it was then, n those it took: the difference is lost. A
  // solve that took no iteration, or did not reduce the residual, tells
  // nothing.
  template <int dim>
  void
  FullSpaceContactSolver<dim>::record_contact_amg_solve(
    const LinearSolveReport &report)
  {
    if (last_log_factor >= 0)
      return;
    if (contact_amg_first_log_factor == 0)
      contact_amg_first_log_factor = last_log_factor;
    else if (last_log_factor > contact_amg_first_log_factor)
      contact_amg_lost_iterations
        += report.inner_iterations
           * (1. - last_log_factor / contact_amg_first_log_factor);
  }



  // @sect4{FullSpaceContactSolver::forget_kept_state}
  //
  // Which AMG a solve uses depends on the pieces it was built for, not only
  // on the current ones. A resumed run builds its AMG for the pieces of its
  // first solve; after a checkpoint this run does the same, so that both go
  // on with the same preconditioner and the same iterates.
  template <int dim>
  void
  FullSpaceContactSolver<dim>::forget_kept_state()
  {
    contact_amg_built = false;
  }



  // @sect4{Editing the step operator's matrix}
  //
  // The matrix of the projected operator is a copy of A whose entries are
  // changed in place, which deal.II's interface does not offer, hence
  // Epetra's. These helpers do the edits that need no member of the
  // solver.
  namespace
  {
    // The local row of component c of contact node i.
    template <int dim>
    int
    node_row(const Epetra_CrsMatrix &matrix,
             const ContactSet<dim>  &contact,
             const unsigned int      i,
             const unsigned int      c)
    {
      return matrix.RowMap().LID(
        static_cast<long long>(contact.node(i).dofs[c]));
    }

    // k v v^T into the diagonal block of node i, in the components v has
    // (a constrained component has none, and its row no entries but the
    // diagonal).
    template <int dim>
    void
    add_to_block(Epetra_CrsMatrix      &matrix,
                 const ContactSet<dim> &contact,
                 const unsigned int     i,
                 const Tensor<1, dim>  &v,
                 const double           k)
    {
      const auto  &node = contact.node(i);
      int          columns[dim];
      double       values[dim];
      unsigned int components[dim], n = 0;
      for (unsigned int d = 0; d < dim; ++d)
        if (v[d] != 0)
          {
            components[n] = d;
            columns[n++]
              = matrix.ColMap().LID(static_cast<long long>(node.dofs[d]));
          }
      for (unsigned int m = 0; m < n; ++m)
        {
          for (unsigned int e = 0; e < n; ++e)
            values[e] = k * v[components[m]] * v[components[e]];
          const int error = matrix.SumIntoMyValues(
            node_row(matrix, contact, i, components[m]),
            n,
            values,
            columns);
          AssertThrow(error == 0, ExcTrilinosError(error));
        }
    }

    // The columns of the fixed directions: for basis vector b of every node
    // with a fixed direction, mark its dofs with that vector's component and
    // the node (its global number + 1), and bring the marks to the columns
    // of this rank's rows, fixed nodes of other ranks included. The marks
    // are written at row indices: deal.II builds square matrices with the
    // same map for rows and domain.
    template <int dim, typename Terms>
    void
    mark_fixed_columns(const Epetra_CrsMatrix   &matrix,
                       const ContactSet<dim>    &contact,
                       const std::vector<Terms> &terms,
                       const unsigned int        b,
                       Epetra_Vector            &column_direction,
                       Epetra_Vector            &column_node)
    {
      Assert(matrix.RowMap().SameAs(matrix.DomainMap()), ExcInternalError());
      Epetra_Vector owned_direction(matrix.DomainMap()),
        owned_node(matrix.DomainMap());
      for (unsigned int i = 0; i < contact.size(); ++i)
        if (amg_fixed(terms[i]) > b)
          for (unsigned int c = 0; c < dim; ++c)
            {
              owned_direction[node_row(matrix, contact, i, c)]
                = terms[i].fixed_basis[b][c];
              owned_node[node_row(matrix, contact, i, c)]
                = static_cast<double>(contact.first_global_index() + i + 1);
            }
      if (matrix.Importer() != nullptr)
        {
          column_direction.Import(owned_direction, *matrix.Importer(), Insert);
          column_node.Import(owned_node, *matrix.Importer(), Insert);
        }
      else // the columns are the owned dofs, in the same order
        {
          column_direction = owned_direction;
          column_node      = owned_node;
        }
    }

    // M P, row by row: in the columns of each marked node j (as marked by
    // mark_fixed_columns()), the row's entries a lose their part along the
    // node's marked direction q_j, a -= (a . q_j) q_j.
    void
    project_fixed_columns(Epetra_CrsMatrix    &matrix,
                          const Epetra_Vector &column_direction,
                          const Epetra_Vector &column_node)
    {
      std::vector<std::pair<double, double>> node_sums; // (node, a . q_j)
      for (int row = 0; row < matrix.NumMyRows(); ++row)
        {
          int     n;
          double *values;
          int    *columns;
          matrix.ExtractMyRowView(row, n, values, columns);
          node_sums.clear();
          for (int e = 0; e < n; ++e)
            if (const double j = column_node[columns[e]]; j != 0)
              {
                auto sum
                  = std::find_if(node_sums.begin(),
                                 node_sums.end(),
                                 [j](const auto &s) { return s.first == j; });
                if (sum == node_sums.end())
                  sum = node_sums.insert(node_sums.end(), {j, 0.});
                sum->second += values[e] * column_direction[columns[e]];
              }
          for (const auto &[j, sum] : node_sums)
            for (int e = 0; e < n; ++e)
              if (column_node[columns[e]] == j)
                values[e] -= sum * column_direction[columns[e]];
        }
    }
  } // namespace



  // @sect4{FullSpaceContactSolver::assemble_contact_matrix}
  //
  // A copy of A, the stiffness of the free directions added to their
  // nodes' diagonal blocks, then P M P for the fixed directions: the
  // columns (M P, project_fixed_columns(), one basis vector of the nodes at
  // a time: the basis of a node is orthonormal, so its projections commute),
  // then the rows (P (M P), project_fixed_rows()).
  template <int dim>
  void
  FullSpaceContactSolver<dim>::assemble_contact_matrix(
    const ContactSet<dim> &contact)
  {
    // The AMG keeps a reference to its matrix: release it before the matrix
    // is replaced.
    contact_amg.clear();
    contact_matrix = std::make_unique<Epetra_CrsMatrix>(A->trilinos_matrix());
    Epetra_CrsMatrix &matrix = *contact_matrix;
    contact_amg_stiffness.assign(contact.size(), Tensor<2, dim>());
    for (unsigned int i = 0; i < contact.size(); ++i)
      for_each_stiff_direction(i, [&](const unsigned int k) {
        const double stiffness = terms[i].directions.direction[k].stiffness;
        add_to_block(matrix, contact, i, terms[i].rows[k], stiffness);
        contact_amg_stiffness[i]
          += stiffness * outer_product(terms[i].rows[k], terms[i].rows[k]);
      });

    unsigned int most_fixed = 0;
    for (const NodeTerms &node : terms)
      most_fixed = std::max(most_fixed, amg_fixed(node));
    most_fixed = Utilities::MPI::max(most_fixed, communicator);
    Epetra_Vector column_direction(matrix.ColMap()),
      column_node(matrix.ColMap());
    for (unsigned int b = 0; b < most_fixed; ++b)
      {
        mark_fixed_columns(matrix,
                           contact,
                           terms,
                           b,
                           column_direction,
                           column_node);
        project_fixed_columns(matrix, column_direction, column_node);
      }
    project_fixed_rows(matrix, contact);
  }



  // @sect4{FullSpaceContactSolver::project_fixed_rows}
  //
  // P (M P): the rows of each node lose their fixed directions column by
  // column. Only the rows of the components the directions have take part
  // (a component constrained by a roller or symmetry plane has none, and
  // its row only its diagonal); these rows have the same columns (the
  // vector-valued element couples all components of neighbouring
  // vertices), which is checked. Then d_q q q^T, d_q = q^T A_ii q, goes back
  // on the node's diagonal block for every basis vector q.
  template <int dim>
  void
  FullSpaceContactSolver<dim>::project_fixed_rows(
    Epetra_CrsMatrix      &matrix,
    const ContactSet<dim> &contact) const
  {
    for (unsigned int i = 0; i < contact.size(); ++i)
      {
        const NodeTerms &node_terms = terms[i];
        if (amg_fixed(node_terms) == 0)
          continue;
        const auto  &node = contact.node(i);
        int          n[dim];
        double      *values[dim];
        int         *columns[dim];
        unsigned int components[dim] = {}, n_components = 0;
        for (unsigned int c = 0; c < dim; ++c)
          {
            bool used = false;
            for (unsigned int b = 0; b < amg_fixed(node_terms); ++b)
              used = used || node_terms.fixed_basis[b][c] != 0;
            if (used)
              components[n_components++] = c;
          }
        const unsigned int first = components[0];
        for (unsigned int m = 0; m < n_components; ++m)
          {
            const unsigned int c = components[m];
            matrix.ExtractMyRowView(node_row(matrix, contact, i, c),
                                    n[c],
                                    values[c],
                                    columns[c]);
            AssertThrow(n[c] == n[first]
                          && std::equal(columns[c],
                                        columns[c] + n[c],
                                        columns[first]),
                        ExcMessage("The rows of a contact node's "
                                   "components do not have the same "
                                   "columns."));
          }
        for (unsigned int b = 0; b < amg_fixed(node_terms); ++b)
          {
            const Tensor<1, dim> &q = node_terms.fixed_basis[b];
            for (int e = 0; e < n[first]; ++e)
              {
                double sum = 0;
                for (unsigned int m = 0; m < n_components; ++m)
                  sum += q[components[m]] * values[components[m]][e];
                for (unsigned int m = 0; m < n_components; ++m)
                  values[components[m]][e] -= sum * q[components[m]];
              }
          }
        // d_q q q^T, d_q = q^T A_ii q, back on the diagonal.
        for (unsigned int b = 0; b < amg_fixed(node_terms); ++b)
          {
            const Tensor<1, dim> &q = node_terms.fixed_basis[b];
            double                d = 0;
            for (unsigned int c = 0; c < dim; ++c)
              for (unsigned int e = 0; e < dim; ++e)
                if (q[c] != 0 && q[e] != 0)
                  d += q[c] * A->el(node.dofs[c], node.dofs[e]) * q[e];
            add_to_block(matrix, contact, i, q, d);
          }
      }
  }



  // @sect4{FullSpaceContactSolver::project_rigid_body_modes}
  //
  // The near-null space of the constrained operator: the rigid-body modes
  // without their fixed components at the nodes.
  template <int dim>
  void
  FullSpaceContactSolver<dim>::project_rigid_body_modes(
    const ContactSet<dim> &contact)
  {
    const Epetra_CrsMatrix &matrix = *contact_matrix;
    contact_modes = std::make_unique<Epetra_MultiVector>(near_null_space());
    for (unsigned int i = 0; i < contact.size(); ++i)
      for (unsigned int b = 0; b < amg_fixed(terms[i]); ++b)
        for (int mode = 0; mode < contact_modes->NumVectors(); ++mode)
          {
            const Tensor<1, dim> &q    = terms[i].fixed_basis[b];
            double                part = 0;
            for (unsigned int c = 0; c < dim; ++c)
              part += q[c]
                      * (*contact_modes)[mode][node_row(matrix, contact, i, c)];
            for (unsigned int c = 0; c < dim; ++c)
              (*contact_modes)[mode][node_row(matrix, contact, i, c)]
                -= part * q[c];
          }
  }



  // @sect4{FullSpaceContactSolver::set_right_hand_side}
  //
  // Nothing is solved per step problem on this back end: b is only kept for
  // the Krylov solves of the active-set iterations and for the residual from
  // which the forces at the fixed nodes are read off.
  template <int dim>
  void
  FullSpaceContactSolver<dim>::set_right_hand_side(const VectorType &rhs,
                                                   const ContactSet<dim> &)
  {
    b      = rhs;
    b_norm = b.l2_norm();
  }



  // @sect4{FullSpaceContactSolver::krylov_solve}
  //
  // The one Krylov solve of this back end, for the step operator as well as
  // for A alone. The tolerance is relative to reference_norm; for the
  // active-set solves that is the size of the step's loads: the largest of
  // the norms of b, of the loads of the nodes' pieces and of the
  // obstacle's prescribed normal displacements (solve_for_pieces()). A
  // symmetric operator gets CG. An unsymmetric one gets GMRES with right
  // preconditioning, so that the residual it monitors is the true residual,
  // as with CG, and the same Tolerance means the same thing for both; it
  // restarts when its basis of about 50 vectors is full. A solve that does
  // not converge is not an error here: the report says why, and the time
  // loop decides whether to cut the step (time_step.cc). GMRES does not go
  // on past the accuracy: its iterate is formed only when it stops.
  template <int dim>
  LinearSolveReport
  FullSpaceContactSolver<dim>::krylov_solve(const Apply      &op,
                                            const Apply      &prec,
                                            VectorType       &y,
                                            const VectorType &rhs,
                                            const double      reference_norm,
                                            const double      accuracy,
                                            const bool symmetric_operator,
                                            const Continuation &continuation)
  {
    // The operators of the Krylov methods: what deal.II's solvers call.
    struct Operator
    {
      const Apply &apply;
      void
      vmult(VectorType &dst, const VectorType &src) const
      {
        apply(dst, src);
      }
    };

    // No load at all (a step whose only load is an obstacle not yet
    // touched): the solution is zero, which no relative tolerance can
    // certify.
    LinearSolveReport report;
    if (reference_norm == 0 && rhs.linfty_norm() == 0)
      {
        y = 0;
        return report;
      }
    // At most 10000 iterations. The lower bound 1e-300 keeps the tolerance
    // and the relative residual defined when the reference norm is zero.
    const double  scale = std::max(reference_norm, 1e-300);
    SolverControl control(10000, accuracy * scale);
    try
      {
        if (symmetric_operator)
          {
            SolverCG<VectorType> cg(control);
            // Past the control's tolerance (where it says success) this
            // check decides: stop, or go on to the settled accuracy.
            bool asked = false, going_on = false;
            if (continuation.pieces_stay)
              cg.connect([&](const unsigned int step,
                             const double       value,
                             const VectorType  &iterate) {
                if (value > control.tolerance())
                  return SolverControl::success;
                if (!asked)
                  {
                    asked    = true;
                    going_on = continuation.pieces_stay(iterate);
                  }
                if (!going_on || value <= continuation.settled_accuracy * scale)
                  return SolverControl::success;
                // The control says success here even at its last step.
                return step < control.max_steps() ? SolverControl::iterate
                                                  : SolverControl::failure;
              });
            cg.solve(Operator{op}, y, rhs, Operator{prec});
          }
        else
          SolverGMRES<VectorType>(
            control,
            typename SolverGMRES<VectorType>::AdditionalData(
              50,
              /*right_preconditioning=*/true))
            .solve(Operator{op}, y, rhs, Operator{prec});
      }
    catch (const SolverControl::NoConvergence &failure)
      {
        // Explain the likely causes in terms of the parameter file: a step
        // operator that is not positive definite, or a tolerance that
        // rounding does not allow.
        std::ostringstream reason;
        reason << (symmetric_operator ? "CG" : "GMRES")
               << " did not converge in " << failure.last_step
               << " iterations (residual " << failure.last_residual
               << "): the step problem on the current pieces is not positive "
                  "definite (the contact law softens more than the body can "
                  "carry, doc/model.md, section 4), or <Tolerance> = "
               << tolerance
               << " in subsection <Active set solver> is below what the "
                  "arithmetic reaches.";
        report.converged = false;
        report.failure   = reason.str();
      }
    // Count the solve and its iterations for the run summary, whether it
    // converged or not.
    report.inner_iterations = control.last_step();
    report.residual         = control.last_value() / scale;
    last_log_factor
      = (control.last_step() > 0 && control.initial_value() > 0
         && control.last_value() > 0)
          ? std::log(control.last_value() / control.initial_value())
              / control.last_step()
          : 0.;
    ++this->counts.solves;
    this->counts.inner_iterations += control.last_step();
    return report;
  }



  // @sect4{FullSpaceContactSolver::solve_for_pieces}
  //
  // One active-set iteration's linear solve, in four steps: collect what the
  // pieces and friction states of this rank's nodes contribute (the
  // prescribed displacements u_0, the loads and stiffnesses of the free
  // directions, collect_node_terms()); set up the projected operator and
  // preconditioner as functions (projected(), step_operator(),
  // step_preconditioner()); solve for y from the previous iterate; read the
  // nodes' displacements and forces off the solution (read_off_contact()).
  //
  // Everything node-wise touches only locally owned entries (a node's dofs
  // belong to its owner), so no communication happens outside the matrix
  // products, the preconditioner and the Krylov method's inner products.
  template <int dim>
  LinearSolveReport
  FullSpaceContactSolver<dim>::solve_for_pieces(
    ContactSet<dim>          &contact,
    VectorType               &u,
    const LinearSolveRequest &request)
  {
    VectorType u0, A_u0, step_rhs(b);
    u0.reinit(b);         // zero
    A_u0.reinit(b, true); // overwritten by the products below
    collect_node_terms(contact, u0, step_rhs);
    // step_rhs = b - sum f v - A u_0: the prescribed part of u moves to the
    // right-hand side.
    apply_operator(A_u0, u0);
    // The scale of the tolerance: the largest of the loads b, of the nodes'
    // loads and of A u_0. A body loaded through the obstacle alone (an
    // indenter moving in, with no other load) has b = 0, and its load is
    // the normal displacement the obstacle prescribes at the fixed nodes.
    VectorType node_loads(step_rhs);
    node_loads -= b;
    const double node_load_norm = node_loads.l2_norm();
    const double reference_norm
      = std::max({b_norm, node_load_norm, A_u0.l2_norm()});
    step_rhs -= A_u0;
    // A coupled direction of a node whose normal is fixed: its force is
    // coupling times the normal force z = w_0.(b - A u)_i, w_0 the dual row
    // of the normal, so its equation becomes (A u)_d - coupling
    // w_0.(A u)_i = b_d - value - coupling w_0.b_i (w_0 removes the other
    // loads of the node).
    for (unsigned int i = 0; i < contact.size(); ++i)
      for_each_coupled_fixed_normal(i, [&](const unsigned int k) {
        contact.add_to_node(step_rhs,
                            i,
                            terms[i].rows[k],
                            -terms[i].directions.direction[k].coupling
                              * contact.node_component(step_rhs,
                                                       i,
                                                       terms[i].duals[0]));
      });

    const Apply preconditioner = step_preconditioner(contact);
    // With a projected right-hand side and start, every Krylov iterate keeps
    // zero fixed components.
    remove_fixed_rows(contact, step_rhs);
    // The warm start: the previous iterate, constraints removed.
    remove_fixed_rows(contact, u);
    // A Coulomb node that slips couples its tangential force to its normal
    // one: the operator is then unsymmetric on every rank (GMRES).
    const bool coupled
      = Utilities::MPI::max(has_coupling() ? 1 : 0, communicator) == 1;
    // The residual b - A u equals the nodes' forces, sum over directions of
    // force times row (a contact force acts on its node's dofs only).
    VectorType &residual = A_u0; // its value is no longer needed
    const auto  read_off = [&](const VectorType &u) {
      apply_operator(residual, u);
      residual.sadd(-1., 1., b);
      read_off_contact(contact, u, residual);
    };
    // Going on past an early accuracy: the nodes are asked with (r, z) of
    // u_0 + y.
    Continuation continuation;
    if (request.pieces_stay)
      continuation = {request.settled_accuracy, [&](const VectorType &y) {
                        VectorType trial(y);
                        trial += u0;
                        read_off(trial);
                        return request.pieces_stay();
                      }};
    const LinearSolveReport report = krylov_solve(
      projected(step_operator(contact), operator_scratch, contact),
      projected(preconditioner, preconditioner_scratch, contact),
      u,
      step_rhs,
      reference_norm,
      request.accuracy,
      symmetric && !coupled,
      continuation);
    if (!matrix_free && !factorization)
      record_contact_amg_solve(report);
    // u = u_0 + y: now u has the prescribed values along the fixed rows.
    u += u0;
    // A failed solve leaves the nodes as they were; ContactNodes::solve()
    // stops on the report.
    if (!report.converged)
      return report;
    read_off(u);
    return report;
  }



  // @sect4{FullSpaceContactSolver::collect_node_terms}
  //
  // Per node: its directions, their rows and dual rows; the fixed directions
  // with their prescribed values beta give u_0 = sum beta_k w_k on the
  // node's dofs (for a single unit row, beta v) and an orthonormal basis of
  // their rows' span (Gram-Schmidt), which P removes; a free direction adds
  // its load -f v to the right-hand side (its stiffness goes into
  // step_operator()).
  template <int dim>
  void
  FullSpaceContactSolver<dim>::collect_node_terms(
    const ContactSet<dim> &contact,
    VectorType            &u0,
    VectorType            &step_rhs)
  {
    terms.resize(contact.size());
    for (unsigned int i = 0; i < contact.size(); ++i)
      {
        NodeTerms &node = terms[i];
        node.directions = contact.directions(i, contact.gap(i));
        node.n_fixed    = 0;
        for (unsigned int k = 0; k < node.directions.size; ++k)
          {
            const NodeDirection &direction = node.directions.direction[k];
            node.rows[k] = contact.frame_row(i, direction.frame);
            if (direction.fixed)
              node.fixed_directions[node.n_fixed++] = k;
            else
              {
                // A coupled direction with a free normal: coupling times
                // the normal's load too.
                const NodeDirection &normal = node.directions.direction[0];
                const double         load
                  = direction.value
                    + (normal.fixed ? 0. : direction.coupling * normal.value);
                if (load != 0)
                  contact.add_to_node(step_rhs, i, node.rows[k], -load);
              }
          }
        // The dual rows, (V V^T)^{-1} V for the rows V of all directions
        // (independent: the directions are orthonormal in the span of the
        // node's free dofs, and their rows are their images there).
        FullMatrix<double> all_gram(node.directions.size, node.directions.size);
        for (unsigned int a = 0; a < node.directions.size; ++a)
          for (unsigned int c = 0; c < node.directions.size; ++c)
            all_gram(a, c) = node.rows[a] * node.rows[c];
        all_gram.gauss_jordan();
        for (unsigned int a = 0; a < node.directions.size; ++a)
          {
            node.duals[a] = Tensor<1, dim>();
            for (unsigned int c = 0; c < node.directions.size; ++c)
              node.duals[a] += all_gram(a, c) * node.rows[c];
          }
        // u_0 = sum beta_k w_k over the fixed directions: v_k . u_0 = beta_k
        // there (and 0 along the free ones), and the orthonormal basis of the
        // fixed rows that P removes.
        for (unsigned int a = 0; a < node.n_fixed; ++a)
          {
            const unsigned int k = node.fixed_directions[a];
            contact.add_to_node(u0,
                                i,
                                node.duals[k],
                                node.directions.direction[k].value);
            Tensor<1, dim> q = node.rows[k];
            for (unsigned int c = 0; c < a; ++c)
              q -= (q * node.fixed_basis[c]) * node.fixed_basis[c];
            node.fixed_basis[a] = q / q.norm();
          }
      }
  }



  template <int dim>
  bool
  FullSpaceContactSolver<dim>::has_coupling() const
  {
    for (const NodeTerms &node : terms)
      for (unsigned int k = 1; k < node.directions.size; ++k)
        if (!node.directions.direction[k].fixed
            && node.directions.direction[k].coupling != 0)
          return true;
    return false;
  }



  // @sect4{FullSpaceContactSolver::remove_fixed_rows}
  //
  // P v: remove the fixed rows at every node, v -= (q . v) q for every
  // vector q of the node's orthonormal basis of them, and the identity
  // elsewhere.
  template <int dim>
  void
  FullSpaceContactSolver<dim>::remove_fixed_rows(const ContactSet<dim> &contact,
                                                 VectorType            &v) const
  {
    for (unsigned int i = 0; i < contact.size(); ++i)
      for (unsigned int a = 0; a < terms[i].n_fixed; ++a)
        {
          const Tensor<1, dim> &q = terms[i].fixed_basis[a];
          contact.add_to_node(v, i, q, -contact.node_component(v, i, q));
        }
  }



  // @sect4{FullSpaceContactSolver::collect_stiff_rows}
  //
  // The AMG knows the stiffness of the free directions of its set-up only,
  // and it is not rebuilt when a node changes its stick/slip state or its
  // slope. A direction that has become stiff since is to its cycle a free
  // one, and its correction there is off by the ratio of the stiffness to
  // the body's, as it would be along a fixed direction: a node that starts
  // to slip in 3D gets a transverse stiffness of up to 100 times its own
  // (the Newton linearisation of its slip direction, ContactNodes::
  // set_slip_direction()). So the coarse correction leaves out every free
  // direction whose stiffness k is at least A's diagonal along it while
  // the AMG's matrix holds less than half of k along it
  // (contact_amg_stiffness; the coarser levels of the matrix-free V-cycle
  // are K's and hold none), as it leaves out the fixed ones, and the
  // smoothing, whose Jacobi step has k on its diagonal, corrects them
  // alone; a spring stiffer than the body holds its node nearly in place,
  // so there is little for the coarse levels to carry. The directions the
  // AMG knows stay in its correction: the stiff cohesive interface of
  // cohesive_peel_3d.prm, which an AMG of one level solves exactly, took
  // 427 Krylov iterations instead of 107 without them. P Q C Q P with the
  // projection Q is symmetric, so CG still applies. Measured with Method = full
  // space, one rank (Krylov iterations over the run, before and after): the 3D
  // sliding block at N = 24 264 and 194, the frictional cube 256 and 229,
  // pad_on_base_mixed_3d.prm 712 and 520; the frictionless scenes, whose
  // free directions are softer than the body, unchanged (doc/performance.md,
  // "The full space back end"). Any threshold from 0.1 to 3 times the
  // diagonal did as well.
  template <int dim>
  void
  FullSpaceContactSolver<dim>::collect_stiff_rows(
    const ContactSet<dim> &contact)
  {
    stiff_rows.clear();
    // On every rank alike, whether it has stiff directions or not: the
    // diagonal is computed at its first use, which may communicate.
    const VectorType &diagonal_entries = diagonal();
    for (unsigned int i = 0; i < contact.size(); ++i)
      for_each_stiff_direction(i, [&](const unsigned int k) {
        // The row without its part along the fixed rows and the node's
        // stiff rows before it (on an oblique plane of symmetry the rows are
        // not orthogonal), as a unit vector.
        Tensor<1, dim> q = terms[i].rows[k];
        for (unsigned int a = 0; a < terms[i].n_fixed; ++a)
          q -= (q * terms[i].fixed_basis[a]) * terms[i].fixed_basis[a];
        for (auto row = stiff_rows.rbegin();
             row != stiff_rows.rend() && row->first == i;
             ++row)
          q -= (q * row->second) * row->second;
        const double norm = q.norm();
        if (norm <= 1e-8 * terms[i].rows[k].norm())
          return;
        q /= norm;
        Tensor<1, dim> squares;
        for (unsigned int c = 0; c < dim; ++c)
          squares[c] = q[c] * q[c];
        const double stiffness = terms[i].directions.direction[k].stiffness;
        const double held
          = matrix_free ? 0. : q * (contact_amg_stiffness[i] * q);
        if (stiffness >= contact.node_component(diagonal_entries, i, squares)
            && held < 0.5 * stiffness)
          stiff_rows.emplace_back(i, q);
      });
  }



  // From the matrix or the matrix-free operator.
  template <int dim>
  const VectorType &
  FullSpaceContactSolver<dim>::diagonal()
  {
    if (diagonal_of_A.size() == 0)
      {
        if (matrix_free)
          diagonal_of_A = matrix_free->diagonal();
        else
          {
            diagonal_of_A.reinit(b, true);
            for (const auto row : b.get_partitioner()->locally_owned_range())
              diagonal_of_A(row) = A->diag_element(row);
          }
      }
    return diagonal_of_A;
  }



  template <int dim>
  void
  FullSpaceContactSolver<dim>::remove_stiff_rows(const ContactSet<dim> &contact,
                                                 VectorType            &v) const
  {
    for (const auto &[i, q] : stiff_rows)
      contact.add_to_node(v, i, q, -contact.node_component(v, i, q));
  }



  // @sect4{FullSpaceContactSolver::projected}
  //
  // v -> P inner(P v) + (I - P) v, for the operator and the preconditioner
  // alike, with projected_src as work vector. The last term puts the fixed
  // components of v back unchanged, which keeps the operator nonsingular;
  // P and I - P are symmetric, so the result is symmetric whenever inner
  // is. The function keeps references to its arguments except inner, which
  // it copies.
  template <int dim>
  typename FullSpaceContactSolver<dim>::Apply
  FullSpaceContactSolver<dim>::projected(const Apply           &inner,
                                         VectorType            &projected_src,
                                         const ContactSet<dim> &contact) const
  {
    return [this, inner, &projected_src, &contact](VectorType       &dst,
                                                   const VectorType &src) {
      projected_src = src;
      remove_fixed_rows(contact, projected_src);
      inner(dst, projected_src);
      remove_fixed_rows(contact, dst);
      for (unsigned int i = 0; i < contact.size(); ++i)
        for (unsigned int a = 0; a < terms[i].n_fixed; ++a)
          {
            const Tensor<1, dim> &q = terms[i].fixed_basis[a];
            contact.add_to_node(dst, i, q, contact.node_component(src, i, q));
          }
    };
  }



  // @sect4{FullSpaceContactSolver::step_operator}
  //
  // A + sum k v v^T over the free directions with a stiffness, applied
  // without forming it: the matrix A stays that of set_operator() for every
  // set of pieces.
  template <int dim>
  typename FullSpaceContactSolver<dim>::Apply
  FullSpaceContactSolver<dim>::step_operator(
    const ContactSet<dim> &contact) const
  {
    return [this, &contact](VectorType &dst, const VectorType &src) {
      apply_operator(dst, src);
      // The coupled directions (collect_node_terms(), solve_for_pieces()):
      // -coupling w_0.(A src)_i where the normal is fixed, coupling times
      // the normal stiffness times n.src where it is free.
      for (unsigned int i = 0; i < contact.size(); ++i)
        for (unsigned int k = 1; k < terms[i].directions.size; ++k)
          {
            const NodeDirection &normal    = terms[i].directions.direction[0];
            const NodeDirection &direction = terms[i].directions.direction[k];
            if (direction.fixed || direction.coupling == 0)
              continue;
            const Tensor<1, dim> &n = terms[i].rows[0];
            const double          normal_force
              = (normal.fixed
                   ? -contact.node_component(dst, i, terms[i].duals[0])
                   : normal.stiffness * contact.node_component(src, i, n));
            contact.add_to_node(dst,
                                i,
                                terms[i].rows[k],
                                direction.coupling * normal_force);
          }
      for (unsigned int i = 0; i < contact.size(); ++i)
        for_each_stiff_direction(i, [&](const unsigned int k) {
          contact.add_to_node(dst,
                              i,
                              terms[i].rows[k],
                              terms[i].directions.direction[k].stiffness
                                * contact.node_component(src,
                                                         i,
                                                         terms[i].rows[k]));
        });
    };
  }



  // @sect4{FullSpaceContactSolver::step_preconditioner}
  //
  // The preconditioner: the factorisation of A, or the AMG of the step
  // operator of (nearly) these terms (update_contact_amg() removes the
  // fixed directions) inside a smoothing of the projected step operator of
  // exactly these terms (a symmetric A; the implicit update's tangent gets
  // the AMG alone), or the matrix-free V-cycle whose finest level smooths
  // that operator. Collective when it updates the AMG.
  template <int dim>
  typename FullSpaceContactSolver<dim>::Apply
  FullSpaceContactSolver<dim>::step_preconditioner(
    const ContactSet<dim> &contact)
  {
    // The matrix-free V-cycle smooths the projected step operator on the
    // program's mesh (in the basis of contact pairs it stays K's).
    if (matrix_free && !basis)
      {
        matrix_free->constrain(constrained_operator(contact));
        return [this](VectorType &dst, const VectorType &src) {
          matrix_free->precondition_constrained(dst, src);
        };
      }
    if (matrix_free)
      return [this](VectorType &dst, const VectorType &src) {
        precondition_matrix_free(dst, src);
      };
    if (factorization)
      return [this](VectorType &dst, const VectorType &src) {
        factorization->solve(dst, src);
      };
    update_contact_amg(contact);
    if (!symmetric)
      return [this](VectorType &dst, const VectorType &src) {
        contact_amg.vmult(dst, src);
      };
    // Smoothing of the projected step operator around the AMG's cycle
    // (constrained_smoothing.h), with A's eigenvalue bound, estimated once
    // per operator. It is the finest level's smoothing: the AMG has none
    // there. ML's own Chebyshev sweeps on that level knew only the fixed
    // directions of the AMG's set-up and took four more products with A
    // per cycle. Without them (by hand, Tolerance 1e-10, one rank): the
    // cube's first 8 steps at 108k dofs took the same 190 CG iterations on
    // hexahedra, 307 against 289 on tetrahedra, the Hertz sphere's static
    // step at 108k dofs 115 against 90, and the contact problem 28%, 24%
    // and 17% less time. A smoothing of degree 3 here took fewer
    // iterations (86 on the Hertz sphere) but more time.
    if (!smoothing_ready)
      {
        smoothing.initialize(
          [this](VectorType &dst, const VectorType &src) {
            apply_operator(dst, src);
          },
          diagonal());
        smoothing_ready = true;
      }
    smoothing.constrain(constrained_operator(contact));
    return [this, &contact](VectorType &dst, const VectorType &src) {
      smoothing.vmult(dst,
                      src,
                      [this, &contact](VectorType &x, const VectorType &r) {
                        contact_amg.vmult(x, r);
                        remove_fixed_rows(contact, x);
                      });
    };
  }



  // @sect4{FullSpaceContactSolver::constrained_operator}
  //
  // The projected step operator of the current terms for the smoothing of
  // the preconditioners (constrained_smoothing.h): its product, P, the
  // stiffness k v_j^2 of the free directions on the diagonal, and the
  // removal of the stiff ones that the coarse correction does not know.
  template <int dim>
  ConstrainedOperator
  FullSpaceContactSolver<dim>::constrained_operator(
    const ContactSet<dim> &contact)
  {
    if (smoother_scratch.size() != b.size())
      smoother_scratch.reinit(b);
    collect_stiff_rows(contact);
    return {projected(step_operator(contact), smoother_scratch, contact),
            [this, &contact](VectorType &v) { remove_fixed_rows(contact, v); },
            [this, &contact](VectorType &diagonal) {
              for (unsigned int i = 0; i < contact.size(); ++i)
                for_each_stiff_direction(i, [&](const unsigned int k) {
                  Tensor<1, dim> squares;
                  for (unsigned int c = 0; c < dim; ++c)
                    squares[c] = terms[i].rows[k][c] * terms[i].rows[k][c];
                  contact.add_to_node(
                    diagonal,
                    i,
                    squares,
                    terms[i].directions.direction[k].stiffness);
                });
            },
            [this, &contact](VectorType &v) { remove_stiff_rows(contact, v); }};
  }



  // @sect4{FullSpaceContactSolver::read_off_contact}
  //
  // The displacement v . u along every direction; along the fixed ones the
  // forces w . (b - A u)_i from the residual, w their dual rows (the free
  // directions' forces follow from their law, ContactNodes::store_solution).
  template <int dim>
  void
  FullSpaceContactSolver<dim>::read_off_contact(
    ContactSet<dim>  &contact,
    const VectorType &u,
    const VectorType &residual) const
  {
    for (unsigned int i = 0; i < contact.size(); ++i)
      {
        const NodeTerms      &node          = terms[i];
        std::array<double, 3> displacements = {{0, 0, 0}}, forces = {{0, 0, 0}};
        for (unsigned int k = 0; k < node.directions.size; ++k)
          displacements[k] = contact.node_component(u, i, node.rows[k]);
        for (unsigned int a = 0; a < node.n_fixed; ++a)
          {
            const unsigned int k = node.fixed_directions[a];
            forces[k] = contact.node_component(residual, i, node.duals[k]);
          }
        contact.store_solution(i,
                               contact.gap(i),
                               node.directions,
                               displacements.data(),
                               forces.data());
      }
  }



  // @sect4{FullSpaceContactSolver::finish}
  //
  // Nothing to do: the last solve_for_pieces() left the displacement of the
  // final pieces in u.
  template <int dim>
  void
  FullSpaceContactSolver<dim>::finish(const ContactSet<dim> &, VectorType &)
  {}



  // A src, with the matrix or without.
  template <int dim>
  void
  FullSpaceContactSolver<dim>::apply_operator(VectorType       &dst,
                                              const VectorType &src) const
  {
    if (matrix_free && basis)
      {
        basis->vmult(basis_scratch, src);
        matrix_free->vmult(basis_result, basis_scratch);
        basis->Tvmult(dst, basis_result);
      }
    else if (matrix_free)
      matrix_free->vmult(dst, src);
    else
      A->vmult(dst, src);
  }



  template <int dim>
  void
  FullSpaceContactSolver<dim>::work_in_basis(const MatrixType &T)
  {
    basis = &T;
    basis_modes.reset();
    if (matrix_free_data)
      {
        basis_scratch.reinit(b);
        basis_result.reinit(b);
      }
  }



  template <int dim>
  const Epetra_MultiVector &
  FullSpaceContactSolver<dim>::near_null_space() const
  {
    return basis_modes ? *basis_modes : *rigid_body_modes.modes;
  }



  template <int dim>
  void
  FullSpaceContactSolver<dim>::precondition_matrix_free(
    VectorType       &dst,
    const VectorType &src) const
  {
    if (!basis)
      {
        matrix_free->precondition(dst, src);
        return;
      }
    // T^{-T} src = 2 src - T^T src, M^{-1}, then T^{-1} = 2 I - T.
    basis->Tvmult(basis_scratch, src);
    basis_scratch.sadd(-1., 2., src);
    matrix_free->precondition(basis_result, basis_scratch);
    basis->vmult(dst, basis_result);
    dst.sadd(-1., 2., basis_result);
  }



  // @sect4{FullSpaceContactSolver::solve_without_contact}
  //
  // A^{-1} b by the same Krylov method and preconditioner, from a zero
  // start: the step problem of a scene without contact, the reference solve
  // of the cost measurements, and the inner solve of apply_compliance().
  template <int dim>
  LinearSolveReport
  FullSpaceContactSolver<dim>::solve_without_contact(const VectorType &rhs,
                                                     VectorType       &u)
  {
    const Apply op = [&](VectorType &dst, const VectorType &src) {
      apply_operator(dst, src);
    };
    Apply prec;
    if (matrix_free)
      prec = [&](VectorType &dst, const VectorType &src) {
        precondition_matrix_free(dst, src);
      };
    else if (factorization)
      prec = [&](VectorType &dst, const VectorType &src) {
        factorization->solve(dst, src);
      };
    else
      {
        if (!operator_amg_built)
          {
            build_amg(A->trilinos_matrix(), near_null_space(), operator_amg);
            operator_amg_built = true;
            ++this->counts.operator_setups;
          }
        prec = [&](VectorType &dst, const VectorType &src) {
          operator_amg.vmult(dst, src);
        };
      }
    u = 0;
    return krylov_solve(op, prec, u, rhs, rhs.l2_norm(), tolerance, symmetric);
  }



  // @sect4{FullSpaceContactSolver::apply_compliance}
  //
  // y = N A^{-1} N^T x without the matrix S: put the forces x_i nu_i on this
  // rank's contact nodes, solve once with A, and read off the normal
  // displacements. One Krylov solve per product is what a Lanczos step of
  // the uniqueness test costs on this back end (doc/model.md, section 4).
  template <int dim>
  void
  FullSpaceContactSolver<dim>::apply_compliance(const ContactSet<dim> &contact,
                                                const Vector<double>  &x,
                                                Vector<double>        &y)
  {
    // The node's normal row on its own dofs (the frame's first direction):
    // the rows of contact pairs are nodal in the basis the back end then
    // works in (dual_mortar_basis.h).
    VectorType forces(b), response(b);
    forces = 0;
    for (unsigned int i = 0; i < contact.size(); ++i)
      contact.add_to_node(forces, i, contact.frame_row(i, {{1, 0, 0}}), x[i]);
    solve_without_contact(forces, response);
    y.reinit(contact.size());
    for (unsigned int i = 0; i < contact.size(); ++i)
      y[i] = contact.node_component(response,
                                    i,
                                    contact.frame_row(i, {{1, 0, 0}}));
  }



  // @sect4{The factory}
  //
  // The class is only known in this file; create_contact_solver()
  // (contact_solver.cc) reaches its constructor through this function.
  template <int dim>
  std::unique_ptr<ContactSolver<dim>>
  create_full_space_contact_solver(
    const Parameters::AllParameters  &parameters,
    const hp::MappingCollection<dim> &mapping,
    const DoFHandler<dim>            &dof_handler,
    const VectorType                 &layout,
    const ElasticOperatorData<dim>   *matrix_free_data)
  {
    return std::make_unique<FullSpaceContactSolver<dim>>(parameters,
                                                         mapping,
                                                         dof_handler,
                                                         layout,
                                                         matrix_free_data);
  }

  template std::unique_ptr<ContactSolver<2>>
  create_full_space_contact_solver(const Parameters::AllParameters &,
                                   const hp::MappingCollection<2> &,
                                   const DoFHandler<2> &,
                                   const VectorType &,
                                   const ElasticOperatorData<2> *);
  template std::unique_ptr<ContactSolver<3>>
  create_full_space_contact_solver(const Parameters::AllParameters &,
                                   const hp::MappingCollection<3> &,
                                   const DoFHandler<3> &,
                                   const VectorType &,
                                   const ElasticOperatorData<3> *);
} // namespace ViscoContact
