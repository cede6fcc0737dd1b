// Meshes: the generated box or a Gmsh file, refined uniformly and toward the
// contact boundary, and the check that the named boundary parts exist.
//
// The stages are those of the header (mesh.h): a coarse mesh on a serial
// Triangulation, the refinements, then the distributed mesh the program runs
// on (p4est for hypercubes, a fully distributed mesh for simplices). The
// generated simplex boxes are built here rather than by deal.II's generator
// because the convergence study needs nested meshes, and the published
// benchmark needs one particular diagonal.

#include <deal.II/base/exceptions.h>
#include <deal.II/base/function_parser.h>
#include <deal.II/base/mpi.h>

#include <deal.II/distributed/fully_distributed_tria.h>
#include <deal.II/distributed/tria.h>

#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/grid_in.h>
#include <deal.II/grid/grid_tools.h>
#include <deal.II/grid/manifold_lib.h>
#include <deal.II/grid/tria_description.h>
#include <deal.II/grid/tria_accessor.h>
#include <deal.II/grid/tria_iterator.h>


#include "scene/loads.h"
#include "mesh/coarse_cell_order.h"
#include "mesh/mesh.h"
#include "mesh/mesh_checks.h"
#include "robustness/mpi_tools.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

namespace ViscoContact
{
  namespace
  {
    // Whether an id is among the given ones.
    bool
    contains(const std::vector<types::boundary_id> &ids,
             const types::boundary_id               id)
    {
      return std::find(ids.begin(), ids.end(), id) != ids.end();
    }

    // The union over all ranks of the ids each rank has.
    template <typename Id>
    std::set<Id>
    union_over_ranks(const std::set<Id> &local_ids, const MPI_Comm communicator)
    {
      const std::vector<Id> ids
        = Utilities::MPI::compute_set_union(std::vector<Id>(local_ids.begin(),
                                                            local_ids.end()),
                                            communicator);
      return std::set<Id>(ids.begin(), ids.end());
    }

    // The Material id function at the centre of every cell of the coarse
    // mesh. Children inherit their parent's id when a cell is refined, also
    // when p4est rebuilds a repartitioned mesh from the coarse one, so the
    // ids survive refinement, repartitioning and resume.
    template <int dim>
    void
    set_material_ids(const Parameters::AllParameters &parameters,
                     Triangulation<dim>              &triangulation)
    {
      FunctionParser<dim> region(1);
      initialize_load(region,
                      "Geometry",
                      "Material id function",
                      parameters.material_id_function,
                      parameters.lengths);
      for (const auto &cell : triangulation.active_cell_iterators())
        {
          const Point<dim> centre = cell->center();
          const double     value  = region.value(centre);
          if (!(std::isfinite(value) && value >= 0
                && value < numbers::invalid_material_id
                && value == std::round(value)))
            {
              std::ostringstream where;
              where << "(" << centre << ")";
              AssertThrow(false,
                          ExcMessage(
                            "Invalid parameter <Material id function> in "
                            "subsection <Geometry>: value <"
                            + parameters.material_id_function + ">; it is "
                            + std::to_string(value) + " at the cell centre "
                            + where.str()
                            + "; accepted: a whole number >= 0 at the centre "
                              "of every cell."));
            }
          cell->set_material_id(static_cast<types::material_id>(value));
        }
    }
  } // namespace



  // @sect4{create_simplex_box}
  //
  // The vertices of the box are numbered lexicographically (x fastest);
  // every square (cube) is cut into simplices by the pattern. Each simplex
  // is listed with positive orientation (counter-clockwise triangles,
  // tetrahedra with a positive Jacobian), which is what deal.II's reference
  // simplices have.
  //
  // Why nested: the convergence study (convergence_study.cc) compares a
  // coarse run with a reference run on a finer mesh, point by point, and
  // needs every reference cell to lie inside one coarse cell. For "/",
  // backslash, crossed and Kuhn's subdivision in 3D, the simplices are the
  // pieces into which a fixed family of lines (planes) cuts the box: the
  // grid lines x_d = k h_d, plus the diagonals x/h_x - y/h_y = integer
  // ("/"), x/h_x + y/h_y = integer (backslash), both (crossed), or
  // x_a/h_a - x_b/h_b = integer (Kuhn's tetrahedra). Multiplying the number
  // of subdivisions keeps every line of the coarse family in the fine one,
  // so each fine simplex lies in one coarse simplex. For union jack, the
  // fine squares along the diagonal of a coarse square have that square's
  // parity, hence its diagonal, so every coarse diagonal is again made of
  // fine edges. deal.II's five tetrahedra per cube alternate between
  // neighbouring cubes and are not nested; the convergence study rejects
  // them.
  namespace
  {
    // The boundary ids that colorize gives a hypercube box, 2d and 2d + 1 at
    // x_d = 0 and x_d = L_d, set from the face centres with a tolerance
    // relative to the box size.
    template <int dim>
    void
    set_box_boundary_ids(Triangulation<dim>        &triangulation,
                         const std::vector<double> &lengths)
    {
      for (const auto &face : triangulation.active_face_iterators())
        if (face->at_boundary())
          for (unsigned int d = 0; d < dim; ++d)
            {
              const double x         = face->center()[d];
              const double tolerance = 1e-10 * lengths[d];
              if (std::abs(x) < tolerance)
                face->set_boundary_id(2 * d);
              else if (std::abs(x - lengths[d]) < tolerance)
                face->set_boundary_id(2 * d + 1);
            }
    }



