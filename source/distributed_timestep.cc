// The time loop of DistributedViscoplasticContact<dim>: the right-hand
// side, the full-space active-set solve with CG around the constant elastic
// operator, the explicit stress update, and parallel output.

#include <deal.II/base/exceptions.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/timer.h>
#include <deal.II/base/utilities.h>

#include <deal.II/fe/fe_values.h>

#include <deal.II/lac/solver_cg.h>
#include <deal.II/lac/solver_control.h>

#include <deal.II/numerics/data_out.h>

#include "checkpoint.h"
#include "time_loop.h"
#include "distributed_viscoplastic_contact.h"


#include <cmath>
#include <functional>
#include <filesystem>
#include <iomanip>
#include <sstream>

namespace ViscoContact
{
  namespace
  {
    using VectorType = TrilinosWrappers::MPI::Vector;

    // v_i -= (nu . v_i) nu at the nodes whose normal displacement is fixed:
    // the orthogonal projection P onto the displacements that respect the
    // constraints u.nu = beta as homogeneous ones.
    template <int dim>
    void
    project_out_normals(const std::vector<DistributedContactNode<dim>> &nodes,
                        const std::vector<bool>                        &fixed,
                        VectorType                                     &v)
    {
      for (unsigned int i = 0; i < nodes.size(); ++i)
        if (fixed[i])
          {
            double normal_part = 0;
            for (unsigned int c = 0; c < dim; ++c)
              normal_part += nodes[i].normal[c] * v[nodes[i].dofs[c]];
            for (unsigned int c = 0; c < dim; ++c)
              v[nodes[i].dofs[c]] -= normal_part * nodes[i].normal[c];
          }
      v.compress(VectorOperation::add);
    }

    // dst += (I - P) src.
    template <int dim>
    void
    add_normal_parts(const std::vector<DistributedContactNode<dim>> &nodes,
                     const std::vector<bool>                        &fixed,
                     const VectorType                               &src,
                     VectorType                                     &dst)
    {
      for (unsigned int i = 0; i < nodes.size(); ++i)
        if (fixed[i])
          {
            double normal_part = 0;
            for (unsigned int c = 0; c < dim; ++c)
              normal_part += nodes[i].normal[c] * src[nodes[i].dofs[c]];
            for (unsigned int c = 0; c < dim; ++c)
              dst[nodes[i].dofs[c]] += normal_part * nodes[i].normal[c];
          }
      dst.compress(VectorOperation::add);
    }

    // v -> P inner(P v) + (I - P) v. With inner = K + sum_i k_i nu_i nu_i^T
    // (k_i = w_i s_i at the nodes on sloped pieces of slope s_i) this is
    // the operator of one active-set iteration; with inner = M^{-1}, the
    // preconditioner of K, its preconditioner. Both are symmetric, and
    // positive definite when inner is, so CG applies.
    template <int dim>
    class ProjectedOperator
    {
    public:
      using Inner = std::function<void(VectorType &, const VectorType &)>;

      ProjectedOperator(const Inner                                    &inner,
                        const std::vector<DistributedContactNode<dim>> &nodes,
                        const std::vector<bool>                        &fixed)
        : inner(inner)
        , nodes(nodes)
        , fixed(fixed)
      {}

      void
      vmult(VectorType &dst, const VectorType &src) const
      {
        projected.reinit(src, /*omit_zeroing_entries=*/true);
        projected = src;
        project_out_normals(nodes, fixed, projected);
        inner(dst, projected);
        project_out_normals(nodes, fixed, dst);
        add_normal_parts(nodes, fixed, src, dst);
      }

    private:
      const Inner                                    &inner;
      const std::vector<DistributedContactNode<dim>> &nodes;
      const std::vector<bool>                        &fixed;
      mutable VectorType                              projected;
    };
  } // namespace



