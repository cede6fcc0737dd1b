// Meshes: the generated box or a Gmsh file, refined uniformly and toward the
// contact boundary, and the check that the named boundary parts exist.

#include <deal.II/base/exceptions.h>
#include <deal.II/base/mpi.h>

#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/grid_in.h>
#include <deal.II/grid/tria_accessor.h>
#include <deal.II/grid/tria_iterator.h>

#include "mesh.h"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

namespace ViscoContact
{
  namespace
  {
    bool
    contains(const std::vector<types::boundary_id> &ids,
             const types::boundary_id               id)
    {
      return std::find(ids.begin(), ids.end(), id) != ids.end();
    }
  } // namespace



  // @sect4{create_coarse_mesh}
  //
  // The box (0,L1)x(0,L2)(x(0,L3)) with Subdivisions squares (cubes) along
  // each edge, on simplex meshes each square split into two triangles (each
  // cube into five tetrahedra). deal.II 9.4 cannot colorize the simplex
  // generator, so the boundary ids are set from the face centres with the
  // numbering colorize uses for hypercubes: 2d and 2d+1 at x_d = 0 and L_d.
  //
  // A Gmsh file brings its own boundary ids (the physical groups of its
  // boundary faces); its cells must all be of the chosen Cell type, since
  // the finite element and the stress points are chosen from it.
  template <int dim>
  void
  create_coarse_mesh(const Parameters::AllParameters &parameters,
                     Triangulation<dim>              &triangulation)
  {
    const bool simplex = (parameters.cell_type == "simplex");
    if (!parameters.mesh_file.empty())
      {
        const std::string &file = parameters.mesh_file;
        AssertThrow(std::filesystem::is_regular_file(file),
                    ExcMessage("Invalid parameter <Mesh file> in subsection "
                               "<Geometry>: value <"
                               + file
                               + ">; accepted: an existing Gmsh .msh file "
                                 "(relative to the working directory) or "
                                 "nothing for the generated box."));
        std::string reader_message;
        try
          {
            GridIn<dim> grid_in;
            grid_in.attach_triangulation(triangulation);
            std::ifstream in(file);
            grid_in.read_msh(in);
          }
        catch (const ExceptionBase &exc)
          {
            std::ostringstream info;
            exc.print_info(info);
            reader_message = info.str();
          }
        catch (const std::exception &exc)
          {
            reader_message = exc.what();
          }
        AssertThrow(reader_message.empty() && triangulation.n_cells() > 0,
                    ExcMessage("Invalid parameter <Mesh file> in subsection "
                               "<Geometry>: value <"
                               + file
                               + ">; accepted: a Gmsh .msh file (format 2 or "
                                 "4, ASCII) of a "
                               + std::to_string(dim)
                               + "D mesh. The reader says: " + reader_message));
        for (const auto &cell : triangulation.active_cell_iterators())
          AssertThrow(cell->reference_cell().is_simplex() == simplex,
                      ExcMessage(
                        "Invalid parameter <Mesh file> in subsection "
                        "<Geometry>: value <"
                        + file + ">: it has "
                        + cell->reference_cell().to_string()
                        + " cells; accepted: a mesh of "
                        + (simplex ? "simplices" : "quadrilaterals/hexahedra")
                        + " only, as <Cell type> = " + parameters.cell_type
                        + " requires."));
        return;
      }

    Point<dim>                corner;
    std::vector<unsigned int> repetitions(dim, parameters.subdivisions);
    for (unsigned int d = 0; d < dim; ++d)
      corner[d] = parameters.lengths[d];

    if (simplex)
      {
        GridGenerator::subdivided_hyper_rectangle_with_simplices(triangulation,
                                                                 repetitions,
                                                                 Point<dim>(),
                                                                 corner);
        for (const auto &face : triangulation.active_face_iterators())
          if (face->at_boundary())
            for (unsigned int d = 0; d < dim; ++d)
              {
                const double x         = face->center()[d];
                const double tolerance = 1e-10 * parameters.lengths[d];
                if (std::abs(x) < tolerance)
                  face->set_boundary_id(2 * d);
                else if (std::abs(x - parameters.lengths[d]) < tolerance)
                  face->set_boundary_id(2 * d + 1);
              }
      }
    else
      GridGenerator::subdivided_hyper_rectangle(triangulation,
                                                repetitions,
                                                Point<dim>(),
                                                corner,
                                                /*colorize=*/true);
  }



