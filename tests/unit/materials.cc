// Unit tests of Materials<dim> (materials.h): the law each subsection
// builds, the law of each material id and owned cell, and the stability
// limit of the explicit update over the laws.

#include <deal.II/distributed/tria.h>

#include <deal.II/dofs/dof_handler.h>

#include <deal.II/fe/fe_q.h>

#include <deal.II/grid/grid_generator.h>

#include <gtest/gtest.h>

#include "materials.h"
#include "test_scenes.h"

#include <cmath>
#include <limits>

using namespace dealii;
using namespace ViscoContact;

namespace
{
  // Subsection Material (id 1, Perzyna) and Material 2 (id 2, hardening
  // plasticity, implicit update in plane strain).
  const std::string two_materials = R"(
    set Plane model = plane strain
    subsection Material
      set Material ids     = 1
      set Young's modulus  = 1000
      set Poisson ratio    = 0.3
      set Viscosity        = 50
      set Yield stress     = 2
    end
    subsection Material 2
      set Material ids      = 2
      set Young's modulus   = 3000
      set Poisson ratio     = 0.25
      set Yield stress      = 5
      set Law               = hardening plasticity
      set Hardening modulus = 100
    end
    subsection Time
      set Stress update = implicit
    end
  )";

  Parameters::AllParameters
  parse_two_materials()
  {
    Parameters::AllParameters parameters;
    parameters.further_materials.resize(1);
    parameters.further_contact_zones.resize(1);
    ParameterHandler prm;
    parameters.add_parameters(prm);
    prm.parse_input_from_string(two_materials);
    return parameters;
  }
} // namespace

TEST(Materials, LawOfEachSubsectionAndMaterialId)
{
  const Parameters::AllParameters parameters = parse_two_materials();
  const Materials<2>              materials(parameters);
  ASSERT_EQ(materials.laws().size(), 2u);
  // Perzyna's law has a rate form, hardening plasticity has none.
  EXPECT_TRUE(materials.of_id(1).has_rate_form());
  EXPECT_FALSE(materials.of_id(2).has_rate_form());
  EXPECT_EQ(materials.of_id(1).yield_stress(), 2.);
  EXPECT_EQ(materials.of_id(2).yield_stress(), 5.);
  // Hooke's law of each: E_xxxx = lambda + 2 mu in plane strain.
  const auto c_xxxx = [](const double E, const double k) {
    return E * (1 - k) / ((1 + k) * (1 - 2 * k));
  };
  EXPECT_NEAR(materials.of_id(1).elasticity_tensor()[0][0][0][0],
              c_xxxx(1000, 0.3),
              1e-10);
  EXPECT_NEAR(materials.of_id(2).elasticity_tensor()[0][0][0][0],
              c_xxxx(3000, 0.25),
              1e-10);
  // The stability limit is the smallest of the laws': Perzyna's
  // 4 lambda / lambda_max(E) (hardening plasticity sets none).
  EXPECT_NEAR(materials.explicit_stability_limit(),
              4 * 50 / materials.of_id(1).largest_elastic_eigenvalue(),
              1e-14);
}

TEST(Materials, LawOfEachOwnedCell)
{
  const Parameters::AllParameters parameters = parse_two_materials();
  Materials<2>                    materials(parameters);
  // Four cells, the left half of id 1, the right half of id 2.
  parallel::distributed::Triangulation<2> triangulation(MPI_COMM_WORLD);
  GridGenerator::hyper_cube(triangulation);
  triangulation.refine_global(1);
  for (const auto &cell : triangulation.active_cell_iterators())
    cell->set_material_id(cell->center()[0] < 0.5 ? 1 : 2);
  DoFHandler<2> dof_handler(triangulation);
  dof_handler.distribute_dofs(FE_Q<2>(1));
  std::vector<DoFHandler<2>::active_cell_iterator> cells;
  for (const auto &cell : dof_handler.active_cell_iterators())
    if (cell->is_locally_owned())
      cells.push_back(cell);
  materials.set_cells(cells);
  for (unsigned int k = 0; k < cells.size(); ++k)
    {
      EXPECT_EQ(&materials.of_cell(k),
                &materials.of_id(cells[k]->material_id()));
      EXPECT_EQ(&materials.cell_elasticity()(cells[k]),
                &materials.of_id(cells[k]->material_id()).elasticity_tensor());
    }
  // The von Mises stress of a record through its cell's law: uniaxial
  // stress s (with sigma_zz = 0) has the von Mises stress |s| (on a rank
  // that owns a cell).
  QuadraturePointHistory<2> state;
  state.stress[0][0] = -3;
  if (!cells.empty())
    {
      EXPECT_NEAR(materials.von_mises_stress(0, state), 3, 1e-14);
    }
}
