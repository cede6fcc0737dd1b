// One time step of ViscoplasticContact<dim>: the step problem solved by the
// active-set method around the back end (explicit update), or a Newton
// iteration of such problems (implicit update), and the recovery from a
// failed solve.

#include <deal.II/base/exceptions.h>
#include <deal.II/base/timer.h>

#include "run/step_control.h"
#include "step_report.h"
#include "viscoplastic_contact.h"

#include <algorithm>
#include <cmath>
#include <iomanip>

namespace ViscoContact
{
  // @sect4{ViscoplasticContact::do_time_step}
  //
  // One time step, from the current time of the schedule to the next: with
  // Initial cycles, step 1 is first solved on coarser meshes (nested
  // iteration, InitialCycles::solve()); then the step problem is solved
  // (solve_step_with_recovery(), which may cut the step), and the stresses
  // sigma_n are updated at every stress point with the history of the next
  // step, whose length is the distance to the next time level where it is
  // known (fixed steps; 0 after the last step, where no history is needed).
  //
  // With adaptive steps the step comes with its error test
  // (StepControl::accept_adaptive_step()): a rejected step is repeated from the
  // state at its start with a shorter step. Only once a step is accepted is the
  // next level known: the controller's step fitted to the targets, and the
  // history is advanced for it.
  template <int dim>
  ActiveSetResult
  ViscoplasticContact<dim>::do_time_step()
  {
    const unsigned int n = schedule.step_number() + 1;
    // Adaptive and cut steps are not counted before the run: their number
    // is bounded here (fixed schedules were checked with the parameters).
    plan.check_step_count(n, schedule.current_time());
    if (n == 1 && plan.initial_cycles() > 0)
      InitialCycles<dim>::solve(*this);
    // A run that starts at rest is on a smooth path from u_0 = 0 on
    // (PredictedStart::starts_at_rest()): checked with the values at t_0 on
    // the mesh of the run (the initial cycles' meshes have fewer contact
    // nodes), whose step 1 solve_step_with_recovery() assembles afresh.
    bool starts_at_rest = false;
    if (n == 1 && parameters.predicted_start)
      {
        assemble_right_hand_side(schedule.current_time());
        VectorType prescribed_start(solution);
        prescribed_start = 0;
        if (prescribed.has_values())
          prescribed.distribute(prescribed_start, constraints);
        starts_at_rest
          = PredictedStart<dim>::starts_at_rest(prescribed_start,
                                                system_rhs,
                                                contact_enabled ? &contact_set
                                                                : nullptr,
                                                mpi_communicator);
      }

    StepStart<dim>  start         = StepControl<dim>::save_start(*this);
    double          proposed_step = 0;
    ActiveSetResult result;
    do
      {
        result = solve_step_with_recovery(start);
        update_stresses(schedule.step_length(),
                        schedule.following_step_length());
    } while (
      schedule.is_adaptive()
      && !StepControl<dim>::accept_adaptive_step(*this, start, proposed_step));

    // u_{n-1} and z_{n-1}, the state the step started from, are what the
    // next step's prediction extrapolates from. The initial state u_0 = 0
    // only if the run starts at rest: a load already present at t = 0 makes
    // the first step a jump, not a piece of a smooth path to extrapolate.
    // (Initial cycles have changed start.solution from u_0.)
    if (parameters.predicted_start && n > 1)
      predicted_start.remember(std::move(start.solution),
                               std::move(start.contact.z));
    else if (starts_at_rest)
      {
        start.solution = 0;
        predicted_start.remember(std::move(start.solution),
                                 std::vector<double>(start.contact.z.size()));
      }
    // Friction: the next step's slip is measured from here.
    if (contact_enabled && contact_set.has_friction())
      contact_set.accept_slip(contact_set.tangential_displacements(solution),
                              schedule.step_length());
    // The laws with a history keep this step's: the memory and the bonding
    // its penetrations, the wear its pressures and slips (those of
    // accept_slip()); the nodes then show the accepted state (the worn
    // depth after the step; the next step's gaps).
    for (ContactHistory *history : contact_histories.all())
      if (contact_enabled && history->active())
        {
          history->accept_step(contact_set);
          history->apply_accepted(contact_set);
        }
    schedule.advance_time(proposed_step);
    if (schedule.is_adaptive() && parameters.explicit_history_update()
        && !schedule.is_at_end())
      advance_history(schedule.step_length());
    return result;
  }



