// The convergence study: runs at several resolutions compared exactly with
// a reference run on the reference mesh.

#include <deal.II/base/exceptions.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/base/timer.h>

#include <deal.II/fe/fe_values.h>

#include "convergence_study.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <map>
#include <sstream>

namespace ViscoContact
{
  template <int dim>
  ConvergenceStudy<dim>::ConvergenceStudy(
    const Parameters::AllParameters &parameters)
    : parameters(parameters)
  {}



  // Each run is the scene of the parameter file at its own resolution,
  // without graphical output and terminal chatter, writing its time series
  // into a subdirectory of the study's output directory.
  template <int dim>
  Parameters::AllParameters
  ConvergenceStudy<dim>::parameters_for(const unsigned int subdivisions,
                                        const double       time_step,
                                        const std::string &name) const
  {
    Parameters::AllParameters run_parameters = parameters;
    run_parameters.subdivisions              = subdivisions;
    run_parameters.time_step                 = time_step;
    run_parameters.study_enabled             = false;
    run_parameters.write_vtu                 = false;
    run_parameters.verbose                   = false;
    run_parameters.print_timing_summary      = false;
    run_parameters.profile_times.clear();
    run_parameters.directory = parameters.directory + "/runs/" + name;

    // The run's copy of the parameter file: the study's file with the
    // entries the study changed appended (later entries win), so that it
    // reproduces the run.
    std::ostringstream changes;
    changes
      << std::setprecision(17)
      << "\n# This run of the convergence study changed these entries:\n"
      << "subsection Convergence study\n  set Enabled = false\nend\n"
      << "subsection Geometry\n  set Subdivisions = " << subdivisions
      << "\nend\n"
      << "subsection Time\n  set Time step = " << time_step << "\nend\n"
      << "subsection Output\n  set Output directory = "
      << run_parameters.directory
      << "\n  set Write vtu = false\n  set Verbose = false\n"
      << "  set Print timing summary = false\n  set Profile times =\nend\n";
    run_parameters.parsed_parameters += changes.str();
    return run_parameters;
  }



  // @sect4{ConvergenceStudy::run}
  //
  // The coarse runs first, keeping their states at every time level; then
  // the reference run, which compares with them at every common time level
  // while it goes.
  template <int dim>
  void
  ConvergenceStudy<dim>::run()
  {
    const unsigned int n_runs = parameters.study_subdivisions.size();
    runs.resize(n_runs);
    for (unsigned int r = 0; r < n_runs; ++r)
      {
        Run &run         = runs[r];
        run.subdivisions = parameters.study_subdivisions[r];
        run.time_step    = parameters.study_time_steps[r];
        std::ostringstream name;
        name << "h_1_" << run.subdivisions << "_k_" << run.time_step;
        std::cout << "Convergence study: run " << r + 1 << " of " << n_runs
                  << ", h = 1/" << run.subdivisions << ", k = " << run.time_step
                  << '\n';
        run.problem = std::make_unique<ViscoplasticContact<dim>>(
          parameters_for(run.subdivisions, run.time_step, name.str()));
        ViscoplasticContact<dim> &problem = *run.problem;
        problem.set_step_observer(
          [&run, &problem](const unsigned int, const double time) {
            run.times.push_back(time);
            run.displacements.push_back(problem.get_displacement());
            const unsigned int n_cells
              = problem.get_triangulation().n_active_cells();
            std::vector<SymmetricTensor<2, dim>> stress(n_cells);
            for (unsigned int c = 0; c < n_cells; ++c)
              stress[c] = problem.get_stress(c, 0);
            run.stresses.push_back(std::move(stress));
          });
        Timer timer;
        try
          {
            problem.run();
          }
        catch (const ExceptionBase &exc)
          {
            std::ostringstream info;
            exc.print_info(info);
            run.failed  = true;
            run.failure = info.str();
            std::cout << "Convergence study: the run h = 1/" << run.subdivisions
                      << ", k = " << run.time_step << " failed:\n"
                      << run.failure;
          }
        run.wall_time = timer.wall_time();
      }

    std::cout << "Convergence study: reference run, h = 1/"
              << parameters.reference_subdivisions
              << ", k = " << parameters.reference_time_step << '\n';
    ViscoplasticContact<dim> reference(
      parameters_for(parameters.reference_subdivisions,
                     parameters.reference_time_step,
                     "reference"));
    unsigned int reference_steps = 0;
    reference.set_step_observer(
      [&](const unsigned int step, const double time) {
        if (step == 1)
          for (Run &run : runs)
            build_transfer(run, reference);
        reference_steps = step;
        for (Run &run : runs)
          {
            if (run.failed)
              continue;
            const auto level
              = std::find_if(run.times.begin(), run.times.end(), [&](double t) {
                  return std::abs(t - time) <= 1e-10 * parameters.end_time;
                });
            if (level != run.times.end())
              compare(run, level - run.times.begin(), reference);
          }
      });
    Timer timer;
    reference.run();
    write_table(reference.get_dof_handler().n_dofs(),
                reference_steps,
                timer.wall_time());
  }



