// Adaptive meshes during the run (doc/adaptivity.md, "Adaptive meshes"): the
// refinement indicator, the refinement and coarsening of the p4est mesh with
// the state carried over, and the changes of mesh of the initial cycles.
//
// What the state is, and how each part crosses a change of the mesh:
//  - the displacement u_n: a finite element function, interpolated by
//    deal.II's SolutionTransfer (exact where the mesh is refined; the nodal
//    values of the remaining vertices where it is coarsened), then the
//    hanging-node constraints of the new mesh;
//  - the stress points' sigma_n, the history of the next step, the rate
//    G(sigma_n) (adaptive time steps) and the plastic multiplier: cell data,
//    moved by deal.II's CellDataTransfer with the Q1 transfer of
//    stress_point_transfer.h;
//  - the contact set: the nodal contact pressure z_i / w_i is a nodal field
//    like u and is interpolated with it; the new contact nodes get r = u.nu
//    from the new u, z = w p from the interpolated pressure, and the piece that
//    q = p + c r names. The next step's active-set iteration corrects them.
// Everything else (dofs, constraints, K, the stress-point geometry, the
// contact nodes with their weights and c_i, the back end) is set up again by
// setup_on_mesh(), the function run() uses, and the loads of the next step are
// assembled from the carried-over state.

#include <deal.II/base/exceptions.h>
#include <deal.II/base/geometry_info.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/utilities.h>

#include <deal.II/distributed/cell_data_transfer.templates.h>
#include <deal.II/distributed/grid_refinement.h>
#include <deal.II/distributed/solution_transfer.h>
#include <deal.II/distributed/tria.h>

#include <deal.II/grid/cell_id.h>

#include <deal.II/base/mpi_remote_point_evaluation.h>

#include <deal.II/dofs/dof_tools.h>

#include <deal.II/fe/fe_values.h>

#include <deal.II/numerics/error_estimator.h>
#include <deal.II/numerics/vector_tools_evaluate.h>

#include "mesh/mesh.h"

#include "robustness/checkpoint_file.h"
#include "robustness/mpi_tools.h"
#include "stress_point_transfer.h"
#include "mesh/mesh_adaptation.h"
#include "viscoplastic_contact.h"

#include <algorithm>
#include <array>
#include <cstring>
#include <optional>
#include <set>

namespace ViscoContact
{
  namespace
  {
    // The data of one stress point as doubles: sigma (its independent
    // components), the history, the rate G(sigma) of the last update (for the
    // error estimate of adaptive time steps), the plastic multiplier, and in
    // 2D the zz components of the first three (plane strain); a hypercube
    // cell has 2^dim of them. A fixed-size array is plain data, which
    // CellDataTransfer packs by copying (no serialisation, the same size for
    // every cell).
    template <int dim>
    constexpr unsigned int n_point_fields
      = 3 * SymmetricTensor<2, dim>::n_independent_components + 1
        + (dim == 2 ? 3 : 0);
    template <int dim>
    using CellRecord
      = std::array<double,
                   GeometryInfo<dim>::vertices_per_cell * n_point_fields<dim>>;

    template <int dim>
    void
    pack_point(const QuadraturePointHistory<dim> &state, double *out)
    {
      constexpr unsigned int n
        = SymmetricTensor<2, dim>::n_independent_components;
      for (unsigned int i = 0; i < n; ++i)
        {
          out[i]         = state.stress.access_raw_entry(i);
          out[n + i]     = state.history.access_raw_entry(i);
          out[2 * n + i] = state.rate.access_raw_entry(i);
        }
      out[3 * n] = state.internal_variable;
      if constexpr (dim == 2)
        {
          out[3 * n + 1] = state.stress_zz;
          out[3 * n + 2] = state.history_zz;
          out[3 * n + 3] = state.rate_zz;
        }
    }

