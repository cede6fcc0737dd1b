// Output of ViscoplasticContact<dim>: the .vtu/.pvd records for ParaView,
// the CSV time series and contact profiles, and the run summary.

#include <deal.II/base/exceptions.h>
#include <deal.II/base/timer.h>

#include <deal.II/fe/fe_values.h>

#include <deal.II/numerics/data_out.h>

#include "viscoplastic_contact.h"

#include <filesystem>
#include <iomanip>
#include <sstream>

namespace ViscoContact
{
  // @sect4{ViscoplasticContact::prepare_output_directory}
  //
  // Called once the input is known to be good (parameters parsed, mesh and
  // boundary parts checked), so a bad run never touches an earlier run's
  // results. Writes the complete parsed parameter file for reproducibility
  // and opens the time series.
  template <int dim>
  void
  ViscoplasticContact<dim>::prepare_output_directory()
  {
    const std::filesystem::path directory(parameters.directory);
    std::error_code             error;
    std::filesystem::create_directories(directory, error);
    AssertThrow(!error,
                ExcMessage("Invalid parameter <Output directory> in subsection "
                           "<Output>: value <"
                           + parameters.directory + ">; it cannot be created ("
                           + error.message() + ")."));

    {
      std::ofstream prm_copy(directory / "parameters.prm");
      AssertThrow(prm_copy,
                  ExcMessage("Invalid parameter <Output directory> in "
                             "subsection <Output>: value <"
                             + parameters.directory
                             + ">; it is not writable."));
      prm_copy << parameters.parsed_parameters;
    }

    // A resumed run continues the series of the run it resumes; its rows
    // after the checkpoint are cut off when the checkpoint is read.
    if (parameters.resume)
      time_series.open(directory / "time_series.csv", std::ios::app);
    else
      {
        time_series.open(directory / "time_series.csv");
        time_series << "step,time,active_set_iterations,unilateral_nodes,"
                       "compliance_nodes,no_contact_nodes,total_contact_force,"
                       "max_von_mises,wall_time\n";
      }
    time_series << std::setprecision(10);
  }



  template <int dim>
  void
  ViscoplasticContact<dim>::write_time_series_row(
    const unsigned int                    step,
    const double                          time,
    const ContactActiveSetSolver::Result &result,
    const double                          wall_time)
  {
    const auto states = count_contact_states();
    time_series << step << ',' << time << ',' << result.iterations() << ','
                << states[0] << ',' << states[1] << ',' << states[2] << ','
                << total_contact_force() << ',' << max_von_mises << ','
                << wall_time << '\n';
    time_series.flush();
  }



  // @sect4{ViscoplasticContact::write_contact_profile}
  //
  // The state of every contact node along Gamma_3: the contact pressure
  // z_i/w_i split into the part of the compliant layer, p(u_nu) (at the
  // rigid limit the layer carries p(g-)), and the part of the rigid
  // foundation; the status is 0 (no contact), 1 (normal compliance) or 2
  // (unilateral, u_nu = g).
  template <int dim>
  void
  ViscoplasticContact<dim>::write_contact_profile(const unsigned int step,
                                                  const double       time) const
  {
    if (!contact_enabled)
      return;
    std::ostringstream name;
    name << "contact_profile_" << std::setw(4) << std::setfill('0') << step
         << ".csv";
    std::ofstream out(std::filesystem::path(parameters.directory) / name.str());
    out << std::setprecision(10);
    const char *coordinates[3] = {"x", "y", "z"};
    for (unsigned int d = 0; d < dim; ++d)
      out << coordinates[d] << ',';
    out << "time,u_nu,compliance_pressure,foundation_pressure,contact_pressure,"
           "nodal_force,weight,status\n";

    const Vector<double> &r = active_set_solver.normal_displacements();
    const Vector<double> &z = active_set_solver.normal_forces();
    for (unsigned int i = 0; i < contact_nodes.size(); ++i)
      {
        const ContactLawPiece &piece
          = active_set_solver.law().piece(active_set_solver.pieces()[i]);
        const double pressure   = z[i] / contact_nodes[i].weight;
        const double compliance = (piece.rigid ? piece.p_lower : pressure);
        for (unsigned int d = 0; d < dim; ++d)
          out << contact_nodes[i].location[d] << ',';
        out << time << ',' << r[i] << ',' << compliance << ','
            << pressure - compliance << ',' << pressure << ',' << z[i] << ','
            << contact_nodes[i].weight << ',' << contact_status(i) << '\n';
      }
  }



