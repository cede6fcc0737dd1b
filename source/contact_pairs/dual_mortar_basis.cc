// Contact pairs on the full space back end: the step problem in the dual
// mortar basis (dual_mortar_basis.h).

#include <deal.II/lac/dynamic_sparsity_pattern.h>

#include "contact_pairs/dual_mortar_basis.h"
#include "robustness/file_output.h"

#include <sstream>

namespace ViscoContact
{
  template <int dim>
  DualMortarBasis<dim>::DualMortarBasis(
    std::unique_ptr<ContactSolver<dim>> back_end,
    const AffineConstraints<double>    &constraints,
    const VectorType                   &layout,
    const bool                          matrix_free)
    : back_end(std::move(back_end))
    , constraints(constraints)
    , matrix_free(matrix_free)
    , w(layout)
  {}



  template <int dim>
  std::string
  DualMortarBasis<dim>::description() const
  {
    return back_end->description()
           + " (contact pairs in the dual mortar basis)";
  }



  // @sect4{DualMortarBasis::make_basis}
  //
  // T: the identity, and in the row of every free dof of a pair node the
  // coefficients M_jk / D_j of the opposite side's dofs of the same
  // component (ContactSet::NodeGeometry::opposite). A constrained component
  // of a node keeps its identity row, so that T changes no constraint.
  template <int dim>
  void
  DualMortarBasis<dim>::make_basis(const ContactSet<dim> &contact)
  {
    check_basis(contact);
    const IndexSet        &owned = w.locally_owned_elements();
    DynamicSparsityPattern pattern(w.size(), w.size(), owned);
    for (const auto d : owned)
      pattern.add(d, d);
    const auto free_dof = [&](const unsigned int i, const unsigned int c) {
      return !constraints.is_constrained(contact.node(i).dofs[c]);
    };
    for (unsigned int i = 0; i < contact.size(); ++i)
      for (const auto &entry : contact.node(i).opposite)
        if (free_dof(i, entry.component))
          pattern.add(contact.node(i).dofs[entry.component], entry.dof);
    T.reinit(owned, owned, pattern, w.get_mpi_communicator());
    for (const auto d : owned)
      T.add(d, d, 1.);
    for (unsigned int i = 0; i < contact.size(); ++i)
      for (const auto &entry : contact.node(i).opposite)
        if (free_dof(i, entry.component))
          T.add(contact.node(i).dofs[entry.component],
                entry.dof,
                entry.coefficient);
    T.compress(VectorOperation::add);
  }



  // @sect4{DualMortarBasis::check_basis}
  //
  // Where the basis does not make the rows nodal, it is refused on every
  // rank before a solve: an opposite side's dof that is a free dof of a
  // pair node (two pairs that meet at a vertex: then T^{-1} is not 2 I - T),
  // and a pair node whose constrained component the rows need (a plane of
  // symmetry that is not normal to the node's directions: the opposite
  // side's share of that component has no free dof of the node to go to).
  // The condensed back end takes both, as it takes any rows.
  template <int dim>
  void
  DualMortarBasis<dim>::check_basis(const ContactSet<dim> &contact)
  {
    VectorType pair_dofs(w);
    pair_dofs = 0;
    for (unsigned int i = 0; i < contact.size(); ++i)
      if (!contact.node(i).opposite.empty())
        for (unsigned int c = 0; c < dim; ++c)
          if (!constraints.is_constrained(contact.node(i).dofs[c]))
            pair_dofs.local_element(contact.node(i).local_dofs[c]) = 1;
    pair_dofs.update_ghost_values();
    std::string problem;
    for (unsigned int i = 0; i < contact.size() && problem.empty(); ++i)
      {
        const auto &node = contact.node(i);
        for (const auto &entry : node.opposite)
          {
            bool needed = false;
            for (unsigned int j = 0; j < 1 + node.n_tangents; ++j)
              needed = needed
                       || (j == 0 ? node.direction
                                  : node.tangents[j - 1])[entry.component]
                            != 0.;
            const bool constrained
              = constraints.is_constrained(node.dofs[entry.component]);
            if (pair_dofs.local_element(entry.local_dof) != 0
                || (constrained && needed))
              {
                std::ostringstream message;
                message << "Invalid parameter <Method> in subsection <Linear "
                           "solver>: the contact pair node at ("
                        << node.location
                        << (constrained
                              ? ") lies on a plane of symmetry that its "
                                "contact directions cross"
                              : ") meets an opposite side that is itself "
                                "the zone of a contact pair")
                        << ", which the full space and matrix-free back "
                           "ends cannot take in the dual mortar basis; "
                           "accepted: Method = condensed for this scene.";
                problem = message.str();
                break;
              }
          }
      }
    FileOutput::agree_on_problem(problem, w.get_mpi_communicator());
  }