  // @sect4{DistributedViscoplasticContact::run}
  //
  // The time loop of the serial program, with the same recovery from failed
  // solves, checkpoints and resume. Before it, one solve of the elastic
  // problem without contact is timed: the benchmark's figure of merit is
  // the time per step in units of that solve.
  template <int dim>
  void
  DistributedViscoplasticContact<dim>::run()
  {
    make_grid();
    setup_system();
    setup_preconditioner();
    setup_contact();
    setup_stress_points();

    std::vector<double> times
      = time_levels(parameters.end_time, parameters.time_step);
    unsigned int first_step = 1;
    if (parameters.resume)
      first_step = resume_from_checkpoint(times) + 1;
    prepare_output_directory();
    n_time_steps = times.size() - 1;

    const unsigned int n_ranks
      = Utilities::MPI::n_mpi_processes(mpi_communicator);
    pcout << "Mesh: " << triangulation->n_global_active_cells() << ' '
          << reference_cell.to_string() << " cells, " << dof_handler.n_dofs()
          << " displacement dofs, " << n_global_contact_nodes
          << " contact nodes, " << n_time_steps << " time steps\n"
          << "Model: " << (parameters.plasticity ? "viscoplastic" : "elastic")
          << ", contact " << (contact_enabled ? "on" : "off") << '\n'
          << "Distributed: " << n_ranks << " MPI rank(s), "
          << (reference_cell.is_simplex() ? "fully distributed" : "p4est")
          << " mesh, CG with the "
          << (parameters.preconditioner == "amg" ? "ML AMG" : "MUMPS")
          << " preconditioner of K\n";
    if (parameters.plasticity)
      pcout << "Explicit history update: stable for k < 4 lambda / "
               "lambda_max(E) = "
            << 4 * material.viscosity() / material.largest_elastic_eigenvalue()
            << " s; k = " << parameters.time_step << " s\n";

    const double reference_solve_time = time_reference_elastic_solve();

    if (parameters.write_vtu && first_step == 1)
      output_results(0, 0.);
    Timer loop_timer;
    for (unsigned int n = first_step; n < times.size(); ++n)
      {
        Timer                                step_timer;
        const ContactActiveSetSolver::Result result
          = solve_step_with_recovery(n, times);
        update_stresses(n + 1 < times.size() ? times[n + 1] - times[n] : 0.);
        time_loop_compute_time += step_timer.wall_time();
        n_time_steps = times.size() - 1;

        const auto   states      = count_contact_states();
        const double total_force = total_contact_force();
        const double wall_time   = loop_time_offset + loop_timer.wall_time();
        if (Utilities::MPI::this_mpi_process(mpi_communicator) == 0)
          {
            time_series << n << ',' << times[n] << ',' << result.iterations()
                        << ',' << states[0] << ',' << states[1] << ','
                        << states[2] << ',' << total_force << ','
                        << max_von_mises << ',' << wall_time << '\n';
            time_series.flush();
          }
        if (parameters.verbose)
          print_step_line(pcout,
                          n,
                          times[n],
                          result.iterations(),
                          states,
                          total_force);
        if (parameters.write_vtu
            && (n % parameters.interval == 0 || n + 1 == times.size()))
          output_results(n, times[n]);
        if (parameters.checkpoint_interval > 0
            && n % parameters.checkpoint_interval == 0)
          write_checkpoint(n, times, wall_time);
        if (n == parameters.stop_after_step)
          {
            pcout << "Stopped after step " << n
                  << " as requested (Stop after step, subsection "
                     "<Checkpoint>).\n";
            break;
          }
      }
    print_run_summary(reference_solve_time);
  }



  // @sect4{DistributedViscoplasticContact::solve_step_with_recovery}
  //
  // As in the serial program: a failed solve restores the state at the
  // start of the step, and the step is either cut in half (rescaling the
  // explicit history increment) or the last accepted state is written to
  // failed_step_NNNN.pvtu and the run stops with a report. Every rank takes
  // the same decision: all failure criteria are reduced over the ranks.
  template <int dim>
  ContactActiveSetSolver::Result
  DistributedViscoplasticContact<dim>::solve_step_with_recovery(
    const unsigned int   n,
    std::vector<double> &times)
  {
    const VectorType                               start_solution = solution;
    const std::vector<DistributedContactNode<dim>> start_nodes = contact_nodes;
    while (true)
      {
        const double k = times[n] - times[n - 1];
        {
          TimerOutput::Scope t(computing_timer, "Assemble right-hand side");
          if (loads_depend_on_time || !external_load_assembled)
            assemble_external_load(times[n]);
          external_load_assembled = true;
          system_rhs              = external_load;
          if (parameters.plasticity)
            system_rhs += history_load;
        }
        const ContactActiveSetSolver::Result result = solve_time_step();
        if (result.converged)
          return result;

        const std::array<unsigned int, 3> states = count_contact_states();
        solution                                 = start_solution;
        ghosted_solution                         = solution;
        contact_nodes                            = start_nodes;
        if (cut_failed_step(parameters, pcout, n, times, result.failure))
          {
            if (parameters.plasticity)
              rescale_history_increment(k, times[n] - times[n - 1]);
            continue;
          }

        const std::string state_file = failed_state_file(n, "pvtu");
        output_results(n, times[n - 1], "failed_step");
        AssertThrow(false,
                    ExcMessage(failure_report(parameters,
                                              n,
                                              times[n],
                                              k,
                                              result,
                                              states,
                                              state_file)));
      }
  }



