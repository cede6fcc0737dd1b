#ifndef viscoplastic_contact_materials_h
#define viscoplastic_contact_materials_h

#include <deal.II/base/symmetric_tensor.h>
#include <deal.II/base/types.h>

#include <deal.II/dofs/dof_handler.h>

#include "elastic_operator.h"
#include "material.h"
#include "material_law.h"
#include "parameters.h"

#include <map>
#include <memory>
#include <vector>

namespace ViscoContact
{
  using namespace dealii;

  // @sect3{The materials of a scene}
  //
  // The laws (material_law.h) of subsection Material and of the numbered
  // ones that are used, in that order, each built from its subsection by
  // make_law() (the one place that names the implementations), the law of
  // each material id, and the law of each locally owned cell of the current
  // mesh, in the order of the stress points (set_cells()). With one
  // material for every cell there are no ids.
  template <int dim>
  class Materials
  {
  public:
    explicit Materials(const Parameters::AllParameters &parameters);

    // The law of a subsection (Law, with its constants).
    static std::unique_ptr<const MaterialLaw<dim>>
    make_law(const Parameters::Material &material, const bool plane_strain);

    const std::vector<std::unique_ptr<const MaterialLaw<dim>>> &
    laws() const
    {
      return material_laws;
    }
    const MaterialLaw<dim> &
    of_id(const types::material_id id) const
    {
      return *material_laws[law_index.empty() ? 0 : law_index.at(id)];
    }
    // The elasticity tensor of a cell's material (for the assembly of K).
    ElasticityOfCell<dim>
    cell_elasticity() const;

    // The law of the k-th locally owned cell of the cells last set.
    void
    set_cells(
      const std::vector<typename DoFHandler<dim>::active_cell_iterator> &cells);
    const MaterialLaw<dim> &
    of_cell(const unsigned int k) const
    {
      return *material_laws[cell_law[k]];
    }
    // The von Mises stress of a record of the k-th owned cell (with its
    // sigma_zz in 2D plane strain).
    double
    von_mises_stress(const unsigned int                 k,
                     const QuadraturePointHistory<dim> &state) const
    {
      double stress_zz = 0;
      if constexpr (dim == 2)
        stress_zz = state.stress_zz;
      return of_cell(k).equivalent_stress(state.stress, stress_zz);
    }

    // The largest step of the explicit history update that is stable: the
    // smallest of the laws' (4 lambda / lambda_max(E) for Perzyna's).
    double
    explicit_stability_limit() const;

  private:
    std::vector<std::unique_ptr<const MaterialLaw<dim>>> material_laws;
    std::map<types::material_id, unsigned int>           law_index;
    std::vector<unsigned int>                            cell_law;
  };
} // namespace ViscoContact

#endif
