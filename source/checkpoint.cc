// Checkpoints: the record file written and read by all ranks through MPI
// I/O, the published record of the last complete checkpoint, and the
// checkpoint of ViscoplasticContact<dim> itself.

#include <deal.II/base/exceptions.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/utilities.h>

#include <deal.II/grid/cell_id.h>

#include "checkpoint.h"
#include "mpi_tools.h"
#include "viscoplastic_contact.h"

#include <fstream>
#include <iomanip>
#include <sstream>

namespace ViscoContact
{
  namespace
  {
    // Bumped whenever the layout of the files changes.
    constexpr std::uint32_t checkpoint_version = 2;

    // Every rank learns whether any rank saw an MPI error, and which, and
    // all throw the same message.
    void
    agree_on_errors(const int                    error,
                    const std::filesystem::path &file,
                    const std::string           &what,
                    const MPI_Comm               communicator)
    {
      const int first_error = Utilities::MPI::max(error, communicator);
      AssertThrow(first_error == MPI_SUCCESS,
                  ExcMessage(what + " the checkpoint file " + file.string()
                             + " failed: " + MPITools::error_string(first_error)
                             + "."));
    }
  } // namespace



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



  std::filesystem::path
  checkpoint_directory(const std::string &output_directory)
  {
    return std::filesystem::path(output_directory) / "checkpoint";
  }



  std::filesystem::path
  checkpoint_file(const std::string &output_directory, const unsigned int step)
  {
    std::ostringstream name;
    name << "step_" << std::setw(6) << std::setfill('0') << step << ".bin";
    return checkpoint_directory(output_directory) / name.str();
  }



