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

#include <deal.II/lac/solver_cg.h>
#include <deal.II/lac/solver_control.h>
#include <deal.II/lac/solver_gmres.h>
#include <deal.II/lac/trilinos_precondition.h>

#include "back_ends/contact_solver.h"
#include "back_ends/direct_solver.h"
#include "back_ends/rigid_body_modes.h"

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

namespace ViscoContact
{
  // @sect3{The full space back end}
  //
  // For fixed pieces, a node on a sloped piece (slope s, intercept o)
  // carries the force w (o + s u.nu), a node on a vertical piece at r = beta
  // has u.nu = beta. With u = u_0 + y, u_0 = beta nu at the fixed nodes, y
  // solves
  //   (P (A + sum_i w_i s_i nu_i nu_i^T) P + (I - P)) y
  //     = P (b - sum_i w_i o_i nu_i - A u_0),
  // P the orthogonal projection that removes the normal component at the
  // fixed nodes (a constraint among the components of a node, for any
  // normal). The operator is applied around A, which never changes within a
  // step problem; the preconditioner P M^{-1} P + (I - P) uses an AMG cycle
  // of the step operator (its matrix with the fixed nodes' normal
  // directions removed, rebuilt when enough nodes have changed,
  // update_contact_amg()) or the factorisation
  // M^{-1} of A built by set_operator(). Both are
  // symmetric when A is, and positive definite as long as the uniqueness
  // condition (doc/model.md, section 4) holds: CG then; GMRES for the
  // implicit update's unsymmetric tangent. The forces at the fixed nodes are
  // read off the residual, z_i = nu_i . (b - A u)_i. Here nu_i is the node's
  // row n_i of N; on an oblique plane of symmetry |n_i| != 1, so the
  // projections and u_0 divide by |n_i|^2 (doc/model.md, section 2).
  //
  // Why this form: the sloped pieces only add a rank-one term per node and
  // the vertical pieces only remove one direction per node, so neither the
  // matrix A nor its preconditioner has to be rebuilt when a node changes
  // its piece. The contact terms are applied on the fly, and the block I - P
  // keeps the operator nonsingular while leaving the removed components of y
  // at zero.
  template <int dim>
  class FullSpaceContactSolver : public ContactSolver<dim>
  {
  public:
    FullSpaceContactSolver(const Parameters::AllParameters &parameters,
                           const Mapping<dim>              &mapping,
                           const DoFHandler<dim>           &dof_handler,
                           const VectorType                &layout);

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
    solve_for_pieces(ContactSet<dim> &contact,
                     VectorType      &u,
                     const double     accuracy) override;
    void
    set_right_hand_side(const VectorType      &b,
                        const ContactSet<dim> &contact) override;
    void
    finish(const ContactSet<dim> &contact, VectorType &u) override;
    std::optional<std::vector<double>>
    checkpoint_state() const override;
    void
    restore_checkpoint_state(const ContactSet<dim>     &contact,
                             const std::vector<double> &state) override;

  private:
    using Apply = std::function<void(VectorType &, const VectorType &)>;

    // The six (three in 2D) rigid-body modes at the locally owned rows.
    void
    compute_rigid_body_modes(const Epetra_Map &row_map);
    void
    build_amg(const Epetra_CrsMatrix            &matrix,
              const Epetra_MultiVector          &null_space,
              TrilinosWrappers::PreconditionAMG &amg);
    // The AMG of the step operator of the current pieces, rebuilt when
    // enough nodes have changed their stiffness since it was last built.
    void
    update_contact_amg(const ContactSet<dim>     &contact,
                       const std::vector<double> &stiffness);
    // Whether the AMG built last still serves these stiffnesses: at most 1%
    // of the contact nodes (over all ranks) fixed or free since. Collective.
    bool
    contact_amg_fits(const ContactSet<dim>     &contact,
                     const std::vector<double> &stiffness) const;
    // The matrix of the step operator of these stiffnesses, the fixed
    // nodes' normal directions removed, into contact_matrix (after
    // releasing the AMG built on the previous one).
    void
    assemble_contact_matrix(const ContactSet<dim>     &contact,
                            const std::vector<double> &stiffness);
    // The last step of that matrix: the rows of the fixed nodes lose their
    // normal part, which comes back on their diagonal blocks.
    void
    project_fixed_rows(Epetra_CrsMatrix          &matrix,
                       const ContactSet<dim>     &contact,
                       const std::vector<double> &stiffness) const;
    // The rigid-body modes without their normal components at the fixed
    // nodes, into contact_modes.
    void
    project_rigid_body_modes(const ContactSet<dim>     &contact,
                             const std::vector<double> &stiffness);

