// Checkpoints: the record file written and read by all ranks, the published
// record of the last complete checkpoint, and the checkpoint of
// ViscoplasticContact<dim> itself.

#include <deal.II/base/exceptions.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/utilities.h>

#include <deal.II/grid/cell_id.h>

#include "checkpoint.h"
#include "robustness/file_output.h"
#include "robustness/mpi_tools.h"
#include "time_loop.h"
#include "viscoplastic_contact.h"

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <fcntl.h>
#include <fstream>
#include <iostream>
#include <iomanip>
#include <sstream>
#include <sys/stat.h>
#include <unistd.h>

namespace ViscoContact
{
  namespace
  {
    // The version of the file layout, the first value of every header: a
    // resumed run refuses a checkpoint of another version rather than misread
    // it. Bumped whenever the layout of the files changes.
    constexpr std::uint32_t checkpoint_version = 4;

    // Every rank learns whether any rank saw an error (an errno), and which,
    // and all throw the same message. Without this, a rank that failed alone
    // would throw while the others wait in the next collective call.
    void
    agree_on_errors(const int          error,
                    const std::string &file,
                    const std::string &what,
                    const MPI_Comm     communicator)
    {
      const int first_error = Utilities::MPI::max(error, communicator);
      AssertThrow(first_error == 0,
                  ExcMessage(what + " the checkpoint file " + file
                             + " failed: " + std::strerror(first_error) + "."));
    }

    // Reads size bytes at offset; 0 or the errno (EIO for a file that ends
    // too early).
    int
    read_at(const int         descriptor,
            char             *data,
            const std::size_t size,
            const off_t       offset)
    {
      std::size_t done = 0;
      while (done < size)
        {
          const ssize_t n
            = ::pread(descriptor, data + done, size - done, offset + done);
          if (n < 0 && errno == EINTR)
            continue;
          if (n < 0)
            return errno;
          if (n == 0)
            return EIO;
          done += n;
        }
      return 0;
    }
  } // namespace



  // @sect4{ByteReader}
  //
  // The reader keeps a reference to the bytes (read_record_file() filled them)
  // and a position; the file name only serves the messages. Its checks throw on
  // the rank that finds the problem; since every rank reads the same header, a
  // bad header stops all ranks alike.
  ByteReader::ByteReader(const std::vector<char> &bytes,
                         const std::string       &file)
    : bytes(bytes)
    , file(file)
  {}



  std::string
  ByteReader::read_string()
  {
    const std::vector<char> characters = read_vector<char>();
    return std::string(characters.begin(), characters.end());
  }



  void
  ByteReader::check(const bool condition) const
  {
    AssertThrow(condition,
                ExcMessage("The checkpoint file " + file
                           + " does not belong to this scene or was written "
                             "by another version of the program."));
  }



  void
  ByteReader::check_available(const std::uint64_t n_bytes) const
  {
    AssertThrow(position + n_bytes <= bytes.size(),
                ExcMessage("The checkpoint file " + file
                           + " is shorter than its contents say: it is damaged "
                             "or was written by another version."));
  }



  // @sect4{File names}
  //
  // All checkpoints of a run live in the folder checkpoint/ of its output
  // folder; a step's file has a six-digit number, so that the files sort by
  // step.
  const char *const checkpoint_folder = "checkpoint";
  const char *const checkpoint_info   = "checkpoint/checkpoint.info";

  std::string
  checkpoint_name(const unsigned int step)
  {
    std::ostringstream name;
    name << checkpoint_folder << "/step_" << std::setw(6) << std::setfill('0')
         << step << ".bin";
    return name.str();
  }



