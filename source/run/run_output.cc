// What a run of ViscoplasticContact<dim> writes: the .pvtu/.vtu records and the
// .pvd time record for ParaView, the time series and contact profiles (CSV),
// and the run summary with the cost measurements.

#include <deal.II/base/exceptions.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/multithread_info.h>
#include <deal.II/base/timer.h>
#include <deal.II/base/utilities.h>

#include <deal.II/dofs/dof_tools.h>

#include <deal.II/numerics/data_out.h>

#include "back_ends/blas_threads.h"
#include "mesh/mesh.h"
#include "robustness/checkpoint_file.h"
#include "robustness/file_output.h"
#include "robustness/output_folder.h"
#include "robustness/vtu_record.h"
#include "run/run_output.h"
#include "viscoplastic_contact.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iomanip>
#include <limits>
#include <sstream>
#include <sys/statvfs.h>

namespace ViscoContact
{
  namespace
  {
    // The names and interpretation of a vector field of dim components.
    template <int dim>
    std::pair<
      std::vector<std::string>,
      std::vector<DataComponentInterpretation::DataComponentInterpretation>>
    vector_field(const std::string &name)
    {
      return {
        std::vector<std::string>(dim, name),
        std::vector<DataComponentInterpretation::DataComponentInterpretation>(
          dim,
          DataComponentInterpretation::component_is_part_of_vector)};
    }



    // The first line of time_series.csv: what the columns are. After the
    // counts and the force, the size of the contact zone (width in 2D,
    // area in 3D) and the peak pressure, with several contact zones the
    // contact force of each, then per Dirichlet part and plane of symmetry
    // the components of the force it exerts on the body.
    template <int dim>
    std::string
    time_series_header(const std::vector<unsigned int> &contact_zone_numbers,
                       const std::vector<std::string>  &dirichlet_parts,
                       const std::vector<unsigned int> &frictional_zones,
                       const std::vector<unsigned int> &pair_zones)
    {
      std::string header
        = "step,time,active_set_iterations,unilateral_nodes,compliance_nodes,"
          "no_contact_nodes,total_contact_force,max_von_mises,wall_time,"
          "krylov_iterations,time_step,error_estimate,contact_area,"
          "peak_pressure";
      if (contact_zone_numbers.size() > 1)
        for (const unsigned int number : contact_zone_numbers)
          header += ",contact_force_zone_" + std::to_string(number);
      for (const std::string &part : dirichlet_parts)
        for (unsigned int c = 0; c < dim; ++c)
          header += ",reaction_" + part + "_" + "xyz"[c];
      // With friction: the sticking and slipping nodes, and per frictional
      // zone the tangential force on it.
      if (!frictional_zones.empty())
        header += ",stick_nodes,slip_nodes";
      for (const unsigned int number : frictional_zones)
        for (unsigned int c = 0; c < dim; ++c)
          header += ",tangential_force_zone_" + std::to_string(number) + "_"
                    + "xyz"[c];
      // Per contact pair the force on each side (on the zone's side, from
      // the other body, and on the opposite side), the contact area and the
      // peak pressure.
      for (const unsigned int number : pair_zones)
        {
          for (const std::string side :
               {"pair_force_zone_", "opposite_force_zone_"})
            for (unsigned int c = 0; c < dim; ++c)
              header += "," + side + std::to_string(number) + "_" + "xyz"[c];
          header += ",contact_area_zone_" + std::to_string(number)
                    + ",peak_pressure_zone_" + std::to_string(number);
        }
      return header + "\n";
    }
  } // namespace



  // @sect4{RunOutput::open_folder}
  //
  // The first thing run() does: the output folder is looked at (and, if it
  // exists, locked for this run) before any work is done. A new run refuses
  // a folder with another run's files unless Overwrite = true, and every run
  // refuses a folder another run is using or files in the way that the
  // program did not write (output_folder.h). Old solution_0200.vtu files next
  // to a new solution.pvd of 64 steps, or an old checkpoint that a later
  // Resume would take up, would be mistaken for results of the new run.
  // Nothing in the folder changes here.
  template <int dim>
  void
  RunOutput<dim>::open_folder(const Parameters::AllParameters &parameters,
                              const MPI_Comm                   communicator)
  {
    const OutputFolder::Mode mode
      = parameters.resume      ? OutputFolder::Mode::resume
        : parameters.overwrite ? OutputFolder::Mode::overwrite
                               : OutputFolder::Mode::new_run;
    output_folder = std::make_unique<OutputFolder>(parameters.directory,
                                                   mode,
                                                   parameters.parameter_file,
                                                   communicator);
  }