    // What the pieces of this rank's nodes add to the step problem: which
    // nodes are fixed, the normal stiffness of the others, the prescribed
    // displacement u0 and the loads, into step_rhs.
    void
    collect_piece_terms(const ContactSet<dim> &contact,
                        std::vector<bool>     &fixed,
                        std::vector<double>   &normal_stiffness,
                        VectorType            &u0,
                        VectorType            &step_rhs) const;
    // P v: v without its normal components at the fixed nodes.
    void
    remove_fixed_normals(const ContactSet<dim>   &contact,
                         const std::vector<bool> &fixed,
                         VectorType              &v) const;
    // v -> P inner(P v) + (I - P) v, with the work vector projected_src.
    // The function refers to all arguments but inner, which it copies.
    Apply
    projected(const Apply             &inner,
              VectorType              &projected_src,
              const ContactSet<dim>   &contact,
              const std::vector<bool> &fixed) const;
    // v -> (A + sum_i w_i s_i nu_i nu_i^T) v; refers to its arguments.
    Apply
    step_operator(const ContactSet<dim>     &contact,
                  const std::vector<double> &normal_stiffness) const;
    // The factorisation of A, or the AMG of the step operator of these
    // pieces, updated here (collective).
    Apply
    step_preconditioner(const ContactSet<dim>     &contact,
                        const std::vector<bool>   &fixed,
                        const std::vector<double> &normal_stiffness);
    // r_i and z_i of every node from the solution u and the residual
    // b - A u.
    void
    read_off_contact(ContactSet<dim>  &contact,
                     const VectorType &u,
                     const VectorType &residual) const;
    // Solves op y = rhs from the initial y with the preconditioner prec:
    // CG or GMRES to the relative accuracy (Tolerance unless the active-set
    // iteration asks for less) times reference_norm.
    LinearSolveReport
    krylov_solve(const Apply      &op,
                 const Apply      &prec,
                 VectorType       &y,
                 const VectorType &rhs,
                 const double      reference_norm,
                 const double      accuracy);

    // Preconditioner (subsection Linear solver), Tolerance (subsection
    // Active set solver), and what the AMG needs to build the rigid-body
    // modes.
    const Parameters::Preconditioner preconditioner_type;
    const double                     tolerance;
    const MPI_Comm                   communicator;
    const Mapping<dim>              &mapping;
    const DoFHandler<dim>           &dof_handler;

    // The operator of the current step problems (owned by the caller: the
    // elastic matrix or the current tangent), whether it is symmetric (which
    // decides between CG and GMRES), the factorisation when Preconditioner =
    // direct, and the right-hand side of the current step problem.
    const MatrixType                   *A         = nullptr;
    bool                                symmetric = true;
    std::unique_ptr<Epetra_MultiVector> rigid_body_modes;
    bool node_blocks = true; // a vertex's dim dofs are consecutive rows
    std::optional<SparseDirectSolver> factorization;
    VectorType                        b;
    double                            b_norm = 0;

    // The two AMG preconditioners, each built when first needed after
    // set_operator(): one of A alone, for the solves without contact, and
    // one of the step operator of the pieces the nodes were on when it was
    // built (update_contact_amg()), held in contact_matrix with its near-null
    // space contact_modes. contact_amg_stiffness keeps the normal stiffness
    // of this rank's nodes it was built for (infinite at fixed nodes), to
    // tell how many nodes have changed since.
    TrilinosWrappers::PreconditionAMG   operator_amg, contact_amg;
    bool                                operator_amg_built = false;
    bool                                contact_amg_built  = false;
    std::unique_ptr<Epetra_CrsMatrix>   contact_matrix;
    std::unique_ptr<Epetra_MultiVector> contact_modes;
    std::vector<double>                 contact_amg_stiffness;

    // Work vectors of the projected operator and preconditioner, which the
    // Krylov method applies once per iteration each: allocated once here
    // instead of once per application.
    VectorType operator_scratch, preconditioner_scratch;
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
    const Parameters::AllParameters &parameters,
    const Mapping<dim>              &mapping,
    const DoFHandler<dim>           &dof_handler,
    const VectorType                &layout)
    : preconditioner_type(parameters.preconditioner)
    , tolerance(parameters.tolerance)
    , communicator(layout.get_mpi_communicator())
    , mapping(mapping)
    , dof_handler(dof_handler)
    , b(layout)
    , operator_scratch(layout)
    , preconditioner_scratch(layout)
  {
    if (preconditioner_type == Parameters::Preconditioner::direct)
      factorization.emplace(parameters.direct_solver, communicator);
  }



  // The line for the run's header: the Krylov method and its preconditioner.
  template <int dim>
  std::string
  FullSpaceContactSolver<dim>::description() const
  {
    return std::string("full space: CG (GMRES for the implicit update's "
                       "tangent) on the projected operator, preconditioned by ")
           + (factorization ? factorization->description()
                            : "ML AMG of the step operator with the "
                              "rigid-body modes");
  }