  // @sect4{ViscoplasticContact::solve_step_with_recovery}
  //
  // The step problem, and what happens when its solve fails (the active-set,
  // Krylov or Newton iteration reaches its limit, or the displacement is
  // not finite): the state at the start of the step is restored, and
  // either the step is cut in half (the other half becomes the next step
  // of the schedule; with the explicit update the history increment
  // H_n - H_{n-1} = k G(sigma_{n-1}) is rescaled to the new k) or, when
  // cutting is not asked for or would go below Minimum time step, the last
  // accepted state is written to failed_step_NNNN.pvtu and the run stops
  // with a report. All failure criteria are reduced over the ranks, so
  // every rank takes the same decision.
  template <int dim>
  ActiveSetResult
  ViscoplasticContact<dim>::solve_step_with_recovery(
    const StepStart<dim> &start)
  {
    // Each pass is one attempt with the current schedule; a cut shortens the
    // step and the next pass tries the shorter one. The loop ends by
    // returning a converged result or by throwing.
    while (true)
      {
        // The right-hand side depends on t_n, which a cut has changed.
        const double k = schedule.step_length();
        assemble_right_hand_side(schedule.next_time());
        // The memory pressures and the bonding of this step, from the
        // history at its start (its length k too, which a cut has changed).
        for (ContactHistory *history : contact_histories.all())
          if (contact_enabled && history->active())
            history->start_step(k, contact_set);
        // A moving obstacle carries its sticking nodes over the step.
        if (contact_enabled && contact_zones.has_obstacle_motion()
            && contact_set.has_friction())
          contact_set.set_obstacle_steps(
            contact_zones.obstacle_steps(schedule.current_time(),
                                         schedule.next_time()));
        // The start of the step: extrapolated from the two before it
        // (acceleration/predicted_start.h), then from the coarser meshes.
        if (parameters.predicted_start && schedule.step_number() >= 1)
          predicted_start.predict(schedule.step_length()
                                    / schedule.previous_step_length(),
                                  solution,
                                  contact_enabled ? &contact_set : nullptr);
        if (step_cycles.due(*this))
          step_cycles.start_from_coarser_mesh(*this, start.solution);
        // The step starts with the displacement prescribed at t_n (the
        // implicit update's first Newton iterate must have it).
        if (prescribed.has_values())
          {
            prescribed.distribute(solution, constraints);
            solution.update_ghost_values();
          }
        const ActiveSetResult result
          = (parameters.implicit_update() ? solve_implicit_step(k)
                                          : solve_explicit_step());
        if (result.converged)
          return result;

        // The contact counts of the failed iterate, for the report (collective,
        // before the state is restored). Then back to u_{n-1} with its ghosts,
        // and to the pieces the step started from.
        const std::array<unsigned int, 3> states
          = contact_set.count_states(mpi_communicator);
        StepControl<dim>::restore_start(*this, start);
        if (StepControl<dim>::cut_failed_step(*this, result.failure))
          {
            if (parameters.explicit_history_update())
              rescale_history_increment(k, schedule.step_length());
            continue;
          }

        // No cut: write the last accepted state (u_{n-1}, sigma_{n-1} at
        // t_{n-1}, as restored above) for inspection, then stop on every rank
        // with the same message: what failed, the iteration history, and what
        // can be changed in the parameter file. Nothing of the failed attempt
        // is written, so the output of the run stays a consistent record of
        // accepted steps.
        const unsigned int n          = schedule.step_number() + 1;
        const std::string  state_file = failed_state_file(n, "pvtu");
        output.write_results(*this, n, schedule.current_time(), "failed_step");
        AssertThrow(false,
                    ExcMessage(failure_report(parameters,
                                              n,
                                              schedule.next_time(),
                                              k,
                                              result,
                                              states,
                                              state_file)));
      }
  }



