// The elastic operator K applied cell by cell, and a geometric multigrid
// preconditioner for it on the meshes of global coarsening: the operator of
// the matrix-free back end (Method = matrix free), which stores no matrix
// of the fine mesh at all.

#include <deal.II/base/aligned_vector.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/base/vectorization.h>

#include <deal.II/distributed/tria.h>

#include <deal.II/dofs/dof_tools.h>

#include <deal.II/grid/grid_tools.h>

#include <deal.II/lac/diagonal_matrix.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/precondition.h>
#include <deal.II/lac/sparsity_tools.h>
#include <deal.II/lac/trilinos_precondition.h>

#include <deal.II/matrix_free/fe_evaluation.h>
#include <deal.II/matrix_free/matrix_free.h>
#include <deal.II/matrix_free/operators.h>
#include <deal.II/matrix_free/tools.h>

#include <deal.II/multigrid/mg_base.h>
#include <deal.II/multigrid/mg_smoother.h>
#include <deal.II/multigrid/mg_transfer_global_coarsening.h>
#include <deal.II/multigrid/multigrid.h>

#include "back_ends/elasticity_amg.h"
#include "back_ends/matrix_free_elasticity.h"
#include "elastic_operator.h"

#include <cmath>
#include <map>
#include <sstream>
#include <type_traits>
#include <vector>

namespace ViscoContact
{
  namespace
  {
    // @sect4{The dense cell product}
    //
    // y = M x for a cell matrix M stored column by column (see
    // ElasticityOperator::find_shared_cell_matrices()), summed column by
    // column: the n sums of y are independent, so the products pipeline and
    // vectorise. Summed row by row, each sum waits on its previous term, and
    // strict floating-point order keeps the compiler from reordering it
    // (twice the time of an operator application on the Hertz sphere's
    // refined mesh). Debian builds for the x86-64 baseline (SSE2, two
    // doubles at a time); GCC's target_clones adds AVX2 and AVX-512 copies,
    // of which the loader picks the widest the processor has. Every copy
    // runs each sum in the same order, without fused multiply-adds, so on
    // x86-64 the results do not depend on the processor. (hertz_sphere.prm
    // refined twice, 108k dofs, a whole run on the matrix-free back end: 0.48
    // times as long as summed row by row, 0.90 times as long as with SSE2 only;
    // benchmarks/run_paired_timing.py, 3 pairs.)
    template <int n>
    inline void
    dense_cell_product(const double *__restrict column,
                       const double *__restrict x,
                       double *__restrict y)
    {
      for (int i = 0; i < n; ++i)
        y[i] = 0;
      for (int j = 0; j < n; ++j, column += n)
        for (int i = 0; i < n; ++i)
          y[i] += column[i] * x[j];
    }

#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__)
#  define VC_CELL_PRODUCT_CLONES                                \
    __attribute__((target_clones("avx512f", "avx2", "default"), \
                   optimize("fp-contract=off")))
#else
#  define VC_CELL_PRODUCT_CLONES
#endif

    VC_CELL_PRODUCT_CLONES void
    cell_product(const double *column, const double *x, double *y, const int n)
    {
      if (n == 24)
        dense_cell_product<24>(column, x, y); // Q1 in 3D
      else
        dense_cell_product<8>(column, x, y); // Q1 in 2D
    }



