// The checkpoint of ViscoplasticContact<dim>: what a checkpoint stores per
// cell and in its header, and how a resumed run restores it (the file format
// is robustness/checkpoint_file.h).

#include <deal.II/base/exceptions.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/utilities.h>

#include <deal.II/grid/cell_id.h>

#include "robustness/checkpoint_file.h"
#include "robustness/mpi_tools.h"
#include "viscoplastic_contact.h"

#include <array>
#include <cstring>
#include <unordered_map>

namespace ViscoContact
{
  // @sect4{ViscoplasticContact::checkpoint_record_size}
  //
  // The five vectors of write_checkpoint() at the cell's dofs (u, the contact
  // state, u_{n-1}, the nodes' history, their friction state), then the
  // stress points;
  // QuadraturePointHistory holds only doubles, so the payload after the key
  // is a whole number of doubles.
  template <int dim>
  std::size_t
  ViscoplasticContact<dim>::checkpoint_record_size() const
  {
    static_assert(sizeof(QuadraturePointHistory<dim>) % sizeof(double) == 0);
    return sizeof(CellId::binary_type)
           + 5 * fe->n_dofs_per_cell() * sizeof(double)
           + stress_quadrature.size() * sizeof(QuadraturePointHistory<dim>);
  }



  // @sect4{ViscoplasticContact::write_checkpoint}
  //
  // The mesh is not stored: it is rebuilt from the parameter file, which
  // makes it the same mesh with the same cell ids (deal.II 9.4 cannot
  // reliably save and load fully distributed meshes on several ranks).
  // Stored are, in the header, the time schedule (cut steps included), the
  // counters and the .pvd record; per locally owned cell, keyed by its id:
  // the displacement values at the cell's dofs, the contact state at the
  // cell's dofs (the piece + 1 at the x-dof of a contact node, its force z
  // at the y-dof, zero elsewhere: the warm start of the next active set, so
  // that its iterations are those of the uninterrupted run), the start of
  // step n (u_{n-1}, and z_{n-1} at the x-dof of a contact node: what the
  // predicted start of the next step extrapolates from; zero if there is
  // none), the friction state of a contact node (its stick/slip state at
  // the x-dof, its tangential force t at the other dofs; zero without
  // friction), and the state of every stress point (sigma_n, the history of
  // the next step, the plastic multiplier).
  //
  // Storing values per cell means that a dof shared by several cells is stored
  // several times. In exchange, everything a cell needs travels with the cell's
  // id, and no global dof numbering, which changes with the number of ranks,
  // appears in the file. The contact state is stored the same way, as values at
  // the dofs of a contact node's vertex, for the same reason: the contact nodes
  // are numbered rank by rank, and their numbers mean nothing on another
  // partition.
  template <int dim>
  void
  ViscoplasticContact<dim>::write_checkpoint(const double wall_time)
  {
    const unsigned int step = schedule.step_number();
    TimerOutput::Scope t(report.timer(), "Checkpoint");
    // The folder and the two files go into the manifest before they exist.
    output_folder->create_folder(checkpoint_folder);
    output_folder->record_files({checkpoint_name(step), checkpoint_info});

    const ByteWriter                header  = checkpoint_header(wall_time);
    const std::array<VectorType, 4> vectors = checkpoint_vectors();

    // Collective: the file is complete (written and renamed, the rename on
    // the disk) before the record of the checkpoint is published, and only
    // then is the previous checkpoint's file removed. The records are made
    // as they are written, a piece at a time.
    write_record_file(
      *output_folder,
      checkpoint_name(step),
      header.bytes,
      stress_points.cells().size(),
      checkpoint_record_size(),
      [&](const std::size_t first, const std::size_t end, char *out) {
        write_cell_records(vectors, first, end, out);
      },
      mpi_communicator);
    output_folder->commit(/*durable=*/true);

    CheckpointRecord record;
    record.step    = step;
    record.time    = schedule.current_time();
    record.n_ranks = Utilities::MPI::n_mpi_processes(mpi_communicator);
    record.n_dofs  = dof_handler.n_dofs();
    record.entries = parameters.result_entries;
    publish_checkpoint(*output_folder, record, last_checkpoint_step);
    // What a resumed run cannot restore, this run forgets too.
    if (contact_enabled)
      contact_solver->forget_kept_state();
    last_checkpoint_step = step;
  }



