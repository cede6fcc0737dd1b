// The checks of a mesh read from a Gmsh file (mesh_checks.h): node ids,
// coordinates, degenerate and twisted cells, coincident nodes and
// non-conforming faces.
//
// deal.II's reader builds a triangulation from whatever the file says: a
// node id defined twice silently replaces the first node, a cell may use a
// node twice, and cells whose faces do not match (a hanging node, a crack)
// become separate pieces of boundary. Its own assertions, where they catch
// anything, speak of an internal error. These checks say what is wrong with
// the file, where, and stop before anything is computed.

#include <deal.II/base/exceptions.h>
#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>

#include <deal.II/grid/tria.h>
#include <deal.II/grid/tria_accessor.h>
#include <deal.II/grid/tria_iterator.h>

#include <deal.II/numerics/rtree.h>

#include "mesh/mesh_checks.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <map>
#include <set>
#include <sstream>

namespace ViscoContact
{
  namespace
  {
    // The start of every message about the file.
    std::string
    invalid_mesh(const std::string &file)
    {
      return "Invalid parameter <Mesh file> in subsection <Geometry>: value <"
             + file + ">: ";
    }

    template <int dim>
    std::string
    coordinates(const Point<dim> &point)
    {
      std::ostringstream text;
      text << std::setprecision(6) << '(';
      for (unsigned int d = 0; d < dim; ++d)
        text << (d > 0 ? ", " : "") << point[d];
      text << ')';
      return text.str();
    }

    // "cell 3 of the file (vertices (0, 0), (1, 0), (0, 1))": cells are
    // numbered as in the file (the reader keeps their order), from 1.
    template <int dim>
    std::string
    cell_description(const unsigned int             index,
                     const std::vector<Point<dim>> &corners)
    {
      std::ostringstream text;
      text << "cell " << index + 1 << " of the file (vertices ";
      for (unsigned int v = 0; v < corners.size(); ++v)
        text << (v > 0 ? ", " : "") << coordinates<dim>(corners[v]);
      text << ')';
      return text.str();
    }

    // The largest distance between two nodes along a coordinate direction.
    template <int dim>
    double
    extent_of(const std::vector<Point<dim>> &points)
    {
      double extent = 0;
      for (unsigned int d = 0; d < dim; ++d)
        {
          const auto [lowest, highest]
            = std::minmax_element(points.begin(),
                                  points.end(),
                                  [d](const auto &a, const auto &b) {
                                    return a[d] < b[d];
                                  });
          if (lowest != points.end())
            extent = std::max(extent, (*highest)[d] - (*lowest)[d]);
        }
      return extent;
    }

    // Reads a Gmsh file up to its "$Nodes" line; returns the format version
    // of its $MeshFormat section (0 if none).
    double
    skip_to_gmsh_nodes(std::istream &in)
    {
      std::string token;
      double      version = 0;
      while (in >> token && token != "$Nodes")
        if (token == "$MeshFormat")
          in >> version;
      return version;
    }
  } // namespace



  template <int dim>
  std::vector<Point<dim>>
  corners_of(const typename Triangulation<dim>::cell_iterator &cell)
  {
    std::vector<Point<dim>> corners;
    for (const unsigned int v : cell->vertex_indices())
      corners.push_back(cell->vertex(v));
    return corners;
  }

  // The Jacobian determinant of a cell at its vertex v, from the edges to
  // its neighbours along each reference direction (for a simplex, dim + 1
  // corners, the same at every vertex), and the product of those edges'
  // lengths: their ratio is the sine of the corner's angle (in 3D, of the
  // solid corner), 0 for a degenerate corner, negative for an inverted one.
  template <int dim>
  std::pair<double, double>
  corner_jacobian(const std::vector<Point<dim>> &corners, const unsigned int v)
  {
    Tensor<2, dim> J;
    double         lengths = 1;
    const bool     simplex = (corners.size() == dim + 1);
    for (unsigned int d = 0; d < dim; ++d)
      {
        // Simplex: the edges from vertex 0. Hypercube: the neighbour of v
        // across direction d (lexicographic numbering), with the sign of
        // the direction.
        const unsigned int from = simplex ? 0 : v;
        const unsigned int to   = simplex ? d + 1 : (v ^ (1u << d));
        Tensor<1, dim>     edge = corners[to] - corners[from];
        if (!simplex && (v & (1u << d)))
          edge = -edge;
        for (unsigned int c = 0; c < dim; ++c)
          J[c][d] = edge[c];
        lengths *= edge.norm();
      }
    return {determinant(J), lengths};
  }



