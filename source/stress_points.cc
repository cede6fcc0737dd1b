// StressPointGeometry<dim>: the owned cells, their dofs and the values at
// their stress points, computed once per mesh (stress_points.h).

#include <deal.II/base/exceptions.h>

#include <deal.II/fe/fe_values.h>

#include <deal.II/hp/fe_values.h>

#include "stress_points.h"

#include <cmath>
#include <functional>
#include <unordered_map>

namespace ViscoContact
{
  namespace
  {
    // @sect4{CellShapes}
    //
    // Which owned cells have the same stress-point geometry: JxW and the
    // scalar shape gradients at every stress point, equal up to rounding
    // (1e-12 of the largest value of each kind: cells that are translates of
    // each other, such as those of a box). A hash of a cell's values, each
    // rounded to 2^-30 of that scale, and of the scales finds the
    // candidates, and a candidate's
    // values are computed again to compare, so that only one cell per shape,
    // its representative, is kept. Cells that match a shape use its values,
    // which differ from their own by rounding only.
    template <int dim>
    class CellShapes
    {
    public:
      CellShapes(
        const hp::MappingCollection<dim> &mapping,
        const hp::FECollection<dim>      &fe,
        const hp::QCollection<dim>       &quadrature,
        const std::vector<typename DoFHandler<dim>::active_cell_iterator>
          &cells)
        : cells(cells)
        , candidate(mapping,
                    fe,
                    quadrature,
                    update_gradients | update_JxW_values)
      {}

      // The shape of cell k, whose values fe_values holds.
      unsigned int
      shape_of(const FEValues<dim> &fe_values, const unsigned int k)
      {
        const std::vector<double> values = values_of(fe_values);
        const std::size_t         hash   = hash_of(values);
        for (auto [entry, end] = shapes_of_hash.equal_range(hash); entry != end;
             ++entry)
          {
            candidate.reinit(cells[representatives[entry->second]]);
            if (same(values, values_of(candidate.get_present_fe_values())))
              return entry->second;
          }
        representatives.push_back(k);
        shapes_of_hash.emplace(hash, representatives.size() - 1);
        return representatives.size() - 1;
      }

      // The first cell of every shape.
      std::vector<unsigned int> representatives;

    private:
      // The values the stress points store, JxW first, and the largest
      // magnitude of each kind (JxW, gradient components) at the end.
      std::vector<double>
      values_of(const FEValues<dim> &fe_values) const
      {
        const FiniteElement<dim> &fe = fe_values.get_fe();
        std::vector<double>       values;
        double                    JxW_scale = 0, gradient_scale = 0;
        for (const unsigned int q : fe_values.quadrature_point_indices())
          {
            values.push_back(fe_values.JxW(q));
            JxW_scale = std::max(JxW_scale, std::abs(fe_values.JxW(q)));
          }
        for (const unsigned int q : fe_values.quadrature_point_indices())
          for (unsigned int a = 0; a < fe.base_element(0).n_dofs_per_cell();
               ++a)
            {
              const Tensor<1, dim> gradient = fe_values.shape_grad_component(
                fe.component_to_system_index(0, a),
                q,
                0);
              for (unsigned int d = 0; d < dim; ++d)
                {
                  values.push_back(gradient[d]);
                  gradient_scale
                    = std::max(gradient_scale, std::abs(gradient[d]));
                }
            }
        values.push_back(JxW_scale);
        values.push_back(gradient_scale);
        return values;
      }

      // Each value rounded to 2^-30 of its kind's scale, and the scales
      // themselves to 2^-30 in their logarithm.
      std::size_t
      hash_of(const std::vector<double> &values) const
      {
        const std::size_t n_JxW = n_points;
        const double scales[2]  = {values[values.size() - 2], values.back()};
        std::size_t  hash       = 0;
        const auto   add        = [&hash](const long long key) {
          hash ^= std::hash<long long>()(key) + 0x9e3779b97f4a7c15ULL
                  + (hash << 6) + (hash >> 2);
        };
        for (std::size_t i = 0; i + 2 < values.size(); ++i)
          {
            const double scale = scales[i < n_JxW ? 0 : 1];
            add(std::llround(values[i] / (scale > 0 ? scale : 1.) * (1 << 30)));
          }
        for (const double scale : scales)
          add(std::llround(std::log2(scale > 0 ? scale : 1.) * (1 << 30)));
        return hash;
      }