    // @sect4{ElasticityOperator}
    //
    // K on one mesh, cell by cell: the symmetric gradient at the Gauss
    // points, the isotropic stress sigma = lambda tr(eps) I + 2 mu eps of
    // the cell's material, and back (FEEvaluation with dim components, as
    // in step-37 for a vector field). lambda and mu are read off each
    // material's elasticity tensor (for plane stress its effective 2D
    // tensor, which is isotropic too), one value per cell and SIMD lane.
    // The diagonal, for the Chebyshev smoother's Jacobi step, comes from
    // MatrixFreeTools. deal.II's base class makes the rows of Dirichlet
    // dofs identity rows.
    template <int dim, typename number>
    class ElasticityOperator
      : public MatrixFreeOperators::
          Base<dim, LinearAlgebra::distributed::Vector<number>>
    {
    public:
      using VectorT    = LinearAlgebra::distributed::Vector<number>;
      using Evaluation = FEEvaluation<dim, 1, 2, dim, number>;

      void
      set_materials(
        const std::function<const SymmetricTensor<4, dim> &(types::material_id)>
          &elasticity)
      {
        const MatrixFree<dim, number> &data = *this->data;
        lambda.resize(data.n_cell_batches());
        mu.resize(data.n_cell_batches());
        for (unsigned int batch = 0; batch < data.n_cell_batches(); ++batch)
          for (unsigned int v = 0; v < VectorizedArray<number>::size(); ++v)
            {
              // Empty lanes of the last batch repeat the first cell.
              const unsigned int lane
                = (v < data.n_active_entries_per_cell_batch(batch) ? v : 0);
              const SymmetricTensor<4, dim> &C = elasticity(
                data.get_cell_iterator(batch, lane)->material_id());
              const double l = C[0][0][1][1], m = C[0][1][0][1];
              AssertThrow(std::abs(C[0][0][0][0] - (l + 2 * m))
                            <= 1e-10 * std::abs(C[0][0][0][0]),
                          ExcMessage("Method = matrix free needs isotropic "
                                     "materials."));
              lambda[batch][v] = l;
              mu[batch][v]     = m;
            }
        find_shared_cell_matrices();
      }

      void
      compute_diagonal() override
      {
        this->inverse_diagonal_entries
          = std::make_shared<DiagonalMatrix<VectorT>>();
        VectorT &inverse_diagonal
          = this->inverse_diagonal_entries->get_vector();
        this->data->initialize_dof_vector(inverse_diagonal);
        MatrixFreeTools::compute_diagonal(*this->data,
                                          inverse_diagonal,
                                          &ElasticityOperator::local_compute,
                                          this);
        this->set_constrained_entries_to_one(inverse_diagonal);
        // A hanging dof has a zero row: 1 keeps the smoother defined there
        // (nothing reads its value).
        for (auto &d : inverse_diagonal)
          d = (std::abs(d) > 0 ? number(1) / d : number(1));
      }

    private:
      void
      apply_add(VectorT &dst, const VectorT &src) const override
      {
        this->data->cell_loop(&ElasticityOperator::local_apply, this, dst, src);
      }

      static constexpr unsigned int dofs_per_cell
        = dim * GeometryInfo<dim>::vertices_per_cell;

      void
      local_apply(const MatrixFree<dim, number>               &data,
                  VectorT                                     &dst,
                  const VectorT                               &src,
                  const std::pair<unsigned int, unsigned int> &cells) const
      {
        Evaluation phi(data);
        for (unsigned int cell = cells.first; cell < cells.second; ++cell)
          {
            phi.reinit(cell);
            phi.read_dof_values(src);
            if (shared_matrix.empty() || shared_matrix[cell] == none)
              local_compute(phi);
            else
              apply_shared_matrix(shared_matrix[cell], phi);
            phi.distribute_local_to_global(dst);
          }
      }

      // @sect4{Cells of the same shape}
      //
      // Debian's deal.II 9.4 is built without SIMD (VectorizedArray has
      // one lane), so the sum factorisation above runs on one cell at a
      // time, and for linear elements its overhead per quadrature point
      // dominates. Cells that are translates of each other (Cartesian or
      // affine cells with the same Jacobian and material: all cells of a
      // refinement level of a box, the children of each cell of a graded
      // coarse mesh) have the same cell matrix; a shape that at least
      // min_cells_per_matrix cells share gets it, computed once from the
      // operator above applied to unit vectors and applied as a dense
      // 24 x 24 (8 x 8 in 2D) product, which the compiler vectorises (at
      // most 4.6 kB per 8 cells, 0.2 kB per dof in 3D). The other cells keep
      // the sum factorisation. Reading and writing the cell's dofs (with the
      // constraints) stays MatrixFree's. The cells of one coarse cell are
      // numbered together, so consecutive cells mostly share a matrix and
      // it stays in cache however many there are (the Hertz sphere's graded
      // block of 8^3 boxes refined 2 times: 512 matrices, 511 changes of
      // matrix along its 32768 cells; a whole run on the matrix-free back
      // end took 0.44 times as long as with the sum factorisation).
      static constexpr unsigned int min_cells_per_matrix = 8;

      void
      find_shared_cell_matrices()
      {
        shared_matrix.clear();
        matrices.clear();
        if (VectorizedArray<number>::size() != 1)
          return; // with SIMD lanes the sum factorisation is fast
        const MatrixFree<dim, number> &data      = *this->data;
        const unsigned int             n_batches = data.n_cell_batches();
        // The shape of every affine cell, and how many cells share it.
        std::map<std::vector<number>, unsigned int> shape_of_key;
        std::vector<unsigned int> shape_of_cell(n_batches, none);
        std::vector<unsigned int> cells_of_shape;
        Evaluation                phi(data);
        for (unsigned int cell = 0; cell < n_batches; ++cell)
          {
            if (data.get_mapping_info().get_cell_type(cell)
                > internal::MatrixFreeFunctions::affine)
              continue;
            phi.reinit(cell);
            // An affine cell's Jacobian and JxW are the same at every
            // quadrature point.
            std::vector<number> key{lambda[cell][0],
                                    mu[cell][0],
                                    phi.JxW(0)[0]};
            const auto          inverse_jacobian = phi.inverse_jacobian(0);
            for (unsigned int d = 0; d < dim; ++d)
              for (unsigned int e = 0; e < dim; ++e)
                key.push_back(inverse_jacobian[d][e][0]);
            const auto entry
              = shape_of_key.emplace(key, shape_of_key.size()).first;
            if (entry->second == cells_of_shape.size())
              cells_of_shape.push_back(0);
            ++cells_of_shape[entry->second];
            shape_of_cell[cell] = entry->second;
          }
        // The matrices of the shapes enough cells share, from the first
        // cell of each.
        std::vector<unsigned int> matrix_of_shape(cells_of_shape.size(), none);
        unsigned int              n_matrices = 0;
        for (unsigned int cell = 0; cell < n_batches; ++cell)
          {
            const unsigned int shape = shape_of_cell[cell];
            if (shape == none || cells_of_shape[shape] < min_cells_per_matrix)
              {
                shape_of_cell[cell] = none;
                continue;
              }
            if (matrix_of_shape[shape] == none)
              {
                matrix_of_shape[shape] = n_matrices++;
                phi.reinit(cell);
                // Column j: the operator applied to the unit vector e_j.
                for (unsigned int j = 0; j < dofs_per_cell; ++j)
                  {
                    for (unsigned int i = 0; i < dofs_per_cell; ++i)
                      phi.begin_dof_values()[i] = number(i == j);
                    local_compute(phi);
                    for (unsigned int i = 0; i < dofs_per_cell; ++i)
                      matrices.push_back(phi.begin_dof_values()[i][0]);
                  }
              }
            shape_of_cell[cell] = matrix_of_shape[shape];
          }
        if (n_matrices > 0)
          shared_matrix = std::move(shape_of_cell);
      }

      void
      apply_shared_matrix(const unsigned int index, Evaluation &phi) const
      {
        static_assert(std::is_same_v<number, double>);
        number x[dofs_per_cell], y[dofs_per_cell];
        for (unsigned int j = 0; j < dofs_per_cell; ++j)
          x[j] = phi.begin_dof_values()[j][0];
        cell_product(&matrices[index * dofs_per_cell * dofs_per_cell],
                     x,
                     y,
                     dofs_per_cell);
        for (unsigned int i = 0; i < dofs_per_cell; ++i)
          phi.begin_dof_values()[i] = y[i];
      }

      void
      local_compute(Evaluation &phi) const
      {
        const unsigned int             batch = phi.get_current_cell_index();
        const VectorizedArray<number> &l     = lambda[batch];
        const VectorizedArray<number>  two_m = number(2) * mu[batch];
        phi.evaluate(EvaluationFlags::gradients);
        for (const unsigned int q : phi.quadrature_point_indices())
          {
            SymmetricTensor<2, dim, VectorizedArray<number>> sigma
              = phi.get_symmetric_gradient(q);
            const VectorizedArray<number> lambda_trace = l * trace(sigma);
            sigma *= two_m;
            for (unsigned int d = 0; d < dim; ++d)
              sigma[d][d] += lambda_trace;
            phi.submit_symmetric_gradient(sigma, q);
          }
        phi.integrate(EvaluationFlags::gradients);
      }

      AlignedVector<VectorizedArray<number>> lambda, mu;
      // Per cell the index of its shared matrix, or none; the matrices
      // column by column (all empty where the mesh has too many distinct
      // cells).
      static constexpr unsigned int none = numbers::invalid_unsigned_int;
      std::vector<unsigned int>     shared_matrix;
      std::vector<number>           matrices;
    };



