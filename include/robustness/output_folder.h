#ifndef viscoplastic_contact_output_folder_h
#define viscoplastic_contact_output_folder_h

#include <deal.II/base/mpi.h>

#include <cstdint>
#include <functional>
#include <set>
#include <string>
#include <vector>

namespace ViscoContact
{
  using namespace dealii;

  // @sect3{The output folder}
  //
  // Everything a run writes goes into its Output directory through this
  // class, which keeps four promises (doc/robustness.md, "Output folders"):
  //
  //  - The program deletes only what it wrote. Every file and folder is
  //    listed in the folder's manifest (.viscoplastic_contact.manifest)
  //    before it is created. Overwrite = true removes exactly what the
  //    manifest lists, never by name pattern, never a folder the program did
  //    not create, never the parameter file being run. A file with a name
  //    the program writes but no manifest entry is in the way: the run is
  //    refused with the list.
  //  - What the program reads back is untrusted: the manifest (and the
  //    checkpoint's files and the time series of a resumed run) is read
  //    only as a regular file of this account of bounded size, never a
  //    link or a named pipe, and a manifest line that names anything but
  //    the program's own plain names (a '/' only below checkpoint/ and
  //    runs/, no "..", no absolute path, not the lock or the manifest) makes
  //    the folder refused. Removals go through the folder's descriptor,
  //    follow no link, and touch only regular files and folders of this
  //    account; the folder of temporaries is emptied through its own
  //    descriptor, and removed by name only while the name is still it.
  //  - Files are created, not followed. A file is written into a private
  //    folder of temporaries that the run creates (mode 0700, a random name;
  //    no other account can put anything into it), created there exclusively
  //    (O_CREAT | O_EXCL | O_NOFOLLOW), and renamed into place only when it
  //    is complete. Every path is opened relative to a descriptor of its
  //    folder, so no symbolic link planted in the output folder is followed,
  //    and the rename never replaces a file that is not the run's
  //    (RENAME_NOREPLACE).
  //  - One run per folder: rank 0 holds an advisory lock (flock) on
  //    .viscoplastic_contact.lock for the whole run; a second run into the
  //    folder is refused at once, naming the process that holds it (one
  //    printable line of the lock file). A lock file that is not a regular
  //    file of this account with one name is refused, not written.
  //  - Writes are verified, not trusted: a file counts as written only when
  //    every rank's own write (every byte counted), fsync and close
  //    succeeded. The files all ranks write together (the .vtu pieces, the
  //    contact profiles, the checkpoints) are written with plain POSIX
  //    writes at offsets from a prefix sum, not with MPI I/O: no MPI-I/O
  //    component with fixed-size path buffers, no error noise from it, and
  //    short writes are seen.
  //
  // Writes are staged and committed: stage() and stage_collectively() write
  // temporaries; commit() (collective) agrees on the outcome of all ranks and
  // then renames every staged file into place, or, if any rank failed,
  // removes every temporary and touches no final name.
  class OutputFolder
  {
  public:
    enum class Mode
    {
      new_run,   // the folder must hold no earlier run's files
      overwrite, // an earlier run's files (by its manifest) are removed
      resume     // the folder holds the run that is continued
    };

    // Whether a commit may replace an existing file: never (the name is new
    // to this run: a file under it is not the run's and stays), or own (the
    // file is one the run rewrites: solution.pvd, checkpoint.info, ...).
    enum class Replace
    {
      never,
      own
    };

    // Collective. Looks at the folder without changing what is in it: if it
    // exists, rank 0 takes its lock and checks its entries against the mode
    // (a used folder, foreign files in the way, a folder in use by another
    // run, the parameter file among the files Overwrite would remove). Every
    // rank throws the same message if the folder is refused.
    OutputFolder(const std::string &directory,
                 const Mode         mode,
                 const std::string &parameter_file,
                 const MPI_Comm     communicator);

    // Removes the folder of temporaries and the lock file (rank 0).
    ~OutputFolder();

    OutputFolder(const OutputFolder &) = delete;
    OutputFolder &
    operator=(const OutputFolder &)
      = delete;

    // Collective; once the set-up of the run has succeeded. Creates the
    // folder if need be (and locks it), checks it again, removes what the
    // mode asks for (Overwrite: everything the manifest lists; Resume: the
    // files of the steps after resume_step, which the run writes again),
    // and creates the folder of temporaries.
    void
    prepare(const unsigned int resume_step = 0);