  // @sect4{write_record_file}
  //
  // Layout: the header's size, the header, the number of records and their
  // size, then the records of all ranks in rank order.
  //
  // Every size is a 64-bit integer, so that the reader can check the layout
  // before trusting it. The total number of records is a sum over the ranks;
  // the prefix with the header is built on every rank but only rank 0's is
  // written. Where each rank's records go (the sum of the sizes of the lower
  // ranks' blocks) and the staging under a temporary name are the business
  // of OutputFolder::stage_collectively().
  void
  write_record_file(OutputFolder            &folder,
                    const std::string       &name,
                    const std::vector<char> &header,
                    const std::vector<char> &local_records,
                    const std::uint64_t      record_size,
                    const MPI_Comm           communicator)
  {
    const std::uint64_t n_records
      = Utilities::MPI::sum(std::uint64_t(local_records.size() / record_size),
                            communicator);
    std::string prefix;
    const auto  append = [&prefix](const std::uint64_t value) {
      prefix.append(reinterpret_cast<const char *>(&value), sizeof(value));
    };
    append(header.size());
    prefix.append(header.begin(), header.end());
    append(n_records);
    append(record_size);
    folder.stage_collectively(name,
                              prefix,
                              local_records.data(),
                              local_records.size(),
                              communicator);
  }



  // @sect4{read_record_file}
  //
  // Every rank opens the file (never following a link), reads and checks
  // the header and the counts, and then reads its own equal share of the
  // records, records [n_total rank / n_ranks, n_total (rank + 1) / n_ranks).
  // How many ranks wrote the file does not matter: the records are of fixed
  // size, and which rank ends up owning which cell is sorted out by the
  // caller. Errors are sticky and agreed on by all ranks, so that all throw
  // together.
  void
  read_record_file(const std::string  &file,
                   std::vector<char>  &header,
                   std::vector<char>  &record_share,
                   const std::uint64_t record_size,
                   const MPI_Comm      communicator)
  {
    const int descriptor
      = ::open(file.c_str(), O_RDONLY | O_NOFOLLOW | O_CLOEXEC);
    int         error = descriptor < 0 ? errno : 0;
    struct stat status;
    if (error == 0 && ::fstat(descriptor, &status) != 0)
      error = errno;
    agree_on_errors(error, file, "Opening", communicator);
    const std::uint64_t file_size = status.st_size;

    // The header size comes first. Before anything else is trusted, the header
    // must fit into the file with the three 64-bit sizes.
    std::uint64_t header_size = 0, n_total = 0, stored_size = 0;
    error = read_at(descriptor,
                    reinterpret_cast<char *>(&header_size),
                    sizeof(header_size),
                    0);
    const bool header_fits
      = error == 0
        && header_size
             <= file_size - std::min(file_size, 3 * sizeof(std::uint64_t));
    header.resize(header_fits ? header_size : 0);
    const off_t counts = sizeof(std::uint64_t) + header.size();
    if (header_fits)
      error = read_at(descriptor, header.data(), header_size, 8);
    if (header_fits && error == 0)
      error = read_at(descriptor,
                      reinterpret_cast<char *>(&n_total),
                      sizeof(n_total),
                      counts);
    if (header_fits && error == 0)
      error = read_at(descriptor,
                      reinterpret_cast<char *>(&stored_size),
                      sizeof(stored_size),
                      counts + 8);
    const std::uint64_t records_start = counts + 2 * sizeof(std::uint64_t);
    // The file is consistent if it was read without error, its records have the
    // size this program expects (it depends on dim, the element and the stress
    // points of the cell type), and the file is exactly as long as the header
    // says. This is reduced over the ranks (all read the same bytes, but an I/O
    // error may hit one rank only), so that all ranks throw together.
    const bool consistent
      = Utilities::MPI::min(
          error == 0 && header_fits && stored_size == record_size
              && n_total <= file_size / std::max<std::uint64_t>(record_size, 1)
              && records_start + n_total * record_size == file_size
            ? 1
            : 0,
          communicator)
        == 1;
    if (!consistent)
      {
        ::close(descriptor);
        AssertThrow(false,
                    ExcMessage(
                      "The checkpoint file " + file
                      + " is damaged, or does not belong to this scene "
                        "or to this version of the program."));
      }

    // This rank's share of the records: an equal split of n_total, whatever the
    // number of ranks that wrote them.
    const unsigned int  n_ranks = Utilities::MPI::n_mpi_processes(communicator);
    const unsigned int  rank  = Utilities::MPI::this_mpi_process(communicator);
    const std::uint64_t begin = n_total * rank / n_ranks;
    const std::uint64_t end   = n_total * (rank + 1) / n_ranks;
    record_share.resize((end - begin) * record_size);
    error = read_at(descriptor,
                    record_share.data(),
                    record_share.size(),
                    records_start + begin * record_size);
    ::close(descriptor);
    agree_on_errors(error, file, "Reading", communicator);
  }



