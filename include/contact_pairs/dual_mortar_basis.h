#ifndef viscoplastic_contact_dual_mortar_basis_h
#define viscoplastic_contact_dual_mortar_basis_h

#include <deal.II/lac/affine_constraints.h>

#include "back_ends/contact_solver.h"

#include <memory>

namespace ViscoContact
{
  using namespace dealii;

  // @sect3{Contact pairs on the full space back end: the dual mortar basis}
  //
  // The full space back end imposes the fixed directions of a node by a
  // projection on the node's own dofs, which needs the rows of different
  // nodes to be orthogonal. The row of a node of a contact pair also has
  // entries on the opposite side's dofs (contact_pairs.h), shared with its
  // neighbours. The dual basis makes a change of variables possible that
  // turns those rows into rows on the node's own dofs again (Popp, Gee and
  // Wall's condensation of dual mortar): with
  //   u_j = w_j + sum_k (M_jk / D_j) u_k     (j a node of a pair, k the
  //                                           opposite side's dofs),
  // u = T w, the node's rows a . (u_j - sum_k (M_jk / D_j) u_k) are a . w_j,
  // and the step problem in w has the operator T^T A T and the right-hand
  // side T^T b. T is the identity but in the rows of the pair nodes' free
  // dofs; the opposite side's dofs are no pair node's, so T^{-1} = 2 I - T.
  //
  // DualMortarBasis wraps the full space back end: it forms T once per
  // contact set and T^T A T once per operator (two sparse products, as the
  // operator's set-up by the back end costs anyway), hands the back end the
  // problem in w, and returns u = T w. The back end sees nodal rows (its
  // frame rows, ContactSet::frame_row()) and needs no change. Without a
  // matrix (the matrix-free back end) there is no T^T A T to form: the back
  // end applies T, A and T^T in turn, and preconditions with
  // T^{-1} M^{-1} T^{-T}, M its multigrid of A, which approximates
  // (T^T A T)^{-1} exactly as M approximates A^{-1}.
  template <int dim>
  class DualMortarBasis : public ContactSolver<dim>
  {
  public:
    // matrix_free: the back end has no matrix; it applies T^T A T itself
    // (ContactSolver::work_in_basis()).
    DualMortarBasis(std::unique_ptr<ContactSolver<dim>> back_end,
                    const AffineConstraints<double>    &constraints,
                    const VectorType                   &layout,
                    const bool                          matrix_free);

    std::string
    description() const override;
    void
    set_operator(const MatrixType      &A,
                 const bool             symmetric,
                 const ContactSet<dim> &contact) override;
    void
    set_right_hand_side(const VectorType      &b,
                        const ContactSet<dim> &contact) override;
    LinearSolveReport
    solve_for_pieces(ContactSet<dim>          &contact,
                     VectorType               &u,
                     const LinearSolveRequest &request) override;
    void
    finish(const ContactSet<dim> &contact, VectorType &u) override;
    void
    apply_operator(VectorType &dst, const VectorType &src) const override;
    LinearSolveReport
    solve_without_contact(const VectorType &b, VectorType &u) override;
    void
    apply_compliance(const ContactSet<dim> &contact,
                     const Vector<double>  &x,
                     Vector<double>        &y) override;
    void
    forget_kept_state() override;

  private:
    // T from the pair nodes of the contact set, after check_basis() has
    // refused the scenes it does not make nodal (collective).
    void
    make_basis(const ContactSet<dim> &contact);
    void
    check_basis(const ContactSet<dim> &contact);
    // w = T^{-1} u (the start of a Krylov solve), u = T w.
    void
    to_basis(const VectorType &u);
    void
    from_basis(VectorType &u) const;

    std::unique_ptr<ContactSolver<dim>> back_end;
    const AffineConstraints<double>    &constraints;
    const MatrixType                   *A = nullptr;
    const bool                          matrix_free;
    MatrixType                          T, transformed_A;
    // The step problem's unknown in the basis, w.
    VectorType w;
  };
} // namespace ViscoContact

#endif