    // The folder's path, and the path of a name in it (for messages and for
    // reading).
    const std::string &
    directory() const;
    MPI_Comm
    get_communicator() const;
    std::string
    path(const std::string &name) const;

    // Collective in effect, rank 0 acts: names (relative to the folder, such
    // as "checkpoint/step_000010.bin") that the run is about to create go
    // into the manifest, each once. Folders are created (on rank 0) as
    // they are recorded.
    void
    record_files(const std::vector<std::string> &names);
    void
    create_folder(const std::string &name);

    // Not collective: this rank writes a whole file to a temporary.
    void
    stage(const std::string &name,
          const std::string &content,
          const Replace      replace = Replace::never);

    // Collective over group (the folder's communicator or a part of it):
    // the blocks of the ranks of group in rank order, rank 0 of the group
    // first writing the prefix.
    void
    stage_collectively(const std::string &name,
                       const std::string &prefix,
                       const char        *local_block,
                       const std::size_t  local_size,
                       const MPI_Comm     group,
                       const Replace      replace = Replace::never);

    // The same for a block too large to hold in memory twice: it is made
    // and written piece by piece, fill(begin, size, buffer) putting bytes
    // [begin, begin + size) of this rank's block into buffer, pieces of at
    // most piece_size bytes.
    using BlockFiller
      = std::function<void(std::size_t begin, std::size_t size, char *buffer)>;
    void
    stage_collectively(const std::string &name,
                       const std::string &prefix,
                       const std::size_t  local_size,
                       const std::size_t  piece_size,
                       const BlockFiller &fill,
                       const MPI_Comm     group,
                       const Replace      replace = Replace::never);

    // Collective: every staged file into place, or none (all ranks throw the
    // message of the first failure, naming the file and the system's
    // reason). With durable = true the renames reach the disk (fsync of the
    // folders) before commit() returns.
    void
    commit(const bool durable = false);

    // Rank 0 alone: appends text to a file of the run (created if missing),
    // cutting a failed append back. Returns an empty string or the message.
    std::string
    append(const std::string &name, const std::string &text);

    // Rank 0 alone: removes a file of the run (one the manifest lists); a
    // failure leaves it and is not an error.
    void
    remove(const std::string &name);

    // Not collective: what the destructors of all folders would do, for
    // main() before it ends the ranks with MPI_Abort() (which runs no
    // destructors): the temporaries and the lock file of this rank go.
    static void
    release_all();

    // Whether the parameter file being run is this name in the folder (then
    // the run does not replace it with its listing).
    bool
    is_parameter_file(const std::string &name) const;

    // The names of the manifest, and the file names of the program, for the
    // tests and the messages.
    static const char *manifest_name;
    static const char *lock_name;

  private:
    struct StagedFile
    {
      std::string temporary; // in the folder of temporaries
      std::string name;      // relative to the output folder
      Replace     replace;
    };

    // Rank 0: opens, locks and checks the folder; an empty string or the
    // message.
    std::string
    open_and_check(const bool create);
    std::string
    lock();
    void
    unlock();
    std::string
    check_entries() const;
    std::string
    remove_earlier_run(const unsigned int resume_step);
    std::string
    start_manifest();
    std::string
    append_to_manifest(const std::string &kind, const std::string &name);
    std::string
    failure(const std::string &name, const int error_number) const;
    // An empty string if the file open at descriptor is a regular file of
    // this account with one name, else the message.
    std::string
    own_regular_file(const int descriptor, const std::string &name) const;
    // What both stage_collectively() share: write_block(descriptor, offset)
    // writes this rank's local_size bytes at offset, returning 0 or the
    // errno.
    void
    stage_blocks(const std::string                            &name,
                 const std::string                            &prefix,
                 const std::size_t                             local_size,
                 const std::function<int(int, std::uint64_t)> &write_block,
                 const MPI_Comm                                group,
                 const Replace                                 replace);
    void
    release();

    std::string             folder;
    Mode                    mode;
    std::string             parameter_file;
    MPI_Comm                communicator;
    bool                    root;
    int                     folder_descriptor    = -1;
    int                     lock_descriptor      = -1;
    int                     temporary_descriptor = -1;
    int                     manifest_descriptor  = -1;
    bool                    manifest_unsynced    = false;
    std::string             temporary_folder; // name in the folder
    std::set<std::string>   listed;           // rank 0: the manifest's names
    std::vector<StagedFile> staged;  // the temporaries this rank created
    std::string             problem; // this rank's first failure
    unsigned int            n_staged = 0;
  };
} // namespace ViscoContact

#endif