    template <int dim>
    void
    unpack_point(const double *in, QuadraturePointHistory<dim> &state)
    {
      constexpr unsigned int n
        = SymmetricTensor<2, dim>::n_independent_components;
      for (unsigned int i = 0; i < n; ++i)
        {
          state.stress.access_raw_entry(i)  = in[i];
          state.history.access_raw_entry(i) = in[n + i];
          state.rate.access_raw_entry(i)    = in[2 * n + i];
        }
      // The multiplier is only the starting guess of the next projection; a
      // fitted value below zero (the multiplier is >= 0) starts from zero.
      state.internal_variable = std::max(in[3 * n], 0.);
      if constexpr (dim == 2)
        {
          state.stress_zz  = in[3 * n + 1];
          state.history_zz = in[3 * n + 2];
          state.rate_zz    = in[3 * n + 3];
        }
    }


    // The stress-point data across a change of a p4est mesh: packed per
    // owned cell before (one record of all its stress points), moved by
    // deal.II's CellDataTransfer with the Q1 transfer of
    // stress_point_transfer.h on the refined and the coarsened cells, and
    // unpacked after, into the records of the new owned cells. It remembers
    // the parents of refined cells, for the check in Debug builds.
    template <int dim>
    class StressPointCellTransfer
    {
    public:
      using Cells = std::vector<typename DoFHandler<dim>::active_cell_iterator>;

      StressPointCellTransfer(
        parallel::distributed::Triangulation<dim>      &mesh,
        const Quadrature<dim>                          &stress_quadrature,
        const Cells                                    &cells,
        const std::vector<QuadraturePointHistory<dim>> &records)
        : mesh(mesh)
        , n_q(stress_quadrature.size())
        , q1_transfer(stress_quadrature, n_point_fields<dim>)
        , data_transfer(
            mesh,
            /*transfer_variable_size_data=*/false,
            [this](
              const typename Triangulation<dim>::cell_iterator &parent_cell,
              const Record                                     &parent) {
              parents.insert(parent_cell->id());
              std::vector<Record> children;
              for (const auto &child : q1_transfer.refine(
                     std::vector<double>(parent.begin(), parent.end())))
                children.push_back(to_record(child));
              return children;
            },
            [this](const typename Triangulation<dim>::cell_iterator &,
                   const std::vector<Record> &children) {
              std::vector<std::vector<double>> values;
              for (const Record &child : children)
                values.emplace_back(child.begin(), child.end());
              return to_record(q1_transfer.coarsen(values));
            })
      {
        cell_data.resize(mesh.n_active_cells());
        for (unsigned int k = 0; k < cells.size(); ++k)
          for (unsigned int q = 0; q < n_q; ++q)
            pack_point(records[std::size_t(k) * n_q + q],
                       cell_data[cells[k]->active_cell_index()].data()
                         + q * n_point_fields<dim>);
        data_transfer.prepare_for_coarsening_and_refinement(cell_data);
      }

      // After the mesh has changed and the stress points are set up on it.
      void
      unpack(const Cells                              &cells,
             std::vector<QuadraturePointHistory<dim>> &records)
      {
        cell_data.assign(mesh.n_active_cells(), Record());
        data_transfer.unpack(cell_data);
        for (unsigned int k = 0; k < cells.size(); ++k)
          for (unsigned int q = 0; q < n_q; ++q)
            unpack_point(cell_data[cells[k]->active_cell_index()].data()
                           + q * n_point_fields<dim>,
                         records[std::size_t(k) * n_q + q]);
      }

      const std::set<CellId> &
      refined_parents() const
      {
        return parents;
      }

    private:
      using Record = CellRecord<dim>;

      static Record
      to_record(const std::vector<double> &values)
      {
        Record record;
        std::copy(values.begin(), values.end(), record.begin());
        return record;
      }

      const parallel::distributed::Triangulation<dim> &mesh;
      const unsigned int                               n_q;
      const StressPointTransfer<dim>                   q1_transfer;
      std::set<CellId>                                 parents;
      std::vector<Record>                              cell_data;
      parallel::distributed::CellDataTransfer<dim, dim, std::vector<Record>>
        data_transfer;
    };
  } // namespace



  // @sect4{MeshAdaptation::due}
  //
  // After every Refinement interval-th step, except after the last one (no
  // step would use the new mesh).
  template <int dim>
  bool
  MeshAdaptation<dim>::due(const ViscoplasticContact<dim> &problem)
  {
    return problem.parameters.adaptive_refinement
           && problem.schedule.step_number()
                  % problem.parameters.refinement_interval
                == 0
           && !problem.schedule.is_at_end();
  }



