// The convergence study: runs at several resolutions compared exactly with a
// reference run on the reference mesh, on any number of ranks.
//
// The study drives ordinary ViscoplasticContact objects, one after the
// other, and watches them through their step observer. Nothing is
// interpolated between unrelated meshes: the meshes are nested boxes
// (mesh.cc), so every reference stress point lies in one coarse cell, on
// which the coarse solution is a known polynomial. The coarse data travel to
// where the reference mesh needs them through MPITools::exchange_records(),
// so no rank ever holds a whole run.

#include <deal.II/base/exceptions.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/timer.h>

#include "studies/convergence_study.h"
#include "robustness/file_output.h"

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
  // @sect4{ConvergenceStudy::ConvergenceStudy}
  //
  // Only rank 0 prints (pcout).
  template <int dim>
  ConvergenceStudy<dim>::ConvergenceStudy(
    const Parameters::AllParameters &parameters,
    const MPI_Comm                   communicator)
    : parameters(parameters)
    , communicator(communicator)
    , pcout(std::cout, Utilities::MPI::this_mpi_process(communicator) == 0)
  {}



  // @sect4{ConvergenceStudy::parameters_for}
  //
  // Each run is the scene of the parameter file at its own resolution,
  // without graphical output and terminal chatter, writing its time series
  // into a subdirectory of the study's output directory. The uniqueness
  // check and the contact profiles are skipped: the study uses neither.
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
    // Each run of the study is timed as it is, without initial cycles.
    run_parameters.initial_cycles_entry    = "0";
    run_parameters.resumable               = false;
    run_parameters.write_vtu               = false;
    run_parameters.verbose                 = false;
    run_parameters.print_iteration_history = false;
    run_parameters.print_timing_summary    = false;
    run_parameters.measure_cost_ratios     = false;
    run_parameters.overwrite               = false;
    run_parameters.check_uniqueness        = false;
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
      << "subsection Contact\n  set Check uniqueness = false\nend\n"
      << "subsection Time\n  set Time step = " << time_step << "\nend\n"
      << "subsection Output\n  set Output directory = "
      << run_parameters.directory
      << "\n  set Write vtu = false\n  set Verbose = false\n"
      << "  set Print iteration history = false\n"
      << "  set Print timing summary = false\n"
      << "  set Measure cost ratios = false\n  set Profile times =\nend\n";
    run_parameters.parsed_parameters += changes.str();
    return run_parameters;
  }



  // @sect4{ConvergenceStudy::square_key}
  //
  // The square (cube) of the box with n subdivisions that contains the
  // point, as a key. Coarse cells are keyed by their centre, which lies
  // inside the cell and thus inside the one square that holds the cell;
  // reference stress points by their location, which is inside a reference
  // cell and thus, the meshes being nested, inside one coarse cell and one
  // square. Neither ever sits on a square's boundary, so the key is
  // unambiguous.
  template <int dim>
  std::string
  ConvergenceStudy<dim>::square_key(const Point<dim>  &point,
                                    const unsigned int n) const
  {
    // The square's multi-index (i_1, ..., i_dim), x fastest, as one integer.
    // A point on the far side of the box (x_d = L_d) belongs to the last
    // square, hence the clamp.
    std::uint64_t index = 0;
    for (int d = dim - 1; d >= 0; --d)
      {
        const double h = parameters.lengths[d] / n;
        const int    i = std::clamp(static_cast<int>(std::floor(point[d] / h)),
                                 0,
                                 static_cast<int>(n) - 1);
        index          = index * n + i;
      }
    // The key is the integer's bytes: exchange_records() takes byte strings.
    return std::string(reinterpret_cast<const char *>(&index), sizeof(index));
  }



  // @sect4{ConvergenceStudy::record_state}
  //
  // Per locally owned cell: at the first step its square and vertices, at
  // every step grad u and sigma (as full dim x dim tensors) at its stress
  // points.
  //
  // The record of a cell is one vector of doubles: the number of vertices,
  // their coordinates, and then, per time level, per stress point q and per
  // entry (a, b), the pair (grad u)_ab, sigma_ab. compare() reads it with
  // the same layout. The records stay on the rank of the coarse run's cell
  // until the reference run needs them.
  template <int dim>
  void
  ConvergenceStudy<dim>::record_state(
    Run                            &run,
    const ViscoplasticContact<dim> &problem) const
  {
    const auto         state = problem.stress_point_state();
    const auto        &cells = state.cells();
    const unsigned int n_q   = state.quadrature.size();
    // The first call (after step 1) also creates the records and fills in
    // what does not change: the key, the number of vertices, the vertices.
    if (run.cells.empty())
      {
        run.n_dofs = state.dof_handler.n_dofs();
        run.cells.resize(cells.size());
        for (unsigned int k = 0; k < cells.size(); ++k)
          {
            run.cells[k].first
              = square_key(cells[k]->center(), run.subdivisions);
            std::vector<double> &payload = run.cells[k].second;
            payload.push_back(cells[k]->n_vertices());
            for (const unsigned int v : cells[k]->vertex_indices())
              for (unsigned int d = 0; d < dim; ++d)
                payload.push_back(cells[k]->vertex(v)[d]);
          }
      }
    // Every call appends one time level to every record.
    for (unsigned int k = 0; k < cells.size(); ++k)
      for (unsigned int q = 0; q < n_q; ++q)
        {
          const Tensor<2, dim> gradient = state.displacement_gradient(k, q);
          const SymmetricTensor<2, dim> &stress = state.stress(k, q);
          for (unsigned int a = 0; a < dim; ++a)
            for (unsigned int b = 0; b < dim; ++b)
              {
                run.cells[k].second.push_back(gradient[a][b]);
                run.cells[k].second.push_back(stress[a][b]);
              }
        }
  }



  // @sect4{ConvergenceStudy::run}
  //
  // The coarse runs first, each recording its states at all its time levels;
  // then the reference run, which compares with them at every common time
  // level while it goes.
  //
  // So the reference solution is never stored: at each of its steps the
  // errors of every coarse run at that time are computed and only their
  // maxima kept. Its memory is one run's, plus the records of the coarse
  // cells this rank needs.
  template <int dim>
  void
  ConvergenceStudy<dim>::run()
  {
    // The study's folder is checked and prepared first (with Overwrite =
    // true the earlier study's files go now: the runs' set-ups come later);
    // each run then writes into a folder of its own below runs/.
    folder = std::make_unique<OutputFolder>(parameters.directory,
                                            parameters.overwrite
                                              ? OutputFolder::Mode::overwrite
                                              : OutputFolder::Mode::new_run,
                                            parameters.parameter_file,
                                            communicator);
    folder->prepare();
    folder->create_folder("runs");

    // The coarse runs, one after the other on all ranks.
    runs.resize(parameters.study_subdivisions.size());
    for (unsigned int r = 0; r < runs.size(); ++r)
      run_coarse(r);

    pcout << "Convergence study: reference run, h = 1/"
          << parameters.reference_subdivisions
          << ", k = " << parameters.reference_time_step << std::endl;
    // The reference run, with its own observer.
    folder->create_folder("runs/reference");
    ViscoplasticContact<dim> reference(
      parameters_for(parameters.reference_subdivisions,
                     parameters.reference_time_step,
                     "reference"),
      communicator);
    unsigned int reference_steps = 0;
    reference.set_step_observer(
      [&](const unsigned int step, const double time) {
        // After its first step, when the reference mesh and its stress
        // points exist, every coarse run's cells are brought to the ranks of
        // the reference points they contain.
        if (step == 1)
          for (Run &run : runs)
            if (!run.failed)
              locate(run, reference);
        reference_steps = step;
        // Then, at every step, the comparison with the coarse runs.
        compare_at_time(time, reference);
      });
    // A failure of the reference run itself ends the study with its error.
    Timer timer;
    reference.run();
    write_table(reference.stress_point_state().dof_handler.n_dofs(),
                reference_steps,
                Utilities::MPI::max(timer.wall_time(), communicator));
  }



  // @sect4{ConvergenceStudy::run_coarse}
  //
  // Coarse run r in a folder of its own, on all ranks. After every step the
  // observer notes the time level and records the state. If a step of the
  // run was cut, the run has extra time levels; only the levels that equal
  // a reference time level are compared.
  template <int dim>
  void
  ConvergenceStudy<dim>::run_coarse(const unsigned int r)
  {
    Run &run         = runs[r];
    run.subdivisions = parameters.study_subdivisions[r];
    run.time_step    = parameters.study_time_steps[r];
    std::ostringstream name;
    name << "h_1_" << run.subdivisions << "_k_" << run.time_step;
    folder->create_folder("runs/" + name.str());
    pcout << "Convergence study: run " << r + 1 << " of " << runs.size()
          << ", h = 1/" << run.subdivisions << ", k = " << run.time_step
          << std::endl;
    ViscoplasticContact<dim> problem(parameters_for(run.subdivisions,
                                                    run.time_step,
                                                    name.str()),
                                     communicator);
    problem.set_step_observer([&](const unsigned int, const double time) {
      run.observed_times.push_back(time);
      record_state(run, problem);
    });
    Timer timer;
    try
      {
        problem.run();
      }
    catch (const ExceptionBase &exc)
      {
        // A run that stops with an error (iteration limit, blow-up) stays
        // in the table as failed instead of ending the study. A failed step
        // is decided collectively (time_step.cc reduces its criteria over
        // the ranks), so every rank catches the exception and marks the
        // run.
        std::ostringstream info;
        exc.print_info(info);
        run.failed  = true;
        run.failure = info.str();
        pcout << "Convergence study: the run h = 1/" << run.subdivisions
              << ", k = " << run.time_step << " failed:\n"
              << run.failure;
      }
    // The slowest rank's time is the run's time.
    run.wall_time = Utilities::MPI::max(timer.wall_time(), communicator);
  }



  // @sect4{ConvergenceStudy::compare_at_time}
  //
  // At every step of the reference run: compare each coarse run that has a
  // time level equal to the reference's current time (to a tolerance
  // relative to T). Every rank compares the same runs at the same levels.
  template <int dim>
  void
  ConvergenceStudy<dim>::compare_at_time(
    const double                    time,
    const ViscoplasticContact<dim> &reference)
  {
    for (Run &run : runs)
      {
        if (run.failed)
          continue;
        const auto level = std::find_if(run.observed_times.begin(),
                                        run.observed_times.end(),
                                        [&](double t) {
                                          return std::abs(t - time)
                                                 <= 1e-10 * parameters.end_time;
                                        });
        if (level != run.observed_times.end())
          compare(run, level - run.observed_times.begin(), reference);
      }
  }



  // @sect4{ConvergenceStudy::locate}
  //
  // The coarse cells of the squares that hold this rank's reference stress
  // points come to this rank; each point is located in one of them
  // (barycentric coordinates on simplices; on the axis-aligned boxes of a
  // hypercube mesh the square holds one cell).
  //
  // The result, per reference stress point p = k n_q + q (cell k, point q):
  // the coarse cell containing it (point_cell, an index into the records of
  // located_cells, each record copied once however many points it holds) and
  // its coordinates in that cell (unit_points): the barycentric coordinates
  // on a simplex, the coordinates relative to the box's corner and edge
  // lengths on a hypercube. Both are computed once; compare() then only
  // evaluates.
  namespace
  {
    // Whether the coarse cell of a record (its number of vertices and their
    // coordinates first, as record_state() writes them) contains the point,
    // and the point's coordinates in the cell, unit.
    template <int dim>
    bool
    locate_in_cell(const std::vector<double> &record,
                   const Point<dim>          &point,
                   Point<dim>                &unit)
    {
      // The vertices of the cell, from its record.
      const unsigned int n_vertices = record[0];
      const auto         vertex     = [&](const unsigned int v) {
        Point<dim> x;
        for (unsigned int d = 0; d < dim; ++d)
          x[d] = record[1 + v * dim + d];
        return x;
      };
      bool inside = true;
      if (n_vertices == dim + 1)
        {
          // A simplex: solve x = v_0 + J lambda for the barycentric
          // coordinates lambda (the columns of J are the edges from v_0).
          // The point is inside if all of them and 1 - their sum are
          // nonnegative, up to rounding.
          Tensor<2, dim> J;
          for (unsigned int a = 1; a <= dim; ++a)
            for (unsigned int d = 0; d < dim; ++d)
              J[d][a - 1] = vertex(a)[d] - vertex(0)[d];
          const Tensor<1, dim> lambda = invert(J) * (point - vertex(0));
          double               sum    = 0;
          for (unsigned int d = 0; d < dim; ++d)
            {
              unit[d] = lambda[d];
              sum += lambda[d];
              inside = inside && lambda[d] >= -1e-10;
            }
          inside = inside && sum <= 1 + 1e-10;
        }
      else
        // A hypercube of the box: an axis-aligned box whose last vertex (in
        // deal.II's numbering) is the corner opposite v_0, so the unit
        // coordinates follow axis by axis. It is the only cell of its
        // square, so it contains the point.
        for (unsigned int d = 0; d < dim; ++d)
          unit[d] = (point[d] - vertex(0)[d])
                    / (vertex(n_vertices - 1)[d] - vertex(0)[d]);
      return inside;
    }
  } // namespace



  template <int dim>
  void
  ConvergenceStudy<dim>::locate(Run                            &run,
                                const ViscoplasticContact<dim> &reference) const
  {
    std::vector<Point<dim>>  points;
    std::vector<std::string> keys;
    reference_stress_points(reference, run.subdivisions, points, keys);
    // Ask for each square once.
    std::vector<std::string> requests(keys);
    std::sort(requests.begin(), requests.end());
    requests.erase(std::unique(requests.begin(), requests.end()),
                   requests.end());
    // The coarse cells of the requested squares, from whichever ranks hold
    // them. The records of this rank's coarse cells are no longer needed
    // here afterwards; those that are needed now live in the answers.
    const auto found
      = MPITools::exchange_records(run.cells, requests, communicator);
    run.cells.clear();

    std::map<const std::vector<double> *, unsigned int> index_of;
    run.point_cell.resize(points.size());
    run.unit_points.resize(points.size());
    for (unsigned int p = 0; p < points.size(); ++p)
      {
        // No coarse cell in the point's square: the meshes are not nested
        // boxes.
        const auto entry = found.find(keys[p]);
        AssertThrow(entry != found.end(),
                    ExcMessage("Convergence study: a point of the reference "
                               "mesh lies in no cell of the coarse mesh; the "
                               "meshes are not nested boxes."));
        const std::vector<double> *containing = nullptr;
        for (const std::vector<double> &candidate : entry->second)
          {
            Point<dim> unit;
            if (locate_in_cell(candidate, points[p], unit))
              {
                containing         = &candidate;
                run.unit_points[p] = unit;
                break;
              }
          }
        AssertThrow(containing != nullptr,
                    ExcMessage("Convergence study: a point of the reference "
                               "mesh lies in no cell of the coarse mesh; the "
                               "meshes are not nested."));
        // Keep one copy of each containing cell, and remember which one
        // holds this point.
        const auto [position, inserted]
          = index_of.emplace(containing, run.located_cells.size());
        if (inserted)
          run.located_cells.push_back(*containing);
        run.point_cell[p] = position->second;
      }
  }



  // @sect4{ConvergenceStudy::reference_stress_points}
  //
  // The real location and the square key (for a box with the given
  // subdivisions) of every reference stress point of this rank, in the
  // order of the points p = k n_q + q. Stress points are given on the
  // reference cell; the linear mapping of the cell type (the program's
  // own) places them in the real cell. A rank without cells takes any
  // mapping; it is not used.
  template <int dim>
  void
  ConvergenceStudy<dim>::reference_stress_points(
    const ViscoplasticContact<dim> &reference,
    const unsigned int              subdivisions,
    std::vector<Point<dim>>        &points,
    std::vector<std::string>       &keys) const
  {
    const auto             state      = reference.stress_point_state();
    const auto            &cells      = state.cells();
    const Quadrature<dim> &quadrature = state.quadrature;
    const Mapping<dim>    &mapping
      = cells.empty() ? ReferenceCells::get_hypercube<dim>()
                          .template get_default_linear_mapping<dim>()
                      : cells[0]
                          ->reference_cell()
                          .template get_default_linear_mapping<dim>();
    for (const auto &cell : cells)
      for (unsigned int q = 0; q < quadrature.size(); ++q)
        {
          points.push_back(
            mapping.transform_unit_to_real_cell(cell, quadrature.point(q)));
          keys.push_back(square_key(points.back(), subdivisions));
        }
  }



  // @sect4{ConvergenceStudy::compare}
  //
  // ||eps(u_ref - u_h)||_L2 and ||sigma_ref - sigma_h||_L2 with the
  // reference's stress-point quadrature, summed over the ranks.
  //
  // This is the error of doc/model.md, section 1, at one time level: the
  // coarse run's grad u_h and sigma_h are evaluated at every reference
  // stress point from the located coarse cell, and the squared differences
  // are integrated with the reference's weights JxW. On simplices both
  // fields are constant on each reference cell and the one-point rule is
  // exact; on hypercubes the rule is the reference's own Gauss rule. The
  // maximum over the time levels is taken as the levels come.
  template <int dim>
  void
  ConvergenceStudy<dim>::compare(
    Run                            &run,
    const unsigned int              level,
    const ViscoplasticContact<dim> &reference) const
  {
    const auto             state      = reference.stress_point_state();
    const auto            &cells      = state.cells();
    const Quadrature<dim> &quadrature = state.quadrature;
    const unsigned int     n_q        = quadrature.size();
    double                 error_u = 0, error_sigma = 0;
    for (unsigned int k = 0; k < cells.size(); ++k)
      for (unsigned int q = 0; q < n_q; ++q)
        {
          const unsigned int         p = k * n_q + q;
          const std::vector<double> &payload
            = run.located_cells[run.point_cell[p]];
          // The values of the coarse cell at this time level: they start
          // after the vertex data, at level times n_q x 2 x dim^2 doubles.
          const unsigned int n_vertices = payload[0];
          const double      *values
            = &payload[1 + n_vertices * dim
                       + std::size_t(level) * n_q * 2 * dim * dim];
          // sum_j L_j(x) v_j with the Lagrange polynomials of the coarse
          // cell's stress points (a single point on simplices). On
          // hypercubes the stress points are the tensor-product Gauss
          // points, two per direction at coordinates symmetric about 1/2, so
          // the one-dimensional Lagrange polynomial of a point is
          // (x - other) / (node - other); the product over the directions is
          // the polynomial of degree one in each variable through the 2^dim
          // values, which reproduces the Q1 gradient exactly.
          Tensor<2, dim> gradient, stress;
          for (unsigned int j = 0; j < n_q; ++j)
            {
              double weight = 1;
              if (n_q > 1)
                for (unsigned int d = 0; d < dim; ++d)
                  {
                    const double node  = quadrature.point(j)[d];
                    const double other = 1 - node; // the other Gauss point
                    weight *= (run.unit_points[p][d] - other) / (node - other);
                  }
              // Interpolate both fields with the same weights.
              for (unsigned int a = 0; a < dim; ++a)
                for (unsigned int b = 0; b < dim; ++b)
                  {
                    gradient[a][b]
                      += weight * values[(j * dim * dim + a * dim + b) * 2];
                    stress[a][b]
                      += weight * values[(j * dim * dim + a * dim + b) * 2 + 1];
                  }
            }
          // The differences at the point: the strain of the displacement
          // error and the stress error, squared and weighted.
          const SymmetricTensor<2, dim> strain_error
            = symmetrize(state.displacement_gradient(k, q) - gradient);
          const Tensor<2, dim> stress_error
            = Tensor<2, dim>(state.stress(k, q)) - stress;
          const double JxW = state.JxW(k, q);
          error_u += (strain_error * strain_error) * JxW;
          error_sigma += scalar_product(stress_error, stress_error) * JxW;
        }
    // Sum over the ranks; every rank gets the same norms and keeps the same
    // maxima.
    error_u     = std::sqrt(Utilities::MPI::sum(error_u, communicator));
    error_sigma = std::sqrt(Utilities::MPI::sum(error_sigma, communicator));

    // The maxima over the time levels: of each part separately, and of their
    // sum (which is not the sum of the maxima).
    run.max_error_u     = std::max(run.max_error_u, error_u);
    run.max_error_sigma = std::max(run.max_error_sigma, error_sigma);
    run.max_error       = std::max(run.max_error, error_u + error_sigma);
    ++run.n_compared_levels;
  }



  // @sect4{ConvergenceStudy::write_table}
  //
  // convergence.csv and the same table on the terminal (rank 0): the
  // header, then one row per run (write_table_row()).
  template <int dim>
  void
  ConvergenceStudy<dim>::write_table(
    const types::global_dof_index reference_dofs,
    const unsigned int            reference_steps,
    const double                  reference_wall_time) const
  {
    // Rank 0 writes the table (staged, then committed); all ranks learn
    // whether that worked.
    folder->record_files({"convergence.csv"});
    if (Utilities::MPI::this_mpi_process(communicator) == 0)
      {
        std::ostringstream csv;
        csv << "h,k,subdivisions,dofs,steps,compared_levels,wall_time,error_u,"
               "error_sigma,error,order_u,order_sigma,order\n"
            << std::setprecision(10);
        // The terminal header names the reference resolution and its cost.
        std::cout << "\nConvergence study against h = 1/"
                  << parameters.reference_subdivisions
                  << ", k = " << parameters.reference_time_step << " ("
                  << reference_dofs << " dofs, " << reference_steps
                  << " steps, " << wall_time_text(reference_wall_time)
                  << " s)\n"
                  << "     h          k     dofs steps  wall [s]   "
                     "err_u    order  err_sigma  order      error  order\n";
        for (unsigned int r = 0; r < runs.size(); ++r)
          write_table_row(r, csv);
        folder->stage("convergence.csv", csv.str());
      }
    folder->commit();
  }



  // @sect4{ConvergenceStudy::wall_time_text}
  //
  // Wall times only with the timing summary, so that the table of a test
  // run is reproducible.
  template <int dim>
  std::string
  ConvergenceStudy<dim>::wall_time_text(const double seconds) const
  {
    std::ostringstream text;
    if (parameters.print_timing_summary)
      text << std::setprecision(3) << seconds;
    else
      text << '-';
    return text.str();
  }



  // @sect4{ConvergenceStudy::observed_order}
  //
  // The observed order of one error column (a pointer to the member of Run
  // that holds it) between runs r - 1 and r: log(e_{r-1}/e_r) /
  // log(s_{r-1}/s_r) with s = h + k, or s = k (s = h) when the mesh (the
  // time step) is the same. h is measured along the first edge,
  // L1 / Subdivisions. NaN where the order is not defined: for the first
  // run and after a failed one (there is no error to compare with), and for
  // a run on the reference's own mesh and step, whose error is zero or, on
  // a back end whose arithmetic varies between runs (MUMPS on several
  // ranks), roundoff.
  template <int dim>
  double
  ConvergenceStudy<dim>::observed_order(const unsigned int r,
                                        const double Run::*member) const
  {
    const Run &run = runs[r];
    if (r == 0 || runs[r - 1].failed
        || (run.subdivisions == parameters.reference_subdivisions
            && run.time_step == parameters.reference_time_step))
      return std::numeric_limits<double>::quiet_NaN();
    const Run   &previous = runs[r - 1];
    const double h        = parameters.lengths[0] / run.subdivisions;
    const double h_prev   = parameters.lengths[0] / previous.subdivisions;
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
  }



  // @sect4{ConvergenceStudy::write_table_row}
  //
  // Run r's row of convergence.csv (into csv) and of the terminal table.
  // An order that is not defined (the first run, or after a failed one) is
  // an empty field in the CSV file and "-" on the terminal, never a "nan"
  // among the numbers. A failed run keeps its row, with its resolution and
  // no errors or orders.
  namespace
  {
    std::string
    csv_field(const double value)
    {
      std::ostringstream text;
      if (std::isfinite(value))
        text << std::setprecision(10) << value;
      return text.str();
    }

    std::string
    terminal_order(const double value)
    {
      std::ostringstream text;
      if (std::isfinite(value))
        text << std::fixed << std::setprecision(2) << value;
      else
        text << '-';
      return text.str();
    }
  } // namespace



  template <int dim>
  void
  ConvergenceStudy<dim>::write_table_row(const unsigned int r,
                                         std::ostream      &csv) const
  {
    const Run   &run = runs[r];
    const double h   = parameters.lengths[0] / run.subdivisions;
    // A failed run: its resolution, and no errors.
    if (run.failed)
      {
        csv << h << ',' << run.time_step << ',' << run.subdivisions << ",,,0,"
            << run.wall_time << ",,,,,,\n";
        std::cout << std::setw(6) << "1/" + std::to_string(run.subdivisions)
                  << std::setw(11) << std::setprecision(4) << run.time_step
                  << "   failed: see above\n";
        return;
      }
    // The orders of the displacement part, the stress part and the total.
    const double order_u     = observed_order(r, &Run::max_error_u);
    const double order_sigma = observed_order(r, &Run::max_error_sigma);
    const double order_total = observed_order(r, &Run::max_error);

    // One row of the CSV file, full precision ...
    csv << h << ',' << run.time_step << ',' << run.subdivisions << ','
        << run.n_dofs << ',' << run.observed_times.size() << ','
        << run.n_compared_levels << ',' << run.wall_time << ','
        << run.max_error_u << ',' << run.max_error_sigma << ',' << run.max_error
        << ',' << csv_field(order_u) << ',' << csv_field(order_sigma) << ','
        << csv_field(order_total) << '\n';
    // ... and of the terminal table, aligned in columns.
    std::cout << std::setw(6) << "1/" + std::to_string(run.subdivisions)
              << std::setw(11) << std::setprecision(4) << run.time_step
              << std::setw(9) << run.n_dofs << std::setw(6)
              << run.observed_times.size() << std::setw(10)
              << wall_time_text(run.wall_time) << std::scientific
              << std::setprecision(3) << std::setw(11) << run.max_error_u
              << std::setw(7) << terminal_order(order_u) << std::setw(11)
              << run.max_error_sigma << std::setw(7)
              << terminal_order(order_sigma) << std::setw(11) << run.max_error
              << std::setw(7) << terminal_order(order_total)
              << std::defaultfloat << '\n';
  }



  // The instantiations for 2D and 3D.
  template class ConvergenceStudy<2>;
  template class ConvergenceStudy<3>;
} // namespace ViscoContact