    // The simplex with these vertices, reordered if needed so that its
    // orientation is positive: the sign of the determinant of the edge
    // vectors from vertex 0 is the orientation, and swapping the last two
    // vertices flips it.
    template <int dim>
    CellData<dim>
    positive_simplex(const std::vector<Point<dim>>    &points,
                     std::array<unsigned int, dim + 1> vertices)
    {
      Tensor<2, dim> J;
      for (unsigned int a = 1; a <= dim; ++a)
        for (unsigned int d = 0; d < dim; ++d)
          J[d][a - 1] = points[vertices[a]][d] - points[vertices[0]][d];
      if (determinant(J) < 0)
        std::swap(vertices[dim - 1], vertices[dim]);
      CellData<dim> cell(dim + 1);
      for (unsigned int a = 0; a <= dim; ++a)
        cell.vertices[a] = vertices[a];
      return cell;
    }
  } // namespace



  // @sect4{create_simplex_box (2D)}
  //
  // Two triangles per square for "/", backslash and union jack, four for
  // crossed, with one new vertex in the centre of each square.
  template <>
  void
  create_simplex_box(Triangulation<2>                &triangulation,
                     const std::vector<double>       &lengths,
                     const unsigned int               n,
                     const Parameters::SimplexPattern pattern)
  {
    using Pattern = Parameters::SimplexPattern;
    // The (n + 1)^2 vertices of the squares, x fastest, and the index of
    // vertex (i, j).
    const double          hx = lengths[0] / n, hy = lengths[1] / n;
    std::vector<Point<2>> points;
    for (unsigned int j = 0; j <= n; ++j)
      for (unsigned int i = 0; i <= n; ++i)
        points.emplace_back(i * hx, j * hy);
    const auto vertex = [n](const unsigned int i, const unsigned int j) {
      return j * (n + 1) + i;
    };

    std::vector<CellData<2>> cells;
    for (unsigned int j = 0; j < n; ++j)
      for (unsigned int i = 0; i < n; ++i)
        {
          // The corners of square (i, j): a lower left, b lower right, c
          // upper left, d upper right. Union jack alternates the diagonal
          // like a checkerboard, so that the diagonals meet at every second
          // vertex.
          const unsigned int a = vertex(i, j), b = vertex(i + 1, j),
                             c = vertex(i, j + 1), d = vertex(i + 1, j + 1);
          const bool slash
            = pattern == Pattern::slash
              || (pattern == Pattern::union_jack && (i + j) % 2 == 0);
          if (pattern == Pattern::crossed)
            {
              // Both diagonals: a vertex at the centre, four triangles, one
              // on each edge of the square.
              const unsigned int e = points.size();
              points.emplace_back((i + 0.5) * hx, (j + 0.5) * hy);
              for (const auto &edge : {std::array<unsigned int, 2>{{a, b}},
                                       std::array<unsigned int, 2>{{b, d}},
                                       std::array<unsigned int, 2>{{d, c}},
                                       std::array<unsigned int, 2>{{c, a}}})
                cells.push_back(
                  positive_simplex<2>(points, {{edge[0], edge[1], e}}));
            }
          else if (slash)
            {
              // "/": the diagonal a-d, from (x_i, y_j) to
              // (x_{i+1}, y_{j+1}), as in the published benchmark.
              cells.push_back(positive_simplex<2>(points, {{a, b, d}}));
              cells.push_back(positive_simplex<2>(points, {{a, d, c}}));
            }
          else
            {
              // Backslash: the diagonal b-c.
              cells.push_back(positive_simplex<2>(points, {{a, b, c}}));
              cells.push_back(positive_simplex<2>(points, {{b, d, c}}));
            }
        }
    // Build the triangulation, then give its boundary faces the ids colorize
    // would give.
    triangulation.create_triangulation(points, cells, SubCellData());
    set_box_boundary_ids(triangulation, lengths);
  }