  // @sect4{DistributedViscoplasticContact::time_reference_elastic_solve}
  //
  // One CG solve of K u = f_0 (no contact, no history) with the run's
  // preconditioner: the unit of the benchmark's figure of merit, measured
  // in the same run. Its result is discarded.
  template <int dim>
  double
  DistributedViscoplasticContact<dim>::time_reference_elastic_solve()
  {
    assemble_external_load(0.);
    VectorType reference(locally_owned_dofs, mpi_communicator);
    const std::vector<DistributedContactNode<dim>> no_nodes;
    const std::vector<bool>                        no_flags;
    const typename ProjectedOperator<dim>::Inner   apply_M
      = [this](VectorType &dst, const VectorType &src) {
          apply_preconditioner(dst, src);
        };
    SolverControl        control(10000,
                          parameters.relative_tolerance
                            * std::max(external_load.l2_norm(), 1e-300));
    SolverCG<VectorType> cg(control);
    Timer                timer;
    cg.solve(stiffness_matrix,
             reference,
             external_load,
             ProjectedOperator<dim>(apply_M, no_nodes, no_flags));
    const double time       = timer.wall_time();
    external_load_assembled = false; // the loads of t = 0, not of step 1
    pcout << "Reference: one linear elastic solve (CG, " << control.last_step()
          << " iterations) takes " << std::setprecision(4) << time << " s\n";
    return Utilities::MPI::max(time, mpi_communicator);
  }



  // @sect4{DistributedViscoplasticContact::assemble_external_load}
  //
  // (f_0, v) + (f_2, v)_Gamma2 on the locally owned cells.
  template <int dim>
  void
  DistributedViscoplasticContact<dim>::assemble_external_load(const double time)
  {
    external_load = 0;
    body_force.set_time(time);
    surface_traction.set_time(time);
    const unsigned int                   dofs_per_cell = fe->n_dofs_per_cell();
    Vector<double>                       cell_rhs(dofs_per_cell);
    std::vector<types::global_dof_index> local_dof_indices(dofs_per_cell);
    Vector<double>                       load_value(dim);
    FEValues<dim>                        fe_values(*mapping,
                            *fe,
                            load_quadrature,
                            update_values | update_quadrature_points
                              | update_JxW_values);
    FEFaceValues<dim>                    fe_face_values(*mapping,
                                     *fe,
                                     face_quadrature,
                                     update_values | update_quadrature_points
                                       | update_JxW_values);

    for (const auto &cell : dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          cell_rhs = 0;
          fe_values.reinit(cell);
          for (const unsigned int q : fe_values.quadrature_point_indices())
            {
              body_force.vector_value(fe_values.quadrature_point(q),
                                      load_value);
              for (unsigned int i = 0; i < dofs_per_cell; ++i)
                cell_rhs(i)
                  += load_value(fe->system_to_component_index(i).first)
                     * fe_values.shape_value(i, q) * fe_values.JxW(q);
            }
          for (const unsigned int f : cell->face_indices())
            if (cell->face(f)->at_boundary()
                && std::find(parameters.loaded_ids.begin(),
                             parameters.loaded_ids.end(),
                             cell->face(f)->boundary_id())
                     != parameters.loaded_ids.end())
              {
                fe_face_values.reinit(cell, f);
                for (const unsigned int q :
                     fe_face_values.quadrature_point_indices())
                  {
                    surface_traction.vector_value(
                      fe_face_values.quadrature_point(q),
                      load_value);
                    for (unsigned int i = 0; i < dofs_per_cell; ++i)
                      cell_rhs(i)
                        += load_value(fe->system_to_component_index(i).first)
                           * fe_face_values.shape_value(i, q)
                           * fe_face_values.JxW(q);
                  }
              }
          cell->get_dof_indices(local_dof_indices);
          constraints.distribute_local_to_global(cell_rhs,
                                                 local_dof_indices,
                                                 external_load);
        }
    external_load.compress(VectorOperation::add);
  }