  // @sect4{ConvergenceStudy::build_transfer}
  //
  // Locate every reference vertex and every reference cell centre in the
  // coarse mesh. The coarse cells are sorted into the squares (cubes) of
  // the generated box they lie in, so each point is tested against the few
  // cells of its square and the neighbouring ones. The barycentric
  // coordinates of a point in the coarse simplex that contains it are the
  // values of the coarse P1 shape functions there.
  template <int dim>
  void
  ConvergenceStudy<dim>::build_transfer(
    Run                            &run,
    const ViscoplasticContact<dim> &reference) const
  {
    const DoFHandler<dim> &coarse    = run.problem->get_dof_handler();
    const unsigned int     N         = run.subdivisions;
    const auto             bucket_of = [&](const Point<dim>     &p,
                               const Tensor<1, dim> &shift) {
      unsigned int index = 0;
      for (int d = dim - 1; d >= 0; --d)
        {
          const double h = parameters.lengths[d] / N;
          const int    i
            = std::clamp(static_cast<int>(std::floor((p[d] + shift[d]) / h)),
                         0,
                         int(N) - 1);
          index = index * N + i;
        }
      return index;
    };

    std::map<unsigned int,
             std::vector<typename DoFHandler<dim>::active_cell_iterator>>
      buckets;
    for (const auto &cell : coarse.active_cell_iterators())
      buckets[bucket_of(cell->center(), Tensor<1, dim>())].push_back(cell);

    // The coarse cell containing p, and the barycentric coordinates of p.
    const auto locate = [&](const Point<dim> &p) {
      const double tolerance = 1e-9 * parameters.lengths[0] / N;
      for (unsigned int corner = 0; corner < (1u << dim); ++corner)
        {
          Tensor<1, dim> shift;
          for (unsigned int d = 0; d < dim; ++d)
            shift[d] = ((corner >> d) & 1 ? tolerance : -tolerance);
          for (const auto &cell : buckets[bucket_of(p, shift)])
            {
              Tensor<2, dim> J;
              for (unsigned int a = 1; a <= dim; ++a)
                for (unsigned int d = 0; d < dim; ++d)
                  J[d][a - 1] = cell->vertex(a)[d] - cell->vertex(0)[d];
              const Tensor<1, dim> lambda = invert(J) * (p - cell->vertex(0));
              std::array<double, dim + 1> weights;
              weights[0] = 1;
              for (unsigned int a = 1; a <= dim; ++a)
                {
                  weights[a] = lambda[a - 1];
                  weights[0] -= lambda[a - 1];
                }
              if (*std::min_element(weights.begin(), weights.end()) >= -1e-10)
                return std::make_pair(cell, weights);
            }
        }
      AssertThrow(false,
                  ExcMessage("Convergence study: a point of the reference "
                             "mesh lies in no cell of the coarse mesh; the "
                             "meshes are not nested."));
      return std::make_pair(coarse.begin_active(),
                            std::array<double, dim + 1>());
    };

    const Triangulation<dim> &fine = reference.get_triangulation();
    run.vertex_dofs.resize(fine.n_vertices());
    run.vertex_weights.resize(fine.n_vertices());
    for (unsigned int v = 0; v < fine.n_vertices(); ++v)
      if (fine.get_used_vertices()[v])
        {
          const auto [cell, weights] = locate(fine.get_vertices()[v]);
          run.vertex_weights[v]      = weights;
          for (unsigned int a = 0; a <= dim; ++a)
            for (unsigned int c = 0; c < dim; ++c)
              run.vertex_dofs[v][a * dim + c] = cell->vertex_dof_index(a, c);
        }
    run.cell_map.resize(fine.n_active_cells());
    for (const auto &cell : fine.active_cell_iterators())
      run.cell_map[cell->active_cell_index()]
        = locate(cell->center()).first->active_cell_index();
  }



