// The order of the coarse cells of a p4est mesh (coarse_cell_order.h).
//
// p4est numbers its trees in the order deal.II's
// SparsityTools::reorder_hierarchical() gives the coarse cells, and a cell's
// id names its tree; deal.II visits the cells in the order of the coarse
// mesh. Where the two orders differ, deal.II 9.4's transfer between the
// meshes of global coarsening (the matrix-free back end's multigrid) takes
// time quadratic in the number of cells: it adds the ids of the cells, in
// deal.II's order, one by one to sorted index sets. Measured: 610 s of set-up
// at 10.7M dofs on 19^3 coarse cells. Renumbering the coarse cells in p4est's
// order makes the two orders one.
//
// Written here rather than taken from deal.II: reorder_hierarchical() looks
// for its next pivot by a pass over all candidate rows, which on a Gmsh mesh
// of 314k hexahedra (the Hertz sphere at 986k dofs) took 2.5 to 4.6 s per
// call, and the renumbering needs up to four calls. hierarchical_order()
// keeps the candidates in a set ordered as the pivot is chosen and gives the
// same numbers.

#include <deal.II/base/exceptions.h>
#include <deal.II/base/utilities.h>

#include <deal.II/grid/grid_tools.h>
#include <deal.II/grid/manifold.h>
#include <deal.II/grid/tria_accessor.h>
#include <deal.II/grid/tria_iterator.h>

#include "mesh/coarse_cell_order.h"

#include <algorithm>
#include <limits>
#include <map>
#include <memory>
#include <numeric>
#include <set>
#include <tuple>

namespace ViscoContact
{
  namespace
  {
    using size_type = types::global_dof_index;

    // A symmetric graph in compressed rows, each row's columns sorted (the
    // order in which DynamicSparsityPattern visits them).
    struct Graph
    {
      std::vector<size_type> row_start{0};
      std::vector<size_type> columns;

      size_type
      n_rows() const
      {
        return row_start.size() - 1;
      }
      unsigned int
      row_length(const size_type row) const
      {
        return row_start[row + 1] - row_start[row];
      }
      // The columns of a row, as a range.
      std::pair<const size_type *, const size_type *>
      row(const size_type r) const
      {
        return {columns.data() + row_start[r],
                columns.data() + row_start[r + 1]};
      }
    };

    Graph
    graph_of(const DynamicSparsityPattern &pattern)
    {
      Graph graph;
      graph.row_start.reserve(pattern.n_rows() + 1);
      graph.columns.reserve(pattern.n_nonzero_elements());
      for (size_type r = 0; r < pattern.n_rows(); ++r)
        {
          for (auto entry = pattern.begin(r); entry != pattern.end(r); ++entry)
            graph.columns.push_back(entry->column());
          graph.row_start.push_back(graph.columns.size());
        }
      return graph;
    }

    // The graph with row r renumbered new_number[r].
    Graph
    renumbered(const Graph &graph, const std::vector<size_type> &new_number)
    {
      const size_type n = graph.n_rows();
      Graph           result;
      result.row_start.assign(n + 1, 0);
      for (size_type r = 0; r < n; ++r)
        result.row_start[new_number[r] + 1] = graph.row_length(r);
      std::partial_sum(result.row_start.begin(),
                       result.row_start.end(),
                       result.row_start.begin());
      result.columns.resize(graph.columns.size());
      for (size_type r = 0; r < n; ++r)
        {
          size_type *out
            = result.columns.data() + result.row_start[new_number[r]];
          const auto [begin, end] = graph.row(r);
          for (const size_type *c = begin; c != end; ++c)
            *out++ = new_number[*c];
          std::sort(out - graph.row_length(r), out);
        }
      return result;
    }