  // @sect4{ViscoplasticContact::output_results}
  //
  // One .vtu file per output step, listed with its time in solution.pvd.
  // Displacement is a nodal vector field (use ParaView's "Warp By Vector" for
  // the deformed mesh); stresses are cell data (averaged over the stress
  // points of a cell on hypercubes); the contact quantities are nodal
  // fields, zero away from Gamma_3.
  //
  // With another file stem (failed_step) the file is written for
  // inspection only and not listed in solution.pvd.
  template <int dim>
  void
  ViscoplasticContact<dim>::output_results(const unsigned int step,
                                           const double       time,
                                           const std::string &stem)
  {
    TimerOutput::Scope t(computing_timer, "Output");

    const unsigned int          n_components = dim * (dim + 1) / 2;
    const unsigned int          n_q          = stress_quadrature.size();
    std::vector<Vector<double>> stress(n_components,
                                       Vector<double>(
                                         triangulation.n_active_cells()));
    std::vector<Vector<double>> viscoplastic(n_components,
                                             Vector<double>(
                                               triangulation.n_active_cells()));
    Vector<double>              von_mises(triangulation.n_active_cells());

    FEValues<dim> fe_values(*mapping, *fe, stress_quadrature, update_gradients);
    const FEValuesExtractors::Vector     displacement(0);
    std::vector<SymmetricTensor<2, dim>> strains(n_q);
    for (const auto &cell : dof_handler.active_cell_iterators())
      {
        fe_values.reinit(cell);
        fe_values[displacement].get_function_symmetric_gradients(solution,
                                                                 strains);
        const unsigned int c = cell->active_cell_index();
        for (unsigned int q = 0; q < n_q; ++q)
          {
            const SymmetricTensor<2, dim> &sigma
              = quadrature_point_history[c * n_q + q].stress;
            const SymmetricTensor<2, dim> vp
              = sigma - material.elasticity_tensor() * strains[q];
            for (unsigned int k = 0; k < n_components; ++k)
              {
                const auto index = sigma.unrolled_to_component_indices(k);
                stress[k][c] += sigma[index] / n_q;
                viscoplastic[k][c] += vp[index] / n_q;
              }
            von_mises[c] += material.equivalent_stress(sigma) / n_q;
          }
      }

    Vector<double> contact_pressure(scalar_dof_handler.n_dofs());
    Vector<double> contact_state(scalar_dof_handler.n_dofs());
    if (contact_enabled)
      for (unsigned int i = 0; i < contact_nodes.size(); ++i)
        {
          contact_pressure[contact_nodes[i].scalar_dof]
            = active_set_solver.normal_forces()[i] / contact_nodes[i].weight;
          contact_state[contact_nodes[i].scalar_dof] = contact_status(i);
        }

    DataOut<dim> data_out;
    data_out.attach_triangulation(triangulation);
    data_out.add_data_vector(
      dof_handler,
      solution,
      std::vector<std::string>(dim, "displacement"),
      std::vector<DataComponentInterpretation::DataComponentInterpretation>(
        dim,
        DataComponentInterpretation::component_is_part_of_vector));
    const char *axes = "xyz";
    for (unsigned int k = 0; k < n_components; ++k)
      {
        const auto index
          = SymmetricTensor<2, dim>::unrolled_to_component_indices(k);
        std::string suffix = {axes[index[0]], axes[index[1]]};
        data_out.add_data_vector(stress[k],
                                 "stress_" + suffix,
                                 DataOut<dim>::type_cell_data);
        data_out.add_data_vector(viscoplastic[k],
                                 "viscoplastic_stress_" + suffix,
                                 DataOut<dim>::type_cell_data);
      }
    data_out.add_data_vector(von_mises,
                             "von_mises_stress",
                             DataOut<dim>::type_cell_data);
    data_out.add_data_vector(scalar_dof_handler,
                             contact_pressure,
                             "contact_pressure");
    data_out.add_data_vector(scalar_dof_handler,
                             contact_state,
                             "contact_status");
    data_out.build_patches(*mapping);

    DataOutBase::VtkFlags flags(time, step);
    flags.compression_level = DataOutBase::VtkFlags::best_speed;
    data_out.set_flags(flags);

    std::ostringstream name;
    name << stem << '_' << std::setw(4) << std::setfill('0') << step << ".vtu";
    std::ofstream vtu(std::filesystem::path(parameters.directory) / name.str());
    data_out.write_vtu(vtu);
    if (stem != "solution")
      return;

    times_and_names.emplace_back(time, name.str());
    std::ofstream pvd(std::filesystem::path(parameters.directory)
                      / "solution.pvd");
    DataOutBase::write_pvd_record(pvd, times_and_names);
  }