  // @sect4{FullSpaceContactSolver::compute_rigid_body_modes}
  //
  // Elasticity needs the near-null space of the operator without Dirichlet
  // conditions, the dim translations and the dim(dim-1)/2 infinitesimal
  // rotations, given to ML per locally owned dof (deal.II 9.4's
  // AdditionalData only takes translations, so the parameter list is
  // completed by hand in build_amg()). Smoothed aggregation builds its
  // coarse spaces from these modes; with the translations alone they could
  // not represent the rotations of parts of the body, the low-energy modes
  // of elasticity. The modes depend on the mesh and the dofs only, not on
  // the operator, so they are computed once and reused for every operator.
  template <int dim>
  void
  FullSpaceContactSolver<dim>::compute_rigid_body_modes(
    const Epetra_Map &row_map)
  {
    // The location of every dof, and which vector component each locally
    // owned dof belongs to.
    std::map<types::global_dof_index, Point<dim>> support_points;
    DoFTools::map_dofs_to_support_points(mapping, dof_handler, support_points);
    std::vector<IndexSet> component_dofs(dim);
    for (unsigned int c = 0; c < dim; ++c)
      component_dofs[c]
        = DoFTools::extract_dofs(dof_handler,
                                 dof_handler.get_fe().component_mask(
                                   FEValuesExtractors::Scalar(c)));
    // Three modes in 2D (two translations, one rotation), six in 3D, laid
    // out like the rows of the matrix, so that ML can read them next to it.
    const unsigned int n_modes = (dim == 2 ? 3 : 6);
    rigid_body_modes = std::make_unique<Epetra_MultiVector>(row_map, n_modes);
    // Per locally owned row: find its component c, then write component c
    // of each mode at the row's support point x.
    for (int local = 0; local < row_map.NumMyElements(); ++local)
      {
        const types::global_dof_index dof = row_map.GID64(local);
        unsigned int                  c   = 0;
        while (c < dim && !component_dofs[c].is_element(dof))
          ++c;
        Assert(c < dim, ExcInternalError());
        const Point<dim> &x     = support_points.at(dof);
        const auto        modes = rigid_body_mode_components(c, x);
        for (unsigned int mode = 0; mode < modes.size(); ++mode)
          (*rigid_body_modes)[mode][local] = modes[mode];
        // Rows in blocks of dim, one block per vertex, in component order:
        // what "PDE equations" = dim assumes in build_amg().
        if (c != static_cast<unsigned int>(local) % dim)
          node_blocks = false;
      }
    // Every rank must give ML the same number of PDE equations.
    node_blocks = (Utilities::MPI::min(node_blocks ? 1 : 0, communicator) == 1);
  }



  // @sect4{FullSpaceContactSolver::build_amg}
  //
  // The AMG settings: ML's defaults for elliptic (symmetric) or for
  // nonsymmetric problems, linear elements, Chebyshev smoothing of degree 2,
  // Amesos-KLU on the coarsest level, and two more settings that make the
  // iteration counts (nearly) independent of the mesh, measured by
  // benchmarks/run_preconditioner_comparison.py (doc/performance.md,
  // "Preconditioners"):
  //  - aggregation threshold 0 (it was 0.02): every matrix entry counts as a
  //    connection when ML forms its aggregates. With 0.02 CG took 18, 32, 45
  //    iterations for the cube's elastic solve on hexahedra at 15k, 108k,
  //    824k dofs (23, 34, 53 on tetrahedra); with these two settings 16, 20,
  //    21 (24, 33, 36);
  //  - "PDE equations" = dim: ML aggregates nodes, the dim dofs of a vertex
  //    together, as the rigid-body modes need (deal.II 9.4's AdditionalData
  //    leaves ML's default, 1: every dof its own node). A vertex's dofs are
  //    consecutive in deal.II's numbering of the vector-valued Q1/P1
  //    element; node_blocks, computed with the modes, checks it, and if it
  //    did not hold ML would aggregate dofs.
  // Chebyshev degree 3 or 4 and symmetric Gauss-Seidel took fewer iterations
  // but not less time, a smoother as coarse solver more iterations. An
  // unsymmetric tangent gets ML's settings for nonsymmetric problems.
  template <int dim>
  void
  FullSpaceContactSolver<dim>::build_amg(const Epetra_CrsMatrix   &matrix,
                                         const Epetra_MultiVector &null_space,
                                         TrilinosWrappers::PreconditionAMG &amg)
  {
    TrilinosWrappers::PreconditionAMG::AdditionalData data;
    data.elliptic              = symmetric;
    data.higher_order_elements = false;
    data.smoother_sweeps       = 2;
    data.aggregation_threshold = 0.;
    // Let deal.II translate these settings into ML's parameter list (its
    // constant-mode output is not needed), then replace the null space by
    // the given modes and build the hierarchy.
    Teuchos::ParameterList              ml_parameters;
    std::unique_ptr<Epetra_MultiVector> unused_constant_modes;
    data.set_parameters(ml_parameters, unused_constant_modes, matrix);
    ml_parameters.set("PDE equations", node_blocks ? dim : 1);
    ml_parameters.set("null space: type", "pre-computed");
    ml_parameters.set("null space: dimension", null_space.NumVectors());
    ml_parameters.set("null space: vectors", null_space.Values());
    amg.initialize(matrix, ml_parameters);
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
    A                  = &matrix;
    symmetric          = is_symmetric;
    operator_amg_built = false;
    contact_amg_built  = false;
    if (!factorization && !rigid_body_modes)
      compute_rigid_body_modes(matrix.trilinos_matrix().RowMap());
    if (factorization)
      {
        factorization->factorize(matrix, is_symmetric);
        ++this->counts.operator_setups;
      }
  }