  // @sect4{ViscoplasticContact::checkpoint_header}
  template <int dim>
  ByteWriter
  ViscoplasticContact<dim>::checkpoint_header(const double wall_time) const
  {
    // The header: what identifies the file (version, dim, step), the schedule
    // (with the step controller's state), the run's wall time and compute time
    // so far, the iteration counters, the largest von Mises stress, and the
    // list of .pvtu records for solution.pvd. That list is kept on rank 0 only
    // (output_results()), and rank 0's header is the one written.
    ByteWriter header;
    header.write(checkpoint_version);
    header.write<std::uint32_t>(dim);
    header.write<std::uint32_t>(schedule.step_number());
    schedule.save(header);
    report.save(header, wall_time);
    header.write(max_von_mises);
    header.write<std::uint64_t>(times_and_names.size());
    for (const auto &[time, name] : times_and_names)
      {
        header.write(time);
        header.write_string(name);
      }
    // Whether there is a start of the step to predict from, and whether the
    // back end has a state of its own (both the same on every rank).
    header.write<std::uint32_t>(predicted_start.has_start());
    // The uniqueness check's eigenvalue, if the run computed one.
    header.write<std::uint32_t>(uniqueness_eigenvalue.has_value());
    header.write(uniqueness_eigenvalue.value_or(0.));
    return header;
  }



  // @sect4{ViscoplasticContact::checkpoint_vectors}
  template <int dim>
  std::array<VectorType, 4>
  ViscoplasticContact<dim>::checkpoint_vectors() const
  {
    // The contact state as a displacement-sized vector: each owned contact node
    // writes into the owned entries of its own dofs. The ghost import then
    // makes these values visible in every cell that has the node as a vertex,
    // also on the ranks that do not own the node.
    VectorType contact_state(solution);
    contact_state = 0;
    if (contact_enabled)
      for (unsigned int i = 0; i < contact_set.size(); ++i)
        {
          contact_state.local_element(contact_set.node(i).local_dofs[0])
            = contact_set.piece(i) + 1.;
          contact_state.local_element(contact_set.node(i).local_dofs[1])
            = contact_set.z[i];
        }
    contact_state.update_ghost_values();
    // The start of step n in the same form: u_{n-1}, and per contact node
    // z_{n-1} at its x-dof; and the friction state.
    VectorType start_displacement(solution), node_history(solution),
      friction_state(solution);
    start_displacement = 0;
    node_history       = 0;
    friction_state     = 0;
    if (predicted_start.has_start())
      start_displacement = predicted_start.displacement();
    for (unsigned int i = 0; i < contact_set.size() && contact_enabled; ++i)
      {
        const auto &dofs = contact_set.node(i).local_dofs;
        if (predicted_start.has_start())
          node_history.local_element(dofs[0])
            = predicted_start.contact_forces()[i];
        friction_state.local_element(dofs[0]) = contact_set.friction_state(i);
        for (unsigned int j = 0; j < contact_set.n_tangential(i); ++j)
          friction_state.local_element(dofs[1 + j]) = contact_set.t[i][j];
      }
    start_displacement.update_ghost_values();
    node_history.update_ghost_values();
    friction_state.update_ghost_values();
    return {{std::move(contact_state),
             std::move(start_displacement),
             std::move(node_history),
             std::move(friction_state)}};
  }



