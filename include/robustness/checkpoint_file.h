#ifndef viscoplastic_contact_robustness_checkpoint_file_h
#define viscoplastic_contact_robustness_checkpoint_file_h

#include <deal.II/base/mpi.h>

#include "robustness/output_folder.h"

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <functional>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace ViscoContact
{
  using namespace dealii;

  // @sect3{Checkpoint files}
  //
  // A checkpoint of step n is one file,
  //   <Output directory>/checkpoint/step_NNNNNN.bin,
  // written by all ranks together (OutputFolder::stage_collectively()),
  // and the text file
  // checkpoint/checkpoint.info that names the last complete one. The file
  // holds a header (the same for all ranks) and one fixed-size record per
  // cell of the mesh, keyed by the cell's id: its displacement values, its
  // contact state and its stress points. Cell ids do not depend on the
  // partition, so a checkpoint written on one number of ranks is read on
  // any other: each rank reads an equal share of the records and
  // MPITools::exchange_records() delivers every record to the rank that
  // now owns the cell.
  //
  // The file is staged as a temporary and renamed when complete;
  // checkpoint.info is renamed only after that, and the file of the
  // previous checkpoint is deleted only after that. A run killed at any
  // moment therefore leaves a checkpoint.info that names a complete file.
  //
  // Why records per cell, and not per dof or per rank: dof numbers and the
  // assignment of cells to ranks change with the number of ranks, cell ids do
  // not, and every piece of the state (u at the cell's dofs, the contact state
  // at its vertices, the stress points) belongs to a cell. The mesh itself is
  // not stored; it is rebuilt from the parameter file (see
  // Checkpoints::write()). Every rank's work and memory stay proportional to
  // its share of the cells, on writing and on reading.

  // The version of the file layout, the first value of every header: a
  // resumed run refuses a checkpoint of another version rather than misread
  // it. Bumped whenever the layout of the files changes, or the meaning of a
  // cell id (7: the coarse cells numbered in p4est's order, see mesh.cc; 8:
  // the memory's and the slip weakening's fields and their layout in the
  // header; 9: the bonding of adhesion and the worn depths, each
  // history's layout; 10: the openings a cohesive interface has reached).
  constexpr std::uint32_t checkpoint_version = 10;

  // The header's bytes, built and read in memory. Only trivially copyable
  // values are written, byte for byte in the machine's representation (vectors
  // and strings with their length first), so a checkpoint is meant to be read
  // by the same program on the same kind of machine; the version number and the
  // checks of the reader catch files of another layout.
  class ByteWriter
  {
  public:
    template <typename T>
    void
    write(const T &value)
    {
      static_assert(std::is_trivially_copyable<T>::value,
                    "only plain data can be written directly");
      const char *begin = reinterpret_cast<const char *>(&value);
      bytes.insert(bytes.end(), begin, begin + sizeof(T));
    }
    template <typename T>
    void
    write_vector(const std::vector<T> &values)
    {
      write<std::uint64_t>(values.size());
      for (const T &value : values)
        write(value);
    }
    void
    write_string(const std::string &text)
    {
      write_vector(std::vector<char>(text.begin(), text.end()));
    }

    std::vector<char> bytes;
  };

  // Reads what a ByteWriter wrote, value by value in the same order. Every read
  // first checks that the bytes are there, so a short or damaged header throws
  // with the file's name instead of reading past the end.
  class ByteReader
  {
  public:
    // file: for the messages.
    ByteReader(const std::vector<char> &bytes, const std::string &file);

    template <typename T>
    T
    read()
    {
      static_assert(std::is_trivially_copyable<T>::value,
                    "only plain data can be read directly");
      check_available(sizeof(T));
      T value;
      std::memcpy(&value, bytes.data() + position, sizeof(T));
      position += sizeof(T);
      return value;
    }
    template <typename T>
    std::vector<T>
    read_vector()
    {
      const std::uint64_t n = read<std::uint64_t>();
      check_available(n * sizeof(T));
      std::vector<T> values(n);
      for (T &value : values)
        value = read<T>();
      return values;
    }
    std::string
    read_string();

    // Throws, naming the file, if the condition is false.
    void
    check(const bool condition) const;

  private:
    void
    check_available(const std::uint64_t n_bytes) const;

    const std::vector<char> &bytes;
    const std::string        file;
    std::size_t              position = 0;
  };

  // What checkpoint.info records: the step, its time, the number of ranks
  // that wrote the file (for information), and the size of the problem (a
  // resumed run checks it against its own).
  struct CheckpointRecord
  {
    unsigned int  step    = 0;
    double        time    = 0;
    unsigned int  n_ranks = 1;
    std::uint64_t n_dofs  = 0;
    // The entries that change the result, as "Subsection/Entry = value"
    // (Parameters::AllParameters::result_entries): a resumed run must have
    // the same ones.
    std::vector<std::string> entries;
  };

  // The checkpoint folder, its record and the file of a step, relative to
  // the output folder.
  extern const char *const checkpoint_folder;
  extern const char *const checkpoint_info;
  std::string
  checkpoint_name(const unsigned int step);

  // Collective. A file of the header (rank 0's) followed by the records of
  // all ranks in rank order, each record_size bytes, staged in the output
  // folder (committed by the caller). fill_records(first, end, out) puts
  // this rank's records [first, end) into out; they are made and written a
  // piece of at most about 64 MB at a time, so that a checkpoint needs
  // little memory beyond the run's own (a copy of all records would be
  // 0.7 kB per dof on hexahedra).
  using RecordFiller
    = std::function<void(std::size_t first, std::size_t end, char *out)>;
  void
  write_record_file(OutputFolder            &folder,
                    const std::string       &name,
                    const std::vector<char> &header,
                    const std::size_t        n_local_records,
                    const std::uint64_t      record_size,
                    const RecordFiller      &fill_records,
                    const MPI_Comm           communicator);

  // Collective. The header, and an equal share of the records for each
  // rank (whatever the number of ranks that wrote them), handed to
  // use_records(records) a piece of whole records of at most about 64 MB at
  // a time. Every rank calls use_records equally often (with an empty piece
  // once its share is used up), so that use_records may be collective.
  // check_header() runs once the header is read, before the first piece.
  using RecordUser = std::function<void(const std::vector<char> &records)>;
  void
  read_record_file(const std::string           &file,
                   std::vector<char>           &header,
                   const std::uint64_t          record_size,
                   const RecordUser            &use_records,
                   const MPI_Comm               communicator,
                   const std::function<void()> &check_header = {});

  // Collective. After the checkpoint file is complete: rank 0 publishes
  // the record and removes the file of the previous checkpoint
  // (previous_step, if not numbers::invalid_unsigned_int).
  void
  publish_checkpoint(OutputFolder           &folder,
                     const CheckpointRecord &record,
                     const unsigned int      previous_step);

  // The last complete checkpoint; throws with a message that names the
  // Resume entry if there is none or it was written for another problem
  // size (n_dofs = 0: not checked).
  // The entries of the run that resumes must be those of the record.
  CheckpointRecord
  read_checkpoint_record(const std::string              &output_directory,
                         const std::uint64_t             n_dofs,
                         const std::vector<std::string> &entries);

  // Collective, after the folder is prepared: time_series.csv keeps its
  // header and the rows of steps <= step (the rows of a resumed run's later
  // steps are written again). A series that was deleted gets its header
  // back (header is the header line), with a warning that the rows up to
  // the checkpoint are lost.
  void
  truncate_time_series(OutputFolder      &folder,
                       const std::string &header,
                       const unsigned int step);
} // namespace ViscoContact

#endif
