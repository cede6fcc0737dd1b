// The time loop of ViscoplasticContact<dim>: right-hand side, the active-set
// solve of one step, and the explicit stress and history update.

#include <deal.II/base/exceptions.h>
#include <deal.II/base/timer.h>

#include <deal.II/fe/fe_values.h>

#include "checkpoint.h"
#include "time_loop.h"
#include "viscoplastic_contact.h"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>

namespace ViscoContact
{
  // @sect4{ViscoplasticContact::run}
  //
  // The algorithm of model.md, section 2, as the reader would write it down:
  // set up, then for each time step assemble the right-hand side, solve the
  // step's variational-hemivariational inequality by the active-set method,
  // update the stresses and the history, and write the results. Around it:
  // a resumed run starts after the step of its checkpoint, a checkpoint is
  // written every Checkpoint interval steps, and a run may be told to stop
  // after a given step (as if it had been killed).
  template <int dim>
  void
  ViscoplasticContact<dim>::run()
  {
    make_grid();
    setup_system();
    setup_contact();
    setup_quadrature_point_history();

    std::vector<double> times
      = time_levels(parameters.end_time, parameters.time_step);
    unsigned int first_step = 1;
    if (parameters.resume)
      first_step = resume_from_checkpoint(times) + 1;
    prepare_output_directory();
    n_time_steps = times.size() - 1;

    pcout << "Mesh: " << triangulation.n_active_cells() << ' '
          << reference_cell.to_string() << " cells, " << dof_handler.n_dofs()
          << " displacement dofs, " << contact_nodes.size()
          << " contact nodes, " << n_time_steps << " time steps\n"
          << "Model: " << (parameters.plasticity ? "viscoplastic" : "elastic")
          << ", contact " << (contact_enabled ? "on" : "off") << '\n';
    report_scheme_limits();

    // The step whose contact profile is written for a requested time is the
    // one closest to it in the schedule (which a cut step refines).
    const auto is_profile_step = [&](const unsigned int n) {
      for (const double target : parameters.profile_times)
        {
          unsigned int closest = 0;
          for (unsigned int m = 1; m < times.size(); ++m)
            if (std::abs(times[m] - target) < std::abs(times[closest] - target))
              closest = m;
          if (closest == n)
            return true;
        }
      return false;
    };

    if (parameters.write_vtu && first_step == 1)
      output_results(0, 0.);

    Timer loop_timer;
    for (unsigned int n = first_step; n < times.size(); ++n)
      {
        Timer                                step_timer;
        const ContactActiveSetSolver::Result result
          = solve_step_with_recovery(n, times);
        update_stresses(times[n] - times[n - 1],
                        n + 1 < times.size() ? times[n + 1] - times[n] : 0.);
        time_loop_compute_time += step_timer.wall_time();
        n_time_steps = times.size() - 1;
        if (step_observer)
          step_observer(n, times[n]);

        const double wall_time = loop_time_offset + loop_timer.wall_time();
        write_time_series_row(n, times[n], result, wall_time);
        if (parameters.verbose)
          print_step_line(pcout,
                          n,
                          times[n],
                          result.iterations(),
                          count_contact_states(),
                          total_contact_force());
        if (is_profile_step(n))
          write_contact_profile(n, times[n]);
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

    print_run_summary();
  }



  // @sect4{ViscoplasticContact::solve_step_with_recovery}
  //
  // One time step, and what happens when its solve fails (the active-set
  // or Newton iteration reaches its limit, or the displacement is not
  // finite): the state at the start of the step is restored, and either the
  // step is cut in half (the other half becomes the next step of the
  // schedule; with the explicit update the history increment H_n - H_{n-1}
  // = k G(sigma_{n-1}) is rescaled to the new k) or, when cutting is not
  // asked for or would go below Minimum time step, the last accepted state
  // is written to failed_step_NNNN.vtu and the run stops with a report.
  template <int dim>
  ContactActiveSetSolver::Result
  ViscoplasticContact<dim>::solve_step_with_recovery(const unsigned int   n,
                                                     std::vector<double> &times)
  {
    const Vector<double>          start_solution = solution;
    ContactActiveSetSolver::State start_contact;
    if (contact_enabled)
      start_contact = active_set_solver.state();
    const bool explicit_history
      = parameters.plasticity && parameters.stress_update == "explicit";

    while (true)
      {
        const double k = times[n] - times[n - 1];
        assemble_right_hand_side(times[n]);
        const ContactActiveSetSolver::Result result
          = (parameters.stress_update == "implicit"
               ? solve_implicit_time_step(k)
               : solve_time_step());
        if (result.converged)
          return result;

        const std::array<unsigned int, 3> states = count_contact_states();
        solution                                 = start_solution;
        if (contact_enabled)
          active_set_solver.set_state(start_contact);
        if (cut_failed_step(parameters, pcout, n, times, result.failure))
          {
            if (explicit_history)
              rescale_history_increment(k, times[n] - times[n - 1]);
            continue;
          }

        const std::string state_file = failed_state_file(n, "vtu");
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



  // @sect4{ViscoplasticContact::rescale_history_increment}
  //
  // H_n = H_{n-1} + k G(sigma_{n-1}) was computed with the step length k
  // the schedule had; a cut step needs it with k': H_n += (k' - k) G.
  // sigma_{n-1} is unchanged by the failed attempt, so G is the same.
  template <int dim>
  void
  ViscoplasticContact<dim>::rescale_history_increment(const double old_step,
                                                      const double new_step)
  {
    for (QuadraturePointHistory<dim> &state : quadrature_point_history)
      state.history += (new_step - old_step)
                       * material.viscoplastic_rate(state.stress,
                                                    &state.plastic_multiplier);
    assemble_history_load();
  }



  // @sect4{Access for studies}
  template <int dim>
  void
  ViscoplasticContact<dim>::set_step_observer(
    const std::function<void(const unsigned int, const double)> &observer)
  {
    step_observer = observer;
  }



  template <int dim>
  const Triangulation<dim> &
  ViscoplasticContact<dim>::get_triangulation() const
  {
    return triangulation;
  }



  template <int dim>
  const DoFHandler<dim> &
  ViscoplasticContact<dim>::get_dof_handler() const
  {
    return dof_handler;
  }



  template <int dim>
  const Mapping<dim> &
  ViscoplasticContact<dim>::get_mapping() const
  {
    return *mapping;
  }



  template <int dim>
  const Vector<double> &
  ViscoplasticContact<dim>::get_displacement() const
  {
    return solution;
  }



  template <int dim>
  const SymmetricTensor<2, dim> &
  ViscoplasticContact<dim>::get_stress(const unsigned int active_cell_index,
                                       const unsigned int stress_point) const
  {
    return quadrature_point_history[active_cell_index * stress_quadrature.size()
                                    + stress_point]
      .stress;
  }



  // @sect4{ViscoplasticContact::assemble_right_hand_side}
  //
  // b_n = (f_n, v) - (H_n, eps(v)). The history part was assembled by the
  // previous stress update; the external part is assembled once if the loads
  // do not depend on time.
  template <int dim>
  void
  ViscoplasticContact<dim>::assemble_right_hand_side(const double time)
  {
    TimerOutput::Scope t(computing_timer, "Assemble right-hand side");
    if (loads_depend_on_time || n_external_load_assemblies == 0)
      assemble_external_load(time);
    system_rhs = external_load;
    // The implicit scheme has the history inside its internal force.
    if (parameters.plasticity && parameters.stress_update == "explicit")
      system_rhs += history_load;
  }



  template <int dim>
  void
  ViscoplasticContact<dim>::assemble_external_load(const double time)
  {
    external_load = 0;
    body_force.set_time(time);
    surface_traction.set_time(time);
    const unsigned int                   dofs_per_cell = fe->n_dofs_per_cell();
    Vector<double>                       cell_rhs(dofs_per_cell);
    std::vector<types::global_dof_index> local_dof_indices(dofs_per_cell);
    Vector<double>                       load_value(dim);

    FEValues<dim>     fe_values(*mapping,
                            *fe,
                            load_quadrature,
                            update_values | update_quadrature_points
                              | update_JxW_values);
    FEFaceValues<dim> fe_face_values(*mapping,
                                     *fe,
                                     face_quadrature,
                                     update_values | update_quadrature_points
                                       | update_JxW_values);

    for (const auto &cell : dof_handler.active_cell_iterators())
      {
        cell_rhs       = 0;
        bool has_loads = false;
        if (!body_force_is_zero)
          {
            fe_values.reinit(cell);
            for (const unsigned int q : fe_values.quadrature_point_indices())
              {
                body_force.vector_value(fe_values.quadrature_point(q),
                                        load_value);
                for (unsigned int i = 0; i < dofs_per_cell; ++i)
                  {
                    const unsigned int c
                      = fe->system_to_component_index(i).first;
                    cell_rhs(i) += load_value(c) * fe_values.shape_value(i, q)
                                   * fe_values.JxW(q);
                  }
              }
            has_loads = true;
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
                  surface_traction.vector_value(fe_face_values.quadrature_point(
                                                  q),
                                                load_value);
                  for (unsigned int i = 0; i < dofs_per_cell; ++i)
                    {
                      const unsigned int c
                        = fe->system_to_component_index(i).first;
                      cell_rhs(i) += load_value(c)
                                     * fe_face_values.shape_value(i, q)
                                     * fe_face_values.JxW(q);
                    }
                }
              has_loads = true;
            }
        if (has_loads)
          {
            cell->get_dof_indices(local_dof_indices);
            constraints.distribute_local_to_global(cell_rhs,
                                                   local_dof_indices,
                                                   external_load);
          }
      }
    ++n_external_load_assemblies;
  }



  // @sect4{ViscoplasticContact::assemble_history_load}
  //
  // -(H, eps(v)) from the history stored at the stress points. The time loop
  // gets this vector from update_stresses(), which assembles it while it
  // computes H; this stand-alone version is the reference for the cost
  // measurement in the run summary. With eps(N_a e_c) = sym(e_c (x) grad N_a)
  // and H symmetric, the entry of dof (a, c) is -JxW (H grad N_a)_c.
  template <int dim>
  void
  ViscoplasticContact<dim>::assemble_history_load()
  {
    history_load               = 0;
    const unsigned int n_q     = stress_quadrature.size();
    const unsigned int n_cells = triangulation.n_active_cells();
    for (unsigned int cell = 0; cell < n_cells; ++cell)
      for (unsigned int q = 0; q < n_q; ++q)
        subtract_stress_point_load(
          quadrature_point_history[std::size_t(cell) * n_q + q].history,
          cell,
          q,
          history_load);
    constraints.condense(history_load);
  }



  // @sect4{ViscoplasticContact::solve_time_step}
  //
  // One solve with the factorised elastic operator gives the displacement
  // without contact forces and with it the free normal displacements
  // d = N K^{-1} b at the contact nodes. The active-set method finds the
  // contact forces z on the contact nodes alone (warm-started from the
  // previous step); their response -K^{-1} N^T z = -W z is added from the
  // stored W (or by a second solve). No matrix is assembled or factorised
  // here.
  template <int dim>
  ContactActiveSetSolver::Result
  ViscoplasticContact<dim>::solve_time_step()
  {
    ContactActiveSetSolver::Result result{true, {}, 0, {}};
    {
      TimerOutput::Scope t(computing_timer, "Solve: elastic solves");
      solution = system_rhs;
      solve_elastic(solution);
    }

    if (contact_enabled)
      {
        TimerOutput::Scope t(computing_timer, "Solve: active set on Gamma_3");
        Vector<double>     free_normal_displacement(contact_nodes.size());
        for (unsigned int i = 0; i < contact_nodes.size(); ++i)
          for (unsigned int c = 0; c < dim; ++c)
            free_normal_displacement[i] += contact_nodes[i].normal[c]
                                           * solution[contact_nodes[i].dofs[c]];

        result = active_set_solver.solve(free_normal_displacement,
                                         parameters.max_iterations,
                                         parameters.tolerance);
        total_active_set_iterations += result.iterations();
        if (!result.converged)
          {
            std::ostringstream reason;
            reason << "The active-set iteration did not converge within "
                   << result.iterations()
                   << " iterations (Maximum iterations = "
                   << parameters.max_iterations
                   << ", Tolerance = " << parameters.tolerance
                   << " in subsection <Active set solver>).";
            result.failure = reason.str();
            return result;
          }
      }

    // The response to the contact forces: -W z if W is stored (a dense
    // product over the nodes in contact), else a second solve.
    const Vector<double> &z = active_set_solver.normal_forces();
    if (contact_enabled && z.linfty_norm() > 0)
      {
        if (contact_responses_stored)
          {
            TimerOutput::Scope t(computing_timer, "Solve: contact response");
            contact_responses.vmult(contact_response, z);
          }
        else
          {
            TimerOutput::Scope t(computing_timer, "Solve: elastic solves");
            contact_response = 0;
            for (unsigned int i = 0; i < contact_nodes.size(); ++i)
              for (unsigned int c = 0; c < dim; ++c)
                contact_response[contact_nodes[i].dofs[c]]
                  = z[i] * contact_nodes[i].normal[c];
            solve_elastic(contact_response);
          }
        solution -= contact_response;
      }
    constraints.distribute(solution);

    if (!std::isfinite(solution.l2_norm()))
      {
        result.converged = false;
        result.failure   = "The displacement is not finite (NaN or Inf).";
      }
    return result;
  }



  // @sect4{ViscoplasticContact::displacement_gradient_at}
  //
  // grad u = sum_a u_a (x) grad N_a at stress point q of a cell, from the
  // geometry stored at set-up.
  template <int dim>
  inline Tensor<2, dim>
  ViscoplasticContact<dim>::displacement_gradient_at(
    const Vector<double> &displacement,
    const unsigned int    cell,
    const unsigned int    q) const
  {
    const unsigned int             n_a = n_cell_vertices;
    const types::global_dof_index *dofs
      = &cell_dof_indices[std::size_t(cell) * n_a * dim];
    const Tensor<1, dim> *gradients
      = &stress_point_gradients[(std::size_t(cell) * stress_quadrature.size()
                                 + q)
                                * n_a];
    Tensor<2, dim> gradient;
    for (unsigned int a = 0; a < n_a; ++a)
      for (unsigned int c = 0; c < dim; ++c)
        gradient[c] += displacement[dofs[a * dim + c]] * gradients[a];
    return gradient;
  }



  // @sect4{ViscoplasticContact::subtract_stress_point_load}
  //
  // target -= (H, eps(v)) at stress point q of a cell: with
  // eps(N_a e_c) = sym(e_c (x) grad N_a) and H symmetric, the entry of dof
  // (a, c) is JxW (H grad N_a)_c. Shared by the time loop's history update
  // and the stand-alone assembly it is measured against.
  template <int dim>
  inline void
  ViscoplasticContact<dim>::subtract_stress_point_load(
    const SymmetricTensor<2, dim> &H,
    const unsigned int             cell,
    const unsigned int             q,
    Vector<double>                &target) const
  {
    const unsigned int             n_a = n_cell_vertices;
    const types::global_dof_index *dofs
      = &cell_dof_indices[std::size_t(cell) * n_a * dim];
    const std::size_t point = std::size_t(cell) * stress_quadrature.size() + q;
    const Tensor<1, dim> *gradients = &stress_point_gradients[point * n_a];
    const double          JxW       = stress_point_JxW[point];
    for (unsigned int a = 0; a < n_a; ++a)
      {
        const Tensor<1, dim> force = H * gradients[a];
        for (unsigned int c = 0; c < dim; ++c)
          target[dofs[a * dim + c]] -= JxW * force[c];
      }
  }



  // @sect4{ViscoplasticContact::assemble_tangent_system}
  //
  // For the implicit scheme: at the displacement u, the stresses
  // sigma(eps(u)) of the backward-Euler update at every stress point, the
  // internal force (sigma, eps(v)) and the tangent stiffness
  // (C_alg eps(w), eps(v)) with the consistent tangent
  // C_alg = (d sigma / d trial) E. The state at the stress points is not
  // changed (only the multiplier guesses).
  template <int dim>
  void
  ViscoplasticContact<dim>::assemble_tangent_system(
    const Vector<double> &displacement,
    const double          a)
  {
    TimerOutput::Scope t(computing_timer, "Assemble tangent system");
    tangent_matrix                         = 0;
    internal_force                         = 0;
    const SymmetricTensor<4, dim> &E       = material.elasticity_tensor();
    const unsigned int             n_q     = stress_quadrature.size();
    const unsigned int             n_a     = n_cell_vertices;
    const unsigned int             n_local = n_a * dim;
    const unsigned int             n_cells = triangulation.n_active_cells();
    FullMatrix<double>             cell_matrix(n_local, n_local);
    Vector<double>                 cell_force(n_local);
    std::vector<types::global_dof_index> local_dofs(n_local);

    for (unsigned int cell = 0; cell < n_cells; ++cell)
      {
        const types::global_dof_index *dofs
          = &cell_dof_indices[std::size_t(cell) * n_local];
        std::copy(dofs, dofs + n_local, local_dofs.begin());
        cell_matrix = 0;
        cell_force  = 0;
        for (unsigned int q = 0; q < n_q; ++q)
          {
            const std::size_t     point = std::size_t(cell) * n_q + q;
            const Tensor<1, dim> *gradients
              = &stress_point_gradients[point * n_a];
            const double         JxW = stress_point_JxW[point];
            const Tensor<2, dim> displacement_gradient
              = displacement_gradient_at(displacement, cell, q);

            QuadraturePointHistory<dim> &state
              = quadrature_point_history[point];
            SymmetricTensor<4, dim> trial_tangent = identity_tensor<dim>();
            const SymmetricTensor<2, dim> stress
              = (parameters.plasticity ? material.implicit_stress_update(
                   E * symmetrize(displacement_gradient) + state.history,
                   a,
                   &trial_tangent,
                   &state.plastic_multiplier)
                                       : E * symmetrize(displacement_gradient));
            const SymmetricTensor<4, dim> C = trial_tangent * E;

            for (unsigned int i = 0; i < n_local; ++i)
              {
                const unsigned int ai = i / dim, ci = i % dim;
                cell_force(i) += JxW * (stress * gradients[ai])[ci];
                for (unsigned int j = 0; j < n_local; ++j)
                  {
                    const unsigned int bj = j / dim, cj = j % dim;
                    double             value = 0;
                    for (unsigned int k = 0; k < dim; ++k)
                      for (unsigned int l = 0; l < dim; ++l)
                        value += C[ci][k][cj][l] * gradients[ai][k]
                                 * gradients[bj][l];
                    cell_matrix(i, j) += JxW * value;
                  }
              }
          }
        constraints.distribute_local_to_global(cell_matrix,
                                               cell_force,
                                               local_dofs,
                                               tangent_matrix,
                                               internal_force);
      }
    ++n_operator_assemblies;
  }



  // @sect4{ViscoplasticContact::solve_contact_with}
  //
  // The condensed contact solve of solve_time_step() for an operator that
  // changes (the implicit scheme's tangent): the compliance S and the
  // responses W = K^{-1} N^T are recomputed with the given factorisation
  // (m solves), the nodes keep their pieces as warm start, and
  // u = K^{-1} rhs - W z.
  template <int dim>
  ContactActiveSetSolver::Result
  ViscoplasticContact<dim>::solve_contact_with(
    SparseDirectUMFPACK  &factorization,
    const Vector<double> &rhs,
    Vector<double>       &displacement)
  {
    displacement = rhs;
    factorization.solve(displacement);
    ++n_elastic_solves;
    if (!contact_enabled)
      return ContactActiveSetSolver::Result{true, {}, 0, {}};

    const unsigned int          m = contact_nodes.size();
    FullMatrix<double>          compliance(m, m);
    std::vector<Vector<double>> responses(m,
                                          Vector<double>(dof_handler.n_dofs()));
    Vector<double>              free_normal_displacement(m);
    for (unsigned int j = 0; j < m; ++j)
      {
        for (unsigned int c = 0; c < dim; ++c)
          responses[j][contact_nodes[j].dofs[c]] = contact_nodes[j].normal[c];
        factorization.solve(responses[j]);
        ++n_elastic_solves;
      }
    for (unsigned int i = 0; i < m; ++i)
      for (unsigned int c = 0; c < dim; ++c)
        {
          const types::global_dof_index dof = contact_nodes[i].dofs[c];
          free_normal_displacement[i]
            += contact_nodes[i].normal[c] * displacement[dof];
          for (unsigned int j = 0; j < m; ++j)
            compliance(i, j) += contact_nodes[i].normal[c] * responses[j][dof];
        }
    active_set_solver.update_compliance(compliance);
    const ContactActiveSetSolver::Result result
      = active_set_solver.solve(free_normal_displacement,
                                parameters.max_iterations,
                                parameters.tolerance);
    for (unsigned int j = 0; j < m; ++j)
      displacement.add(-active_set_solver.normal_forces()[j], responses[j]);
    return result;
  }



  // @sect4{ViscoplasticContact::implicit_newton}
  //
  // Newton's method for the step problem of the backward-Euler scheme with
  // the viscous parameter a = k/(2 lambda): linearise sigma(eps(u)) at the
  // current iterate with the consistent tangent, solve the linearised
  // contact problem exactly (the active set on the condensed tangent),
  // repeat until the update is at rounding level. The relative size of each
  // update is printed (with Verbose), which shows the quadratic convergence
  // once the contact set has settled. Returns whether it converged; the
  // iterate is updated in place.
  template <int dim>
  bool
  ViscoplasticContact<dim>::implicit_newton(
    const double                    a,
    Vector<double>                 &iterate,
    ContactActiveSetSolver::Result &result)
  {
    Vector<double> rhs(dof_handler.n_dofs()), next(dof_handler.n_dofs());
    for (unsigned int newton = 1; newton <= parameters.max_iterations; ++newton)
      {
        assemble_tangent_system(iterate, a);
        // K_T u_new = f - F_int(u) + K_T u - N^T z.
        rhs = system_rhs;
        rhs -= internal_force;
        tangent_matrix.vmult_add(rhs, iterate);
        {
          TimerOutput::Scope t(computing_timer, "Solve: factorise tangent");
          tangent_factorization.initialize(tangent_matrix);
          ++n_operator_factorizations;
        }
        ContactActiveSetSolver::Result linearised;
        {
          TimerOutput::Scope t(computing_timer,
                               "Solve: contact on the tangent");
          linearised = solve_contact_with(tangent_factorization, rhs, next);
        }
        result.earlier_iterations += result.history.size();
        result.history   = linearised.history;
        result.converged = linearised.converged;
        ++total_newton_iterations;
        if (!linearised.converged)
          {
            if (parameters.verbose)
              pcout << "    Newton iteration " << newton
                    << ": the active set on the tangent did not converge\n";
            return false;
          }
        constraints.distribute(next);
        const double change = (Vector<double>(next) -= iterate).linfty_norm()
                              / std::max(next.linfty_norm(), 1e-300);
        iterate = next;
        if (parameters.verbose)
          pcout << "    Newton iteration " << newton
                << ": |du|/|u| = " << std::scientific << std::setprecision(2)
                << change << std::defaultfloat << ", active-set iterations "
                << linearised.iterations() << '\n';
        if (!std::isfinite(change))
          return false;
        if (change <= 1e-11)
          return true;
        // Converging Newton iterations are near rounding level long before
        // ten steps; still far away then, the iteration is not going to
        // converge from here, and the caller's continuation takes over.
        if (newton >= 10 && change > 1e-4)
          return false;
      }
    return false;
  }



  // @sect4{ViscoplasticContact::solve_implicit_time_step}
  //
  // Newton from the previous state converges when the plastic tangent is
  // not much softer than the elastic one. When it does not (large
  // k E / lambda: the step is nearly rate-independent and the first Newton
  // steps overshoot), the same step problem is reached by continuation in
  // the viscous parameter: solve with a/J, 2a/J, ..., a, each from the
  // previous solution, for J = 2, 4, ..., 64. Every stage is the
  // backward-Euler step problem with a smaller parameter, and the last one
  // is the step itself, so the scheme is unchanged; only the path of the
  // solver is.
  template <int dim>
  ContactActiveSetSolver::Result
  ViscoplasticContact<dim>::solve_implicit_time_step(const double time_step)
  {
    const double                   a = time_step / (2 * material.viscosity());
    ContactActiveSetSolver::Result result{true, {}, 0, {}};
    Vector<double>                 iterate;
    for (unsigned int stages = 1; stages <= 64; stages *= 2)
      {
        if (stages > 1 && parameters.verbose)
          pcout << "    Newton did not converge; continuation in "
                   "a = k/(2 lambda) with "
                << stages << " stages\n";
        iterate        = solution;
        bool converged = true;
        for (unsigned int stage = 1; stage <= stages && converged; ++stage)
          converged = implicit_newton(a * stage / stages, iterate, result);
        if (converged)
          {
            solution = iterate;
            total_active_set_iterations += result.iterations();
            return result;
          }
      }
    result.converged = false;
    result.failure
      = "The Newton iteration of the implicit scheme did not converge, not "
        "even with continuation in a = k/(2 lambda) over 64 stages (Maximum "
        "iterations = "
        + std::to_string(parameters.max_iterations)
        + " per Newton iteration and per active-set iteration, subsection "
          "<Active set solver>).";
    return result;
  }



  // @sect4{ViscoplasticContact::update_stresses}
  //
  // sigma_n = E eps(u_n) + H_n at every stress point, and, with plasticity,
  // the explicit history update H_{n+1} = H_n + k_{n+1} G(sigma_n) of
  // model.md, section 2. The same loop assembles -(H_{n+1}, eps(v)), the
  // history load of the next step (as assemble_history_load() does), so the
  // stress points are visited once per step. P (the L2 projection onto Q^h)
  // is the identity here: E eps(u_n) is already piecewise constant on P1
  // simplices, and on hypercubes the stresses are stored at the quadrature
  // points themselves.
  template <int dim>
  void
  ViscoplasticContact<dim>::update_stresses(const double current_time_step,
                                            const double next_time_step)
  {
    TimerOutput::Scope t(computing_timer, "Stress update");
    const bool         implicit
      = parameters.plasticity && parameters.stress_update == "implicit";
    const bool update_history
      = parameters.plasticity && !implicit && next_time_step > 0;
    const double a = current_time_step / (2 * material.viscosity());
    const SymmetricTensor<4, dim> &E       = material.elasticity_tensor();
    const unsigned int             n_q     = stress_quadrature.size();
    const unsigned int             n_cells = triangulation.n_active_cells();

    if (update_history)
      history_load = 0;
    max_von_mises = 0;
    for (unsigned int cell = 0; cell < n_cells; ++cell)
      {
        for (unsigned int q = 0; q < n_q; ++q)
          {
            const std::size_t    point = std::size_t(cell) * n_q + q;
            const Tensor<2, dim> displacement_gradient
              = displacement_gradient_at(solution, cell, q);

            QuadraturePointHistory<dim> &state
              = quadrature_point_history[point];
            const SymmetricTensor<2, dim> elastic_stress
              = E * symmetrize(displacement_gradient);
            if (implicit)
              {
                // Backward Euler: sigma_n from the local equation, and the
                // history part of the next step is what is not elastic.
                state.stress
                  = material.implicit_stress_update(elastic_stress
                                                      + state.history,
                                                    a,
                                                    nullptr,
                                                    &state.plastic_multiplier);
                state.history = state.stress - elastic_stress;
              }
            else
              state.stress = elastic_stress + state.history;
            max_von_mises = std::max(max_von_mises,
                                     material.equivalent_stress(state.stress));
            if (update_history)
              {
                state.history
                  += next_time_step
                     * material.viscoplastic_rate(state.stress,
                                                  &state.plastic_multiplier);
                subtract_stress_point_load(state.history,
                                           cell,
                                           q,
                                           history_load);
              }
          }
      }
    if (update_history)
      constraints.condense(history_load);

    // An unstable explicit update ends in stresses that overflow: stop
    // rather than go on with (and write) infinite or NaN fields.
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



  // @sect4{Contact state}
  //
  // A node is in unilateral contact when it sits on the rigid piece
  // (u_nu = g), in normal-compliance contact when it penetrates the layer
  // (0 < u_nu < g) or the layer pushes on it, and out of contact otherwise.
  template <int dim>
  unsigned int
  ViscoplasticContact<dim>::contact_status(const unsigned int node) const
  {
    const ContactLawPiece &piece
      = active_set_solver.law().piece(active_set_solver.pieces()[node]);
    if (piece.rigid)
      return 2;
    if (active_set_solver.normal_displacements()[node] > 0
        || active_set_solver.normal_forces()[node] > 0)
      return 1;
    return 0;
  }



  template <int dim>
  std::array<unsigned int, 3>
  ViscoplasticContact<dim>::count_contact_states() const
  {
    std::array<unsigned int, 3> counts = {{0, 0, 0}};
    if (contact_enabled)
      for (unsigned int i = 0; i < contact_nodes.size(); ++i)
        switch (contact_status(i))
          {
            case 2:
              ++counts[0];
              break;
            case 1:
              ++counts[1];
              break;
            default:
              ++counts[2];
          }
    else
      counts[2] = contact_nodes.size();
    return counts;
  }



  template <int dim>
  double
  ViscoplasticContact<dim>::total_contact_force() const
  {
    if (!contact_enabled)
      return 0;
    double sum = 0;
    for (const double z : active_set_solver.normal_forces())
      sum += z;
    return sum;
  }



  template class ViscoplasticContact<2>;
  template class ViscoplasticContact<3>;
} // namespace ViscoContact