  // @sect4{RunOutput::prepare_folder}
  //
  // Called once the input is known to be good (parameters parsed, mesh,
  // boundary parts and a requested checkpoint checked), so a bad run never
  // touches an earlier run's results. The folder is created (or, with
  // Overwrite = true, the earlier run's files are removed; with Resume, those
  // of the steps after the checkpoint); then the complete parsed parameter
  // file goes in for reproducibility (unless the parameter file being run is
  // that file) and the time series starts with its header, or, resumed, is
  // cut back to the checkpoint's step.
  template <int dim>
  void
  RunOutput<dim>::prepare_folder(const ViscoplasticContact<dim> &problem,
                                 const unsigned int              resume_step)
  {
    output_folder->prepare(resume_step);
    output_folder->record_files({"parameters.prm", "time_series.csv"});
    if (Utilities::MPI::this_mpi_process(problem.mpi_communicator) == 0)
      {
        if (!output_folder->is_parameter_file("parameters.prm"))
          output_folder->stage("parameters.prm",
                               problem.parameters.parsed_parameters,
                               problem.parameters.resume
                                 ? OutputFolder::Replace::own
                                 : OutputFolder::Replace::never);
        if (!problem.parameters.resume)
          output_folder->stage(
            "time_series.csv",
            time_series_header<dim>(problem.contact_zones.numbers(),
                                    problem.prescribed.reaction_names(),
                                    problem.contact_zones.frictional_numbers(),
                                    problem.contact_zones.pair_numbers()));
      }
    output_folder->commit();
    if (problem.parameters.resume)
      truncate_time_series(
        *output_folder,
        time_series_header<dim>(problem.contact_zones.numbers(),
                                problem.prescribed.reaction_names(),
                                problem.contact_zones.frictional_numbers(),
                                problem.contact_zones.pair_numbers()),
        resume_step);
  }



