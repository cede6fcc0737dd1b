// The rigid motions that the constraints of the displacement leave free.
//
// A rigid motion v (the dim translations and the dim(dim-1)/2 infinitesimal
// rotations) has no strain, so the unconstrained stiffness matrix maps its
// nodal values to zero, and (for a connected body) K on the constrained
// space is singular exactly when some combination of rigid motions
// satisfies every constraint. P1 and Q1 interpolate linear fields exactly,
// so the finite element function of a rigid motion is its nodal values
// m_i = v(x_i)[c_i] (x_i the support point of dof i, c_i its component),
// and it satisfies the (homogeneous) constraints when the residual
//   r_i = m_i - sum_j a_ij m_j
// of every constrained dof i vanishes. A hanging-node constraint
// interpolates linearly along the coarse face or edge, so every rigid
// motion satisfies it: hanging nodes stop nothing. u = 0 on a clamped face
// stops everything.
//
// For a combination sum_k alpha_k v_k of the n_modes rigid motions the
// residuals are linear in alpha, r_i . alpha with r_i the vector of the
// residuals of the single modes, and
//   sum_i (r_i . alpha)^2 = alpha^T G alpha,    G = sum_i r_i r_i^T,
// the sum over all constrained dofs (each on the rank that owns it). The
// free combinations are the null space of the small n_modes x n_modes
// matrix G: the eigenvectors of its (numerically) zero eigenvalues. The
// modes are evaluated at positions relative to the centre of the mesh's
// bounding box and scaled by its diameter, so that every mode has entries
// of order one and the eigenvalues of G are measured against 1: an
// eigenvalue below 1e-10 is zero. (An eigenvalue between 1e-10 and 1 is a
// motion stopped only weakly, e.g. a rotation stopped by a single support
// point close to its axis; K is then badly conditioned, not singular.)
//
// This is written by hand: deal.II 9.4 has the rigid-body modes only as the
// near-null space of algebraic multigrid (the constant modes of
// DoFTools::extract_constant_modes, or vectors the user builds, as
// rigid_body_modes.h does), and no function that checks which of them
// the constraints of a problem leave free.

#include <deal.II/base/array_view.h>
#include <deal.II/base/exceptions.h>
#include <deal.II/base/index_set.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/quadrature.h>
#include <deal.II/base/utilities.h>

#include <deal.II/dofs/dof_tools.h>

#include <deal.II/fe/fe.h>
#include <deal.II/fe/fe_values.h>

#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/lapack_full_matrix.h>
#include <deal.II/lac/vector.h>

#include "back_ends/rigid_body_modes.h"
#include "rigid_motions.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <iomanip>
#include <limits>
#include <map>
#include <sstream>
#include <utility>

namespace ViscoContact
{
  namespace
  {
    template <int dim>
    constexpr unsigned int n_rigid_modes = (dim == 2 ? 3 : 6);

    template <int dim>
    using ModeValues = std::array<double, n_rigid_modes<dim>>;

    // The names of the modes, in the order of rigid_body_mode_components():
    // the translations, then the rotations (in 3D about x, y, z).
    template <int dim>
    std::string
    mode_name(const unsigned int k)
    {
      const char *const axes[] = {"x", "y", "z"};
      if (k < dim)
        return std::string("translation in ") + axes[k];
      return std::string("rotation about ") + (dim == 2 ? "z" : axes[k - dim]);
    }



    // The centre and the diameter of the bounding box of the vertices of the
    // locally owned cells of all ranks. One reduction: the maxima of the
    // negated lower corner and of the upper corner.
    template <int dim>
    std::pair<Point<dim>, double>
    bounding_box(const Triangulation<dim> &triangulation,
                 const MPI_Comm            communicator)
    {
      std::array<double, 2 * dim> local, global;
      local.fill(-std::numeric_limits<double>::max());
      for (const auto &cell : triangulation.active_cell_iterators())
        if (cell->is_locally_owned())
          for (const unsigned int v : cell->vertex_indices())
            for (unsigned int d = 0; d < dim; ++d)
              {
                local[d]       = std::max(local[d], -cell->vertex(v)[d]);
                local[dim + d] = std::max(local[dim + d], cell->vertex(v)[d]);
              }
      Utilities::MPI::max(ArrayView<const double>(local.data(), 2 * dim),
                          communicator,
                          ArrayView<double>(global.data(), 2 * dim));
      Point<dim> centre;
      double     diameter = 0;
      for (unsigned int d = 0; d < dim; ++d)
        {
          centre[d] = 0.5 * (global[dim + d] - global[d]);
          diameter += Utilities::fixed_power<2>(global[dim + d] + global[d]);
        }
      diameter = std::sqrt(diameter);
      AssertThrow(diameter > 0,
                  ExcMessage("The mesh has no extent: no rigid motions."));
      return {centre, diameter};
    }



