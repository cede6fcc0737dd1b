// The full space back end: a Krylov method on the projected operator of
// the step problem, preconditioned by AMG or a factorisation of the
// operator, both built once per operator.

#include <deal.II/base/exceptions.h>
#include <deal.II/base/mpi.h>

#include <deal.II/dofs/dof_tools.h>

#include <deal.II/fe/fe.h>
#include <deal.II/fe/fe_values_extractors.h>

#include <deal.II/lac/solver_cg.h>
#include <deal.II/lac/solver_control.h>
#include <deal.II/lac/solver_gmres.h>
#include <deal.II/lac/trilinos_precondition.h>

#include "contact_solver.h"
#include "direct_solver.h"

#include <Epetra_Map.h>
#include <Epetra_MultiVector.h>
#include <Teuchos_ParameterList.hpp>

#include <functional>
#include <optional>
#include <sstream>

namespace ViscoContact
{
  // @sect3{The full space back end}
  //
  // For fixed pieces, a node on a sloped piece (slope s, intercept o)
  // carries the force w (o + s u.nu), a node on a vertical piece at r = beta
  // has u.nu = beta. With u = u_0 + y, u_0 = beta nu at the fixed nodes,
  // y solves
  //   (P (A + sum_i w_i s_i nu_i nu_i^T) P + (I - P)) y
  //     = P (b - sum_i w_i o_i nu_i - A u_0),
  // P the orthogonal projection that removes the normal component at the
  // fixed nodes (a constraint among the components of a node, for any
  // normal). The operator is applied around A, which never changes within
  // a step problem; the preconditioner P M^{-1} P + (I - P) uses the AMG
  // cycle or the factorisation M^{-1} of A built by set_operator(). Both
  // are symmetric when A is, and positive definite as long as the
  // uniqueness condition (doc/model.md, section 4) holds: CG then; GMRES
  // for the implicit update's unsymmetric tangent. The forces at the fixed
  // nodes are read off the residual, z_i = nu_i . (b - A u)_i.
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
    // Per step problem: keep b; per active-set iteration: a Krylov solve
    // on the projected operator, which leaves u final, so finish() has
    // nothing to do.
    void
    set_right_hand_side(const VectorType      &b,
                        const ContactSet<dim> &contact) override;
    LinearSolveReport
    solve_for_pieces(ContactSet<dim> &contact, VectorType &u) override;
    void
    finish(const ContactSet<dim> &contact, VectorType &u) override;

  private:
    using Apply = std::function<void(VectorType &, const VectorType &)>;

    void
    build_amg(const MatrixType &A, const bool symmetric);
    // Solves op y = rhs from the initial y with the preconditioner prec:
    // CG or GMRES to Tolerance relative to the norm of reference.
    LinearSolveReport
    krylov_solve(const Apply      &op,
                 const Apply      &prec,
                 VectorType       &y,
                 const VectorType &rhs,
                 const double      reference_norm);
    void
    apply_preconditioner(VectorType &dst, const VectorType &src) const;

    const Parameters::Preconditioner preconditioner_type;
    const double                     tolerance;
    const MPI_Comm                   communicator;
    const Mapping<dim>              &mapping;
    const DoFHandler<dim>           &dof_handler;

