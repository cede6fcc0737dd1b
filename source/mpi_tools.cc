// Collective text files through MPI I/O, and the rendezvous exchange of
// keyed records.

#include <deal.II/base/exceptions.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/utilities.h>

#include "mpi_tools.h"

#include <cstdint>
#include <cstring>
#include <algorithm>
#include <filesystem>

namespace ViscoContact
{
  namespace MPITools
  {
    std::string
    error_string(const int error_code)
    {
      char text[MPI_MAX_ERROR_STRING];
      int  length = 0;
      MPI_Error_string(error_code, text, &length);
      return std::string(text, length);
    }



    // @sect4{write_blocks_collectively}
    //
    // Offsets from an exclusive prefix sum of the block sizes; every rank
    // writes its block at its offset (collectively), then rank 0 renames
    // the complete file. Errors are agreed on by all ranks before anything
    // is thrown, so no rank waits for another that gave up.
    void
    write_blocks_collectively(const std::string &file,
                              const std::string &prefix,
                              const char        *local_block,
                              const std::size_t  local_size,
                              const MPI_Comm     communicator)
    {
      const bool root = (Utilities::MPI::this_mpi_process(communicator) == 0);
      const std::string temporary = file + ".tmp";
      std::uint64_t     size      = local_size + (root ? prefix.size() : 0);
      std::uint64_t     offset    = 0;
      int               error
        = MPI_Exscan(&size, &offset, 1, MPI_UINT64_T, MPI_SUM, communicator);
      AssertThrowMPI(error);
      if (root)
        offset = prefix.size();

      MPI_File handle;
      error = MPI_File_open(communicator,
                            temporary.c_str(),
                            MPI_MODE_CREATE | MPI_MODE_WRONLY,
                            MPI_INFO_NULL,
                            &handle);
      if (Utilities::MPI::max(error, communicator) == MPI_SUCCESS)
        {
          error = MPI_File_set_size(handle, 0);
          if (error == MPI_SUCCESS && root && !prefix.empty())
            error = MPI_File_write_at(handle,
                                      0,
                                      prefix.data(),
                                      prefix.size(),
                                      MPI_CHAR,
                                      MPI_STATUS_IGNORE);
          error = Utilities::MPI::max(error, communicator);
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
          const int close_error = MPI_File_close(&handle);
          if (error == MPI_SUCCESS)
            error = close_error;
        }
      error               = Utilities::MPI::max(error, communicator);
      std::string problem = (error == MPI_SUCCESS ? "" : error_string(error));
      if (problem.empty() && root)
        {
          std::error_code rename_error;
          std::filesystem::rename(temporary, file, rename_error);
          if (rename_error)
            problem = rename_error.message();
        }
      problem = Utilities::MPI::broadcast(communicator, problem, 0);
      AssertThrow(problem.empty(),
                  ExcMessage("Writing the file " + file + " failed: " + problem
                             + "."));
    }



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



    int
    transfer_in_pieces(
      const std::size_t                                       local_size,
      const MPI_Comm                                          communicator,
      const std::function<int(const std::size_t, const int)> &io)
    {
      const std::size_t piece = std::size_t(1) << 30;
      const std::size_t most  = Utilities::MPI::max(local_size, communicator);
      int               error = MPI_SUCCESS;
      for (std::size_t start = 0; start < most && error == MPI_SUCCESS;
           start += piece)
        {
          const std::size_t begin = std::min(start, local_size);
          error
            = io(begin, static_cast<int>(std::min(piece, local_size - begin)));
          error = Utilities::MPI::max(error, communicator);
        }
      return error;
    }



    namespace
    {
      // A hash that is the same on every rank and every run (FNV-1a).
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
      // payload] one after the other, as chars.
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
    std::map<std::string, std::vector<std::vector<double>>>
    exchange_records(const std::vector<Record>      &records,
                     const std::vector<std::string> &requests,
                     const MPI_Comm                  communicator)
    {
      const unsigned int n_ranks
        = Utilities::MPI::n_mpi_processes(communicator);

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

      outgoing.clear();
      for (const std::string &key : requests)
        append(outgoing[rendezvous_rank(key, n_ranks)], key, nullptr);
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