  // @sect4{ConvergenceStudy::compare}
  //
  // ||eps(u_ref - I u_h)||_L2 with the one-point rule (exact for P1 on the
  // reference mesh) and ||sigma_ref - sigma_h||_L2 cell by cell.
  template <int dim>
  void
  ConvergenceStudy<dim>::compare(
    Run                            &run,
    const unsigned int              level,
    const ViscoplasticContact<dim> &reference) const
  {
    const DoFHandler<dim> &dof_handler = reference.get_dof_handler();
    const Vector<double>  &coarse_u    = run.displacements[level];
    Vector<double>         error       = reference.get_displacement();
    for (const auto &cell : dof_handler.active_cell_iterators())
      for (const unsigned int v : cell->vertex_indices())
        {
          const unsigned int vertex = cell->vertex_index(v);
          for (unsigned int c = 0; c < dim; ++c)
            {
              double value = 0;
              for (unsigned int a = 0; a <= dim; ++a)
                value += run.vertex_weights[vertex][a]
                         * coarse_u[run.vertex_dofs[vertex][a * dim + c]];
              // Vertices are visited once per adjacent cell; assign, do not
              // add.
              error[cell->vertex_dof_index(v, c)]
                = reference.get_displacement()[cell->vertex_dof_index(v, c)]
                  - value;
            }
        }

    const QGaussSimplex<dim>             quadrature(1);
    FEValues<dim>                        fe_values(reference.get_mapping(),
                            dof_handler.get_fe(),
                            quadrature,
                            update_gradients | update_JxW_values);
    const FEValuesExtractors::Vector     displacement(0);
    std::vector<SymmetricTensor<2, dim>> strain(1);
    double                               error_u = 0, error_sigma = 0;
    for (const auto &cell : dof_handler.active_cell_iterators())
      {
        fe_values.reinit(cell);
        fe_values[displacement].get_function_symmetric_gradients(error, strain);
        const unsigned int            c = cell->active_cell_index();
        const SymmetricTensor<2, dim> stress_error
          = reference.get_stress(c, 0) - run.stresses[level][run.cell_map[c]];
        error_u += (strain[0] * strain[0]) * fe_values.JxW(0);
        error_sigma += (stress_error * stress_error) * fe_values.JxW(0);
      }
    error_u     = std::sqrt(error_u);
    error_sigma = std::sqrt(error_sigma);

    run.max_error_u     = std::max(run.max_error_u, error_u);
    run.max_error_sigma = std::max(run.max_error_sigma, error_sigma);
    run.max_error       = std::max(run.max_error, error_u + error_sigma);
    ++run.n_compared_levels;
  }



