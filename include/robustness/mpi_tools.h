#ifndef viscoplastic_contact_mpi_tools_h
#define viscoplastic_contact_mpi_tools_h

#include <deal.II/base/mpi.h>

#include <map>
#include <string>
#include <utility>
#include <vector>

namespace ViscoContact
{
  using namespace dealii;

  // @sect3{Data exchange}
  //
  // exchange_records(): records (a key and a payload of doubles) held by
  // some ranks, delivered to the ranks that ask for their keys, through a
  // rendezvous rank chosen by a hash of the key, so that every rank's work
  // stays proportional to its own share of the problem, whatever the number
  // of ranks. This is how a checkpoint written on one number of ranks is read
  // on another, and how the convergence study brings a coarse run's cells to
  // the ranks of the reference mesh.
  namespace MPITools
  {
    using Record = std::pair<std::string, std::vector<double>>;

    // Collective. Keys are byte strings; several records may share a key.
    // Returns, for every requested key that some rank holds, the payloads
    // of all records with that key (in the order of the ranks that hold
    // them).
    std::map<std::string, std::vector<std::vector<double>>>
    exchange_records(const std::vector<Record>      &records,
                     const std::vector<std::string> &requests,
                     const MPI_Comm                  communicator);
  } // namespace MPITools
} // namespace ViscoContact

#endif
