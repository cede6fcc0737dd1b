// The stress update of ViscoplasticContact<dim>: sigma_n at every stress
// point, and the history of the next step with its load. The work at one
// stress point and one cell is in functions of this file, where the hot
// loop of the explicit update can inline them.

#include <deal.II/base/exceptions.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/parallel.h>
#include <deal.II/base/timer.h>

#include "viscoplastic_contact.h"

#include <array>
#include <cstdlib>
#include <cmath>
#include <limits>
#include <sstream>

namespace ViscoContact
{
  namespace
  {
    // What update_stresses() does at every stress point of a step: which
    // update, whether the history of the next step and the error estimate
    // are computed, and the two step lengths.
    struct StressUpdateStep
    {
      bool   implicit;
      bool   update_history;
      bool   estimate;
      double current_time_step;
      double next_time_step;
    };

    // What the stress points do in this update: which update, whether the
    // history of the next step is computed, and whether the error estimate is.
    // With plasticity off the stresses are elastic and the history stays zero.
    // The history of the next step is only needed if there is a next step
    // (next_time_step > 0); the run summary calls update_stresses() again for
    // its cost measurement, with the time step of the parameter file. The
    // error estimate of the step (doc/adaptivity.md) needs the history rate
    // G(sigma_n) at every stress point. The explicit update evaluates it
    // anyway for the next history (also after the last step, for the
    // estimate), the implicit one has it as the history increment divided by
    // k_n; without plasticity there is no history and no estimate.
    StressUpdateStep
    stress_update_step(const Parameters::AllParameters &parameters,
                       const double                     current_time_step,
                       const double                     next_time_step)
    {
      return {parameters.implicit_update(),
              parameters.explicit_history_update() && next_time_step > 0,
              parameters.any_plasticity() && current_time_step > 0,
              current_time_step,
              next_time_step};
    }



    // An unstable explicit update ends in stresses that overflow: stop rather
    // than go on with (and write) infinite or NaN fields. The limit and the
    // step are printed with 6 significant digits (a fixed format would print a
    // tiny limit as 0).
    [[noreturn]] void
    stop_on_non_finite_stresses(const double stability_limit,
                                const double time_step)
    {
      std::ostringstream message;
      message << "The stresses are no longer finite (NaN or Inf). With the "
                 "explicit history update this means the time step is too "
                 "large: it is stable for k < 4 lambda / lambda_max(E) = "
              << stability_limit
              << " s (doc/model.md, section 3); <Time step> in subsection "
                 "<Time> is "
              << time_step << " s.";
      AssertThrow(false, ExcMessage(message.str()));
      std::abort();
    }