  // @sect4{publish_checkpoint}
  //
  // Rank 0 alone writes checkpoint.info: a few lines of text (step, time,
  // ranks, dofs, the entries), staged and renamed over the old one (rename is
  // atomic on POSIX file systems), so a reader sees either the old or the new
  // record, never a partial one; the rename reaches the disk before the
  // commit returns, so the record never names a file that a crash of the
  // machine could lose. Only once the new record is in place is the previous
  // checkpoint's file removed; a failure to remove it leaves a stale file
  // behind and is not an error. The file just published is never removed,
  // even if the previous step has the same number.
  void
  publish_checkpoint(OutputFolder           &folder,
                     const CheckpointRecord &record,
                     const unsigned int      previous_step)
  {
    std::ostringstream out;
    out << std::setprecision(17) << "step " << record.step << '\n'
        << "time " << record.time << '\n'
        << "ranks " << record.n_ranks << '\n'
        << "dofs " << record.n_dofs << '\n';
    for (const std::string &entry : record.entries)
      out << "entry " << entry << '\n';
    if (Utilities::MPI::this_mpi_process(folder.get_communicator()) == 0)
      folder.stage(checkpoint_info, out.str(), OutputFolder::Replace::own);
    folder.commit(/*durable=*/true);
    if (previous_step != numbers::invalid_unsigned_int
        && previous_step != record.step)
      folder.remove(checkpoint_name(previous_step));
  }



  // @sect4{read_checkpoint_record}
  //
  // Every rank reads checkpoint.info itself (a small text file), so no
  // communication is needed. Missing or damaged, or written for a problem of
  // another size (the number of displacement dofs differs), it stops the run
  // with a message about the Resume entry; the dof count is a cheap check that
  // the parameter file describes the scene that wrote the checkpoint.
  CheckpointRecord
  read_checkpoint_record(const std::string              &output_directory,
                         const std::uint64_t             n_dofs,
                         const std::vector<std::string> &entries)
  {
    const std::filesystem::path info
      = std::filesystem::path(output_directory) / checkpoint_info;
    std::ifstream    in(info);
    CheckpointRecord record;
    std::string      key_step, key_time, key_ranks, key_dofs;
    in >> key_step >> record.step >> key_time >> record.time >> key_ranks
      >> record.n_ranks >> key_dofs >> record.n_dofs;
    AssertThrow(in && key_step == "step" && key_ranks == "ranks"
                  && key_dofs == "dofs",
                ExcMessage("Invalid parameter <Resume> in subsection "
                           "<Checkpoint>: value <true>, but "
                           + info.string()
                           + " does not exist or is damaged; accepted: true "
                             "only when the Output directory holds a complete "
                             "checkpoint of an earlier run of this scene."));
    AssertThrow(n_dofs == 0 || record.n_dofs == n_dofs,
                ExcMessage("Invalid parameter <Resume> in subsection "
                           "<Checkpoint>: the checkpoint of step "
                           + std::to_string(record.step) + " has "
                           + std::to_string(record.n_dofs)
                           + " displacement dofs, this scene "
                           + std::to_string(n_dofs)
                           + "; accepted: resuming the scene that wrote it."));
    // The entries that change the result, one per line after the counts.
    // A resumed run with another material or time step would continue the
    // old state with the new scene: a result of neither. Every entry that
    // differs is named.
    std::string line;
    while (std::getline(in, line))
      if (line.rfind("entry ", 0) == 0)
        record.entries.push_back(line.substr(6));
    std::string differences;
    const auto  name_of = [](const std::string &entry) {
      return entry.substr(0, entry.find(" = "));
    };
    for (const std::string &entry : entries)
      if (std::find(record.entries.begin(), record.entries.end(), entry)
          == record.entries.end())
        {
          // The value the checkpoint was written with, if it has the entry.
          std::string stored = "(none)";
          for (const std::string &old_entry : record.entries)
            if (name_of(old_entry) == name_of(entry))
              stored = old_entry.substr(old_entry.find(" = ") + 3);
          differences += "\n      " + entry + " (checkpoint: " + stored + ")";
        }
    AssertThrow(differences.empty(),
                ExcMessage("Invalid parameter <Resume> in subsection "
                           "<Checkpoint>: the checkpoint of step "
                           + std::to_string(record.step) + " in "
                           + info.string()
                           + " was written with other parameters; these "
                             "entries differ:"
                           + differences
                           + "\n    accepted: resuming with the parameters "
                             "that wrote it (only the Output and Checkpoint "
                             "entries and End time may change)."));
    return record;
  }



