// Checkpoint files: binary streams with error checks, the published record
// of the last complete checkpoint, and the time series of a resumed run.

#include <deal.II/base/exceptions.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/utilities.h>

#include "checkpoint.h"

#include <iomanip>
#include <sstream>

namespace ViscoContact
{
  CheckpointWriter::CheckpointWriter(const std::filesystem::path &file)
    : file(file)
    , temporary(file.string() + ".tmp")
    , out(temporary, std::ios::binary | std::ios::trunc)
  {
    AssertThrow(out,
                ExcMessage("Cannot write the checkpoint file "
                           + temporary.string()
                           + " (is the Output directory writable?)."));
  }



  void
  CheckpointWriter::write_string(const std::string &text)
  {
    write_vector(std::vector<char>(text.begin(), text.end()));
  }



  void
  CheckpointWriter::finish()
  {
    out.flush();
    AssertThrow(out,
                ExcMessage("Writing the checkpoint file " + temporary.string()
                           + " failed (disk full?)."));
    out.close();
    std::filesystem::rename(temporary, file);
  }



  CheckpointReader::CheckpointReader(const std::filesystem::path &file)
    : file(file)
    , in(file, std::ios::binary)
  {
    AssertThrow(in,
                ExcMessage("Cannot read the checkpoint file " + file.string()
                           + "."));
    file_size = std::filesystem::file_size(file);
  }



  std::string
  CheckpointReader::read_string()
  {
    const std::vector<char> characters = read_vector<char>();
    return std::string(characters.begin(), characters.end());
  }



  const std::filesystem::path &
  CheckpointReader::name() const
  {
    return file;
  }



  void
  check_checkpoint_content(const bool condition, const CheckpointReader &in)
  {
    AssertThrow(condition,
                ExcMessage("The checkpoint file " + in.name().string()
                           + " does not belong to this scene or was written "
                             "by another version of the program."));
  }



  void
  CheckpointHeader::write(CheckpointWriter &out) const
  {
    out.write(version);
    out.write(dimension);
    out.write(step);
    out.write_vector(times);
    out.write(wall_time);
    out.write(compute_time);
  }



  void
  CheckpointHeader::read(CheckpointReader   &in,
                         const std::uint32_t expected_version,
                         const std::uint32_t expected_dimension,
                         const std::uint32_t expected_step)
  {
    version = in.read<std::uint32_t>();
    check_checkpoint_content(version == expected_version, in);
    dimension = in.read<std::uint32_t>();
    check_checkpoint_content(dimension == expected_dimension, in);
    step = in.read<std::uint32_t>();
    check_checkpoint_content(step == expected_step, in);
    times = in.read_vector<double>();
    check_checkpoint_content(step < times.size(), in);
    wall_time    = in.read<double>();
    compute_time = in.read<double>();
  }



  void
  write_output_records(
    CheckpointWriter                                  &out,
    const std::vector<std::pair<double, std::string>> &records)
  {
    out.write<std::uint64_t>(records.size());
    for (const auto &entry : records)
      {
        out.write(entry.first);
        out.write_string(entry.second);
      }
  }



  std::vector<std::pair<double, std::string>>
  read_output_records(CheckpointReader &in)
  {
    std::vector<std::pair<double, std::string>> records;
    const std::uint64_t                         n = in.read<std::uint64_t>();
    for (std::uint64_t i = 0; i < n; ++i)
      {
        const double time = in.read<double>();
        records.emplace_back(time, in.read_string());
      }
    return records;
  }



  void
  CheckpointReader::check()
  {
    AssertThrow(in,
                ExcMessage("The checkpoint file " + file.string()
                           + " is shorter than its contents say: it is damaged "
                             "or was written by another version."));
  }



  void
  CheckpointReader::check_size(const std::uint64_t bytes)
  {
    AssertThrow(bytes <= file_size,
                ExcMessage("The checkpoint file " + file.string()
                           + " is damaged or was written by another version."));
  }



  std::filesystem::path
  checkpoint_directory(const std::string &output_directory)
  {
    return std::filesystem::path(output_directory) / "checkpoint";
  }



  std::filesystem::path
  checkpoint_file(const std::string &output_directory,
                  const unsigned int step,
                  const unsigned int rank)
  {
    std::ostringstream name;
    name << "step_" << std::setw(6) << std::setfill('0') << step << ".rank_"
         << std::setw(4) << rank << ".bin";
    return checkpoint_directory(output_directory) / name.str();
  }



  // @sect4{publish_checkpoint}
  //
  // The barrier makes sure every rank's file is renamed before rank 0
  // names the checkpoint complete; the rename of checkpoint.info is atomic
  // on POSIX file systems.
  void
  publish_checkpoint(const std::string      &output_directory,
                     const CheckpointRecord &record,
                     const unsigned int      previous_step,
                     const MPI_Comm          communicator)
  {
    const int error = MPI_Barrier(communicator);
    AssertThrowMPI(error);
    const std::filesystem::path directory
      = checkpoint_directory(output_directory);
    if (Utilities::MPI::this_mpi_process(communicator) == 0)
      {
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
          AssertThrow(out,
                      ExcMessage("Writing " + temporary.string() + " failed."));
        }
        std::filesystem::rename(temporary, info);
      }
    const int error2 = MPI_Barrier(communicator);
    AssertThrowMPI(error2);
    if (previous_step != numbers::invalid_unsigned_int
        && previous_step != record.step)
      {
        std::error_code ignored;
        std::filesystem::remove(
          checkpoint_file(output_directory,
                          previous_step,
                          Utilities::MPI::this_mpi_process(communicator)),
          ignored);
      }
  }



  CheckpointRecord
  read_checkpoint_record(const std::string  &output_directory,
                         const unsigned int  n_ranks,
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
    AssertThrow(record.n_ranks == n_ranks,
                ExcMessage("Invalid parameter <Resume> in subsection "
                           "<Checkpoint>: the checkpoint of step "
                           + std::to_string(record.step) + " was written by "
                           + std::to_string(record.n_ranks)
                           + " MPI rank(s); accepted: resuming on the same "
                             "number of ranks (here "
                           + std::to_string(n_ranks) + ")."));
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
} // namespace ViscoContact
