// Unit tests of PrescribedDisplacements on the unit square (boundary ids 0
// left, 1 right, 2 bottom, 3 top), refined three times, and once more in
// its top-left cell (hanging nodes on the top edge and on the plane of
// symmetry): the bottom clamped, u_y = -0.01 t x prescribed on the top,
// the left edge a plane of symmetry.
// - g_n takes the prescribed values on the top and zero on the bottom and
//   the plane; the hanging node between two top vertices takes their mean.
// - The reactions of a residual of one in every entry count each part's
//   vertices: a hanging node's share goes to its parents with the weights
//   of its constraint (also from inside the body), and a vertex that a
//   Dirichlet part takes in a component gives the plane nothing in it.
// - The lifting load is -(E eps(g_n), eps(v)) as FEValues assembles it.
// - A scene that leaves a rigid motion free is refused, naming it.

#include <deal.II/base/quadrature_lib.h>

#include <deal.II/distributed/tria.h>

#include <deal.II/dofs/dof_handler.h>
#include <deal.II/dofs/dof_tools.h>

#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/fe/mapping_q.h>

#include <deal.II/hp/mapping_collection.h>
#include <deal.II/hp/q_collection.h>

#include <deal.II/grid/grid_generator.h>

#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/vector.h>

#include <gtest/gtest.h>

#include "scene/prescribed_displacements.h"
#include "test_scenes.h"

#include <cmath>
#include <string>

using namespace dealii;
using namespace ViscoContact;

namespace
{
  Parameters::AllParameters
  scene(const std::string &boundary)
  {
    return TestScenes::parse_parameters(
      "subsection Boundary\n" + boundary
        + "  set Loaded boundary ids  =\n"
          "  set Contact boundary ids = 1\n"
          "  subsection Prescribed displacement 1\n"
          "    set Boundary ids = 3\n"
          "    set Components   = y\n"
          "    set Displacement = -0.01 * t * x\n"
          "  end\n"
          "end\n",
      1);
  }

  // The mesh, dofs, constraints and stress points of the square, with the
  // prescribed displacements set up on them.
  struct Square
  {
    Square(const Parameters::AllParameters &parameters)
      : triangulation(MPI_COMM_WORLD)
      , fe(FE_Q<2>(1), 2)
      , mapping(MappingQ<2>(1))
      , prescribed(parameters)
    {
      GridGenerator::hyper_cube(triangulation, 0, 1, true);
      triangulation.refine_global(3);
      for (const auto &cell : triangulation.active_cell_iterators())
        if (cell->is_locally_owned()
            && cell->center().distance(Point<2>(1. / 16, 15. / 16)) < 1e-12)
          cell->set_refine_flag();
      triangulation.execute_coarsening_and_refinement();
      dof_handler.reinit(triangulation);
      dof_handler.distribute_dofs(fe);
      DoFTools::extract_locally_relevant_dofs(dof_handler, relevant);
      prescribed.make_constraints(mapping, dof_handler, relevant, constraints);
      layout.reinit(dof_handler.locally_owned_dofs(), relevant, MPI_COMM_WORLD);
      stress_points.reinit(mapping,
                           dof_handler,
                           hp::QCollection<2>(QGauss<2>(2)),
                           *layout.get_partitioner(),
                           constraints);
      prescribed.reinit(mapping, dof_handler, relevant, stress_points, layout);
    }

    parallel::distributed::Triangulation<2> triangulation;
    const FESystem<2>                       fe;
    const hp::MappingCollection<2>          mapping;
    DoFHandler<2>                           dof_handler;
    IndexSet                                relevant;
    AffineConstraints<double>               constraints;
    VectorType                              layout;
    StressPointGeometry<2>                  stress_points;
    PrescribedDisplacements<2>              prescribed;
  };

  const std::string holding_scene = "  set Clamped boundary ids  = 2\n"
                                    "  set Symmetry boundary ids = 0\n";

  // lambda = mu = 1.
  SymmetricTensor<4, 2>
  elasticity()
  {
    SymmetricTensor<4, 2> E;
    for (unsigned int i = 0; i < 2; ++i)
      for (unsigned int j = 0; j < 2; ++j)
        for (unsigned int k = 0; k < 2; ++k)
          for (unsigned int l = 0; l < 2; ++l)
            E[i][j][k][l] = (i == j && k == l ? 1. : 0.)
                            + (i == k && j == l ? 0.5 : 0.)
                            + (i == l && j == k ? 0.5 : 0.);
    return E;
  }
} // namespace

