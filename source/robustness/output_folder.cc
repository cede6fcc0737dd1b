// The output folder (output_folder.h): the manifest of what a run wrote, the
// lock that keeps a second run out, staged writes into a private folder of
// temporaries, and the commit that renames them into place.
//
// Written with POSIX calls relative to folder descriptors (openat, renameat2,
// unlinkat, ...) rather than std::filesystem or MPI I/O, because only they
// say exactly what happened (errno, counts) and never follow a link the call
// did not ask to follow. deal.II has nothing of the kind.

#include <deal.II/base/exceptions.h>
#include <deal.II/base/utilities.h>

#include "robustness/file_output.h"
#include "robustness/output_folder.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <dirent.h>
#include <fcntl.h>
#include <filesystem>
#include <iostream>
#include <random>
#include <regex>
#include <set>
#include <sstream>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

namespace ViscoContact
{
  const char *OutputFolder::manifest_name = ".viscoplastic_contact.manifest";
  const char *OutputFolder::lock_name     = ".viscoplastic_contact.lock";

  namespace
  {
    // The folders of this process, for release_all().
    std::set<OutputFolder *> &
    open_folders()
    {
      static std::set<OutputFolder *> folders;
      return folders;
    }

    // The prefix of the run's folder of temporaries.
    const std::string temporary_prefix = ".viscoplastic_contact.tmp.";

    // The names the program writes into an output folder (and checkpoint/),
    // for finding files that are in the way. Only for refusing: nothing is
    // ever removed because its name matches.
    bool
    is_program_name(const std::string &name)
    {
      static const std::regex names(
        "parameters\\.prm|solution\\.pvd|time_series\\.csv|convergence\\.csv|"
        "(solution|failed_step)_[0-9]+(\\.[0-9]+)?\\.(vtu|pvtu)|"
        "(contact|opposite)_profile_[0-9]+\\.csv|checkpoint|runs");
      return std::regex_match(name, names);
    }

    bool
    is_checkpoint_name(const std::string &name)
    {
      static const std::regex names("step_[0-9]+\\.bin|checkpoint\\.info");
      return std::regex_match(name, names);
    }

    // The step of a per-step file of the run (solution_0012.0.vtu,
    // contact_profile_0012.csv, opposite_profile_0012.csv,
    // checkpoint/step_000012.bin, ...), or -1.
    long
    step_of(const std::string &name)
    {
      static const std::regex per_step(
        "((solution|failed_step)_([0-9]+)(\\.[0-9]+)?\\.(vtu|pvtu))|"
        "((contact|opposite)_profile_([0-9]+)\\.csv)|"
        "(checkpoint/step_([0-9]+)\\.bin)");
      std::smatch match;
      if (!std::regex_match(name, match, per_step))
        return -1;
      for (const int group : {3, 8, 10})
        if (match[group].matched)
          return std::stol(match[group].str());
      return -1;
    }

    // write() may write less than asked for (a signal, a nearly full disk,
    // a file size limit): repeat until all is written or an error is
    // reported. Returns 0 or the errno.
    int
    write_all(const int         descriptor,
              const char       *data,
              const std::size_t size,
              const off_t       offset,
              const bool        positioned)
    {
      std::size_t done = 0;
      while (done < size)
        {
          const ssize_t n
            = positioned
                ? ::pwrite(descriptor, data + done, size - done, offset + done)
                : ::write(descriptor, data + done, size - done);
          if (n < 0 && errno == EINTR)
            continue;
          if (n < 0)
            return errno;
          if (n == 0)
            return EIO;
          done += n;
        }
      return 0;
    }