  // @sect4{ViscoplasticContact::write_cell_records}
  template <int dim>
  void
  ViscoplasticContact<dim>::write_cell_records(
    const std::array<VectorType, 4> &vectors,
    const std::size_t                first,
    const std::size_t                end,
    char                            *out) const
  {
    // A record: the cell id in binary form, the dofs_per_cell values of u, of
    // the contact state, of u_{n-1} and of the nodes' history, in the cell's
    // dof order, and the n_q stress-point records of the cell, copied as
    // raw bytes (QuadraturePointHistory is plain data: symmetric tensors and
    // doubles, with the zz components in 2D).
    using Key                                          = CellId::binary_type;
    const unsigned int                   dofs_per_cell = fe->n_dofs_per_cell();
    const unsigned int                   n_q = stress_quadrature.size();
    std::vector<types::global_dof_index> dof_indices(dofs_per_cell);
    // The cells in the order of stress_points.cells(); (*vector)(dof) reads
    // owned and ghost entries alike, which is why the vectors must have their
    // ghost values here.
    for (std::size_t k = first; k < end; ++k)
      {
        const Key key
          = stress_points.cells()[k]->id().template to_binary<dim>();
        std::memcpy(out, &key, sizeof(Key));
        out += sizeof(Key);
        stress_points.cells()[k]->get_dof_indices(dof_indices);
        for (const VectorType *vector : std::array<const VectorType *, 5>{
               {&solution, &vectors[0], &vectors[1], &vectors[2], &vectors[3]}})
          for (const types::global_dof_index dof : dof_indices)
            {
              const double value = (*vector)(dof);
              std::memcpy(out, &value, sizeof(double));
              out += sizeof(double);
            }
        // The stress-point records of cell k are contiguous in the flat array:
        // entries k * n_q to k * n_q + n_q - 1.
        std::memcpy(out,
                    &quadrature_point_history[std::size_t(k) * n_q],
                    n_q * sizeof(QuadraturePointHistory<dim>));
        out += n_q * sizeof(QuadraturePointHistory<dim>);
      }
  }



  // @sect4{ViscoplasticContact::resume_from_checkpoint}
  //
  // Reads what write_checkpoint() wrote, on any number of ranks: each rank
  // reads its share of the records, the records travel to the owners of
  // their cells, and every owned cell must be found. Then what the time
  // loop derives from the state is rebuilt (the ghosts, the history load of
  // the next step).
  //
  // It runs after set-up, on the mesh rebuilt from the parameter file; run()
  // continues with the step after the checkpoint's. Everything the loop needs
  // is restored: u_n with its ghosts, the pieces and (r, z) of the contact
  // nodes, every stress-point record, the schedule, the counters and the .pvd
  // list. What the run's summary counts per process (assemblies, set-ups of
  // the back end) starts again from the set-up of the resumed run. The rows
  // of time_series.csv after the checkpoint are removed once the output
  // folder is prepared (prepare_output_directory()).
  template <int dim>
  void
  ViscoplasticContact<dim>::resume_from_checkpoint()
  {
    // The records of an adaptive run are those of its adapted mesh, which is
    // rebuilt first (mesh_adaptation.cc); so are those of a run with initial
    // cycles, whose mesh is not the one make_grid() starts from.
    if (parameters.adaptive_refinement || plan.initial_cycles() > 0)
      restore_checkpoint_mesh();
    const CheckpointRecord checkpoint
      = read_checkpoint_record(parameters.directory,
                               dof_handler.n_dofs(),
                               parameters.result_entries);
    const std::string file
      = output_folder->path(checkpoint_name(checkpoint.step));

    // The header first (a file of another scene, or an End time before the
    // checkpoint, is refused before any cell is touched); then the state of
    // every owned cell, as the file is read. The decision is reduced over the
    // ranks, so that all throw if any cell was not found. Then the ghosts of
    // u are imported, as the stress update and the output expect.
    std::vector<char>         header_bytes;
    ByteReader                header(header_bytes, file);
    CheckpointFlags           flags{false};
    std::pair<double, double> next_step_lengths;
    CellRecordVectors         vectors{solution, solution, solution, solution};
    const bool                complete
      = restore_cell_records(file, header_bytes, vectors, [&]() {
          flags             = read_checkpoint_header(header, checkpoint.step);
          next_step_lengths = continue_schedule_after_checkpoint();
        });
    header.check(Utilities::MPI::min(complete ? 1 : 0, mpi_communicator) == 1);
    solution.update_ghost_values();
    if (contact_enabled)
      restore_contact_nodes(vectors, header);
    restore_prediction_start(vectors, flags);

    // The explicit update's history load is not stored: it is assembled from
    // the restored histories, as update_stresses() would have left it (for
    // the next step's length of this run's schedule, if that changed). The
    // implicit update needs nothing more; its history enters through the
    // internal force.
    if (explicit_history_update()
        && next_step_lengths.first != next_step_lengths.second)
      rescale_history_increment(next_step_lengths.first,
                                next_step_lengths.second);
    else if (explicit_history_update())
      assemble_history_load();
    last_checkpoint_step = checkpoint.step;
    pcout << "Resuming from the checkpoint of step " << checkpoint.step
          << " (t = " << schedule.current_time() << ", written on "
          << checkpoint.n_ranks << " MPI rank(s))\n";
  }



