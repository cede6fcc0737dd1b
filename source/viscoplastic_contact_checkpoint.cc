// Checkpoint and resume of ViscoplasticContact<dim>: the state after a
// time step, written so that a resumed run continues exactly as the
// uninterrupted one would have.

#include <deal.II/base/exceptions.h>

#include "checkpoint.h"
#include "viscoplastic_contact.h"

namespace ViscoContact
{
  namespace
  {
    // Bumped whenever the layout of the files changes.
    constexpr std::uint32_t serial_checkpoint_version = 1;
  } // namespace



  // @sect4{ViscoplasticContact::write_checkpoint}
  //
  // The mesh is not stored: it is rebuilt from the parameter file, which
  // makes it the same mesh with the same numbering. Stored are the time
  // schedule (cut steps included), the displacement u_n, the state at every
  // stress point (sigma_n, the history of the next step, the plastic
  // multiplier), the pieces and last (r, z) of the contact nodes (the warm
  // start of the next active set, so that its iteration counts are those of
  // the uninterrupted run), the counters, and the .pvd record.
  template <int dim>
  void
  ViscoplasticContact<dim>::write_checkpoint(const unsigned int         step,
                                             const std::vector<double> &times,
                                             const double wall_time)
  {
    TimerOutput::Scope t(computing_timer, "Checkpoint");
    std::filesystem::create_directories(
      checkpoint_directory(parameters.directory));
    CheckpointWriter out(checkpoint_file(parameters.directory, step, 0));
    CheckpointHeader header;
    header.version      = serial_checkpoint_version;
    header.dimension    = dim;
    header.step         = step;
    header.times        = times;
    header.wall_time    = wall_time;
    header.compute_time = time_loop_compute_time;
    header.write(out);
    out.write<std::uint32_t>(total_active_set_iterations);
    out.write<std::uint32_t>(total_newton_iterations);
    out.write(max_von_mises);
    out.write_vector(std::vector<double>(solution.begin(), solution.end()));
    out.write_vector(quadrature_point_history);
    if (contact_enabled)
      {
        const ContactActiveSetSolver::State state = active_set_solver.state();
        out.write_vector(state.pieces);
        out.write_vector(std::vector<double>(state.r.begin(), state.r.end()));
        out.write_vector(std::vector<double>(state.z.begin(), state.z.end()));
      }
    write_output_records(out, times_and_names);
    out.finish();

    CheckpointRecord record;
    record.step    = step;
    record.time    = times[step];
    record.n_ranks = 1;
    record.n_dofs  = dof_handler.n_dofs();
    publish_checkpoint(parameters.directory,
                       record,
                       last_checkpoint_step,
                       MPI_COMM_SELF);
    last_checkpoint_step = step;
  }



  // @sect4{ViscoplasticContact::resume_from_checkpoint}
  //
  // Reads what write_checkpoint() wrote, rebuilds what the time loop
  // derives from it (the history load of the next step), and cuts the time
  // series back to the checkpoint's step.
  template <int dim>
  unsigned int
  ViscoplasticContact<dim>::resume_from_checkpoint(std::vector<double> &times)
  {
    const CheckpointRecord record
      = read_checkpoint_record(parameters.directory, 1, dof_handler.n_dofs());
    const std::filesystem::path file
      = checkpoint_file(parameters.directory, record.step, 0);
    CheckpointReader in(file);
    const auto       damaged
      = [&](const bool ok) { check_checkpoint_content(ok, in); };
    CheckpointHeader header;
    header.read(in, serial_checkpoint_version, dim, record.step);
    const unsigned int step     = header.step;
    times                       = header.times;
    loop_time_offset            = header.wall_time;
    time_loop_compute_time      = header.compute_time;
    total_active_set_iterations = in.read<std::uint32_t>();
    total_newton_iterations     = in.read<std::uint32_t>();
    max_von_mises               = in.read<double>();

    const std::vector<double> u = in.read_vector<double>();
    damaged(u.size() == solution.size());
    std::copy(u.begin(), u.end(), solution.begin());
    const std::vector<QuadraturePointHistory<dim>> states
      = in.read_vector<QuadraturePointHistory<dim>>();
    damaged(states.size() == quadrature_point_history.size());
    quadrature_point_history = states;

    if (contact_enabled)
      {
        ContactActiveSetSolver::State state;
        state.pieces                = in.read_vector<unsigned int>();
        const std::vector<double> r = in.read_vector<double>();
        const std::vector<double> z = in.read_vector<double>();
        damaged(state.pieces.size() == contact_nodes.size()
                && r.size() == contact_nodes.size()
                && z.size() == contact_nodes.size());
        state.r.reinit(r.size());
        state.z.reinit(z.size());
        std::copy(r.begin(), r.end(), state.r.begin());
        std::copy(z.begin(), z.end(), state.z.begin());
        active_set_solver.set_state(state);
      }
    times_and_names = read_output_records(in);

    if (parameters.plasticity && parameters.stress_update == "explicit")
      assemble_history_load();
    truncate_time_series(std::filesystem::path(parameters.directory)
                           / "time_series.csv",
                         step);
    last_checkpoint_step = step;
    pcout << "Resuming from the checkpoint of step " << step
          << " (t = " << times[step] << ")\n";
    return step;
  }



  template class ViscoplasticContact<2>;
  template class ViscoplasticContact<3>;
} // namespace ViscoContact