  // @sect4{check_gmsh_sections}
  //
  // The counts at the heads of the $Nodes and $Elements sections of an ASCII
  // Gmsh file, then the node ids. Format 2: "$Nodes" then the count, one
  // "id x y z" line per node, "$Elements" then the count; format 4: blocks
  // ("numEntityBlocks numNodes minTag maxTag", then per block a line "dim
  // tag parametric n", n ids, then n coordinate lines), "$Elements" then
  // "numEntityBlocks numElements minTag maxTag". deal.II's reader sizes its
  // arrays by these counts before it reads a node: a negative count (read
  // as a huge unsigned one) or one far beyond what the file holds would end
  // in an allocation failure instead of a message. Every count must be a
  // whole number no larger than the file's size in bytes (a node or cell
  // takes more than one byte).
  namespace
  {
    // A count of the file: read as a number, which must be a whole one in
    // [0, bound]; the message names what it counts.
    long long
    read_count(std::istream      &in,
               const double       bound,
               const std::string &what,
               const std::string &file)
    {
      std::string token;
      in >> token;
      char              *end   = nullptr;
      const double       value = std::strtod(token.c_str(), &end);
      std::ostringstream message;
      message << invalid_mesh(file) << what << " is <" << token.substr(0, 40)
              << ">; accepted: a whole number from 0 to " << bound
              << " (the size of the file in bytes).";
      AssertThrow(!token.empty() && end == token.c_str() + token.size()
                    && value >= 0 && value <= bound
                    && value == std::floor(value),
                  ExcMessage(message.str()));
      return static_cast<long long>(value);
    }
  } // namespace



  void
  check_gmsh_sections(const std::string &file)
  {
    std::ifstream in(file);
    const double  version = skip_to_gmsh_nodes(in);
    if (!in)
      return; // the reader itself says what is missing
    std::error_code error;
    const double    bound = std::filesystem::file_size(file, error);
    if (error)
      return;
    std::set<long long> ids;
    long long           duplicate = -1;
    const auto          note      = [&](const long long id) {
      if (!ids.insert(id).second && duplicate < 0)
        duplicate = id;
    };
    if (version < 4)
      {
        const long long n
          = read_count(in, bound, "the node count of its $Nodes section", file);
        for (long long i = 0; i < n && in; ++i)
          {
            long long id;
            double    x, y, z;
            in >> id >> x >> y >> z;
            note(id);
          }
      }
    else
      {
        const long long n_blocks
          = read_count(in,
                       bound,
                       "the number of blocks of its $Nodes section",
                       file);
        read_count(in, bound, "the node count of its $Nodes section", file);
        long long min_tag = 0, max_tag = 0;
        in >> min_tag >> max_tag;
        for (long long b = 0; b < n_blocks && in; ++b)
          {
            int entity_dim = 0, entity_tag = 0, parametric = 0;
            in >> entity_dim >> entity_tag >> parametric;
            const long long n
              = read_count(in,
                           bound,
                           "the node count of a block of its $Nodes section",
                           file);
            for (long long i = 0; i < n && in; ++i)
              {
                long long id;
                in >> id;
                note(id);
              }
            // The coordinates: 3 numbers per node, plus the parametric
            // coordinates (entity_dim of them) if there are any.
            const long long numbers = n * (3 + (parametric ? entity_dim : 0));
            double          value;
            for (long long i = 0; i < numbers && in; ++i)
              in >> value;
          }
      }
    AssertThrow(
      duplicate < 0,
      ExcMessage(invalid_mesh(file) + "the node id " + std::to_string(duplicate)
                 + " is defined twice in its $Nodes section; "
                   "accepted: a mesh whose nodes have distinct ids."));
    std::string token;
    while (in >> token && token != "$Elements")
      ;
    if (!in)
      return;
    if (version >= 4)
      read_count(in,
                 bound,
                 "the number of blocks of its $Elements section",
                 file);
    read_count(in, bound, "the element count of its $Elements section", file);
  }



