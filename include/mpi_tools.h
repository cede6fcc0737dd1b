#ifndef viscoplastic_contact_mpi_tools_h
#define viscoplastic_contact_mpi_tools_h

#include <deal.II/base/mpi.h>

#include <functional>
#include <map>
#include <string>
#include <utility>
#include <vector>

namespace ViscoContact
{
  using namespace dealii;

  // @sect3{Parallel files and data exchange}
  //
  // Two tools that keep every rank's work proportional to its own share of
  // the problem, whatever the number of ranks:
  //  - write_text_collectively(): one text file from the blocks of all
  //    ranks (in rank order), written with MPI I/O at offsets known from a
  //    prefix sum, so no rank collects the others' data. The file is
  //    written under a temporary name and renamed when complete;
  //  - exchange_records(): records (a key and a payload of doubles) held by
  //    some ranks, delivered to the ranks that ask for their keys, through
  //    a rendezvous rank chosen by a hash of the key. This is how a
  //    checkpoint written on one number of ranks is read on another, and
  //    how the convergence study brings a coarse run's cells to the ranks
  //    of the reference mesh.
  namespace MPITools
  {
    // Collective. A failure (the file cannot be written, the disk is full)
    // throws on every rank, with the file name and MPI's reason.
    void
    write_text_collectively(const std::string &file,
                            const std::string &local_text,
                            const MPI_Comm     communicator);

    // Collective. The general form: rank 0's prefix, then the blocks of all
    // ranks in rank order. try_write_blocks_collectively() returns the
    // message of a failure (the same on every rank) instead of throwing.
    std::string
    try_write_blocks_collectively(const std::string &file,
                                  const std::string &prefix,
                                  const char        *local_block,
                                  const std::size_t  local_size,
                                  const MPI_Comm     communicator);
    void
    write_blocks_collectively(const std::string &file,
                              const std::string &prefix,
                              const char        *local_block,
                              const std::size_t  local_size,
                              const MPI_Comm     communicator);

    // Collective. Calls io(start, size) for consecutive pieces of a local
    // block of local_size bytes, at most 1 GiB each (MPI counts are int),
    // the same number of times on every rank (with empty pieces where a
    // rank has less), as collective MPI I/O needs. Returns the first error
    // of any rank, or MPI_SUCCESS.
    int
    transfer_in_pieces(
      const std::size_t                                       local_size,
      const MPI_Comm                                          communicator,
      const std::function<int(const std::size_t, const int)> &io);

    using Record = std::pair<std::string, std::vector<double>>;

    // Collective. Keys are byte strings; several records may share a key.
    // Returns, for every requested key that some rank holds, the payloads
    // of all records with that key (in the order of the ranks that hold
    // them).
    std::map<std::string, std::vector<std::vector<double>>>
    exchange_records(const std::vector<Record>      &records,
                     const std::vector<std::string> &requests,
                     const MPI_Comm                  communicator);

    // MPI's text for an error code.
    std::string
    error_string(const int error_code);

    // The system's reason for an I/O error class of MPI (No space left on
    // device, ...) with MPI's text; MPI's text alone for other errors.
    std::string
    describe_error(const int error_code);
  } // namespace MPITools
} // namespace ViscoContact

#endif
