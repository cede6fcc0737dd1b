// Unit tests of the stress-point geometry (StressPointGeometry): the cell
// loops of the time loop read grad u and assemble (tau, eps(v)) from values
// stored once per mesh instead of FEValues. A linear field is reproduced by
// Q1 elements, so its gradient at every stress point is exact, and the load
// of a constant stress tested with it is tau : sym(A) times the volume, on a
// mesh with hanging nodes too (whose cells add through the constraints),
// and the tangent of an isotropic C gives the energy sym(A) : C : sym(A)
// times the volume; on a mesh of triangles and quadrilaterals too.

#include <deal.II/base/function.h>
#include <deal.II/base/index_set.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/quadrature_lib.h>

#include <deal.II/distributed/tria.h>

#include <deal.II/dofs/dof_handler.h>
#include <deal.II/dofs/dof_tools.h>

#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/fe/mapping_q.h>

#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/grid_tools.h>

#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/full_matrix.h>

#include <deal.II/numerics/vector_tools.h>

#include <gtest/gtest.h>

#include "discretisation.h"
#include "stress_points.h"

#include <cmath>

using namespace dealii;
using namespace ViscoContact;

namespace
{
  // u(x) = A x + b.
  template <int dim>
  class LinearField : public Function<dim>
  {
  public:
    LinearField(const Tensor<2, dim> &A)
      : Function<dim>(dim)
      , A(A)
    {}
    double
    value(const Point<dim> &x, const unsigned int c) const override
    {
      return (A * x)[c] + 0.1 * (c + 1);
    }

  private:
    const Tensor<2, dim> A;
  };

  template <int dim>
  Tensor<2, dim>
  gradient_of_the_field()
  {
    Tensor<2, dim> A;
    for (unsigned int i = 0; i < dim; ++i)
      for (unsigned int j = 0; j < dim; ++j)
        A[i][j] = 0.3 * (i + 1) - 0.2 * j + (i == j ? 1. : 0.);
    return A;
  }

  // The box [0, 2] x [0, 1] (x [0, 1]) refined twice, sheared (every cell
  // the same shape) or with its vertices moved at random (every cell its
  // own), or with one cell refined once more (hanging nodes).
  enum class Mesh
  {
    sheared,
    distorted,
    hanging
  };