  // @sect4{gmsh_node_count}
  //
  // Format 2: "$Nodes" then the count; format 4: "$Nodes" then
  // "numEntityBlocks numNodes minTag maxTag".
  double
  gmsh_node_count(const std::string &file)
  {
    std::ifstream in(file);
    const double  version = skip_to_gmsh_nodes(in);
    double        blocks = 0, nodes = 0;
    if (version < 4)
      in >> nodes;
    else
      in >> blocks >> nodes;
    return in ? nodes : 0;
  }



  // @sect4{check_mesh_cells}
  //
  // The cells as deal.II's reader hands them to the triangulation (it has
  // already turned cells of the other orientation around, so a consistent
  // mesh has positive Jacobians everywhere), before anything is built: the
  // coordinates of their nodes (check_coordinates()), then each cell in the
  // order of the file (check_cell()).
  namespace
  {
    // Coordinates of the nodes the cells use: finite, and an extent whose
    // dim-th power neither overflows nor underflows, so that measures,
    // Jacobians and their inverses are normal numbers.
    template <int dim>
    void
    check_coordinates(const std::vector<Point<dim>>    &vertices,
                      const std::vector<CellData<dim>> &cells,
                      const std::string                &file)
    {
      std::vector<bool> used(vertices.size(), false);
      for (const CellData<dim> &cell : cells)
        for (const unsigned int v : cell.vertices)
          if (v < vertices.size())
            used[v] = true;
      std::vector<Point<dim>> used_vertices;
      double                  magnitude = 0;
      for (unsigned int v = 0; v < vertices.size(); ++v)
        if (used[v])
          {
            for (unsigned int d = 0; d < dim; ++d)
              {
                AssertThrow(std::isfinite(vertices[v][d]),
                            ExcMessage(invalid_mesh(file)
                                       + "a node has a coordinate that is not "
                                         "finite; accepted: finite "
                                         "coordinates."));
                magnitude = std::max(magnitude, std::abs(vertices[v][d]));
              }
            used_vertices.push_back(vertices[v]);
          }
      const double       extent = extent_of(used_vertices);
      std::ostringstream message;
      message << std::setprecision(3) << invalid_mesh(file) << "its nodes span "
              << extent << " at coordinates up to " << magnitude
              << "; accepted: a mesh whose extent lies in [1e-50, 1e50] and "
                 "is at least 1e-10 of its largest coordinate (scale or "
                 "move its coordinates).";
      AssertThrow(extent >= 1e-50 && magnitude <= 1e50
                    && extent >= 1e-10 * magnitude,
                  ExcMessage(message.str()));
    }



    // Cell c of the file: a simplex or a hypercube (the only cells whose
    // corners corner_jacobian() knows; Gmsh's wedges and pyramids are
    // refused before anything indexes their corners), no node twice, and
    // at every corner a Jacobian of the common orientation whose size is
    // not negligible against the corner's edges.
    template <int dim>
    void
    check_cell(const unsigned int             c,
               const CellData<dim>           &cell,
               const std::vector<Point<dim>> &vertices,
               const std::string             &file)
    {
      std::vector<Point<dim>> corners;
      for (const unsigned int v : cell.vertices)
        corners.push_back(vertices[v]);
      AssertThrow(corners.size() == dim + 1 || corners.size() == (1u << dim),
                  ExcMessage(invalid_mesh(file)
                             + cell_description<dim>(c, corners) + " has "
                             + std::to_string(corners.size())
                             + " nodes, a kind of cell this program does not "
                               "support; accepted: "
                             + (dim == 2 ? "triangles (3 nodes) and "
                                           "quadrilaterals (4 nodes) in 2D."
                                         : "tetrahedra (4 nodes) and "
                                           "hexahedra (8 nodes) in 3D.")));
      const std::set<unsigned int> distinct(cell.vertices.begin(),
                                            cell.vertices.end());
      AssertThrow(distinct.size() == corners.size(),
                  ExcMessage(invalid_mesh(file)
                             + cell_description<dim>(c, corners)
                             + " uses a node more than once; accepted: "
                               "cells with distinct nodes."));
      for (unsigned int v = 0; v < corners.size(); ++v)
        {
          const auto [jacobian, lengths] = corner_jacobian<dim>(corners, v);
          AssertThrow(jacobian > 1e-10 * lengths,
                      ExcMessage(invalid_mesh(file)
                                 + cell_description<dim>(c, corners)
                                 + (jacobian > -1e-10 * lengths
                                      ? " is degenerate (its corners lie "
                                        "(nearly) on a line or plane)"
                                      : " is inverted or twisted (its "
                                        "corners are not in the order of the "
                                        "other cells)")
                                 + "; accepted: cells of positive volume, "
                                   "with their nodes in Gmsh's order."));
        }
    }
  } // namespace