    // The matrix-free set-up of one mesh: Gauss points of the program's
    // stress quadrature, gradients and JxW only, no threads (the program
    // runs one rank per core).
    template <int dim, typename number>
    std::shared_ptr<const MatrixFree<dim, number>>
    matrix_free_of(const Mapping<dim>              &mapping,
                   const DoFHandler<dim>           &dof_handler,
                   const AffineConstraints<double> &constraints)
    {
      typename MatrixFree<dim, number>::AdditionalData data;
      data.tasks_parallel_scheme
        = MatrixFree<dim, number>::AdditionalData::none;
      data.mapping_update_flags = update_gradients | update_JxW_values;
      auto matrix_free          = std::make_shared<MatrixFree<dim, number>>();
      matrix_free->reinit(mapping,
                          dof_handler,
                          constraints,
                          QGauss<1>(2),
                          data);
      return matrix_free;
    }



    // @sect4{coarsening_sequence}
    //
    // The meshes of the multigrid, coarsest first, the program's mesh last.
    // deal.II's create_geometric_coarsening_sequence() copies the whole
    // mesh and coarsens the copy, level by level; for a mesh refined
    // uniformly from its coarse mesh (a box, a coarse Gmsh file with Global
    // refinements) the same meshes come from the coarse mesh refined 0, 1,
    // ... times, without a second copy of the finest mesh in memory. The
    // coarse cells keep their order, so the cells of the levels match.
    template <int dim>
    std::vector<std::shared_ptr<const Triangulation<dim>>>
    coarsening_sequence(const Triangulation<dim> &fine)
    {
      const auto *distributed
        = dynamic_cast<const parallel::distributed::Triangulation<dim> *>(
          &fine);
      const unsigned int n_levels = fine.n_global_levels();
      const bool         uniform
        = distributed != nullptr
          && fine.n_global_active_cells()
               == static_cast<types::global_cell_index>(fine.n_cells(0))
                    << (dim * (n_levels - 1));
      if (!uniform)
        return MGTransferGlobalCoarseningTools::
          create_geometric_coarsening_sequence(fine);
      std::vector<std::shared_ptr<const Triangulation<dim>>> levels(n_levels);
      const auto coarse = GridTools::get_coarse_mesh_description(fine);
      for (unsigned int level = 0; level + 1 < n_levels; ++level)
        {
          auto mesh
            = std::make_shared<parallel::distributed::Triangulation<dim>>(
              distributed->get_communicator(),
              fine.get_mesh_smoothing());
          for (const types::manifold_id id : fine.get_manifold_ids())
            if (id != numbers::flat_manifold_id)
              mesh->set_manifold(id, fine.get_manifold(id));
          mesh->create_triangulation(std::get<0>(coarse),
                                     std::get<1>(coarse),
                                     std::get<2>(coarse));
          mesh->refine_global(level);
          levels[level] = mesh;
        }
      // The program's mesh, not owned here.
      levels.back() = std::shared_ptr<const Triangulation<dim>>(
        &fine,
        [](const Triangulation<dim> *) {});
      return levels;
    }