  // @sect4{write_record_file}
  //
  // Layout: the header's size, the header, the number of records and their
  // size, then the records of all ranks in rank order.
  void
  write_record_file(const std::filesystem::path &file,
                    const std::vector<char>     &header,
                    const std::vector<char>     &local_records,
                    const std::uint64_t          record_size,
                    const MPI_Comm               communicator)
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
    MPITools::write_blocks_collectively(file.string(),
                                        prefix,
                                        local_records.data(),
                                        local_records.size(),
                                        communicator);
  }



  // @sect4{read_record_file}
  template <typename T>
  T
  read_value(MPI_File handle, const MPI_Offset offset, int &error)
  {
    T value{};
    if (error == MPI_SUCCESS)
      error = MPI_File_read_at(handle,
                               offset,
                               &value,
                               sizeof(T),
                               MPI_CHAR,
                               MPI_STATUS_IGNORE);
    return value;
  }



  void
  read_record_file(const std::filesystem::path &file,
                   std::vector<char>           &header,
                   std::vector<char>           &record_share,
                   const std::uint64_t          record_size,
                   const MPI_Comm               communicator)
  {
    MPI_File handle;
    int      error = MPI_File_open(communicator,
                              file.c_str(),
                              MPI_MODE_RDONLY,
                              MPI_INFO_NULL,
                              &handle);
    agree_on_errors(error, file, "Opening", communicator);
    MPI_Offset file_size = 0;
    MPI_File_get_size(handle, &file_size);

    const std::uint64_t header_size
      = read_value<std::uint64_t>(handle, 0, error);
    const bool header_fits
      = header_size + 3 * sizeof(std::uint64_t) <= std::uint64_t(file_size);
    header.resize(header_fits ? header_size : 0);
    if (error == MPI_SUCCESS && header_fits)
      error = MPI_File_read_at(handle,
                               sizeof(std::uint64_t),
                               header.data(),
                               header_size,
                               MPI_CHAR,
                               MPI_STATUS_IGNORE);
    const MPI_Offset    counts = sizeof(std::uint64_t) + header_size;
    const std::uint64_t n_total
      = header_fits ? read_value<std::uint64_t>(handle, counts, error) : 0;
    const std::uint64_t stored_size
      = header_fits ? read_value<std::uint64_t>(handle, counts + 8, error) : 0;
    const MPI_Offset records_start = counts + 2 * sizeof(std::uint64_t);
    const bool       consistent
      = Utilities::MPI::min(error == MPI_SUCCESS && header_fits
                                && stored_size == record_size
                                && records_start + n_total * record_size
                                     == std::uint64_t(file_size)
                              ? 1
                              : 0,
                            communicator)
        == 1;
    if (!consistent)
      {
        MPI_File_close(&handle);
        AssertThrow(false,
                    ExcMessage(
                      "The checkpoint file " + file.string()
                      + " is damaged, or does not belong to this scene "
                        "or to this version of the program."));
      }

    const unsigned int  n_ranks = Utilities::MPI::n_mpi_processes(communicator);
    const unsigned int  rank  = Utilities::MPI::this_mpi_process(communicator);
    const std::uint64_t begin = n_total * rank / n_ranks;
    const std::uint64_t end   = n_total * (rank + 1) / n_ranks;
    record_share.resize((end - begin) * record_size);
    error = Utilities::MPI::max(error, communicator);
    if (error == MPI_SUCCESS)
      error = MPITools::transfer_in_pieces(
        record_share.size(),
        communicator,
        [&](const std::size_t start, const int n) {
          return MPI_File_read_at_all(handle,
                                      records_start + begin * record_size
                                        + start,
                                      record_share.data() + start,
                                      n,
                                      MPI_CHAR,
                                      MPI_STATUS_IGNORE);
        });
    MPI_File_close(&handle);
    agree_on_errors(error, file, "Reading", communicator);
  }



  // @sect4{publish_checkpoint}
  //
  // The rename of checkpoint.info is atomic on POSIX file systems.
  void
  publish_checkpoint(const std::string      &output_directory,
                     const CheckpointRecord &record,
                     const unsigned int      previous_step,
                     const MPI_Comm          communicator)
  {
    std::string problem;
    if (Utilities::MPI::this_mpi_process(communicator) == 0)
      {
        const std::filesystem::path directory
          = checkpoint_directory(output_directory);
        const std::filesystem::path info = directory / "checkpoint.info";
        const std::filesystem::path temporary
          = directory / "checkpoint.info.tmp";
        {
          std::ofstream out(temporary);
          out << std::setprecision(17) << "step " << record.step << '\n'
              << "time " << record.time << '\n'
              << "ranks " << record.n_ranks << '\n'
              << "dofs " << record.n_dofs << '\n';
          out.flush();
          if (!out)
            problem = "Writing " + temporary.string() + " failed.";
        }
        std::error_code error;
        if (problem.empty())
          std::filesystem::rename(temporary, info, error);
        if (error)
          problem = "Renaming " + temporary.string()
                    + " failed: " + error.message() + ".";
        if (problem.empty() && previous_step != numbers::invalid_unsigned_int
            && previous_step != record.step)
          std::filesystem::remove(checkpoint_file(output_directory,
                                                  previous_step),
                                  error);
      }
    problem = Utilities::MPI::broadcast(communicator, problem, 0);
    AssertThrow(problem.empty(), ExcMessage(problem));
  }



  CheckpointRecord
  read_checkpoint_record(const std::string  &output_directory,
                         const std::uint64_t n_dofs)
  {
    const std::filesystem::path info
      = checkpoint_directory(output_directory) / "checkpoint.info";
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
    AssertThrow(record.n_dofs == n_dofs,
                ExcMessage("Invalid parameter <Resume> in subsection "
                           "<Checkpoint>: the checkpoint of step "
                           + std::to_string(record.step) + " has "
                           + std::to_string(record.n_dofs)
                           + " displacement dofs, this scene "
                           + std::to_string(n_dofs)
                           + "; accepted: resuming the scene that wrote it."));
    return record;
  }



  void
  truncate_time_series(const std::filesystem::path &file,
                       const unsigned int           step)
  {
    std::ifstream            in(file);
    std::vector<std::string> kept;
    std::string              line;
    while (std::getline(in, line))
      {
        if (kept.empty())
          {
            kept.push_back(line); // the header
            continue;
          }
        const unsigned int row_step
          = std::stoul(line.substr(0, line.find(',')));
        if (row_step <= step)
          kept.push_back(line);
      }
    in.close();
    std::ofstream out(file, std::ios::trunc);
    for (const std::string &row : kept)
      out << row << '\n';
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
  // that its iterations are those of the uninterrupted run), and the state
  // of every stress point (sigma_n, the history of the next step, the
  // plastic multiplier).
  template <int dim>
  void
  ViscoplasticContact<dim>::write_checkpoint(const unsigned int         step,
                                             const std::vector<double> &times,
                                             const double wall_time)
  {
    TimerOutput::Scope t(computing_timer, "Checkpoint");
    if (Utilities::MPI::this_mpi_process(mpi_communicator) == 0)
      std::filesystem::create_directories(
        checkpoint_directory(parameters.directory));

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

    using Key                        = CellId::binary_type;
    const unsigned int dofs_per_cell = fe->n_dofs_per_cell();
    const unsigned int n_q           = stress_quadrature.size();
    const std::size_t  record_size   = sizeof(Key)
                                    + 2 * dofs_per_cell * sizeof(double)
                                    + n_q * sizeof(QuadraturePointHistory<dim>);
    std::vector<char> records(owned_cells.size() * record_size);
    std::vector<types::global_dof_index> dof_indices(dofs_per_cell);
    char                                *out = records.data();
    for (unsigned int k = 0; k < owned_cells.size(); ++k)
      {
        const Key key = owned_cells[k]->id().template to_binary<dim>();
        std::memcpy(out, &key, sizeof(Key));
        out += sizeof(Key);
        owned_cells[k]->get_dof_indices(dof_indices);
        for (const VectorType *vector : {&solution, &contact_state})
          for (const types::global_dof_index dof : dof_indices)
            {
              const double value = (*vector)(dof);
              std::memcpy(out, &value, sizeof(double));
              out += sizeof(double);
            }
        std::memcpy(out,
                    &quadrature_point_history[std::size_t(k) * n_q],
                    n_q * sizeof(QuadraturePointHistory<dim>));
        out += n_q * sizeof(QuadraturePointHistory<dim>);
      }
    write_record_file(checkpoint_file(parameters.directory, step),
                      header.bytes,
                      records,
                      record_size,
                      mpi_communicator);

    CheckpointRecord record;
    record.step    = step;
    record.time    = times[step];
    record.n_ranks = Utilities::MPI::n_mpi_processes(mpi_communicator);
    record.n_dofs  = dof_handler.n_dofs();
    publish_checkpoint(parameters.directory,
                       record,
                       last_checkpoint_step,
                       mpi_communicator);
    last_checkpoint_step = step;
  }



  // @sect4{ViscoplasticContact::resume_from_checkpoint}
  //
  // Reads what write_checkpoint() wrote, on any number of ranks: each rank
  // reads its share of the records, the records travel to the owners of
  // their cells, and every owned cell must be found. Then what the time
  // loop derives from the state is rebuilt (the ghosts, the history load of
  // the next step) and the time series is cut back to the checkpoint.
  template <int dim>
  unsigned int
  ViscoplasticContact<dim>::resume_from_checkpoint(std::vector<double> &times)
  {
    const CheckpointRecord checkpoint
      = read_checkpoint_record(parameters.directory, dof_handler.n_dofs());
    const std::filesystem::path file
      = checkpoint_file(parameters.directory, checkpoint.step);

    using Key                        = CellId::binary_type;
    const unsigned int dofs_per_cell = fe->n_dofs_per_cell();
    const unsigned int n_q           = stress_quadrature.size();
    const unsigned int n_doubles
      = 2 * dofs_per_cell
        + n_q * sizeof(QuadraturePointHistory<dim>) / sizeof(double);
    const std::size_t record_size = sizeof(Key) + n_doubles * sizeof(double);
    std::vector<char> header_bytes, share;
    read_record_file(file, header_bytes, share, record_size, mpi_communicator);

    ByteReader header(header_bytes, file.string());
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

    // The records of this rank's share go to the owners of their cells.
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

    VectorType contact_state(solution);
    contact_state = 0;
    solution      = 0;
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
            }
        std::memcpy(&quadrature_point_history[std::size_t(k) * n_q],
                    values.data() + 2 * dofs_per_cell,
                    n_q * sizeof(QuadraturePointHistory<dim>));
      }
    header.check(Utilities::MPI::min(complete ? 1 : 0, mpi_communicator) == 1);
    solution.update_ghost_values();

    if (contact_enabled)
      for (unsigned int i = 0; i < contact_set.size(); ++i)
        {
          const double piece
            = contact_state.local_element(contact_set.node(i).local_dofs[0])
              - 1.;
          header.check(piece >= 0 && piece < contact_set.law().n_pieces());
          contact_set.set_piece(i, static_cast<unsigned int>(piece + 0.5));
          contact_set.z[i]
            = contact_state.local_element(contact_set.node(i).local_dofs[1]);
          contact_set.r[i] = contact_set.normal_component(solution, i);
        }

    if (parameters.plasticity
        && parameters.stress_update == Parameters::StressUpdate::explicit_euler)
      assemble_history_load();
    if (Utilities::MPI::this_mpi_process(mpi_communicator) == 0)
      truncate_time_series(std::filesystem::path(parameters.directory)
                             / "time_series.csv",
                           step);
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