  template <int dim>
  void
  check_mesh_cells(const std::vector<Point<dim>>    &vertices,
                   const std::vector<CellData<dim>> &cells,
                   const std::string                &file)
  {
    check_coordinates(vertices, cells, file);
    for (unsigned int c = 0; c < cells.size(); ++c)
      check_cell(c, cells[c], vertices, file);
  }



  // @sect4{check_mesh_conformity}
  //
  // The mesh built from cells that passed check_mesh_cells(): no coincident
  // nodes (check_coincident_nodes()), then no hanging nodes
  // (check_hanging_nodes()), both to within 1e-10 of the mesh's extent.
  namespace
  {
    // No two of the used vertices (with their numbers) closer than
    // tolerance: a node defined twice under two ids, or a crack (a body
    // that is not connected across a line of double nodes).
    // Nodes of the two sides of a contact pair may coincide, or lie on the
    // other side's faces: the vertices of the faces with a pair's boundary
    // ids are exempt.
    template <int dim>
    std::set<unsigned int>
    pair_vertices_of(const Triangulation<dim>              &triangulation,
                     const std::vector<types::boundary_id> &pair_ids)
    {
      std::set<unsigned int> vertices;
      for (const auto &cell : triangulation.active_cell_iterators())
        for (const auto &face : cell->face_iterators())
          if (face->at_boundary()
              && std::find(pair_ids.begin(),
                           pair_ids.end(),
                           face->boundary_id())
                   != pair_ids.end())
            for (const unsigned int v : face->vertex_indices())
              vertices.insert(face->vertex_index(v));
      return vertices;
    }

    template <int dim>
    void
    check_coincident_nodes(
      const std::vector<std::pair<Point<dim>, unsigned int>> &used_vertices,
      const std::set<unsigned int>                           &pair_vertices,
      const double                                            tolerance,
      const std::string                                      &file)
    {
      const auto vertex_tree = pack_rtree(used_vertices);
      for (const auto &[point, index] : used_vertices)
        {
          Point<dim> a = point, b = point;
          for (unsigned int d = 0; d < dim; ++d)
            {
              a[d] -= tolerance;
              b[d] += tolerance;
            }
          std::vector<std::pair<Point<dim>, unsigned int>> near;
          vertex_tree.query(boost::geometry::index::intersects(
                              BoundingBox<dim>(std::make_pair(a, b))),
                            std::back_inserter(near));
          if (near.size() > 1 && pair_vertices.count(index) == 1
              && std::all_of(near.begin(), near.end(), [&](const auto &other) {
                   return pair_vertices.count(other.second) == 1;
                 }))
            continue;
          AssertThrow(near.size() == 1,
                      ExcMessage(invalid_mesh(file) + "two nodes coincide at "
                                 + coordinates<dim>(point)
                                 + " (a node defined twice, or a crack); "
                                   "accepted: a conforming mesh of each "
                                   "body, whose cells share their nodes "
                                   "(bodies may meet where a contact zone "
                                   "and its Opposite boundary ids do)."));
        }
    }