  // @sect4{DualMortarBasis::set_operator}
  template <int dim>
  void
  DualMortarBasis<dim>::set_operator(const MatrixType      &matrix,
                                     const bool             symmetric,
                                     const ContactSet<dim> &contact)
  {
    A = &matrix;
    make_basis(contact);
    back_end->work_in_basis(T);
    if (matrix_free)
      {
        back_end->set_operator(matrix, symmetric, contact);
        this->counts = back_end->statistics();
        return;
      }
    // Trilinos' product leaves out the terms of a stored zero of A (an
    // exact zero coupling of two components on a regular mesh), so the rows
    // of one node's components could differ in their columns, which the
    // back ends need equal: the product takes the pattern of the same
    // product with all values 1, and the values of T^T A T. (The values
    // are set to 1 through Epetra: deal.II 9.4's matrix iterator costs
    // O(n) per row.)
    {
      const auto ones = [](const MatrixType &source) {
        MatrixType copy;
        copy.copy_from(source);
        const int error = const_cast<Epetra_CrsMatrix &>(copy.trilinos_matrix())
                            .PutScalar(1.);
        AssertThrow(error == 0, ExcTrilinosError(error));
        return copy;
      };
      MatrixType A_T;
      ones(matrix).mmult(A_T, ones(T));
      ones(T).Tmmult(transformed_A, A_T);
    }
    {
      MatrixType A_T, product;
      matrix.mmult(A_T, T);
      T.Tmmult(product, A_T);
      transformed_A = 0;
      transformed_A.add(1., product);
    }
    back_end->set_operator(transformed_A, symmetric, contact);
    this->counts = back_end->statistics();
  }



  template <int dim>
  void
  DualMortarBasis<dim>::to_basis(const VectorType &u)
  {
    // w = T^{-1} u = 2 u - T u.
    T.vmult(w, u);
    w.sadd(-1., 2., u);
  }



  template <int dim>
  void
  DualMortarBasis<dim>::from_basis(VectorType &u) const
  {
    T.vmult(u, w);
  }



  template <int dim>
  void
  DualMortarBasis<dim>::set_right_hand_side(const VectorType      &b,
                                            const ContactSet<dim> &contact)
  {
    VectorType transformed_b(b);
    T.Tvmult(transformed_b, b);
    back_end->set_right_hand_side(transformed_b, contact);
    this->counts = back_end->statistics();
  }



  // The back end solves for w from the start T^{-1} u; u = T w.
  template <int dim>
  LinearSolveReport
  DualMortarBasis<dim>::solve_for_pieces(ContactSet<dim>          &contact,
                                         VectorType               &u,
                                         const LinearSolveRequest &request)
  {
    to_basis(u);
    const LinearSolveReport report
      = back_end->solve_for_pieces(contact, w, request);
    from_basis(u);
    this->counts = back_end->statistics();
    return report;
  }



  template <int dim>
  void
  DualMortarBasis<dim>::finish(const ContactSet<dim> &contact, VectorType &u)
  {
    to_basis(u);
    back_end->finish(contact, w);
    from_basis(u);
    this->counts = back_end->statistics();
  }



  // A src in u: without a matrix, the back end's A between T^{-1} and
  // T^{-T} (its operator is T^T A T).
  template <int dim>
  void
  DualMortarBasis<dim>::apply_operator(VectorType       &dst,
                                       const VectorType &src) const
  {
    if (!matrix_free)
      {
        A->vmult(dst, src);
        return;
      }
    VectorType w_src(src), w_dst(src);
    T.vmult(w_src, src);
    w_src.sadd(-1., 2., src);
    back_end->apply_operator(w_dst, w_src);
    T.Tvmult(dst, w_dst);
    dst.sadd(-1., 2., w_dst);
  }



  template <int dim>
  LinearSolveReport
  DualMortarBasis<dim>::solve_without_contact(const VectorType &b,
                                              VectorType       &u)
  {
    VectorType transformed_b(b);
    T.Tvmult(transformed_b, b);
    to_basis(u);
    const LinearSolveReport report
      = back_end->solve_without_contact(transformed_b, w);
    from_basis(u);
    this->counts = back_end->statistics();
    return report;
  }



  // N A^{-1} N^T = N_w (T^T A T)^{-1} N_w^T with the nodal rows N_w of the
  // basis: the back end's own product.
  template <int dim>
  void
  DualMortarBasis<dim>::apply_compliance(const ContactSet<dim> &contact,
                                         const Vector<double>  &x,
                                         Vector<double>        &y)
  {
    back_end->apply_compliance(contact, x, y);
    this->counts = back_end->statistics();
  }



  template <int dim>
  void
  DualMortarBasis<dim>::forget_kept_state()
  {
    back_end->forget_kept_state();
  }



  template class DualMortarBasis<2>;
  template class DualMortarBasis<3>;
} // namespace ViscoContact