    // Component c of every mode at x, in the scaled position (x - centre) /
    // diameter. rigid_body_mode_components() gives the rotations of 3D as
    // cross(x, e_d); the sign is turned so that every rotation is
    // right-handed, cross(e_d, x), as the 2D one already is.
    template <int dim>
    ModeValues<dim>
    mode_values(const unsigned int c,
                const Point<dim>  &x,
                const Point<dim>  &centre,
                const double       diameter)
    {
      Point<dim> y;
      for (unsigned int d = 0; d < dim; ++d)
        y[d] = (x[d] - centre[d]) / diameter;
      ModeValues<dim> m = rigid_body_mode_components<dim>(c, y);
      if constexpr (dim == 3)
        for (unsigned int k = dim; k < n_rigid_modes<dim>; ++k)
          m[k] = -m[k];
      return m;
    }



    // The name of a free motion, a unit vector of mode coefficients: the
    // mode alone if it is nearly all of it, otherwise the combination with
    // its coefficients to two digits (those below 0.01 left out).
    template <int dim>
    std::string
    motion_name(const ModeValues<dim> &alpha)
    {
      for (unsigned int k = 0; k < n_rigid_modes<dim>; ++k)
        if (std::abs(alpha[k]) > 0.999)
          return mode_name<dim>(k);
      std::ostringstream name;
      name << std::fixed << std::setprecision(2);
      bool first = true;
      for (unsigned int k = 0; k < n_rigid_modes<dim>; ++k)
        if (std::abs(alpha[k]) >= 0.01)
          {
            if (first)
              name << (alpha[k] < 0 ? "-" : "");
            else
              name << (alpha[k] < 0 ? " - " : " + ");
            name << std::abs(alpha[k]) << ' ' << mode_name<dim>(k);
            first = false;
          }
      return name.str();
    }



    // The rigid modes at the support points of the dofs in to_evaluate,
    // on the cells this rank knows (every locally relevant dof lies on
    // one); FEValues maps the unit support points only on cells that carry
    // a dof to evaluate.
    template <int dim>
    std::vector<ModeValues<dim>>
    modes_at_support_points(const Mapping<dim>    &mapping,
                            const DoFHandler<dim> &dof_handler,
                            const IndexSet        &to_evaluate,
                            const MPI_Comm         communicator)
    {
      const FiniteElement<dim> &fe = dof_handler.get_fe();
      const auto [centre, diameter]
        = bounding_box(dof_handler.get_triangulation(), communicator);
      std::vector<ModeValues<dim>> values(to_evaluate.n_elements());
      std::vector<bool>            evaluated(to_evaluate.n_elements(), false);
      FEValues<dim>                fe_values(mapping,
                              fe,
                              Quadrature<dim>(fe.get_unit_support_points()),
                              update_quadrature_points);
      std::vector<types::global_dof_index> dof_indices(fe.n_dofs_per_cell());
      for (const auto &cell : dof_handler.active_cell_iterators())
        if (!cell->is_artificial())
          {
            cell->get_dof_indices(dof_indices);
            bool reinitialized = false;
            for (unsigned int k = 0; k < dof_indices.size(); ++k)
              if (to_evaluate.is_element(dof_indices[k]))
                {
                  const auto n = to_evaluate.index_within_set(dof_indices[k]);
                  if (evaluated[n])
                    continue;
                  if (!reinitialized)
                    fe_values.reinit(cell);
                  reinitialized = true;
                  values[n]
                    = mode_values<dim>(fe.system_to_component_index(k).first,
                                       fe_values.quadrature_point(k),
                                       centre,
                                       diameter);
                  evaluated[n] = true;
                }
          }
      AssertThrow(std::find(evaluated.begin(), evaluated.end(), false)
                    == evaluated.end(),
                  ExcInternalError());
      return values;
    }