    // Whether point lies within tolerance of the triangle (p0, p1, p2) in
    // 3D: of its plane, and inside it by its barycentric coordinates.
    bool
    lies_on_triangle(const Point<3> &point,
                     const Point<3> &p0,
                     const Point<3> &p1,
                     const Point<3> &p2,
                     const double    tolerance)
    {
      const Tensor<1, 3> e1 = p1 - p0, e2 = p2 - p0, x = point - p0;
      const Tensor<1, 3> n = cross_product_3d(e1, e2);
      if (n.norm() == 0 || std::abs(x * n) > tolerance * n.norm())
        return false;
      // Barycentric coordinates in the plane.
      const double d11 = e1 * e1, d12 = e1 * e2, d22 = e2 * e2, x1 = x * e1,
                   x2  = x * e2;
      const double det = d11 * d22 - d12 * d12;
      const double s   = (d22 * x1 - d12 * x2) / det;
      const double t   = (d11 * x2 - d12 * x1) / det;
      return s >= -1e-10 && t >= -1e-10 && s + t <= 1 + 1e-10;
    }



    // Whether point lies on the face with the given corners: in 2D within
    // tolerance of the segment; in 3D of one of the triangles (0, 1, 2)
    // and, for a quadrilateral, (1, 3, 2).
    template <int dim>
    bool
    lies_on_face(const Point<dim>              &point,
                 const std::vector<Point<dim>> &corners,
                 const double                   tolerance)
    {
      if constexpr (dim == 2)
        {
          const Tensor<1, 2> e = corners[1] - corners[0],
                             x = point - corners[0];
          const double t       = (x * e) / (e * e);
          return t > 0 && t < 1 && (x - t * e).norm() <= tolerance;
        }
      else
        return lies_on_triangle(point,
                                corners[0],
                                corners[1],
                                corners[2],
                                tolerance)
               || (corners.size() == 4
                   && lies_on_triangle(point,
                                       corners[1],
                                       corners[3],
                                       corners[2],
                                       tolerance));
    }



    // Whether point lies within tolerance of a vertex of a face in 3D that
    // is a vertex of a contact pair, or of an edge whose two ends are: where
    // two bodies meet along a pair, the nodes of one lie on the corners and
    // edges the other's pair faces share with its other faces.
    template <int dim, typename FaceIterator>
    bool
    lies_on_pair_edge(const Point<dim>             &point,
                      const FaceIterator           &face,
                      const std::set<unsigned int> &pair_vertices,
                      const double                  tolerance)
    {
      if constexpr (dim == 3)
        {
          for (const unsigned int v : face->vertex_indices())
            if (pair_vertices.count(face->vertex_index(v)) == 1
                && (point - face->vertex(v)).norm() <= tolerance)
              return true;
          for (unsigned int l = 0; l < face->n_lines(); ++l)
            {
              const auto line = face->line(l);
              if (pair_vertices.count(line->vertex_index(0)) == 0
                  || pair_vertices.count(line->vertex_index(1)) == 0)
                continue;
              const Tensor<1, 3> e = line->vertex(1) - line->vertex(0),
                                 x = point - line->vertex(0);
              const double t       = std::clamp((x * e) / (e * e), 0., 1.);
              if ((x - t * e).norm() <= tolerance)
                return true;
            }
        }
      return false;
    }



    // The vertices of the faces on the boundary, each once, with their
    // numbers.
    template <int dim>
    std::vector<std::pair<Point<dim>, unsigned int>>
    boundary_vertices_of(const Triangulation<dim> &triangulation)
    {
      std::vector<std::pair<Point<dim>, unsigned int>> boundary_vertices;
      std::set<unsigned int>                           seen;
      for (const auto &cell : triangulation.active_cell_iterators())
        for (const auto &face : cell->face_iterators())
          if (face->at_boundary())
            for (const unsigned int v : face->vertex_indices())
              if (seen.insert(face->vertex_index(v)).second)
                boundary_vertices.emplace_back(face->vertex(v),
                                               face->vertex_index(v));
      return boundary_vertices;
    }