  // @sect4{RunOutput::print_header}
  // The run's header: the size of the problem (global counts), the model, the
  // back end with the reason for the choice, and the parallel layout. pcout
  // prints on rank 0 only.
  template <int dim>
  void
  RunOutput<dim>::print_header(const ViscoplasticContact<dim> &problem,
                               const unsigned int              n_steps) const
  {
    problem.pcout << "Mesh: " << problem.triangulation->n_global_active_cells()
                  << ' ' << problem.discretisation.describe() << " cells, "
                  << problem.dof_handler.n_dofs() << " displacement dofs, "
                  << (problem.contact_enabled
                        ? problem.contact_set.n_global_nodes()
                        : 0)
                  << " contact nodes, ";
    if (problem.parameters.time_step_control
        == Parameters::TimeStepControl::adaptive)
      problem.pcout << "adaptive time steps\n";
    else
      problem.pcout << n_steps << " time steps\n";
    // With initial cycles the mesh above is the first of them (a resumed run
    // starts on the checkpoint's mesh and runs none).
    if (problem.plan.initial_cycles() > 0 && !problem.parameters.resume)
      problem.pcout << "Initial cycles: step 1 on "
                    << problem.plan.initial_cycles()
                    << " coarser meshes first, from this one, "
                    << (problem.discretisation.has_simplices()
                          ? "each finer one built anew"
                        : problem.parameters.initial_refinement
                            == Parameters::InitialRefinement::global
                          ? "refined globally"
                          : "refined adaptively")
                    << (problem.plan.initial_cycles_reason().empty()
                          ? ""
                          : " (Initial cycles = auto: "
                              + problem.plan.initial_cycles_reason() + ")")
                    << '\n';
    else if (!problem.plan.initial_cycles_reason().empty())
      problem.pcout << "Initial cycles: none (Initial cycles = auto: "
                    << problem.plan.initial_cycles_reason() << ")\n";
    const std::string step_cycles_auto
      = problem.plan.step_cycles_reason().empty()
          ? ""
          : " (Step cycles = auto: " + problem.plan.step_cycles_reason() + ")";
    // Without initial cycles the back end is already that of the run's mesh.
    if (problem.plan.step_cycles_dropped()
        && problem.plan.initial_cycles() == 0)
      problem.pcout
        << "Step cycles: none (Step cycles = auto: Method = auto chose "
           "the condensed back end)\n";
    else if (problem.plan.step_cycles() > 0)
      problem.pcout
        << "Step cycles: every step"
        << (problem.plan.initial_cycles() > 0 ? " after the first" : "")
        << " solved on " << problem.plan.step_cycles() << " coarser mesh"
        << (problem.plan.step_cycles() > 1 ? "es" : "")
        << " first, whose contact zone starts it on the mesh of the run "
           "where it moved further than the predicted start"
        << step_cycles_auto << '\n';
    else if (!step_cycles_auto.empty())
      problem.pcout << "Step cycles: none" << step_cycles_auto << '\n';
    // A rate-independent law has no rate form (hardening plasticity).
    const auto rate_independent
      = [](const auto &m) { return m->is_plastic() && !m->has_rate_form(); };
    const bool any_rate_independent
      = std::any_of(problem.materials.laws().begin(),
                    problem.materials.laws().end(),
                    rate_independent);
    problem.pcout << "Model: "
                  << (!problem.parameters.any_plasticity() ? "elastic"
                      : any_rate_independent ? "plastic (hardening plasticity)"
                                             : "viscoplastic");
    if (problem.parameters.plane_model == Parameters::PlaneModel::plane_strain)
      problem.pcout << " plane strain";
    if (problem.materials.laws().size() > 1)
      problem.pcout << " (" << problem.materials.laws().size() << " materials, "
                    << std::count_if(problem.materials.laws().begin(),
                                     problem.materials.laws().end(),
                                     [](const auto &m) {
                                       return m->is_plastic();
                                     })
                    << (any_rate_independent ? " plastic)" : " viscoplastic)");
    problem.pcout << ", contact " << (problem.contact_enabled ? "on" : "off");
    const auto pairs
      = std::count_if(problem.contact_zones.descriptions().begin(),
                      problem.contact_zones.descriptions().end(),
                      [](const auto &zone) {
                        return !zone.opposite_ids.empty();
                      });
    if (problem.contact_enabled && pairs > 0)
      problem.pcout << " (" << pairs << " zone(s) between two bodies)";
    problem.pcout << ", "
                  << (problem.parameters.stress_update
                          == Parameters::StressUpdate::explicit_euler
                        ? "explicit"
                        : "implicit")
                  << " stress update\n";
    // Contact off because no boundary part is named is most likely a
    // mistake in the parameter file: said, not silently accepted.
    if (problem.parameters.used_contact_zones().empty())
      problem.pcout
        << "WARNING: contact is off: <Contact boundary ids> in subsection "
           "<Boundary> names no boundary part (nor does any subsection "
           "Contact zone N), so the body has no contact boundary and the "
           "contact law is not used.\n";
    else if (problem.contact_zones.descriptions().size() > 1)
      problem.pcout << "Contact zones: "
                    << problem.contact_zones.descriptions().size() << '\n';
    problem.pcout << "Back end: " << problem.contact_solver->description()
                  << " (" << problem.plan.back_end().reason << ")\n"
                  << "Parallel: "
                  << Utilities::MPI::n_mpi_processes(problem.mpi_communicator)
                  << " MPI rank(s), "
                  << (problem.discretisation.has_simplices()
                        ? "fully distributed"
                        : "p4est")
                  << " mesh\n";
  }



