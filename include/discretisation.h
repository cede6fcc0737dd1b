#ifndef viscoplastic_contact_discretisation_h
#define viscoplastic_contact_discretisation_h

#include <deal.II/dofs/dof_handler.h>

#include <deal.II/grid/reference_cell.h>

#include <deal.II/hp/fe_collection.h>
#include <deal.II/hp/fe_values.h>
#include <deal.II/hp/mapping_collection.h>
#include <deal.II/hp/q_collection.h>

#include "parameters.h"

#include <vector>

namespace ViscoContact
{
  using namespace dealii;

  // @sect3{The discretisation}
  //
  // The cell types of the mesh and, per cell type, the linear mapping, the
  // linear Lagrange element (P1 on triangles and tetrahedra, Q1 on
  // quadrilaterals and hexahedra; the displacement is dim copies of it, the
  // scalar one alone carries the nodal fields of the output) and the
  // quadratures, as deal.II's hp collections: entry i of each belongs to
  // cell_types[i], and a cell's active_fe_index is the index of its type.
  // A mesh of one cell type has one entry (Cell type = simplex or
  // hypercube); Cell type = mixed has both (a Gmsh mesh of triangles and
  // quadrilaterals, or of tetrahedra and hexahedra, say one body of each
  // joined by a contact pair).
  //
  // The stress points: the 2^dim Gauss points of a hypercube; one point per
  // simplex, where the P1 strain is constant (doc/model.md, section 2). On
  // a mixed mesh every cell has the same number of stress points, so that
  // the records of the material state keep one stride: a simplex then
  // carries 2^dim copies of its centroid, each with 1/2^dim of its volume,
  // which hold the same state (the same strain and, from the same start,
  // the same history) at 2^dim times the cost of one.
  template <int dim>
  class Discretisation
  {
  public:
    explicit Discretisation(const Parameters::CellType cell_type);

    std::vector<ReferenceCell> cell_types;
    hp::MappingCollection<dim> mapping;
    hp::FECollection<dim>      fe;
    hp::FECollection<dim>      scalar_fe;
    hp::QCollection<dim>       stress_quadrature;
    // The loads: the Gauss-type rule of order 2 of the cell type, and of
    // its faces.
    hp::QCollection<dim>     load_quadrature;
    hp::QCollection<dim - 1> face_quadrature;

    // The index of a cell type in the collections.
    unsigned int
    index(const ReferenceCell &cell_type) const;
    bool
    is_mixed() const
    {
      return cell_types.size() > 1;
    }
    bool
    has_simplices() const;
    // The stress points of every cell.
    unsigned int
    n_stress_points() const
    {
      return stress_quadrature[0].size();
    }
    // The most vertices of a cell.
    unsigned int
    max_vertices() const;
    // The names of the cell types for the run's header, deal.II's ("Quad",
    // "Quad and Tri").
    std::string
    describe() const;

    // The dofs of elements (fe or scalar_fe) on the mesh of dof_handler:
    // each locally owned cell gets the element of its cell type.
    void
    distribute_dofs(DoFHandler<dim>             &dof_handler,
                    const hp::FECollection<dim> &elements) const;
  };

  // The values the loads are integrated with (Loads::cell_load()): shape
  // values, points and JxW at the load quadrature of each cell, and normals
  // on its faces.
  template <int dim>
  struct LoadValues
  {
    explicit LoadValues(const Discretisation<dim> &discretisation)
      : cell(discretisation.mapping,
             discretisation.fe,
             discretisation.load_quadrature,
             update_values | update_quadrature_points | update_JxW_values)
      , face(discretisation.mapping,
             discretisation.fe,
             discretisation.face_quadrature,
             update_values | update_quadrature_points | update_normal_vectors
               | update_JxW_values)
    {}
    hp::FEValues<dim>     cell;
    hp::FEFaceValues<dim> face;
  };
} // namespace ViscoContact

#endif