    // @sect4{CoarseAMG}
    //
    // The coarse solve of the multigrid: one V-cycle of ML's smoothed
    // aggregation of the coarse mesh's assembled K, in double precision.
    class CoarseAMG : public MGCoarseGridBase<VectorType>
    {
    public:
      CoarseAMG(const TrilinosWrappers::PreconditionAMG &amg)
        : amg(amg)
      {}

      void
      operator()(const unsigned int,
                 VectorType       &dst,
                 const VectorType &src) const override
      {
        amg.vmult(dst, src);
      }

    private:
      const TrilinosWrappers::PreconditionAMG &amg;
    };
  } // namespace



  // @sect4{MatrixFreeElasticity::Implementation}
  //
  // The multigrid: on every mesh of the coarsening sequence (the finest is
  // the program's own) a DoFHandler, its constraints and its operator, the
  // transfer between consecutive meshes, Chebyshev smoothers, and the AMG
  // of the coarsest mesh. The finest level's operator is also the Krylov
  // method's. All in double precision: without SIMD lanes (see
  // ElasticityOperator) single precision saves no time in the cell loops,
  // and a second MatrixFree object of the finest mesh would cost memory.
  template <int dim>
  struct MatrixFreeElasticity<dim>::Implementation
  {
    using LevelVector      = VectorType;
    using LevelOperator    = ElasticityOperator<dim, double>;
    using Smoother         = PreconditionChebyshev<LevelOperator, LevelVector>;
    using GlobalCoarsening = MGTransferGlobalCoarsening<dim, LevelVector>;

    // deal.II's transfer, except that in a constrained cycle the finest
    // level hands down and gets back nothing along the stiff free
    // directions (ConstrainedOperator::remove_stiff): the coarser levels
    // are K's, to which such a direction is free.
    class Transfer : public GlobalCoarsening
    {
    public:
      using GlobalCoarsening::GlobalCoarsening;
      const Implementation *m = nullptr;