  // @sect4{create_simplex_box (3D)}
  //
  // Either deal.II's generator with five tetrahedra per cube, or Kuhn's six
  // tetrahedra around the diagonal of each cube (Simplex pattern = /).
  template <>
  void
  create_simplex_box(Triangulation<3>                &triangulation,
                     const std::vector<double>       &lengths,
                     const unsigned int               n,
                     const Parameters::SimplexPattern pattern)
  {
    if (pattern == Parameters::SimplexPattern::five_tetrahedra)
      {
        // deal.II's generator; only its boundary ids have to be added.
        GridGenerator::subdivided_hyper_rectangle_with_simplices(
          triangulation,
          std::vector<unsigned int>(3, n),
          Point<3>(),
          Point<3>(lengths[0], lengths[1], lengths[2]));
        set_box_boundary_ids(triangulation, lengths);
        return;
      }

    // Kuhn's subdivision: for every ordering (p0, p1, p2) of the axes, the
    // tetrahedron of the path from the lower to the upper corner of the cube
    // that steps along e_p0, then e_p1, then e_p2. All cubes are cut the
    // same way, so the faces match. In the cube's own coordinates t, the
    // tetrahedron of an ordering is {t_p0 >= t_p1 >= t_p2}: the six of them
    // fill the cube and all share its diagonal.
    std::vector<Point<3>> points;
    for (unsigned int k = 0; k <= n; ++k)
      for (unsigned int j = 0; j <= n; ++j)
        for (unsigned int i = 0; i <= n; ++i)
          points.emplace_back(i * lengths[0] / n,
                              j * lengths[1] / n,
                              k * lengths[2] / n);
    // The index of vertex (i, j, k), x fastest.
    const auto vertex = [n](const std::array<unsigned int, 3> &index) {
      return (index[2] * (n + 1) + index[1]) * (n + 1) + index[0];
    };
    std::array<unsigned int, 3> axes = {{0, 1, 2}};
    std::vector<CellData<3>>    cells;
    for (unsigned int k = 0; k < n; ++k)
      for (unsigned int j = 0; j < n; ++j)
        for (unsigned int i = 0; i < n; ++i)
          {
            // Start each cube from the ordering (0, 1, 2);
            // std::next_permutation then runs through all six orderings.
            std::sort(axes.begin(), axes.end());
            do
              {
                // Walk from the lower corner, one unit step along each axis
                // in the order of the permutation: the four vertices of the
                // path are the tetrahedron.
                std::array<unsigned int, 3> corner = {{i, j, k}};
                std::array<unsigned int, 4> tetrahedron;
                tetrahedron[0] = vertex(corner);
                for (unsigned int s = 0; s < 3; ++s)
                  {
                    ++corner[axes[s]];
                    tetrahedron[s + 1] = vertex(corner);
                  }
                cells.push_back(positive_simplex<3>(points, tetrahedron));
            } while (std::next_permutation(axes.begin(), axes.end()));
          }
    triangulation.create_triangulation(points, cells, SubCellData());
    set_box_boundary_ids(triangulation, lengths);
  }



  namespace
  {
    // The triangulation a Gmsh file is read into: it checks the cells the
    // reader hands it before it builds anything (deal.II's own checks of a
    // cell's nodes and faces are assertions, which abort a Debug build and
    // are absent from a Release one).
    template <int dim>
    class CheckedTriangulation : public Triangulation<dim>
    {
    public:
      explicit CheckedTriangulation(const std::string &file)
        : file(file)
      {}

      using Triangulation<dim>::create_triangulation;

      void
      create_triangulation(const std::vector<Point<dim>>    &vertices,
                           const std::vector<CellData<dim>> &cells,
                           const SubCellData &subcell_data) override
      {
        try
          {
            check_mesh_cells(vertices, cells, file);
          }
        catch (...)
          {
            cells_rejected = true;
            throw;
          }
        Triangulation<dim>::create_triangulation(vertices, cells, subcell_data);
      }

      // Whether the reader stopped because check_mesh_cells() rejected a
      // cell (its message is then the one to give).
      bool cells_rejected = false;

    private:
      const std::string file;
    };
  } // namespace



  namespace
  {
    // @sect4{attach_box_map}
    //
    // The Box map's manifold, id 0, on a mesh whose objects carry that id
    // (map_box() sets it; a fully distributed mesh gets it with its
    // description, and must have the manifold before it builds its levels by
    // refinement). Nothing without a Box map.
    template <int dim>
    void
    attach_box_map(const Parameters::AllParameters &parameters,
                   Triangulation<dim>              &triangulation)
    {
      if (parameters.box_map.empty())
        return;
      triangulation.set_manifold(
        0,
        FunctionManifold<dim>(parameters.box_map,
                              parameters.box_map_inverse,
                              Tensor<1, dim>(),
                              expression_constants(parameters.lengths)));
    }



    // @sect4{check_box_map_orientation}
    //
    // Every locally owned cell of a mesh moved by the Box map keeps its
    // orientation: the Jacobian of the cell's linear (simplex) or
    // multilinear (hypercube) map has a positive determinant at each vertex.
    // Checked on the coarse box and again on the refined mesh, since a map
    // can fold inside a coarse cell.
    template <int dim>
    void
    check_box_map_orientation(const Parameters::AllParameters &parameters,
                              const Triangulation<dim>        &triangulation)
    {
      for (const auto &cell : triangulation.active_cell_iterators())
        {
          if (!cell->is_locally_owned())
            continue;
          const std::vector<Point<dim>> corners = corners_of<dim>(cell);
          for (unsigned int v = 0; v < corners.size(); ++v)
            {
              if (!(corner_jacobian<dim>(corners, v).first > 0))
                {
                  std::ostringstream where;
                  where << "(" << cell->center() << ")";
                  AssertThrow(false,
                              ExcMessage(
                                "Invalid parameter <Box map> in subsection "
                                "<Geometry>: value <"
                                + parameters.box_map
                                + ">; it turns the cell at " + where.str()
                                + " inside out; accepted: a map that keeps "
                                  "the orientation of every cell."));
                }
            }
        }
    }