  // @sect4{RunOutput::write_time_series_row}
  //
  // One row per step: the counts and the force are sums over all ranks, written
  // by rank 0. They are computed on every rank before the other ranks return,
  // since the sums are collective operations. The row is flushed at once, so
  // that the file is complete up to the last finished step even if the run is
  // killed; a resumed run cuts it back to its checkpoint. The row is appended
  // (rewriting the whole file per step would cost O(steps^2)); a failed append
  // is undone and stops all ranks.
  template <int dim>
  void
  RunOutput<dim>::write_time_series_row(ViscoplasticContact<dim> &problem,
                                        const unsigned int        step,
                                        const double              time,
                                        const double              time_step,
                                        const ActiveSetResult    &result,
                                        const double              wall_time)
  {
    const auto states
      = problem.contact_set.count_states(problem.mpi_communicator);
    const double force
      = problem.contact_set.total_force(problem.mpi_communicator);
    const double size
      = problem.contact_enabled
          ? problem.contact_set.contact_area(problem.mpi_communicator)
          : 0.;
    const double peak
      = problem.contact_enabled
          ? problem.contact_set.peak_pressure(problem.mpi_communicator)
          : 0.;
    const std::vector<double> zone_forces
      = problem.contact_enabled
          ? problem.contact_set.zone_forces(problem.mpi_communicator)
          : std::vector<double>(problem.contact_zones.descriptions().size(),
                                0.);
    const std::vector<Tensor<1, dim>> reactions = problem.reaction_forces(time);
    const bool                        friction
      = problem.contact_enabled && problem.contact_set.has_friction();
    const std::array<unsigned int, 2> friction_counts
      = friction
          ? problem.contact_set.count_friction_states(problem.mpi_communicator)
          : std::array<unsigned int, 2>{{0, 0}};
    const std::vector<Tensor<1, dim>> tangential_forces
      = friction
          ? problem.contact_set.zone_tangential_forces(problem.mpi_communicator)
          : std::vector<Tensor<1, dim>>();
    const bool pairs = problem.contact_enabled
                       && !problem.contact_zones.pair_numbers().empty();
    const std::vector<std::array<Tensor<1, dim>, 2>> side_forces
      = pairs ? problem.contact_set.zone_side_forces(problem.mpi_communicator)
              : std::vector<std::array<Tensor<1, dim>, 2>>();
    const std::vector<std::array<double, 2>> zone_areas
      = pairs
          ? problem.contact_set.zone_areas_and_peaks(problem.mpi_communicator)
          : std::vector<std::array<double, 2>>();
    std::string failure;
    if (Utilities::MPI::this_mpi_process(problem.mpi_communicator) == 0)
      {
        std::ostringstream row;
        row << std::setprecision(10) << step << ',' << time << ','
            << result.iterations() << ',' << states[0] << ',' << states[1]
            << ',' << states[2] << ',' << force << ',' << problem.max_von_mises
            << ',' << wall_time << ',' << result.inner_iterations() << ','
            << time_step << ',' << problem.error_estimate << ',' << size << ','
            << peak;
        if (zone_forces.size() > 1)
          for (const double zone_force : zone_forces)
            row << ',' << zone_force;
        // A component that balances to round-off of the forces (the
        // horizontal reaction of a vertical load, say) is written as 0,
        // not as the digits of the rounding.
        double scale = std::abs(force);
        for (const Tensor<1, dim> &reaction : reactions)
          for (unsigned int c = 0; c < dim; ++c)
            scale = std::max(scale, std::abs(reaction[c]));
        for (const Tensor<1, dim> &reaction : reactions)
          for (unsigned int c = 0; c < dim; ++c)
            row << ','
                << (std::abs(reaction[c]) > 1e-12 * scale ? reaction[c] : 0.);
        if (friction)
          {
            row << ',' << friction_counts[0] << ',' << friction_counts[1];
            const auto &zones = problem.contact_zones.descriptions();
            for (unsigned int zone = 0; zone < zones.size(); ++zone)
              if (zones[zone].friction->has_friction())
                for (unsigned int c = 0; c < dim; ++c)
                  row << ','
                      << (std::abs(tangential_forces[zone][c]) > 1e-12 * scale
                            ? tangential_forces[zone][c]
                            : 0.);
          }
        if (pairs)
          {
            const auto &zones = problem.contact_zones.descriptions();
            for (unsigned int zone = 0; zone < zones.size(); ++zone)
              if (!zones[zone].opposite_ids.empty())
                {
                  for (const Tensor<1, dim> &side_force : side_forces[zone])
                    for (unsigned int c = 0; c < dim; ++c)
                      row << ','
                          << (std::abs(side_force[c]) > 1e-12 * scale
                                ? side_force[c]
                                : 0.);
                  row << ',' << zone_areas[zone][0] << ','
                      << zone_areas[zone][1];
                }
          }
        row << '\n';
        failure = output_folder->append("time_series.csv", row.str());
      }
    FileOutput::agree_on_problem(failure, problem.mpi_communicator);
  }



  // @sect4{RunOutput::write_contact_profile}
  //
  // contact_profile_NNNN.csv: the state of every contact node along
  // Gamma_3 (contact_set.h), written by all ranks into one file; with
  // contact pairs also opposite_profile_NNNN.csv, the same columns at the
  // vertices of the opposite sides that the zones cover (OppositeSide).
  //
  // Collective: each rank formats the lines of its own contact nodes, and the
  // blocks are written in rank order at offsets from a prefix sum, so no rank
  // gathers the others' nodes (OutputFolder::stage_collectively()).
  template <int dim>
  void
  RunOutput<dim>::write_contact_profile(const ViscoplasticContact<dim> &problem,
                                        const unsigned int              step,
                                        const double                    time)
  {
    std::vector<std::pair<std::string, std::string>> profiles;
    const auto name = [step](const std::string &kind) {
      std::ostringstream name;
      name << kind << "_profile_" << std::setw(4) << std::setfill('0') << step
           << ".csv";
      return name.str();
    };
    profiles.emplace_back(name("contact"),
                          problem.contact_set.profile_text(time));
    if (problem.contact_set.has_pairs())
      profiles.emplace_back(name("opposite"),
                            problem.contact_set.opposite_profile_text(time));
    for (const auto &[file, text] : profiles)
      {
        output_folder->record_files({file});
        output_folder->stage_collectively(file,
                                          "",
                                          text.data(),
                                          text.size(),
                                          problem.mpi_communicator);
        output_folder->commit();
      }
  }



