// The condensed back end: the operator factorised by a sparse direct
// solver, the contact problem of fixed pieces solved on the contact nodes.

#include <deal.II/base/exceptions.h>
#include <deal.II/base/mpi.h>

#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/lapack_full_matrix.h>

#include "condensed_system.h"
#include "contact_solver.h"
#include "direct_solver.h"

#include <algorithm>

namespace ViscoContact
{
  namespace
  {
    // The values of all ranks, one after the other (rank order): what each
    // rank needs of the small, node-sized vectors of the condensed problem.
    template <typename T>
    std::vector<T>
    gather_on_all_ranks(const std::vector<T> &local,
                        const MPI_Comm        communicator)
    {
      const int        n_ranks = Utilities::MPI::n_mpi_processes(communicator);
      const int        size    = local.size();
      std::vector<int> sizes(n_ranks), offsets(n_ranks + 1, 0);
      int              error = MPI_Allgather(&size,
                                1,
                                MPI_INT,
                                sizes.data(),
                                1,
                                MPI_INT,
                                communicator);
      AssertThrowMPI(error);
      for (int p = 0; p < n_ranks; ++p)
        offsets[p + 1] = offsets[p] + sizes[p];
      std::vector<T> all(offsets[n_ranks]);
      error = MPI_Allgatherv(local.data(),
                             size,
                             Utilities::MPI::mpi_type_id_for_type<T>,
                             all.data(),
                             sizes.data(),
                             offsets.data(),
                             Utilities::MPI::mpi_type_id_for_type<T>,
                             communicator);
      AssertThrowMPI(error);
      return all;
    }
  } // namespace



  // @sect3{The condensed back end}
  //
  // With A factorised, the displacement of fixed nodal forces z is
  // u = A^{-1} b - W z, W = A^{-1} N^T, and the contact problem of fixed
  // pieces is the dense m x m problem of CondensedContactSystem on the
  // contact compliance S = N W. set_operator() pays for it: one
  // factorisation and one solve per contact node (in blocks of 64
  // right-hand sides, which CHOLMOD solves with BLAS-3 kernels). After
  // that, an active-set iteration never touches the bulk unknowns, and a
  // step costs one solve with A plus the product W z.
  //
  // On several ranks the factorisation is MUMPS', each rank keeps the rows
  // of W of its own dofs, and S (m^2 doubles) is held by every rank, which
  // solves the small dense problem itself (all ranks do the same
  // arithmetic, so their decisions agree). That is why Method = auto
  // chooses this back end only for small contact surfaces.
  template <int dim>
  class CondensedContactSolver : public ContactSolver<dim>
  {
  public:
    CondensedContactSolver(const Parameters::AllParameters &parameters,
                           const VectorType                &layout);

    // Set-up: the factorisation of A, and W and S from one solve per
    // contact node.
    void
    set_operator(const MatrixType      &A,
                 const bool             symmetric,
                 const ContactSet<dim> &contact) override;
    std::string
    description() const override;
    // Per step problem: A^{-1} b and d = N A^{-1} b; per active-set
    // iteration: the dense problem on the contact nodes; at the end:
    // u = A^{-1} b - W z.
    void
    set_right_hand_side(const VectorType      &b,
                        const ContactSet<dim> &contact) override;
    LinearSolveReport
    solve_for_pieces(ContactSet<dim> &contact, VectorType &u) override;
    void
    finish(const ContactSet<dim> &contact, VectorType &u) override;
    // S x, and a solve with the factorisation.
    void
    apply_compliance(const ContactSet<dim> &contact,
                     const Vector<double>  &x,
                     Vector<double>        &y) override;
    LinearSolveReport
    solve_without_contact(const VectorType &b, VectorType &u) override;

  private:
    const MPI_Comm         communicator;
    SparseDirectSolver     factorization;
    CondensedContactSystem condensed_system;

    // W = A^{-1} N^T, the rows of the locally owned dofs, kept when it
    // takes less than 1 GiB on this rank (the product W z is then one BLAS
    // call); otherwise finish() solves once more.
    LAPACKFullMatrix<double> contact_responses;
    bool                     responses_stored = false;

