#ifndef viscoplastic_contact_checkpoint_h
#define viscoplastic_contact_checkpoint_h

#include <deal.II/base/mpi.h>


#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace ViscoContact
{
  using namespace dealii;

  // @sect3{Checkpoints}
  //
  // A checkpoint of step n is one binary file per MPI rank,
  //   <Output directory>/checkpoint/step_NNNNNN.rank_RRRR.bin,
  // and the text file checkpoint/checkpoint.info that names the last
  // complete one. Every file is written under a temporary name and renamed
  // when it is complete; checkpoint.info is renamed only after all ranks
  // have renamed their files, and the files of the previous checkpoint are
  // deleted only after that. A run killed at any moment therefore leaves a
  // checkpoint.info that names complete files.
  //
  // The solvers decide what goes into their files (CheckpointWriter and
  // CheckpointReader are plain binary streams with error checks); the data
  // are keyed by what does not depend on the partition (cell ids, node
  // locations), never by a rank-local index alone.
  class CheckpointWriter
  {
  public:
    explicit CheckpointWriter(const std::filesystem::path &file);

    template <typename T>
    void
    write(const T &value)
    {
      static_assert(std::is_trivially_copyable<T>::value,
                    "only plain data can be written directly");
      out.write(reinterpret_cast<const char *>(&value), sizeof(T));
    }
    template <typename T>
    void
    write_vector(const std::vector<T> &values)
    {
      static_assert(std::is_trivially_copyable<T>::value,
                    "only plain data can be written directly");
      write<std::uint64_t>(values.size());
      out.write(reinterpret_cast<const char *>(values.data()),
                sizeof(T) * values.size());
    }
    void
    write_string(const std::string &text);

    // Flush, check and rename to the final name.
    void
    finish();

  private:
    std::filesystem::path file, temporary;
    std::ofstream         out;
  };

  class CheckpointReader
  {
  public:
    explicit CheckpointReader(const std::filesystem::path &file);

    template <typename T>
    T
    read()
    {
      T value;
      in.read(reinterpret_cast<char *>(&value), sizeof(T));
      check();
      return value;
    }
    template <typename T>
    std::vector<T>
    read_vector()
    {
      const std::uint64_t n = read<std::uint64_t>();
      check_size(n * sizeof(T));
      std::vector<T> values(n);
      in.read(reinterpret_cast<char *>(values.data()), sizeof(T) * n);
      check();
      return values;
    }
    std::string
    read_string();

    const std::filesystem::path &
    name() const;

  private:
    void
    check();
    void
    check_size(const std::uint64_t bytes);

    std::filesystem::path file;
    std::ifstream         in;
    std::uint64_t         file_size;
  };

  // What every checkpoint file starts with: the layout version, the space
  // dimension, the step, the time schedule (cut steps included), and the
  // wall and compute time of the time loop so far.
  struct CheckpointHeader
  {
    std::uint32_t       version   = 0;
    std::uint32_t       dimension = 0;
    std::uint32_t       step      = 0;
    std::vector<double> times;
    double              wall_time    = 0;
    double              compute_time = 0;

    void
    write(CheckpointWriter &out) const;
    // Reads a header and checks it against what the reader expects.
    void
    read(CheckpointReader   &in,
         const std::uint32_t expected_version,
         const std::uint32_t expected_dimension,
         const std::uint32_t expected_step);
  };

  // The .pvd record: (time, file name) per output step.
  void
  write_output_records(
    CheckpointWriter                                  &out,
    const std::vector<std::pair<double, std::string>> &records);
  std::vector<std::pair<double, std::string>>
  read_output_records(CheckpointReader &in);

  // A consistency check of a file being read: throws, naming the file, if
  // the condition is false.
  void
  check_checkpoint_content(const bool condition, const CheckpointReader &in);

  // What checkpoint.info records: the step, its time, the number of ranks
  // that wrote the files, and the size of the problem (a resumed run checks
  // it against its own).
  struct CheckpointRecord
  {
    unsigned int  step    = 0;
    double        time    = 0;
    unsigned int  n_ranks = 1;
    std::uint64_t n_dofs  = 0;
  };

  std::filesystem::path
  checkpoint_directory(const std::string &output_directory);
  std::filesystem::path
  checkpoint_file(const std::string &output_directory,
                  const unsigned int step,
                  const unsigned int rank);

  // Collective. Called by every rank after it has finished its own file:
  // rank 0 publishes the record, then every rank removes its file of the
  // previous checkpoint (previous_step, if not numbers::invalid_unsigned_int).
  void
  publish_checkpoint(const std::string      &output_directory,
                     const CheckpointRecord &record,
                     const unsigned int      previous_step,
                     const MPI_Comm          communicator);

  // The last complete checkpoint; throws with a message that names the
  // Resume entry if there is none or it was written by another number of
  // ranks or for another problem size.
  CheckpointRecord
  read_checkpoint_record(const std::string  &output_directory,
                         const unsigned int  n_ranks,
                         const std::uint64_t n_dofs);

  // Keep the header and the rows of steps <= step of time_series.csv (the
  // rows of a resumed run's later steps are written again).
  void
  truncate_time_series(const std::filesystem::path &file,
                       const unsigned int           step);

} // namespace ViscoContact

#endif
