// Writing files safely: temporary names, checked writes with the system's
// reason, and one outcome for all ranks (file_output.h).

#include <deal.II/base/exceptions.h>
#include <deal.II/base/utilities.h>

#include "robustness/file_output.h"

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fcntl.h>
#include <filesystem>
#include <sys/stat.h>
#include <unistd.h>

namespace ViscoContact
{
  namespace FileOutput
  {
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



    // @sect4{write_file}
    //
    // mkstemp() creates the temporary exclusively (O_EXCL) with a random
    // name in the target's folder, so the rename stays within one file
    // system and no link planted under a predictable name is followed.
    // rename() replaces the name itself (a link under it, not its target).
    std::string
    write_file(const std::string &file,
               const std::string &content,
               const bool         replace)
    {
      const std::filesystem::path target(file);
      std::string                 pattern = (target.parent_path()
                             / ("." + target.filename().string() + ".XXXXXX"))
                              .string();
      const int descriptor = ::mkstemp(pattern.data());
      if (descriptor < 0)
        return "Writing the file " + file + " failed: " + std::strerror(errno)
               + ".";
      int         error = simulate_failure(file) ? ENOSPC : 0;
      std::size_t done  = 0;
      while (error == 0 && done < content.size())
        {
          const ssize_t n
            = ::write(descriptor, content.data() + done, content.size() - done);
          if (n < 0 && errno == EINTR)
            continue;
          if (n <= 0)
            error = (n < 0 ? errno : EIO);
          else
            done += n;
        }
      if (error == 0 && ::fchmod(descriptor, 0644) != 0)
        error = errno;
      if (error == 0 && ::fsync(descriptor) != 0)
        error = errno;
      if (::close(descriptor) != 0 && error == 0)
        error = errno;
      if (error == 0 && replace
          && std::rename(pattern.c_str(), file.c_str()) != 0)
        error = errno;
      // Without replacing: renameat2(RENAME_NOREPLACE), or where the file
      // system does not offer it, a hard link (which fails if the name
      // exists) and the removal of the temporary.
      bool linked = false;
      if (error == 0 && !replace
          && ::renameat2(AT_FDCWD,
                         pattern.c_str(),
                         AT_FDCWD,
                         file.c_str(),
                         RENAME_NOREPLACE)
               != 0)
        {
          error = errno;
          if (error == EINVAL || error == ENOSYS || error == EOPNOTSUPP)
            {
              error  = ::link(pattern.c_str(), file.c_str()) == 0 ? 0 : errno;
              linked = (error == 0);
            }
        }
      if (error != 0 || linked)
        ::unlink(pattern.c_str());
      if (error == EEXIST)
        return "The file " + file
               + " exists and is not replaced (--force replaces it).";
      if (error != 0)
        return "Writing the file " + file + " failed: " + std::strerror(error)
               + ".";
      return "";
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