  // @sect4{RunOutput::write_results}
  //
  // One .pvtu record per output step (with at most 8 .vtu pieces, whatever
  // the number of ranks, each written by a group of ranks), listed with its
  // time in solution.pvd. The displacement is a nodal vector field (ParaView's
  // "Warp By Vector" shows the deformed body). The stresses, their
  // viscoplastic part sigma - E eps(u) and the von Mises stress are
  // constant per cell (averaged over the stress points of a hypercube);
  // like every field of a deal.II .vtu file they are written at the
  // vertices of each cell, so ParaView lists them as point data,
  // discontinuous from cell to cell. The contact fields are nodal, zero
  // away from Gamma_3; "subdomain" is the rank that owns the cell, and
  // "material_id" (with several materials) the cell's material id. In plane
  // strain "stress_zz" is the out-of-plane stress.
  //
  // With another file stem (failed_step) the record is written for
  // inspection only and not listed in solution.pvd.
  //
  // In parallel, each rank writes the patches of its own cells, so every field
  // must be complete there: the cell fields on the owned cells, and the nodal
  // fields at every vertex of the owned cells, the ghosts included.
  template <int dim>
  void
  RunOutput<dim>::write_results(ViscoplasticContact<dim> &problem,
                                const unsigned int        step,
                                const double              time,
                                const std::string        &stem)
  {
    TimerOutput::Scope t(problem.report.timer(), "Output");
    const Fields       fields = compute_fields(problem);

    // The displacement is one vector field of dim components, as are the
    // tangential traction and the slip; the stress components get names
    // like stress_xy.
    const auto vector_field = [](const std::string &name) {
      return std::make_pair(
        std::vector<std::string>(dim, name),
        std::vector<DataComponentInterpretation::DataComponentInterpretation>(
          dim,
          DataComponentInterpretation::component_is_part_of_vector));
    };
    DataOut<dim> data_out;
    data_out.attach_triangulation(*problem.triangulation);
    {
      const auto [names, interpretation] = vector_field("displacement");
      data_out.add_data_vector(problem.dof_handler,
                               problem.solution,
                               names,
                               interpretation);
    }
    fields.add_to(data_out, problem.dof_handler, problem.scalar_dof_handler);
    // Time and step number go into the .vtu files themselves; the data are
    // compressed with zlib's fastest level.
    DataOutBase::VtkFlags flags(time, step);
    flags.compression_level = DataOutBase::VtkFlags::best_speed;
    data_out.set_flags(flags);
    // The .vtu pieces are written by groups of ranks (at most 8 files), and
    // rank 0 writes the .pvtu record that lists them; the step number
    // has 4 digits in the file names. Every file goes to a temporary name
    // first, and a failure on any rank stops all ranks with the file and the
    // reason (robustness/vtu_record.h).
    const std::string record = write_vtu_record(data_out,
                                                flags,
                                                stem,
                                                step,
                                                problem.stress_points.cells(),
                                                problem.discretisation.mapping,
                                                *output_folder,
                                                problem.mpi_communicator);
    // Only rank 0 keeps the list of records and rewrites solution.pvd with it
    // after every record; the list goes into the checkpoints, so that a resumed
    // run extends the same .pvd file. The record and the .pvd list are
    // committed together, once every piece is in place.
    if (stem == "solution"
        && Utilities::MPI::this_mpi_process(problem.mpi_communicator) == 0)
      {
        times_and_names.emplace_back(time, record);
        std::ostringstream pvd;
        DataOutBase::write_pvd_record(pvd, times_and_names);
        output_folder->record_files({"solution.pvd"});
        output_folder->stage("solution.pvd",
                             pvd.str(),
                             OutputFolder::Replace::own);
      }
    output_folder->commit();
  }