  // @sect4{DistributedViscoplasticContact::apply_preconditioner}
  //
  // dst = M^{-1} src with the preconditioner of K built at set-up: one AMG
  // V-cycle, or the solve with the MUMPS factors.
  template <int dim>
  void
  DistributedViscoplasticContact<dim>::apply_preconditioner(
    VectorType       &dst,
    const VectorType &src) const
  {
    if (direct_solver)
      direct_solver->solve(dst, src);
    else
      amg_preconditioner.vmult(dst, src);
  }



  // @sect4{DistributedViscoplasticContact::solve_step_problem}
  //
  // For the current pieces: nodes on sloped pieces (slope s, intercept o)
  // carry the force w (o + s u.nu), nodes on vertical pieces at r = beta
  // have u.nu = beta. With u = u_0 + y, u_0 = beta nu at the fixed nodes,
  // y solves A y = P (b - sum w o nu - K u_0), started from P u of the
  // previous iteration (warm start). Returns the CG iterations.
  template <int dim>
  unsigned int
  DistributedViscoplasticContact<dim>::solve_step_problem(
    const VectorType &rhs,
    VectorType       &displacement)
  {
    const unsigned int  m = contact_nodes.size();
    std::vector<bool>   fixed(m, false);
    std::vector<double> normal_stiffness(m, 0.);
    VectorType          constrained_part(locally_owned_dofs, mpi_communicator);
    VectorType          step_rhs(rhs);
    for (unsigned int i = 0; i < m; ++i)
      {
        const DistributedContactNode<dim> &node = contact_nodes[i];
        const ContactLawPiece &piece = contact_law->piece(node.piece);
        for (unsigned int c = 0; c < dim; ++c)
          if (piece.vertical)
            constrained_part[node.dofs[c]] = piece.r_lower * node.normal[c];
          else
            step_rhs[node.dofs[c]]
              -= node.weight * piece.intercept * node.normal[c];
        fixed[i]            = piece.vertical;
        normal_stiffness[i] = (piece.vertical ? 0. : node.weight * piece.slope);
      }
    constrained_part.compress(VectorOperation::insert);
    step_rhs.compress(VectorOperation::add);
    VectorType K_u0(locally_owned_dofs, mpi_communicator);
    stiffness_matrix.vmult(K_u0, constrained_part);
    step_rhs -= K_u0;
    project_out_normals(contact_nodes, fixed, step_rhs);
    project_out_normals(contact_nodes, fixed, displacement);

    const typename ProjectedOperator<dim>::Inner apply_K
      = [&](VectorType &dst, const VectorType &src) {
          stiffness_matrix.vmult(dst, src);
          for (unsigned int i = 0; i < m; ++i)
            if (normal_stiffness[i] != 0)
              {
                const DistributedContactNode<dim> &node = contact_nodes[i];
                double                             normal_part = 0;
                for (unsigned int c = 0; c < dim; ++c)
                  normal_part += node.normal[c] * src[node.dofs[c]];
                for (unsigned int c = 0; c < dim; ++c)
                  dst[node.dofs[c]]
                    += normal_stiffness[i] * normal_part * node.normal[c];
              }
          dst.compress(VectorOperation::add);
        };
    const typename ProjectedOperator<dim>::Inner apply_M
      = [this](VectorType &dst, const VectorType &src) {
          apply_preconditioner(dst, src);
        };
    SolverControl        control(10000,
                          parameters.relative_tolerance
                            * std::max(rhs.l2_norm(), 1e-300));
    SolverCG<VectorType> cg(control);
    try
      {
        cg.solve(ProjectedOperator<dim>(apply_K, contact_nodes, fixed),
                 displacement,
                 step_rhs,
                 ProjectedOperator<dim>(apply_M, contact_nodes, fixed));
      }
    catch (const SolverControl::NoConvergence &failure)
      {
        std::ostringstream reason;
        reason << "CG did not converge in " << failure.last_step
               << " iterations (residual " << failure.last_residual
               << "): the step problem on the current pieces is not positive "
                  "definite (the contact law softens more than the body can "
                  "carry, model.md, section 4), or <Relative tolerance> = "
               << parameters.relative_tolerance
               << " in subsection <Linear solver> is below what the "
                  "arithmetic reaches.";
        cg_failure = reason.str();
      }
    displacement += constrained_part;
    total_cg_iterations += control.last_step();
    ++n_cg_solves;
    return control.last_step();
  }



