// Writing files safely: temporary names, checked writes with the system's
// reason, and one outcome for all ranks (file_output.h).

#include <deal.II/base/exceptions.h>
#include <deal.II/base/utilities.h>

#include "file_output.h"

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

namespace ViscoContact
{
  namespace FileOutput
  {
    namespace
    {
      // The message of a failed write, the same wording everywhere.
      std::string
      failure(const std::string &file, const int error_number)
      {
        return "Writing the file " + file
               + " failed: " + std::strerror(error_number) + ".";
      }

      // write() may write less than asked for (a signal, a nearly full
      // disk): repeat until everything is written or an error is reported.
      bool
      write_all(const int descriptor, const std::string &text)
      {
        std::size_t done = 0;
        while (done < text.size())
          {
            const ssize_t n
              = ::write(descriptor, text.data() + done, text.size() - done);
            if (n < 0 && errno == EINTR)
              continue;
            if (n <= 0)
              return false;
            done += n;
          }
        return true;
      }
    } // namespace



    // The value is PATTERN or PATTERN:N: the writes of files whose name
    // contains PATTERN fail, from the N-th such write on (the first, without
    // N). N lets a test fail a file that is written repeatedly (the time
    // series gets its header, then a row per step) at a later write.
    bool
    simulate_failure(const std::string &file)
    {
      const char *value = std::getenv("VISCOPLASTIC_CONTACT_FAIL_WRITE");
      if (value == nullptr || *value == '\0')
        return false;
      std::string       pattern = value;
      unsigned int      first   = 1;
      const std::size_t colon   = pattern.rfind(':');
      if (colon != std::string::npos)
        {
          first   = std::atoi(pattern.c_str() + colon + 1);
          pattern = pattern.substr(0, colon);
        }
      if (file.find(pattern) == std::string::npos)
        return false;
      static unsigned int n_matching_writes = 0;
      return ++n_matching_writes >= first;
    }



    // @sect4{write_file_atomically}
    //
    // POSIX calls rather than a stream, since they say why they failed
    // (errno). close() is checked too: on network file systems a full disk
    // is often reported only there.
    std::string
    write_file_atomically(const std::string &file,
                          const std::string &content,
                          const bool         durable)
    {
      const std::string temporary = file + ".tmp";
      const int         descriptor
        = ::open(temporary.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
      if (descriptor < 0)
        return failure(file, errno);
      int error = 0;
      if (simulate_failure(file))
        error = ENOSPC;
      else if (!write_all(descriptor, content))
        error = errno;
      else if (durable && ::fsync(descriptor) != 0)
        error = errno;
      if (::close(descriptor) != 0 && error == 0)
        error = errno;
      if (error == 0 && std::rename(temporary.c_str(), file.c_str()) != 0)
        error = errno;
      if (error != 0)
        {
          // No partial file is left behind, under either name.
          ::unlink(temporary.c_str());
          return failure(file, error);
        }
      return "";
    }



    // @sect4{append_to_file}
    std::string
    append_to_file(const std::string &file, const std::string &text)
    {
      const int descriptor
        = ::open(file.c_str(), O_WRONLY | O_CREAT | O_APPEND, 0644);
      if (descriptor < 0)
        return failure(file, errno);
      struct stat status;
      const off_t old_size
        = (::fstat(descriptor, &status) == 0 ? status.st_size : -1);
      int error = 0;
      if (simulate_failure(file))
        error = ENOSPC;
      else if (!write_all(descriptor, text))
        error = errno;
      // A partly written row is removed again: the file ends after the last
      // complete row.
      if (error != 0 && old_size >= 0)
        (void)!::ftruncate(descriptor, old_size);
      if (::close(descriptor) != 0 && error == 0)
        error = errno;
      return error == 0 ? "" : failure(file, error);
    }



    // @sect4{agree_on_problem}
    //
    // The lowest rank with a problem is found by a minimum over the ranks
    // (a rank without a problem contributes n_ranks), and its message is
    // broadcast from there. Two collective calls whatever happened, so every
    // rank leaves this function at the same point of the program.
    void
    agree_on_problem(const std::string &problem, const MPI_Comm communicator)
    {
      const unsigned int n_ranks
        = Utilities::MPI::n_mpi_processes(communicator);
      const unsigned int first = Utilities::MPI::min(
        problem.empty() ? n_ranks
                        : Utilities::MPI::this_mpi_process(communicator),
        communicator);
      if (first == n_ranks)
        return;
      const std::string message
        = Utilities::MPI::broadcast(communicator, problem, first);
      AssertThrow(false, ExcMessage(message));
    }
  } // namespace FileOutput
} // namespace ViscoContact