  // @sect4{FullSpaceContactSolver::update_contact_amg}
  //
  // The step operator differs from A by the normal stiffness of the nodes on
  // sloped pieces and, above all, by the nodes on vertical pieces, whose
  // normal displacement is fixed. A preconditioner of A alone treats those
  // as free: with a few hundred fixed nodes, CG needs about twice as many
  // iterations per digit as for A (measured in doc/performance.md). So the
  // AMG is built for the matrix of the projected operator itself,
  //   P (A + sum_i w_i s_i nu_i nu_i^T) P + sum_{i fixed} d_i nu_i nu_i^T,
  // d_i = nu_i^T A_ii nu_i: at a fixed node the normal direction is removed
  // from its rows and columns, as a Dirichlet condition would be, and comes
  // back only on the node's own diagonal block, with the node's stiffness as
  // scale. Its near-null space is P applied to the rigid-body modes, which
  // the constrained operator no longer has in its null space. (Earlier, a
  // penalty 1000 nu^T A_ii nu at the fixed nodes with the unprojected modes
  // took 30% more CG iterations on tetrahedra: the coarse spaces carried the
  // fixed normal components, and the AMG settings had to differ on
  // simplices; doc/performance.md.) Every change touches only entries in
  // the pattern of A: the node's dim x dim blocks, and the columns of its
  // dofs.
  //
  // Building an AMG costs about 20 CG iterations, so it is not rebuilt for
  // every set of pieces: only when more than 1% of the contact nodes (over
  // all ranks) have become fixed or free since it was built (a changed slope
  // matters little, a fixed node much: the slopes are small against the
  // stiffness of the body, measured in doc/performance.md).
  // Within a time step few nodes move, so most steps reuse the AMG of the
  // previous one, while a cold start, where most nodes move, rebuilds it
  // as the pieces change. contact_amg_fits() decides, then
  // assemble_contact_matrix() and project_rigid_body_modes() give the AMG
  // its matrix and near-null space.
  template <int dim>
  void
  FullSpaceContactSolver<dim>::update_contact_amg(
    const ContactSet<dim>     &contact,
    const std::vector<double> &stiffness)
  {
    if (contact_amg_fits(contact, stiffness))
      return;
    assemble_contact_matrix(contact, stiffness);
    project_rigid_body_modes(contact, stiffness);
    build_amg(*contact_matrix, *contact_modes, contact_amg);
    contact_amg_stiffness = stiffness;
    contact_amg_built     = true;
    ++this->counts.operator_setups;
  }



  // @sect4{FullSpaceContactSolver::contact_amg_fits}
  //
  // A node has changed if it has become fixed (infinite stiffness) or free
  // since the AMG was built; a changed slope does not count. Every rank
  // takes part in the sum, whether an AMG has been built or not.
  template <int dim>
  bool
  FullSpaceContactSolver<dim>::contact_amg_fits(
    const ContactSet<dim>     &contact,
    const std::vector<double> &stiffness) const
  {
    unsigned int changed = 0;
    if (contact_amg_built)
      for (unsigned int i = 0; i < contact.size(); ++i)
        changed
          += (std::isinf(stiffness[i]) != std::isinf(contact_amg_stiffness[i]));
    changed = Utilities::MPI::sum(changed, communicator);
    return contact_amg_built && changed <= 0.01 * contact.n_global_nodes();
  }



  // @sect4{Editing the step operator's matrix}
  //
  // The matrix of the projected operator is a copy of A whose entries are
  // changed in place, which deal.II's interface does not offer, hence
  // Epetra's. These helpers do the edits that need no member of the
  // solver.
  namespace
  {
    // n_i / |n_i|: the node's vector n_i (r_i = n_i . u) has length 1
    // except where an oblique plane of symmetry couples its components
    // (ContactSet::find_nodes()); projections need the unit vector.
    template <int dim>
    Tensor<1, dim>
    unit_normal(const ContactSet<dim> &contact, const unsigned int i)
    {
      return contact.node(i).normal / contact.node(i).normal.norm();
    }

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

    // k nu_i nu_i^T into the diagonal block of node i, in the components
    // the normal has (a constrained component has none, and its row no
    // entries but the diagonal).
    template <int dim>
    void
    add_to_block(Epetra_CrsMatrix      &matrix,
                 const ContactSet<dim> &contact,
                 const unsigned int     i,
                 const double           k)
    {
      const auto  &node = contact.node(i);
      int          columns[dim];
      double       values[dim];
      unsigned int components[dim], n = 0;
      for (unsigned int d = 0; d < dim; ++d)
        if (node.normal[d] != 0)
          {
            components[n] = d;
            columns[n++]
              = matrix.ColMap().LID(static_cast<long long>(node.dofs[d]));
          }
      for (unsigned int m = 0; m < n; ++m)
        {
          for (unsigned int e = 0; e < n; ++e)
            values[e]
              = k * node.normal[components[m]] * node.normal[components[e]];
          const int error = matrix.SumIntoMyValues(
            node_row(matrix, contact, i, components[m]),
            n,
            values,
            columns);
          AssertThrow(error == 0, ExcTrilinosError(error));
        }
    }

