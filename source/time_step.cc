// One time step of ViscoplasticContact<dim>: the step problem solved by the
// active-set method around the back end (explicit update), or a Newton
// iteration of such problems (implicit update), and the recovery from a
// failed solve.

#include <deal.II/base/exceptions.h>
#include <deal.II/base/timer.h>

#include "time_loop.h"
#include "viscoplastic_contact.h"

#include <cmath>
#include <iomanip>

namespace ViscoContact
{
  // @sect4{ViscoplasticContact::solve_step_with_recovery}
  //
  // One time step, and what happens when its solve fails (the active-set,
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
  ViscoplasticContact<dim>::solve_step_with_recovery(const unsigned int   n,
                                                     std::vector<double> &times)
  {
    const VectorType          start_solution = solution;
    const ContactNodes::State start_contact  = contact_set.state();
    const bool                explicit_history
      = parameters.plasticity
        && parameters.stress_update == Parameters::StressUpdate::explicit_euler;

    while (true)
      {
        const double k = times[n] - times[n - 1];
        assemble_right_hand_side(times[n]);
        const ActiveSetResult result
          = (parameters.stress_update
                 == Parameters::StressUpdate::implicit_euler
               ? solve_implicit_step(k)
               : solve_explicit_step());
        if (result.converged)
          return result;

        const std::array<unsigned int, 3> states = count_contact_states();
        solution                                 = start_solution;
        solution.update_ghost_values();
        contact_set.set_state(start_contact);
        if (cut_failed_step(parameters, pcout, n, times, result.failure))
          {
            if (explicit_history)
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



  // @sect4{ViscoplasticContact::solve_contact_problem}
  //
  // One step problem with the operator the back end holds and the
  // right-hand side rhs: the active-set iteration of ContactNodes around
  // the back end's solves for fixed pieces, then the displacement of the
  // final pieces. Without contact it is one solve. The displacement is
  // left in solution (with its constrained entries and ghosts set).
  template <int dim>
  ActiveSetResult
  ViscoplasticContact<dim>::solve_contact_problem(const VectorType &rhs)
  {
    TimerOutput::Scope t(computing_timer, "Solve: contact problem");
    ActiveSetResult    result;
    // The back ends work on the locally owned entries; the ghosts are
    // imported again once the displacement is final.
    solution.zero_out_ghost_values();
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
        contact_solver->set_right_hand_side(rhs, contact_set);
        result = contact_set.solve(
          [&]() {
            return contact_solver->solve_for_pieces(contact_set, solution);
          },
          parameters.max_iterations,
          parameters.tolerance,
          mpi_communicator);
        if (result.converged)
          contact_solver->finish(contact_set, solution);
      }
    total_inner_iterations += result.inner_iterations();
    if (!result.converged)
      return result;

    constraints.distribute(solution);
    solution.update_ghost_values();
    if (!std::isfinite(solution.l2_norm()))
      {
        result.converged = false;
        result.failure   = "The displacement is not finite (NaN or Inf).";
      }
    return result;
  }



  // @sect4{ViscoplasticContact::solve_explicit_step}
  //
  // The paper's scheme: the operator is K for the whole run, so a step is
  // one step problem with b_n.
  template <int dim>
  ActiveSetResult
  ViscoplasticContact<dim>::solve_explicit_step()
  {
    const ActiveSetResult result = solve_contact_problem(system_rhs);
    total_active_set_iterations += contact_enabled ? result.iterations() : 0;
    return result;
  }



  // @sect4{ViscoplasticContact::implicit_newton}
  //
  // Newton's method for the step problem of the backward-Euler scheme with
  // the viscous parameter a = k/(2 lambda): linearise sigma(eps(u)) at the
  // current iterate with the consistent tangent, hand the tangent to the
  // back end, solve the linearised contact problem exactly (the active set
  // on the tangent), repeat until the update is at rounding level. The
  // relative size of each update is printed (with Verbose), which shows the
  // quadratic convergence once the contact set has settled. Returns whether
  // it converged; the iterate is updated in place.
  template <int dim>
  bool
  ViscoplasticContact<dim>::implicit_newton(const double     a,
                                            VectorType      &iterate,
                                            ActiveSetResult &result)
  {
    VectorType rhs(solution);
    for (unsigned int newton = 1; newton <= parameters.max_iterations; ++newton)
      {
        iterate.update_ghost_values();
        assemble_tangent_system(iterate, a);
        // K_T u_new = f - F_int(u) + K_T u - N^T z.
        tangent_matrix.vmult(rhs, iterate);
        rhs += system_rhs;
        rhs -= internal_force;
        {
          TimerOutput::Scope t(computing_timer, "Solve: set up tangent");
          if (contact_enabled)
            contact_set.set_operator(tangent_matrix);
          contact_solver->set_operator(tangent_matrix, false, contact_set);
        }
        solution                         = iterate;
        const ActiveSetResult linearised = solve_contact_problem(rhs);
        result.earlier_inner_iterations  = result.inner_iterations();
        result.earlier_iterations += result.history.size();
        result.earlier_inner_iterations += linearised.earlier_inner_iterations;
        result.history   = linearised.history;
        result.converged = linearised.converged;
        result.failure   = linearised.failure;
        ++total_newton_iterations;
        if (!linearised.converged)
          {
            if (parameters.verbose)
              pcout << "    Newton iteration " << newton
                    << ": the linearised contact problem was not solved\n";
            return false;
          }
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
    const double    a = time_step / (2 * material.viscosity());
    ActiveSetResult result;
    VectorType      start(solution), iterate(solution);
    for (unsigned int stages = 1; stages <= 64; stages *= 2)
      {
        if (stages > 1 && parameters.verbose)
          pcout << "    Newton did not converge; continuation in "
                   "a = k/(2 lambda) with "
                << stages << " stages\n";
        iterate        = start;
        bool converged = true;
        for (unsigned int stage = 1; stage <= stages && converged; ++stage)
          converged = implicit_newton(a * stage / stages, iterate, result);
        if (converged)
          {
            solution = iterate;
            solution.update_ghost_values();
            result.converged = true;
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



  // @sect4{Contact state}
  //
  // Counts over all ranks: at the rigid limit, in normal-compliance
  // contact, out of contact; and the total contact force.
  template <int dim>
  std::array<unsigned int, 3>
  ViscoplasticContact<dim>::count_contact_states() const
  {
    if (!contact_enabled)
      return {{0, 0, 0}};
    return contact_set.count_states(mpi_communicator);
  }



  template <int dim>
  double
  ViscoplasticContact<dim>::total_contact_force() const
  {
    return contact_enabled ? contact_set.total_force(mpi_communicator) : 0.;
  }



  template class ViscoplasticContact<2>;
  template class ViscoplasticContact<3>;
} // namespace ViscoContact