  // @sect4{MeshAdaptation::refinement_indicators}
  //
  // One number per active cell (the entries of owned cells are used): Kelly's
  // estimator of the displacement, raised to the largest Kelly value of the
  // mesh on the cells where the solution is known to be less regular than
  // Kelly's face jumps see (doc/adaptivity.md):
  //  - the contact front: a cell with contact nodes in different states (out
  //    of contact, in the layer, at the rigid limit). There the contact law
  //    changes its branch, and the normal pressure, hence the stress flux
  //    through Gamma_3, has a kink or a jump;
  //  - the boundary of the plastic zone: a cell with a vertex that touches
  //    stress points inside and outside the yield set. There the viscoplastic
  //    rate switches on, and the history H, which is discontinuous from cell
  //    to cell and not seen by the jumps of grad u, changes its behaviour.
  // Kelly's estimator itself sums the jumps of the normal derivative of u over
  // the interior faces: up to the (bounded) elasticity tensor the jumps of the
  // elastic stress flux. Boundary faces contribute nothing: on the loaded and
  // free parts the traction is smooth data, and on Gamma_3 the traction is the
  // contact pressure, which is not known to the estimator (treating Gamma_3 as
  // traction-free would flag every cell in contact).
  template <int dim>
  Vector<float>
  MeshAdaptation<dim>::refinement_indicators(
    const ViscoplasticContact<dim> &problem)
  {
    Vector<float> indicators(problem.triangulation->n_active_cells());
    KellyErrorEstimator<dim>::estimate(
      problem.discretisation.mapping[0],
      problem.dof_handler,
      problem.discretisation.face_quadrature,
      std::map<types::boundary_id, const Function<dim> *>(),
      problem.solution,
      indicators);

    // Vertex fields on the scalar dof layout: whether a vertex touches a
    // plastic stress point, an elastic one, and the contact state + 1 of a
    // contact node (0 elsewhere). The first two are collected from the owned
    // cells with a maximum over the ranks, so that a vertex on a partition
    // boundary sees the stress points of all its cells.
    VectorType touches_plastic(problem.scalar_partitioner),
      touches_elastic(problem.scalar_partitioner),
      contact_state(problem.scalar_partitioner);
    const unsigned int n_q = problem.discretisation.n_stress_points();
    const auto         scalar_cell_of = [&](const auto &cell) {
      return typename DoFHandler<dim>::active_cell_iterator(
        &problem.dof_handler.get_triangulation(),
        cell->level(),
        cell->index(),
        &problem.scalar_dof_handler);
    };
    if (problem.parameters.any_plasticity())
      {
        for (unsigned int k = 0; k < problem.stress_points.cells().size(); ++k)
          {
            const MaterialLaw<dim> &material = problem.materials.of_cell(k);
            bool                    plastic = false, elastic = false;
            for (unsigned int q = 0; q < n_q; ++q)
              (material.is_plastic()
                   && problem.materials.von_mises_stress(
                        k,
                        problem
                          .quadrature_point_history[std::size_t(k) * n_q + q])
                        > material.yield_stress()
                 ? plastic
                 : elastic)
                = true;
            const auto scalar_cell
              = scalar_cell_of(problem.stress_points.cells()[k]);
            for (const unsigned int v : scalar_cell->vertex_indices())
              {
                const auto dof = scalar_cell->vertex_dof_index(v, 0);
                if (plastic)
                  touches_plastic(dof) = 1;
                if (elastic)
                  touches_elastic(dof) = 1;
              }
          }
        touches_plastic.compress(VectorOperation::max);
        touches_elastic.compress(VectorOperation::max);
        touches_plastic.update_ghost_values();
        touches_elastic.update_ghost_values();
      }
    if (problem.contact_enabled)
      {
        for (unsigned int i = 0; i < problem.contact_set.size(); ++i)
          contact_state(problem.contact_set.node(i).scalar_dof)
            = problem.contact_set.status(i) + 1.;
        contact_state.update_ghost_values();
      }

    // The largest Kelly value of the mesh, and the raised cells.
    float largest = 0;
    for (const auto &cell : problem.stress_points.cells())
      largest = std::max(largest, indicators[cell->active_cell_index()]);
    largest = Utilities::MPI::max(largest, problem.mpi_communicator);
    for (const auto &cell : problem.stress_points.cells())
      {
        const auto scalar_cell   = scalar_cell_of(cell);
        bool       zone_boundary = false;
        double     lowest_state = 3, highest_state = 0;
        for (const unsigned int v : scalar_cell->vertex_indices())
          {
            const auto dof = scalar_cell->vertex_dof_index(v, 0);
            zone_boundary
              = zone_boundary
                || (touches_plastic(dof) > 0 && touches_elastic(dof) > 0);
            if (contact_state(dof) > 0)
              {
                lowest_state  = std::min(lowest_state, contact_state(dof));
                highest_state = std::max(highest_state, contact_state(dof));
              }
          }
        // Raised above every unflagged cell, and among themselves still in
        // the order of their Kelly values: the marking takes a fraction of
        // them when Maximum cells does not allow all.
        if (zone_boundary || lowest_state < highest_state)
          indicators[cell->active_cell_index()] += largest > 0 ? largest : 1.f;
      }
    return indicators;
  }



