// Collective text files through MPI I/O, and the rendezvous exchange of
// keyed records.
//
// Both tools keep every rank's work and memory proportional to its own share
// of the data: no rank collects the blocks of a file or the records of the
// others. Both are collective. The file writer agrees on errors before
// acting on them: a rank that hits an error does not simply throw, since the
// others would then wait forever in the next collective call. Instead every
// error code is reduced over the ranks first, and all ranks throw (or go on)
// together.

#include <deal.II/base/exceptions.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/utilities.h>

#include "file_output.h"
#include "mpi_tools.h"

#include <cerrno>
#include <cstdint>
#include <cstring>
#include <algorithm>
#include <filesystem>

namespace ViscoContact
{
  namespace MPITools
  {
    // MPI's text for an error code, for the messages of failed file
    // operations.
    std::string
    error_string(const int error_code)
    {
      char text[MPI_MAX_ERROR_STRING];
      int  length = 0;
      MPI_Error_string(error_code, text, &length);
      return std::string(text, length);
    }



    // MPI's I/O error classes that correspond to a system error get the
    // system's words, as in the messages of the files written without MPI
    // ("No space left on device"), followed by MPI's text.
    std::string
    describe_error(const int error_code)
    {
      int error_class = error_code;
      MPI_Error_class(error_code, &error_class);
      const std::map<int, int> system_error = {{MPI_ERR_NO_SPACE, ENOSPC},
                                               {MPI_ERR_QUOTA, EDQUOT},
                                               {MPI_ERR_ACCESS, EACCES},
                                               {MPI_ERR_READ_ONLY, EROFS},
                                               {MPI_ERR_NO_SUCH_FILE, ENOENT}};
      const auto               entry        = system_error.find(error_class);
      if (entry == system_error.end())
        return error_string(error_code);
      return std::string(std::strerror(entry->second)) + " ("
             + error_string(error_code) + ")";
    }



    // @sect4{write_blocks_collectively}
    //
    // Offsets from an exclusive prefix sum of the block sizes; every rank
    // writes its block at its offset (collectively), then rank 0 renames the
    // complete file. Errors are agreed on by all ranks before anything is
    // thrown, so no rank waits for another that gave up.
    //
    // The file is written under a temporary name and renamed only when every
    // rank has written its part: a reader (or a resumed run) sees the old
    // file or the complete new one, never a partly written one.
    std::string
    try_write_blocks_collectively(const std::string &file,
                                  const std::string &prefix,
                                  const char        *local_block,
                                  const std::size_t  local_size,
                                  const MPI_Comm     communicator)
    {
      const bool root = (Utilities::MPI::this_mpi_process(communicator) == 0);
      const std::string temporary = file + ".tmp";
      // This rank's share of the file: its block, plus the prefix on rank 0.
      // The exclusive prefix sum of the shares is where this rank's block
      // starts.
      std::uint64_t size   = local_size + (root ? prefix.size() : 0);
      std::uint64_t offset = 0;
      int           error
        = MPI_Exscan(&size, &offset, 1, MPI_UINT64_T, MPI_SUM, communicator);
      AssertThrowMPI(error);
      // MPI_Exscan leaves rank 0's result undefined; its block starts after
      // the prefix.
      if (root)
        offset = prefix.size();

      // Opening is collective. If it failed on any rank (the maximum of the
      // error codes over the ranks is not MPI_SUCCESS), no rank writes.
      MPI_File handle;
      error = MPI_File_open(communicator,
                            temporary.c_str(),
                            MPI_MODE_CREATE | MPI_MODE_WRONLY,
                            MPI_INFO_NULL,
                            &handle);
      if (Utilities::MPI::max(error, communicator) == MPI_SUCCESS)
        {
          // Truncate what an earlier, longer temporary file may have left,
          // and let rank 0 write the prefix at the start. Then agree on the
          // outcome before the collective write.
          error = MPI_File_set_size(handle, 0);
          if (error == MPI_SUCCESS && root && !prefix.empty())
            error = MPI_File_write_at(handle,
                                      0,
                                      prefix.data(),
                                      prefix.size(),
                                      MPI_CHAR,
                                      MPI_STATUS_IGNORE);
          error = Utilities::MPI::max(error, communicator);
          // The blocks, in pieces that fit MPI's int counts, with a
          // collective write per piece.
          if (error == MPI_SUCCESS)
            error = transfer_in_pieces(
              local_size,
              communicator,
              [&](const std::size_t start, const int n) {
                return MPI_File_write_at_all(handle,
                                             offset + start,
                                             local_block + start,
                                             n,
                                             MPI_CHAR,
                                             MPI_STATUS_IGNORE);
              });
          // The test switch of FileOutput: the last rank fails as on a full
          // disk, the case where one rank alone sees the error.
          if (error == MPI_SUCCESS && FileOutput::simulate_failure(file)
              && Utilities::MPI::this_mpi_process(communicator) + 1
                   == Utilities::MPI::n_mpi_processes(communicator))
            error = MPI_ERR_NO_SPACE;
          // Closing is collective too; its error counts only if everything
          // before succeeded.
          const int close_error = MPI_File_close(&handle);
          if (error == MPI_SUCCESS)
            error = close_error;
        }
      // One outcome for all ranks. Only rank 0 renames, and it may fail
      // alone, so its result is broadcast: every rank returns the same
      // message, or none does. A failed file is removed, so that no partial
      // file is left behind.
      error               = Utilities::MPI::max(error, communicator);
      std::string problem = (error == MPI_SUCCESS ? "" : describe_error(error));
      if (root)
        {
          std::error_code file_error;
          if (problem.empty())
            std::filesystem::rename(temporary, file, file_error);
          if (file_error)
            problem = file_error.message();
          if (!problem.empty())
            std::filesystem::remove(temporary, file_error);
        }
      problem = Utilities::MPI::broadcast(communicator, problem, 0);
      return problem.empty()
               ? ""
               : "Writing the file " + file + " failed: " + problem + ".";
    }