      // Equal up to 1e-12 of each kind's scale.
      bool
      same(const std::vector<double> &a, const std::vector<double> &b) const
      {
        // Cells of different types have different numbers of values.
        if (a.size() != b.size())
          return false;
        const std::size_t n_JxW     = n_points;
        const double      scales[2] = {a[a.size() - 2], a.back()};
        for (std::size_t i = 0; i < a.size(); ++i)
          {
            const double scale
              = (i + 2 >= a.size() ? a[i] : scales[i < n_JxW ? 0 : 1]);
            if (std::abs(a[i] - b[i]) > 1e-12 * scale)
              return false;
          }
        return true;
      }


      const std::vector<typename DoFHandler<dim>::active_cell_iterator> &cells;
      hp::FEValues<dim> candidate;
      // The stress points of every cell (every element's quadrature has
      // as many).
      const std::size_t n_points
        = candidate.get_quadrature_collection()[0].size();
      std::unordered_multimap<std::size_t, unsigned int> shapes_of_hash;
    };
  } // namespace



  // @sect4{StressPointGeometry::reinit}
  //
  // The list of owned cells fixes the numbering k. Ghost and artificial
  // cells have no stress points here: their stresses belong to the rank
  // that owns them.
  template <int dim>
  void
  StressPointGeometry<dim>::reinit(
    const hp::MappingCollection<dim>  &mapping,
    const DoFHandler<dim>             &dof_handler,
    const hp::QCollection<dim>        &quadrature,
    const Utilities::MPI::Partitioner &partitioner,
    const AffineConstraints<double>   &constraints)
  {
    this->constraints = &constraints;
    owned_cells.clear();
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
        owned_cells.push_back(cell);
    const std::size_t n_cells = owned_cells.size();
    n_points_per_cell         = quadrature[0].size();
    const unsigned int n_q    = n_points_per_cell;
    for (const auto &rule : quadrature)
      AssertThrow(rule.size() == n_q, ExcInternalError());

    // For the linear elements the scalar dofs of a cell are its vertices, so
    // a cell has n_cell_vertices * dim displacement dofs. On a mesh of
    // several cell types n_cell_vertices is the largest number: a cell with
    // fewer vertices (a triangle among quadrilaterals) repeats the dofs of
    // its first vertex in the places of the others, with zero gradients, so
    // that they add nothing.
    const hp::FECollection<dim> &elements = dof_handler.get_fe_collection();
    n_cell_vertices                       = 0;
    for (const auto &element : elements)
      n_cell_vertices
        = std::max(n_cell_vertices, element.base_element(0).n_dofs_per_cell());
    cell_local_dofs.resize(n_cells * n_cell_vertices * dim);
    cell_is_constrained.assign(n_cells, false);
    cell_shape.resize(n_cells);
    hp::FEValues<dim>                    hp_fe_values(mapping,
                                   elements,
                                   quadrature,
                                   update_gradients | update_JxW_values);
    std::vector<types::global_dof_index> dof_indices;
    CellShapes<dim> shapes(mapping, elements, quadrature, owned_cells);
    for (std::size_t k = 0; k < n_cells; ++k)
      {
        const FiniteElement<dim> &fe = owned_cells[k]->get_fe();
        hp_fe_values.reinit(owned_cells[k]);
        dof_indices.resize(fe.n_dofs_per_cell());
        owned_cells[k]->get_dof_indices(dof_indices);
        // Every dof of an owned cell is locally relevant, so each has a
        // local index (owned or ghost). A cell with a constrained dof
        // (clamped, or hanging) is marked: its contributions must go
        // through the constraints.
        const unsigned int n_a = fe.base_element(0).n_dofs_per_cell();
        for (unsigned int a = 0; a < n_cell_vertices; ++a)
          for (unsigned int d = 0; d < dim; ++d)
            {
              const types::global_dof_index dof
                = dof_indices[fe.component_to_system_index(d, a < n_a ? a : 0)];
              cell_local_dofs[(k * n_cell_vertices + a) * dim + d]
                = partitioner.global_to_local(dof);
              if (constraints.is_constrained(dof))
                cell_is_constrained[k] = true;
            }
        // The cell's shape: that of an earlier cell with the same geometry.
        cell_shape[k]
          = shapes.shape_of(hp_fe_values.get_present_fe_values(), k);
      }

    // JxW and the gradients of the scalar shape functions N_a of each shape:
    // the shape function of vertex a in component 0 is N_a e_0, so its
    // gradient in that component is grad N_a, which is all the strains need
    // (eps(N_a e_c) = sym(e_c (x) grad N_a)).
    const std::vector<unsigned int> &representatives = shapes.representatives;
    stress_point_JxW.resize(representatives.size() * n_q);
    stress_point_gradients.assign(representatives.size() * n_q
                                    * n_cell_vertices,
                                  Tensor<1, dim>());
    for (unsigned int shape = 0; shape < representatives.size(); ++shape)
      {
        const auto               &cell = owned_cells[representatives[shape]];
        const FiniteElement<dim> &fe   = cell->get_fe();
        hp_fe_values.reinit(cell);
        const FEValues<dim> &fe_values = hp_fe_values.get_present_fe_values();
        for (unsigned int q = 0; q < n_q; ++q)
          {
            stress_point_JxW[shape * n_q + q] = fe_values.JxW(q);
            for (unsigned int a = 0; a < fe.base_element(0).n_dofs_per_cell();
                 ++a)
              stress_point_gradients[(shape * n_q + q) * n_cell_vertices + a]
                = fe_values.shape_grad_component(
                  fe.component_to_system_index(0, a),
                  q,
                  0);
          }
      }
  }