    // Non-conforming faces: in a conforming mesh a face that is on the
    // boundary holds no other boundary node than its own vertices. A
    // hanging node (a vertex on the edge of a larger neighbour) leaves the
    // larger cell's face without a neighbour, with that vertex inside it.
    // The boundary nodes near each boundary face (in its bounding box,
    // widened by tolerance) are candidates.
    template <int dim>
    void
    check_hanging_nodes(const Triangulation<dim>     &triangulation,
                        const std::set<unsigned int> &pair_vertices,
                        const double                  tolerance,
                        const std::string            &file)
    {
      const std::vector<std::pair<Point<dim>, unsigned int>> boundary_vertices
        = boundary_vertices_of(triangulation);
      const auto boundary_tree = pack_rtree(boundary_vertices);
      for (const auto &cell : triangulation.active_cell_iterators())
        for (const auto &face : cell->face_iterators())
          if (face->at_boundary())
            {
              std::vector<Point<dim>> corners;
              std::set<unsigned int>  own;
              bool                    on_pair = true;
              for (const unsigned int v : face->vertex_indices())
                {
                  corners.push_back(face->vertex(v));
                  own.insert(face->vertex_index(v));
                  on_pair
                    = on_pair && pair_vertices.count(face->vertex_index(v));
                }
              Point<dim> a = corners[0], b = corners[0];
              for (const Point<dim> &p : corners)
                for (unsigned int d = 0; d < dim; ++d)
                  {
                    a[d] = std::min(a[d], p[d] - tolerance);
                    b[d] = std::max(b[d], p[d] + tolerance);
                  }
              std::vector<std::pair<Point<dim>, unsigned int>> inside;
              boundary_tree.query(boost::geometry::index::intersects(
                                    BoundingBox<dim>(std::make_pair(a, b))),
                                  std::back_inserter(inside));
              for (const auto &[point, index] : inside)
                {
                  if (own.count(index) > 0
                      || (pair_vertices.count(index) == 1
                          && (on_pair
                              || lies_on_pair_edge<dim>(point,
                                                        face,
                                                        pair_vertices,
                                                        tolerance))))
                    continue;
                  const bool on_face
                    = lies_on_face<dim>(point, corners, tolerance);
                  AssertThrow(
                    !on_face,
                    ExcMessage(invalid_mesh(file) + "the node at "
                               + coordinates<dim>(point) + " lies on a face of "
                               + cell_description<dim>(cell->index(),
                                                       corners_of<dim>(cell))
                               + " without being one of its vertices "
                                 "(a hanging node: the mesh is not "
                                 "conforming); accepted: a conforming "
                                 "mesh, whose neighbouring cells share "
                                 "whole faces (bodies may meet where a "
                                 "contact zone and its Opposite boundary "
                                 "ids do)."));
                }
            }
    }
  } // namespace



  template <int dim>
  void
  check_mesh_conformity(const Triangulation<dim>              &triangulation,
                        const std::string                     &file,
                        const std::vector<types::boundary_id> &pair_ids)
  {
    const std::vector<Point<dim>> &vertices = triangulation.get_vertices();
    const std::vector<bool>       &used     = triangulation.get_used_vertices();
    std::vector<std::pair<Point<dim>, unsigned int>> used_vertices;
    std::vector<Point<dim>>                          used_points;
    for (unsigned int v = 0; v < vertices.size(); ++v)
      if (used[v])
        {
          used_vertices.emplace_back(vertices[v], v);
          used_points.push_back(vertices[v]);
        }
    const double                 tolerance = 1e-10 * extent_of(used_points);
    const std::set<unsigned int> pair_vertices
      = pair_vertices_of(triangulation, pair_ids);
    check_coincident_nodes(used_vertices, pair_vertices, tolerance, file);
    check_hanging_nodes(triangulation, pair_vertices, tolerance, file);
  }



  template void
  check_mesh_cells(const std::vector<Point<2>> &,
                   const std::vector<CellData<2>> &,
                   const std::string &);
  template void
  check_mesh_cells(const std::vector<Point<3>> &,
                   const std::vector<CellData<3>> &,
                   const std::string &);
  template void
  check_mesh_conformity(const Triangulation<2> &,
                        const std::string &,
                        const std::vector<types::boundary_id> &);
  template void
  check_mesh_conformity(const Triangulation<3> &,
                        const std::string &,
                        const std::vector<types::boundary_id> &);
  template std::vector<Point<2>>
  corners_of<2>(const Triangulation<2>::cell_iterator &);
  template std::vector<Point<3>>
  corners_of<3>(const Triangulation<3>::cell_iterator &);
  template std::pair<double, double>
  corner_jacobian<2>(const std::vector<Point<2>> &, const unsigned int);
  template std::pair<double, double>
  corner_jacobian<3>(const std::vector<Point<3>> &, const unsigned int);
} // namespace ViscoContact