  // @sect4{DistributedViscoplasticContact::solve_time_step}
  //
  // The primal-dual active set method of model.md, section 5, in the full
  // space: solve on the current pieces, read the nodal normal forces off
  // the residual (z_i = nu . (b - K u)_i at fixed nodes, w (o + s r) on
  // sloped ones), move every node to the piece q = z/w + c r names, and
  // stop when no node moves on any rank. The criterion is the one of the
  // condensed solver (ContactLaw::next_piece), so both methods have the
  // same fixed points.
  template <int dim>
  ContactActiveSetSolver::Result
  DistributedViscoplasticContact<dim>::solve_time_step()
  {
    TimerOutput::Scope             t(computing_timer, "Solve: active set + CG");
    ContactActiveSetSolver::Result result{false, {}, 0, {}};
    cg_failure.clear();
    if (!contact_enabled)
      {
        solve_step_problem(system_rhs, solution);
        result.converged = cg_failure.empty();
      }
    for (unsigned int iteration = 0;
         contact_enabled && iteration < parameters.max_iterations;
         ++iteration)
      {
        const unsigned int cg_iterations
          = solve_step_problem(system_rhs, solution);
        if (!cg_failure.empty())
          break;

        VectorType residual(locally_owned_dofs, mpi_communicator);
        stiffness_matrix.vmult(residual, solution);
        residual.sadd(-1., 1., system_rhs);

        unsigned int changed = 0, rigid = 0;
        for (DistributedContactNode<dim> &node : contact_nodes)
          {
            const ContactLawPiece &piece = contact_law->piece(node.piece);
            node.r                       = 0;
            double normal_residual       = 0;
            for (unsigned int c = 0; c < dim; ++c)
              {
                node.r += node.normal[c] * solution[node.dofs[c]];
                normal_residual += node.normal[c] * residual[node.dofs[c]];
              }
            node.z
              = (piece.vertical
                   ? normal_residual
                   : node.weight * (piece.intercept + piece.slope * node.r));
            const unsigned int next
              = contact_law->next_piece(node.piece,
                                        node.z / node.weight + node.c * node.r,
                                        node.c);
            if (next != node.piece)
              {
                node.piece = next;
                ++changed;
              }
            if (contact_law->piece(node.piece).rigid)
              ++rigid;
          }
        changed = Utilities::MPI::sum(changed, mpi_communicator);
        rigid   = Utilities::MPI::sum(rigid, mpi_communicator);
        result.history.push_back({changed, rigid, double(cg_iterations)});
        if (changed == 0)
          {
            result.converged = true;
            break;
          }
      }
    total_active_set_iterations += result.iterations();

    if (!cg_failure.empty())
      result.failure = cg_failure;
    else if (!result.converged)
      result.failure = "The active-set iteration did not converge within "
                       + std::to_string(result.iterations())
                       + " iterations (Maximum iterations = "
                       + std::to_string(parameters.max_iterations)
                       + " in subsection <Active set solver>; the linear "
                         "residual column of the history is the number of CG "
                         "iterations).";
    if (!result.failure.empty())
      {
        result.converged = false;
        return result;
      }

    constraints.distribute(solution);
    ghosted_solution = solution;
    if (!std::isfinite(solution.l2_norm()))
      {
        result.converged = false;
        result.failure   = "The displacement is not finite (NaN or Inf).";
      }
    return result;
  }