  // @sect4{truncate_time_series}
  //
  // Called by a resumed run: the rows the interrupted run wrote after its
  // checkpoint are dropped, since the resumed run computes those steps again
  // and appends their rows. The file is small (one row per step); rank 0
  // reads it and stages the kept rows (never following a link).
  void
  truncate_time_series(OutputFolder      &folder,
                       const std::string &header,
                       const unsigned int step)
  {
    const std::string name = "time_series.csv";
    if (Utilities::MPI::this_mpi_process(folder.get_communicator()) == 0)
      {
        std::string content;
        const int   descriptor = ::open(folder.path(name).c_str(),
                                      O_RDONLY | O_NOFOLLOW | O_CLOEXEC);
        char        buffer[65536];
        ssize_t     n = 0;
        while (descriptor >= 0
               && ((n = ::read(descriptor, buffer, sizeof(buffer))) > 0
                   || (n < 0 && errno == EINTR)))
          if (n > 0)
            content.append(buffer, n);
        if (descriptor >= 0)
          ::close(descriptor);
        std::istringstream lines(content);
        std::string        line, text;
        bool               first = true;
        while (std::getline(lines, line))
          {
            // The header, and the complete rows up to the checkpoint.
            if (first)
              text += line + '\n';
            else if (!line.empty()
                     && std::strtoul(line.c_str(), nullptr, 10) <= step)
              text += line + '\n';
            first = false;
          }
        if (text.empty())
          {
            std::cerr << "Warning: " << folder.path(name)
                      << " was missing or empty; it starts again with its "
                         "header, and the rows of steps 1 to "
                      << step << " are lost." << std::endl;
            text = header;
          }
        folder.stage(name, text, OutputFolder::Replace::own);
      }
    folder.commit();
  }