  // @sect4{ViscoplasticContact::print_run_summary}
  //
  // What a user checks after a run: iteration counts, how often the elastic
  // operator was assembled, factorised and solved with (once, once, and per
  // step), norms of the final state, and with the timing summary the cost of
  // an average step relative to the work every step has without contact,
  // measured now in the same process.
  template <int dim>
  void
  ViscoplasticContact<dim>::print_run_summary()
  {
    FEValues<dim>                        fe_values(*mapping,
                            *fe,
                            stress_quadrature,
                            update_gradients | update_JxW_values);
    const FEValuesExtractors::Vector     displacement(0);
    const unsigned int                   n_q = stress_quadrature.size();
    std::vector<SymmetricTensor<2, dim>> strains(n_q);
    double                               strain_norm = 0, stress_norm = 0;
    for (const auto &cell : dof_handler.active_cell_iterators())
      {
        fe_values.reinit(cell);
        fe_values[displacement].get_function_symmetric_gradients(solution,
                                                                 strains);
        for (unsigned int q = 0; q < n_q; ++q)
          {
            const auto &sigma
              = quadrature_point_history[cell->active_cell_index() * n_q + q]
                  .stress;
            strain_norm += (strains[q] * strains[q]) * fe_values.JxW(q);
            stress_norm += (sigma * sigma) * fe_values.JxW(q);
          }
      }

    const auto states = count_contact_states();
    pcout << std::setprecision(8) << "\nRun summary\n"
          << "  final state: ||eps(u)||_L2 = " << std::sqrt(strain_norm)
          << ", ||sigma||_L2 = " << std::sqrt(stress_norm)
          << ", max von Mises = " << max_von_mises << '\n'
          << "  final contact: " << states[0] << " unilateral, " << states[1]
          << " compliance, " << states[2]
          << " no contact, total force = " << total_contact_force() << '\n'
          << (parameters.stress_update == "implicit"
                ? "  Newton iterations (implicit scheme): "
                    + std::to_string(total_newton_iterations) + "\n"
                : std::string())
          << "  active-set iterations: " << total_active_set_iterations
          << " in " << n_time_steps << " steps\n"
          << "  elastic operator: assembled " << n_operator_assemblies
          << "x, factorised " << n_operator_factorizations
          << "x; external load assembled " << n_external_load_assemblies
          << "x\n"
          << "  elastic solves: " << n_elastic_solves << " ("
          << contact_nodes.size() * (contact_enabled ? 1 : 0)
          << " for the contact compliance at set-up)\n";

    if (!parameters.print_timing_summary)
      return;

    computing_timer.print_summary();

    // The reference costs, measured now in this process (the run is over, so
    // the state may be overwritten), averaged over a few repetitions:
    // (a) the history right-hand side of the explicit scheme as the time
    //     loop builds it, i.e. H_{n+1} = H_n + k G(sigma_n) at every stress
    //     point (the Perzyna projection) and -(H_{n+1}, eps(v)), plus one
    //     solve with the factorised operator;
    // (b) only the assembly of -(H, eps(v)) from stored H, plus one solve.
    // A step costs at least (a) without contact; the ratio to (a) is the
    // cost of the contact iteration.
    const unsigned int repetitions = 5;
    Vector<double>     rhs_copy;
    Timer              timer;
    for (unsigned int r = 0; r < repetitions; ++r)
      {
        update_stresses(parameters.time_step, parameters.time_step);
        rhs_copy = system_rhs;
        solve_elastic(rhs_copy);
      }
    const double reference_with_update = timer.wall_time() / repetitions;
    timer.restart();
    for (unsigned int r = 0; r < repetitions; ++r)
      {
        assemble_history_load();
        rhs_copy = system_rhs;
        solve_elastic(rhs_copy);
      }
    const double reference_assembly = timer.wall_time() / repetitions;

    const double step_cost    = time_loop_compute_time / n_time_steps;
    double       contact_time = 0;
    for (const auto &section : computing_timer.get_summary_data(
           TimerOutput::OutputData::total_wall_time))
      if (section.first == "Solve: active set on Gamma_3"
          || section.first == "Solve: contact response")
        contact_time += section.second;
    contact_time /= n_time_steps;

    if (parameters.direct_solver == "cholmod")
      pcout << "Sparse Cholesky factor of the elastic operator: "
            << cholesky_factorization.n_nonzeros_in_factor() << " nonzeros ("
            << dof_handler.n_dofs() << " unknowns)\n";
    pcout << std::setprecision(4)
          << "Cost measurement (wall time, this process):\n"
          << "  average time step (without output): " << step_cost * 1e3
          << " ms, of which contact " << contact_time * 1e3 << " ms\n"
          << "  (a) history update and load + one elastic solve: "
          << reference_with_update * 1e3 << " ms\n"
          << "  (b) history load assembly + one elastic solve: "
          << reference_assembly * 1e3 << " ms\n"
          << "  ratio step / (a): " << step_cost / reference_with_update << '\n'
          << "  ratio step / (b): " << step_cost / reference_assembly << '\n'
          << "  time loop (without output): " << time_loop_compute_time
          << " s\n";
  }



  template class ViscoplasticContact<2>;
  template class ViscoplasticContact<3>;
} // namespace ViscoContact