    // @sect4{map_box}
    //
    // Box map: every vertex p of the box moves to map(p), and every object
    // of the mesh gets a FunctionManifold of the map, so that refinement
    // puts a new vertex at map(the point between its parents in the box).
    // The manifold is built from the expressions (not from the parsed
    // functions) because the meshes that copy it clone it, and a clone of a
    // manifold of expressions parses them anew instead of pointing into this
    // one. The checks give errors that name the entries: the map is finite
    // and its inverse takes the point back at the vertices of the box and at
    // the points refinement adds first (the centres of the edges, faces and
    // cells; the vertices alone would not see a wrong inverse on a box of
    // one cell), and every cell keeps its orientation.
    template <int dim>
    void
    map_box(const Parameters::AllParameters &parameters,
            Triangulation<dim>              &triangulation)
    {
      FunctionParser<dim> forward(dim), inverse(dim);
      initialize_load(forward,
                      "Geometry",
                      "Box map",
                      parameters.box_map,
                      parameters.lengths,
                      /*time_dependent=*/false);
      initialize_load(inverse,
                      "Geometry",
                      "Box map inverse",
                      parameters.box_map_inverse,
                      parameters.lengths,
                      /*time_dependent=*/false);
      const auto evaluate
        = [](const FunctionParser<dim> &function, const Point<dim> &p) {
            Vector<double> values(dim);
            function.vector_value(p, values);
            Point<dim> result;
            for (unsigned int d = 0; d < dim; ++d)
              result[d] = values[d];
            return result;
          };
      const auto where = [](const Point<dim> &p) {
        std::ostringstream text;
        text << "(" << p << ")";
        return text.str();
      };
      const double size = *std::max_element(parameters.lengths.begin(),
                                            parameters.lengths.end());
      // The points to check, in the box: its vertices and the centres of
      // its edges, faces and cells.
      // Each object once: the box of a simplex mesh is the whole mesh.
      std::vector<Point<dim>> points = triangulation.get_vertices();
      for (const auto &cell : triangulation.active_cell_iterators())
        points.push_back(cell->center());
      for (const auto &face : triangulation.active_face_iterators())
        points.push_back(face->center());
      if (dim == 3)
        {
          // Each edge once, marked by its user flag.
          triangulation.clear_user_flags_line();
          for (const auto &cell : triangulation.active_cell_iterators())
            for (unsigned int l = 0; l < cell->n_lines(); ++l)
              if (!cell->line(l)->user_flag_set())
                {
                  cell->line(l)->set_user_flag();
                  points.push_back(cell->line(l)->center());
                }
          triangulation.clear_user_flags_line();
        }
      std::vector<Point<dim>> moved(points.size());
      for (unsigned int i = 0; i < points.size(); ++i)
        {
          moved[i]    = evaluate(forward, points[i]);
          bool finite = true;
          for (unsigned int d = 0; d < dim; ++d)
            finite = finite && std::isfinite(moved[i][d]);
          AssertThrow(finite,
                      ExcMessage("Invalid parameter <Box map> in subsection "
                                 "<Geometry>: value <"
                                 + parameters.box_map + ">; it is "
                                 + where(moved[i]) + " at the box point "
                                 + where(points[i])
                                 + "; accepted: a map that is finite on the "
                                   "box."));
        }
      GridTools::transform(
        [&](const Point<dim> &p) { return evaluate(forward, p); },
        triangulation);
      check_box_map_orientation(parameters, triangulation);
      for (unsigned int i = 0; i < points.size(); ++i)
        {
          const Point<dim> back   = evaluate(inverse, moved[i]);
          bool             finite = true;
          for (unsigned int d = 0; d < dim; ++d)
            finite = finite && std::isfinite(back[d]);
          AssertThrow(finite && back.distance(points[i]) <= 1e-8 * size,
                      ExcMessage("Invalid parameter <Box map inverse> in "
                                 "subsection <Geometry>: value <"
                                 + parameters.box_map_inverse
                                 + ">; Box map takes the box point "
                                 + where(points[i]) + " to " + where(moved[i])
                                 + ", which the inverse takes to " + where(back)
                                 + "; accepted: the inverse of Box map, "
                                   "finite on the moved box."));
        }
      triangulation.set_all_manifold_ids(0);
      attach_box_map(parameters, triangulation);
    }
  } // namespace



  // @sect4{create_box}
  //
  // The box (0,L1)x(0,L2)(x(0,L3)) of Subdivisions squares (cubes) along each
  // edge, its faces colorized, moved by the Box map if there is one.
  template <int dim>
  void
  create_box(const Parameters::AllParameters &parameters,
             Triangulation<dim>              &triangulation)
  {
    const bool simplex
      = (parameters.cell_type == Parameters::CellType::simplex);

    // The generated box: its far corner and the number of squares (cubes)
    // along each edge.
    Point<dim>                corner;
    std::vector<unsigned int> repetitions(dim, parameters.subdivisions);
    for (unsigned int d = 0; d < dim; ++d)
      corner[d] = parameters.lengths[d];

    if (simplex)
      create_simplex_box(triangulation,
                         parameters.lengths,
                         parameters.subdivisions,
                         parameters.simplex_pattern);
    else
      GridGenerator::subdivided_hyper_rectangle(triangulation,
                                                repetitions,
                                                Point<dim>(),
                                                corner,
                                                /*colorize=*/true);
    if (!parameters.box_map.empty())
      map_box(parameters, triangulation);
  }