    // The throwing form: every rank throws the same message, or none does.
    void
    write_blocks_collectively(const std::string &file,
                              const std::string &prefix,
                              const char        *local_block,
                              const std::size_t  local_size,
                              const MPI_Comm     communicator)
    {
      const std::string problem = try_write_blocks_collectively(file,
                                                                prefix,
                                                                local_block,
                                                                local_size,
                                                                communicator);
      AssertThrow(problem.empty(), ExcMessage(problem));
    }



    // @sect4{write_text_collectively}
    //
    // A text file from the text blocks of all ranks, in rank order, without
    // a prefix.
    void
    write_text_collectively(const std::string &file,
                            const std::string &local_text,
                            const MPI_Comm     communicator)
    {
      write_blocks_collectively(file,
                                "",
                                local_text.data(),
                                local_text.size(),
                                communicator);
    }



    // @sect4{transfer_in_pieces}
    //
    // Collective MPI I/O needs every rank to take part in every call, but
    // the ranks' blocks differ in size, and an MPI count is an int, so a
    // block of more than 2 GiB cannot go in one call. The loop therefore
    // runs over the pieces of the largest block, the same number of times on
    // every rank; a rank whose block is shorter takes part with empty
    // pieces.
    int
    transfer_in_pieces(
      const std::size_t                                       local_size,
      const MPI_Comm                                          communicator,
      const std::function<int(const std::size_t, const int)> &io)
    {
      // Pieces of 1 GiB, well within the range of an int count.
      const std::size_t piece = std::size_t(1) << 30;
      const std::size_t most  = Utilities::MPI::max(local_size, communicator);
      int               error = MPI_SUCCESS;
      for (std::size_t start = 0; start < most && error == MPI_SUCCESS;
           start += piece)
        {
          // Where this rank's piece starts (its end, once its block is done)
          // and how long it is (0 then).
          const std::size_t begin = std::min(start, local_size);
          error
            = io(begin, static_cast<int>(std::min(piece, local_size - begin)));
          // Agree on the outcome after every piece, so that all ranks stop
          // at the same piece when one of them fails.
          error = Utilities::MPI::max(error, communicator);
        }
      return error;
    }



    namespace
    {
      // A hash that is the same on every rank and every run (FNV-1a on the
      // key's bytes), unlike std::hash, whose values the standard leaves to
      // the implementation. Its residue modulo the number of ranks spreads
      // the keys about evenly over the ranks.
      unsigned int
      rendezvous_rank(const std::string &key, const unsigned int n_ranks)
      {
        std::uint64_t hash = 1469598103934665603ull;
        for (const char c : key)
          {
            hash ^= static_cast<unsigned char>(c);
            hash *= 1099511628211ull;
          }
        return hash % n_ranks;
      }

