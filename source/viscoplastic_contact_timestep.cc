// The time loop of ViscoplasticContact<dim>: right-hand side, the active-set
// solve of one step, and the explicit stress and history update.

#include <deal.II/base/exceptions.h>
#include <deal.II/base/timer.h>

#include <deal.II/fe/fe_values.h>

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
  // update the stresses and the history, and write the results.
  template <int dim>
  void
  ViscoplasticContact<dim>::run()
  {
    make_grid();
    setup_system();
    setup_contact();
    setup_quadrature_point_history();
    prepare_output_directory();

    const std::vector<double> times = time_levels();
    n_time_steps                    = times.size() - 1;

    pcout << "Mesh: " << triangulation.n_active_cells() << ' '
          << reference_cell.to_string() << " cells, " << dof_handler.n_dofs()
          << " displacement dofs, " << contact_nodes.size()
          << " contact nodes, " << n_time_steps << " time steps\n"
          << "Model: " << (parameters.plasticity ? "viscoplastic" : "elastic")
          << ", contact " << (contact_enabled ? "on" : "off") << '\n';
    report_scheme_limits();

    // The steps whose contact profile is written: the ones closest to the
    // requested times.
    for (const double t : parameters.profile_times)
      {
        unsigned int closest = 0;
        for (unsigned int n = 1; n < times.size(); ++n)
          if (std::abs(times[n] - t) < std::abs(times[closest] - t))
            closest = n;
        profile_steps.push_back(closest);
      }

    if (parameters.write_vtu)
      output_results(0, 0.);

    Timer loop_timer;
    for (unsigned int n = 1; n <= n_time_steps; ++n)
      {
        Timer step_timer;
        assemble_right_hand_side(times[n]);
        const ContactActiveSetSolver::Result result
          = solve_time_step(n, times[n]);
        update_stresses(n < n_time_steps ? times[n + 1] - times[n] : 0.);
        time_loop_compute_time += step_timer.wall_time();
        if (step_observer)
          step_observer(n, times[n]);

        write_time_series_row(n, times[n], result, loop_timer.wall_time());
        if (parameters.verbose)
          {
            const auto states = count_contact_states();
            pcout << "Step " << std::setw(4) << n << "  t = " << std::setw(9)
                  << std::setprecision(6) << times[n]
                  << "  active-set iterations " << std::setw(2)
                  << result.iterations() << "  unilateral " << std::setw(4)
                  << states[0] << "  compliance " << std::setw(4) << states[1]
                  << "  no contact " << std::setw(4) << states[2]
                  << "  contact force " << std::setprecision(8)
                  << total_contact_force() << '\n';
          }
        if (std::find(profile_steps.begin(), profile_steps.end(), n)
            != profile_steps.end())
          write_contact_profile(n, times[n]);
        if (parameters.write_vtu
            && (n % parameters.interval == 0 || n == n_time_steps))
          output_results(n, times[n]);
      }

    print_run_summary();
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



  template <int dim>
  unsigned int
  ViscoplasticContact<dim>::n_stress_points_per_cell() const
  {
    return stress_quadrature.size();
  }



  // @sect4{ViscoplasticContact::time_levels}
  //
  // t_n = n k, with the last step shortened so that the run ends at T.
  template <int dim>
  std::vector<double>
  ViscoplasticContact<dim>::time_levels() const
  {
    const double       T = parameters.end_time, k = parameters.time_step;
    const unsigned int N
      = static_cast<unsigned int>(std::ceil(T / k * (1 - 1e-12)));
    std::vector<double> times(N + 1);
    for (unsigned int n = 0; n < N; ++n)
      times[n] = n * k;
    times[N] = T;
    return times;
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
    if (parameters.plasticity)
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
    const unsigned int n_a     = n_cell_vertices;
    const unsigned int n_cells = triangulation.n_active_cells();
    for (unsigned int cell = 0; cell < n_cells; ++cell)
      {
        const types::global_dof_index *dofs
          = &cell_dof_indices[std::size_t(cell) * n_a * dim];
        for (unsigned int q = 0; q < n_q; ++q)
          {
            const std::size_t              point = std::size_t(cell) * n_q + q;
            const SymmetricTensor<2, dim> &H
              = quadrature_point_history[point].history;
            const Tensor<1, dim> *gradients
              = &stress_point_gradients[point * n_a];
            const double JxW = stress_point_JxW[point];
            for (unsigned int a = 0; a < n_a; ++a)
              {
                const Tensor<1, dim> force = H * gradients[a];
                for (unsigned int c = 0; c < dim; ++c)
                  history_load[dofs[a * dim + c]] -= JxW * force[c];
              }
          }
      }
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
  ViscoplasticContact<dim>::solve_time_step(const unsigned int step,
                                            const double       time)
  {
    ContactActiveSetSolver::Result result{true, {}};
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
            const auto         states = count_contact_states();
            std::ostringstream message;
            message << "The active-set iteration did not converge in time step "
                    << step << " (t = " << time << ") within "
                    << result.iterations()
                    << " iterations (Maximum iterations = "
                    << parameters.max_iterations
                    << ", Tolerance = " << parameters.tolerance
                    << " in subsection <Active set solver>).\n"
                    << "Iteration history:\n"
                    << result.describe()
                    << "Contact state at the end: " << states[0]
                    << " nodes at the rigid limit, " << states[1]
                    << " in normal-compliance contact, " << states[2]
                    << " out of contact.\n"
                    << "If the contact law softens more than the body can "
                       "carry (model.md, section 4) the step problem may have "
                       "several solutions or none.";
            AssertThrow(false, ExcMessage(message.str()));
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

    AssertThrow(std::isfinite(solution.l2_norm()),
                ExcMessage("The displacement of time step "
                           + std::to_string(step)
                           + " is not finite (NaN or Inf)."));
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
  ViscoplasticContact<dim>::update_stresses(const double next_time_step)
  {
    TimerOutput::Scope t(computing_timer, "Stress update");
    const bool update_history = parameters.plasticity && next_time_step > 0;
    const SymmetricTensor<4, dim> &E       = material.elasticity_tensor();
    const unsigned int             n_q     = stress_quadrature.size();
    const unsigned int             n_a     = n_cell_vertices;
    const unsigned int             n_cells = triangulation.n_active_cells();

    if (update_history)
      history_load = 0;
    max_von_mises = 0;
    for (unsigned int cell = 0; cell < n_cells; ++cell)
      {
        const types::global_dof_index *dofs
          = &cell_dof_indices[std::size_t(cell) * n_a * dim];
        for (unsigned int q = 0; q < n_q; ++q)
          {
            const std::size_t     point = std::size_t(cell) * n_q + q;
            const Tensor<1, dim> *gradients
              = &stress_point_gradients[point * n_a];

            Tensor<2, dim> displacement_gradient;
            for (unsigned int a = 0; a < n_a; ++a)
              for (unsigned int c = 0; c < dim; ++c)
                displacement_gradient[c]
                  += solution[dofs[a * dim + c]] * gradients[a];

            QuadraturePointHistory<dim> &state
              = quadrature_point_history[point];
            state.stress
              = E * symmetrize(displacement_gradient) + state.history;
            max_von_mises = std::max(max_von_mises,
                                     material.equivalent_stress(state.stress));
            if (update_history)
              {
                state.history
                  += next_time_step
                     * material.viscoplastic_rate(state.stress,
                                                  &state.plastic_multiplier);
                const double JxW = stress_point_JxW[point];
                for (unsigned int a = 0; a < n_a; ++a)
                  {
                    const Tensor<1, dim> force = state.history * gradients[a];
                    for (unsigned int c = 0; c < dim; ++c)
                      history_load[dofs[a * dim + c]] -= JxW * force[c];
                  }
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