  // @sect4{create_coarse_mesh}
  //
  // The box (0,L1)x(0,L2)(x(0,L3)) with Subdivisions squares (cubes) along
  // each edge (create_box()), on simplex meshes cut by the Simplex pattern
  // (create_simplex_box(); deal.II 9.4 cannot colorize its simplex
  // generator, so the boundary ids are set from the face centres with the
  // numbering colorize uses for hypercubes: 2d and 2d+1 at x_d = 0 and L_d).
  //
  // A Gmsh file brings its own boundary ids (the physical groups of its
  // boundary faces); its cells must all be of the chosen Cell type (both
  // kinds with mixed), since the finite elements and the stress points are
  // chosen from it.
  //
  // Every problem with the file is reported as an invalid value of Mesh
  // file, with what is accepted, rather than as an exception from deep
  // inside the reader. Last, a Material id function overrides the cells'
  // material ids.
  template <int dim>
  void
  create_coarse_mesh(const Parameters::AllParameters &parameters,
                     Triangulation<dim>              &triangulation)
  {
    const bool simplex
      = (parameters.cell_type == Parameters::CellType::simplex);
    if (!parameters.mesh_file.empty())
      {
        // The file must exist (main.cc has made a relative path relative to
        // the parameter file).
        const std::string &file = parameters.mesh_file;
        AssertThrow(std::filesystem::is_regular_file(file),
                    ExcMessage("Invalid parameter <Mesh file> in subsection "
                               "<Geometry>: value <"
                               + file
                               + ">; accepted: an existing Gmsh .msh file "
                                 "(a relative path is relative to the "
                                 "directory of the parameter file) or "
                                 "nothing for the generated box."));
        // The reader's own complaint, whatever its type, becomes part of the
        // message; an empty mesh is an error too.
        // A count the reader would take for a size (a negative one, say)
        // or a node id defined twice (which would silently replace the
        // first node) is refused first.
        check_gmsh_sections(file);
        std::string               reader_message;
        CheckedTriangulation<dim> checked_mesh(file);
        try
          {
            GridIn<dim> grid_in;
            grid_in.attach_triangulation(checked_mesh);
            std::ifstream in(file);
            grid_in.read_msh(in);
          }
        catch (const ExceptionBase &exc)
          {
            if (checked_mesh.cells_rejected)
              throw;
            std::ostringstream info;
            exc.print_info(info);
            reader_message = info.str();
            // deal.II's internal errors describe deal.II, not the file.
            if (reader_message.find("This exception -- which is used in many "
                                    "places")
                != std::string::npos)
              reader_message = "it cannot build a mesh from the file's cells "
                               "(they do not form a valid mesh).";
          }
        catch (const std::exception &exc)
          {
            reader_message = exc.what();
          }
        AssertThrow(reader_message.empty() && checked_mesh.n_cells() > 0,
                    ExcMessage("Invalid parameter <Mesh file> in subsection "
                               "<Geometry>: value <"
                               + file
                               + ">; accepted: a Gmsh .msh file (format 2 or "
                                 "4, ASCII) of a "
                               + std::to_string(dim)
                               + "D mesh. The reader says: " + reader_message));
        // One cell of the wrong type is enough to reject the file (with
        // Cell type = mixed, every type is right).
        const bool mixed = parameters.cell_type == Parameters::CellType::mixed;
        for (const auto &cell : checked_mesh.active_cell_iterators())
          AssertThrow(
            mixed || cell->reference_cell().is_simplex() == simplex,
            ExcMessage(
              "Invalid parameter <Mesh file> in subsection "
              "<Geometry>: value <"
              + file + ">: it has " + cell->reference_cell().to_string()
              + " cells; accepted: a mesh of "
              + (simplex ? "simplices" : "quadrilaterals/hexahedra")
              + " only, as <Cell type> = " + (simplex ? "simplex" : "hypercube")
              + " requires (Cell type = mixed takes both)."));
        // Coincident nodes, conformity.
        // except between the two sides of a contact pair, whose ids must
        // then be on the mesh (every rank reads the whole file).
        check_boundary_ids(parameters, checked_mesh, MPI_COMM_SELF);
        std::vector<types::boundary_id> pair_ids;
        for (const auto &zone : parameters.used_contact_zones())
          if (!zone.contact->opposite_ids.empty())
            {
              pair_ids.insert(pair_ids.end(),
                              zone.boundary_ids.begin(),
                              zone.boundary_ids.end());
              pair_ids.insert(pair_ids.end(),
                              zone.contact->opposite_ids.begin(),
                              zone.contact->opposite_ids.end());
            }
        check_mesh_conformity(checked_mesh, file, pair_ids);
        triangulation.copy_triangulation(checked_mesh);
      }
    else
      create_box(parameters, triangulation);
    if (!parameters.material_id_function.empty())
      set_material_ids(parameters, triangulation);
  }



  // @sect4{coarser_equivalent_box}
  //
  // The generated box of Subdivisions = m 2^j squares (cubes) per edge is
  // the box of m per edge refined j times, where refinement reproduces it:
  // always for hypercubes, for triangles cut by "/" or backslash (the
  // children of the two triangles of a square are the two triangles of
  // each of its four half-size squares, cut the same way; tetrahedra are
  // refined into other shapes than Kuhn's). Returns the parameters of the
  // coarse box and j, taking at most max_refinements factors of 2 out of
  // Subdivisions (none for a Gmsh mesh and the other simplex patterns, and
  // none with a Material id function, which is evaluated on the cells of
  // Subdivisions).
  namespace
  {
    std::pair<Parameters::AllParameters, unsigned int>
    coarser_equivalent_box(const Parameters::AllParameters &parameters,
                           const unsigned int               max_refinements)
    {
      using Pattern = Parameters::SimplexPattern;
      const bool refinement_reproduces_box
        = parameters.mesh_file.empty()
          && parameters.material_id_function.empty()
          && (parameters.cell_type == Parameters::CellType::hypercube
              || (parameters.dimension == 2
                  && (parameters.simplex_pattern == Pattern::slash
                      || parameters.simplex_pattern == Pattern::backslash)));
      Parameters::AllParameters coarse_parameters = parameters;
      unsigned int              box_refinements   = 0;
      if (refinement_reproduces_box)
        while (coarse_parameters.subdivisions % 2 == 0
               && box_refinements < max_refinements)
          {
            coarse_parameters.subdivisions /= 2;
            ++box_refinements;
          }
      return {coarse_parameters, box_refinements};
    }
  } // namespace