    const MatrixType                   *A         = nullptr;
    bool                                symmetric = true;
    TrilinosWrappers::PreconditionAMG   amg;
    std::unique_ptr<Epetra_MultiVector> rigid_body_modes;
    std::optional<SparseDirectSolver>   factorization;
    VectorType                          b;
  };



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
  {
    if (preconditioner_type == Parameters::Preconditioner::direct)
      factorization.emplace(
        parameters.direct_solver == Parameters::DirectSolver::automatic
          ? (Utilities::MPI::n_mpi_processes(communicator) == 1
               ? Parameters::DirectSolver::cholmod
               : Parameters::DirectSolver::mumps)
          : parameters.direct_solver,
        communicator);
  }



  template <int dim>
  std::string
  FullSpaceContactSolver<dim>::description() const
  {
    return std::string("full space: CG (GMRES for the implicit update's "
                       "tangent) on the projected operator, preconditioned by ")
           + (factorization ? factorization->description()
                            : "ML AMG with the rigid-body modes");
  }



  // @sect4{FullSpaceContactSolver::build_amg}
  //
  // Elasticity needs the near-null space of the operator without Dirichlet
  // conditions, the dim translations and the dim(dim-1)/2 infinitesimal
  // rotations, given to ML per locally owned dof (deal.II 9.4's
  // AdditionalData only takes translations, so the parameter list is
  // completed by hand). An unsymmetric tangent gets ML's settings for
  // nonsymmetric problems.
  template <int dim>
  void
  FullSpaceContactSolver<dim>::build_amg(const MatrixType &matrix,
                                         const bool        is_symmetric)
  {
    if (!rigid_body_modes)
      {
        std::map<types::global_dof_index, Point<dim>> support_points;
        DoFTools::map_dofs_to_support_points(mapping,
                                             dof_handler,
                                             support_points);
        std::vector<IndexSet> component_dofs(dim);
        for (unsigned int c = 0; c < dim; ++c)
          component_dofs[c]
            = DoFTools::extract_dofs(dof_handler,
                                     dof_handler.get_fe().component_mask(
                                       FEValuesExtractors::Scalar(c)));
        const unsigned int n_modes = (dim == 2 ? 3 : 6);
        const Epetra_Map  &row_map = matrix.trilinos_matrix().RowMap();
        rigid_body_modes
          = std::make_unique<Epetra_MultiVector>(row_map, n_modes);
        for (int local = 0; local < row_map.NumMyElements(); ++local)
          {
            const types::global_dof_index dof = row_map.GID64(local);
            unsigned int                  c   = 0;
            while (c < dim && !component_dofs[c].is_element(dof))
              ++c;
            Assert(c < dim, ExcInternalError());
            const Point<dim> &x           = support_points[dof];
            (*rigid_body_modes)[c][local] = 1.; // translation along e_c
            if (dim == 2)
              (*rigid_body_modes)[2][local] = (c == 0 ? -x[1] : x[0]);
            else
              {
                // Rotations about the axes: e_d x x, component c.
                const unsigned int c1 = (c + 1) % 3, c2 = (c + 2) % 3;
                for (unsigned int d = 0; d < 3; ++d)
                  (*rigid_body_modes)[3 + d][local]
                    = (d == c2 ? x[c1] : (d == c1 ? -x[c2] : 0.));
              }
          }
      }

    TrilinosWrappers::PreconditionAMG::AdditionalData data;
    data.elliptic              = is_symmetric;
    data.higher_order_elements = false;
    data.smoother_sweeps       = 2;
    data.aggregation_threshold = 0.02;
    Teuchos::ParameterList              ml_parameters;
    std::unique_ptr<Epetra_MultiVector> unused_constant_modes;
    data.set_parameters(ml_parameters, unused_constant_modes, matrix);
    ml_parameters.set("null space: type", "pre-computed");
    ml_parameters.set("null space: dimension", rigid_body_modes->NumVectors());
    ml_parameters.set("null space: vectors", rigid_body_modes->Values());
    amg.initialize(matrix, ml_parameters);
  }



  template <int dim>
  void
  FullSpaceContactSolver<dim>::set_operator(const MatrixType &matrix,
                                            const bool        is_symmetric,
                                            const ContactSet<dim> &)
  {
    A         = &matrix;
    symmetric = is_symmetric;
    if (factorization)
      factorization->factorize(matrix, is_symmetric);
    else
      build_amg(matrix, is_symmetric);
    ++this->counts.operator_setups;
  }



  template <int dim>
  void
  FullSpaceContactSolver<dim>::set_right_hand_side(const VectorType &rhs,
                                                   const ContactSet<dim> &)
  {
    b = rhs;
  }



  template <int dim>
  void
  FullSpaceContactSolver<dim>::apply_preconditioner(VectorType       &dst,
                                                    const VectorType &src) const
  {
    if (factorization)
      factorization->solve(dst, src);
    else
      amg.vmult(dst, src);
  }



  template <int dim>
  LinearSolveReport
  FullSpaceContactSolver<dim>::krylov_solve(const Apply      &op,
                                            const Apply      &prec,
                                            VectorType       &y,
                                            const VectorType &rhs,
                                            const double      reference_norm)
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

    SolverControl control(10000, tolerance * std::max(reference_norm, 1e-300));
    LinearSolveReport report;
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
    report.inner_iterations = control.last_step();
    report.residual = control.last_value() / std::max(reference_norm, 1e-300);
    ++this->counts.solves;
    this->counts.inner_iterations += control.last_step();
    return report;
  }



  // @sect4{FullSpaceContactSolver::solve_for_pieces}
  //
  // Everything node-wise touches only locally owned entries (a node's dofs
  // belong to its owner), so no communication happens outside the matrix
  // products, the preconditioner and the Krylov method's inner products.
  template <int dim>
  LinearSolveReport
  FullSpaceContactSolver<dim>::solve_for_pieces(ContactSet<dim> &contact,
                                                VectorType      &u)
  {
    const unsigned int  m = contact.size();
    std::vector<bool>   fixed(m);
    std::vector<double> normal_stiffness(m, 0.);
    VectorType          u0(b), step_rhs(b), A_u0(b);
    u0 = 0;
    for (unsigned int i = 0; i < m; ++i)
      {
        const ContactLawPiece &piece = contact.law().piece(contact.piece(i));
        fixed[i]                     = piece.vertical;
        if (piece.vertical)
          contact.add_normal(u0, i, piece.r_lower);
        else
          {
            contact.add_normal(step_rhs,
                               i,
                               -contact.weight(i) * piece.intercept);
            normal_stiffness[i] = contact.weight(i) * piece.slope;
          }
      }
    A->vmult(A_u0, u0);
    step_rhs -= A_u0;

    const auto project = [&](VectorType &v) {
      for (unsigned int i = 0; i < m; ++i)
        if (fixed[i])
          contact.add_normal(v, i, -contact.normal_component(v, i));
    };
    // v -> P inner(P v) + (I - P) v.
    const auto projected = [&](const Apply &inner) -> Apply {
      return [&, inner](VectorType &dst, const VectorType &src) {
        VectorType projected_src(src);
        project(projected_src);
        inner(dst, projected_src);
        project(dst);
        for (unsigned int i = 0; i < m; ++i)
          if (fixed[i])
            contact.add_normal(dst, i, contact.normal_component(src, i));
      };
    };
    const Apply step_operator = [&](VectorType &dst, const VectorType &src) {
      A->vmult(dst, src);
      for (unsigned int i = 0; i < m; ++i)
        if (normal_stiffness[i] != 0)
          contact.add_normal(dst,
                             i,
                             normal_stiffness[i]
                               * contact.normal_component(src, i));
    };
    const Apply preconditioner = [&](VectorType &dst, const VectorType &src) {
      apply_preconditioner(dst, src);
    };

    project(step_rhs);
    project(u); // the warm start: the previous iterate, constraints removed
    const LinearSolveReport report = krylov_solve(projected(step_operator),
                                                  projected(preconditioner),
                                                  u,
                                                  step_rhs,
                                                  b.l2_norm());
    u += u0;
    if (!report.converged)
      return report;

    VectorType residual(b);
    A->vmult(residual, u);
    residual.sadd(-1., 1., b);
    for (unsigned int i = 0; i < m; ++i)
      {
        const ContactLawPiece &piece = contact.law().piece(contact.piece(i));
        contact.r[i]                 = contact.normal_component(u, i);
        contact.z[i]                 = (piece.vertical
                                          ? contact.normal_component(residual, i)
                                          : contact.weight(i)
                              * (piece.intercept + piece.slope * contact.r[i]));
      }
    return report;
  }



  template <int dim>
  void
  FullSpaceContactSolver<dim>::finish(const ContactSet<dim> &, VectorType &)
  {}



  template <int dim>
  LinearSolveReport
  FullSpaceContactSolver<dim>::solve_without_contact(const VectorType &rhs,
                                                     VectorType       &u)
  {
    const Apply op
      = [&](VectorType &dst, const VectorType &src) { A->vmult(dst, src); };
    const Apply prec = [&](VectorType &dst, const VectorType &src) {
      apply_preconditioner(dst, src);
    };
    u = 0;
    return krylov_solve(op, prec, u, rhs, rhs.l2_norm());
  }



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