    // The columns of the fixed nodes (infinite stiffness): mark their dofs
    // with their normal component and the node (its global number + 1)
    // and bring the marks to the columns of this rank's rows, fixed nodes
    // of other ranks included. The marks are written at row indices:
    // deal.II builds square matrices with the same map for rows and
    // domain.
    template <int dim>
    void
    mark_fixed_columns(const Epetra_CrsMatrix    &matrix,
                       const ContactSet<dim>     &contact,
                       const std::vector<double> &stiffness,
                       Epetra_Vector             &column_normal,
                       Epetra_Vector             &column_node)
    {
      Assert(matrix.RowMap().SameAs(matrix.DomainMap()), ExcInternalError());
      Epetra_Vector owned_normal(matrix.DomainMap()),
        owned_node(matrix.DomainMap());
      for (unsigned int i = 0; i < contact.size(); ++i)
        if (std::isinf(stiffness[i]))
          for (unsigned int c = 0; c < dim; ++c)
            {
              owned_normal[node_row(matrix, contact, i, c)]
                = unit_normal(contact, i)[c];
              owned_node[node_row(matrix, contact, i, c)]
                = static_cast<double>(contact.first_global_index() + i + 1);
            }
      if (matrix.Importer() != nullptr)
        {
          column_normal.Import(owned_normal, *matrix.Importer(), Insert);
          column_node.Import(owned_node, *matrix.Importer(), Insert);
        }
      else // the columns are the owned dofs, in the same order
        {
          column_normal = owned_normal;
          column_node   = owned_node;
        }
    }