    // Implicit: the trial stress is E eps(u_n) plus the stored history
    // sigma_{n-1} - E eps(u_{n-1}); the backward-Euler update projects it (no
    // tangent needed here), and the new history is the non-elastic part of
    // sigma_n; its rate, for the estimate, follows from sigma_n = trial +
    // k_n G(sigma_n). Explicit: sigma_n = E eps(u_n) + H_n, with H_n stored by
    // the previous step, then H_{n+1} = H_n + k_{n+1} G(sigma_n) with the
    // plastic multiplier as the starting guess of the projection (the caller
    // adds the point's contribution -(H_{n+1}, eps(v)) JxW to the next step's
    // load). strain is eps(u_n) at the point, JxW its weight.
    //
    // In 2D plane strain the zz components of sigma, H and G follow the same
    // formulas (the zz component of E eps(u) is lambda tr eps(u)); they enter
    // the von Mises stress and the projection, not the load (eps_zz(v) = 0).
    template <int dim>
    void
    update_stress_point(const StressUpdateStep        &step,
                        const MaterialLaw<dim>        &material,
                        const SymmetricTensor<2, dim> &strain,
                        const double                   JxW,
                        QuadraturePointHistory<dim>   &state,
                        double                        &max_von_mises_of_cell,
                        std::array<double, 3>         &estimate_sums)
    {
      const SymmetricTensor<2, dim> elastic_stress
        = material.elasticity_tensor() * strain;
      // The zz components (a copy, written back at the end; zero but in 2D
      // plane strain).
      OutOfPlaneState<2> zz;
      if constexpr (dim == 2)
        zz = state;
      const double elastic_zz = material.out_of_plane_elastic_stress(strain);
      // An elastic material has no history: its stress is elastic, it has no
      // rate and no load, and only its stress counts in the estimate.
      const bool              plastic = material.is_plastic();
      SymmetricTensor<2, dim> rate;
      double                  rate_zz = 0;
      if (plastic && step.implicit)
        {
          state.stress
            = material.implicit_update(elastic_stress + state.history,
                                       elastic_zz + zz.history_zz,
                                       step.current_time_step,
                                       zz.stress_zz,
                                       nullptr,
                                       state.internal_variable);
          const SymmetricTensor<2, dim> new_history
            = state.stress - elastic_stress;
          const double new_history_zz = zz.stress_zz - elastic_zz;
          if (step.estimate)
            {
              rate = (new_history - state.history) / step.current_time_step;
              rate_zz
                = (new_history_zz - zz.history_zz) / step.current_time_step;
            }
          state.history = new_history;
          zz.history_zz = new_history_zz;
        }
      else
        {
          state.stress = elastic_stress + state.history;
          zz.stress_zz = elastic_zz + zz.history_zz;
        }
      // The largest von Mises stress, for the time series. std::max would
      // silently drop a NaN, so a non-finite value is recorded as infinity,
      // which survives the maximum over the ranks.
      const double von_mises
        = material.equivalent_stress(state.stress, zz.stress_zz);
      max_von_mises_of_cell = std::isfinite(von_mises)
                                ? std::max(max_von_mises_of_cell, von_mises)
                                : std::numeric_limits<double>::infinity();
      if (plastic && !step.implicit && (step.update_history || step.estimate))
        rate = material.rate(state.stress,
                             zz.stress_zz,
                             rate_zz,
                             state.internal_variable);
      if (plastic && step.update_history)
        {
          state.history += step.next_time_step * rate;
          zz.history_zz += step.next_time_step * rate_zz;
        }
      // The estimate's terms at this point (per cell: the sums of
      // (E^-1 dG, dG) JxW with dG = G(sigma_n) - G(sigma_{n-1}), of
      // (E^-1 sigma_n, sigma_n) JxW and of sigma_Y^2 / lambda_max(E) JxW), and
      // the rate kept for the next step's estimate.
      if (step.estimate)
        {
          estimate_sums[1]
            += material.complementary_energy(state.stress, zz.stress_zz) * JxW;
          if (plastic)
            {
              estimate_sums[0]
                += material.complementary_energy(rate - state.rate,
                                                 rate_zz - zz.rate_zz)
                   * JxW;
              estimate_sums[2] += material.yield_stress()
                                  * material.yield_stress()
                                  / material.largest_elastic_eigenvalue() * JxW;
              state.rate = rate;
              zz.rate_zz = rate_zz;
            }
        }
      if constexpr (dim == 2)
        static_cast<OutOfPlaneState<2> &>(state) = zz;
    }



    // The relative error estimate of the step (doc/adaptivity.md): the
    // difference between the forward-Euler history increment k_n G(sigma_{n-1})
    // (backward Euler: k_n G(sigma_n)) and the trapezoidal one
    // k_n/2 (G(sigma_{n-1}) + G(sigma_n)), in the energy norm
    // (E^-1 tau, tau)^(1/2) over the body, relative to the stress in the same
    // norm, but at least to sigma_Y (|Omega| / lambda_max(E))^(1/2) (over the
    // viscoplastic materials), the size of a stress at the yield limit, so
    // that an unloaded body does not make the estimate blow up. The sums are
    // added in the order of the cells, so the estimate does not depend on the
    // number of threads; one sum over the ranks.
    double
    step_error_estimate(const std::array<double, 3> &local_sums,
                        const double                 time_step,
                        const MPI_Comm               communicator)
    {
      std::array<double, 3> sums = {{0., 0., 0.}};
      Utilities::MPI::sum(ArrayView<const double>(local_sums.data(), 3),
                          communicator,
                          ArrayView<double>(sums.data(), 3));
      const double scale = std::max(std::sqrt(sums[1]), std::sqrt(sums[2]));
      return time_step / 2 * std::sqrt(sums[0])
             / std::max(scale, std::numeric_limits<double>::min());
    }


