// Writing files safely: temporary names, checked writes with the system's
// reason, and one outcome for all ranks (file_output.h).

#include <deal.II/base/exceptions.h>
#include <deal.II/base/utilities.h>

#include "robustness/file_output.h"

#include <cerrno>
#include <cstdio>
#include <cstdint>
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



    // @sect4{read_own_file}
    //
    // O_NONBLOCK makes the open of a named pipe return at once (a regular
    // file ignores it); fstat() on the descriptor then says what was opened,
    // so nothing is read from what is not a regular file of this account.
    // The size is checked before anything is allocated.
    ReadResult
    read_own_file(const int          base,
                  const std::string &name,
                  const std::size_t  max_size,
                  std::string       &content,
                  std::string       &reason)
    {
      content.clear();
      reason.clear();
      const int descriptor
        = ::openat(base,
                   name.c_str(),
                   O_RDONLY | O_NOFOLLOW | O_NONBLOCK | O_CLOEXEC | O_NOCTTY);
      if (descriptor < 0)
        {
          if (errno == ENOENT)
            return ReadResult::missing;
          reason = errno == ELOOP ? "is a symbolic link"
                                  : std::string("cannot be opened (")
                                      + std::strerror(errno) + ")";
          return ReadResult::refused;
        }
      struct stat status;
      if (::fstat(descriptor, &status) != 0)
        reason
          = std::string("cannot be examined (") + std::strerror(errno) + ")";
      else if (S_ISFIFO(status.st_mode))
        reason = "is a named pipe, not a regular file";
      else if (!S_ISREG(status.st_mode))
        reason = "is not a regular file";
      else if (status.st_uid != ::geteuid())
        reason = "belongs to another account";
      else if (static_cast<std::uint64_t>(status.st_size) > max_size)
        reason = "has " + std::to_string(status.st_size)
                 + " bytes, more than the " + std::to_string(max_size)
                 + " this program writes there";
      if (!reason.empty())
        {
          ::close(descriptor);
          return ReadResult::refused;
        }
      content.resize(status.st_size);
      std::size_t done = 0;
      while (done < content.size())
        {
          const ssize_t n
            = ::read(descriptor, content.data() + done, content.size() - done);
          if (n < 0 && errno == EINTR)
            continue;
          if (n <= 0)
            break;
          done += n;
        }
      // A file that shrank while it was read keeps what was there.
      content.resize(done);
      ::close(descriptor);
      return ReadResult::read;
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