      void
      prolongate(const unsigned int to_level,
                 LevelVector       &dst,
                 const LevelVector &src) const override
      {
        dst = 0;
        prolongate_and_add(to_level, dst, src);
      }
      void
      prolongate_and_add(const unsigned int to_level,
                         LevelVector       &dst,
                         const LevelVector &src) const override
      {
        if (!m->stiff_cycle(to_level))
          return GlobalCoarsening::prolongate_and_add(to_level, dst, src);
        m->fine_scratch = 0;
        GlobalCoarsening::prolongate_and_add(to_level, m->fine_scratch, src);
        m->remove_stiff(m->fine_scratch);
        dst += m->fine_scratch;
      }
      void
      restrict_and_add(const unsigned int from_level,
                       LevelVector       &dst,
                       const LevelVector &src) const override
      {
        if (!m->stiff_cycle(from_level))
          return GlobalCoarsening::restrict_and_add(from_level, dst, src);
        m->fine_scratch.copy_locally_owned_data_from(src);
        m->remove_stiff(m->fine_scratch);
        GlobalCoarsening::restrict_and_add(from_level, dst, m->fine_scratch);
      }
    };
    // Whether a transfer from or to this level leaves out the stiff
    // directions, and the removal on a vector of the finest level.
    bool
    stiff_cycle(const unsigned int level) const
    {
      return constrained_cycle && level == level_operators.max_level()
             && constrained.remove_stiff;
    }
    void
    remove_stiff(LevelVector &vector) const
    {
      constrained_src.copy_locally_owned_data_from(vector);
      constrained.remove_stiff(constrained_src);
      vector.copy_locally_owned_data_from(constrained_src);
    }

    Implementation(const ElasticOperatorData<dim> &data,
                   const VectorType               &layout);

    void
    set_up_levels();
    void
    set_up_coarse_solver();
    // K of the program's mesh: the finest level's operator.
    const LevelOperator &
    fine_operator() const
    {
      return level_operators[level_operators.max_level()];
    }
    LevelOperator &
    fine_operator()
    {
      return level_operators[level_operators.max_level()];
    }
    // dst = src at the locally owned constrained dofs.
    void
    copy_constrained_rows(VectorType &dst, const VectorType &src) const;

    // The finest level of a constrained V-cycle (precondition_constrained()):
    // the constrained operator and its Jacobi step on MatrixFree's vectors,
    // through copies into the program's, for deal.II's Chebyshev smoother.
    void
    apply_constrained(LevelVector &dst, const LevelVector &src) const;
    void
    constrained_jacobi(LevelVector &dst, const LevelVector &src) const;
    struct FineOperator : public Subscriptor
    {
      explicit FineOperator(const Implementation *m)
        : m(m)
      {}
      const Implementation *m;
      void
      vmult(LevelVector &dst, const LevelVector &src) const
      {
        m->apply_constrained(dst, src);
      }
    };
    struct FineJacobi
    {
      const Implementation *m;
      void
      vmult(LevelVector &dst, const LevelVector &src) const
      {
        m->constrained_jacobi(dst, src);
      }
    };
    using FineSmoother
      = PreconditionChebyshev<FineOperator, LevelVector, FineJacobi>;

    // What deal.II's Multigrid sees: K on every level, and on the finest
    // the constrained operator while a constrained V-cycle runs.
    class LevelMatrix : public MGMatrixBase<LevelVector>
    {
    public:
      explicit LevelMatrix(const Implementation &m)
        : m(m)
      {}
      void
      vmult(const unsigned int level,
            LevelVector       &dst,
            const LevelVector &src) const override
      {
        if (m.constrained_cycle && level == m.level_operators.max_level())
          m.apply_constrained(dst, src);
        else
          m.level_operators[level].vmult(dst, src);
      }
      void
      vmult_add(const unsigned int level,
                LevelVector       &dst,
                const LevelVector &src) const override
      {
        LevelVector product;
        product.reinit(dst, true);
        vmult(level, product, src);
        dst += product;
      }
      // Multigrid's V-cycle uses vmult() only; K is symmetric.
      void
      Tvmult(const unsigned int level,
             LevelVector       &dst,
             const LevelVector &src) const override
      {
        vmult(level, dst, src);
      }
      void
      Tvmult_add(const unsigned int level,
                 LevelVector       &dst,
                 const LevelVector &src) const override
      {
        vmult_add(level, dst, src);
      }
      unsigned int
      get_minlevel() const override
      {
        return m.level_operators.min_level();
      }
      unsigned int
      get_maxlevel() const override
      {
        return m.level_operators.max_level();
      }

    private:
      const Implementation &m;
    };
    class LevelSmoother : public MGSmootherBase<LevelVector>
    {
    public:
      explicit LevelSmoother(const Implementation &m)
        : m(m)
      {}
      void
      smooth(const unsigned int level,
             LevelVector       &u,
             const LevelVector &rhs) const override
      {
        if (m.constrained_cycle && level == m.level_operators.max_level())
          m.fine_smoother.step(u, rhs);
        else
          m.smoother.smooth(level, u, rhs);
      }
      void
      apply(const unsigned int level,
            LevelVector       &u,
            const LevelVector &rhs) const override
      {
        if (m.constrained_cycle && level == m.level_operators.max_level())
          m.fine_smoother.vmult(u, rhs);
        else
          m.smoother.apply(level, u, rhs);
      }
      void
      clear() override
      {}

    private:
      const Implementation &m;
    };

