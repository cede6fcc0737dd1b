#ifndef viscoplastic_contact_mpi_tools_h
#define viscoplastic_contact_mpi_tools_h

#include <deal.II/base/exceptions.h>
#include <deal.II/base/mpi.h>

#include <exception>
#include <map>
#include <sstream>
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

    // The same exchange in rounds, for more records than a rank can hold
    // twice (a checkpoint's): the requests go to their rendezvous ranks
    // once, which keep who asked for each key; each deliver() then sends a
    // batch of records there and on to the ranks that asked for their keys,
    // and returns those that arrived here. Collective: every rank calls
    // deliver() equally often (with an empty batch when it has none).
    class RecordRouter
    {
    public:
      RecordRouter(const std::vector<std::string> &requests,
                   const MPI_Comm                  communicator);

      std::vector<Record>
      deliver(const std::vector<Record> &records) const;

    private:
      MPI_Comm communicator;
      // On the rendezvous rank of each key: the ranks that asked for it.
      std::map<std::string, std::vector<unsigned int>> askers;
    };

    // @sect4{Errors that all ranks agree on}
    //
    // Work that only some ranks do (a group root reading the mesh) may fail
    // there while the others wait in a collective call. Such work is run
    // through failure_of(), which turns an exception into its message, and
    // agree_on_failure() then makes every rank throw ExcOnAllRanks with the
    // message of the first failing rank: main() reports it once and all
    // ranks end in order.
    class ExcOnAllRanks : public ExceptionBase
    {
    public:
      explicit ExcOnAllRanks(const std::string &message)
        : message(message)
      {}

      void
      print_info(std::ostream &out) const override
      {
        out << message;
      }

    private:
      const std::string message;
    };

    // The message main() would print for the exception function() throws,
    // or an empty string if it returns.
    template <typename Function>
    std::string
    failure_of(const Function &function)
    {
      try
        {
          function();
        }
      catch (const ExceptionBase &exc)
        {
          std::ostringstream message;
          exc.print_info(message);
          return message.str();
        }
      catch (const std::exception &exc)
        {
          return std::string("    ") + exc.what() + "\n";
        }
      return "";
    }

    // Collective. If some rank's failure is not empty, every rank throws
    // ExcOnAllRanks with that of the lowest such rank.
    void
    agree_on_failure(const std::string &failure, const MPI_Comm communicator);

    // @sect4{Ending all ranks after an error}
    //
    // An error that every rank raised at the same point (most are: a
    // message agreed on by agree_on_problem(), a check every rank makes)
    // lets every rank end in order, with the message printed once; only an
    // error on some ranks, while the others wait in a collective call that
    // will never complete, needs MPI_Abort (and gets Open MPI's banner).
    // main() holds an ErrorAgreement for the whole run: it duplicates
    // MPI_COMM_WORLD at the start (collective), so that its non-blocking
    // barrier never meets another collective call of the program.
    class ErrorAgreement
    {
    public:
      ErrorAgreement();
      ~ErrorAgreement();

      // Whether every rank has called this within timeout seconds (each
      // after its own error).
      bool
      all_ranks_stopped(const double timeout) const;

    private:
      MPI_Comm communicator = MPI_COMM_NULL;
    };
  } // namespace MPITools
} // namespace ViscoContact

#endif