    // The stress points of the k-th owned cell, whose records start at
    // records, by update_stress_point() from eps(u_n) (u with its ghosts, as
    // solve_contact_problem() leaves it); with the history update the cell's
    // load -(H_{n+1}, eps(v)) JxW into cell_vector (ordered (vertex,
    // component)). The largest von Mises stress of the cell and its terms of
    // the estimate are added to max_von_mises_of_cell and estimate_sums.
    template <int dim>
    void
    update_cell(const StressUpdateStep         &step,
                const MaterialLaw<dim>         &material,
                const StressPointGeometry<dim> &geometry,
                const VectorType               &u,
                const unsigned int              k,
                QuadraturePointHistory<dim>    *records,
                const ArrayView<double>        &cell_vector,
                double                         &max_von_mises_of_cell,
                std::array<double, 3>          &estimate_sums)
    {
      std::fill(cell_vector.begin(), cell_vector.end(), 0.);
      for (unsigned int q = 0; q < geometry.n_points(); ++q)
        {
          update_stress_point(step,
                              material,
                              symmetrize(
                                geometry.displacement_gradient(u, k, q)),
                              step.estimate ? geometry.JxW(k, q) : 0.,
                              records[q],
                              max_von_mises_of_cell,
                              estimate_sums);
          if (material.is_plastic() && step.update_history)
            geometry.add_load(-records[q].history, k, q, cell_vector);
        }
    }

  } // namespace