  // @sect4{StressPointGeometry::displacement_gradient}
  //
  // grad u = sum_a u_a (x) grad N_a at stress point q of the k-th owned
  // cell, from the geometry stored at set-up and the ghosted entries of u.
  //
  // Row c of the result is grad u_c = sum_a u_{a,c} grad N_a. The values are
  // read through the local indices stored for the cell, which point into the
  // owned part or the ghost part of the vector's storage; hence the ghost
  // values must be current, except on one rank, where the vector has no ghosts
  // and the owned part is everything.
  template <int dim>
  Tensor<2, dim>
  StressPointGeometry<dim>::displacement_gradient(
    const VectorType  &displacement,
    const unsigned int k,
    const unsigned int q) const
  {
    // The cell's dofs start at entry k * n_a * dim of cell_local_dofs, its
    // stress point gradients at shape_gradients(k, q).
    const unsigned int    n_a    = n_cell_vertices;
    const unsigned int   *dofs   = &cell_local_dofs[std::size_t(k) * n_a * dim];
    const double         *values = displacement.get_values(); // owned, ghosts
    const Tensor<1, dim> *gradients = shape_gradients(k, q);
    Assert(displacement.has_ghost_elements()
             || displacement.get_partitioner()->n_mpi_processes() == 1,
           ExcMessage("The displacement needs its ghost values here."));
    Tensor<2, dim> gradient;
    for (unsigned int a = 0; a < n_a; ++a)
      for (unsigned int c = 0; c < dim; ++c)
        gradient[c] += values[dofs[a * dim + c]] * gradients[a];
    return gradient;
  }