  // @sect4{MeshAdaptation::adapt}
  //
  // Mark, transfer, refine, set up, restore (the order of step-40/step-75 for
  // distributed meshes), then the loads of the next step on the new mesh. If
  // nothing is marked the mesh and the state stay as they are.
  template <int dim>
  void
  MeshAdaptation<dim>::adapt(ViscoplasticContact<dim> &problem,
                             const double              time)
  {
    // The timer's sections: the whole adaptation and, within it, its parts
    // (the set-up on the new mesh has its own sections).
    TimerOutput::Scope t(problem.report.timer(), "Mesh adaptation");
    const auto cells_before = problem.triangulation->n_global_active_cells();
    const auto dofs_before  = problem.dof_handler.n_dofs();
    if (!mark_cells(problem))
      return;
    refine_and_transfer(problem,
                        /*transfer_stress_points=*/true,
                        problem.schedule.current_time());

    // The loads of the next step on the new mesh: the external load (the time
    // loop assembles it only once if it does not depend on t) and the history
    // load of the explicit update from the carried-over history.
    problem.assemble_external_load(time);
    if (problem.parameters.explicit_history_update())
      problem.assemble_history_load();

    if (problem.parameters.verbose)
      problem.pcout << "Mesh adapted at t = " << time << ": " << cells_before
                    << " -> " << problem.triangulation->n_global_active_cells()
                    << " cells, " << dofs_before << " -> "
                    << problem.dof_handler.n_dofs() << " dofs, "
                    << (problem.contact_enabled
                          ? problem.contact_set.n_global_nodes()
                          : 0)
                    << " contact nodes" << std::endl;
  }