TEST(PrescribedDisplacements, ValuesOnTheParts)
{
  Square square(scene(holding_scene));
  square.prescribed.check_rigid_motions(square.mapping,
                                        square.dof_handler,
                                        square.constraints);
  const SymmetricTensor<4, 2> E = elasticity();
  square.prescribed.set_time(
    2.,
    false,
    [&](unsigned int) -> const auto & { return E; });
  VectorType u(square.layout);
  u = 0;
  square.prescribed.distribute(u, square.constraints);
  u.update_ghost_values();
  for (const auto &cell : square.dof_handler.active_cell_iterators())
    if (cell->is_locally_owned())
      for (const unsigned int v : cell->vertex_indices())
        {
          const Point<2> x  = cell->vertex(v);
          const double   ux = u(cell->vertex_dof_index(v, 0));
          const double   uy = u(cell->vertex_dof_index(v, 1));
          if (std::abs(x[1] - 1) < 1e-12)
            {
              EXPECT_NEAR(uy, -0.02 * x[0], 1e-15) << x;
            }
          else if (std::abs(x[1]) < 1e-12)
            {
              EXPECT_TRUE(ux == 0 && uy == 0) << x;
            }
          if (std::abs(x[0]) < 1e-12)
            {
              EXPECT_EQ(ux, 0) << x;
            }
        }
}

TEST(PrescribedDisplacements, ReactionsOfAUnitResidual)
{
  Square square(scene(holding_scene));
  EXPECT_EQ(
    square.prescribed.reaction_names(),
    (std::vector<std::string>{"clamped", "prescribed_1", "symmetry_0"}));
  VectorType residual(square.layout);
  for (unsigned int i = 0; i < residual.locally_owned_size(); ++i)
    residual.local_element(i) = 1;
  const std::vector<Tensor<1, 2>> forces
    = square.prescribed.reactions(residual, nullptr);
  ASSERT_EQ(forces.size(), 3u);
  // 9 vertices on the bottom; 10 on the top and on the left (one hanging
  // each), of which the bottom-left corner gives the plane nothing; and
  // the hanging nodes on the refined cell's right and bottom edges give
  // half of theirs to a top and a left vertex.
  const auto expect_force =
    [&](const unsigned int part, const double x, const double y) {
      EXPECT_EQ(forces[part][0], x) << square.prescribed.reaction_names()[part];
      EXPECT_EQ(forces[part][1], y) << square.prescribed.reaction_names()[part];
    };
  expect_force(0, 9, 9);
  expect_force(1, 0, 10.5);
  expect_force(2, 9.5, 0);
}

TEST(PrescribedDisplacements, LiftingAsFEValuesAssemblesIt)
{
  Square                      square(scene(holding_scene));
  const SymmetricTensor<4, 2> E = elasticity();
  square.prescribed.set_time(
    1.5,
    true,
    [&](unsigned int) -> const auto & { return E; });
  VectorType g(square.layout);
  g = 0;
  square.prescribed.distribute(g, square.constraints);
  g.update_ghost_values();

  // -(E eps(g), eps(v)) over every owned cell, through the homogeneous
  // constraints.
  VectorType                           expected(square.layout);
  QGauss<2>                            quadrature(2);
  FEValues<2>                          fe_values(square.mapping[0],
                        square.fe,
                        quadrature,
                        update_gradients | update_JxW_values);
  const unsigned int                   n = square.fe.n_dofs_per_cell();
  std::vector<types::global_dof_index> dofs(n);
  Vector<double>                       cell_vector(n);
  for (const auto &cell : square.dof_handler.active_cell_iterators())
    if (cell->is_locally_owned())
      {
        fe_values.reinit(cell);
        cell->get_dof_indices(dofs);
        cell_vector = 0;
        for (const unsigned int q : fe_values.quadrature_point_indices())
          {
            SymmetricTensor<2, 2> strain;
            for (unsigned int j = 0; j < n; ++j)
              {
                const unsigned int c
                  = square.fe.system_to_component_index(j).first;
                Tensor<2, 2> gradient;
                gradient[c] = fe_values.shape_grad_component(j, q, c);
                strain += g(dofs[j]) * symmetrize(gradient);
              }
            const SymmetricTensor<2, 2> stress = E * strain;
            for (unsigned int i = 0; i < n; ++i)
              {
                const unsigned int c
                  = square.fe.system_to_component_index(i).first;
                Tensor<2, 2> gradient;
                gradient[c] = fe_values.shape_grad_component(i, q, c);
                cell_vector(i) -= scalar_product(stress, symmetrize(gradient))
                                  * fe_values.JxW(q);
              }
          }
        square.constraints.distribute_local_to_global(cell_vector,
                                                      dofs,
                                                      expected);
      }
  expected.compress(VectorOperation::add);
  VectorType difference(square.layout);
  difference = square.prescribed.lifting_load();
  difference -= expected;
  EXPECT_GT(expected.l2_norm(), 1e-3);
  EXPECT_LT(difference.linfty_norm(), 1e-14 * expected.linfty_norm());
}

TEST(PrescribedDisplacements, FreeRigidMotionIsRefused)
{
  // Only the plane of symmetry and the top's y: the body slides along x.
  Square square(scene("  set Clamped boundary ids  =\n"
                      "  set Symmetry boundary ids = 2\n"));
  try
    {
      square.prescribed.check_rigid_motions(square.mapping,
                                            square.dof_handler,
                                            square.constraints);
      FAIL() << "a body free to move along x was accepted";
    }
  catch (const std::exception &error)
    {
      EXPECT_NE(std::string(error.what()).find("free to move rigidly"),
                std::string::npos)
        << error.what();
    }
}
