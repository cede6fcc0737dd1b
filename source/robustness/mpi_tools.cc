// The rendezvous exchange of keyed records (mpi_tools.h).

#include <deal.II/base/mpi.h>
#include <deal.II/base/utilities.h>

#include "robustness/mpi_tools.h"

#include <cstdint>
#include <cstring>
#include <unistd.h>

namespace ViscoContact
{
  namespace MPITools
  {
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



    // @sect4{RecordRouter}
    //
    // Three rounds of point-to-point messages between the ranks that have
    // something to say (Utilities::MPI::some_to_some): the requests go to
    // the rendezvous ranks of their keys once, at construction; then per
    // batch the records go there too, and the rendezvous rank forwards each
    // to the ranks that asked for its key as it arrives, so that no rank
    // holds more than a batch of records at a time. Each rank handles about
    // its share of all records.
    //
    // Why a rendezvous: the rank that holds a record does not know who will
    // ask for it, and the rank that asks does not know who holds it. Both
    // know the key, and with it the rendezvous rank, where holders and
    // askers meet without anyone gathering all records or all requests. The
    // records of a key arrive there in the order of the ranks that sent them
    // (some_to_some returns the buffers ordered by rank), and are forwarded
    // in that order.
    RecordRouter::RecordRouter(const std::vector<std::string> &requests,
                               const MPI_Comm                  communicator)
      : communicator(communicator)
    {
      const unsigned int n_ranks
        = Utilities::MPI::n_mpi_processes(communicator);
      std::map<unsigned int, std::vector<char>> outgoing;
      for (const std::string &key : requests)
        append(outgoing[rendezvous_rank(key, n_ranks)], key, nullptr);
      for (const auto &[rank, buffer] :
           Utilities::MPI::some_to_some(communicator, outgoing))
        for_each_entry(buffer,
                       [&, rank = rank](const std::string &key,
                                        std::vector<double> &) {
                         askers[key].push_back(rank);
                       });
    }



    std::vector<Record>
    RecordRouter::deliver(const std::vector<Record> &records) const
    {
      const unsigned int n_ranks
        = Utilities::MPI::n_mpi_processes(communicator);
      std::map<unsigned int, std::vector<char>> outgoing;
      for (const Record &record : records)
        append(outgoing[rendezvous_rank(record.first, n_ranks)],
               record.first,
               &record.second);
      std::map<unsigned int, std::vector<char>> forwarded;
      for (const auto &[rank, buffer] :
           Utilities::MPI::some_to_some(communicator, outgoing))
        for_each_entry(buffer,
                       [&](const std::string   &key,
                           std::vector<double> &payload) {
                         const auto entry = askers.find(key);
                         if (entry != askers.end())
                           for (const unsigned int asker : entry->second)
                             append(forwarded[asker], key, &payload);
                       });
      outgoing.clear();
      std::vector<Record> arrived;
      for (const auto &[rank, buffer] :
           Utilities::MPI::some_to_some(communicator, forwarded))
        for_each_entry(buffer,
                       [&](const std::string   &key,
                           std::vector<double> &payload) {
                         arrived.emplace_back(key, std::move(payload));
                       });
      return arrived;
    }



    // @sect4{exchange_records}
    //
    // All records in one batch.
    std::map<std::string, std::vector<std::vector<double>>>
    exchange_records(const std::vector<Record>      &records,
                     const std::vector<std::string> &requests,
                     const MPI_Comm                  communicator)
    {
      std::map<std::string, std::vector<std::vector<double>>> result;
      for (auto &[key, payload] :
           RecordRouter(requests, communicator).deliver(records))
        result[key].push_back(std::move(payload));
      return result;
    }



    // @sect4{agree_on_failure}
    //
    // One reduction finds the lowest failing rank (or none), one broadcast
    // sends its message.
    void
    agree_on_failure(const std::string &failure, const MPI_Comm communicator)
    {
      const unsigned int n_ranks
        = Utilities::MPI::n_mpi_processes(communicator);
      const unsigned int first_failing = Utilities::MPI::min(
        failure.empty() ? n_ranks
                        : Utilities::MPI::this_mpi_process(communicator),
        communicator);
      if (first_failing < n_ranks)
        throw ExcOnAllRanks(
          Utilities::MPI::broadcast(communicator, failure, first_failing));
    }



    // @sect4{ErrorAgreement}
    ErrorAgreement::ErrorAgreement()
    {
      const int error = MPI_Comm_dup(MPI_COMM_WORLD, &communicator);
      AssertThrowMPI(error);
    }



    // Freed before MPI_Finalize (main() holds the object inside the scope of
    // MPI_InitFinalize); collective, so only where every rank gets here.
    ErrorAgreement::~ErrorAgreement()
    {
      if (communicator != MPI_COMM_NULL)
        MPI_Comm_free(&communicator);
    }



    // A non-blocking barrier, polled until it completes or the time is up.
    // A barrier that does not complete cannot be taken back; the caller
    // then ends the ranks with MPI_Abort (and the destructor is never run).
    bool
    ErrorAgreement::all_ranks_stopped(const double timeout) const
    {
      MPI_Request request;
      if (MPI_Ibarrier(communicator, &request) != MPI_SUCCESS)
        return false;
      const double start = MPI_Wtime();
      int          done  = 0;
      while (MPI_Test(&request, &done, MPI_STATUS_IGNORE) == MPI_SUCCESS
             && !done && MPI_Wtime() - start < timeout)
        ::usleep(1000);
      return done != 0;
    }
  } // namespace MPITools
} // namespace ViscoContact