  // @sect4{MeshAdaptation::mark_cells}
  //
  // The marking takes a fixed fraction of the cells with the largest and the
  // smallest indicators, with p4est's bisection over all ranks
  // (parallel::distributed::GridRefinement), and refines fewer cells if the
  // mesh would exceed Maximum cells; cells on Maximum refinement level are not
  // refined. Returns whether any cell is marked.
  template <int dim>
  bool
  MeshAdaptation<dim>::mark_cells(ViscoplasticContact<dim> &problem)
  {
    TimerOutput::Scope t(problem.report.timer(),
                         "Mesh adaptation: indicators and marking");
    auto &mesh = dynamic_cast<parallel::distributed::Triangulation<dim> &>(
      *problem.triangulation);
    problem.solution.update_ghost_values();
    const Vector<float> indicators = refinement_indicators(problem);
    // The marking for a refine fraction, and the number of cells it would
    // give: a refined cell adds 2^dim - 1 cells, a coarsened one removes
    // (2^dim - 1) / 2^dim, after prepare_coarsening_and_refinement() has
    // added the refinements p4est's 2:1 balance needs and dropped the
    // coarsenings it cannot do. The fixed-number marking bounds the count
    // before that balance; if the balanced mesh would still exceed Maximum
    // cells, the refine fraction is reduced until it does not (to zero if the
    // mesh is already at the bound: then it is only coarsened).
    const auto cells_before = mesh.n_global_active_cells();
    const auto mark         = [&](const double refine_fraction) {
      for (const auto &cell : mesh.active_cell_iterators())
        {
          cell->clear_refine_flag();
          cell->clear_coarsen_flag();
        }
      parallel::distributed::GridRefinement::refine_and_coarsen_fixed_number(
        mesh,
        indicators,
        refine_fraction,
        problem.parameters.coarsen_fraction,
        problem.parameters.maximum_cells);
      for (const auto &cell : mesh.active_cell_iterators())
        if (cell->is_locally_owned() && cell->refine_flag_set()
            && cell->level()
                 >= int(problem.parameters.maximum_refinement_level))
          cell->clear_refine_flag();
      mesh.prepare_coarsening_and_refinement();
      double marked[2] = {0, 0};
      for (const auto &cell : mesh.active_cell_iterators())
        if (cell->is_locally_owned())
          {
            marked[0] += cell->refine_flag_set();
            marked[1] += cell->coarsen_flag_set();
          }
      for (double &count : marked)
        count = Utilities::MPI::sum(count, problem.mpi_communicator);
      const double children = GeometryInfo<dim>::max_children_per_cell;
      return std::make_pair(marked[0] + marked[1] > 0,
                            cells_before + (children - 1) * marked[0]
                              - (children - 1) / children * marked[1]);
    };
    // A mesh at the bound is only coarsened; otherwise the fraction is scaled
    // by the share of the predicted growth that fits (with a margin, since
    // the balance does not scale exactly), a few times at most.
    double refine_fraction = cells_before < problem.parameters.maximum_cells
                               ? problem.parameters.refine_fraction
                               : 0.;
    auto   outcome         = mark(refine_fraction);
    for (unsigned int attempt = 0;
         outcome.second > problem.parameters.maximum_cells
         && refine_fraction > 0;
         ++attempt)
      {
        refine_fraction
          = attempt < 4
              ? 0.9 * refine_fraction
                  * (double(problem.parameters.maximum_cells) - cells_before)
                  / (outcome.second - cells_before)
              : 0.;
        outcome = mark(refine_fraction);
      }
    return outcome.first;
  }