    const ElasticOperatorData<dim>       data;
    const MPI_Comm                       communicator;
    std::vector<types::global_dof_index> constrained_rows; // local indices
    mutable VectorType                   src_copy, dst_copy;

    // The multigrid, level 0 the coarsest mesh.
    std::vector<std::shared_ptr<const Triangulation<dim>>> triangulations;
    std::vector<std::unique_ptr<DoFHandler<dim>>>          coarse_dof_handlers;
    std::vector<const DoFHandler<dim> *>                   dof_handlers;
    MGLevelObject<AffineConstraints<double>>               level_constraints;
    MGLevelObject<LevelOperator>                           level_operators;
    MGLevelObject<MGTwoLevelTransfer<dim, LevelVector>>    two_level_transfers;
    std::unique_ptr<Transfer>                              transfer;
    TrilinosWrappers::SparseMatrix                         coarse_matrix;
    TrilinosWrappers::PreconditionAMG                      coarse_amg;
    std::unique_ptr<CoarseAMG>                             coarse_solver;
    mg::SmootherRelaxation<Smoother, LevelVector>          smoother;
    // The constrained operator (constrain()), its Jacobi step, work
    // vectors in the program's layout, and the finest level's smoother for
    // it.
    ConstrainedOperator constrained;
    ConstrainedJacobi   constrained_jacobi_step;
    mutable VectorType  constrained_src, constrained_dst;
    // K's diagonal in the program's layout, once at set-up.
    VectorType                              diagonal;
    mutable bool                            constrained_cycle = false;
    mutable LevelVector                     fine_scratch;
    FineOperator                            fine_operator_of_cycle{this};
    FineSmoother                            fine_smoother;
    LevelMatrix                             level_matrix{*this};
    LevelSmoother                           level_smoother{*this};
    std::unique_ptr<Multigrid<LevelVector>> multigrid;
    std::unique_ptr<PreconditionMG<dim, LevelVector, Transfer>> preconditioner;
  };



  // @sect4{MatrixFreeElasticity::Implementation::Implementation}
  //
  // The fine operator, the list of constrained rows (Dirichlet and hanging
  // dofs: identity rows, as the assembled K's are decoupled), then the
  // levels and one V-cycle, in which the Chebyshev smoothers estimate their
  // eigenvalues (a set-up cost, not a solve's).
  template <int dim>
  MatrixFreeElasticity<dim>::Implementation::Implementation(
    const ElasticOperatorData<dim> &data,
    const VectorType               &layout)
    : data(data)
    , communicator(layout.get_mpi_communicator())
  {
    set_up_levels();
    fine_operator().initialize_dof_vector(src_copy);
    fine_operator().initialize_dof_vector(dst_copy);
    const IndexSet &owned = data.dof_handler.locally_owned_dofs();
    for (const types::global_dof_index dof : owned)
      if (data.constraints.is_constrained(dof))
        constrained_rows.push_back(owned.index_within_set(dof));
    set_up_coarse_solver();
    smoother.initialize(level_operators, [&] {
      MGLevelObject<typename Smoother::AdditionalData> smoother_data(
        level_operators.min_level(),
        level_operators.max_level());
      for (unsigned int level = smoother_data.min_level();
           level <= smoother_data.max_level();
           ++level)
        {
          smoother_data[level].smoothing_range     = data.smoothing_range;
          smoother_data[level].degree              = data.smoother_degree;
          smoother_data[level].eig_cg_n_iterations = 10;
          smoother_data[level].preconditioner
            = level_operators[level].get_matrix_diagonal_inverse();
        }
      return smoother_data;
    }());
    // The finest level's smoother of the constrained operator uses K's
    // largest eigenvalue (with the Jacobi step) instead of estimating its
    // own for every set of pieces: removing directions and adding a
    // stiffness that the diagonal includes do not raise it much, and the
    // estimate carries a safety factor of 1.2.
    {
      LevelVector vector;
      fine_operator().initialize_dof_vector(vector);
      typename FineSmoother::AdditionalData fine_data;
      fine_data.degree              = data.smoother_degree;
      fine_data.smoothing_range     = data.smoothing_range;
      fine_data.eig_cg_n_iterations = 0;
      fine_data.max_eigenvalue      = smoother[smoother.max_level()]
                                   .estimate_eigenvalues(vector)
                                   .max_eigenvalue_estimate;
      fine_data.preconditioner = std::make_shared<FineJacobi>(FineJacobi{this});
      fine_smoother.initialize(fine_operator_of_cycle, fine_data);
    }
    for (VectorType *vector : {&constrained_src, &constrained_dst})
      vector->reinit(layout);
    diagonal.reinit(layout, true);
    const VectorType &inverse_diagonal
      = fine_operator().get_matrix_diagonal_inverse()->get_vector();
    for (unsigned int i = 0; i < diagonal.locally_owned_size(); ++i)
      diagonal.local_element(i) = 1. / inverse_diagonal.local_element(i);
    multigrid = std::make_unique<Multigrid<LevelVector>>(level_matrix,
                                                         *coarse_solver,
                                                         *transfer,
                                                         level_smoother,
                                                         level_smoother);
    preconditioner
      = std::make_unique<PreconditionMG<dim, LevelVector, Transfer>>(
        data.dof_handler,
        *multigrid,
        *transfer);
    VectorType x(layout), y(layout);
    x = 1.;
    preconditioner->vmult(y, x);
  }