  // @sect4{StressPointGeometry::add_load}
  //
  // cell_vector += (tau, eps(v)) JxW at stress point q of the k-th owned
  // cell: with eps(N_a e_c) = sym(e_c (x) grad N_a) and tau symmetric, the
  // entry of the cell's dof (a, c) is JxW (tau grad N_a)_c.
  //
  // Called with tau = -H, this is the history load (ViscoplasticContact's
  // update_stresses(), assemble_history_load()); the tangent assembly computes
  // its internal force inline with the same formula. It only adds into a cell
  // vector; distribute() then adds the cell vector to a global one.
  template <int dim>
  void
  StressPointGeometry<dim>::add_load(const SymmetricTensor<2, dim> &tau,
                                     const unsigned int             k,
                                     const unsigned int             q,
                                     const ArrayView<double> &cell_vector) const
  {
    const Tensor<1, dim> *gradients = shape_gradients(k, q);
    const double          JxW       = this->JxW(k, q);
    for (unsigned int a = 0; a < n_cell_vertices; ++a)
      {
        const Tensor<1, dim> force = tau * gradients[a];
        for (unsigned int c = 0; c < dim; ++c)
          cell_vector[a * dim + c] += JxW * force[c];
      }
  }



  // @sect4{StressPointGeometry::add_tangent}
  //
  // The cell dof i is (vertex ai, component ci). With eps(N_a e_c) =
  // sym(e_c (x) grad N_a) and the minor symmetries of C, the entry (i, j) is
  // JxW sum_{m,l} C_{ci m cj l} (grad N_ai)_m (grad N_bj)_l.
  template <int dim>
  void
  StressPointGeometry<dim>::add_tangent(const SymmetricTensor<4, dim> &C,
                                        const unsigned int             k,
                                        const unsigned int             q,
                                        FullMatrix<double> &cell_matrix) const
  {
    const Tensor<1, dim> *gradients = shape_gradients(k, q);
    const double          JxW       = this->JxW(k, q);
    const unsigned int    n_local   = n_cell_vertices * dim;
    for (unsigned int i = 0; i < n_local; ++i)
      {
        const unsigned int ai = i / dim, ci = i % dim;
        for (unsigned int j = 0; j < n_local; ++j)
          {
            const unsigned int bj = j / dim, cj = j % dim;
            double             value = 0;
            for (unsigned int m = 0; m < dim; ++m)
              for (unsigned int l = 0; l < dim; ++l)
                value += C[ci][m][cj][l] * gradients[ai][m] * gradients[bj][l];
            cell_matrix(i, j) += JxW * value;
          }
      }
  }



  // @sect4{StressPointGeometry::distribute}
  //
  // target += the cell vector of the k-th owned cell (dofs ordered (vertex
  // a, component c)). Cells without constrained dofs add straight into the
  // local storage; the others go through the constraints (hanging nodes,
  // the clamped Gamma_1). The caller compresses.
  //
  // The direct path is the common one (most cells touch neither Gamma_1 nor a
  // hanging node) and needs no global dof numbers at all. Entries of dofs owned
  // by other ranks land in the ghost part of target's storage, which is why the
  // caller must start from a zeroed vector and finish with
  // compress(VectorOperation::add).
  template <int dim>
  void
  StressPointGeometry<dim>::distribute(
    const unsigned int             k,
    const ArrayView<const double> &cell_vector,
    VectorType                    &target) const
  {
    const unsigned int  n_local = n_cell_vertices * dim;
    const unsigned int *dofs    = &cell_local_dofs[std::size_t(k) * n_local];
    if (!cell_is_constrained[k])
      {
        double *values = target.get_values(); // owned entries, then ghosts
        for (unsigned int i = 0; i < n_local; ++i)
          values[dofs[i]] += cell_vector[i];
        return;
      }
    // A cell with constrained dofs: back to global dof numbers, which
    // AffineConstraints works with, and let it drop the clamped entries and
    // distribute those of hanging nodes.
    std::vector<types::global_dof_index> global_dofs(n_local);
    const auto &partitioner = *target.get_partitioner();
    for (unsigned int i = 0; i < n_local; ++i)
      global_dofs[i] = partitioner.local_to_global(dofs[i]);
    constraints->distribute_local_to_global(cell_vector.begin(),
                                            cell_vector.end(),
                                            global_dofs.begin(),
                                            target);
  }



  template class StressPointGeometry<2>;
  template class StressPointGeometry<3>;
} // namespace ViscoContact
