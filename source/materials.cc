// The materials of a scene: the laws from their subsections, and the law of
// each material id and of each owned cell.

#include <deal.II/base/exceptions.h>

#include "hardening_plasticity.h"
#include "materials.h"

#include <algorithm>
#include <limits>

namespace ViscoContact
{
  // @sect4{Materials::make_law}
  //
  // The one place that names the implementations of MaterialLaw: a new law
  // is a class of its own, a value of the entry Law, and a line here.
  template <int dim>
  std::unique_ptr<const MaterialLaw<dim>>
  Materials<dim>::make_law(const Parameters::Material &material,
                           const bool                  plane_strain)
  {
    if (material.plasticity
        && material.law == Parameters::MaterialLawType::hardening_plasticity)
      return std::make_unique<HardeningPlasticity<dim>>(
        material.young_modulus,
        material.poisson_ratio,
        material.yield_stress,
        material.hardening_modulus,
        plane_strain);
    return std::make_unique<PerzynaMaterial<dim>>(material.young_modulus,
                                                  material.poisson_ratio,
                                                  material.viscosity,
                                                  material.yield_stress,
                                                  material.plasticity,
                                                  plane_strain);
  }



  // @sect4{Materials::Materials}
  //
  // The laws in the order of used_materials(), and the number of each
  // material id among them (none with one material for every cell, whose
  // subsection Material has no ids).
  template <int dim>
  Materials<dim>::Materials(const Parameters::AllParameters &parameters)
  {
    const bool plane_strain
      = parameters.plane_model == Parameters::PlaneModel::plane_strain;
    const auto used = parameters.used_materials();
    for (unsigned int m = 0; m < used.size(); ++m)
      {
        material_laws.push_back(make_law(*used[m].second, plane_strain));
        for (const auto id : used[m].second->material_ids)
          law_index[id] = m;
      }
  }



  template <int dim>
  ElasticityOfCell<dim>
  Materials<dim>::cell_elasticity() const
  {
    return [this](const typename DoFHandler<dim>::active_cell_iterator &cell)
             -> const SymmetricTensor<4, dim> & {
      return of_id(cell->material_id()).elasticity_tensor();
    };
  }



  template <int dim>
  void
  Materials<dim>::set_cells(
    const std::vector<typename DoFHandler<dim>::active_cell_iterator> &cells)
  {
    cell_law.clear();
    for (const auto &cell : cells)
      cell_law.push_back(law_index.empty() ? 0
                                           : law_index.at(cell->material_id()));
  }



  // @sect4{Materials::explicit_stability_limit}
  //
  // The smallest limit of the laws (forward Euler on the relaxation of a
  // viscoplastic material is stable for k < 4 lambda / lambda_max(E),
  // doc/model.md, section 3; an elastic material sets no limit).
  template <int dim>
  double
  Materials<dim>::explicit_stability_limit() const
  {
    double limit = std::numeric_limits<double>::infinity();
    for (const auto &law : material_laws)
      limit = std::min(limit, law->explicit_stability_limit());
    return limit;
  }



  template class Materials<2>;
  template class Materials<3>;
} // namespace ViscoContact