  // @sect4{MatrixFreeElasticity::Implementation::set_up_levels}
  //
  // Global coarsening (step-75, coarsening_sequence()): the mesh coarsened
  // until only the coarse cells are left, so that an adapted mesh with
  // hanging nodes has its levels too. Each level has its own dofs,
  // constraints (data.make_constraints: the Dirichlet parts and planes of
  // symmetry of the coarser mesh) and operator; the finest is the program's
  // mesh, dofs and constraints.
  template <int dim>
  void
  MatrixFreeElasticity<dim>::Implementation::set_up_levels()
  {
    triangulations = coarsening_sequence(data.dof_handler.get_triangulation());
    const unsigned int finest = triangulations.size() - 1;
    dof_handlers.resize(finest + 1);
    level_constraints.resize(0, finest);
    level_operators.resize(0, finest);
    two_level_transfers.resize(0, finest);
    for (unsigned int level = 0; level <= finest; ++level)
      {
        if (level == finest)
          {
            dof_handlers[level] = &data.dof_handler;
            level_constraints[level].copy_from(data.constraints);
          }
        else
          {
            coarse_dof_handlers.push_back(
              std::make_unique<DoFHandler<dim>>(*triangulations[level]));
            coarse_dof_handlers.back()->distribute_dofs(
              data.dof_handler.get_fe());
            dof_handlers[level] = coarse_dof_handlers.back().get();
            IndexSet relevant;
            DoFTools::extract_locally_relevant_dofs(*dof_handlers[level],
                                                    relevant);
            data.make_constraints(*dof_handlers[level],
                                  relevant,
                                  level_constraints[level]);
          }
        level_operators[level].initialize(
          matrix_free_of<dim, double>(data.mapping,
                                      *dof_handlers[level],
                                      level_constraints[level]));
        level_operators[level].set_materials(data.elasticity);
        level_operators[level].compute_diagonal();
        if (level > 0)
          two_level_transfers[level].reinit(*dof_handlers[level],
                                            *dof_handlers[level - 1],
                                            level_constraints[level],
                                            level_constraints[level - 1]);
      }
    transfer = std::make_unique<Transfer>(
      two_level_transfers,
      [this](const unsigned int level, LevelVector &vector) {
        level_operators[level].initialize_dof_vector(vector);
      });
    transfer->m = this;
    fine_operator().initialize_dof_vector(fine_scratch);
  }



  // @sect4{MatrixFreeElasticity::Implementation::set_up_coarse_solver}
  //
  // The coarsest mesh is the coarse mesh of the scene (the box's
  // subdivisions, or the Gmsh file's cells), which may be large: its K is
  // assembled as the matrix-based back ends do it and preconditioned by
  // ML's smoothed aggregation with the rigid-body modes.
  template <int dim>
  void
  MatrixFreeElasticity<dim>::Implementation::set_up_coarse_solver()
  {
    const DoFHandler<dim>           &dof_handler = *dof_handlers[0];
    const AffineConstraints<double> &constraints = level_constraints[0];
    const IndexSet                  &owned = dof_handler.locally_owned_dofs();
    IndexSet                         relevant;
    DoFTools::extract_locally_relevant_dofs(dof_handler, relevant);
    DynamicSparsityPattern dsp(relevant);
    DoFTools::make_sparsity_pattern(dof_handler, dsp, constraints, false);
    SparsityTools::distribute_sparsity_pattern(dsp,
                                               owned,
                                               communicator,
                                               relevant);
    coarse_matrix.reinit(owned, owned, dsp, communicator);
    assemble_elastic_operator(
      hp::MappingCollection<dim>(data.mapping),
      dof_handler,
      hp::QCollection<dim>(QGauss<dim>(2)),
      ElasticityOfCell<dim>(
        [this](const typename DoFHandler<dim>::active_cell_iterator &cell)
          -> const SymmetricTensor<4, dim> & {
          return data.elasticity(cell->material_id());
        }),
      constraints,
      coarse_matrix);
    const RigidBodyModes modes
      = compute_rigid_body_modes(hp::MappingCollection<dim>(data.mapping),
                                 dof_handler,
                                 coarse_matrix.trilinos_matrix().RowMap(),
                                 communicator);
    build_elasticity_amg(coarse_matrix.trilinos_matrix(),
                         *modes.modes,
                         modes.node_blocks,
                         dim,
                         true,
                         coarse_amg);
    coarse_solver = std::make_unique<CoarseAMG>(coarse_amg);
  }



