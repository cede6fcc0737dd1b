#ifndef viscoplastic_contact_file_output_h
#define viscoplastic_contact_file_output_h

#include <deal.II/base/mpi.h>

#include <cstddef>
#include <string>

namespace ViscoContact
{
  using namespace dealii;

  // @sect3{Writing files safely}
  //
  // The helpers that every writer uses; the files of a run go through
  // OutputFolder (output_folder.h), which stages and commits them.
  //  - agree_on_problem() turns a failure that one rank saw into the same
  //    exception on every rank, so that no rank waits in a collective call
  //    for another that gave up;
  //  - write_file() writes a file outside a run's folder (the parameter
  //    file of --print-parameters): to a temporary created exclusively next
  //    to it, renamed into place when complete, replacing an existing file
  //    only if asked to.
  //
  // For the tests, the environment variable VISCOPLASTIC_CONTACT_FAIL_WRITE
  // makes writes fail as on a full disk: every file whose name contains its
  // value (on the last rank of a group, for files ranks write together);
  // with the value PATTERN:N from the N-th such write on.
  namespace FileOutput
  {
    // True if the test switch VISCOPLASTIC_CONTACT_FAIL_WRITE is set and its
    // value is part of the file name.
    bool
    simulate_failure(const std::string &file);

    // Writes content to file through a temporary in the same folder,
    // created exclusively. An existing file is replaced only with replace =
    // true (a symbolic link under the name is replaced, never followed).
    // Returns an empty string on success, otherwise the message. Not
    // collective.
    std::string
    write_file(const std::string &file,
               const std::string &content,
               const bool         replace);

    // Collective: if any rank has a non-empty problem, every rank throws
    // the message of the lowest such rank; otherwise nothing happens.
    void
    agree_on_problem(const std::string &problem, const MPI_Comm communicator);

    // A file the program wrote and reads back (a manifest, checkpoint.info,
    // the time series) is untrusted input: something else may have put a
    // link, a named pipe, another account's file or a huge sparse file
    // under its name. read_own_file() opens name below the folder
    // descriptor base (AT_FDCWD: name is a path) without following a link
    // and without blocking, and reads it only if it is a regular file of
    // this account of at most max_size bytes. Otherwise content is empty
    // and reason says why ("is a named pipe, not a regular file", ...).
    enum class ReadResult
    {
      read,
      missing,
      refused
    };
    ReadResult
    read_own_file(const int          base,
                  const std::string &name,
                  const std::size_t  max_size,
                  std::string       &content,
                  std::string       &reason);
  } // namespace FileOutput
} // namespace ViscoContact

#endif
