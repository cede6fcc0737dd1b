// The cell types, elements, mappings and quadratures of a run
// (discretisation.h).

#include <deal.II/base/quadrature_lib.h>

#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_simplex_p.h>
#include <deal.II/fe/fe_system.h>

#include "discretisation.h"

#include <memory>

namespace ViscoContact
{
  template <int dim>
  Discretisation<dim>::Discretisation(const Parameters::CellType cell_type)
  {
    if (cell_type != Parameters::CellType::simplex)
      cell_types.push_back(ReferenceCells::get_hypercube<dim>());
    if (cell_type != Parameters::CellType::hypercube)
      cell_types.push_back(ReferenceCells::get_simplex<dim>());
    const unsigned int gauss_points = 1u << dim;
    for (const ReferenceCell &cell : cell_types)
      {
        mapping.push_back(cell.template get_default_linear_mapping<dim>());
        std::unique_ptr<FiniteElement<dim>> linear;
        if (cell.is_simplex())
          linear = std::make_unique<FE_SimplexP<dim>>(1);
        else
          linear = std::make_unique<FE_Q<dim>>(1);
        fe.push_back(FESystem<dim>(*linear, dim));
        scalar_fe.push_back(*linear);
        Quadrature<dim> stress_points
          = cell.template get_gauss_type_quadrature<dim>(cell.is_simplex() ? 1
                                                                           : 2);
        if (cell.is_simplex() && is_mixed())
          stress_points = Quadrature<dim>(
            std::vector<Point<dim>>(gauss_points, stress_points.point(0)),
            std::vector<double>(gauss_points,
                                stress_points.weight(0) / gauss_points));
        stress_quadrature.push_back(stress_points);
        load_quadrature.push_back(
          cell.template get_gauss_type_quadrature<dim>(2));
        face_quadrature.push_back(
          cell.face_reference_cell(0)
            .template get_gauss_type_quadrature<dim - 1>(2));
      }
  }



  template <int dim>
  unsigned int
  Discretisation<dim>::index(const ReferenceCell &cell_type) const
  {
    for (unsigned int i = 0; i < cell_types.size(); ++i)
      if (cell_types[i] == cell_type)
        return i;
    AssertThrow(false, ExcInternalError());
    return 0;
  }



  template <int dim>
  bool
  Discretisation<dim>::has_simplices() const
  {
    for (const ReferenceCell &cell : cell_types)
      if (cell.is_simplex())
        return true;
    return false;
  }



  template <int dim>
  unsigned int
  Discretisation<dim>::max_vertices() const
  {
    unsigned int vertices = 0;
    for (const ReferenceCell &cell : cell_types)
      vertices = std::max(vertices, cell.n_vertices());
    return vertices;
  }



  template <int dim>
  std::string
  Discretisation<dim>::describe() const
  {
    std::string names;
    for (unsigned int i = 0; i < cell_types.size(); ++i)
      names += (i == 0 ? "" : " and ") + cell_types[i].to_string();
    return names;
  }



  template <int dim>
  void
  Discretisation<dim>::distribute_dofs(
    DoFHandler<dim>             &dof_handler,
    const hp::FECollection<dim> &elements) const
  {
    if (is_mixed())
      for (const auto &cell : dof_handler.active_cell_iterators())
        if (cell->is_locally_owned())
          cell->set_active_fe_index(index(cell->reference_cell()));
    dof_handler.distribute_dofs(elements);
  }



  template class Discretisation<2>;
  template class Discretisation<3>;
} // namespace ViscoContact