  // @sect4{refine_mesh}
  //
  // Uniform refinement, then Contact refinement levels rounds in which every
  // cell with a vertex on Gamma_3 is refined: the cells along the contact
  // boundary all end on the finest level, so no contact node is a hanging
  // node, and the mesh coarsens away from Gamma_3 (2:1 across faces on
  // p4est meshes).
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
        // a vertex only is refined too.
        std::vector<bool> on_contact_boundary(triangulation.n_vertices(),
                                              false);
        for (const auto &cell : triangulation.active_cell_iterators())
          if (!cell->is_artificial())
            for (const unsigned int f : cell->face_indices())
              if (cell->face(f)->at_boundary()
                  && contains(parameters.contact_ids,
                              cell->face(f)->boundary_id()))
                for (const unsigned int v : cell->face(f)->vertex_indices())
                  on_contact_boundary[cell->face(f)->vertex_index(v)] = true;
        for (const auto &cell : triangulation.active_cell_iterators())
          if (cell->is_locally_owned())
            for (const unsigned int v : cell->vertex_indices())
              if (on_contact_boundary[cell->vertex_index(v)])
                {
                  cell->set_refine_flag();
                  break;
                }
        triangulation.execute_coarsening_and_refinement();
      }
  }



  // @sect4{check_boundary_ids}
  //
  // Every boundary part named in the parameter file must be on the mesh
  // (on some rank), and Gamma_1 must not be empty: without it the elastic
  // operator is singular.
  template <int dim>
  void
  check_boundary_ids(const Parameters::AllParameters &parameters,
                     const Triangulation<dim>        &triangulation,
                     const MPI_Comm                   communicator)
  {
    std::set<types::boundary_id> local_ids;
    for (const auto &cell : triangulation.active_cell_iterators())
      if (cell->is_locally_owned())
        for (const unsigned int f : cell->face_indices())
          if (cell->face(f)->at_boundary())
            local_ids.insert(cell->face(f)->boundary_id());
    const std::vector<types::boundary_id> present_list
      = Utilities::MPI::compute_set_union(
        std::vector<types::boundary_id>(local_ids.begin(), local_ids.end()),
        communicator);
    const std::set<types::boundary_id> present(present_list.begin(),
                                               present_list.end());

    std::string accepted;
    for (const auto id : present)
      accepted += (accepted.empty() ? "" : ", ") + std::to_string(id);
    accepted = "ids of this mesh: " + accepted
               + (parameters.mesh_file.empty()
                    ? " (the generated box: 0/1 at x = 0/L1, 2/3 at y = 0/L2, "
                      "4/5 at z = 0/L3)"
                    : " (the physical groups of the boundary faces in "
                        + parameters.mesh_file + ")");
    const auto check_ids = [&](const std::vector<types::boundary_id> &ids,
                               const std::string                     &entry) {
      for (const auto id : ids)
        AssertThrow(present.count(id) == 1,
                    ExcMessage("Invalid parameter <" + entry
                               + "> in subsection <Boundary>: boundary id "
                               + std::to_string(id)
                               + " is not on the mesh; accepted: " + accepted
                               + "."));
    };
    check_ids(parameters.clamped_ids, "Clamped boundary ids");
    check_ids(parameters.contact_ids, "Contact boundary ids");
    check_ids(parameters.loaded_ids, "Loaded boundary ids");
  }



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
} // namespace ViscoContact