  // @sect4{DistributedViscoplasticContact::update_stresses}
  //
  // sigma_n = E eps(u_n) + H_n at the stress points of the locally owned
  // cells, the explicit history update H_{n+1} = H_n + k G(sigma_n), and in
  // the same loop the history load -(H_{n+1}, eps(v)) of the next step.
  template <int dim>
  void
  DistributedViscoplasticContact<dim>::update_stresses(
    const double next_time_step)
  {
    TimerOutput::Scope t(computing_timer, "Stress update");
    const bool update_history = parameters.plasticity && next_time_step > 0;
    const FEValuesExtractors::Vector     displacements(0);
    FEValues<dim>                        fe_values(*mapping,
                            *fe,
                            stress_quadrature,
                            update_gradients | update_JxW_values);
    const unsigned int                   dofs_per_cell = fe->n_dofs_per_cell();
    const unsigned int                   n_q = stress_quadrature.size();
    std::vector<SymmetricTensor<2, dim>> strains(n_q);
    Vector<double>                       cell_rhs(dofs_per_cell);
    std::vector<types::global_dof_index> local_dof_indices(dofs_per_cell);
    const SymmetricTensor<4, dim>       &E = material.elasticity_tensor();

    if (update_history)
      history_load = 0;
    double local_max_von_mises = 0;
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          fe_values.reinit(cell);
          fe_values[displacements]
            .get_function_symmetric_gradients(ghosted_solution, strains);
          cell_rhs = 0;
          for (unsigned int q = 0; q < n_q; ++q)
            {
              QuadraturePointHistory<dim> &state = quadrature_point_history
                [std::size_t(cell->active_cell_index()) * n_q + q];
              state.stress = E * strains[q] + state.history;
              local_max_von_mises
                = std::max(local_max_von_mises,
                           material.equivalent_stress(state.stress));
              if (update_history)
                {
                  state.history
                    += next_time_step
                       * material.viscoplastic_rate(state.stress,
                                                    &state.plastic_multiplier);
                  for (unsigned int i = 0; i < dofs_per_cell; ++i)
                    cell_rhs(i)
                      -= scalar_product(
                           state.history,
                           fe_values[displacements].symmetric_gradient(i, q))
                         * fe_values.JxW(q);
                }
            }
          if (update_history)
            {
              cell->get_dof_indices(local_dof_indices);
              constraints.distribute_local_to_global(cell_rhs,
                                                     local_dof_indices,
                                                     history_load);
            }
        }
    if (update_history)
      history_load.compress(VectorOperation::add);
    max_von_mises = Utilities::MPI::max(local_max_von_mises, mpi_communicator);

