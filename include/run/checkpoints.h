#ifndef viscoplastic_contact_checkpoints_h
#define viscoplastic_contact_checkpoints_h

#include <deal.II/base/numbers.h>

#include "back_ends/linear_algebra.h"
#include "robustness/checkpoint_file.h"

#include <array>
#include <cstddef>
#include <functional>
#include <string>
#include <utility>
#include <vector>

namespace ViscoContact
{
  using namespace dealii;

  template <int dim>
  class ViscoplasticContact;

  // @sect3{The checkpoints of a run}
  //
  // What a checkpoint stores of a ViscoplasticContact (the problem) and how
  // a resumed run restores it; the file format, its safety and the record
  // of the last checkpoint are robustness/checkpoint_file.h. One file per
  // checkpoint, one record per cell keyed by the cell's id, so that a run can
  // be resumed on any number of ranks; the header holds the schedule, the
  // counters and the .pvd list.
  //
  // The object reads every part of the problem's state that a resumed run
  // needs (the displacement, the contact nodes, the stress points, the start
  // of the step, the schedule and the report), and sets them when it
  // resumes: it is the problem's friend, as StepCycles is. It keeps only the
  // step of the last checkpoint written or resumed from.
  template <int dim>
  class Checkpoints
  {
  public:
    // Collective: the checkpoint of the problem's current step. The file is
    // complete on the disk before it is published, and only then is the
    // previous checkpoint removed.
    void
    write(ViscoplasticContact<dim> &problem, const double wall_time);
    // Collective: the problem (set up on the mesh of the parameter file)
    // restored from the last checkpoint of its output folder, on any number
    // of ranks; a damaged file or one of another scene is refused before
    // anything is written.
    void
    resume(ViscoplasticContact<dim> &problem);
    // A scheduler's signal received on any rank: all ranks stop after the
    // problem's current step, with a checkpoint of it (unless one was just
    // written).
    void
    stop_if_signalled(ViscoplasticContact<dim> &problem,
                      const bool                checkpoint_written,
                      const double              wall_time);

  private:
    struct Flags
    {
      bool has_step_start;
    };
    // The values a checkpoint stores at the dofs of every cell besides u
    // (restored into the problem's solution): the contact state, the start
    // of the step, the nodes' history and their friction state, the
    // variables of the laws with a history (a memory term, adhesion:
    // ContactHistory::nodal_fields(), one after the other), with slip
    // weakening the weakening variable.
    struct CellVectors
    {
      VectorType              contact_state;
      VectorType              start_displacement;
      VectorType              node_history;
      VectorType              friction_state;
      std::vector<VectorType> histories;
      // With slip weakening: the weakening variable at a node's x-dof.
      std::vector<VectorType> weakening_state;
    };

    // The bytes of a cell's record: the cell id, the values of the vectors
    // at the cell's dofs, its stress-point records.
    static std::size_t
    record_size(const ViscoplasticContact<dim> &problem);
    // The header (the same on every rank; rank 0's is written), the vectors
    // the records hold besides u, with their ghost values, and the records
    // of the problem's owned cells [first, end).
    static ByteWriter
    make_header(const ViscoplasticContact<dim> &problem,
                const double                    wall_time);
    static CellVectors
    cell_vectors(const ViscoplasticContact<dim> &problem);
    static void
    write_cell_records(const ViscoplasticContact<dim> &problem,
                       const CellVectors              &vectors,
                       const std::size_t               first,
                       const std::size_t               end,
                       char                           *out);
    // The vectors of a record: u, then those of CellVectors.
    static unsigned int
    n_record_vectors(const ViscoplasticContact<dim> &problem);
    static unsigned int
    n_weakening_fields(const ViscoplasticContact<dim> &problem);
    // The nodal fields of the laws with a history.
    static unsigned int
    n_history_fields(const ViscoplasticContact<dim> &problem);

    // The mesh of the checkpoint (of an adaptive run, or of one with initial
    // cycles) rebuilt from the mesh of the parameter file, and the problem
    // set up on it.
    static void
    restore_mesh(ViscoplasticContact<dim> &problem);
    static Flags
    read_header(ViscoplasticContact<dim> &problem,
                ByteReader               &header,
                const unsigned int        step);
    // The schedule after the checkpoint for this run's End time; returns the
    // next step's length before and after.
    static std::pair<double, double>
    continue_schedule(ViscoplasticContact<dim> &problem);
    // The records of this rank's share of the file sent to the owners of
    // their cells and restored on the owned dofs and stress points, after
    // check_header() has read the header; false on a rank that did not find
    // all its cells.
    static bool
    restore_cell_records(ViscoplasticContact<dim>    &problem,
                         const std::string           &file,
                         std::vector<char>           &header,
                         CellVectors                 &vectors,
                         const std::function<void()> &check_header);
    static void
    restore_contact_nodes(ViscoplasticContact<dim> &problem,
                          const CellVectors        &vectors,
                          const ByteReader         &header);
    static void
    restore_prediction_start(ViscoplasticContact<dim> &problem,
                             const CellVectors        &vectors,
                             const Flags              &flags);

    unsigned int last_step_written = numbers::invalid_unsigned_int;
  };
} // namespace ViscoContact

#endif
