#ifndef viscoplastic_contact_file_output_h
#define viscoplastic_contact_file_output_h

#include <deal.II/base/mpi.h>

#include <string>

namespace ViscoContact
{
  using namespace dealii;

  // @sect3{Writing files safely}
  //
  // Every file the program writes goes through the functions of this
  // namespace (or, for the files all ranks write together, through
  // MPITools::write_blocks_collectively(), which uses the same rules):
  //  - a file is written under a temporary name (FILE.tmp) and renamed to
  //    its name only when it is complete, so that no truncated file is ever
  //    left under a final name;
  //  - a failed write returns a message that names the file and the
  //    system's reason (strerror(errno), "No space left on device" on a full
  //    disk), and removes the temporary file;
  //  - agree_on_problem() turns a failure that one rank saw into the same
  //    exception on every rank, so that no rank waits in a collective call
  //    for another that gave up.
  //
  // For the tests, the environment variable VISCOPLASTIC_CONTACT_FAIL_WRITE
  // makes writes fail as on a full disk: every file whose name contains its
  // value (on the last rank, for files all ranks write together); with the
  // value PATTERN:N from the N-th such write on.
  namespace FileOutput
  {
    // True if the test switch VISCOPLASTIC_CONTACT_FAIL_WRITE is set and its
    // value is part of the file name.
    bool
    simulate_failure(const std::string &file);

    // Writes content to file (temporary name, then rename). Returns an empty
    // string on success, otherwise the message. With durable = true the data
    // reach the disk (fsync) before the rename. Not collective.
    std::string
    write_file_atomically(const std::string &file,
                          const std::string &content,
                          const bool         durable = false);

    // Appends text to file (created if missing). A failed append is undone
    // (the file is cut back to its old length), so that the file never ends
    // in a partial line. Returns an empty string or the message. Not
    // collective.
    std::string
    append_to_file(const std::string &file, const std::string &text);

    // Collective: if any rank has a non-empty problem, every rank throws
    // the message of the lowest such rank; otherwise nothing happens.
    void
    agree_on_problem(const std::string &problem, const MPI_Comm communicator);
  } // namespace FileOutput
} // namespace ViscoContact

#endif