    // The folder of a relative name ("checkpoint/step_000010.bin") opened
    // below base without following links, and the name's last component.
    // Returns a descriptor to close (or base itself, not to be closed), or
    // -1 with errno set.
    int
    open_parent(const int base, const std::string &name, std::string &leaf)
    {
      const std::size_t slash = name.rfind('/');
      if (slash == std::string::npos)
        {
          leaf = name;
          return base;
        }
      leaf = name.substr(slash + 1);
      return ::openat(base,
                      name.substr(0, slash).c_str(),
                      O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
    }

    // The largest manifest the program reads: a line of about 40 bytes per
    // file, with at most 10000 .vtu records of at most 9 files each, a
    // profile per Profile time and a checkpoint per step, is far below it.
    constexpr std::size_t max_manifest_size = std::size_t(256) << 20;

    // Whether a manifest line names something the program makes, by kind:
    // a file of its own name (no '/', no "..", no absolute path, no other
    // file of the folder: not the manifest, not the lock), a folder it
    // creates (checkpoint/, runs/ of a study and the runs in it), or a
    // folder of temporaries. Everything else was put there by something
    // else, and the program obeys none of it.
    bool
    is_manifest_entry(const std::string &kind, const std::string &name)
    {
      static const std::regex files(
        "parameters\\.prm|solution\\.pvd|time_series\\.csv|convergence\\."
        "csv|(solution|failed_step)_[0-9]+(\\.[0-9]+)?\\.(vtu|pvtu)|"
        "(contact|opposite)_profile_[0-9]+\\.csv|checkpoint/(step_[0-9]+\\.bin|"
        "checkpoint\\.info)");
      static const std::regex folders(
        "checkpoint|runs|runs/(reference|h_1_[0-9]+_k_[0-9][0-9.e+-]*)");
      static const std::regex temporaries(
        "\\.viscoplastic_contact\\.tmp\\.[a-z0-9]{10}");
      return name.size() < 256
             && ((kind == "file" && std::regex_match(name, files))
                 || (kind == "folder" && std::regex_match(name, folders))
                 || (kind == "temporary"
                     && std::regex_match(name, temporaries)));
    }

    // The manifest's entries: "KIND NAME" per line, KIND one of file,
    // folder, temporary. A last line without its newline is an append that
    // did not complete and is ignored.
    using Manifest = std::vector<std::pair<std::string, std::string>>;
    Manifest
    parse_manifest(const std::string &content)
    {
      Manifest    entries;
      std::size_t start = 0;
      while (start < content.size())
        {
          const std::size_t end = content.find('\n', start);
          if (end == std::string::npos)
            break;
          const std::string line  = content.substr(start, end - start);
          start                   = end + 1;
          const std::size_t space = line.find(' ');
          if (line.empty() || line[0] == '#')
            continue;
          if (space == std::string::npos)
            entries.emplace_back(line, "");
          else
            entries.emplace_back(line.substr(0, space), line.substr(space + 1));
        }
      return entries;
    }

    // The manifest below base, read as untrusted input
    // (FileOutput::read_own_file()) and every line checked
    // (is_manifest_entry()). Returns an empty string (entries: the
    // manifest's, none if there is none) or what is wrong with it, for
    // "its manifest NAME ...".
    std::string
    read_manifest(const int base, Manifest &entries)
    {
      entries.clear();
      std::string content, reason;
      if (FileOutput::read_own_file(base,
                                    OutputFolder::manifest_name,
                                    max_manifest_size,
                                    content,
                                    reason)
          == FileOutput::ReadResult::refused)
        return reason;
      entries = parse_manifest(content);
      for (const auto &[kind, name] : entries)
        if (!is_manifest_entry(kind, name))
          {
            std::string line = kind + " " + name;
            if (line.size() > 80)
              line = line.substr(0, 80) + "...";
            for (char &c : line)
              if (!std::isprint(static_cast<unsigned char>(c)))
                c = '?';
            entries.clear();
            return "has the line <" + line
                   + ">, a name this program never writes there";
          }
      return "";
    }

    // Whether a file or folder that a manifest lists may be removed: this
    // account's (a folder shared with others may hold their files under
    // the names a manifest lists).
    bool
    owned(const struct stat &status)
    {
      return status.st_uid == ::geteuid();
    }



    // The entries of a folder (without . and ..), sorted.
    std::vector<std::string>
    folder_entries(const int descriptor)
    {
      std::vector<std::string> names;
      const int                copy = ::dup(descriptor);
      if (copy < 0)
        return names;
      DIR *folder = ::fdopendir(copy);
      if (folder == nullptr)
        {
          ::close(copy);
          return names;
        }
      ::rewinddir(folder);
      while (const dirent *entry = ::readdir(folder))
        {
          const std::string name = entry->d_name;
          if (name != "." && name != "..")
            names.push_back(name);
        }
      ::closedir(folder);
      std::sort(names.begin(), names.end());
      return names;
    }

    // The kind of an entry below base, without following links.
    bool
    status_of(const int base, const std::string &name, struct stat &status)
    {
      std::string leaf;
      const int   parent = open_parent(base, name, leaf);
      if (parent < 0)
        return false;
      const bool found
        = ::fstatat(parent, leaf.c_str(), &status, AT_SYMLINK_NOFOLLOW) == 0;
      if (parent != base)
        ::close(parent);
      return found;
    }

    // Removes a folder of temporaries: the entries of the folder that
    // descriptor holds, then its name below base, if the name still is that
    // folder. Only a folder of this account with mode 0700 is touched (the
    // program creates them so: nobody else can have put anything into it).
    // Everything goes through the descriptor, so a folder moved away and
    // replaced by another under its name during the run loses nothing.
    void
    remove_temporary_folder_at(const int          base,
                               const std::string &name,
                               const int          descriptor)
    {
      struct stat folder, named;
      if (::fstat(descriptor, &folder) != 0 || !S_ISDIR(folder.st_mode)
          || !owned(folder) || (folder.st_mode & 0077) != 0)
        return;
      for (const std::string &entry : folder_entries(descriptor))
        ::unlinkat(descriptor, entry.c_str(), 0);
      if (::fstatat(base, name.c_str(), &named, AT_SYMLINK_NOFOLLOW) == 0
          && named.st_dev == folder.st_dev && named.st_ino == folder.st_ino)
        ::unlinkat(base, name.c_str(), AT_REMOVEDIR);
    }

    // The same for a folder of temporaries known by its name only (one of a
    // killed run, listed in the manifest).
    void
    remove_temporary_folder(const int base, const std::string &name)
    {
      const int descriptor
        = ::openat(base,
                   name.c_str(),
                   O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
      if (descriptor < 0)
        return;
      remove_temporary_folder_at(base, name, descriptor);
      ::close(descriptor);
    }

    // Removes what the manifest of the folder below base lists (the folder
    // of an earlier run, or of a run of a convergence study inside it),
    // except the file with the identity protected (the parameter file being
    // run). Files first, in reverse order of listing, then the folders that
    // are empty then; a listed name that is no longer a regular file (or a
    // folder) of this account is not the run's any more and stays. Then the
    // manifest itself, and in a folder inside (a run of a study) a stale lock
    // file; the lock of the top folder is the one this run holds. A manifest
    // that is not the program's (read_manifest()) removes nothing; the top
    // one has been checked (check_entries()).
    void
    remove_listed(const int          base,
                  const struct stat *protected_file,
                  const bool         inner_folder)
    {
      Manifest entries;
      if (!read_manifest(base, entries).empty())
        return;
      for (auto entry = entries.rbegin(); entry != entries.rend(); ++entry)
        {
          const auto &[kind, name] = *entry;
          struct stat status;
          if (!status_of(base, name, status) || !owned(status))
            continue;
          std::string leaf;
          const int   parent = open_parent(base, name, leaf);
          if (parent < 0)
            continue;
          if (kind == "file" && S_ISREG(status.st_mode)
              && !(protected_file != nullptr
                   && status.st_dev == protected_file->st_dev
                   && status.st_ino == protected_file->st_ino))
            ::unlinkat(parent, leaf.c_str(), 0);
          else if (kind == "temporary" && S_ISDIR(status.st_mode))
            remove_temporary_folder(parent, leaf);
          else if (kind == "folder" && S_ISDIR(status.st_mode))
            {
              // A folder with a manifest of its own (a run of a study) is
              // cleared by that manifest first.
              const int inner
                = ::openat(parent,
                           leaf.c_str(),
                           O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
              if (inner >= 0)
                {
                  remove_listed(inner, protected_file, true);
                  ::close(inner);
                }
              ::unlinkat(parent, leaf.c_str(), AT_REMOVEDIR);
            }
          if (parent != base)
            ::close(parent);
        }
      struct stat status;
      ::unlinkat(base, OutputFolder::manifest_name, 0);
      if (inner_folder
          && ::fstatat(base,
                       OutputFolder::lock_name,
                       &status,
                       AT_SYMLINK_NOFOLLOW)
               == 0
          && S_ISREG(status.st_mode) && owned(status))
        ::unlinkat(base, OutputFolder::lock_name, 0);
    }

    // "a, b, c and 4 more": the first few names of a list, for messages.
    std::string
    short_list(const std::vector<std::string> &names)
    {
      std::string list;
      for (unsigned int i = 0; i < std::min<std::size_t>(4, names.size()); ++i)
        list += (i > 0 ? ", " : "") + names[i];
      if (names.size() > 4)
        list += " and " + std::to_string(names.size() - 4) + " more";
      return list;
    }


    // The manifest of a folder, and those of the runs of a study in the
    // folders it lists ("runs/..."): an empty string, or the problem of the
    // first manifest that is not as the program wrote it, whose name
    // (relative to the folder) is then in name.
    std::string
    read_manifests(const int    folder_descriptor,
                   Manifest    &entries,
                   std::string &name)
    {
      std::string problem = read_manifest(folder_descriptor, entries);
      for (const auto &[kind, listed] : entries)
        if (problem.empty() && kind == "folder"
            && listed.rfind("runs/", 0) == 0)
          {
            std::string leaf;
            const int   parent = open_parent(folder_descriptor, listed, leaf);
            const int   inner
              = parent < 0
                  ? -1
                  : ::openat(parent,
                             leaf.c_str(),
                             O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
            Manifest inner_entries;
            if (inner >= 0)
              {
                problem = read_manifest(inner, inner_entries);
                name    = listed + "/" + OutputFolder::manifest_name;
                ::close(inner);
              }
            if (parent >= 0 && parent != folder_descriptor)
              ::close(parent);
          }
      return problem;
    }

    // The entries of a folder with the names of the program's output that
    // its manifest does not list (listed), and the listed names that have
    // become symbolic links (neither removed nor replaced: they are not the
    // run's any more), with the checkpoint files a listed checkpoint folder
    // does not list. The listed files that exist go into earlier_run.
    std::vector<std::string>
    names_in_the_way(const int                    folder_descriptor,
                     const std::set<std::string> &listed,
                     std::vector<std::string>    &earlier_run)
    {
      std::vector<std::string> in_the_way;
      for (const std::string &name : folder_entries(folder_descriptor))
        {
          const bool is_listed = listed.count(name) > 0;
          if (is_listed && name[0] != '.')
            earlier_run.push_back(name);
          else if (!is_listed && is_program_name(name))
            in_the_way.push_back(name);
        }
      for (const std::string &name : listed)
        {
          struct stat status;
          if (status_of(folder_descriptor, name, status)
              && S_ISLNK(status.st_mode))
            in_the_way.push_back(name);
        }
      if (listed.count("checkpoint") > 0)
        {
          const int inner
            = ::openat(folder_descriptor,
                       "checkpoint",
                       O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
          if (inner >= 0)
            {
              for (const std::string &name : folder_entries(inner))
                if (is_checkpoint_name(name)
                    && listed.count("checkpoint/" + name) == 0)
                  in_the_way.push_back("checkpoint/" + name);
              ::close(inner);
            }
        }
      return in_the_way;
    }

    std::string
    host_name()
    {
      char name[256] = {};
      if (::gethostname(name, sizeof(name) - 1) != 0)
        return "this machine";
      return name;
    }

    // The name under which a file is staged in the folder of temporaries:
    // its relative name with the folder separators replaced, so that every
    // rank of a collective write knows it without being told.
    std::string
    temporary_name(const std::string &name)
    {
      std::string temporary = name;
      std::replace(temporary.begin(), temporary.end(), '/', '@');
      return temporary + ".tmp";
    }
  } // namespace



  // @sect4{OutputFolder::OutputFolder}
  //
  // Only rank 0 looks at the folder; the others learn the outcome.
  OutputFolder::OutputFolder(const std::string &directory,
                             const Mode         mode,
                             const std::string &parameter_file,
                             const MPI_Comm     communicator)
    : folder(directory)
    , mode(mode)
    , parameter_file(parameter_file)
    , communicator(communicator)
    , root(Utilities::MPI::this_mpi_process(communicator) == 0)
  {
    open_folders().insert(this);
    std::string message;
    if (root)
      {
        message = open_and_check(/*create=*/false);
        if (!message.empty())
          unlock();
      }
    try
      {
        FileOutput::agree_on_problem(message, communicator);
      }
    catch (...)
      {
        release();
        throw;
      }
  }



  OutputFolder::~OutputFolder()
  {
    release();
  }



  void
  OutputFolder::release_all()
  {
    const std::set<OutputFolder *> folders = open_folders();
    for (OutputFolder *folder : folders)
      folder->release();
  }



  // The temporaries this rank staged, the folder of temporaries (rank 0,
  // which created it) and the lock.
  void
  OutputFolder::release()
  {
    open_folders().erase(this);
    for (const StagedFile &file : staged)
      ::unlinkat(temporary_descriptor, file.temporary.c_str(), 0);
    if (root && folder_descriptor >= 0 && !temporary_folder.empty())
      {
        if (temporary_descriptor >= 0)
          remove_temporary_folder_at(folder_descriptor,
                                     temporary_folder,
                                     temporary_descriptor);
        else
          remove_temporary_folder(folder_descriptor, temporary_folder);
      }
    if (temporary_descriptor >= 0)
      ::close(temporary_descriptor);
    if (manifest_descriptor >= 0)
      ::close(manifest_descriptor);
    if (root)
      unlock();
    if (folder_descriptor >= 0)
      ::close(folder_descriptor);
    staged.clear();
    temporary_descriptor = manifest_descriptor = folder_descriptor = -1;
    temporary_folder.clear();
  }



  const std::string &
  OutputFolder::directory() const
  {
    return folder;
  }



  MPI_Comm
  OutputFolder::get_communicator() const
  {
    return communicator;
  }



  std::string
  OutputFolder::path(const std::string &name) const
  {
    return (std::filesystem::path(folder) / name).string();
  }



  std::string
  OutputFolder::failure(const std::string &name, const int error_number) const
  {
    return "Writing the file " + path(name)
           + " failed: " + std::strerror(error_number) + ".";
  }



  // @sect4{OutputFolder::open_and_check}
  //
  // Rank 0: the folder's descriptor, its lock, and the check of its entries.
  // Without create, a folder that does not exist is fine (there is nothing
  // to check); prepare() creates it.
  std::string
  OutputFolder::open_and_check(const bool create)
  {
    const std::string entry_name
      = "Invalid parameter <Output directory> in subsection <Output>: value <"
        + folder + ">";
    if (folder_descriptor < 0)
      {
        std::error_code error;
        if (create)
          std::filesystem::create_directories(folder, error);
        if (error)
          return entry_name + "; it cannot be created (" + error.message()
                 + ").";
        folder_descriptor
          = ::open(folder.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
        if (folder_descriptor < 0 && errno == ENOENT && !create)
          return mode == Mode::resume
                   ? "Invalid parameter <Resume> in subsection <Checkpoint>: "
                     "value <true>, but the Output directory <"
                       + folder
                       + "> does not exist; accepted: true only when the "
                         "Output "
                         "directory holds a run of this program to continue."
                   : "";
        if (folder_descriptor < 0)
          return entry_name + "; it cannot be opened as a folder ("
                 + std::strerror(errno) + ").";
      }
    if (lock_descriptor < 0)
      {
        const std::string message = lock();
        if (!message.empty())
          return message;
      }
    return check_entries();
  }



  // @sect4{OutputFolder::lock}
  //
  // flock() on the lock file, without waiting. The file is opened without
  // following a link and without blocking (a named pipe under its name), and
  // it must be a regular file of this account with no other name (a hard
  // link planted under the name would otherwise have its target truncated
  // and overwritten). After taking the lock, the descriptor must still be
  // the file under the name: a run that ended between our open() and flock()
  // may have removed it (each run removes its lock file at its end, while it
  // still holds the lock), and a lock on a removed file keeps nobody out.
  std::string
  OutputFolder::lock()
  {
    const std::string entry_name
      = "Invalid parameter <Output directory> in subsection <Output>: value <"
        + folder + ">";
    for (unsigned int attempt = 0; attempt < 100; ++attempt)
      {
        const int descriptor = ::openat(folder_descriptor,
                                        lock_name,
                                        O_RDWR | O_CREAT | O_NOFOLLOW
                                          | O_NONBLOCK | O_CLOEXEC | O_NOCTTY,
                                        0644);
        if (descriptor < 0)
          return entry_name + "; its lock file " + path(lock_name)
                 + " cannot be created or opened ("
                 + (errno == ELOOP ? std::string("it is a symbolic link")
                                   : std::string(std::strerror(errno)))
                 + "); accepted: a folder whose lock file, if any, is one "
                   "this program made (remove it if no run is using the "
                   "folder).";
        struct stat opened;
        if (::fstat(descriptor, &opened) != 0 || !S_ISREG(opened.st_mode)
            || opened.st_nlink != 1 || opened.st_uid != ::geteuid())
          {
            const bool fifo = S_ISFIFO(opened.st_mode);
            ::close(descriptor);
            return entry_name + "; its lock file " + path(lock_name) + " is "
                   + (fifo                           ? "a named pipe"
                      : !S_ISREG(opened.st_mode)     ? "not a regular file"
                      : opened.st_uid != ::geteuid() ? "another account's file"
                                                     : "a link to another file")
                   + ", not one this program made, and the run does not "
                     "write into it; accepted: a folder without it (remove "
                     "it if no run is using the folder, or choose another "
                     "Output directory).";
          }
        if (::flock(descriptor, LOCK_EX | LOCK_NB) != 0)
          {
            const int error = errno;
            if (error == EWOULDBLOCK)
              {
                // Who holds it, as that run wrote it: a line of it at most,
                // printable characters only (the file is not trusted).
                char          buffer[201] = {};
                const ssize_t n
                  = ::pread(descriptor, buffer, sizeof(buffer) - 1, 0);
                ::close(descriptor);
                std::string holder(buffer, n > 0 ? n : 0);
                holder = holder.substr(0, holder.find('\n'));
                for (char &c : holder)
                  if (!std::isprint(static_cast<unsigned char>(c)))
                    c = '?';
                return entry_name + "; another run is writing into it ("
                       + (holder.empty() ? "process unknown" : holder)
                       + "); accepted: a folder no other run is using. Wait "
                         "for that run to end, or choose another Output "
                         "directory.";
              }
            // A file system without locks (some network file systems):
            // said, and the run goes on unprotected.
            std::cerr << "Warning: the Output directory <" << folder
                      << "> cannot be locked (" << std::strerror(error)
                      << "); make sure that no other run writes into it."
                      << std::endl;
          }
        struct stat named;
        if (::fstatat(folder_descriptor, lock_name, &named, AT_SYMLINK_NOFOLLOW)
              != 0
            || opened.st_dev != named.st_dev || opened.st_ino != named.st_ino)
          {
            ::close(descriptor);
            continue;
          }
        // Who holds it, for the message of a run that is refused.
        const auto now = std::chrono::system_clock::to_time_t(
          std::chrono::system_clock::now());
        char started[64];
        std::strftime(started,
                      sizeof(started),
                      "%Y-%m-%d %H:%M:%S",
                      std::localtime(&now));
        std::string holder = "process " + std::to_string(::getpid()) + " on "
                             + host_name() + ", started " + started + "\n";
        if (::ftruncate(descriptor, 0) == 0)
          (void)!write_all(descriptor, holder.data(), holder.size(), 0, true);
        lock_descriptor = descriptor;
        return "";
      }
    return entry_name
           + "; its lock file keeps changing; accepted: a folder no other run "
             "is using.";
  }



  // The lock file is removed while it is still locked (see lock()), then
  // released; a file that has taken its name meanwhile stays.
  void
  OutputFolder::unlock()
  {
    if (lock_descriptor < 0)
      return;
    struct stat locked, named;
    if (::fstat(lock_descriptor, &locked) == 0
        && ::fstatat(folder_descriptor, lock_name, &named, AT_SYMLINK_NOFOLLOW)
             == 0
        && locked.st_dev == named.st_dev && locked.st_ino == named.st_ino)
      ::unlinkat(folder_descriptor, lock_name, 0);
    ::close(lock_descriptor);
    lock_descriptor = -1;
  }



  // @sect4{OutputFolder::check_entries}
  //
  // What is in the folder, against the mode. Names the program writes that
  // no manifest lists are in the way in every mode (they are another
  // program's, or an older version's); a manifest's files that still exist
  // are an earlier run's, which only Overwrite (or Resume) accepts.
  std::string
  OutputFolder::check_entries() const
  {
    const std::string entry_name
      = "Invalid parameter <Output directory> in subsection <Output>: value <"
        + folder + ">";
    // The manifest is obeyed only as the program wrote it, and so are those
    // of the runs of a study in the folders it lists.
    Manifest    entries;
    struct stat status;
    const bool  has_manifest
      = status_of(folder_descriptor, manifest_name, status);
    std::string       manifest_name_read = manifest_name;
    const std::string manifest_problem
      = read_manifests(folder_descriptor, entries, manifest_name_read);
    const std::string manifest_path = path(manifest_name_read);
    if (!manifest_problem.empty())
      return entry_name + "; its manifest " + manifest_path + " "
             + manifest_problem
             + ": it is not as this program wrote it, and the run neither "
               "reads nor removes anything by it; accepted: a folder whose "
               "manifest is this program's (move the folder's files away "
               "yourself and remove the manifest, or choose another Output "
               "directory).";
    std::set<std::string> listed_names;
    for (const auto &entry : entries)
      listed_names.insert(entry.second);

    std::vector<std::string> earlier_run;
    std::vector<std::string> in_the_way
      = names_in_the_way(folder_descriptor, listed_names, earlier_run);
    std::sort(in_the_way.begin(), in_the_way.end());
    if (!in_the_way.empty())
      return entry_name
             + " holds files with the names of this program's output that no "
               "manifest of this program lists, or links under them ("
             + short_list(in_the_way)
             + "): they were written by something else or by an older "
               "version of the program, and the run neither replaces nor "
               "removes them; accepted: a folder without them (move or "
               "remove them yourself, or choose another Output directory).";
    if (mode == Mode::new_run && !earlier_run.empty())
      return entry_name + " holds the files of another run ("
             + short_list(earlier_run)
             + "); accepted: a directory without them, or Overwrite = true in "
               "subsection Output to remove exactly the files that run "
               "wrote (its manifest "
             + std::string(manifest_name)
             + " lists them), or Resume = true in subsection Checkpoint to "
               "continue that run.";
    if (mode == Mode::resume && !has_manifest)
      return "Invalid parameter <Resume> in subsection <Checkpoint>: value "
             "<true>, but the Output directory <"
             + folder + "> holds no run of this program (it has no manifest "
             + manifest_name
             + "); accepted: true only when the Output directory holds a run "
               "of this program to continue.";
    // Overwrite must not remove the parameter file being run (a run of the
    // parameters.prm an earlier run wrote, say).
    struct stat parameters;
    if (mode == Mode::overwrite && !parameter_file.empty()
        && ::stat(parameter_file.c_str(), &parameters) == 0)
      for (const std::string &name : listed_names)
        {
          struct stat status;
          if (status_of(folder_descriptor, name, status)
              && status.st_dev == parameters.st_dev
              && status.st_ino == parameters.st_ino)
            return entry_name + ": Overwrite = true would remove " + path(name)
                   + ", which is the parameter file being run; accepted: "
                     "a parameter file outside the files of the run to "
                     "overwrite (copy it elsewhere first).";
        }
    return "";
  }



  // @sect4{OutputFolder::prepare}
  //
  // Rank 0 creates, locks and checks the folder (again: it may have been
  // created since the constructor looked), removes what the mode asks for,
  // starts or continues the manifest and creates the folder of temporaries
  // under a random name. Then every rank opens the folder and the folder of
  // temporaries, and checks that the latter is the run's own (this
  // account's, mode 0700).
  void
  OutputFolder::prepare(const unsigned int resume_step)
  {
    std::string message;
    if (root)
      {
        message = open_and_check(/*create=*/true);
        if (message.empty())
          message = remove_earlier_run(resume_step);
        if (message.empty())
          message = start_manifest();
        if (message.empty())
          {
            std::random_device              device;
            std::uniform_int_distribution<> digit(0, 35);
            const char *symbols = "abcdefghijklmnopqrstuvwxyz0123456789";
            for (unsigned int attempt = 0; attempt < 100; ++attempt)
              {
                std::string name = temporary_prefix;
                for (unsigned int i = 0; i < 10; ++i)
                  name += symbols[digit(device)];
                message = append_to_manifest("temporary", name);
                if (!message.empty())
                  break;
                if (::mkdirat(folder_descriptor, name.c_str(), 0700) == 0)
                  {
                    temporary_folder = name;
                    break;
                  }
                if (errno != EEXIST)
                  {
                    message = failure(name, errno);
                    break;
                  }
              }
            if (message.empty() && temporary_folder.empty())
              message = failure(temporary_prefix, EEXIST);
          }
      }
    FileOutput::agree_on_problem(message, communicator);

    temporary_folder
      = Utilities::MPI::broadcast(communicator, temporary_folder, 0);
    if (folder_descriptor < 0)
      folder_descriptor
        = ::open(folder.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (folder_descriptor >= 0)
      temporary_descriptor
        = ::openat(folder_descriptor,
                   temporary_folder.c_str(),
                   O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
    struct stat status;
    if (temporary_descriptor < 0 || ::fstat(temporary_descriptor, &status) != 0)
      message = failure(temporary_folder, errno);
    else if (status.st_uid != ::geteuid() || (status.st_mode & 0077) != 0)
      message = "The folder of temporaries " + path(temporary_folder)
                + " is not this run's own (another owner or mode); the run "
                  "does not write into it.";
    FileOutput::agree_on_problem(message, communicator);
  }



  // @sect4{OutputFolder::remove_earlier_run}
  //
  // Rank 0. Overwrite: everything the manifest lists goes (remove_listed()).
  // Resume: the files of steps after the checkpoint (the resumed run writes
  // them again, and a rename does not replace them) and checkpoint files
  // other than the one resumed from. In every mode: folders of temporaries
  // of killed runs.
  std::string
  OutputFolder::remove_earlier_run(const unsigned int resume_step)
  {
    if (mode == Mode::overwrite)
      {
        struct stat        parameters;
        const struct stat *protected_file = nullptr;
        if (!parameter_file.empty()
            && ::stat(parameter_file.c_str(), &parameters) == 0)
          protected_file = &parameters;
        remove_listed(folder_descriptor, protected_file, false);
        return "";
      }
    Manifest entries;
    read_manifest(folder_descriptor, entries);
    for (const auto &[kind, name] : entries)
      {
        const long step = step_of(name);
        if (kind == "temporary")
          remove_temporary_folder(folder_descriptor, name);
        else if (mode == Mode::resume && kind == "file"
                 && (step > long(resume_step)
                     || (step >= 0 && step != long(resume_step)
                         && name.rfind("checkpoint/", 0) == 0)))
          {
            std::string leaf;
            const int   parent = open_parent(folder_descriptor, name, leaf);
            struct stat status;
            if (parent >= 0
                && ::fstatat(parent, leaf.c_str(), &status, AT_SYMLINK_NOFOLLOW)
                     == 0
                && S_ISREG(status.st_mode) && owned(status))
              ::unlinkat(parent, leaf.c_str(), 0);
            if (parent >= 0 && parent != folder_descriptor)
              ::close(parent);
          }
      }
    return "";
  }



  // @sect4{OutputFolder::start_manifest}
  //
  // Rank 0. A new manifest for a new run; for a resumed run the old one,
  // compacted to what still exists (written to a new file, made durable and
  // renamed over the old one). Then it is kept open for appending.
  std::string
  OutputFolder::start_manifest()
  {
    std::string content = "# The files and folders viscoplastic_contact "
                          "wrote here; Overwrite = true removes exactly "
                          "these.\n";
    listed.clear();
    if (mode == Mode::resume)
      {
        Manifest old;
        read_manifest(folder_descriptor, old);
        for (const auto &[kind, name] : old)
          {
            struct stat status;
            if (kind != "temporary"
                && status_of(folder_descriptor, name, status)
                && listed.insert(name).second)
              content += kind + " " + name + "\n";
          }
      }
    const std::string new_name = std::string(manifest_name) + ".new";
    ::unlinkat(folder_descriptor, new_name.c_str(), 0);
    const int descriptor
      = ::openat(folder_descriptor,
                 new_name.c_str(),
                 O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC,
                 0644);
    if (descriptor < 0)
      return failure(manifest_name, errno);
    int error = write_all(descriptor, content.data(), content.size(), 0, false);
    if (error == 0 && ::fsync(descriptor) != 0)
      error = errno;
    if (::close(descriptor) != 0 && error == 0)
      error = errno;
    if (error == 0
        && ::renameat(folder_descriptor,
                      new_name.c_str(),
                      folder_descriptor,
                      manifest_name)
             != 0)
      error = errno;
    if (error != 0)
      {
        ::unlinkat(folder_descriptor, new_name.c_str(), 0);
        return failure(manifest_name, error);
      }
    manifest_descriptor
      = ::openat(folder_descriptor,
                 manifest_name,
                 O_WRONLY | O_APPEND | O_NOFOLLOW | O_NONBLOCK | O_CLOEXEC);
    if (manifest_descriptor < 0)
      return failure(manifest_name, errno);
    return own_regular_file(manifest_descriptor, manifest_name);
  }



  // A file the run writes into by name (the manifest, the time series)
  // must still be the run's: a regular file of this account with no other
  // name. Anything else has been put there meanwhile, and nothing is
  // written into it.
  std::string
  OutputFolder::own_regular_file(const int          descriptor,
                                 const std::string &name) const
  {
    struct stat status;
    if (::fstat(descriptor, &status) != 0)
      return failure(name, errno);
    if (S_ISREG(status.st_mode) && status.st_nlink == 1 && owned(status))
      return "";
    return "The file " + path(name)
           + " is not the one this run wrote (it has been replaced by "
           + (S_ISREG(status.st_mode) ? "a file with another name or owner"
                                      : "something that is not a file")
           + "); the run does not write into it. Make sure that nothing "
             "else writes into the Output directory.";
  }



  // Rank 0: one line, in one write() (appends of whole lines), each name
  // once.
  std::string
  OutputFolder::append_to_manifest(const std::string &kind,
                                   const std::string &name)
  {
    if (!listed.insert(name).second)
      return "";
    const std::string line = kind + " " + name + "\n";
    const int         error
      = write_all(manifest_descriptor, line.data(), line.size(), 0, false);
    if (error != 0)
      {
        listed.erase(name);
        return failure(manifest_name, error);
      }
    manifest_unsynced = true;
    return "";
  }



  // @sect4{OutputFolder::record_files, create_folder}
  void
  OutputFolder::record_files(const std::vector<std::string> &names)
  {
    if (!root)
      return;
    for (const std::string &name : names)
      if (problem.empty())
        problem = append_to_manifest("file", name);
  }



  // Collective: rank 0 lists and creates the folder (a folder that exists
  // already is fine if it is a folder and not a link), all ranks agree.
  void
  OutputFolder::create_folder(const std::string &name)
  {
    std::string message;
    if (root && listed.count(name) == 0)
      {
        message = append_to_manifest("folder", name);
        std::string leaf;
        const int   parent = open_parent(folder_descriptor, name, leaf);
        struct stat status;
        if (message.empty() && parent < 0)
          message = failure(name, errno);
        else if (message.empty() && ::mkdirat(parent, leaf.c_str(), 0755) != 0
                 && !(errno == EEXIST
                      && ::fstatat(parent,
                                   leaf.c_str(),
                                   &status,
                                   AT_SYMLINK_NOFOLLOW)
                           == 0
                      && S_ISDIR(status.st_mode)))
          message = failure(name, errno);
        if (parent >= 0 && parent != folder_descriptor)
          ::close(parent);
      }
    FileOutput::agree_on_problem(message, communicator);
  }



  // @sect4{OutputFolder::stage}
  //
  // The temporary is created exclusively in the run's folder of
  // temporaries, written, flushed to the disk and closed, each step
  // checked. A failure is remembered (the first one) and reported by
  // commit().
  void
  OutputFolder::stage(const std::string &name,
                      const std::string &content,
                      const Replace      replace)
  {
    if (!problem.empty())
      return;
    const std::string temporary = temporary_name(name);
    const int         descriptor
      = ::openat(temporary_descriptor,
                 temporary.c_str(),
                 O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC,
                 0644);
    if (descriptor < 0)
      {
        problem = failure(name, errno);
        return;
      }
    staged.push_back({temporary, name, replace});
    int error
      = FileOutput::simulate_failure(path(name))
          ? ENOSPC
          : write_all(descriptor, content.data(), content.size(), 0, false);
    if (error == 0 && ::fsync(descriptor) != 0)
      error = errno;
    if (::close(descriptor) != 0 && error == 0)
      error = errno;
    if (error != 0)
      problem = failure(name, error);
  }



  // @sect4{OutputFolder::stage_collectively}
  //
  // Rank 0 of the group creates the temporary and tells the others whether
  // it could; each rank with something to write opens it (never creating,
  // never following a link), writes its block at its offset (an exclusive
  // prefix sum of the block sizes, after the prefix), flushes and closes it.
  // The group then agrees on the first failure, so that every rank of the
  // group knows the file failed; the commit agrees over all ranks.
  void
  OutputFolder::stage_collectively(const std::string &name,
                                   const std::string &prefix,
                                   const char        *local_block,
                                   const std::size_t  local_size,
                                   const MPI_Comm     group,
                                   const Replace      replace)
  {
    stage_blocks(
      name,
      prefix,
      local_size,
      [&](const int descriptor, const std::uint64_t offset) {
        return write_all(descriptor, local_block, local_size, offset, true);
      },
      group,
      replace);
  }



  // The block piece by piece through one buffer of piece_size bytes: the
  // memory a checkpoint needs beyond the run's own data is that buffer.
  void
  OutputFolder::stage_collectively(const std::string &name,
                                   const std::string &prefix,
                                   const std::size_t  local_size,
                                   const std::size_t  piece_size,
                                   const BlockFiller &fill,
                                   const MPI_Comm     group,
                                   const Replace      replace)
  {
    Assert(piece_size > 0, ExcInternalError());
    stage_blocks(
      name,
      prefix,
      local_size,
      [&](const int descriptor, const std::uint64_t offset) {
        std::vector<char> buffer(std::min(local_size, piece_size));
        for (std::size_t begin = 0; begin < local_size; begin += piece_size)
          {
            const std::size_t size = std::min(piece_size, local_size - begin);
            fill(begin, size, buffer.data());
            const int error = write_all(descriptor,
                                        buffer.data(),
                                        size,
                                        offset + begin,
                                        true);
            if (error != 0)
              return error;
          }
        return 0;
      },
      group,
      replace);
  }



  void
  OutputFolder::stage_blocks(
    const std::string                            &name,
    const std::string                            &prefix,
    const std::size_t                             local_size,
    const std::function<int(int, std::uint64_t)> &write_block,
    const MPI_Comm                                group,
    const Replace                                 replace)
  {
    const unsigned int group_rank = Utilities::MPI::this_mpi_process(group);
    const unsigned int group_size = Utilities::MPI::n_mpi_processes(group);
    const std::string  temporary  = temporary_name(name);

    // Where this rank's block starts.
    std::uint64_t size   = local_size + (group_rank == 0 ? prefix.size() : 0);
    std::uint64_t offset = 0;
    const int     mpi_error
      = MPI_Exscan(&size, &offset, 1, MPI_UINT64_T, MPI_SUM, group);
    AssertThrowMPI(mpi_error);
    if (group_rank == 0)
      offset = prefix.size();

    // Rank 0 of the group creates the file and writes the prefix; the others
    // open it once they know it exists. A rank with nothing to write does
    // not open it at all.
    int error      = problem.empty() ? 0 : EIO;
    int descriptor = -1;
    if (group_rank == 0 && error == 0)
      {
        descriptor
          = ::openat(temporary_descriptor,
                     temporary.c_str(),
                     O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC,
                     0644);
        if (descriptor < 0)
          error = errno;
        else
          {
            staged.push_back({temporary, name, replace});
            error
              = write_all(descriptor, prefix.data(), prefix.size(), 0, true);
          }
      }
    int created = (group_rank == 0 && descriptor >= 0) ? 1 : 0;
    MPI_Bcast(&created, 1, MPI_INT, 0, group);
    if (!created && error == 0)
      error = EIO;
    if (group_rank > 0 && error == 0 && local_size > 0)
      {
        descriptor = ::openat(temporary_descriptor,
                              temporary.c_str(),
                              O_WRONLY | O_NOFOLLOW | O_CLOEXEC);
        if (descriptor < 0)
          error = errno;
      }
    if (descriptor >= 0)
      {
        // The test switch: the last rank of the group fails as on a full
        // disk (the case where one rank alone sees the error).
        if (error == 0 && FileOutput::simulate_failure(path(name))
            && group_rank + 1 == group_size)
          error = ENOSPC;
        if (error == 0)
          error = write_block(descriptor, offset);
        if (error == 0 && ::fsync(descriptor) != 0)
          error = errno;
        if (::close(descriptor) != 0 && error == 0)
          error = errno;
      }
    // The group's first failure, with its reason, on every rank of the
    // group (a rank that failed earlier keeps its own message).
    const unsigned int first
      = Utilities::MPI::min(error != 0 ? group_rank : group_size, group);
    if (first < group_size)
      {
        int reason = error;
        MPI_Bcast(&reason, 1, MPI_INT, first, group);
        if (problem.empty())
          problem = failure(name, reason);
      }
  }



  // @sect4{OutputFolder::commit}
  //
  // First every rank's outcome (and rank 0's flush of the manifest, which
  // must list a file before it appears under its name) is agreed on. Then
  // each rank renames the temporaries it created: without replacing
  // anything, unless the file is one the run rewrites. Where the file system
  // cannot rename without replacing (RENAME_NOREPLACE is refused with
  // EINVAL, as on NFS), a hard link to the new name (which fails if the name
  // exists) and the removal of the temporary do the same.
  void
  OutputFolder::commit(const bool durable)
  {
    if (root && manifest_unsynced && problem.empty())
      {
        if (::fsync(manifest_descriptor) != 0)
          problem = failure(manifest_name, errno);
        manifest_unsynced = false;
      }
    std::string message = problem;
    try
      {
        FileOutput::agree_on_problem(message, communicator);
      }
    catch (...)
      {
        for (const StagedFile &file : staged)
          ::unlinkat(temporary_descriptor, file.temporary.c_str(), 0);
        staged.clear();
        problem.clear();
        throw;
      }

    std::set<int> touched_folders;
    for (const StagedFile &file : staged)
      {
        if (!message.empty())
          {
            ::unlinkat(temporary_descriptor, file.temporary.c_str(), 0);
            continue;
          }
        std::string leaf;
        const int   parent = open_parent(folder_descriptor, file.name, leaf);
        int         error  = parent < 0 ? errno : 0;
        if (error == 0 && file.replace == Replace::own)
          {
            if (::renameat(temporary_descriptor,
                           file.temporary.c_str(),
                           parent,
                           leaf.c_str())
                != 0)
              error = errno;
          }
        else if (error == 0)
          {
            if (::renameat2(temporary_descriptor,
                            file.temporary.c_str(),
                            parent,
                            leaf.c_str(),
                            RENAME_NOREPLACE)
                != 0)
              {
                error = errno;
                if (error == EINVAL || error == ENOSYS || error == EOPNOTSUPP)
                  {
                    error = 0;
                    if (::linkat(temporary_descriptor,
                                 file.temporary.c_str(),
                                 parent,
                                 leaf.c_str(),
                                 0)
                        != 0)
                      error = errno;
                    else
                      ::unlinkat(temporary_descriptor,
                                 file.temporary.c_str(),
                                 0);
                  }
              }
          }
        if (error == EEXIST)
          message = "The file " + path(file.name)
                    + " is in the way: it exists, and this run did not write "
                      "it, so it is not replaced; move it away, or choose "
                      "another Output directory.";
        else if (error != 0)
          message = failure(file.name, error);
        if (error != 0)
          ::unlinkat(temporary_descriptor, file.temporary.c_str(), 0);
        if (durable && error == 0 && parent >= 0 && ::fsync(parent) != 0)
          message = failure(file.name, errno);
        if (parent >= 0 && parent != folder_descriptor)
          ::close(parent);
      }
    staged.clear();
    problem.clear();
    FileOutput::agree_on_problem(message, communicator);
  }



  // @sect4{OutputFolder::append}
  //
  // The time series grows by a row per step (rewriting it would cost
  // O(steps^2)). A failed append is cut back, so the file always ends with a
  // complete row.
  std::string
  OutputFolder::append(const std::string &name, const std::string &text)
  {
    const int descriptor = ::openat(folder_descriptor,
                                    name.c_str(),
                                    O_WRONLY | O_APPEND | O_CREAT | O_NOFOLLOW
                                      | O_NONBLOCK | O_CLOEXEC,
                                    0644);
    if (descriptor < 0)
      return failure(name, errno);
    const std::string problem = own_regular_file(descriptor, name);
    if (!problem.empty())
      {
        ::close(descriptor);
        return problem;
      }
    struct stat status;
    const off_t old_size
      = (::fstat(descriptor, &status) == 0 ? status.st_size : -1);
    int error = FileOutput::simulate_failure(path(name))
                  ? ENOSPC
                  : write_all(descriptor, text.data(), text.size(), 0, false);
    if (error != 0 && old_size >= 0)
      (void)!::ftruncate(descriptor, old_size);
    if (::close(descriptor) != 0 && error == 0)
      error = errno;
    return error == 0 ? "" : failure(name, error);
  }



  void
  OutputFolder::remove(const std::string &name)
  {
    if (!root || listed.count(name) == 0)
      return;
    std::string leaf;
    const int   parent = open_parent(folder_descriptor, name, leaf);
    if (parent < 0)
      return;
    struct stat status;
    if (::fstatat(parent, leaf.c_str(), &status, AT_SYMLINK_NOFOLLOW) == 0
        && S_ISREG(status.st_mode) && owned(status))
      ::unlinkat(parent, leaf.c_str(), 0);
    if (parent != folder_descriptor)
      ::close(parent);
  }



  bool
  OutputFolder::is_parameter_file(const std::string &name) const
  {
    struct stat parameters, status;
    return !parameter_file.empty()
           && ::stat(parameter_file.c_str(), &parameters) == 0
           && folder_descriptor >= 0
           && status_of(folder_descriptor, name, status)
           && status.st_dev == parameters.st_dev
           && status.st_ino == parameters.st_ino;
  }
} // namespace ViscoContact