  // @sect4{RunOutput::Fields::add_to}
  //
  // The fields to a record, after the displacement: per cell the stress
  // components (named like stress_xy) and their viscoplastic parts, the
  // von Mises stress, the subdomain, the material id and sigma_zz where
  // computed; at the vertices the contact fields, and with friction the
  // tangential traction and the slip (vector fields) and the stick/slip
  // state.
  template <int dim>
  void
  RunOutput<dim>::Fields::add_to(
    DataOut<dim>          &data_out,
    const DoFHandler<dim> &dof_handler,
    const DoFHandler<dim> &scalar_dof_handler) const
  {
    const char *axes = "xyz";
    for (unsigned int i = 0; i < stress.size(); ++i)
      {
        const auto index
          = SymmetricTensor<2, dim>::unrolled_to_component_indices(i);
        const std::string suffix = {axes[index[0]], axes[index[1]]};
        data_out.add_data_vector(stress[i],
                                 "stress_" + suffix,
                                 DataOut<dim>::type_cell_data);
        data_out.add_data_vector(viscoplastic[i],
                                 "viscoplastic_stress_" + suffix,
                                 DataOut<dim>::type_cell_data);
      }
    for (const auto &[field, name] :
         {std::pair<const Vector<float> *, std::string>{&von_mises,
                                                        "von_mises_stress"},
          {&subdomain, "subdomain"},
          {&material_id, "material_id"},
          {&stress_zz, "stress_zz"}})
      if (field->size() > 0)
        data_out.add_data_vector(*field, name, DataOut<dim>::type_cell_data);
    const std::vector<std::string> contact_names
      = ContactSet<dim>::output_field_names();
    for (unsigned int i = 0; i < contact.size(); ++i)
      data_out.add_data_vector(scalar_dof_handler,
                               contact[i],
                               contact_names[i]);
    if (friction_state.size() > 0)
      {
        for (const auto &[field, name] :
             {std::pair<const VectorType *, std::string>{&tangential_traction,
                                                         "tangential_traction"},
              {&slip, "slip"}})
          {
            const auto [names, interpretation] = vector_field<dim>(name);
            data_out.add_data_vector(dof_handler,
                                     *field,
                                     names,
                                     interpretation);
          }
        data_out.add_data_vector(scalar_dof_handler,
                                 friction_state,
                                 "friction_state");
      }
    if (memory_pressure.size() > 0)
      data_out.add_data_vector(scalar_dof_handler,
                               memory_pressure,
                               "memory_pressure");
    if (bonding.size() > 0)
      data_out.add_data_vector(scalar_dof_handler, bonding, "bonding");
    if (wear.size() > 0)
      data_out.add_data_vector(scalar_dof_handler, wear, "wear");
    if (damage.size() > 0)
      data_out.add_data_vector(scalar_dof_handler, damage, "damage");
  }