  // @sect4{ConvergenceStudy::write_table}
  //
  // convergence.csv and the same table on the terminal. The observed order
  // between consecutive runs is log(e_{i-1}/e_i) / log(s_{i-1}/s_i) with
  // s = h + k, or s = k (s = h) when the mesh (the time step) is the same.
  template <int dim>
  void
  ConvergenceStudy<dim>::write_table(const unsigned int reference_dofs,
                                     const unsigned int reference_steps,
                                     const double reference_wall_time) const
  {
    std::filesystem::create_directories(parameters.directory);
    std::ofstream csv(std::filesystem::path(parameters.directory)
                      / "convergence.csv");
    csv << "h,k,subdivisions,dofs,steps,compared_levels,wall_time,error_u,"
           "error_sigma,error,order_u,order_sigma,order\n"
        << std::setprecision(10);
    // Wall times only with the timing summary, so that the table of a test
    // run is reproducible.
    const auto wall_time_text = [&](const double seconds) {
      std::ostringstream text;
      if (parameters.print_timing_summary)
        text << std::setprecision(3) << seconds;
      else
        text << '-';
      return text.str();
    };
    std::cout << "\nConvergence study against h = 1/"
              << parameters.reference_subdivisions
              << ", k = " << parameters.reference_time_step << " ("
              << reference_dofs << " dofs, " << reference_steps << " steps, "
              << wall_time_text(reference_wall_time) << " s)\n"
              << "     h          k     dofs steps  wall [s]   "
                 "err_u    order  err_sigma  order      error  order\n";
    for (unsigned int r = 0; r < runs.size(); ++r)
      {
        const Run   &run   = runs[r];
        const double h     = parameters.lengths[0] / run.subdivisions;
        const auto   order = [&](const double Run::*member) -> double {
          if (r == 0 || runs[r - 1].failed)
            return std::numeric_limits<double>::quiet_NaN();
          const Run   &previous = runs[r - 1];
          const double h_prev = parameters.lengths[0] / previous.subdivisions;
          // The order in the quantity that varies: k on a fixed mesh, h at a
          // fixed step, h + k when both change.
          const double size_prev
            = (previous.subdivisions == run.subdivisions ? 0. : h_prev)
              + (previous.time_step == run.time_step ? 0. : previous.time_step);
          const double size
            = (previous.subdivisions == run.subdivisions ? 0. : h)
              + (previous.time_step == run.time_step ? 0. : run.time_step);
          return std::log(previous.*member / run.*member)
                 / std::log(size_prev / size);
        };
        if (run.failed)
          {
            csv << h << ',' << run.time_step << ',' << run.subdivisions
                << ",,,0," << run.wall_time << ",inf,inf,inf,nan,nan,nan\n";
            std::cout << std::setw(6) << "1/" + std::to_string(run.subdivisions)
                      << std::setw(11) << std::setprecision(4) << run.time_step
                      << "   failed: see above\n";
            continue;
          }
        const double       order_u     = order(&Run::max_error_u);
        const double       order_sigma = order(&Run::max_error_sigma);
        const double       order_total = order(&Run::max_error);
        const unsigned int dofs = run.problem->get_dof_handler().n_dofs();

        csv << h << ',' << run.time_step << ',' << run.subdivisions << ','
            << dofs << ',' << run.times.size() << ',' << run.n_compared_levels
            << ',' << run.wall_time << ',' << run.max_error_u << ','
            << run.max_error_sigma << ',' << run.max_error << ',' << order_u
            << ',' << order_sigma << ',' << order_total << '\n';
        std::cout << std::setw(6) << "1/" + std::to_string(run.subdivisions)
                  << std::setw(11) << std::setprecision(4) << run.time_step
                  << std::setw(9) << dofs << std::setw(6) << run.times.size()
                  << std::setw(10) << wall_time_text(run.wall_time)
                  << std::scientific << std::setprecision(3) << std::setw(11)
                  << run.max_error_u << std::fixed << std::setprecision(2)
                  << std::setw(7) << order_u << std::scientific
                  << std::setprecision(3) << std::setw(11)
                  << run.max_error_sigma << std::fixed << std::setprecision(2)
                  << std::setw(7) << order_sigma << std::scientific
                  << std::setprecision(3) << std::setw(11) << run.max_error
                  << std::fixed << std::setprecision(2) << std::setw(7)
                  << order_total << std::defaultfloat << '\n';
      }
  }



  template class ConvergenceStudy<2>;
  template class ConvergenceStudy<3>;
} // namespace ViscoContact