  // @sect4{MeshAdaptation::refine_and_transfer}
  //
  // The marked mesh is refined and coarsened, everything is set up on it
  // (setup_on_mesh(), which leaves the initial state), and the state is
  // carried over: u and the contact pressure always, the stress-point data
  // and the histories of the contact laws (memory, bonding) if
  // transfer_stress_points (the adaptation during the run; the initial
  // cycles keep the initial history of the first step). The loads are left
  // to the caller.
  template <int dim>
  void
  MeshAdaptation<dim>::refine_and_transfer(ViscoplasticContact<dim> &problem,
                                           const bool   transfer_stress_points,
                                           const double state_time)
  {
    auto &mesh = dynamic_cast<parallel::distributed::Triangulation<dim> &>(
      *problem.triangulation);
    std::optional<TimerOutput::Scope> part;
    part.emplace(problem.report.timer(), "Mesh adaptation: transfer");
    problem.solution.update_ghost_values();

    // The nodal fields: u and the contact pressure z_i / w_i at the x-dof of
    // each contact node (zero elsewhere), both with their ghosts, as
    // SolutionTransfer reads them on the owned cells. Both must be finite
    // element functions of the current mesh, i.e. satisfy its hanging-node
    // constraints (u does): otherwise a hanging vertex next to a contact node
    // would get one value from its fine cells and another from the coarse
    // neighbour when that one is refined. The pressure away from Gamma_3 is
    // never read; on Gamma_3 the constraints change nothing (in 2D a vertex of
    // Gamma_3 is never hanging, in 3D a hanging one is no contact node).
    const VectorType pressure = problem.contact_set.pressure_field(
      problem.solution,
      problem.prescribed.hanging_node_constraints());
    // With a law that has a history (a memory term, adhesion) during the
    // run, its variables as nodal fields too (the initial cycles keep the
    // initial history, as for the stresses).
    const bool transfer_histories
      = transfer_stress_points && problem.contact_enabled;
    std::vector<VectorType> histories;
    if (transfer_histories)
      histories
        = nodal_fields_of(problem.contact_histories.all(),
                          problem.contact_set,
                          problem.solution,
                          problem.prescribed.hanging_node_constraints());
    // With slip weakening, the weakening variables likewise (friction starts
    // again from stick on the new mesh, but its bound keeps its weakening).
    std::vector<VectorType> weakening_state;
    if (transfer_stress_points && problem.contact_enabled
        && problem.contact_set.has_slip_weakening())
      weakening_state.push_back(problem.contact_set.weakening_field(
        problem.solution,
        problem.prescribed.hanging_node_constraints()));
    std::vector<const VectorType *> old_fields{&problem.solution, &pressure};
    for (const auto *fields : {&histories, &weakening_state})
      for (const VectorType &field : *fields)
        old_fields.push_back(&field);
    parallel::distributed::SolutionTransfer<dim, VectorType> nodal_transfer(
      problem.dof_handler);
    nodal_transfer.prepare_for_coarsening_and_refinement(old_fields);

    // The stress-point data, one record per active cell.
    std::optional<StressPointCellTransfer<dim>> stress_point_transfer;
    if (transfer_stress_points)
      stress_point_transfer.emplace(mesh,
                                    problem.discretisation.stress_quadrature[0],
                                    problem.stress_points.cells(),
                                    problem.quadrature_point_history);

    // The new mesh (p4est also rebalances the partition), and everything on
    // it, from the initial state.
    mesh.execute_coarsening_and_refinement();
    part.reset();
    problem.setup_on_mesh();
    part.emplace(problem.report.timer(), "Mesh adaptation: transfer");

    // u on the new mesh, then the constraints of its hanging nodes.
    VectorType new_pressure(problem.solution);
    problem.solution.zero_out_ghost_values();
    new_pressure.zero_out_ghost_values();
    std::vector<VectorType>   new_histories(histories.size(), new_pressure);
    std::vector<VectorType>   new_weakening_state(weakening_state.size(),
                                                new_pressure);
    std::vector<VectorType *> nodal_fields{&problem.solution, &new_pressure};
    for (auto *fields : {&new_histories, &new_weakening_state})
      for (VectorType &field : *fields)
        nodal_fields.push_back(&field);
    nodal_transfer.interpolate(nodal_fields);
    if (transfer_histories)
      restore_from_nodal_fields(problem.contact_histories.all(),
                                problem.contact_set,
                                new_histories);
    for (const VectorType &field : new_weakening_state)
      problem.contact_set.set_weakening_from(field);
    problem.set_dirichlet_values(problem.schedule.current_time());
    problem.prescribed.distribute(problem.solution, problem.constraints);
    problem.solution.update_ghost_values();

    // The stress points of the new owned cells, in the order of
    // stress_points.cells().
    if (transfer_stress_points)
      {
        stress_point_transfer->unpack(problem.stress_points.cells(),
                                      problem.quadrature_point_history);
        check_stress_point_transfer(problem,
                                    stress_point_transfer->refined_parents());
      }

    set_contact_state_from(problem, new_pressure, state_time);
  }



  // @sect4{MeshAdaptation::set_contact_state_from}
  //
  // The contact set after a transfer: (r, z) from u and the pressure, and the
  // piece they name. r = u.nu - s with the gap s at the time of the state:
  // setup_on_mesh() left the gaps of the schedule's current time, which the
  // initial cycles' state (solved for the end of step 1) is not at; with a
  // moving obstacle those gaps would put every node out of contact.
  template <int dim>
  void
  MeshAdaptation<dim>::set_contact_state_from(ViscoplasticContact<dim> &problem,
                                              const VectorType &pressure,
                                              const double      state_time)
  {
    if (!problem.contact_enabled)
      return;
    problem.set_gaps(state_time);
    problem.contact_set.set_state_from(problem.solution,
                                       pressure,
                                       /*with_friction=*/true);
    // Friction starts again from stick on the new mesh, its slip measured
    // from the transferred displacement.
    problem.contact_set.reset_slip(
      problem.contact_set.tangential_displacements(problem.solution),
      std::vector<ContactNodes::Tangential>(problem.contact_set.size(),
                                            {{0, 0}}));
  }