  // @sect4{ViscoplasticContact::read_checkpoint_header}
  //
  // The header is checked field by field against this run: version,
  // dimension and step. The schedule replaces the one computed from the
  // parameter file, since the interrupted run may have cut steps.
  template <int dim>
  typename ViscoplasticContact<dim>::CheckpointFlags
  ViscoplasticContact<dim>::read_checkpoint_header(ByteReader        &header,
                                                   const unsigned int step)
  {
    header.check(header.read<std::uint32_t>() == checkpoint_version);
    header.check(header.read<std::uint32_t>() == dim);
    header.check(header.read<std::uint32_t>() == step);
    schedule.load(header);
    header.check(schedule.step_number() == step);
    report.load(header);
    max_von_mises = header.read<double>();
    times_and_names.clear();
    const std::uint64_t n_records = header.read<std::uint64_t>();
    for (std::uint64_t i = 0; i < n_records; ++i)
      {
        const double time = header.read<double>();
        times_and_names.emplace_back(time, header.read_string());
      }
    CheckpointFlags flags;
    flags.has_step_start        = header.read<std::uint32_t>() == 1;
    const bool   has_eigenvalue = header.read<std::uint32_t>() == 1;
    const double eigenvalue     = header.read<double>();
    if (has_eigenvalue)
      uniqueness_eigenvalue = eigenvalue;
    return flags;
  }



  // @sect4{ViscoplasticContact::continue_schedule_after_checkpoint}
  //
  // End time is the one entry of the scene a resumed run may change (to go
  // further, or to stop earlier). The levels up to the checkpoint stay those
  // of the interrupted run (with its cut steps); the levels after it are
  // those of the new schedule (TimeSchedule::continue_to()). With the same
  // End time and Profile times they are the same levels, so without cuts the
  // resumed run repeats the uninterrupted one exactly. If the next step's
  // length changes, the history the explicit update stored for the old one is
  // rescaled by the caller, once the stress points are restored.
  template <int dim>
  std::pair<double, double>
  ViscoplasticContact<dim>::continue_schedule_after_checkpoint()
  {
    const double old_next_step = schedule.step_length();
    if (!schedule.is_adaptive() && parameters.end_time == schedule.end_time())
      return {old_next_step, old_next_step};
    // An adaptive run may end at the checkpoint; a fixed schedule always has
    // a level after it.
    const double checkpoint_time = schedule.current_time();
    AssertThrow(schedule.is_adaptive() ? parameters.end_time >= checkpoint_time
                                       : parameters.end_time > checkpoint_time,
                ExcMessage("Invalid parameter <End time> in subsection "
                           "<Time>: value <"
                           + std::to_string(parameters.end_time)
                           + ">, but the checkpoint to resume from is at t = "
                           + std::to_string(checkpoint_time)
                           + "; accepted: an End time after the "
                             "checkpoint's time."));
    schedule.continue_to(landing_targets());
    return {old_next_step, schedule.step_length()};
  }