  // @sect4{ViscoplasticContact::solve_contact_problem}
  //
  // One step problem with the operator the back end holds and the
  // right-hand side rhs: the active-set iteration of ContactNodes around
  // the back end's solves for fixed pieces, then the displacement of the
  // final pieces. Without contact it is one solve. The displacement is
  // left in solution (with its constrained entries and ghosts set).
  //
  // The division of labour: ContactNodes::solve() owns the iteration (move
  // every node to the piece q_i names, stop when no node moved on any rank and
  // the solve met its tolerance, doc/model.md, section 2); the back end only
  // solves the linear problems of fixed pieces and writes r and z of the owned
  // nodes. This function is the same for the explicit step (operator K,
  // right-hand side b_n) and for every Newton iteration of the implicit one
  // (the tangent, its linearised right-hand side).
  template <int dim>
  ActiveSetResult
  ViscoplasticContact<dim>::solve_contact_problem(const VectorType &rhs)
  {
    TimerOutput::Scope t(report.timer(), "Solve: contact problem");
    ActiveSetResult    result;
    // The back ends work on the locally owned entries; the ghosts are imported
    // again once the displacement is final. Ghost entries would be stale while
    // the solvers write into the vector, and a deal.II vector in its ghosted
    // state cannot be compressed; the full space back end uses the owned
    // entries of solution as its starting guess.
    solution.zero_out_ghost_values();
    // No contact nodes: the displacement is A^{-1} rhs, one solve of the back
    // end (a Krylov solve or the factorisation).
    if (!contact_enabled)
      {
        const LinearSolveReport report
          = contact_solver->solve_without_contact(rhs, solution);
        result.converged                = report.converged;
        result.failure                  = report.failure;
        result.earlier_inner_iterations = report.inner_iterations;
      }
    else
      {
        // With contact: the back end takes the right-hand side first (the
        // condensed back end computes d = N A^{-1} b here, one solve; the full
        // space back end keeps b), and each active-set iteration then asks it
        // for the (r, z) of the current pieces. The iteration warm-starts from
        // the pieces the nodes are on: those of the previous step or Newton
        // iteration.
        contact_solver->set_right_hand_side(rhs, contact_set);
        result = contact_set.solve(
          [&](const LinearSolveRequest &request) {
            return contact_solver->solve_for_pieces(contact_set,
                                                    solution,
                                                    request);
          },
          parameters.max_iterations,
          parameters.tolerance,
          mpi_communicator);
        // finish() gives the displacement of the final pieces: u =
        // A^{-1} b - W z on the condensed back end, nothing to do on the full
        // space back end, whose last solve left u in solution.
        if (result.converged)
          contact_solver->finish(contact_set, solution);
      }
    report.count_inner_iterations(result.inner_iterations());
    if (!result.converged)
      return result;

    // The constrained entries (Dirichlet, hanging, symmetry) get their
    // values from the constraints and g_n, then the ghosts are imported so
    // that the stress update can read every dof of the owned cells.
    prescribed.distribute(solution, constraints);
    solution.update_ghost_values();
    // A NaN or Inf anywhere makes the global norm non-finite on every rank
    // (l2_norm() is a reduction), so all ranks declare the failure together.
    if (!std::isfinite(solution.l2_norm()))
      {
        result.converged = false;
        result.failure   = "The displacement is not finite (NaN or Inf).";
      }
    return result;
  }



  // @sect4{ViscoplasticContact::solve_explicit_step}
  //
  // The paper's scheme: the operator is K for the whole run, so a step is one
  // step problem with b_n. All of the viscoplasticity is in the history load of
  // b_n, computed from the previous step's stresses; the back end keeps the
  // factorisation or preconditioner of K from set-up.
  template <int dim>
  ActiveSetResult
  ViscoplasticContact<dim>::solve_explicit_step()
  {
    const ActiveSetResult result = solve_contact_problem(system_rhs);
    report.count_active_set_iterations(result.iterations());
    return result;
  }



  // @sect4{ViscoplasticContact::implicit_newton}
  //
  // Newton's method for the step problem of the backward-Euler scheme with
  // the step length k (the viscous parameter a = k/(2 lambda) of each
  // material): linearise sigma(eps(u)) at the
  // current iterate with the consistent tangent, hand the tangent to the
  // back end, solve the linearised contact problem exactly (the active set
  // on the tangent), repeat until the update is at rounding level. The
  // relative size of each update is printed (with Verbose), which shows the
  // quadratic convergence once the contact set has settled. Returns whether
  // it converged; the iterate is updated in place.
  //
  // The contact law is not linearised: every Newton iteration solves a complete
  // contact problem with the piecewise-linear law kept exactly, so Newton only
  // has to deal with the nonlinearity of the stress update. The active set of
  // each iteration starts from the pieces of the previous one, so once the
  // contact zone has settled it needs few iterations.
  template <int dim>
  bool
  ViscoplasticContact<dim>::implicit_newton(const double     time_step,
                                            VectorType      &iterate,
                                            ActiveSetResult &result)
  {
    VectorType rhs(solution);
    for (unsigned int newton = 1; newton <= parameters.max_iterations; ++newton)
      {
        // The tangent assembly reads the displacement at every dof of the owned
        // cells, the ghosts included.
        iterate.update_ghost_values();
        assemble_tangent_system(iterate, time_step);
        // K_T u_new = f - F_int(u) + K_T u - N^T z.
        tangent_matrix.vmult(rhs, iterate);
        rhs += system_rhs;
        rhs -= internal_force;
        // The tangent is the step's operator for this iteration: the parameters
        // c_i are recomputed from its diagonal blocks, and the back end sets it
        // up anew (a factorisation and the compliance, or an AMG hierarchy). It
        // is passed as unsymmetric: in 2D plane stress it is, and GMRES or an
        // LU factorisation work in either case.
        {
          TimerOutput::Scope t(report.timer(), "Solve: set up tangent");
          if (contact_enabled)
            contact_set.set_operator(tangent_matrix);
          contact_solver->set_operator(tangent_matrix, false, contact_set);
        }
        // The full space back end starts its Krylov solve from the current
        // iterate.
        solution                         = iterate;
        const ActiveSetResult linearised = solve_contact_problem(rhs);
        // The statistics of the step accumulate over the Newton iterations: the
        // earlier iterations and Krylov iterations are moved to the earlier_*
        // counters, and history holds the last active-set run, whose
        // convergence decides.
        result.earlier_inner_iterations = result.inner_iterations();
        result.earlier_iterations += result.history.size();
        result.earlier_inner_iterations += linearised.earlier_inner_iterations;
        result.history   = linearised.history;
        result.converged = linearised.converged;
        result.failure   = linearised.failure;
        report.count_newton_iteration();
        if (!linearised.converged)
          {
            if (parameters.verbose)
              pcout << "    Newton iteration " << newton
                    << ": the linearised contact problem was not solved\n";
            return false;
          }
        // The relative change in the maximum norm; linfty_norm() is a maximum
        // over the ranks, so every rank sees the same number and takes the same
        // decision below.
        VectorType change(solution);
        change -= iterate;
        const double relative_change
          = change.linfty_norm() / std::max(solution.linfty_norm(), 1e-300);
        iterate = solution;
        if (parameters.verbose)
          pcout << "    Newton iteration " << newton
                << ": |du|/|u| = " << std::scientific << std::setprecision(2)
                << relative_change << std::defaultfloat
                << ", active-set iterations " << linearised.iterations()
                << '\n';
        if (!std::isfinite(relative_change))
          return false;
        if (relative_change <= 1e-11)
          return true;
        // Converging Newton iterations are near rounding level long before
        // ten steps; still far away then, the iteration is not going to
        // converge from here, and the caller's continuation takes over.
        if (newton >= 10 && relative_change > 1e-4)
          return false;
      }
    return false;
  }