    // The replies to the requests of other ranks (requested: the dofs each
    // asked this rank for, values at the dofs of to_evaluate), and the
    // answers to this rank's requests: the modes at the dofs it asked for.
    template <int dim>
    std::map<types::global_dof_index, ModeValues<dim>>
    exchange_modes(
      const std::vector<ModeValues<dim>> &values,
      const IndexSet                     &to_evaluate,
      const std::map<unsigned int, std::vector<types::global_dof_index>>
        &requests,
      const std::map<unsigned int, std::vector<types::global_dof_index>>
                    &requested,
      const MPI_Comm communicator)
    {
      constexpr unsigned int                      n_modes = n_rigid_modes<dim>;
      std::map<unsigned int, std::vector<double>> replies;
      for (const auto &[rank, dofs] : requested)
        {
          std::vector<double> &reply = replies[rank];
          for (const auto j : dofs)
            {
              const ModeValues<dim> &m
                = values[to_evaluate.index_within_set(j)];
              reply.insert(reply.end(), m.begin(), m.end());
            }
        }
      std::map<types::global_dof_index, ModeValues<dim>> remote_values;
      for (const auto &[rank, answer] :
           Utilities::MPI::some_to_some(communicator, replies))
        {
          const std::vector<types::global_dof_index> &dofs = requests.at(rank);
          AssertThrow(answer.size() == n_modes * dofs.size(),
                      ExcInternalError());
          for (unsigned int n = 0; n < dofs.size(); ++n)
            std::copy(answer.begin() + n_modes * n,
                      answer.begin() + n_modes * (n + 1),
                      remote_values[dofs[n]].begin());
        }
      return remote_values;
    }



    // The null space of the Gram matrix G of the modes over the constrained
    // dofs: the names of the rigid motions the constraints leave free.
    template <int dim>
    std::vector<std::string>
    null_space_names(
      const std::array<double, n_rigid_modes<dim> * n_rigid_modes<dim>> &gram)
    {
      constexpr unsigned int n_modes = n_rigid_modes<dim>;
      // The eigenvectors of the eigenvalues of G below the tolerance, 1e-10
      // or, for sums over very many constrained dofs, the roundoff of the
      // eigenvalues of G (machine epsilon times its norm, at most its trace)
      // if that is larger.
      LAPACKFullMatrix<double> G(n_modes);
      double                   trace = 0;
      for (unsigned int k = 0; k < n_modes; ++k)
        {
          for (unsigned int l = 0; l < n_modes; ++l)
            G(k, l) = gram[k * n_modes + l];
          trace += gram[k * n_modes + k];
        }
      const double tolerance
        = std::max(1e-10, 100 * std::numeric_limits<double>::epsilon() * trace);
      Vector<double>     eigenvalues;
      FullMatrix<double> eigenvectors;
      G.compute_eigenvalues_symmetric(-1. - trace,
                                      tolerance,
                                      2 * std::numeric_limits<double>::min(),
                                      eigenvalues,
                                      eigenvectors);
      const unsigned int n_free = eigenvalues.size();

      // The eigenvectors of a multiple eigenvalue (such as the three of an
      // unconstrained body) are any orthonormal basis of the null space. Its
      // reduced row echelon form (pivots in the order of the modes) is the
      // basis with single modes wherever the null space contains them, and
      // otherwise combinations of as few modes as there can be; each vector
      // is then scaled to length 1, its first coefficient positive.
      std::vector<ModeValues<dim>> basis(n_free);
      for (unsigned int f = 0; f < n_free; ++f)
        for (unsigned int k = 0; k < n_modes; ++k)
          basis[f][k] = eigenvectors(k, f);
      unsigned int row = 0;
      for (unsigned int k = 0; k < n_modes && row < n_free; ++k)
        {
          unsigned int pivot = row;
          for (unsigned int f = row + 1; f < n_free; ++f)
            if (std::abs(basis[f][k]) > std::abs(basis[pivot][k]))
              pivot = f;
          if (std::abs(basis[pivot][k]) < 1e-8)
            continue;
          std::swap(basis[row], basis[pivot]);
          const double scale = 1. / basis[row][k];
          for (double &coefficient : basis[row])
            coefficient *= scale;
          for (unsigned int f = 0; f < n_free; ++f)
            if (f != row)
              {
                const double factor = basis[f][k];
                for (unsigned int l = 0; l < n_modes; ++l)
                  basis[f][l] -= factor * basis[row][l];
              }
          ++row;
        }

      std::vector<std::string> names;
      for (ModeValues<dim> &alpha : basis)
        {
          double norm = 0;
          for (const double coefficient : alpha)
            norm += coefficient * coefficient;
          norm = std::sqrt(norm);
          for (double &coefficient : alpha)
            coefficient /= norm;
          names.push_back(motion_name<dim>(alpha));
        }
      return names;
    }
  } // namespace