    // A^{-1} b, the free normal displacements d = N A^{-1} b and the
    // forces z of all contact nodes.
    VectorType     free_displacement;
    Vector<double> d, r_all, z_all;
  };



  template <int dim>
  CondensedContactSolver<dim>::CondensedContactSolver(
    const Parameters::AllParameters &parameters,
    const VectorType                &layout)
    : communicator(layout.get_mpi_communicator())
    , factorization(parameters.direct_solver
                        == Parameters::DirectSolver::automatic
                      ? (Utilities::MPI::n_mpi_processes(communicator) == 1
                           ? Parameters::DirectSolver::cholmod
                           : Parameters::DirectSolver::mumps)
                      : parameters.direct_solver,
                    communicator)
    , free_displacement(layout)
  {}



  template <int dim>
  std::string
  CondensedContactSolver<dim>::description() const
  {
    return "condensed: the operator factorised (" + factorization.description()
           + "), the active set on the contact nodes";
  }



  // @sect4{CondensedContactSolver::set_operator}
  //
  // Columns of W for 64 contact nodes at a time: each rank puts the normals
  // of its nodes of the block into the right-hand sides, all ranks solve
  // together, and each reads off the rows of S of its own nodes. The rows
  // are then gathered on all ranks.
  template <int dim>
  void
  CondensedContactSolver<dim>::set_operator(const MatrixType      &A,
                                            const bool             symmetric,
                                            const ContactSet<dim> &contact)
  {
    factorization.factorize(A, symmetric);
    ++this->counts.operator_setups;

    const unsigned int n_local = free_displacement.locally_owned_size();
    const unsigned int m_local = contact.size();
    const unsigned int m       = contact.n_global_nodes();
    if (m == 0) // no contact: the factorisation is all there is to do
      return;
    const types::global_dof_index first = contact.first_global_index();
    responses_stored = (8. * n_local * m < 1024. * 1024. * 1024.);
    contact_responses.reinit(responses_stored ? n_local : 0,
                             responses_stored ? m : 0);

    std::vector<double> own_rows(std::size_t(m_local) * m);
    const unsigned int  block = 64;
    std::vector<double> columns;
    for (unsigned int first_column = 0; first_column < m; first_column += block)
      {
        const unsigned int n_columns = std::min(block, m - first_column);
        columns.assign(std::size_t(n_local) * n_columns, 0.);
        for (unsigned int i = 0; i < m_local; ++i)
          if (first + i >= first_column && first + i < first_column + n_columns)
            for (unsigned int c = 0; c < dim; ++c)
              columns[std::size_t(first + i - first_column) * n_local
                      + contact.node(i).local_dofs[c]]
                = contact.node(i).normal[c];
        factorization.solve(columns, n_columns);
        this->counts.solves += n_columns;
        for (unsigned int j = 0; j < n_columns; ++j)
          {
            const double *response = &columns[std::size_t(j) * n_local];
            for (unsigned int i = 0; i < m_local; ++i)
              for (unsigned int c = 0; c < dim; ++c)
                own_rows[std::size_t(i) * m + first_column + j]
                  += contact.node(i).normal[c]
                     * response[contact.node(i).local_dofs[c]];
            if (responses_stored)
              for (unsigned int k = 0; k < n_local; ++k)
                contact_responses(k, first_column + j) = response[k];
          }
      }

    const std::vector<double> all_rows
      = gather_on_all_ranks(own_rows, communicator);
    FullMatrix<double> S(m, m);
    for (unsigned int i = 0; i < m; ++i)
      for (unsigned int j = 0; j < m; ++j)
        S(i, j) = all_rows[std::size_t(i) * m + j];
    // S is symmetric in exact arithmetic when A is; make it so in floating
    // point.
    if (symmetric)
      for (unsigned int i = 0; i < m; ++i)
        for (unsigned int j = 0; j < i; ++j)
          S(i, j) = S(j, i) = 0.5 * (S(i, j) + S(j, i));

    std::vector<double> weights(m_local);
    for (unsigned int i = 0; i < m_local; ++i)
      weights[i] = contact.weight(i);
    condensed_system.reinit(contact.law(),
                            S,
                            gather_on_all_ranks(weights, communicator));
  }