    AssertThrow(std::isfinite(max_von_mises),
                ExcMessage(
                  "The stresses are no longer finite (NaN or Inf). With the "
                  "explicit history update this means the time step is too "
                  "large: it is stable for k < 4 lambda / lambda_max(E) = "
                  + std::to_string(4 * material.viscosity()
                                   / material.largest_elastic_eigenvalue())
                  + " s (model.md, section 3); <Time step> in subsection "
                    "<Time> is "
                  + std::to_string(parameters.time_step) + " s."));
  }



  // @sect4{DistributedViscoplasticContact::assemble_history_load}
  //
  // -(H, eps(v)) from the stored history alone: after a cut step rescaled
  // the history increment, and after a resume (the time loop otherwise
  // assembles it inside update_stresses()).
  template <int dim>
  void
  DistributedViscoplasticContact<dim>::assemble_history_load()
  {
    const FEValuesExtractors::Vector     displacements(0);
    FEValues<dim>                        fe_values(*mapping,
                            *fe,
                            stress_quadrature,
                            update_gradients | update_JxW_values);
    const unsigned int                   dofs_per_cell = fe->n_dofs_per_cell();
    const unsigned int                   n_q = stress_quadrature.size();
    Vector<double>                       cell_rhs(dofs_per_cell);
    std::vector<types::global_dof_index> local_dof_indices(dofs_per_cell);
    history_load = 0;
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          fe_values.reinit(cell);
          cell_rhs = 0;
          for (unsigned int q = 0; q < n_q; ++q)
            {
              const SymmetricTensor<2, dim> &H
                = quadrature_point_history
                    [std::size_t(cell->active_cell_index()) * n_q + q]
                      .history;
              for (unsigned int i = 0; i < dofs_per_cell; ++i)
                cell_rhs(i)
                  -= scalar_product(
                       H,
                       fe_values[displacements].symmetric_gradient(i, q))
                     * fe_values.JxW(q);
            }
          cell->get_dof_indices(local_dof_indices);
          constraints.distribute_local_to_global(cell_rhs,
                                                 local_dof_indices,
                                                 history_load);
        }
    history_load.compress(VectorOperation::add);
  }



  // @sect4{DistributedViscoplasticContact::rescale_history_increment}
  //
  // H_n += (k' - k) G(sigma_{n-1}) at the stress points of the locally
  // owned cells, for a step cut from k to k'.
  template <int dim>
  void
  DistributedViscoplasticContact<dim>::rescale_history_increment(
    const double old_step,
    const double new_step)
  {
    const unsigned int n_q = stress_quadrature.size();
    for (const auto &cell : triangulation->active_cell_iterators())
      if (cell->is_locally_owned())
        for (unsigned int q = 0; q < n_q; ++q)
          {
            QuadraturePointHistory<dim> &state
              = quadrature_point_history[std::size_t(cell->active_cell_index())
                                           * n_q
                                         + q];
            state.history
              += (new_step - old_step)
                 * material.viscoplastic_rate(state.stress,
                                              &state.plastic_multiplier);
          }
    assemble_history_load();
  }



  // @sect4{Contact state}
  //
  // Counts over all ranks: at the rigid limit, in normal-compliance contact
  // (penetrating the layer or pressed by it), out of contact.
  template <int dim>
  std::array<unsigned int, 3>
  DistributedViscoplasticContact<dim>::count_contact_states() const
  {
    std::array<unsigned int, 3> counts = {{0, 0, 0}};
    for (const DistributedContactNode<dim> &node : contact_nodes)
      {
        if (contact_enabled && contact_law->piece(node.piece).rigid)
          ++counts[0];
        else if (contact_enabled && (node.r > 0 || node.z > 0))
          ++counts[1];
        else
          ++counts[2];
      }
    for (unsigned int &count : counts)
      count = Utilities::MPI::sum(count, mpi_communicator);
    return counts;
  }



  template <int dim>
  double
  DistributedViscoplasticContact<dim>::total_contact_force() const
  {
    double sum = 0;
    for (const DistributedContactNode<dim> &node : contact_nodes)
      sum += node.z;
    return Utilities::MPI::sum(sum, mpi_communicator);
  }



  // @sect4{DistributedViscoplasticContact::prepare_output_directory}
  //
  // Called once the input is known to be good. Rank 0 creates the
  // directory, writes the parsed parameters and opens the time series; the
  // other ranks learn whether that worked, so that all stop together.
  template <int dim>
  void
  DistributedViscoplasticContact<dim>::prepare_output_directory()
  {
    const std::filesystem::path directory(parameters.directory);
    std::string                 problem;
    if (Utilities::MPI::this_mpi_process(mpi_communicator) == 0)
      {
        std::error_code error;
        std::filesystem::create_directories(directory, error);
        if (error)
          problem = "it cannot be created (" + error.message() + ")";
        else
          {
            std::ofstream prm_copy(directory / "parameters.prm");
            prm_copy << parameters.parsed_parameters;
            // A resumed run continues the series of the run it resumes.
            time_series.open(directory / "time_series.csv",
                             parameters.resume ? std::ios::app
                                               : std::ios::trunc);
            if (!prm_copy || !time_series)
              problem = "it is not writable";
            if (!parameters.resume)
              time_series
                << "step,time,active_set_iterations,unilateral_nodes,"
                   "compliance_nodes,no_contact_nodes,total_contact_force,"
                   "max_von_mises,wall_time\n";
            time_series << std::setprecision(10);
          }
      }
    problem = Utilities::MPI::broadcast(mpi_communicator, problem, 0);
    AssertThrow(problem.empty(),
                ExcMessage("Invalid parameter <Output directory> in subsection "
                           "<Output>: value <"
                           + parameters.directory + ">; " + problem + "."));
  }



  // @sect4{DistributedViscoplasticContact::output_results}
  //
  // Each rank writes its cells into a group file (at most 8 files per step,
  // whatever the number of ranks, through MPI I/O), rank 0 the .pvtu record
  // and the .pvd time record. Cell data: the von Mises stress and the
  // stress averaged over the cell's stress points, and the owning rank.
  template <int dim>
  void
  DistributedViscoplasticContact<dim>::output_results(const unsigned int step,
                                                      const double       time,
                                                      const std::string &stem)
  {
    TimerOutput::Scope t(computing_timer, "Output");
    DataOut<dim>       data_out;
    data_out.attach_dof_handler(dof_handler);
    const std::vector<DataComponentInterpretation::DataComponentInterpretation>
      interpretation(dim,
                     DataComponentInterpretation::component_is_part_of_vector);
    data_out.add_data_vector(ghosted_solution,
                             std::vector<std::string>(dim, "displacement"),
                             DataOut<dim>::type_dof_data,
                             interpretation);

    const unsigned int         n_q = stress_quadrature.size();
    Vector<float>              von_mises(triangulation->n_active_cells());
    Vector<float>              subdomain(triangulation->n_active_cells());
    std::vector<Vector<float>> stress(dim * (dim + 1) / 2,
                                      Vector<float>(
                                        triangulation->n_active_cells()));
    for (const auto &cell : triangulation->active_cell_iterators())
      if (cell->is_locally_owned())
        {
          SymmetricTensor<2, dim> mean;
          for (unsigned int q = 0; q < n_q; ++q)
            mean += quadrature_point_history
                      [std::size_t(cell->active_cell_index()) * n_q + q]
                        .stress
                    / double(n_q);
          const unsigned int index = cell->active_cell_index();
          von_mises[index]         = material.equivalent_stress(mean);
          subdomain[index]         = cell->subdomain_id();
          unsigned int component   = 0;
          for (unsigned int a = 0; a < dim; ++a)
            for (unsigned int b = a; b < dim; ++b)
              stress[component++][index] = mean[a][b];
        }
    data_out.add_data_vector(von_mises, "von_mises");
    const char  *names[3]  = {"x", "y", "z"};
    unsigned int component = 0;
    for (unsigned int a = 0; a < dim; ++a)
      for (unsigned int b = a; b < dim; ++b)
        data_out.add_data_vector(stress[component++],
                                 std::string("stress_") + names[a] + names[b]);
    data_out.add_data_vector(subdomain, "subdomain");
    data_out.build_patches(*mapping);

    const unsigned int n_groups
      = std::min(8u, Utilities::MPI::n_mpi_processes(mpi_communicator));
    const std::string record
      = data_out.write_vtu_with_pvtu_record(parameters.directory + "/",
                                            stem,
                                            step,
                                            mpi_communicator,
                                            4,
                                            n_groups);
    if (stem == "solution"
        && Utilities::MPI::this_mpi_process(mpi_communicator) == 0)
      {
        times_and_names.emplace_back(time, record);
        std::ofstream pvd(std::filesystem::path(parameters.directory)
                          / "solution.pvd");
        DataOutBase::write_pvd_record(pvd, times_and_names);
      }
  }



  // @sect4{DistributedViscoplasticContact::print_run_summary}
  //
  // What was built how often, the solver effort, the figure of merit (time
  // per step / one elastic solve), peak memory over the ranks, the final
  // displacement norm (compared between rank counts by the tests) and the
  // timing table.
  template <int dim>
  void
  DistributedViscoplasticContact<dim>::print_run_summary(
    const double reference_solve_time)
  {
    Utilities::System::MemoryStats memory;
    Utilities::System::get_memory_stats(memory);
    const double peak_memory_mb
      = Utilities::MPI::sum(double(memory.VmHWM) / 1024., mpi_communicator);
    const double step_time
      = Utilities::MPI::max(time_loop_compute_time, mpi_communicator)
        / std::max(1u, n_time_steps);

    pcout << "Elastic operator: " << n_operator_assemblies
          << " assembly, preconditioner built " << n_preconditioner_setups
          << " time(s)\n"
          << "Active-set iterations: " << total_active_set_iterations << " in "
          << n_time_steps << " steps (" << std::setprecision(3)
          << double(total_active_set_iterations) / std::max(1u, n_time_steps)
          << " per step); CG iterations per solve: "
          << double(total_cg_iterations) / std::max(1u, n_cg_solves) << '\n'
          << std::setprecision(8) << "Final displacement: l2 norm "
          << solution.l2_norm() << ", max norm " << solution.linfty_norm()
          << '\n';
    if (parameters.print_timing_summary)
      {
        pcout << std::setprecision(4) << "Time per step: " << step_time
              << " s = " << step_time / reference_solve_time
              << " elastic solves (one elastic solve: " << reference_solve_time
              << " s); per dof and step: "
              << step_time / dof_handler.n_dofs() * 1e6 << " us\n"
              << "Peak memory (sum over ranks): " << peak_memory_mb << " MB\n";
        computing_timer.print_summary();
      }
  }



  template class DistributedViscoplasticContact<2>;
  template class DistributedViscoplasticContact<3>;
} // namespace ViscoContact