  // @sect4{mesh_group_size}
  //
  // Mesh group size, or (0) the ranks of the largest compute node of the
  // run (the ranks that share memory, MPI_Comm_split_type), at most all
  // ranks. deal.II's groups are blocks of consecutive ranks, which are the
  // ranks of one node when the MPI launcher places the ranks by node (its
  // default; a last, partly filled node then gets a smaller group); placed
  // otherwise, a group spans nodes and nothing but the memory per node
  // changes.
  unsigned int
  mesh_group_size(const Parameters::AllParameters &parameters,
                  const MPI_Comm                   communicator)
  {
    unsigned int group_size = parameters.mesh_group_size;
    if (group_size == 0)
      {
        MPI_Comm node_communicator;
        MPI_Comm_split_type(communicator,
                            MPI_COMM_TYPE_SHARED,
                            0,
                            MPI_INFO_NULL,
                            &node_communicator);
        group_size = Utilities::MPI::max(Utilities::MPI::n_mpi_processes(
                                           node_communicator),
                                         communicator);
        MPI_Comm_free(&node_communicator);
      }
    return std::min(group_size, Utilities::MPI::n_mpi_processes(communicator));
  }



  // @sect4{create_distributed_mesh}
  //
  // Hypercube meshes live on p4est: every rank holds the coarse mesh, p4est
  // distributes the refined cells, and the refinement toward Gamma_3 runs in
  // parallel. Each coarse cell is a p4est tree, and trees are expensive
  // (every rank stores all of them), so the generated box of Subdivisions =
  // m 2^j cubes per edge is made of m^dim coarse cells refined j times: the
  // same mesh.
  //
  // A simplex mesh is built and refined as a serial mesh, partitioned by
  // METIS, and each rank gets its part: one rank in every group of Mesh
  // group size consecutive ranks (mesh_group_size()) builds the whole mesh
  // and hands the members their parts, one at a time
  // (create_description_from_triangulation_in_groups()), so that the
  // members never hold it, and the whole mesh exists once per group (per
  // compute node by default), during set-up only. Every group root builds
  // the same mesh and the same partition (METIS is deterministic). Should a
  // root fail to read or check the mesh, the members would wait for their
  // parts forever: the roots build the mesh before the hand-out, and all
  // ranks agree on a failure first (MPITools::agree_on_failure()), so that
  // every rank stops with the message. A generated box of triangles is
  // also built from fewer coarse cells and refined, at most four times:
  // deal.II 9.4's fully distributed mesh takes time in its coarse cells (its
  // set-up sorts the cells with a search among the coarse cells in every
  // comparison) and in its levels (it rebuilds the id of every cell on
  // every level), and four refinements balance the two. (Measured at N =
  // 512, 524k triangles: the mesh takes 1.8 s with four, 2.1 s with all
  // nine, 2.5 s with none.) On one rank both kinds of mesh are the one-rank
  // case of the same classes.
  template <int dim>
  std::unique_ptr<parallel::DistributedTriangulationBase<dim>>
  create_distributed_mesh(const Parameters::AllParameters &parameters,
                          const MPI_Comm                   communicator,
                          const bool                       multigrid_hierarchy)
  {
    std::unique_ptr<parallel::DistributedTriangulationBase<dim>> mesh;
    if (parameters.cell_type != Parameters::CellType::hypercube)
      {
        // Simplices: the group roots build and refine the whole mesh
        // serially and partition it into one part per rank (METIS sets the
        // subdomain ids of the cells).
        const unsigned int group_size
          = mesh_group_size(parameters, communicator);
        Triangulation<dim> serial_mesh;
        std::string        failure;
        if (Utilities::MPI::this_mpi_process(communicator) % group_size == 0)
          failure = MPITools::failure_of([&]() {
            const auto [coarse_parameters, box_refinements]
              = coarser_equivalent_box(parameters,
                                       parameters.box_refinement_limit);
            create_coarse_mesh(coarse_parameters, serial_mesh);
            serial_mesh.refine_global(box_refinements);
            refine_mesh(parameters, serial_mesh);
            GridTools::partition_triangulation(Utilities::MPI::n_mpi_processes(
                                                 communicator),
                                               serial_mesh);
          });
        MPITools::agree_on_failure(failure, communicator);
        // The hand-out: each rank gets the description of its part (its
        // cells and a layer of ghosts, with their ancestors), from which the
        // fully distributed mesh is built. deal.II's function calls the
        // generator and the partitioner on the roots: here they only hand
        // over the mesh built above.
        const auto description = TriangulationDescription::Utilities::
          create_description_from_triangulation_in_groups<dim, dim>(
            [&serial_mesh](Triangulation<dim> &root_mesh) {
              root_mesh = std::move(serial_mesh);
            },
            [](Triangulation<dim> &, const MPI_Comm &, const unsigned int) {},
            communicator,
            group_size);
        auto distributed_mesh
          = std::make_unique<parallel::fullydistributed::Triangulation<dim>>(
            communicator);
        attach_box_map(parameters, *distributed_mesh);
        distributed_mesh->create_triangulation(description);
        mesh = std::move(distributed_mesh);
      }
    else
      {
        // The coarse mesh, identical on every rank, becomes p4est's forest;
        // the factors of 2 taken out of the subdivisions return as global
        // refinements, which p4est distributes.
        const auto [coarse_parameters, box_refinements]
          = coarser_equivalent_box(parameters, numbers::invalid_unsigned_int);
        Triangulation<dim> coarse_mesh;
        MPITools::agree_on_failure(MPITools::failure_of([&]() {
                                     create_coarse_mesh(coarse_parameters,
                                                        coarse_mesh);
                                     number_coarse_cells_as_p4est_trees(
                                       coarse_mesh);
                                   }),
                                   communicator);
        using DistributedMesh = parallel::distributed::Triangulation<dim>;
        auto distributed_mesh
          = multigrid_hierarchy
              ? std::make_unique<DistributedMesh>(
                communicator,
                Triangulation<dim>::limit_level_difference_at_vertices,
                DistributedMesh::construct_multigrid_hierarchy)
              : std::make_unique<DistributedMesh>(communicator);
        distributed_mesh->copy_triangulation(coarse_mesh);
        if (box_refinements > 0)
          distributed_mesh->refine_global(box_refinements);
        // Then the refinements the parameter file asks for, in parallel.
        refine_mesh(parameters, *distributed_mesh);
        mesh = std::move(distributed_mesh);
      }
    // A Box map must not fold the cells refinement made inside the box's
    // cells either.
    if (!parameters.box_map.empty())
      MPITools::agree_on_failure(MPITools::failure_of([&]() {
                                   check_box_map_orientation(parameters, *mesh);
                                 }),
                                 communicator);
    // Last, the boundary parts and materials the parameter file names must
    // exist, and every material id of the mesh must have its material.
    check_boundary_ids(parameters, *mesh, communicator);
    check_material_ids(parameters, *mesh, communicator);
    return mesh;
  }