  // @sect4{ViscoplasticContact::solve_implicit_step}
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
  ActiveSetResult
  ViscoplasticContact<dim>::solve_implicit_step(const double time_step)
  {
    // Every attempt starts from the state at the start of the step (start);
    // iterate carries the solution from stage to stage.
    ActiveSetResult result;
    VectorType      start(solution), iterate(solution);
    // stages = 1 is plain Newton with the step's own a; then 2, 4, ..., 64
    // stages.
    for (unsigned int stages = 1; stages <= 64; stages *= 2)
      {
        if (stages > 1 && parameters.verbose)
          pcout << "    Newton did not converge; continuation in "
                   "a = k/(2 lambda) with "
                << stages << " stages\n";
        iterate        = start;
        bool converged = true;
        // The stages of one attempt: a/J, 2a/J, ..., a (k/J, 2k/J, ..., k in
        // a = k/(2 lambda)), each from the previous stage's solution; the
        // attempt fails as soon as one stage fails.
        for (unsigned int stage = 1; stage <= stages && converged; ++stage)
          converged
            = implicit_newton(time_step * stage / stages, iterate, result);
        // The last stage was the step's own problem: its solution is u_n.
        if (converged)
          {
            solution = iterate;
            solution.update_ghost_values();
            result.converged = true;
            report.count_active_set_iterations(result.iterations());
            return result;
          }
      }
    // No number of stages helped: report the failure to
    // solve_step_with_recovery(), which cuts the step or stops.
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



  // @sect4{ViscoplasticContact::rescale_history_increment}
  //
  // H_n = H_{n-1} + k G(sigma_{n-1}) was computed with the step length k
  // the schedule had; a cut step needs it with k': H_n += (k' - k) G.
  // sigma_{n-1} is unchanged by the failed attempt, so G is the same.
  //
  // Each rank updates the stress points of its own cells; the history load of
  // the new step is then assembled anew from them (the one update_stresses()
  // assembled belongs to the old k).
  template <int dim>
  void
  ViscoplasticContact<dim>::rescale_history_increment(const double old_step,
                                                      const double new_step)
  {
    const unsigned int n_q = discretisation.n_stress_points();
    for (unsigned int k = 0; k < stress_points.cells().size(); ++k)
      if (materials.of_cell(k).is_plastic())
        for (unsigned int q = 0; q < n_q; ++q)
          {
            QuadraturePointHistory<dim> &state
              = quadrature_point_history[std::size_t(k) * n_q + q];
            double stress_zz = 0, rate_zz = 0;
            if constexpr (dim == 2)
              stress_zz = state.stress_zz;
            state.history
              += (new_step - old_step)
                 * materials.of_cell(k).rate(state.stress,
                                             stress_zz,
                                             rate_zz,
                                             state.internal_variable);
            if constexpr (dim == 2)
              state.history_zz += (new_step - old_step) * rate_zz;
          }
    assemble_history_load();
  }



  template class ViscoplasticContact<2>;
  template class ViscoplasticContact<3>;
} // namespace ViscoContact