  // One solve gives A^{-1} b and with it d = N A^{-1} b.
  template <int dim>
  void
  CondensedContactSolver<dim>::set_right_hand_side(
    const VectorType      &b,
    const ContactSet<dim> &contact)
  {
    factorization.solve(free_displacement, b);
    ++this->counts.solves;
    std::vector<double> own(contact.size());
    for (unsigned int i = 0; i < contact.size(); ++i)
      own[i] = contact.normal_component(free_displacement, i);
    const std::vector<double> all = gather_on_all_ranks(own, communicator);
    d.reinit(all.size());
    std::copy(all.begin(), all.end(), d.begin());
  }



  template <int dim>
  LinearSolveReport
  CondensedContactSolver<dim>::solve_for_pieces(ContactSet<dim> &contact,
                                                VectorType &)
  {
    const std::vector<unsigned int> pieces
      = gather_on_all_ranks(contact.pieces(), communicator);
    LinearSolveReport report;
    report.residual = condensed_system.solve(pieces, d, r_all, z_all);
    const types::global_dof_index first = contact.first_global_index();
    for (unsigned int i = 0; i < contact.size(); ++i)
      {
        contact.r[i] = r_all[first + i];
        contact.z[i] = z_all[first + i];
      }
    return report;
  }



  // u = A^{-1} b - W z: a dense product over the nodes with a force, or
  // one more solve when W is not stored.
  template <int dim>
  void
  CondensedContactSolver<dim>::finish(const ContactSet<dim> &contact,
                                      VectorType            &u)
  {
    const unsigned int n_local = free_displacement.locally_owned_size();
    u                          = free_displacement;
    if (z_all.size() == 0 || z_all.linfty_norm() == 0)
      return;
    if (responses_stored)
      {
        Vector<double> response(n_local);
        contact_responses.vmult(response, z_all);
        for (unsigned int k = 0; k < n_local; ++k)
          u.local_element(k) -= response[k];
        return;
      }
    VectorType forces(free_displacement), response(free_displacement);
    forces = 0;
    for (unsigned int i = 0; i < contact.size(); ++i)
      contact.add_normal(forces, i, contact.z[i]);
    factorization.solve(response, forces);
    ++this->counts.solves;
    u -= response;
  }



  template <int dim>
  LinearSolveReport
  CondensedContactSolver<dim>::solve_without_contact(const VectorType &b,
                                                     VectorType       &u)
  {
    factorization.solve(u, b);
    ++this->counts.solves;
    return LinearSolveReport();
  }



  template <int dim>
  void
  CondensedContactSolver<dim>::apply_compliance(const ContactSet<dim> &contact,
                                                const Vector<double>  &x,
                                                Vector<double>        &y)
  {
    const std::vector<double> x_all
      = gather_on_all_ranks(std::vector<double>(x.begin(), x.end()),
                            communicator);
    const FullMatrix<double>     &S     = condensed_system.compliance();
    const types::global_dof_index first = contact.first_global_index();
    y.reinit(contact.size());
    for (unsigned int i = 0; i < contact.size(); ++i)
      for (unsigned int j = 0; j < x_all.size(); ++j)
        y[i] += S(first + i, j) * x_all[j];
  }



  template class CondensedContactSolver<2>;
  template class CondensedContactSolver<3>;

  template <int dim>
  std::unique_ptr<ContactSolver<dim>>
  create_condensed_contact_solver(const Parameters::AllParameters &parameters,
                                  const VectorType                &layout)
  {
    return std::make_unique<CondensedContactSolver<dim>>(parameters, layout);
  }

  template std::unique_ptr<ContactSolver<2>>
  create_condensed_contact_solver(const Parameters::AllParameters &,
                                  const VectorType &);
  template std::unique_ptr<ContactSolver<3>>
  create_condensed_contact_solver(const Parameters::AllParameters &,
                                  const VectorType &);
} // namespace ViscoContact