  // @sect4{MeshAdaptation::rebuild_and_transfer}
  //
  // A simplex mesh cannot be refined in place, so the initial cycles build
  // each finer mesh anew (create_distributed_mesh(), with its own partition)
  // and interpolate: u and the contact pressure of the current mesh are
  // evaluated at the support points of the next mesh's dofs on the contact
  // boundary, wherever they lie among the ranks (deal.II's
  // RemotePointEvaluation). What the warm start needs is there: each
  // contact node's (r, z), hence its piece; u is zero elsewhere, a cold
  // initial guess for the first Krylov solve only. (Evaluating u at every
  // dof took 44 s for 526k dofs on 2 ranks, deal.II 9.4's point search
  // being superlinear, against 3.8 s for the whole contact solve.) The
  // meshes of a generated box with the "/" or backslash pattern are nested,
  // the others need not be: a point outside the current mesh (a curved
  // boundary) gets zero, which only makes the warm start a little colder.
  // Like refine_and_transfer(), the history is left initial and the loads
  // to the caller.
  template <int dim>
  void
  MeshAdaptation<dim>::rebuild_and_transfer(ViscoplasticContact<dim> &problem,
                                            const unsigned int coarsenings,
                                            const double       state_time)
  {
    std::optional<TimerOutput::Scope> part;
    part.emplace(problem.report.timer(), "Mesh adaptation: transfer");
    // The back end and the matrices of this mesh go first: the group root
    // of the next mesh holds it whole while it is built.
    problem.contact_solver.reset();
    problem.stiffness_matrix.clear();
    problem.tangent_matrix.clear();
    std::unique_ptr<parallel::DistributedTriangulationBase<dim>> next_mesh
      = create_distributed_mesh<dim>(problem.parameters.coarsened(coarsenings),
                                     problem.mpi_communicator);

    // The support points of the next mesh's owned dofs on the contact
    // boundary, with their vector components, numbered as setup_system()
    // will number them (the same distribute_dofs() on the same mesh).
    std::vector<Point<dim>>              points;
    std::vector<types::global_dof_index> point_dofs;
    std::vector<unsigned int>            point_components;
    {
      DoFHandler<dim> next_dofs(*next_mesh);
      // (Simplex or hypercube meshes only: Cell type = mixed has no
      // initial cycles.)
      const FiniteElement<dim> &fe = problem.discretisation.fe[0];
      next_dofs.distribute_dofs(fe);
      const std::vector<types::boundary_id> contact_ids
        = problem.parameters.all_contact_ids();
      const IndexSet owned = next_dofs.locally_owned_dofs()
                             & DoFTools::extract_boundary_dofs(
                               next_dofs,
                               ComponentMask(),
                               std::set<types::boundary_id>(contact_ids.begin(),
                                                            contact_ids.end()));
      FEValues<dim> support_values(problem.discretisation.mapping[0],
                                   fe,
                                   Quadrature<dim>(
                                     fe.get_unit_support_points()),
                                   update_quadrature_points);
      std::vector<types::global_dof_index> cell_dofs(fe.n_dofs_per_cell());
      std::vector<bool>                    seen(owned.n_elements(), false);
      for (const auto &cell : next_dofs.active_cell_iterators())
        if (cell->is_locally_owned())
          {
            support_values.reinit(cell);
            cell->get_dof_indices(cell_dofs);
            for (unsigned int i = 0; i < cell_dofs.size(); ++i)
              if (owned.is_element(cell_dofs[i])
                  && !seen[owned.index_within_set(cell_dofs[i])])
                {
                  seen[owned.index_within_set(cell_dofs[i])] = true;
                  point_dofs.push_back(cell_dofs[i]);
                  point_components.push_back(
                    fe.system_to_component_index(i).first);
                  points.push_back(support_values.quadrature_point(i));
                }
          }
    }

    // u and the pressure there, from the current mesh.
    problem.solution.update_ghost_values();
    const VectorType pressure = problem.contact_set.pressure_field(
      problem.solution,
      problem.prescribed.hanging_node_constraints());
    std::vector<Tensor<1, dim>> u_values, pressure_values;
    {
      Utilities::MPI::RemotePointEvaluation<dim> evaluation;
      evaluation.reinit(points,
                        *problem.triangulation,
                        problem.discretisation.mapping[0]);
      u_values        = VectorTools::point_values<dim>(evaluation,
                                                problem.dof_handler,
                                                problem.solution);
      pressure_values = VectorTools::point_values<dim>(evaluation,
                                                       problem.dof_handler,
                                                       pressure);
      for (unsigned int p = 0; p < points.size(); ++p)
        if (!evaluation.point_found(p))
          u_values[p] = pressure_values[p] = Tensor<1, dim>();
    }

    // The next mesh replaces the current one; nothing may refer to the old
    // one when it goes.
    problem.dof_handler.reinit(*next_mesh);
    problem.scalar_dof_handler.reinit(*next_mesh);
    problem.triangulation = std::move(next_mesh);
    part.reset();
    problem.setup_on_mesh();
    part.emplace(problem.report.timer(), "Mesh adaptation: transfer");

    // The values at the owned dofs, then the boundary values and the
    // constraints.
    VectorType new_pressure(problem.solution);
    problem.solution = 0;
    new_pressure     = 0;
    for (unsigned int p = 0; p < points.size(); ++p)
      {
        problem.solution[point_dofs[p]] = u_values[p][point_components[p]];
        new_pressure[point_dofs[p]] = pressure_values[p][point_components[p]];
      }
    problem.set_dirichlet_values(problem.schedule.current_time());
    problem.prescribed.distribute(problem.solution, problem.constraints);
    problem.solution.update_ghost_values();
    new_pressure.update_ghost_values();
    set_contact_state_from(problem, new_pressure, state_time);
  }



