#ifndef viscoplastic_contact_condensed_system_h
#define viscoplastic_contact_condensed_system_h

#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/lapack_full_matrix.h>
#include <deal.II/lac/vector.h>

#include "contact_law.h"

#include <optional>
#include <vector>

namespace ViscoContact
{
  using namespace dealii;

  // @sect3{The contact problem condensed to the contact nodes}
  //
  // With the operator K factorised, the displacement of a step problem is
  // u = K^{-1} (b - N^T z), N taking u to its normal components r = N u at
  // the m contact nodes and z the nodal normal forces. Hence
  //   r = d - S z,   d = N K^{-1} b,   S = N K^{-1} N^T (m x m),
  // and for fixed pieces of the contact law the nodal equations are linear
  // in z alone: a node on a sloped piece (slope s, intercept o) has
  // z_i = w_i (o + s r_i), i.e. the row
  //   z_i / (w_i s) + (S z)_i = d_i + o / s,
  // a node on a vertical piece at r = beta has (S z)_i = d_i - beta, and a
  // node on a flat piece (s = 0) has the known force z_i = w_i o. Only the
  // unknown forces enter the dense system, whose LU factorisation is kept
  // while the pieces do not change (in most time steps they do not).
  class CondensedContactSystem
  {
  public:
    // The law, the contact compliance S (taken over: pass a temporary or
    // std::move, so that m^2 doubles are not copied) and the lumped weights
    // of all m contact nodes.
    void
    reinit(const ContactLaw          &law,
           FullMatrix<double>         compliance,
           const std::vector<double> &weights);

    // z and r = d - S z for the pieces of all nodes and the free normal
    // displacements d = N K^{-1} b. Returns how far the nodes are from the
    // linear equations of their pieces (rounding), relative to the size of
    // the normal displacements involved.
    double
    solve(const std::vector<unsigned int> &pieces,
          const Vector<double>            &free_normal_displacement,
          Vector<double>                  &r,
          Vector<double>                  &z);

    const FullMatrix<double> &
    compliance() const;
    unsigned int
    n_factorizations() const;

  private:
    std::optional<ContactLaw> contact_law;
    FullMatrix<double>        S;
    std::vector<double>       w;

    LAPACKFullMatrix<double>  system_matrix;
    std::vector<unsigned int> factorized_pieces;
    std::vector<unsigned int> unknown_nodes;
    unsigned int              factorization_count = 0;
  };
} // namespace ViscoContact

#endif
