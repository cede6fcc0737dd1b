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
#include <deal.II/base/bounding_box.h>
#include <deal.II/base/exceptions.h>
#include <deal.II/base/index_set.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/quadrature.h>
#include <deal.II/base/utilities.h>

#include <deal.II/distributed/tria_base.h>

#include <deal.II/dofs/dof_tools.h>

#include <deal.II/fe/fe.h>
#include <deal.II/fe/fe_values.h>

#include <deal.II/hp/fe_values.h>

#include <deal.II/grid/grid_tools.h>

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
#include <numeric>
#include <set>
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



    // The bounding box of every body over the locally owned cells of all
    // ranks. One reduction: the maxima of the negated lower corners and of
    // the upper corners.
    template <int dim>
    std::vector<BoundingBox<dim>>
    body_boxes(const Triangulation<dim>        &triangulation,
               const std::vector<unsigned int> &cell_bodies,
               const unsigned int               n_bodies,
               const MPI_Comm                   communicator)
    {
      std::vector<double> local(2 * dim * n_bodies,
                                -std::numeric_limits<double>::max()),
        global(local.size());
      for (const auto &cell : triangulation.active_cell_iterators())
        if (cell->is_locally_owned())
          {
            double *box
              = &local[2 * dim * cell_bodies[cell->active_cell_index()]];
            for (const unsigned int v : cell->vertex_indices())
              for (unsigned int d = 0; d < dim; ++d)
                {
                  box[d]       = std::max(box[d], -cell->vertex(v)[d]);
                  box[dim + d] = std::max(box[dim + d], cell->vertex(v)[d]);
                }
          }
      Utilities::MPI::max(ArrayView<const double>(local.data(), local.size()),
                          communicator,
                          ArrayView<double>(global.data(), global.size()));
      std::vector<BoundingBox<dim>> boxes;
      for (unsigned int b = 0; b < n_bodies; ++b)
        {
          Point<dim> lower, upper;
          for (unsigned int d = 0; d < dim; ++d)
            {
              lower[d] = -global[2 * dim * b + d];
              upper[d] = global[2 * dim * b + dim + d];
            }
          AssertThrow(lower.distance(upper) > 0,
                      ExcMessage("The mesh has no extent: no rigid motions."));
          boxes.emplace_back(std::make_pair(lower, upper));
        }
      return boxes;
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
    modes_at_support_points(const hp::MappingCollection<dim>    &mapping,
                            const DoFHandler<dim>               &dof_handler,
                            const IndexSet                      &to_evaluate,
                            const std::vector<unsigned int>     &cell_bodies,
                            const std::vector<BoundingBox<dim>> &boxes)
    {
      std::vector<ModeValues<dim>> values(to_evaluate.n_elements());
      std::vector<bool>            evaluated(to_evaluate.n_elements(), false);
      hp::QCollection<dim>         support_points;
      for (const auto &element : dof_handler.get_fe_collection())
        support_points.push_back(
          Quadrature<dim>(element.get_unit_support_points()));
      hp::FEValues<dim>                    hp_fe_values(mapping,
                                     dof_handler.get_fe_collection(),
                                     support_points,
                                     update_quadrature_points);
      std::vector<types::global_dof_index> dof_indices;
      for (const auto &cell : dof_handler.active_cell_iterators())
        if (!cell->is_artificial())
          {
            const FiniteElement<dim> &fe = cell->get_fe();
            dof_indices.resize(fe.n_dofs_per_cell());
            cell->get_dof_indices(dof_indices);
            bool reinitialized = false;
            for (unsigned int k = 0; k < dof_indices.size(); ++k)
              if (to_evaluate.is_element(dof_indices[k]))
                {
                  const auto n = to_evaluate.index_within_set(dof_indices[k]);
                  if (evaluated[n])
                    continue;
                  if (!reinitialized)
                    hp_fe_values.reinit(cell);
                  reinitialized = true;
                  const FEValues<dim> &fe_values
                    = hp_fe_values.get_present_fe_values();
                  const BoundingBox<dim> &box
                    = boxes[cell_bodies[cell->active_cell_index()]];
                  values[n]
                    = mode_values<dim>(fe.system_to_component_index(k).first,
                                       fe_values.quadrature_point(k),
                                       box.center(),
                                       box.get_boundary_points().first.distance(
                                         box.get_boundary_points().second));
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



  // @sect4{body_of_cells}
  //
  // The bodies of the mesh, its connected components (cells joined by a
  // vertex): the body number of every active cell this rank knows (by
  // active_cell_index(); artificial cells get none), and the number of
  // bodies. A rank sees only its own and its ghost cells, so each cell
  // starts with the global id of its coarse cell, every rank joins its
  // cells by their vertices and gives each component the smallest id in
  // it, and the owners send their cells' ids to the ranks that see them
  // as ghosts, until no id changes on any rank (a few rounds: as many as
  // ranks a body spans in a row). The bodies are numbered in the order of
  // their smallest coarse cell id, the same on every rank.
  template <int dim>
  std::vector<unsigned int>
  body_of_cells(const Triangulation<dim> &triangulation,
                const MPI_Comm            communicator,
                unsigned int             &n_bodies)
  {
    constexpr auto                     none = numbers::invalid_coarse_cell_id;
    std::vector<types::coarse_cell_id> label(triangulation.n_active_cells(),
                                             none);
    for (const auto &cell : triangulation.active_cell_iterators())
      if (!cell->is_artificial())
        label[cell->active_cell_index()] = cell->id().get_coarse_cell_id();
    const bool parallel_mesh
      = dynamic_cast<const parallel::TriangulationBase<dim> *>(&triangulation)
        != nullptr;
    for (bool changed = true; changed;)
      {
        if (parallel_mesh)
          GridTools::exchange_cell_data_to_ghosts<types::coarse_cell_id,
                                                  Triangulation<dim>>(
            triangulation,
            [&](const auto &cell) {
              return std_cxx17::optional<types::coarse_cell_id>(
                label[cell->active_cell_index()]);
            },
            [&](const auto &cell, const types::coarse_cell_id &id) {
              label[cell->active_cell_index()] = id;
            });
        // Union-find over the cells this rank knows, by shared vertices.
        std::vector<unsigned int> root(label.size());
        std::iota(root.begin(), root.end(), 0u);
        const auto find = [&](unsigned int c) {
          while (root[c] != c)
            c = root[c] = root[root[c]];
          return c;
        };
        std::vector<unsigned int> cell_at_vertex(triangulation.n_vertices(),
                                                 numbers::invalid_unsigned_int);
        for (const auto &cell : triangulation.active_cell_iterators())
          if (!cell->is_artificial())
            for (const unsigned int v : cell->vertex_indices())
              {
                unsigned int &other = cell_at_vertex[cell->vertex_index(v)];
                if (other == numbers::invalid_unsigned_int)
                  other = cell->active_cell_index();
                else
                  {
                    const unsigned int a = find(other),
                                       b = find(cell->active_cell_index());
                    root[std::max(a, b)] = std::min(a, b);
                  }
              }
        std::map<unsigned int, types::coarse_cell_id> smallest;
        for (const auto &cell : triangulation.active_cell_iterators())
          if (!cell->is_artificial())
            {
              const unsigned int c  = cell->active_cell_index();
              auto               it = smallest.emplace(find(c), label[c]).first;
              it->second            = std::min(it->second, label[c]);
            }
        bool local_change = false;
        for (const auto &cell : triangulation.active_cell_iterators())
          if (!cell->is_artificial())
            {
              const unsigned int          c  = cell->active_cell_index();
              const types::coarse_cell_id id = smallest.at(find(c));
              local_change
                = local_change || (cell->is_locally_owned() && id != label[c]);
              label[c] = id;
            }
        changed = Utilities::MPI::max(local_change ? 1u : 0u, communicator) > 0;
      }
    std::set<types::coarse_cell_id> own_labels;
    for (const auto &cell : triangulation.active_cell_iterators())
      if (cell->is_locally_owned())
        own_labels.insert(label[cell->active_cell_index()]);
    const std::set<types::coarse_cell_id> all_labels
      = Utilities::MPI::compute_set_union(own_labels, communicator);
    const std::vector<types::coarse_cell_id> labels(all_labels.begin(),
                                                    all_labels.end());
    n_bodies = labels.size();
    std::vector<unsigned int> body(label.size(), numbers::invalid_unsigned_int);
    for (unsigned int c = 0; c < label.size(); ++c)
      if (label[c] != none)
        body[c] = std::lower_bound(labels.begin(), labels.end(), label[c])
                  - labels.begin();
    return body;
  }



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
  std::vector<FreeBody<dim>>
  free_rigid_motions(const hp::MappingCollection<dim> &mapping,
                     const DoFHandler<dim>            &dof_handler,
                     const AffineConstraints<double>  &constraints,
                     const MPI_Comm                    communicator)
  {
    constexpr unsigned int n_modes = n_rigid_modes<dim>;
    for (const auto &fe : dof_handler.get_fe_collection())
      AssertThrow(fe.n_components() == dim && fe.is_primitive()
                    && fe.has_support_points(),
                  ExcMessage("free_rigid_motions() needs primitive elements "
                             "with dim components and support points."));

    // (0) The bodies, and the body of every constrained dof this rank owns
    // (a constraint couples dofs of one body only).
    unsigned int                    n_bodies = 0;
    const std::vector<unsigned int> cell_bodies
      = body_of_cells(dof_handler.get_triangulation(), communicator, n_bodies);
    const std::vector<BoundingBox<dim>> boxes
      = body_boxes(dof_handler.get_triangulation(),
                   cell_bodies,
                   n_bodies,
                   communicator);
    const IndexSet &owned = dof_handler.locally_owned_dofs();
    std::map<types::global_dof_index, unsigned int> line_body;
    std::vector<types::global_dof_index>            cell_dofs;
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          cell_dofs.resize(cell->get_fe().n_dofs_per_cell());
          cell->get_dof_indices(cell_dofs);
          for (const auto i : cell_dofs)
            if (owned.is_element(i) && constraints.is_constrained(i))
              line_body[i] = cell_bodies[cell->active_cell_index()];
        }

    // (1) The lines of G and the dofs whose modes they need.
    std::vector<types::global_dof_index> lines, needed_dofs;
    for (const auto &[i, body] : line_body)
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
                                cell_bodies,
                                boxes);

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

    // (4) G = sum_i r_i r_i^T over the constrained dofs of all ranks, one
    // per body (inhomogeneities play no part).
    const unsigned int  size = n_modes * n_modes;
    std::vector<double> local_gram(n_bodies * size), gram(n_bodies * size);
    for (const auto i : lines)
      {
        ModeValues<dim> r = mode_values_of(i);
        for (const auto &[j, a] : *constraints.get_constraint_entries(i))
          {
            const ModeValues<dim> &m = mode_values_of(j);
            for (unsigned int k = 0; k < n_modes; ++k)
              r[k] -= a * m[k];
          }
        double *body_gram = &local_gram[line_body.at(i) * size];
        for (unsigned int k = 0; k < n_modes; ++k)
          for (unsigned int l = 0; l < n_modes; ++l)
            body_gram[k * n_modes + l] += r[k] * r[l];
      }
    Utilities::MPI::sum(ArrayView<const double>(local_gram.data(),
                                                local_gram.size()),
                        communicator,
                        ArrayView<double>(gram.data(), gram.size()));

    // (5) The names of the motions in the null space of each body's G.
    // Every rank has the same G; rank 0's names make sure of the same
    // answer also where a reduction could round differently on each rank.
    std::vector<std::vector<std::string>> names(n_bodies);
    for (unsigned int b = 0; b < n_bodies; ++b)
      {
        std::array<double, size> body_gram;
        std::copy(gram.begin() + b * size,
                  gram.begin() + (b + 1) * size,
                  body_gram.begin());
        names[b] = null_space_names<dim>(body_gram);
      }
    names = Utilities::MPI::broadcast(communicator, names, 0);
    std::vector<FreeBody<dim>> free;
    for (unsigned int b = 0; b < n_bodies; ++b)
      if (!names[b].empty())
        free.push_back({b + 1,
                        n_bodies,
                        boxes[b].get_boundary_points().first,
                        boxes[b].get_boundary_points().second,
                        names[b]});
    return free;
  }



  template std::vector<unsigned int>
  body_of_cells(const Triangulation<2> &, const MPI_Comm, unsigned int &);
  template std::vector<unsigned int>
  body_of_cells(const Triangulation<3> &, const MPI_Comm, unsigned int &);
  template std::vector<FreeBody<2>>
  free_rigid_motions(const hp::MappingCollection<2> &,
                     const DoFHandler<2> &,
                     const AffineConstraints<double> &,
                     const MPI_Comm);
  template std::vector<FreeBody<3>>
  free_rigid_motions(const hp::MappingCollection<3> &,
                     const DoFHandler<3> &,
                     const AffineConstraints<double> &,
                     const MPI_Comm);
} // namespace ViscoContact