  template <int dim>
  void
  check_geometry(const Mesh mesh)
  {
    const MPI_Comm                            comm = MPI_COMM_WORLD;
    parallel::distributed::Triangulation<dim> triangulation(comm);
    Point<dim>                                corner;
    for (unsigned int d = 0; d < dim; ++d)
      corner[d] = d == 0 ? 2. : 1.;
    GridGenerator::hyper_rectangle(triangulation, Point<dim>(), corner);
    triangulation.refine_global(2);
    double volume = 2.;
    if (mesh == Mesh::sheared)
      GridTools::transform(
        [](const Point<dim> &x) {
          Point<dim> y = x;
          y[0] += 0.5 * x[1];
          return y;
        },
        triangulation);
    else if (mesh == Mesh::distorted)
      {
        // The same moves on every rank (distort_random draws per rank).
        GridTools::transform(
          [](const Point<dim> &x) {
            Point<dim> y = x;
            for (unsigned int d = 0; d < dim; ++d)
              y[d] += 0.03 * std::sin(7. * x[(d + 1) % dim] + 3. * x[d]);
            return y;
          },
          triangulation);
        volume = 0;
      }
    else
      {
        for (const auto &cell : triangulation.active_cell_iterators())
          if (cell->is_locally_owned() && cell->center()[0] < 0.5
              && cell->center()[1] < 0.5)
            cell->set_refine_flag();
        triangulation.execute_coarsening_and_refinement();
      }

    const FESystem<dim> fe(FE_Q<dim>(1), dim);
    DoFHandler<dim>     dof_handler(triangulation);
    dof_handler.distribute_dofs(fe);
    IndexSet relevant;
    DoFTools::extract_locally_relevant_dofs(dof_handler, relevant);
    AffineConstraints<double> constraints(relevant);
    DoFTools::make_hanging_node_constraints(dof_handler, constraints);
    constraints.close();
    VectorType          u(dof_handler.locally_owned_dofs(), relevant, comm);
    const MappingQ<dim> mapping(1);
    const QGauss<dim>   quadrature(2);

    StressPointGeometry<dim> geometry;
    geometry.reinit(hp::MappingCollection<dim>(mapping),
                    dof_handler,
                    hp::QCollection<dim>(quadrature),
                    *u.get_partitioner(),
                    constraints);
    EXPECT_EQ(geometry.n_cells(), triangulation.n_locally_owned_active_cells());
    EXPECT_EQ(geometry.n_points(), quadrature.size());
    EXPECT_EQ(geometry.n_vertices(), GeometryInfo<dim>::vertices_per_cell);
    // A sheared box has one shape; a refined one two (the coarse and the
    // fine cells); every cell of the distorted one is its own.
    if (mesh == Mesh::sheared)
      {
        EXPECT_EQ(geometry.n_shapes(), geometry.n_cells() > 0 ? 1u : 0u);
      }
    else if (mesh == Mesh::hanging)
      {
        EXPECT_LE(geometry.n_shapes(), 2u);
      }
    else
      {
        EXPECT_EQ(geometry.n_shapes(), geometry.n_cells());
      }

    const Tensor<2, dim> A = gradient_of_the_field<dim>();
    VectorTools::interpolate(mapping, dof_handler, LinearField<dim>(A), u);
    u.update_ghost_values();

    SymmetricTensor<2, dim> tau;
    for (unsigned int i = 0; i < dim; ++i)
      for (unsigned int j = i; j < dim; ++j)
        tau[i][j] = 1. + i - 0.5 * j;
    // Isotropic, lambda = mu = 1.
    SymmetricTensor<4, dim> C;
    for (unsigned int i = 0; i < dim; ++i)
      for (unsigned int j = 0; j < dim; ++j)
        for (unsigned int k = 0; k < dim; ++k)
          for (unsigned int l = 0; l < dim; ++l)
            C[i][j][k][l] = (i == j && k == l ? 1. : 0.)
                            + (i == k && j == l ? 0.5 : 0.)
                            + (i == l && j == k ? 0.5 : 0.);
    FullMatrix<double>  cell_matrix(geometry.n_vertices() * dim,
                                   geometry.n_vertices() * dim);
    double              local_energy = 0;
    VectorType          load(u.get_partitioner());
    double              local_volume = 0;
    std::vector<double> cell_vector(geometry.n_vertices() * dim);
    for (unsigned int k = 0; k < geometry.n_cells(); ++k)
      {
        std::fill(cell_vector.begin(), cell_vector.end(), 0.);
        for (unsigned int q = 0; q < geometry.n_points(); ++q)
          {
            const Tensor<2, dim> gradient
              = geometry.displacement_gradient(u, k, q);
            EXPECT_LT((gradient - A).norm(), 1e-12 * A.norm());
            geometry.add_load(tau, k, q, make_array_view(cell_vector));
            local_volume += geometry.JxW(k, q);
          }
        geometry.distribute(k, make_array_view(cell_vector), load);
        // u_k^T M_k u_k with M_k the cell's (C eps(w), eps(v)).
        cell_matrix = 0;
        for (unsigned int q = 0; q < geometry.n_points(); ++q)
          geometry.add_tangent(C, k, q, cell_matrix);
        for (unsigned int i = 0; i < cell_vector.size(); ++i)
          for (unsigned int j = 0; j < cell_vector.size(); ++j)
            local_energy += u.local_element(geometry.local_dofs(k)[i])
                            * cell_matrix(i, j)
                            * u.local_element(geometry.local_dofs(k)[j]);
      }
    load.compress(VectorOperation::add);
    const double total_volume = Utilities::MPI::sum(local_volume, comm);
    if (volume > 0)
      {
        EXPECT_NEAR(total_volume, volume, 1e-13);
      }
    // (C eps(u), eps(u)) = sym(A) : C : sym(A) |Omega|.
    const double energy = Utilities::MPI::sum(local_energy, comm);
    const double expected_energy
      = (symmetrize(A) * C * symmetrize(A)) * total_volume;
    EXPECT_NEAR(energy, expected_energy, 1e-12 * expected_energy);
    // (tau, eps(u)) = tau : sym(A) |Omega| for the linear field; the
    // constrained entries of the load are zero, their parts passed on.
    u.zero_out_ghost_values();
    EXPECT_NEAR(load * u,
                (tau * symmetrize(A)) * total_volume,
                1e-12 * std::abs(tau * symmetrize(A)) * total_volume);
  }