  // @sect4{ViscoplasticContact::restore_cell_records}
  //
  // The records of this rank's share of the file go to the owners of their
  // cells, a piece of the file at a time (read_record_file()), so that no
  // rank holds more than a piece of them besides the run's own data. Each
  // becomes a (key, payload) pair: the key is the binary cell id, the
  // payload the doubles of u, of the contact state, of the start of the
  // step, of the nodes' history and of the stress points. Each rank asks
  // once for the keys of its own cells; a RecordRouter meets the holders
  // and the askers at a rendezvous rank chosen by a hash of the key, so no
  // rank needs to know who holds which cell.
  //
  // The received values go into the owned entries only: a dof of an owned
  // cell that another rank owns is set there, by the rank that owns it (every
  // owned dof lies on at least one owned cell). A cell whose record is
  // missing, duplicated or of the wrong size makes the checkpoint
  // incomplete.
  template <int dim>
  bool
  ViscoplasticContact<dim>::restore_cell_records(
    const std::string           &file,
    std::vector<char>           &header,
    CellRecordVectors           &vectors,
    const std::function<void()> &check_header)
  {
    using Key                        = CellId::binary_type;
    const unsigned int dofs_per_cell = fe->n_dofs_per_cell();
    const unsigned int n_q           = stress_quadrature.size();
    const std::size_t  record_size   = checkpoint_record_size();
    const unsigned int n_doubles = (record_size - sizeof(Key)) / sizeof(double);

    // Where the record of each owned cell goes: its place in
    // stress_points.cells().
    std::unordered_map<std::string, unsigned int> place_of;
    std::vector<std::string> requests(stress_points.cells().size());
    for (unsigned int k = 0; k < stress_points.cells().size(); ++k)
      {
        const Key key
          = stress_points.cells()[k]->id().template to_binary<dim>();
        requests[k].assign(reinterpret_cast<const char *>(&key), sizeof(Key));
        place_of.emplace(requests[k], k);
      }
    const MPITools::RecordRouter router(requests, mpi_communicator);
    requests = std::vector<std::string>();

    VectorType *const targets[5] = {&solution,
                                    &vectors.contact_state,
                                    &vectors.start_displacement,
                                    &vectors.node_history,
                                    &vectors.friction_state};
    for (VectorType *target : targets)
      *target = 0;
    std::vector<unsigned int> times_found(stress_points.cells().size(), 0);
    std::vector<types::global_dof_index> dof_indices(dofs_per_cell);
    bool                                 complete = true;
    const auto                           restore
      = [&](const std::string &key, const std::vector<double> &values) {
          const auto entry = place_of.find(key);
          if (entry == place_of.end() || values.size() != n_doubles)
            {
              complete = false;
              return;
            }
          const unsigned int k = entry->second;
          ++times_found[k];
          stress_points.cells()[k]->get_dof_indices(dof_indices);
          for (unsigned int i = 0; i < dofs_per_cell; ++i)
            if (locally_owned_dofs.is_element(dof_indices[i]))
              for (unsigned int v = 0; v < 5; ++v)
                (*targets[v])(dof_indices[i]) = values[v * dofs_per_cell + i];
          // The stress-point records go back to their place k * n_q + q, byte
          // for byte.
          std::memcpy(&quadrature_point_history[std::size_t(k) * n_q],
                      values.data() + 5 * dofs_per_cell,
                      n_q * sizeof(QuadraturePointHistory<dim>));
        };
    read_record_file(
      file,
      header,
      record_size,
      [&](const std::vector<char> &piece) {
        std::vector<MPITools::Record> records(piece.size() / record_size);
        for (std::size_t r = 0; r < records.size(); ++r)
          {
            const char *in = piece.data() + r * record_size;
            records[r].first.assign(in, sizeof(Key));
            records[r].second.resize(n_doubles);
            std::memcpy(records[r].second.data(),
                        in + sizeof(Key),
                        n_doubles * sizeof(double));
          }
        for (const auto &[key, values] : router.deliver(records))
          restore(key, values);
      },
      mpi_communicator,
      check_header);
    for (const unsigned int n : times_found)
      complete = complete && (n == 1);
    return complete;
  }