  // @sect4{MeshAdaptation::check_stress_point_transfer}
  //
  // A check of the whole transfer in Debug builds (nothing in Release): with
  // the implicit update the stored history is sigma_n - E eps(u_n). On a
  // refined cell u is transferred exactly, E eps(u) of a Q1 field is Q1 on an
  // affine cell, and the Q1 transfer of sigma and of the history is exact for
  // it, so sigma - history = E eps(u) at the children's stress points to
  // round-off. A wrong order of the children or of the Gauss points would
  // break it.
  template <int dim>
  void
  MeshAdaptation<dim>::check_stress_point_transfer(
    [[maybe_unused]] const ViscoplasticContact<dim> &problem,
    [[maybe_unused]] const std::set<CellId>         &refined_parents)
  {
#ifdef DEBUG
    const unsigned int n_q = problem.discretisation.n_stress_points();
    if (problem.parameters.implicit_update()
        && problem.parameters.mesh_file.empty())
      for (unsigned int k = 0; k < problem.stress_points.cells().size(); ++k)
        if (problem.stress_points.cells()[k]->level() > 0
            && refined_parents.count(
                 problem.stress_points.cells()[k]->parent()->id())
                 > 0)
          for (unsigned int q = 0; q < n_q; ++q)
            {
              const QuadraturePointHistory<dim> &state
                = problem.quadrature_point_history[std::size_t(k) * n_q + q];
              const SymmetricTensor<2, dim> elastic
                = problem.materials.of_cell(k).elasticity_tensor()
                  * symmetrize(
                    problem.stress_points
                      .displacement_gradient(problem.solution, k, q));
              Assert((state.stress - state.history - elastic).norm()
                       <= 1e-10 * (1 + state.stress.norm()),
                     ExcMessage("The transfer of the stress points does not "
                                "reproduce E eps(u) on a refined cell."));
            }
#endif
  }



  template class MeshAdaptation<2>;
  template class MeshAdaptation<3>;
} // namespace ViscoContact