  // [0, 2] x [0, 1] in squares of side 1/2: quadrilaterals for x < 1, each
  // square cut into two triangles for x > 1 (Cell type = mixed, one body:
  // the triangles share the vertices at x = 1 with the quadrilaterals),
  // refined globally.
  // Every cell has the 4 stress points of the quadrilaterals (a triangle 4
  // copies of its centroid, discretisation.h) and 4 vertices (a triangle
  // repeats its first vertex's dofs with zero gradients), and the
  // gradient of a linear field, the volume and the energy are exact on
  // both kinds of cells.
  void
  check_mixed_geometry(const unsigned int refinements)
  {
    std::vector<Point<2>>    vertices;
    std::vector<CellData<2>> cells;
    const auto               v
      = [](const unsigned int i, const unsigned int j) { return j * 5 + i; };
    for (unsigned int j = 0; j <= 2; ++j)
      for (unsigned int i = 0; i <= 4; ++i)
        vertices.emplace_back(0.5 * i, 0.5 * j);
    for (unsigned int j = 0; j < 2; ++j)
      for (unsigned int i = 0; i < 4; ++i)
        if (i < 2)
          {
            CellData<2> quadrilateral(4);
            quadrilateral.vertices
              = {v(i, j), v(i + 1, j), v(i, j + 1), v(i + 1, j + 1)};
            cells.push_back(quadrilateral);
          }
        else
          for (const std::vector<unsigned int> &corners :
               {std::vector<unsigned int>{v(i, j),
                                          v(i + 1, j),
                                          v(i + 1, j + 1)},
                std::vector<unsigned int>{v(i, j),
                                          v(i + 1, j + 1),
                                          v(i, j + 1)}})
            {
              CellData<2> triangle(3);
              triangle.vertices = corners;
              cells.push_back(triangle);
            }
    Triangulation<2> triangulation;
    triangulation.create_triangulation(vertices, cells, SubCellData());
    triangulation.refine_global(refinements);

    const Discretisation<2> discretisation(Parameters::CellType::mixed);
    ASSERT_TRUE(discretisation.is_mixed());
    DoFHandler<2> dof_handler(triangulation);
    discretisation.distribute_dofs(dof_handler, discretisation.fe);
    // The two kinds of cells share their vertices' dofs, also where
    // refinement has added vertices on the edges between them.
    EXPECT_EQ(dof_handler.n_dofs(), 2 * triangulation.n_used_vertices());
    AffineConstraints<double> constraints;
    constraints.close();
    VectorType u(complete_index_set(dof_handler.n_dofs()), MPI_COMM_SELF);

    StressPointGeometry<2> geometry;
    geometry.reinit(discretisation.mapping,
                    dof_handler,
                    discretisation.stress_quadrature,
                    *u.get_partitioner(),
                    constraints);
    EXPECT_EQ(geometry.n_cells(), 12u << (2 * refinements));
    EXPECT_EQ(geometry.n_points(), 4u);
    EXPECT_EQ(geometry.n_vertices(), 4u);
    // One shape of quadrilaterals and two of triangles (their cuts differ;
    // refined, each triangle's children take two shapes more).
    if (refinements == 0)
      {
        EXPECT_EQ(geometry.n_shapes(), 3u);
      }

    const Tensor<2, 2> A = gradient_of_the_field<2>();
    VectorTools::interpolate(discretisation.mapping,
                             dof_handler,
                             LinearField<2>(A),
                             u);
    double volume = 0, triangle_volume = 0;
    for (unsigned int k = 0; k < geometry.n_cells(); ++k)
      for (unsigned int q = 0; q < geometry.n_points(); ++q)
        {
          const Tensor<2, 2> gradient = geometry.displacement_gradient(u, k, q);
          EXPECT_LT((gradient - A).norm(), 1e-12 * A.norm());
          volume += geometry.JxW(k, q);
          if (geometry.cells()[k]->reference_cell().is_simplex())
            triangle_volume += geometry.JxW(k, q);
        }
    EXPECT_NEAR(volume, 2., 1e-14);
    EXPECT_NEAR(triangle_volume, 1., 1e-14);
  }
} // namespace

TEST(StressPointGeometry, MixedTrianglesAndQuadrilaterals2D)
{
  check_mixed_geometry(0);
}

TEST(StressPointGeometry, MixedTrianglesAndQuadrilateralsRefined2D)
{
  check_mixed_geometry(2);
}

TEST(StressPointGeometry, ShearedBox2D)
{
  check_geometry<2>(Mesh::sheared);
}

TEST(StressPointGeometry, DistortedBox2D)
{
  check_geometry<2>(Mesh::distorted);
}

TEST(StressPointGeometry, HangingNodes2D)
{
  check_geometry<2>(Mesh::hanging);
}

TEST(StressPointGeometry, ShearedBox3D)
{
  check_geometry<3>(Mesh::sheared);
}

TEST(StressPointGeometry, HangingNodes3D)
{
  check_geometry<3>(Mesh::hanging);
}