    // deal.II's internal::reorder_hierarchical(): visited[k] is the row
    // numbered k. Rows are taken in groups: a pivot and its neighbours not yet
    // taken. The first pivot is the first row with the fewest neighbours (by
    // deal.II's own comparison, kept as it is); each next one is, among the
    // rows next to those taken, the one with the fewest neighbours not yet
    // taken, then the most neighbours, then the lowest index. The groups are
    // then ordered the same way as rows of the graph of groups.
    void
    visiting_order(const Graph &graph, std::vector<size_type> &visited)
    {
      const size_type           n       = graph.n_rows();
      constexpr size_type       untaken = numbers::invalid_dof_index;
      constexpr unsigned int    most    = std::numeric_limits<unsigned>::max();
      std::vector<size_type>    group_of(n, untaken);
      std::vector<unsigned int> remaining(n);
      for (size_type r = 0; r < n; ++r)
        remaining[r] = graph.row_length(r);

      using Key         = std::tuple<unsigned int, unsigned int, size_type>;
      const auto key_of = [&](const size_type r) {
        return Key(remaining[r], most - graph.row_length(r), r);
      };
      std::set<Key>     candidates;
      std::vector<bool> is_candidate(n, false);
      // The groups' rows, one group after the other.
      std::vector<size_type> members;
      std::vector<size_type> group_start{0};
      members.reserve(n);

      while (true)
        {
          // The first pivot of a connected part: deal.II compares a row's
          // length with the remaining neighbours of the row found so far.
          size_type first = untaken, bound = untaken;
          for (size_type r = 0; r < n; ++r)
            if (group_of[r] == untaken && graph.row_length(r) < bound)
              {
                first = r;
                bound = remaining[r];
                if (remaining[r] <= 1)
                  break;
              }
          if (first == untaken)
            break;

          candidates.insert(key_of(first));
          is_candidate[first] = true;
          while (!candidates.empty())
            {
              const size_type pivot = std::get<2>(*candidates.begin());
              const size_type group = group_start.size() - 1;
              const size_type start = members.size();
              members.push_back(pivot);
              group_of[pivot] = group;
              {
                const auto [begin, end] = graph.row(pivot);
                for (const size_type *c = begin; c != end; ++c)
                  if (group_of[*c] == untaken)
                    {
                      members.push_back(*c);
                      group_of[*c] = group;
                    }
              }
              for (size_type m = start; m < members.size(); ++m)
                {
                  const auto [begin, end] = graph.row(members[m]);
                  for (const size_type *c = begin; c != end; ++c)
                    {
                      if (group_of[*c] == untaken && !is_candidate[*c])
                        {
                          candidates.insert(key_of(*c));
                          is_candidate[*c] = true;
                        }
                      if (is_candidate[*c])
                        {
                          candidates.erase(key_of(*c));
                          --remaining[*c];
                          candidates.insert(key_of(*c));
                        }
                      else
                        --remaining[*c];
                    }
                  if (is_candidate[members[m]])
                    {
                      candidates.erase(key_of(members[m]));
                      is_candidate[members[m]] = false;
                    }
                }
              group_start.push_back(members.size());
            }
        }
      AssertThrow(members.size() == n, ExcInternalError());

      const size_type        n_groups = group_start.size() - 1;
      std::vector<size_type> group_order(n_groups);
      if (n_groups < n)
        {
          // The graph of the groups: two groups are neighbours if a row of
          // one is a neighbour of a row of the other.
          Graph groups;
          for (size_type g = 0; g < n_groups; ++g)
            {
              const size_type row_begin = groups.columns.size();
              for (size_type m = group_start[g]; m < group_start[g + 1]; ++m)
                {
                  const auto [begin, end] = graph.row(members[m]);
                  for (const size_type *c = begin; c != end; ++c)
                    groups.columns.push_back(group_of[*c]);
                }
              const auto row_begin_it = groups.columns.begin() + row_begin;
              std::sort(row_begin_it, groups.columns.end());
              groups.columns.erase(std::unique(row_begin_it,
                                               groups.columns.end()),
                                   groups.columns.end());
              groups.row_start.push_back(groups.columns.size());
            }
          visiting_order(groups, group_order);
        }
      else
        std::iota(group_order.begin(), group_order.end(), size_type(0));

      size_type k = 0;
      for (const size_type g : group_order)
        for (size_type m = group_start[g]; m < group_start[g + 1]; ++m)
          visited[k++] = members[m];
    }

    std::vector<size_type>
    hierarchical_order(const Graph &graph)
    {
      std::vector<size_type> visited(graph.n_rows());
      visiting_order(graph, visited);
      return Utilities::invert_permutation(visited);
    }

    bool
    is_identity(const std::vector<size_type> &numbers)
    {
      for (size_type i = 0; i < numbers.size(); ++i)
        if (numbers[i] != i)
          return false;
      return true;
    }
  } // namespace