  // @sect4{refine_mesh}
  //
  // Uniform refinement, then Contact refinement levels rounds in which every
  // cell with a vertex on Gamma_3 is refined: the cells along the contact
  // boundary all end on the finest level, so no contact node is a hanging
  // node, and the mesh coarsens away from Gamma_3 (2:1 across faces on p4est
  // meshes).
  //
  // The same function refines the serial simplex mesh (where every cell is
  // locally owned) and the distributed p4est mesh (where each rank flags its
  // own cells).
  template <int dim>
  void
  refine_mesh(const Parameters::AllParameters &parameters,
              Triangulation<dim>              &triangulation)
  {
    if (parameters.global_refinements > 0)
      triangulation.refine_global(parameters.global_refinements);

    for (unsigned int level = 0; level < parameters.contact_refinements;
         ++level)
      {
        // The vertices of Gamma_3 this rank sees; a cell touching Gamma_3 at
        // a vertex only is refined too. Ghost cells are included, so that an
        // owned cell whose contact vertex lies on a face of a ghost cell is
        // found.
        const std::vector<types::boundary_id> contact_ids
          = parameters.all_contact_ids();
        std::vector<bool> on_contact_boundary(triangulation.n_vertices(),
                                              false);
        for (const auto &cell : triangulation.active_cell_iterators())
          if (!cell->is_artificial())
            for (const unsigned int f : cell->face_indices())
              if (cell->face(f)->at_boundary()
                  && contains(contact_ids, cell->face(f)->boundary_id()))
                for (const unsigned int v : cell->face(f)->vertex_indices())
                  on_contact_boundary[cell->face(f)->vertex_index(v)] = true;
        // Flag every owned cell with at least one such vertex; one is
        // enough.
        for (const auto &cell : triangulation.active_cell_iterators())
          if (cell->is_locally_owned())
            for (const unsigned int v : cell->vertex_indices())
              if (on_contact_boundary[cell->vertex_index(v)])
                {
                  cell->set_refine_flag();
                  break;
                }
        // Refine; on p4est this also restores the 2:1 balance and rebalances
        // the partition.
        triangulation.execute_coarsening_and_refinement();
      }
  }