  template <int dim>
  void
  MatrixFreeElasticity<dim>::Implementation::copy_constrained_rows(
    VectorType       &dst,
    const VectorType &src) const
  {
    for (const types::global_dof_index row : constrained_rows)
      dst.local_element(row) = src.local_element(row);
  }



  // @sect4{The finest level of a constrained V-cycle}
  //
  // The constrained operator A = P (K + sum k v v^T) P + I - P decouples the
  // fixed directions from the free ones, so a smoother started from zero
  // with a right-hand side without fixed components keeps them zero, and
  // the residual restricted to the coarser levels has none either: those
  // levels see K on the span of the free directions (as truncated
  // multigrid does). What the prolongation adds along fixed directions the
  // outer projection removes.
  template <int dim>
  void
  MatrixFreeElasticity<dim>::Implementation::apply_constrained(
    LevelVector       &dst,
    const LevelVector &src) const
  {
    constrained_src.copy_locally_owned_data_from(src);
    constrained.apply(constrained_dst, constrained_src);
    dst.copy_locally_owned_data_from(constrained_dst);
  }



  template <int dim>
  void
  MatrixFreeElasticity<dim>::Implementation::constrained_jacobi(
    LevelVector       &dst,
    const LevelVector &src) const
  {
    constrained_src.copy_locally_owned_data_from(src);
    constrained_jacobi_step.vmult(constrained_dst, constrained_src);
    dst.copy_locally_owned_data_from(constrained_dst);
  }



  template <int dim>
  MatrixFreeElasticity<dim>::MatrixFreeElasticity(
    const ElasticOperatorData<dim> &data,
    const VectorType               &layout)
    : implementation(std::make_unique<Implementation>(data, layout))
  {}



  template <int dim>
  MatrixFreeElasticity<dim>::~MatrixFreeElasticity() = default;



  // @sect4{MatrixFreeElasticity::vmult}
  //
  // The program's vectors have the ghosts of all locally relevant dofs,
  // MatrixFree's only those its cells read: the owned entries are copied
  // in and out (a fraction of the product's cost).
  template <int dim>
  void
  MatrixFreeElasticity<dim>::vmult(VectorType &dst, const VectorType &src) const
  {
    Implementation &m = *implementation;
    m.src_copy.copy_locally_owned_data_from(src);
    m.fine_operator().vmult(m.dst_copy, m.src_copy);
    dst.copy_locally_owned_data_from(m.dst_copy);
    m.copy_constrained_rows(dst, src);
  }



  template <int dim>
  void
  MatrixFreeElasticity<dim>::precondition(VectorType       &dst,
                                          const VectorType &src) const
  {
    implementation->preconditioner->vmult(dst, src);
    implementation->copy_constrained_rows(dst, src);
  }



  // The Jacobi step needs K's diagonal in the program's layout (the owned
  // entries are the same).
  template <int dim>
  void
  MatrixFreeElasticity<dim>::constrain(const ConstrainedOperator &constrained)
  {
    Implementation &m = *implementation;
    m.constrained     = constrained;
    m.constrained_jacobi_step.reinit(diagonal(), constrained);
  }



  template <int dim>
  const VectorType &
  MatrixFreeElasticity<dim>::diagonal() const
  {
    return implementation->diagonal;
  }



  template <int dim>
  void
  MatrixFreeElasticity<dim>::precondition_constrained(
    VectorType       &dst,
    const VectorType &src) const
  {
    const Implementation &m = *implementation;
    m.constrained_cycle     = true;
    m.preconditioner->vmult(dst, src);
    m.constrained_cycle = false;
    m.copy_constrained_rows(dst, src);
  }



  template <int dim>
  std::string
  MatrixFreeElasticity<dim>::description() const
  {
    const Implementation &m = *implementation;
    std::ostringstream    text;
    text << "a geometric multigrid V-cycle on " << m.dof_handlers.size()
         << " meshes by global coarsening (coarsest "
         << m.dof_handlers[0]->n_dofs()
         << " dofs, ML AMG there), Chebyshev smoothing of degree "
         << m.data.smoother_degree;
    return text.str();
  }



  template class MatrixFreeElasticity<2>;
  template class MatrixFreeElasticity<3>;
} // namespace ViscoContact