  // @sect4{RunOutput::compute_fields}
  //
  // The cell fields have one entry per active cell of this rank's view of
  // the mesh (owned, ghost and artificial cells), indexed by
  // active_cell_index() as DataOut expects; only the entries of owned cells
  // are set, and only those are written. Per owned cell: the average over
  // its stress points of sigma_n, of its viscoplastic part and of the von
  // Mises stress, its subdomain, with several materials its material id,
  // and in plane strain sigma_zz. The nodal contact fields live on the
  // scalar DoFHandler, the friction fields (with friction: the tangential
  // traction and the slip of the last step, and the stick/slip state) on
  // the displacement's and the scalar one, with a memory term the memory
  // pressure on the scalar one; the ghost import gives every
  // rank the values at all vertices of its cells, also those of contact
  // nodes owned by a neighbour.
  template <int dim>
  typename RunOutput<dim>::Fields
  RunOutput<dim>::compute_fields(const ViscoplasticContact<dim> &problem)
  {
    const unsigned int n_components = dim * (dim + 1) / 2;
    const unsigned int n_cells      = problem.triangulation->n_active_cells();
    const unsigned int n_q          = problem.discretisation.n_stress_points();
    Fields             fields;
    fields.stress.assign(n_components, Vector<float>(n_cells));
    fields.viscoplastic.assign(n_components, Vector<float>(n_cells));
    fields.von_mises.reinit(n_cells);
    fields.subdomain.reinit(n_cells);
    if (problem.materials.laws().size() > 1)
      fields.material_id.reinit(n_cells);
    bool plane_strain = false;
    if constexpr (dim == 2)
      plane_strain = (problem.parameters.plane_model
                      == Parameters::PlaneModel::plane_strain);
    if (plane_strain)
      fields.stress_zz.reinit(n_cells);
    for (unsigned int k = 0; k < problem.stress_points.n_cells(); ++k)
      {
        const auto                    &cell = problem.stress_points.cells()[k];
        const unsigned int             c    = cell->active_cell_index();
        const SymmetricTensor<4, dim> &E
          = problem.materials.of_cell(k).elasticity_tensor();
        fields.subdomain[c] = cell->subdomain_id();
        if (fields.material_id.size() > 0)
          fields.material_id[c] = cell->material_id();
        for (unsigned int q = 0; q < n_q; ++q)
          {
            const QuadraturePointHistory<dim> &state
              = problem.quadrature_point_history[std::size_t(k) * n_q + q];
            // The viscoplastic part is recomputed as sigma_n - E eps(u_n)
            // instead of being read from the stored history, because with the
            // explicit update the stored history is already H_{n+1}, the one of
            // the next step (after every step but the last).
            const SymmetricTensor<2, dim> vp
              = state.stress
                - E
                    * symmetrize(
                      problem.stress_points
                        .displacement_gradient(problem.solution, k, q));
            // Component i of the symmetric tensor, in deal.II's unrolled order
            // (the diagonal first); each stress point contributes 1/n_q of the
            // cell's average.
            for (unsigned int i = 0; i < n_components; ++i)
              {
                const auto index
                  = SymmetricTensor<2, dim>::unrolled_to_component_indices(i);
                fields.stress[i][c] += state.stress[index] / n_q;
                fields.viscoplastic[i][c] += vp[index] / n_q;
              }
            fields.von_mises[c]
              += problem.materials.von_mises_stress(k, state) / n_q;
            if constexpr (dim == 2)
              if (plane_strain)
                fields.stress_zz[c] += state.stress_zz / n_q;
          }
      }

    fields.contact.assign(ContactSet<dim>::output_field_names().size(),
                          VectorType(problem.scalar_partitioner));
    if (problem.contact_enabled)
      problem.contact_set.fill_output_fields(fields.contact);
    for (VectorType &field : fields.contact)
      field.update_ghost_values();
    if (problem.contact_enabled && problem.contact_set.has_friction())
      {
        fields.tangential_traction.reinit(problem.solution);
        fields.slip.reinit(problem.solution);
        fields.friction_state.reinit(problem.scalar_partitioner);
        problem.contact_set.fill_friction_fields(fields.tangential_traction,
                                                 fields.slip,
                                                 fields.friction_state);
        for (VectorType *field : {&fields.tangential_traction,
                                  &fields.slip,
                                  &fields.friction_state})
          field->update_ghost_values();
      }
    if (problem.contact_enabled && problem.contact_set.has_memory())
      {
        fields.memory_pressure.reinit(problem.scalar_partitioner);
        problem.contact_set.fill_memory_field(fields.memory_pressure);
        fields.memory_pressure.update_ghost_values();
      }
    if (problem.contact_enabled
        && (problem.contact_set.has_adhesion() || problem.contact_set.has_wear()
            || problem.contact_set.has_cohesion()))
      {
        if (problem.contact_set.has_adhesion())
          fields.bonding.reinit(problem.scalar_partitioner);
        if (problem.contact_set.has_wear())
          fields.wear.reinit(problem.scalar_partitioner);
        if (problem.contact_set.has_cohesion())
          fields.damage.reinit(problem.scalar_partitioner);
        problem.contact_set.fill_history_fields(fields.bonding,
                                                fields.wear,
                                                fields.damage);
        for (VectorType *field :
             {&fields.bonding, &fields.wear, &fields.damage})
          if (field->size() > 0)
            field->update_ghost_values();
      }
    return fields;
  }



  // @sect4{RunOutput::print_summary}
  //
  // The final state as the summary shows it (run/run_report.h): the L2 norms
  // of eps(u) and sigma with the stress quadrature (each rank sums over its
  // own stress points, and only the two sums are reduced), the contact, the
  // norms of u, and what the back end did. With Measure cost ratios, the
  // cost of an average step relative to the work every step has without
  // contact, measured now in the same process: one solve with the step
  // operator (the back end's, no contact) and one stress update with the
  // history load. These ratios are what the benchmarks report.
  template <int dim>
  void
  RunOutput<dim>::print_summary(ViscoplasticContact<dim> &problem)
  {
    const unsigned int n_q         = problem.discretisation.n_stress_points();
    double             strain_norm = 0, stress_norm = 0;
    for (unsigned int k = 0; k < problem.stress_points.cells().size(); ++k)
      for (unsigned int q = 0; q < n_q; ++q)
        {
          const SymmetricTensor<2, dim> strain = symmetrize(
            problem.stress_points.displacement_gradient(problem.solution,
                                                        k,
                                                        q));
          const SymmetricTensor<2, dim> &sigma
            = problem.quadrature_point_history[std::size_t(k) * n_q + q].stress;
          const double JxW = problem.stress_points.JxW(k, q);
          strain_norm += (strain * strain) * JxW;
          stress_norm += (sigma * sigma) * JxW;
        }
    // All collective (global norms, sums over the ranks): every rank computes
    // them, rank 0 prints.
    const auto &statistics = problem.contact_solver->statistics();
    const RunReport::FinalState state{
      problem.parameters.implicit_update(),
      std::sqrt(Utilities::MPI::sum(strain_norm, problem.mpi_communicator)),
      std::sqrt(Utilities::MPI::sum(stress_norm, problem.mpi_communicator)),
      problem.max_von_mises,
      problem.contact_set.count_states(problem.mpi_communicator),
      problem.contact_set.total_force(problem.mpi_communicator),
      problem.solution.l2_norm(),
      problem.solution.linfty_norm(),
      problem.schedule.step_number(),
      problem.schedule.n_rejected_steps(),
      problem.plan.step_cycles(),
      problem.plan.step_cycles_dropped(),
      statistics.operator_setups,
      statistics.solves,
      statistics.inner_iterations};
    // The peak memory before the cost measurement, whose extra solves may
    // build a preconditioner the run did not need.
    if (problem.parameters.print_timing_summary)
      problem.report.record_peak_memory("over the run");
    problem.report.print_summary(state);
    if (problem.parameters.print_timing_summary)
      problem.report.print_timer_summary();
    if (problem.parameters.measure_cost_ratios)
      problem.report.print_cost_measurement(measure_reference_costs(problem));
  }



