// ViscoplasticContact<dim>: the constructor, the algorithm (run), and the
// access the convergence study needs.

#include <deal.II/base/exceptions.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/utilities.h>

#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_simplex_p.h>
#include <deal.II/fe/fe_system.h>

#include "loads.h"
#include "time_loop.h"
#include "viscoplastic_contact.h"

namespace ViscoContact
{
  namespace
  {
    template <int dim>
    ReferenceCell
    reference_cell_of(const Parameters::AllParameters &parameters)
    {
      return parameters.cell_type == Parameters::CellType::simplex
               ? ReferenceCells::get_simplex<dim>()
               : ReferenceCells::get_hypercube<dim>();
    }

    template <int dim>
    std::unique_ptr<FiniteElement<dim>>
    linear_element(const ReferenceCell &cell)
    {
      if (cell.is_simplex())
        return std::make_unique<FE_SimplexP<dim>>(1);
      return std::make_unique<FE_Q<dim>>(1);
    }
  } // namespace



  // @sect4{ViscoplasticContact::ViscoplasticContact}
  //
  // The choice between simplices and hypercubes is made here, once: the
  // reference cell gives the mapping, the finite element (P1 or Q1) and
  // the quadratures, and everything else is written for either. On
  // simplices the P1 strain is constant per cell and one stress point per
  // cell is the piecewise-constant stress space; on hypercubes the stresses
  // live at the 2^dim Gauss points.
  template <int dim>
  ViscoplasticContact<dim>::ViscoplasticContact(
    const Parameters::AllParameters &parameters,
    const MPI_Comm                   communicator)
    : parameters(parameters)
    , mpi_communicator(communicator)
    , pcout(std::cout, Utilities::MPI::this_mpi_process(communicator) == 0)
    , computing_timer(communicator,
                      pcout,
                      TimerOutput::never,
                      TimerOutput::wall_times)
    , reference_cell(reference_cell_of<dim>(parameters))
    , mapping(reference_cell.template get_default_linear_mapping<dim>())
    , fe(std::make_unique<FESystem<dim>>(*linear_element<dim>(reference_cell),
                                         dim))
    , scalar_fe(linear_element<dim>(reference_cell))
    , stress_quadrature(reference_cell.template get_gauss_type_quadrature<dim>(
        reference_cell.is_simplex() ? 1 : 2))
    , load_quadrature(reference_cell.template get_gauss_type_quadrature<dim>(2))
    , face_quadrature(reference_cell.face_reference_cell(0)
                        .template get_gauss_type_quadrature<dim - 1>(2))
    , material(parameters.young_modulus,
               parameters.poisson_ratio,
               parameters.viscosity,
               parameters.yield_stress)
    , body_force(dim)
    , surface_traction(dim)
  {
    AssertThrow(parameters.dimension == dim, ExcInternalError());
    initialize_load(body_force,
                    "Body force",
                    parameters.body_force,
                    parameters.lengths);
    initialize_load(surface_traction,
                    "Surface traction",
                    parameters.surface_traction,
                    parameters.lengths);
    body_force_is_zero   = is_zero_expression(parameters.body_force);
    loads_depend_on_time = mentions_time(parameters.body_force)
                           || mentions_time(parameters.surface_traction);
  }



  template <int dim>
  ViscoplasticContact<dim>::~ViscoplasticContact()
  {
    // The DoFHandlers refer to the triangulation: release them first.
    scalar_dof_handler.clear();
    dof_handler.clear();
  }



  // @sect4{ViscoplasticContact::run}
  //
  // The algorithm of doc/model.md, section 2, as the reader would write it
  // down: set up, then for each time step assemble the right-hand side,
  // solve the step's variational-hemivariational inequality by the
  // active-set method (for the implicit update: a Newton iteration of such
  // solves), update the stresses and the history, and write the results.
  // Around it: a resumed run starts after the step of its checkpoint, a
  // checkpoint is written every Checkpoint interval steps, and a run may be
  // told to stop after a given step (as if it had been killed).
  template <int dim>
  void
  ViscoplasticContact<dim>::run()
  {
    make_grid();
    setup_system();
    setup_stress_points();
    setup_contact();
    setup_back_end();

    std::vector<double> times
      = time_levels(parameters.end_time, parameters.time_step);
    unsigned int first_step = 1;
    if (parameters.resume)
      first_step = resume_from_checkpoint(times) + 1;
    prepare_output_directory();
    n_time_steps = times.size() - 1;
    print_header(n_time_steps);
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
        Timer                 step_timer;
        const ActiveSetResult result = solve_step_with_recovery(n, times);
        update_stresses(times[n] - times[n - 1],
                        n + 1 < times.size() ? times[n + 1] - times[n] : 0.);
        time_loop_compute_time += step_timer.wall_time();
        n_time_steps = times.size() - 1;
        n_steps_done = n;
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
        if (contact_enabled && is_profile_step(n))
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



  // @sect4{Access for studies}
  template <int dim>
  void
  ViscoplasticContact<dim>::set_step_observer(
    const std::function<void(const unsigned int, const double)> &observer)
  {
    step_observer = observer;
  }



  template <int dim>
  const DoFHandler<dim> &
  ViscoplasticContact<dim>::get_dof_handler() const
  {
    return dof_handler;
  }



  template <int dim>
  const Quadrature<dim> &
  ViscoplasticContact<dim>::get_stress_quadrature() const
  {
    return stress_quadrature;
  }



  template <int dim>
  const std::vector<typename DoFHandler<dim>::active_cell_iterator> &
  ViscoplasticContact<dim>::get_owned_cells() const
  {
    return owned_cells;
  }



  template <int dim>
  const SymmetricTensor<2, dim> &
  ViscoplasticContact<dim>::get_stress(const unsigned int k,
                                       const unsigned int q) const
  {
    return quadrature_point_history[std::size_t(k) * stress_quadrature.size()
                                    + q]
      .stress;
  }



  template <int dim>
  Tensor<2, dim>
  ViscoplasticContact<dim>::get_displacement_gradient(
    const unsigned int k,
    const unsigned int q) const
  {
    return displacement_gradient_at(solution, k, q);
  }



  template <int dim>
  double
  ViscoplasticContact<dim>::get_stress_point_weight(const unsigned int k,
                                                    const unsigned int q) const
  {
    return stress_point_JxW[std::size_t(k) * stress_quadrature.size() + q];
  }



  template class ViscoplasticContact<2>;
  template class ViscoplasticContact<3>;
} // namespace ViscoContact