    // M P, row by row: in the columns of each fixed node j (as marked by
    // mark_fixed_columns()), the row's entries a lose their normal part,
    // a -= (a . nu_j) nu_j.
    void
    project_fixed_columns(Epetra_CrsMatrix    &matrix,
                          const Epetra_Vector &column_normal,
                          const Epetra_Vector &column_node)
    {
      std::vector<std::pair<double, double>> node_sums; // (node, a . nu_j)
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
                sum->second += values[e] * column_normal[columns[e]];
              }
          for (const auto &[j, sum] : node_sums)
            for (int e = 0; e < n; ++e)
              if (column_node[columns[e]] == j)
                values[e] -= sum * column_normal[columns[e]];
        }
    }
  } // namespace



  // @sect4{FullSpaceContactSolver::assemble_contact_matrix}
  //
  // A copy of A, the normal stiffness of the nodes on sloped pieces added
  // to their diagonal blocks, then P M P for the fixed nodes: the columns
  // (M P, project_fixed_columns()), then the rows (P (M P),
  // project_fixed_rows()).
  template <int dim>
  void
  FullSpaceContactSolver<dim>::assemble_contact_matrix(
    const ContactSet<dim>     &contact,
    const std::vector<double> &stiffness)
  {
    // The AMG keeps a reference to its matrix: release it before the matrix
    // is replaced.
    contact_amg.clear();
    contact_matrix = std::make_unique<Epetra_CrsMatrix>(A->trilinos_matrix());
    Epetra_CrsMatrix &matrix = *contact_matrix;
    for (unsigned int i = 0; i < contact.size(); ++i)
      if (stiffness[i] != 0 && !std::isinf(stiffness[i]))
        add_to_block(matrix, contact, i, stiffness[i]);

    Epetra_Vector column_normal(matrix.ColMap()), column_node(matrix.ColMap());
    mark_fixed_columns(matrix, contact, stiffness, column_normal, column_node);
    project_fixed_columns(matrix, column_normal, column_node);
    project_fixed_rows(matrix, contact, stiffness);
  }



  // @sect4{FullSpaceContactSolver::project_fixed_rows}
  //
  // P (M P): the rows of each fixed node lose their normal part column by
  // column. Only the rows of the components the normal has take part (a
  // component constrained by a roller or symmetry plane has none, and its
  // row only its diagonal); these rows have the same columns (the
  // vector-valued element couples all components of neighbouring
  // vertices), which is checked. Then d_i nu_i nu_i^T, d_i = nu_i^T A_ii
  // nu_i, goes back on the node's diagonal block.
  template <int dim>
  void
  FullSpaceContactSolver<dim>::project_fixed_rows(
    Epetra_CrsMatrix          &matrix,
    const ContactSet<dim>     &contact,
    const std::vector<double> &stiffness) const
  {
    for (unsigned int i = 0; i < contact.size(); ++i)
      if (std::isinf(stiffness[i]))
        {
          const auto          &node   = contact.node(i);
          const Tensor<1, dim> normal = unit_normal(contact, i);
          int                  n[dim];
          double              *values[dim];
          int                 *columns[dim];
          unsigned int         components[dim] = {}, n_components = 0;
          for (unsigned int c = 0; c < dim; ++c)
            if (node.normal[c] != 0)
              components[n_components++] = c;
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
          for (int e = 0; e < n[first]; ++e)
            {
              double sum = 0;
              for (unsigned int m = 0; m < n_components; ++m)
                sum += normal[components[m]] * values[components[m]][e];
              for (unsigned int m = 0; m < n_components; ++m)
                values[components[m]][e] -= sum * normal[components[m]];
            }
          // d_i nu_i nu_i^T, d_i = nu_i^T A_ii nu_i, back on the diagonal
          // (add_to_block() adds multiples of n_i n_i^T).
          double d = 0;
          for (unsigned int c = 0; c < dim; ++c)
            for (unsigned int e = 0; e < dim; ++e)
              d += normal[c] * A->el(node.dofs[c], node.dofs[e]) * normal[e];
          add_to_block(matrix, contact, i, d / node.normal.norm_square());
        }
  }



  // @sect4{FullSpaceContactSolver::project_rigid_body_modes}
  //
  // The near-null space of the constrained operator: the rigid-body modes
  // without their normal components at the fixed nodes.
  template <int dim>
  void
  FullSpaceContactSolver<dim>::project_rigid_body_modes(
    const ContactSet<dim>     &contact,
    const std::vector<double> &stiffness)
  {
    const Epetra_CrsMatrix &matrix = *contact_matrix;
    contact_modes = std::make_unique<Epetra_MultiVector>(*rigid_body_modes);
    for (unsigned int i = 0; i < contact.size(); ++i)
      if (std::isinf(stiffness[i]))
        for (int mode = 0; mode < contact_modes->NumVectors(); ++mode)
          {
            const Tensor<1, dim> normal      = unit_normal(contact, i);
            double               normal_part = 0;
            for (unsigned int c = 0; c < dim; ++c)
              normal_part
                += normal[c]
                   * (*contact_modes)[mode][node_row(matrix, contact, i, c)];
            for (unsigned int c = 0; c < dim; ++c)
              (*contact_modes)[mode][node_row(matrix, contact, i, c)]
                -= normal_part * normal[c];
          }
  }



  // @sect4{FullSpaceContactSolver::checkpoint_state}
  //
  // Which AMG the next solve would use depends on the pieces it was built
  // for, not only on the current ones; a resumed run that built it for its
  // first pieces would precondition differently and end within Tolerance of
  // the uninterrupted run, not equal to it. So the stiffness it was built for
  // goes into the checkpoint, and the resumed run builds the same AMG.
  template <int dim>
  std::optional<std::vector<double>>
  FullSpaceContactSolver<dim>::checkpoint_state() const
  {
    if (!contact_amg_built)
      return std::nullopt;
    return contact_amg_stiffness;
  }



  template <int dim>
  void
  FullSpaceContactSolver<dim>::restore_checkpoint_state(
    const ContactSet<dim>     &contact,
    const std::vector<double> &state)
  {
    // A run resumed with Preconditioner = direct uses no AMG.
    if (factorization)
      return;
    contact_amg_built = false;
    update_contact_amg(contact, state);
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
  // loop decides whether to cut the step (time_step.cc).
  template <int dim>
  LinearSolveReport
  FullSpaceContactSolver<dim>::krylov_solve(const Apply      &op,
                                            const Apply      &prec,
                                            VectorType       &y,
                                            const VectorType &rhs,
                                            const double      reference_norm,
                                            const double      accuracy)
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
    SolverControl control(10000, accuracy * std::max(reference_norm, 1e-300));
    try
      {
        if (symmetric)
          SolverCG<VectorType>(control).solve(Operator{op},
                                              y,
                                              rhs,
                                              Operator{prec});
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
        reason << (symmetric ? "CG" : "GMRES") << " did not converge in "
               << failure.last_step << " iterations (residual "
               << failure.last_residual
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
    report.residual = control.last_value() / std::max(reference_norm, 1e-300);
    ++this->counts.solves;
    this->counts.inner_iterations += control.last_step();
    return report;
  }



  // @sect4{FullSpaceContactSolver::solve_for_pieces}
  //
  // One active-set iteration's linear solve, in four steps: collect what the
  // pieces of this rank's nodes contribute (the prescribed normal
  // displacements u_0, the loads -w o nu and the normal stiffnesses w s,
  // collect_piece_terms()); set up the projected operator and
  // preconditioner as functions (projected(), step_operator(),
  // step_preconditioner()); solve for y from the previous iterate; read r
  // and z off the solution (read_off_contact()).
  //
  // Everything node-wise touches only locally owned entries (a node's dofs
  // belong to its owner), so no communication happens outside the matrix
  // products, the preconditioner and the Krylov method's inner products.
  template <int dim>
  LinearSolveReport
  FullSpaceContactSolver<dim>::solve_for_pieces(ContactSet<dim> &contact,
                                                VectorType      &u,
                                                const double     accuracy)
  {
    const unsigned int  m = contact.size();
    std::vector<bool>   fixed(m);
    std::vector<double> normal_stiffness(m, 0.);
    VectorType          u0, A_u0, step_rhs(b);
    u0.reinit(b);         // zero
    A_u0.reinit(b, true); // overwritten by the products below
    collect_piece_terms(contact, fixed, normal_stiffness, u0, step_rhs);
    // step_rhs = b - sum_i w_i o_i nu_i - A u_0: the prescribed part of u
    // moves to the right-hand side.
    A->vmult(A_u0, u0);
    // The scale of the tolerance: the largest of the loads b, of the pieces'
    // loads and of A u_0. A body loaded through the obstacle alone (an
    // indenter moving in, with no other load) has b = 0, and its load is
    // the normal displacement the obstacle prescribes at the fixed nodes.
    VectorType piece_loads(step_rhs);
    piece_loads -= b;
    const double piece_load_norm = piece_loads.l2_norm();
    const double reference_norm
      = std::max({b_norm, piece_load_norm, A_u0.l2_norm()});
    step_rhs -= A_u0;

    const Apply preconditioner
      = step_preconditioner(contact, fixed, normal_stiffness);
    // With a projected right-hand side and start, every Krylov iterate keeps
    // zero normal components at the fixed nodes.
    remove_fixed_normals(contact, fixed, step_rhs);
    // The warm start: the previous iterate, constraints removed.
    remove_fixed_normals(contact, fixed, u);
    const LinearSolveReport report = krylov_solve(
      projected(step_operator(contact, normal_stiffness),
                operator_scratch,
                contact,
                fixed),
      projected(preconditioner, preconditioner_scratch, contact, fixed),
      u,
      step_rhs,
      reference_norm,
      accuracy);
    // u = u_0 + y: now u.nu_i = beta at the fixed nodes.
    u += u0;
    // A failed solve leaves r and z as they were; ContactNodes::solve()
    // stops on the report.
    if (!report.converged)
      return report;

    // The residual b - A u equals N^T z: at node i its normal component is
    // the force z_i (the contact force of node i acts on that node's dofs
    // only).
    VectorType &residual = A_u0; // its value is no longer needed
    A->vmult(residual, u);
    residual.sadd(-1., 1., b);
    read_off_contact(contact, u, residual);
    return report;
  }



  // @sect4{FullSpaceContactSolver::collect_piece_terms}
  //
  // Split the nodes by their pieces. A vertical piece (a jump of the law,
  // or the rigid foundation) fixes the normal displacement to
  // beta = r_lower: the node is fixed, u_0 gets beta nu_i. A sloped piece
  // adds the load -w_i o_i nu_i to the right-hand side and the normal
  // stiffness w_i s_i to the operator (zero on a flat piece, whose force
  // w_i o_i is then known).
  template <int dim>
  void
  FullSpaceContactSolver<dim>::collect_piece_terms(
    const ContactSet<dim> &contact,
    std::vector<bool>     &fixed,
    std::vector<double>   &normal_stiffness,
    VectorType            &u0,
    VectorType            &step_rhs) const
  {
    for (unsigned int i = 0; i < contact.size(); ++i)
      {
        const ContactLawPiece &piece = contact.current_piece(i);
        fixed[i]                     = piece.vertical;
        // r = nu.u - s with the obstacle's gap s: a vertical piece fixes
        // nu.u = beta + s, a sloped one has the intercept o - slope s in nu.u.
        if (piece.vertical)
          contact.add_normal(u0,
                             i,
                             (piece.r_lower + contact.gap(i))
                               / contact.node(i).normal.norm_square());
        else
          {
            contact.add_normal(step_rhs,
                               i,
                               -contact.weight(i)
                                 * (piece.intercept
                                    - piece.slope * contact.gap(i)));
            normal_stiffness[i] = contact.weight(i) * piece.slope;
          }
      }
  }



  // @sect4{FullSpaceContactSolver::remove_fixed_normals}
  //
  // P v: remove the normal component at every fixed node, the orthogonal
  // projection I - n_i n_i^T / |n_i|^2 on the node's dofs and the identity
  // elsewhere.
  template <int dim>
  void
  FullSpaceContactSolver<dim>::remove_fixed_normals(
    const ContactSet<dim>   &contact,
    const std::vector<bool> &fixed,
    VectorType              &v) const
  {
    for (unsigned int i = 0; i < contact.size(); ++i)
      if (fixed[i])
        contact.add_normal(v,
                           i,
                           -contact.normal_component(v, i)
                             / contact.node(i).normal.norm_square());
  }



  // @sect4{FullSpaceContactSolver::projected}
  //
  // v -> P inner(P v) + (I - P) v, for the operator and the preconditioner
  // alike, with projected_src as work vector. The last term puts the
  // normal components of v at the fixed nodes back unchanged, which keeps
  // the operator nonsingular; P and I - P are symmetric, so the result is
  // symmetric whenever inner is. The function keeps references to its
  // arguments except inner, which it copies.
  template <int dim>
  typename FullSpaceContactSolver<dim>::Apply
  FullSpaceContactSolver<dim>::projected(const Apply             &inner,
                                         VectorType              &projected_src,
                                         const ContactSet<dim>   &contact,
                                         const std::vector<bool> &fixed) const
  {
    return
      [this, inner, &projected_src, &contact, &fixed](VectorType       &dst,
                                                      const VectorType &src) {
        projected_src = src;
        remove_fixed_normals(contact, fixed, projected_src);
        inner(dst, projected_src);
        remove_fixed_normals(contact, fixed, dst);
        for (unsigned int i = 0; i < contact.size(); ++i)
          if (fixed[i])
            contact.add_normal(dst,
                               i,
                               contact.normal_component(src, i)
                                 / contact.node(i).normal.norm_square());
      };
  }



  // @sect4{FullSpaceContactSolver::step_operator}
  //
  // A + sum_i w_i s_i nu_i nu_i^T, applied without forming it: the matrix
  // A stays that of set_operator() for every set of pieces.
  template <int dim>
  typename FullSpaceContactSolver<dim>::Apply
  FullSpaceContactSolver<dim>::step_operator(
    const ContactSet<dim>     &contact,
    const std::vector<double> &normal_stiffness) const
  {
    return [this, &contact, &normal_stiffness](VectorType       &dst,
                                               const VectorType &src) {
      A->vmult(dst, src);
      for (unsigned int i = 0; i < contact.size(); ++i)
        if (normal_stiffness[i] != 0)
          contact.add_normal(dst,
                             i,
                             normal_stiffness[i]
                               * contact.normal_component(src, i));
    };
  }



  // @sect4{FullSpaceContactSolver::step_preconditioner}
  //
  // The preconditioner: the factorisation of A, or the AMG of the step
  // operator of (nearly) these pieces, the fixed nodes marked by an
  // infinite stiffness (update_contact_amg() removes their normal
  // directions). Collective when it updates the AMG.
  template <int dim>
  typename FullSpaceContactSolver<dim>::Apply
  FullSpaceContactSolver<dim>::step_preconditioner(
    const ContactSet<dim>     &contact,
    const std::vector<bool>   &fixed,
    const std::vector<double> &normal_stiffness)
  {
    if (factorization)
      return [this](VectorType &dst, const VectorType &src) {
        factorization->solve(dst, src);
      };
    std::vector<double> stiffness = normal_stiffness;
    for (unsigned int i = 0; i < contact.size(); ++i)
      if (fixed[i])
        stiffness[i] = std::numeric_limits<double>::infinity();
    update_contact_amg(contact, stiffness);
    return [this](VectorType &dst, const VectorType &src) {
      contact_amg.vmult(dst, src);
    };
  }



  // @sect4{FullSpaceContactSolver::read_off_contact}
  //
  // r_i = nu_i . u_i at every node. At a fixed node the force is read off
  // the residual; on a sloped piece the law gives it exactly,
  // z_i = w_i (o_i + s_i r_i).
  template <int dim>
  void
  FullSpaceContactSolver<dim>::read_off_contact(
    ContactSet<dim>  &contact,
    const VectorType &u,
    const VectorType &residual) const
  {
    for (unsigned int i = 0; i < contact.size(); ++i)
      {
        const ContactLawPiece &piece = contact.current_piece(i);
        contact.r[i] = contact.normal_component(u, i) - contact.gap(i);
        contact.z[i] = (piece.vertical
                          ? contact.normal_component(residual, i)
                              / contact.node(i).normal.norm_square()
                          : contact.weight(i)
                              * (piece.intercept + piece.slope * contact.r[i]));
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
    const Apply op
      = [&](VectorType &dst, const VectorType &src) { A->vmult(dst, src); };
    Apply prec;
    if (factorization)
      prec = [&](VectorType &dst, const VectorType &src) {
        factorization->solve(dst, src);
      };
    else
      {
        if (!operator_amg_built)
          {
            build_amg(A->trilinos_matrix(), *rigid_body_modes, operator_amg);
            operator_amg_built = true;
            ++this->counts.operator_setups;
          }
        prec = [&](VectorType &dst, const VectorType &src) {
          operator_amg.vmult(dst, src);
        };
      }
    u = 0;
    return krylov_solve(op, prec, u, rhs, rhs.l2_norm(), tolerance);
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
    VectorType forces(b), response(b);
    forces = 0;
    for (unsigned int i = 0; i < contact.size(); ++i)
      contact.add_normal(forces, i, x[i]);
    solve_without_contact(forces, response);
    y.reinit(contact.size());
    for (unsigned int i = 0; i < contact.size(); ++i)
      y[i] = contact.normal_component(response, i);
  }



  // @sect4{The factory}
  //
  // The class is only known in this file; create_contact_solver()
  // (contact_solver.cc) reaches its constructor through this function.
  template <int dim>
  std::unique_ptr<ContactSolver<dim>>
  create_full_space_contact_solver(const Parameters::AllParameters &parameters,
                                   const Mapping<dim>              &mapping,
                                   const DoFHandler<dim>           &dof_handler,
                                   const VectorType                &layout)
  {
    return std::make_unique<FullSpaceContactSolver<dim>>(parameters,
                                                         mapping,
                                                         dof_handler,
                                                         layout);
  }

  template std::unique_ptr<ContactSolver<2>>
  create_full_space_contact_solver(const Parameters::AllParameters &,
                                   const Mapping<2> &,
                                   const DoFHandler<2> &,
                                   const VectorType &);
  template std::unique_ptr<ContactSolver<3>>
  create_full_space_contact_solver(const Parameters::AllParameters &,
                                   const Mapping<3> &,
                                   const DoFHandler<3> &,
                                   const VectorType &);
} // namespace ViscoContact