  // @sect4{free_rigid_motions}
  //
  // In five steps: (1) the constrained dofs this rank owns and the dofs
  // their constraints refer to; (2) those of the latter whose support
  // points this rank does not know (not locally relevant: a constraint
  // between distant dofs, as of periodicity, or a chain that closing the
  // constraints resolved beyond the ghost layer) are asked of their
  // owners; (3) the modes at the support points of the dofs needed
  // here and by other ranks, then sent to those; (4) G, summed over the
  // ranks; (5) its null space and the names of the motions.
  template <int dim>
  std::vector<std::string>
  free_rigid_motions(const Mapping<dim>              &mapping,
                     const DoFHandler<dim>           &dof_handler,
                     const AffineConstraints<double> &constraints,
                     const MPI_Comm                   communicator)
  {
    constexpr unsigned int    n_modes = n_rigid_modes<dim>;
    const FiniteElement<dim> &fe      = dof_handler.get_fe();
    AssertThrow(fe.n_components() == dim && fe.is_primitive()
                  && fe.has_support_points(),
                ExcMessage("free_rigid_motions() needs a primitive element "
                           "with dim components and support points."));

    // (1) The lines of G and the dofs whose modes they need.
    const IndexSet &owned = dof_handler.locally_owned_dofs();
    std::vector<types::global_dof_index> lines, needed_dofs;
    for (const auto i : owned)
      if (constraints.is_constrained(i))
        {
          lines.push_back(i);
          needed_dofs.push_back(i);
          for (const auto &entry : *constraints.get_constraint_entries(i))
            needed_dofs.push_back(entry.first);
        }
    std::sort(needed_dofs.begin(), needed_dofs.end());
    needed_dofs.erase(std::unique(needed_dofs.begin(), needed_dofs.end()),
                      needed_dofs.end());
    IndexSet needed(dof_handler.n_dofs());
    needed.add_indices(needed_dofs.begin(), needed_dofs.end());

    // (2) The dofs to evaluate here: the needed ones among the locally
    // relevant dofs, and those other ranks ask for (which this rank owns).
    const IndexSet relevant
      = DoFTools::extract_locally_relevant_dofs(dof_handler);
    IndexSet missing = needed;
    missing.subtract_set(relevant);
    IndexSet   to_evaluate = needed & relevant;
    const bool any_missing
      = Utilities::MPI::max(missing.n_elements() > 0 ? 1u : 0u, communicator)
        > 0;
    std::map<unsigned int, std::vector<types::global_dof_index>> requests,
      requested;
    if (any_missing)
      {
        const std::vector<unsigned int> owners
          = Utilities::MPI::compute_index_owner(owned, missing, communicator);
        unsigned int n = 0;
        for (const auto j : missing)
          requests[owners[n++]].push_back(j);
        requested = Utilities::MPI::some_to_some(communicator, requests);
        for (const auto &[rank, dofs] : requested)
          to_evaluate.add_indices(dofs.begin(), dofs.end());
      }

    // (3) The modes at the support points, here and for other ranks.
    const std::vector<ModeValues<dim>> values
      = modes_at_support_points(mapping,
                                dof_handler,
                                to_evaluate,
                                communicator);

    // The modes of the dofs other ranks evaluated for this one.
    const std::map<types::global_dof_index, ModeValues<dim>> remote_values
      = any_missing ? exchange_modes<dim>(values,
                                          to_evaluate,
                                          requests,
                                          requested,
                                          communicator)
                    : std::map<types::global_dof_index, ModeValues<dim>>();
    const auto mode_values_of
      = [&](const types::global_dof_index j) -> const ModeValues<dim> & {
      if (to_evaluate.is_element(j))
        return values[to_evaluate.index_within_set(j)];
      return remote_values.at(j);
    };

    // (4) G = sum_i r_i r_i^T over the constrained dofs of all ranks
    // (inhomogeneities play no part).
    std::array<double, n_modes * n_modes> local_gram{}, gram;
    for (const auto i : lines)
      {
        ModeValues<dim> r = mode_values_of(i);
        for (const auto &[j, a] : *constraints.get_constraint_entries(i))
          {
            const ModeValues<dim> &m = mode_values_of(j);
            for (unsigned int k = 0; k < n_modes; ++k)
              r[k] -= a * m[k];
          }
        for (unsigned int k = 0; k < n_modes; ++k)
          for (unsigned int l = 0; l < n_modes; ++l)
            local_gram[k * n_modes + l] += r[k] * r[l];
      }
    Utilities::MPI::sum(ArrayView<const double>(local_gram.data(),
                                                local_gram.size()),
                        communicator,
                        ArrayView<double>(gram.data(), gram.size()));

    // (5) The names of the motions in the null space of G.
    const std::vector<std::string> names = null_space_names<dim>(gram);
    // Every rank has the same G; rank 0's names make sure of the same
    // answer also where a reduction could round differently on each rank.
    return Utilities::MPI::broadcast(communicator, names, 0);
  }



  template std::vector<std::string>
  free_rigid_motions(const Mapping<2> &,
                     const DoFHandler<2> &,
                     const AffineConstraints<double> &,
                     const MPI_Comm);
  template std::vector<std::string>
  free_rigid_motions(const Mapping<3> &,
                     const DoFHandler<3> &,
                     const AffineConstraints<double> &,
                     const MPI_Comm);
} // namespace ViscoContact