  // @sect4{check_boundary_ids}
  //
  // Every boundary part named in the parameter file must be on the mesh (on
  // some rank), and Gamma_1 must not be empty: without it the elastic
  // operator is singular. (The parameter file's pattern requires at least
  // one clamped id; this check makes sure it is on the mesh.)
  template <int dim>
  void
  check_boundary_ids(const Parameters::AllParameters &parameters,
                     const Triangulation<dim>        &triangulation,
                     const MPI_Comm                   communicator)
  {
    // The boundary ids of this rank's faces, then their union over all
    // ranks: a part may well lie entirely on other ranks.
    std::set<types::boundary_id> local_ids;
    for (const auto &cell : triangulation.active_cell_iterators())
      if (cell->is_locally_owned())
        for (const unsigned int f : cell->face_indices())
          if (cell->face(f)->at_boundary())
            local_ids.insert(cell->face(f)->boundary_id());
    const std::set<types::boundary_id> present
      = union_over_ranks(local_ids, communicator);

    // The message lists the ids that are there, and where they come from.
    const std::string accepted
      = "ids of this mesh: " + Parameters::id_list(present)
        + (parameters.mesh_file.empty()
             ? " (the generated box: 0/1 at x = 0/L1, 2/3 at y = 0/L2, "
               "4/5 at z = 0/L3)"
             : " (the physical groups of the boundary faces in "
                 + parameters.mesh_file + ")");
    // Each named id must be among them; the message names the entry.
    const auto check_ids = [&](const std::vector<types::boundary_id> &ids,
                               const std::string                     &entry,
                               const std::string &subsection = "Boundary") {
      for (const auto id : ids)
        AssertThrow(present.count(id) == 1,
                    ExcMessage(
                      "Invalid parameter <" + entry + "> in subsection <"
                      + subsection + ">: boundary id " + std::to_string(id)
                      + " is not on the mesh; accepted: " + accepted + "."));
    };
    check_ids(parameters.clamped_ids, "Clamped boundary ids");
    check_ids(parameters.contact_ids, "Contact boundary ids");
    check_ids(parameters.loaded_ids, "Loaded boundary ids");
    check_ids(parameters.symmetry_ids, "Symmetry boundary ids");
    for (const auto &[number, entry] :
         parameters.used_prescribed_displacements())
      check_ids(entry->boundary_ids,
                "Boundary ids",
                "Boundary/Prescribed displacement " + std::to_string(number));
    for (const auto &zone : parameters.used_contact_zones())
      {
        if (zone.subsection != "Contact")
          check_ids(zone.boundary_ids, "Boundary ids", zone.subsection);
        check_ids(zone.contact->opposite_ids,
                  "Opposite boundary ids",
                  zone.subsection);
      }
    for (const auto &[number, load] : parameters.used_surface_loads())
      check_ids(load->boundary_ids,
                "Boundary ids",
                "Loads/Surface load " + std::to_string(number));
  }



  // @sect4{check_material_ids}
  //
  // The material ids of the mesh and those of the materials must be the same
  // sets: a cell without a material, or a material without cells (a typing
  // error, most likely), is refused, naming the ids.
  template <int dim>
  void
  check_material_ids(const Parameters::AllParameters &parameters,
                     const Triangulation<dim>        &triangulation,
                     const MPI_Comm                   communicator)
  {
    std::set<types::material_id> local_ids;
    for (const auto &cell : triangulation.active_cell_iterators())
      if (cell->is_locally_owned())
        local_ids.insert(cell->material_id());
    const std::set<types::material_id> present
      = union_over_ranks(local_ids, communicator);
    const std::string source
      = "the material ids of this mesh: " + Parameters::id_list(present)
        + (!parameters.material_id_function.empty()
             ? " (the values of <Material id function> in subsection "
               "<Geometry>)"
           : parameters.mesh_file.empty()
             ? " (the generated box)"
             : " (the physical groups of the cells in " + parameters.mesh_file
                 + ")");

    std::set<types::material_id> named;
    for (const auto &[name, material] : parameters.used_materials())
      for (const auto id : material->material_ids)
        {
          AssertThrow(present.count(id) == 1,
                      ExcMessage("Invalid parameter <Material ids> in "
                                 "subsection <"
                                 + name + ">: material id " + std::to_string(id)
                                 + " is not on the mesh; accepted: " + source
                                 + "."));
          named.insert(id);
        }
    // Subsection Material without ids is every cell of a one-material mesh.
    if (named.empty())
      {
        AssertThrow(present.size() == 1,
                    ExcMessage("Invalid parameter <Material ids> in subsection "
                               "<Material>: value <>; accepted: an empty list "
                               "only for a mesh with one material id, but "
                               + source
                               + ". Name each of them in <Material ids> of "
                                 "subsection <Material> or of a subsection "
                                 "<Material N> (N = 2, 3, ...)."));
      }
    else
      {
        std::set<types::material_id> missing;
        std::set_difference(present.begin(),
                            present.end(),
                            named.begin(),
                            named.end(),
                            std::inserter(missing, missing.end()));
        AssertThrow(missing.empty(),
                    ExcMessage("The mesh has cells of material id "
                               + Parameters::id_list(missing)
                               + " that no material names (" + source
                               + "); name each in <Material ids> of "
                                 "subsection <Material> or of a subsection "
                                 "<Material N> (N = 2, 3, ...)."));
      }
  }



  // The instantiations for 2D and 3D.
  template std::unique_ptr<parallel::DistributedTriangulationBase<2>>
  create_distributed_mesh(const Parameters::AllParameters &,
                          const MPI_Comm,
                          const bool);
  template std::unique_ptr<parallel::DistributedTriangulationBase<3>>
  create_distributed_mesh(const Parameters::AllParameters &,
                          const MPI_Comm,
                          const bool);
  template void
  create_coarse_mesh(const Parameters::AllParameters &, Triangulation<2> &);
  template void
  create_coarse_mesh(const Parameters::AllParameters &, Triangulation<3> &);
  template void
  refine_mesh(const Parameters::AllParameters &, Triangulation<2> &);
  template void
  refine_mesh(const Parameters::AllParameters &, Triangulation<3> &);
  template void
  check_boundary_ids(const Parameters::AllParameters &,
                     const Triangulation<2> &,
                     const MPI_Comm);
  template void
  check_boundary_ids(const Parameters::AllParameters &,
                     const Triangulation<3> &,
                     const MPI_Comm);
  template void
  check_material_ids(const Parameters::AllParameters &,
                     const Triangulation<2> &,
                     const MPI_Comm);
  template void
  check_material_ids(const Parameters::AllParameters &,
                     const Triangulation<3> &,
                     const MPI_Comm);
} // namespace ViscoContact