  // @sect4{ViscoplasticContact::restore_contact_nodes}
  //
  // The contact nodes, on the rank that owns them now: the piece and the
  // force from the values at their own dofs (the piece was stored + 1, so
  // that 0 means "no contact node"), r = u.nu_i from the restored
  // displacement. The next active set then starts from the pieces of the
  // interrupted run. A piece out of range means a file of another scene;
  // that is decided over all ranks, like the cells, so that all throw
  // together.
  template <int dim>
  void
  ViscoplasticContact<dim>::restore_contact_nodes(
    const CellRecordVectors &vectors,
    const ByteReader        &header)
  {
    bool                                  pieces_valid = true;
    std::vector<ContactNodes::Tangential> tangential_forces(
      contact_set.size(),
      ContactNodes::Tangential{{0, 0}});
    for (unsigned int i = 0; i < contact_set.size(); ++i)
      {
        const auto  &dofs  = contact_set.node(i).local_dofs;
        const double piece = vectors.contact_state.local_element(dofs[0]) - 1.;
        // A piece of the node's own zone's law.
        if (!(piece >= 0 && piece < contact_set.laws().n_pieces())
            || contact_set.laws().zone_of_piece(
                 static_cast<unsigned int>(piece + 0.5))
                 != contact_set.zone(i))
          {
            pieces_valid = false;
            continue;
          }
        contact_set.set_piece(i, static_cast<unsigned int>(piece + 0.5));
        contact_set.z[i] = vectors.contact_state.local_element(dofs[1]);
        contact_set.r[i]
          = contact_set.normal_component(solution, i) - contact_set.gap(i);
        const double state = vectors.friction_state.local_element(dofs[0]);
        if (!(state >= 0 && state <= 2))
          {
            pieces_valid = false;
            continue;
          }
        contact_set.set_friction_state(i,
                                       static_cast<ContactNodes::FrictionState>(
                                         static_cast<unsigned int>(state
                                                                   + 0.5)));
        for (unsigned int j = 0; j < contact_set.n_tangential(i); ++j)
          tangential_forces[i][j]
            = vectors.friction_state.local_element(dofs[1 + j]);
      }
    // The slip of the next step is measured from the restored displacement;
    // a slipping node's bound and direction follow from its forces, as in
    // the interrupted run (ContactNodes::accept_slip()).
    contact_set.reset_slip(contact_set.tangential_displacements(solution),
                           tangential_forces);
    header.check(Utilities::MPI::min(pieces_valid ? 1 : 0, mpi_communicator)
                 == 1);
  }



  // @sect4{ViscoplasticContact::restore_prediction_start}
  //
  // The start of the checkpoint's step, for the prediction of the next one,
  // unless the interrupted run had none (its step was the first on its
  // mesh). The back ends keep nothing across a checkpoint
  // (ContactSolver::forget_kept_state()).
  template <int dim>
  void
  ViscoplasticContact<dim>::restore_prediction_start(
    const CellRecordVectors &vectors,
    const CheckpointFlags   &flags)
  {
    if (flags.has_step_start)
      {
        VectorType displacement = vectors.start_displacement;
        displacement.update_ghost_values();
        std::vector<double> contact_forces;
        for (unsigned int i = 0; i < contact_set.size() && contact_enabled; ++i)
          contact_forces.push_back(vectors.node_history.local_element(
            contact_set.node(i).local_dofs[0]));
        predicted_start.remember(std::move(displacement),
                                 std::move(contact_forces));
      }
  }



  template class ViscoplasticContact<2>;
  template class ViscoplasticContact<3>;
} // namespace ViscoContact