  std::vector<types::global_dof_index>
  hierarchical_order(const DynamicSparsityPattern &graph)
  {
    return hierarchical_order(graph_of(graph));
  }



  // @sect4{number_coarse_cells_as_p4est_trees}
  //
  // reorder_hierarchical() of the renumbered mesh is again a permutation, so
  // the renumbering is repeated until it is the identity (twice for the
  // generated boxes; a Gmsh mesh that never gets there after four rounds
  // keeps a nearly sorted order, which costs little). The rounds renumber the
  // graph of the cells, not the mesh, which is rebuilt once. The cells keep
  // their vertices in order, so their faces keep their local numbers, with
  // their boundary and manifold ids.
  template <int dim>
  void
  number_coarse_cells_as_p4est_trees(Triangulation<dim> &coarse_mesh)
  {
    DynamicSparsityPattern connectivity;
    GridTools::get_vertex_connectivity_of_cells(coarse_mesh, connectivity);
    Graph graph = graph_of(connectivity);
    connectivity.reinit(0, 0);
    std::vector<size_type> tree_of_cell(graph.n_rows());
    std::iota(tree_of_cell.begin(), tree_of_cell.end(), size_type(0));
    for (unsigned int round = 0; round < 4; ++round)
      {
        const std::vector<size_type> order = hierarchical_order(graph);
        if (is_identity(order))
          break;
        for (size_type &tree : tree_of_cell)
          tree = order[tree];
        graph = renumbered(graph, order);
      }
    if (is_identity(tree_of_cell))
      return;

    // The cells in tree order, and what their faces (and, in 3D, edges)
    // carry, to be given back to the rebuilt cells.
    struct FaceIds
    {
      types::boundary_id boundary_id;
      types::manifold_id manifold_id;
    };
    std::vector<CellData<dim>>        cells(tree_of_cell.size());
    std::vector<std::vector<FaceIds>> face_ids(cells.size());
    std::vector<std::vector<FaceIds>> line_ids(cells.size());
    for (const auto &cell : coarse_mesh.cell_iterators_on_level(0))
      {
        const size_type tree = tree_of_cell[cell->index()];
        CellData<dim>  &data = cells[tree];
        data.vertices.resize(cell->n_vertices());
        for (const unsigned int v : cell->vertex_indices())
          data.vertices[v] = cell->vertex_index(v);
        data.material_id = cell->material_id();
        data.manifold_id = cell->manifold_id();
        for (const unsigned int f : cell->face_indices())
          face_ids[tree].push_back(
            {cell->face(f)->boundary_id(), cell->face(f)->manifold_id()});
        if (dim == 3)
          for (const unsigned int l : cell->line_indices())
            line_ids[tree].push_back(
              {cell->line(l)->boundary_id(), cell->line(l)->manifold_id()});
      }
    // clear() drops the manifolds too: they are put back.
    std::map<types::manifold_id, std::unique_ptr<Manifold<dim>>> manifolds;
    for (const types::manifold_id id : coarse_mesh.get_manifold_ids())
      if (id != numbers::flat_manifold_id)
        manifolds[id] = coarse_mesh.get_manifold(id).clone();
    const std::vector<Point<dim>> vertices = coarse_mesh.get_vertices();
    coarse_mesh.clear();
    for (const auto &[id, manifold] : manifolds)
      coarse_mesh.set_manifold(id, *manifold);
    coarse_mesh.create_triangulation(vertices, cells, SubCellData());
    for (const auto &cell : coarse_mesh.cell_iterators_on_level(0))
      {
        const unsigned int tree = cell->index();
        for (const unsigned int f : cell->face_indices())
          {
            if (cell->face(f)->at_boundary())
              cell->face(f)->set_boundary_id(face_ids[tree][f].boundary_id);
            cell->face(f)->set_manifold_id(face_ids[tree][f].manifold_id);
          }
        if (dim == 3)
          for (const unsigned int l : cell->line_indices())
            {
              if (cell->line(l)->at_boundary())
                cell->line(l)->set_boundary_id(line_ids[tree][l].boundary_id);
              cell->line(l)->set_manifold_id(line_ids[tree][l].manifold_id);
            }
      }
  }



  template void
  number_coarse_cells_as_p4est_trees(Triangulation<2> &);
  template void
  number_coarse_cells_as_p4est_trees(Triangulation<3> &);
} // namespace ViscoContact