  // @sect4{ViscoplasticContact::update_stresses}
  //
  // sigma_n = E eps(u_n) + H_n at every stress point of the locally owned
  // cells, and, with plasticity, the explicit history update
  // H_{n+1} = H_n + k_{n+1} G(sigma_n) of doc/model.md, section 2. The
  // same loop assembles -(H_{n+1}, eps(v)), the history load of the next
  // step, so the stress points are visited once per step. The projection
  // onto the stress space is the identity here: E eps(u_n) is piecewise
  // constant on P1 simplices, and on hypercubes the stresses are stored at
  // the quadrature points themselves.
  //
  // With the implicit update, sigma_n solves the backward-Euler equation at
  // each stress point (as in the last Newton iteration), and the history of
  // the next step is what of sigma_n is not elastic.
  //
  // This is where the explicit and the implicit update differ, and why the
  // explicit one is cheap: its step problem has the constant operator K, and
  // all of the plasticity happens here, one evaluation of G per stress point,
  // pointwise; the only communication is the compress() of the history load and
  // one scalar maximum. The price is the stability limit
  // k < 4 lambda / lambda_max(E) (doc/model.md, section 3). The implicit update
  // has no limit, but its Newton iteration needs a tangent and a new set-up of
  // the back end per iteration; here it only recomputes the converged stress.
  //
  // The field state.history means, between steps, the history of the next step:
  // H_{n+1} for the explicit update, sigma_n - E eps(u_n) for the implicit one
  // (the bracket of the trial stress of doc/model.md, section 3). In both cases
  // the step problem of step n+1 reads it as it is.
  template <int dim>
  void
  ViscoplasticContact<dim>::update_stresses(const double current_time_step,
                                            const double next_time_step)
  {
    TimerOutput::Scope     t(report.timer(), "Stress update");
    const StressUpdateStep step
      = stress_update_step(parameters, current_time_step, next_time_step);
    const unsigned int n_q     = discretisation.n_stress_points();
    const unsigned int n_local = stress_points.n_vertices() * dim;

    // The work at the stress points is independent from point to point, so
    // the threads of this rank (as many as deal.II's MultithreadInfo allows:
    // the cores of a node shared among its ranks) share it. Only the
    // addition of the cells' loads into history_load would collide (two
    // cells share dofs): it is done afterwards, by one thread, in the order
    // of the cells, so the result does not depend on the number of threads.
    // The cells are taken in chunks, which bounds the buffer of cell loads;
    // each cell's load goes straight into its slot of the buffer.
    const unsigned int  chunk_size = 4096;
    std::vector<double> cell_loads(step.update_history ? chunk_size * n_local
                                                       : 0);
    const auto          cell_load = [&](const unsigned int slot) {
      return step.update_history
                        ? ArrayView<double>(cell_loads.data()
                                     + std::size_t(slot) * n_local,
                                   n_local)
                        : ArrayView<double>();
    };
    std::vector<double>                cell_max_von_mises(chunk_size);
    std::vector<std::array<double, 3>> cell_estimate_sums(chunk_size);

    // history_load is rebuilt from zero, ghost entries included; each cell adds
    // into it below.
    if (step.update_history)
      history_load = 0;
    double                local_max_von_mises = 0;
    std::array<double, 3> local_sums          = {{0., 0., 0.}};
    // Each rank visits the stress points of its own cells only; the record of
    // stress point q of the k-th owned cell is entry k * n_q + q.
    const unsigned int n_cells = stress_points.cells().size();
    for (unsigned int first = 0; first < n_cells; first += chunk_size)
      {
        const unsigned int end = std::min(first + chunk_size, n_cells);
        parallel::apply_to_subranges(
          first,
          end,
          [&](const unsigned int begin, const unsigned int stop) {
            for (unsigned int k = begin; k < stop; ++k)
              {
                cell_max_von_mises[k - first] = 0.;
                cell_estimate_sums[k - first] = {{0., 0., 0.}};
                update_cell(step,
                            materials.of_cell(k),
                            stress_points,
                            solution,
                            k,
                            &quadrature_point_history[std::size_t(k) * n_q],
                            cell_load(k - first),
                            cell_max_von_mises[k - first],
                            cell_estimate_sums[k - first]);
              }
          },
          256);
        // The serial part: the loads into history_load, cell by cell.
        for (unsigned int k = first; k < end; ++k)
          {
            local_max_von_mises
              = std::max(local_max_von_mises, cell_max_von_mises[k - first]);
            for (unsigned int i = 0; i < 3; ++i)
              local_sums[i] += cell_estimate_sums[k - first][i];
            if (step.update_history)
              stress_points.distribute(k, cell_load(k - first), history_load);
          }
      }
    // The ghost entries of history_load hold contributions to dofs that other
    // ranks own: compress() adds them there. The maximum von Mises stress is
    // the one scalar reduced over the ranks.
    if (step.update_history)
      history_load.compress(VectorOperation::add);
    max_von_mises = Utilities::MPI::max(local_max_von_mises, mpi_communicator);

    error_estimate
      = step.estimate
          ? step_error_estimate(local_sums, current_time_step, mpi_communicator)
          : 0.;

    if (!std::isfinite(max_von_mises))
      stop_on_non_finite_stresses(materials.explicit_stability_limit(),
                                  schedule.grid_step_length());
  }



  // @sect4{ViscoplasticContact::advance_history}
  //
  // With adaptive steps the length of the next step is only known once the
  // estimate of the current one is: update_stresses() then stores G(sigma_n)
  // at every stress point without updating the history (next_time_step = 0),
  // and this function completes the explicit update,
  // H_{n+1} = H_n + k_{n+1} G(sigma_n), and assembles the load of the next
  // step from it.
  template <int dim>
  void
  ViscoplasticContact<dim>::advance_history(const double next_time_step)
  {
    TimerOutput::Scope t(report.timer(), "Stress update");
    for (QuadraturePointHistory<dim> &state : quadrature_point_history)
      {
        state.history += next_time_step * state.rate;
        if constexpr (dim == 2)
          state.history_zz += next_time_step * state.rate_zz;
      }
    assemble_history_load();
  }



  template class ViscoplasticContact<2>;
  template class ViscoplasticContact<3>;
} // namespace ViscoContact
