// The checkpoint file format (checkpoint_file.h): the record file written and
// read by all ranks, and the published record of the last complete checkpoint.
// Hand-written because deal.II 9.4 has no format that resumes on another
// number of ranks for fully distributed (simplex) meshes.

#include <deal.II/base/exceptions.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/utilities.h>

#include <deal.II/grid/cell_id.h>

#include "robustness/checkpoint_file.h"
#include "robustness/file_output.h"
#include "robustness/mpi_tools.h"

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <fcntl.h>
#include <fstream>
#include <iostream>
#include <iomanip>
#include <memory>
#include <sstream>
#include <sys/stat.h>
#include <unistd.h>

namespace ViscoContact
{
  namespace
  {
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
    // The records a checkpoint is written and read by at a time: about
    // 64 MB, at least one.
    std::uint64_t
    records_per_piece(const std::uint64_t record_size)
    {
      return std::max<std::uint64_t>(1,
                                     (std::uint64_t(64) << 20) / record_size);
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
                    const std::size_t        n_local_records,
                    const std::uint64_t      record_size,
                    const RecordFiller      &fill_records,
                    const MPI_Comm           communicator)
  {
    const std::uint64_t n_records
      = Utilities::MPI::sum(std::uint64_t(n_local_records), communicator);
    std::string prefix;
    const auto  append = [&prefix](const std::uint64_t value) {
      prefix.append(reinterpret_cast<const char *>(&value), sizeof(value));
    };
    append(header.size());
    prefix.append(header.begin(), header.end());
    append(n_records);
    append(record_size);
    // Pieces of whole records.
    const std::size_t per_piece = records_per_piece(record_size);
    folder.stage_collectively(
      name,
      prefix,
      n_local_records * record_size,
      per_piece * record_size,
      [&](const std::size_t begin, const std::size_t size, char *buffer) {
        fill_records(begin / record_size, (begin + size) / record_size, buffer);
      },
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
  read_record_file(const std::string           &file,
                   std::vector<char>           &header,
                   const std::uint64_t          record_size,
                   const RecordUser            &use_records,
                   const MPI_Comm               communicator,
                   const std::function<void()> &check_header)
  {
    // Not following a link, not blocking on a named pipe; only a regular
    // file is read.
    const int descriptor
      = ::open(file.c_str(), O_RDONLY | O_NOFOLLOW | O_NONBLOCK | O_CLOEXEC);
    int error = descriptor < 0 ? errno : 0;
    // Closed on every way out, also where a check or the caller throws.
    const std::unique_ptr<const int, void (*)(const int *)> closer(
      &descriptor,
      [](const int *d) {
        if (*d >= 0)
          ::close(*d);
      });
    struct stat status;
    if (error == 0 && ::fstat(descriptor, &status) != 0)
      error = errno;
    if (error == 0 && !S_ISREG(status.st_mode))
      error = EINVAL;
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
        AssertThrow(false,
                    ExcMessage(
                      "The checkpoint file " + file
                      + " is damaged, or does not belong to this scene "
                        "or to this version of the program."));
      }

    // This rank's share of the records: an equal split of n_total, whatever the
    // number of ranks that wrote them, read a piece at a time; as many pieces
    // on every rank.
    const unsigned int  n_ranks = Utilities::MPI::n_mpi_processes(communicator);
    const unsigned int  rank  = Utilities::MPI::this_mpi_process(communicator);
    const std::uint64_t begin = n_total * rank / n_ranks;
    const std::uint64_t end   = n_total * (rank + 1) / n_ranks;
    const std::uint64_t per_piece = records_per_piece(record_size);
    const std::uint64_t n_pieces
      = Utilities::MPI::max((end - begin + per_piece - 1) / per_piece,
                            communicator);
    // The caller's checks of the header (the same bytes on every rank, so
    // that all ranks throw alike) come before any record is used.
    if (check_header)
      check_header();
    std::vector<char> piece;
    for (std::uint64_t p = 0; p < n_pieces; ++p)
      {
        const std::uint64_t first = std::min(end, begin + p * per_piece);
        const std::uint64_t last  = std::min(end, first + per_piece);
        piece.resize((last - first) * record_size);
        if (error == 0)
          error = read_at(descriptor,
                          piece.data(),
                          piece.size(),
                          records_start + first * record_size);
        agree_on_errors(error, file, "Reading", communicator);
        use_records(piece);
      }
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
    // Untrusted input: a regular file of this account of at most 1 MB (a
    // few hundred entries), never a link or a named pipe.
    std::string content, reason;
    const auto  result = FileOutput::read_own_file(AT_FDCWD,
                                                  info.string(),
                                                  std::size_t(1) << 20,
                                                  content,
                                                  reason);
    AssertThrow(result != FileOutput::ReadResult::refused,
                ExcMessage("Invalid parameter <Resume> in subsection "
                           "<Checkpoint>: value <true>, but "
                           + info.string() + " " + reason
                           + "; accepted: true only when the Output directory "
                             "holds a complete checkpoint of an earlier run "
                             "of this scene, as the program wrote it."));
    std::istringstream in(content);
    CheckpointRecord   record;
    std::string        key_step, key_time, key_ranks, key_dofs;
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
    std::string       problem;
    if (Utilities::MPI::this_mpi_process(folder.get_communicator()) == 0)
      {
        // Untrusted input: a regular file of this account, never a link or
        // a named pipe, of at most 1 GB (rows of a few hundred bytes for
        // millions of steps).
        std::string content, reason;
        if (FileOutput::read_own_file(AT_FDCWD,
                                      folder.path(name),
                                      std::size_t(1) << 30,
                                      content,
                                      reason)
            == FileOutput::ReadResult::refused)
          problem = "Invalid parameter <Resume> in subsection <Checkpoint>: "
                    "value <true>, but "
                    + folder.path(name) + " " + reason
                    + "; accepted: the time series as the program wrote it "
                      "(or none).";
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
        if (text.empty() && problem.empty())
          {
            std::cerr << "Warning: " << folder.path(name)
                      << " was missing or empty; it starts again with its "
                         "header, and the rows of steps 1 to "
                      << step << " are lost." << std::endl;
            text = header;
          }
        if (problem.empty())
          folder.stage(name, text, OutputFolder::Replace::own);
      }
    FileOutput::agree_on_problem(problem, folder.get_communicator());
    folder.commit();
  }
} // namespace ViscoContact