      // Buffers of keys and payloads: [key size, key bytes, payload size,
      // payload] one after the other, as chars. The sizes are 64-bit
      // integers, so a buffer is read back the same way on every rank. A
      // request is a key with an empty payload (payload = nullptr).
      void
      append(std::vector<char>         &buffer,
             const std::string         &key,
             const std::vector<double> *payload)
      {
        const std::uint64_t key_size = key.size();
        const std::uint64_t n_values = payload ? payload->size() : 0;
        const std::size_t   start    = buffer.size();
        buffer.resize(start + 2 * sizeof(std::uint64_t) + key_size
                      + n_values * sizeof(double));
        char *out = buffer.data() + start;
        std::memcpy(out, &key_size, sizeof(key_size));
        out += sizeof(key_size);
        std::memcpy(out, key.data(), key_size);
        out += key_size;
        std::memcpy(out, &n_values, sizeof(n_values));
        out += sizeof(n_values);
        if (n_values > 0)
          std::memcpy(out, payload->data(), n_values * sizeof(double));
      }

      // Calls function(key, payload) for every entry of a buffer, in the
      // order in which they were appended.
      template <typename Function>
      void
      for_each_entry(const std::vector<char> &buffer, const Function &function)
      {
        const char *in  = buffer.data();
        const char *end = in + buffer.size();
        while (in < end)
          {
            std::uint64_t key_size, n_values;
            std::memcpy(&key_size, in, sizeof(key_size));
            in += sizeof(key_size);
            std::string key(in, key_size);
            in += key_size;
            std::memcpy(&n_values, in, sizeof(n_values));
            in += sizeof(n_values);
            std::vector<double> payload(n_values);
            if (n_values > 0)
              std::memcpy(payload.data(), in, n_values * sizeof(double));
            in += n_values * sizeof(double);
            function(key, payload);
          }
      }
    } // namespace



    // @sect4{exchange_records}
    //
    // Three rounds of point-to-point messages between the ranks that have
    // something to say (Utilities::MPI::some_to_some): the records go to
    // their rendezvous ranks, the requests too, and the rendezvous ranks
    // answer. Each rank handles about its share of all records.
    //
    // Why a rendezvous: the rank that holds a record does not know who will
    // ask for it, and the rank that asks does not know who holds it. Both
    // know the key, and with it the rendezvous rank, where holders and
    // askers meet without anyone gathering all records or all requests. The
    // records of a key arrive there in the order of the ranks that sent them
    // (some_to_some returns the buffers ordered by rank), which gives the
    // order the header promises.
    std::map<std::string, std::vector<std::vector<double>>>
    exchange_records(const std::vector<Record>      &records,
                     const std::vector<std::string> &requests,
                     const MPI_Comm                  communicator)
    {
      const unsigned int n_ranks
        = Utilities::MPI::n_mpi_processes(communicator);

      // Round 1: every record goes to the rendezvous rank of its key, which
      // keeps all payloads per key.
      std::map<unsigned int, std::vector<char>> outgoing;
      for (const Record &record : records)
        append(outgoing[rendezvous_rank(record.first, n_ranks)],
               record.first,
               &record.second);
      std::map<std::string, std::vector<std::vector<double>>> held;
      for (const auto &[rank, buffer] :
           Utilities::MPI::some_to_some(communicator, outgoing))
        for_each_entry(buffer,
                       [&](const std::string   &key,
                           std::vector<double> &payload) {
                         held[key].push_back(std::move(payload));
                       });

      // Round 2: every request goes to the rendezvous rank of its key.
      outgoing.clear();
      for (const std::string &key : requests)
        append(outgoing[rendezvous_rank(key, n_ranks)], key, nullptr);
      // The rendezvous rank answers each asking rank with all payloads of
      // the keys it asked for; a key that no rank holds is simply not
      // answered.
      std::map<unsigned int, std::vector<char>> answers;
      for (const auto &[rank, buffer] :
           Utilities::MPI::some_to_some(communicator, outgoing))
        {
          std::vector<char> &answer = answers[rank];
          for_each_entry(buffer,
                         [&](const std::string &key, std::vector<double> &) {
                           const auto entry = held.find(key);
                           if (entry != held.end())
                             for (const std::vector<double> &payload :
                                  entry->second)
                               append(answer, key, &payload);
                         });
        }

      // Round 3: the answers go back to the ranks that asked.
      std::map<std::string, std::vector<std::vector<double>>> result;
      for (const auto &[rank, buffer] :
           Utilities::MPI::some_to_some(communicator, answers))
        for_each_entry(buffer,
                       [&](const std::string   &key,
                           std::vector<double> &payload) {
                         result[key].push_back(std::move(payload));
                       });
      return result;
    }
  } // namespace MPITools
} // namespace ViscoContact