  // @sect4{ViscoplasticContact::checkpoint_record_size}
  //
  // The four vectors of write_checkpoint() at the cell's dofs (u, the contact
  // state, u_{n-1}, the nodes' history), then the stress points;
  // QuadraturePointHistory holds only doubles, so the payload after the key
  // is a whole number of doubles.
  template <int dim>
  std::size_t
  ViscoplasticContact<dim>::checkpoint_record_size() const
  {
    static_assert(sizeof(QuadraturePointHistory<dim>) % sizeof(double) == 0);
    return sizeof(CellId::binary_type)
           + 4 * fe->n_dofs_per_cell() * sizeof(double)
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
  // none) with the back end's value per contact node at its y-dof
  // (ContactSolver::checkpoint_state()), and the state of every stress point
  // (sigma_n, the history of the next step, the plastic multiplier).
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
  ViscoplasticContact<dim>::write_checkpoint(const unsigned int         step,
                                             const std::vector<double> &times,
                                             const double wall_time)
  {
    TimerOutput::Scope t(computing_timer, "Checkpoint");
    // The folder and the two files go into the manifest before they exist.
    output_folder->create_folder(checkpoint_folder);
    output_folder->record_files({checkpoint_name(step), checkpoint_info});

    // The header: what identifies the file (version, dim, step), the schedule,
    // the run's wall time and compute time so far, the iteration counters, the
    // largest von Mises stress, and the list of .pvtu records for solution.pvd.
    // That list is kept on rank 0 only (output_results()), and rank 0's header
    // is the one written.
    ByteWriter header;
    header.write(checkpoint_version);
    header.write<std::uint32_t>(dim);
    header.write<std::uint32_t>(step);
    header.write_vector(times);
    header.write(wall_time);
    header.write(time_loop_compute_time);
    header.write<std::uint32_t>(total_active_set_iterations);
    header.write<std::uint32_t>(total_newton_iterations);
    header.write<std::uint32_t>(total_inner_iterations);
    header.write(max_von_mises);
    header.write<std::uint64_t>(times_and_names.size());
    for (const auto &[time, name] : times_and_names)
      {
        header.write(time);
        header.write_string(name);
      }
    // The adaptive controller's state (doc/adaptivity.md): the step it wants
    // next, before landing on a target, and the rejected steps so far. The
    // next level itself is the last entry of the schedule, and the history
    // of the stress points was advanced for it.
    header.write(desired_time_step);
    header.write<std::uint32_t>(n_rejected_steps);
    // Whether there is a start of the step to predict from, and whether the
    // back end has a state of its own (both the same on every rank). The
    // implicit update sets up a new operator in every Newton iteration, so
    // nothing the back end built lives on into the next step.
    const std::optional<std::vector<double>> back_end_state
      = contact_enabled && !implicit_update()
          ? contact_solver->checkpoint_state()
          : std::nullopt;
    header.write<std::uint32_t>(previous_step_start.has_value());
    header.write<std::uint32_t>(back_end_state.has_value());

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
    // z_{n-1} at its x-dof and the back end's value at its y-dof.
    VectorType start_displacement(solution), node_history(solution);
    start_displacement = 0;
    node_history       = 0;
    if (previous_step_start)
      start_displacement = previous_step_start->displacement;
    for (unsigned int i = 0; i < contact_set.size() && contact_enabled; ++i)
      {
        const auto &dofs = contact_set.node(i).local_dofs;
        if (previous_step_start)
          node_history.local_element(dofs[0])
            = previous_step_start->contact_forces[i];
        if (back_end_state)
          node_history.local_element(dofs[1]) = (*back_end_state)[i];
      }
    start_displacement.update_ghost_values();
    node_history.update_ghost_values();

    // A record: the cell id in binary form, the dofs_per_cell values of u, of
    // the contact state, of u_{n-1} and of the nodes' history, in the cell's
    // dof order, and the n_q stress-point records of the cell, copied as
    // raw bytes (QuadraturePointHistory is plain data: two symmetric tensors
    // and a double).
    using Key                        = CellId::binary_type;
    const unsigned int dofs_per_cell = fe->n_dofs_per_cell();
    const unsigned int n_q           = stress_quadrature.size();
    const std::size_t  record_size   = checkpoint_record_size();
    std::vector<char>  records(owned_cells.size() * record_size);
    std::vector<types::global_dof_index> dof_indices(dofs_per_cell);
    char                                *out = records.data();
    // The cells in the order of owned_cells; (*vector)(dof) reads owned and
    // ghost entries alike, which is why both vectors must have their ghost
    // values here.
    for (unsigned int k = 0; k < owned_cells.size(); ++k)
      {
        const Key key = owned_cells[k]->id().template to_binary<dim>();
        std::memcpy(out, &key, sizeof(Key));
        out += sizeof(Key);
        owned_cells[k]->get_dof_indices(dof_indices);
        for (const VectorType *vector :
             {&solution, &contact_state, &start_displacement, &node_history})
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
    // Collective: the file is complete (written and renamed, the rename on
    // the disk) before the record of the checkpoint is published, and only
    // then is the previous checkpoint's file removed.
    write_record_file(*output_folder,
                      checkpoint_name(step),
                      header.bytes,
                      records,
                      record_size,
                      mpi_communicator);
    output_folder->commit(/*durable=*/true);

    CheckpointRecord record;
    record.step    = step;
    record.time    = times[step];
    record.n_ranks = Utilities::MPI::n_mpi_processes(mpi_communicator);
    record.n_dofs  = dof_handler.n_dofs();
    record.entries = parameters.result_entries;
    publish_checkpoint(*output_folder, record, last_checkpoint_step);
    // What a resumed run cannot restore, this run forgets too.
    if (contact_enabled)
      contact_solver->forget_kept_state();
    last_checkpoint_step = step;
  }



  // @sect4{ViscoplasticContact::resume_from_checkpoint}
  //
  // Reads what write_checkpoint() wrote, on any number of ranks: each rank
  // reads its share of the records, the records travel to the owners of
  // their cells, and every owned cell must be found. Then what the time
  // loop derives from the state is rebuilt (the ghosts, the history load of
  // the next step) and the time series is cut back to the checkpoint.
  //
  // It runs after set-up, on the mesh rebuilt from the parameter file, and it
  // returns the step of the checkpoint; run() continues with the step after it.
  // Everything the loop needs is restored: u_n with its ghosts, the pieces and
  // (r, z) of the contact nodes, every stress-point record, the schedule, the
  // counters and the .pvd list. What the run's summary counts per process
  // (assemblies, set-ups of the back end) starts again from the set-up of the
  // resumed run.
  template <int dim>
  unsigned int
  ViscoplasticContact<dim>::resume_from_checkpoint(std::vector<double> &times)
  {
    // The records of an adaptive run are those of its adapted mesh, which is
    // rebuilt first (mesh_adaptation.cc); so are those of a run with initial
    // cycles, whose mesh is not the one make_grid() starts from.
    if (parameters.adaptive_refinement || parameters.initial_cycles > 0)
      restore_checkpoint_mesh();
    const CheckpointRecord checkpoint
      = read_checkpoint_record(parameters.directory,
                               dof_handler.n_dofs(),
                               parameters.result_entries);
    const std::string file
      = output_folder->path(checkpoint_name(checkpoint.step));

    // The record size follows from dim, the element and the stress quadrature,
    // as for write_checkpoint(); a record's payload after the key is n_doubles
    // doubles.
    using Key                        = CellId::binary_type;
    const unsigned int dofs_per_cell = fe->n_dofs_per_cell();
    const unsigned int n_q           = stress_quadrature.size();
    const std::size_t  record_size   = checkpoint_record_size();
    const unsigned int n_doubles = (record_size - sizeof(Key)) / sizeof(double);
    std::vector<char>  header_bytes, share;
    read_record_file(file, header_bytes, share, record_size, mpi_communicator);

    // The header is checked field by field against this run: version, dimension
    // and step. The schedule replaces the one computed from the parameter file,
    // since the interrupted run may have cut steps.
    ByteReader header(header_bytes, file);
    header.check(header.read<std::uint32_t>() == checkpoint_version);
    header.check(header.read<std::uint32_t>() == dim);
    const unsigned int step = header.read<std::uint32_t>();
    header.check(step == checkpoint.step);
    times = header.read_vector<double>();
    header.check(step < times.size());
    loop_time_offset            = header.read<double>();
    time_loop_compute_time      = header.read<double>();
    total_active_set_iterations = header.read<std::uint32_t>();
    total_newton_iterations     = header.read<std::uint32_t>();
    total_inner_iterations      = header.read<std::uint32_t>();
    max_von_mises               = header.read<double>();
    times_and_names.clear();
    const std::uint64_t n_records = header.read<std::uint64_t>();
    for (std::uint64_t i = 0; i < n_records; ++i)
      {
        const double time = header.read<double>();
        times_and_names.emplace_back(time, header.read_string());
      }
    desired_time_step             = header.read<double>();
    n_rejected_steps              = header.read<std::uint32_t>();
    const bool has_step_start     = header.read<std::uint32_t>() == 1;
    const bool has_back_end_state = header.read<std::uint32_t>() == 1;

    // End time is the one entry of the scene a resumed run may change (to go
    // further, or to stop earlier). The levels up to the checkpoint stay those
    // of the interrupted run (with its cut steps); the levels after it are
    // those of the new schedule: with fixed steps the levels of an
    // uninterrupted run to the new End time, with adaptive steps the next
    // level fitted again to this run's targets (the schedule of an adaptive
    // run ends with the next level, which the controller fitted to the
    // targets of the interrupted run; with the same End time and Profile
    // times it is the same level). So without cuts the resumed run repeats
    // the uninterrupted one exactly. If the next step's length changes, the
    // history the explicit update stored for the old one is rescaled below,
    // once the stress points are restored.
    const bool adaptive
      = parameters.time_step_control == Parameters::TimeStepControl::adaptive;
    std::pair<double, double> rescaled_next_step(0., 0.);
    if (adaptive || parameters.end_time != times.back())
      {
        // An adaptive run may end at the checkpoint; a fixed schedule always
        // has a level after it.
        AssertThrow(adaptive ? parameters.end_time >= times[step]
                             : parameters.end_time > times[step],
                    ExcMessage(
                      "Invalid parameter <End time> in subsection "
                      "<Time>: value <"
                      + std::to_string(parameters.end_time)
                      + ">, but the checkpoint to resume from is at t = "
                      + std::to_string(times[step])
                      + "; accepted: an End time after the "
                        "checkpoint's time."));
        const double old_next_step
          = step + 1 < times.size() ? times[step + 1] - times[step] : 0.;
        times.resize(step + 1);
        if (!adaptive)
          {
            for (const double t :
                 time_levels(parameters.end_time, parameters.time_step))
              if (t > times[step] * (1 + 1e-12) + 1e-300)
                times.push_back(t);
          }
        else if (times[step] < parameters.end_time * (1 - 1e-12))
          times.push_back(
            next_time_level(times[step], desired_time_step, landing_targets()));
        rescaled_next_step
          = {old_next_step,
             step + 1 < times.size() ? times[step + 1] - times[step] : 0.};
      }

    // The records of this rank's share go to the owners of their cells. Each
    // becomes a (key, payload) pair: the key is the binary cell id, the payload
    // the doubles of u, of the contact state and of the stress points. Each
    // rank then asks for the keys of its own cells; exchange_records() meets
    // the holders and the askers at a rendezvous rank chosen by a hash of the
    // key, so no rank needs to know who holds which cell.
    std::vector<MPITools::Record> records(share.size() / record_size);
    for (std::size_t r = 0; r < records.size(); ++r)
      {
        const char *in = share.data() + r * record_size;
        records[r].first.assign(in, sizeof(Key));
        records[r].second.resize(n_doubles);
        std::memcpy(records[r].second.data(),
                    in + sizeof(Key),
                    n_doubles * sizeof(double));
      }
    std::vector<std::string> requests(owned_cells.size());
    for (unsigned int k = 0; k < owned_cells.size(); ++k)
      {
        const Key key = owned_cells[k]->id().template to_binary<dim>();
        requests[k].assign(reinterpret_cast<const char *>(&key), sizeof(Key));
      }
    const auto found
      = MPITools::exchange_records(records, requests, mpi_communicator);

    // Write the received values into the owned entries only: a dof of an owned
    // cell that another rank owns is set there, by the rank that owns it (every
    // owned dof lies on at least one owned cell). A cell whose record is
    // missing, duplicated or of the wrong size marks the checkpoint as
    // incomplete.
    VectorType contact_state(solution), start_displacement(solution),
      node_history(solution);
    contact_state      = 0;
    start_displacement = 0;
    node_history       = 0;
    solution           = 0;
    std::vector<types::global_dof_index> dof_indices(dofs_per_cell);
    bool                                 complete = true;
    for (unsigned int k = 0; k < owned_cells.size(); ++k)
      {
        const auto entry = found.find(requests[k]);
        if (entry == found.end() || entry->second.size() != 1
            || entry->second[0].size() != n_doubles)
          {
            complete = false;
            continue;
          }
        const std::vector<double> &values = entry->second[0];
        owned_cells[k]->get_dof_indices(dof_indices);
        for (unsigned int i = 0; i < dofs_per_cell; ++i)
          if (locally_owned_dofs.is_element(dof_indices[i]))
            {
              solution(dof_indices[i])      = values[i];
              contact_state(dof_indices[i]) = values[dofs_per_cell + i];
              start_displacement(dof_indices[i])
                = values[2 * dofs_per_cell + i];
              node_history(dof_indices[i]) = values[3 * dofs_per_cell + i];
            }
        // The stress-point records go back to their place k * n_q + q, byte for
        // byte.
        std::memcpy(&quadrature_point_history[std::size_t(k) * n_q],
                    values.data() + 4 * dofs_per_cell,
                    n_q * sizeof(QuadraturePointHistory<dim>));
      }
    // The decision is reduced over the ranks, so that all throw if any cell was
    // not found. Then the ghosts of u are imported, as the stress update and
    // the output expect.
    header.check(Utilities::MPI::min(complete ? 1 : 0, mpi_communicator) == 1);
    solution.update_ghost_values();

    // The contact nodes, on the rank that owns them now: the piece and the
    // force from the values at their own dofs (the piece was stored + 1, so
    // that 0 means "no contact node"), r = u.nu_i from the restored
    // displacement. The next active set then starts from the pieces of the
    // interrupted run.
    // A piece out of range means a file of another scene; that is decided
    // over all ranks, like the cells above, so that all throw together.
    if (contact_enabled)
      {
        bool pieces_valid = true;
        for (unsigned int i = 0; i < contact_set.size(); ++i)
          {
            const double piece
              = contact_state.local_element(contact_set.node(i).local_dofs[0])
                - 1.;
            if (!(piece >= 0 && piece < contact_set.law().n_pieces()))
              {
                pieces_valid = false;
                continue;
              }
            contact_set.set_piece(i, static_cast<unsigned int>(piece + 0.5));
            contact_set.z[i]
              = contact_state.local_element(contact_set.node(i).local_dofs[1]);
            contact_set.r[i] = contact_set.normal_component(solution, i);
          }
        header.check(Utilities::MPI::min(pieces_valid ? 1 : 0, mpi_communicator)
                     == 1);
      }
    // The start of the checkpoint's step, for the prediction of the next one,
    // unless the interrupted run had none (its step was the first on its
    // mesh); and the back end's state, from which it rebuilds what it had.
    std::vector<double> back_end_state;
    for (unsigned int i = 0; i < contact_set.size() && contact_enabled; ++i)
      back_end_state.push_back(
        node_history.local_element(contact_set.node(i).local_dofs[1]));
    if (has_back_end_state && contact_enabled)
      contact_solver->restore_checkpoint_state(contact_set, back_end_state);
    if (has_step_start)
      {
        previous_step_start.emplace();
        previous_step_start->displacement = start_displacement;
        previous_step_start->displacement.update_ghost_values();
        for (unsigned int i = 0; i < contact_set.size() && contact_enabled; ++i)
          previous_step_start->contact_forces.push_back(
            node_history.local_element(contact_set.node(i).local_dofs[0]));
      }

    // The explicit update's history load is not stored: it is assembled from
    // the restored histories, as update_stresses() would have left it. The
    // implicit update needs nothing more; its history enters through the
    // internal force.
    if (explicit_history_update()
        && rescaled_next_step.first != rescaled_next_step.second)
      rescale_history_increment(rescaled_next_step.first,
                                rescaled_next_step.second);
    else if (explicit_history_update())
      assemble_history_load();
    // The rows of time_series.csv after the checkpoint are removed once the
    // output folder is prepared (prepare_output_directory()).
    last_checkpoint_step = step;
    n_steps_done         = step;
    pcout << "Resuming from the checkpoint of step " << step
          << " (t = " << times[step] << ", written on " << checkpoint.n_ranks
          << " MPI rank(s))\n";
    return step;
  }



  template class ViscoplasticContact<2>;
  template class ViscoplasticContact<3>;
} // namespace ViscoContact