  // @sect4{RunOutput::measure_reference_costs}
  //
  // The reference costs, measured now (the run is over, so the state may
  // be overwritten) and taken as the maximum over the ranks.
  template <int dim>
  RunReport::CostMeasurement
  RunOutput<dim>::measure_reference_costs(ViscoplasticContact<dim> &problem)
  {
    VectorType reference(problem.solution);
    // The solve with the operator the back end holds at the end of the run (K
    // for the explicit update, the last tangent for the implicit one), on the
    // external load; where an obstacle or prescribed displacements alone load
    // the body (a zero load costs no iteration), on K u, the load that holds
    // the final displacement. The wall time per solve is the maximum over the
    // ranks, as the slowest rank sets the pace.
    VectorType load(problem.external_load);
    const bool holding_load = (load.l2_norm() == 0);
    if (holding_load)
      problem.contact_solver->apply_operator(load, problem.solution);
    // One solve first, untimed: it builds the preconditioner of the operator
    // where the back end has none yet (the AMG of K alone), a set-up that is
    // not part of a solve. Then one timed solve, and two more where it took
    // less than a second (they average out the noise of short solves; at
    // 10^7 dofs they would add minutes to the run). The decision is the
    // slowest rank's, so every rank takes it.
    problem.contact_solver->solve_without_contact(load, reference);
    Timer        timer;
    unsigned int krylov_iterations
      = problem.contact_solver->solve_without_contact(load, reference)
          .inner_iterations;
    const unsigned int repetitions
      = Utilities::MPI::max(timer.wall_time(), problem.mpi_communicator) > 1
          ? 1
          : 3;
    for (unsigned int r = 1; r < repetitions; ++r)
      krylov_iterations
        += problem.contact_solver->solve_without_contact(load, reference)
             .inner_iterations;
    const double solve_time
      = Utilities::MPI::max(timer.wall_time() / repetitions,
                            problem.mpi_communicator);
    // Products with the operator, as many as a solve took iterations (at
    // least 3): with the solve they split a Krylov iteration into the
    // operator and the preconditioner with the vector updates.
    const unsigned int products = std::max(3u, krylov_iterations / repetitions);
    timer.restart();
    for (unsigned int r = 0; r < products; ++r)
      problem.contact_solver->apply_operator(reference, load);
    const double operator_time
      = Utilities::MPI::max(timer.wall_time() / products,
                            problem.mpi_communicator);
    // One stress update (for the explicit update with the history update and
    // the assembly of its load): the work every step does besides the solve.
    timer.restart();
    for (unsigned int r = 0; r < repetitions; ++r)
      problem.update_stresses(problem.schedule.grid_step_length(),
                              problem.schedule.grid_step_length());
    const double update_time
      = Utilities::MPI::max(timer.wall_time() / repetitions,
                            problem.mpi_communicator);
    // The threads of the BLAS in the sparse factorisation (1 where the BLAS
    // has none).
    unsigned int factorisation_threads = 1;
    {
      const BlasThreadsOfRank threads;
      factorisation_threads = blas_threads();
    }
    return {problem.schedule.step_number(),
            solve_time,
            krylov_iterations / repetitions,
            operator_time,
            holding_load,
            update_time,
            factorisation_threads,
            double(problem.dof_handler.n_dofs())};
  }



  template class RunOutput<2>;
  template class RunOutput<3>;
} // namespace ViscoContact
