// The checkpoints of ViscoplasticContact<dim>: what a checkpoint stores per
// cell and in its header, and how a resumed run restores it (the file format
// is robustness/checkpoint_file.h).

#include <deal.II/base/exceptions.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/utilities.h>

#include <deal.II/distributed/tria.h>

#include <deal.II/grid/cell_id.h>

#include "robustness/checkpoint_file.h"
#include "robustness/mpi_tools.h"
#include "robustness/stop_signals.h"
#include "run/checkpoints.h"
#include "viscoplastic_contact.h"

#include <array>
#include <cstring>
#include <set>
#include <unordered_map>

namespace ViscoContact
{
  // @sect4{Checkpoints::record_size}
  //
  // The vectors of write() at the cell's dofs (u, the contact state,
  // u_{n-1}, the nodes' history, their friction state, with a memory term
  // its history), then the stress points;
  // QuadraturePointHistory holds only doubles, so the payload after the key
  // is a whole number of doubles.
  template <int dim>
  std::size_t
  Checkpoints<dim>::record_size(const ViscoplasticContact<dim> &problem)
  {
    static_assert(sizeof(QuadraturePointHistory<dim>) % sizeof(double) == 0);
    return sizeof(CellId::binary_type)
           + n_record_vectors(problem)
               * problem.discretisation.fe.max_dofs_per_cell() * sizeof(double)
           + problem.discretisation.n_stress_points()
               * sizeof(QuadraturePointHistory<dim>);
  }



  // One field of weakening variables (accumulated slips or slip rates)
  // where a zone's friction weakens; the memory's variables per node (0
  // without memory).
  template <int dim>
  unsigned int
  Checkpoints<dim>::n_weakening_fields(const ViscoplasticContact<dim> &problem)
  {
    return problem.contact_set.has_slip_weakening() ? 1 : 0;
  }



  template <int dim>
  unsigned int
  Checkpoints<dim>::n_history_fields(const ViscoplasticContact<dim> &problem)
  {
    unsigned int n = 0;
    for (const ContactHistory *history : problem.contact_histories.all())
      n += history->n_nodal_fields(dim);
    return n;
  }



  template <int dim>
  unsigned int
  Checkpoints<dim>::n_record_vectors(const ViscoplasticContact<dim> &problem)
  {
    return 5 + n_history_fields(problem) + n_weakening_fields(problem);
  }



  // @sect4{Checkpoints::write}
  //
  // The mesh is not stored: it is rebuilt from the parameter file, which
  // makes it the same mesh with the same cell ids (deal.II 9.4 cannot
  // reliably save and load fully distributed meshes on several ranks).
  // Stored are, in the header, the time schedule (cut steps included), the
  // counters and the .pvd record; per locally owned cell, keyed by its id:
  // the displacement values at the cell's dofs, the contact state at the
  // cell's dofs (the piece + 1 at the x-dof of a contact node, its force z
  // at the y-dof, zero elsewhere: the warm start of the next active set, so
  // that its iterations are those of the uninterrupted run), the start of
  // step n (u_{n-1}, and z_{n-1} at the x-dof of a contact node: what the
  // predicted start of the next step extrapolates from; zero if there is
  // none), the friction state of a contact node (its stick/slip state at
  // the x-dof, its tangential force t at the other dofs; zero without
  // friction), with a memory term or adhesion the history variables at the
  // dofs of a contact node (ContactHistory::nodal_fields()), with slip
  // weakening each
  // node's weakening variable at its x-dof, and the state of every
  // stress point (sigma_n, the history of the next step, the plastic
  // multiplier).
  //
  // Storing values per cell means that a dof shared by several cells is stored
  // several times. In exchange, everything a cell needs travels with the cell's
  // id, and no global dof numbering, which changes with the number of ranks,
  // appears in the file. The contact state is stored the same way, as values at
  // the dofs of a contact node's vertex, for the same reason: the contact nodes
  // are numbered rank by rank, and their numbers mean nothing on another
  // partition.
  template <int dim>
  void
  Checkpoints<dim>::write(ViscoplasticContact<dim> &problem,
                          const double              wall_time)
  {
    const unsigned int step = problem.schedule.step_number();
    TimerOutput::Scope t(problem.report.timer(), "Checkpoint");
    // The folder and the two files go into the manifest before they exist.
    problem.output.folder().create_folder(checkpoint_folder);
    problem.output.folder().record_files(
      {checkpoint_name(step), checkpoint_info});

    const ByteWriter  header  = make_header(problem, wall_time);
    const CellVectors vectors = cell_vectors(problem);

    // Collective: the file is complete (written and renamed, the rename on
    // the disk) before the record of the checkpoint is published, and only
    // then is the previous checkpoint's file removed. The records are made
    // as they are written, a piece at a time.
    write_record_file(
      problem.output.folder(),
      checkpoint_name(step),
      header.bytes,
      problem.stress_points.cells().size(),
      record_size(problem),
      [&](const std::size_t first, const std::size_t end, char *out) {
        write_cell_records(problem, vectors, first, end, out);
      },
      problem.mpi_communicator);
    problem.output.folder().commit(/*durable=*/true);

    CheckpointRecord record;
    record.step    = step;
    record.time    = problem.schedule.current_time();
    record.n_ranks = Utilities::MPI::n_mpi_processes(problem.mpi_communicator);
    record.n_dofs  = problem.dof_handler.n_dofs();
    record.entries = problem.parameters.result_entries;
    publish_checkpoint(problem.output.folder(), record, last_step_written);
    // What a resumed run cannot restore, this run forgets too.
    if (problem.contact_enabled)
      problem.contact_solver->forget_kept_state();
    last_step_written = step;
  }



  // @sect4{Checkpoints::make_header}
  template <int dim>
  ByteWriter
  Checkpoints<dim>::make_header(const ViscoplasticContact<dim> &problem,
                                const double                    wall_time)
  {
    // The header: what identifies the file (version, dim, step), the schedule
    // (with the step controller's state), the run's wall time and compute time
    // so far, the iteration counters, the largest von Mises stress, and the
    // list of .pvtu records for solution.pvd. That list is kept on rank 0 only
    // (RunOutput::write_results()), and rank 0's header is the one written.
    ByteWriter header;
    header.write(checkpoint_version);
    header.write<std::uint32_t>(dim);
    header.write<std::uint32_t>(problem.schedule.step_number());
    problem.schedule.save(header);
    problem.report.save(header, wall_time);
    header.write(problem.max_von_mises);
    header.write<std::uint64_t>(problem.output.pvd_records().size());
    for (const auto &[time, name] : problem.output.pvd_records())
      {
        header.write(time);
        header.write_string(name);
      }
    // Whether there is a start of the step to predict from, and whether the
    // back end has a state of its own (both the same on every rank).
    header.write<std::uint32_t>(problem.predicted_start.has_start());
    // The uniqueness check's eigenvalue, if the run computed one.
    header.write<std::uint32_t>(problem.uniqueness_eigenvalue.has_value());
    header.write(problem.uniqueness_eigenvalue.value_or(0.));
    // The layout of the nodal fields after the four state vectors: the
    // variables per node of each law with a history (0 if a zone has none)
    // and whether the slips are stored (a kernel of another number of terms
    // may take as many fields).
    for (const ContactHistory *history : problem.contact_histories.all())
      header.write<std::uint32_t>(history->active() ? history->n_variables()
                                                    : 0);
    header.write<std::uint32_t>(n_weakening_fields(problem));
    return header;
  }



  // @sect4{Checkpoints::cell_vectors}
  template <int dim>
  typename Checkpoints<dim>::CellVectors
  Checkpoints<dim>::cell_vectors(const ViscoplasticContact<dim> &problem)
  {
    // The contact state as a displacement-sized vector: each owned contact node
    // writes into the owned entries of its own dofs. The ghost import then
    // makes these values visible in every cell that has the node as a vertex,
    // also on the ranks that do not own the node.
    VectorType contact_state(problem.solution);
    contact_state = 0;
    if (problem.contact_enabled)
      for (unsigned int i = 0; i < problem.contact_set.size(); ++i)
        {
          contact_state.local_element(problem.contact_set.node(i).local_dofs[0])
            = problem.contact_set.piece(i) + 1.;
          contact_state.local_element(problem.contact_set.node(i).local_dofs[1])
            = problem.contact_set.z[i];
        }
    contact_state.update_ghost_values();
    // The start of step n in the same form: u_{n-1}, and per contact node
    // z_{n-1} at its x-dof; and the friction state.
    VectorType start_displacement(problem.solution),
      node_history(problem.solution), friction_state(problem.solution);
    start_displacement = 0;
    node_history       = 0;
    friction_state     = 0;
    if (problem.predicted_start.has_start())
      start_displacement = problem.predicted_start.displacement();
    for (unsigned int i = 0;
         i < problem.contact_set.size() && problem.contact_enabled;
         ++i)
      {
        const auto &dofs = problem.contact_set.node(i).local_dofs;
        if (problem.predicted_start.has_start())
          node_history.local_element(dofs[0])
            = problem.predicted_start.contact_forces()[i];
        friction_state.local_element(dofs[0])
          = problem.contact_set.friction_state(i);
        for (unsigned int j = 0; j < problem.contact_set.n_tangential(i); ++j)
          friction_state.local_element(dofs[1 + j])
            = problem.contact_set.t[i][j];
      }
    start_displacement.update_ghost_values();
    node_history.update_ghost_values();
    friction_state.update_ghost_values();
    std::vector<VectorType> histories;
    if (problem.contact_enabled)
      histories
        = nodal_fields_of(problem.contact_histories.all(),
                          problem.contact_set,
                          problem.solution,
                          problem.prescribed.hanging_node_constraints());
    std::vector<VectorType> weakening_state;
    if (problem.contact_enabled && n_weakening_fields(problem) > 0)
      weakening_state.push_back(problem.contact_set.weakening_field(
        problem.solution,
        problem.prescribed.hanging_node_constraints()));
    return {std::move(contact_state),
            std::move(start_displacement),
            std::move(node_history),
            std::move(friction_state),
            std::move(histories),
            std::move(weakening_state)};
  }



  // @sect4{Checkpoints::write_cell_records}
  template <int dim>
  void
  Checkpoints<dim>::write_cell_records(const ViscoplasticContact<dim> &problem,
                                       const CellVectors              &vectors,
                                       const std::size_t               first,
                                       const std::size_t               end,
                                       char                           *out)
  {
    // A record: the cell id in binary form, the dofs_per_cell values of u, of
    // the contact state, of u_{n-1}, of the nodes' history, of their
    // friction state and of the memory's fields, in the cell's dof order, and
    // the n_q stress-point records of the cell, copied as raw bytes
    // (QuadraturePointHistory is plain data: symmetric tensors and doubles,
    // with the zz components in 2D). (dofs_per_cell the most of any cell: a
    // cell with fewer, a triangle among quadrilaterals, fills its record with
    // zeros.)
    using Key = CellId::binary_type;
    const unsigned int dofs_per_cell
      = problem.discretisation.fe.max_dofs_per_cell();
    const unsigned int n_q = problem.discretisation.n_stress_points();
    std::vector<types::global_dof_index> dof_indices;
    std::vector<const VectorType *>      record_vectors{&problem.solution,
                                                   &vectors.contact_state,
                                                   &vectors.start_displacement,
                                                   &vectors.node_history,
                                                   &vectors.friction_state};
    for (const auto *fields : {&vectors.histories, &vectors.weakening_state})
      for (const VectorType &field : *fields)
        record_vectors.push_back(&field);
    // The cells in the order of stress_points.cells(); (*vector)(dof) reads
    // owned and ghost entries alike, which is why the vectors must have their
    // ghost values here.
    for (std::size_t k = first; k < end; ++k)
      {
        const Key key
          = problem.stress_points.cells()[k]->id().template to_binary<dim>();
        std::memcpy(out, &key, sizeof(Key));
        out += sizeof(Key);
        const auto &cell = problem.stress_points.cells()[k];
        dof_indices.resize(cell->get_fe().n_dofs_per_cell());
        cell->get_dof_indices(dof_indices);
        for (const VectorType *vector : record_vectors)
          for (unsigned int i = 0; i < dofs_per_cell; ++i)
            {
              const double value
                = i < dof_indices.size() ? (*vector)(dof_indices[i]) : 0.;
              std::memcpy(out, &value, sizeof(double));
              out += sizeof(double);
            }
        // The stress-point records of cell k are contiguous in the flat array:
        // entries k * n_q to k * n_q + n_q - 1.
        std::memcpy(out,
                    &problem.quadrature_point_history[std::size_t(k) * n_q],
                    n_q * sizeof(QuadraturePointHistory<dim>));
        out += n_q * sizeof(QuadraturePointHistory<dim>);
      }
  }



  // @sect4{Checkpoints::resume}
  //
  // Reads what write() wrote, on any number of ranks: each rank
  // reads its share of the records, the records travel to the owners of
  // their cells, and every owned cell must be found. Then what the time
  // loop derives from the state is rebuilt (the ghosts, the history load of
  // the next step).
  //
  // It runs after set-up, on the mesh rebuilt from the parameter file; run()
  // continues with the step after the checkpoint's. Everything the loop needs
  // is restored: u_n with its ghosts, the pieces and (r, z) of the contact
  // nodes, every stress-point record, the schedule, the counters and the .pvd
  // list. What the run's summary counts per process (assemblies, set-ups of
  // the back end) starts again from the set-up of the resumed run. The rows
  // of time_series.csv after the checkpoint are removed once the output
  // folder is prepared (RunOutput::prepare_folder()).
  template <int dim>
  void
  Checkpoints<dim>::resume(ViscoplasticContact<dim> &problem)
  {
    // The records of an adaptive run are those of its adapted mesh, which is
    // rebuilt first (restore_mesh()); so are those of a run with initial
    // cycles, whose mesh is not the one make_grid() starts from.
    if (problem.parameters.adaptive_refinement
        || problem.plan.initial_cycles() > 0)
      restore_mesh(problem);
    const CheckpointRecord checkpoint
      = read_checkpoint_record(problem.parameters.directory,
                               problem.dof_handler.n_dofs(),
                               problem.parameters.result_entries);
    const std::string file
      = problem.output.folder().path(checkpoint_name(checkpoint.step));

    // The header first (a file of another scene, or an End time before the
    // checkpoint, is refused before any cell is touched); then the state of
    // every owned cell, as the file is read. The decision is reduced over the
    // ranks, so that all throw if any cell was not found. Then the ghosts of
    // u are imported, as the stress update and the output expect.
    std::vector<char>         header_bytes;
    ByteReader                header(header_bytes, file);
    Flags                     flags{false};
    std::pair<double, double> next_step_lengths;
    CellVectors               vectors{
      problem.solution,
      problem.solution,
      problem.solution,
      problem.solution,
      std::vector<VectorType>(n_history_fields(problem), problem.solution),
      std::vector<VectorType>(n_weakening_fields(problem), problem.solution)};
    const bool complete
      = restore_cell_records(problem, file, header_bytes, vectors, [&]() {
          flags             = read_header(problem, header, checkpoint.step);
          next_step_lengths = continue_schedule(problem);
        });
    header.check(Utilities::MPI::min(complete ? 1 : 0, problem.mpi_communicator)
                 == 1);
    problem.solution.update_ghost_values();
    if (problem.contact_enabled)
      restore_contact_nodes(problem, vectors, header);
    restore_prediction_start(problem, vectors, flags);

    // The explicit update's history load is not stored: it is assembled from
    // the restored histories, as update_stresses() would have left it (for
    // the next step's length of this run's schedule, if that changed). The
    // implicit update needs nothing more; its history enters through the
    // internal force.
    if (problem.parameters.explicit_history_update()
        && next_step_lengths.first != next_step_lengths.second)
      problem.rescale_history_increment(next_step_lengths.first,
                                        next_step_lengths.second);
    else if (problem.parameters.explicit_history_update())
      problem.assemble_history_load();
    last_step_written = checkpoint.step;
    problem.pcout << "Resuming from the checkpoint of step " << checkpoint.step
                  << " (t = " << problem.schedule.current_time()
                  << ", written on " << checkpoint.n_ranks << " MPI rank(s))\n";
  }



  // @sect4{Checkpoints::restore_mesh}
  //
  // A checkpoint holds one record per active cell, keyed by its cell id
  // (robustness/checkpoint_file.h): the ids of the records are the adapted
  // mesh. The mesh built from the parameter file is refined where a checkpoint
  // cell descends from one of its cells and coarsened where one of its cells
  // descends from a checkpoint cell, pass by pass (coarsening goes one level
  // per pass), until its active cells are those of the checkpoint; then
  // everything is set up on it. No rank gathers all ids: each checkpoint cell
  // and each of its ancestors is a record keyed by its id (payload 1 for the
  // cell, 0 for an ancestor), and each rank asks for the ids of its own cells
  // (MPITools::exchange_records(), as the records themselves are read; the
  // rendezvous rank of a coarse cell gets its record from every rank that holds
  // one of its descendants): a cell found with payload 1 stays, one found as an
  // ancestor is refined, one not found is coarsened. Whether the mesh matches
  // is checked by Checkpoints::resume(), which must find every owned cell's
  // record.
  template <int dim>
  void
  Checkpoints<dim>::restore_mesh(ViscoplasticContact<dim> &problem)
  {
    // The checkpoint's step (its dof count belongs to the adapted mesh, so it
    // is checked later), and the records of this rank's share, as
    // Checkpoints::resume() reads them.
    const CheckpointRecord checkpoint
      = read_checkpoint_record(problem.parameters.directory,
                               0,
                               problem.parameters.result_entries);
    using Key              = CellId::binary_type;
    const std::size_t size = record_size(problem);

    // The records of this rank's share, a piece of the file at a time: their
    // cells, and their ancestors once each.
    std::vector<MPITools::Record> records;
    std::set<std::string>         ancestors;
    std::vector<char>             header;
    read_record_file(
      problem.output.folder().path(checkpoint_name(checkpoint.step)),
      header,
      size,
      [&](const std::vector<char> &piece) {
        for (std::size_t r = 0; r < piece.size() / size; ++r)
          {
            Key key;
            std::memcpy(&key, piece.data() + r * size, sizeof(Key));
            const CellId cell(key);
            records.emplace_back(cell.to_string(), std::vector<double>{1.});
            const auto path = cell.get_child_indices();
            for (unsigned int level = 0; level < path.size(); ++level)
              {
                const std::string ancestor
                  = CellId(cell.get_coarse_cell_id(), level, path.data())
                      .to_string();
                if (ancestors.insert(ancestor).second)
                  records.emplace_back(ancestor, std::vector<double>{0.});
              }
          }
      },
      problem.mpi_communicator);

    auto &mesh = dynamic_cast<parallel::distributed::Triangulation<dim> &>(
      *problem.triangulation);
    // At most one level of coarsening per pass, and the levels are bounded by
    // Maximum refinement level (and p4est's limit).
    for (unsigned int pass = 0; pass < 64; ++pass)
      {
        std::vector<std::string> requests;
        for (const auto &cell : mesh.active_cell_iterators())
          if (cell->is_locally_owned())
            requests.push_back(cell->id().to_string());
        const auto found_records
          = MPITools::exchange_records(records,
                                       requests,
                                       problem.mpi_communicator);
        unsigned int marked = 0;
        for (const auto &cell : mesh.active_cell_iterators())
          if (cell->is_locally_owned())
            {
              const auto found = found_records.find(cell->id().to_string());
              const bool is_checkpoint_cell
                = found != found_records.end()
                  && std::any_of(found->second.begin(),
                                 found->second.end(),
                                 [](const std::vector<double> &payload) {
                                   return payload[0] == 1.;
                                 });
              if (is_checkpoint_cell)
                continue;
              if (found != found_records.end())
                cell->set_refine_flag();
              else if (cell->level() > 0)
                cell->set_coarsen_flag();
              else
                continue;
              ++marked;
            }
        if (Utilities::MPI::sum(marked, problem.mpi_communicator) == 0)
          break;
        mesh.execute_coarsening_and_refinement();
      }
    problem.setup_on_mesh();
  }



  // @sect4{Checkpoints::read_header}
  //
  // The header is checked field by field against this run: version,
  // dimension and step. The schedule replaces the one computed from the
  // parameter file, since the interrupted run may have cut steps.
  template <int dim>
  typename Checkpoints<dim>::Flags
  Checkpoints<dim>::read_header(ViscoplasticContact<dim> &problem,
                                ByteReader               &header,
                                const unsigned int        step)
  {
    header.check(header.read<std::uint32_t>() == checkpoint_version);
    header.check(header.read<std::uint32_t>() == dim);
    header.check(header.read<std::uint32_t>() == step);
    problem.schedule.load(header);
    header.check(problem.schedule.step_number() == step);
    problem.report.load(header);
    problem.max_von_mises = header.read<double>();
    std::vector<std::pair<double, std::string>> pvd_records;
    const std::uint64_t n_records = header.read<std::uint64_t>();
    for (std::uint64_t i = 0; i < n_records; ++i)
      {
        const double time = header.read<double>();
        pvd_records.emplace_back(time, header.read_string());
      }
    problem.output.set_pvd_records(std::move(pvd_records));
    Flags flags;
    flags.has_step_start        = header.read<std::uint32_t>() == 1;
    const bool   has_eigenvalue = header.read<std::uint32_t>() == 1;
    const double eigenvalue     = header.read<double>();
    if (has_eigenvalue)
      problem.uniqueness_eigenvalue = eigenvalue;
    for (const ContactHistory *history : problem.contact_histories.all())
      header.check(header.read<std::uint32_t>()
                   == (history->active() ? history->n_variables() : 0));
    header.check(header.read<std::uint32_t>() == n_weakening_fields(problem));
    return flags;
  }



  // @sect4{Checkpoints::continue_schedule}
  //
  // End time is the one entry of the scene a resumed run may change (to go
  // further, or to stop earlier). The levels up to the checkpoint stay those
  // of the interrupted run (with its cut steps); the levels after it are
  // those of the new schedule (TimeSchedule::continue_to()). With the same
  // End time and Profile times they are the same levels, so without cuts the
  // resumed run repeats the uninterrupted one exactly. If the next step's
  // length changes, the history the explicit update stored for the old one is
  // rescaled by the caller, once the stress points are restored.
  template <int dim>
  std::pair<double, double>
  Checkpoints<dim>::continue_schedule(ViscoplasticContact<dim> &problem)
  {
    const double old_next_step = problem.schedule.step_length();
    if (!problem.schedule.is_adaptive()
        && problem.parameters.end_time == problem.schedule.end_time())
      return {old_next_step, old_next_step};
    // An adaptive run may end at the checkpoint; a fixed schedule always has
    // a level after it.
    const double checkpoint_time = problem.schedule.current_time();
    AssertThrow(problem.schedule.is_adaptive()
                  ? problem.parameters.end_time >= checkpoint_time
                  : problem.parameters.end_time > checkpoint_time,
                ExcMessage("Invalid parameter <End time> in subsection "
                           "<Time>: value <"
                           + std::to_string(problem.parameters.end_time)
                           + ">, but the checkpoint to resume from is at t = "
                           + std::to_string(checkpoint_time)
                           + "; accepted: an End time after the "
                             "checkpoint's time."));
    problem.schedule.continue_to(
      landing_targets(problem.parameters.profile_times,
                      problem.parameters.end_time));
    return {old_next_step, problem.schedule.step_length()};
  }



  // @sect4{Checkpoints::restore_cell_records}
  //
  // The records of this rank's share of the file go to the owners of their
  // cells, a piece of the file at a time (read_record_file()), so that no
  // rank holds more than a piece of them besides the run's own data. Each
  // becomes a (key, payload) pair: the key is the binary cell id, the
  // payload the doubles of u, of the contact state, of the start of the
  // step, of the nodes' history and of the stress points. Each rank asks
  // once for the keys of its own cells; a RecordRouter meets the holders
  // and the askers at a rendezvous rank chosen by a hash of the key, so no
  // rank needs to know who holds which cell.
  //
  // The received values go into the owned entries only: a dof of an owned
  // cell that another rank owns is set there, by the rank that owns it (every
  // owned dof lies on at least one owned cell). A cell whose record is
  // missing, duplicated or of the wrong size makes the checkpoint
  // incomplete.
  template <int dim>
  bool
  Checkpoints<dim>::restore_cell_records(
    ViscoplasticContact<dim>    &problem,
    const std::string           &file,
    std::vector<char>           &header,
    CellVectors                 &vectors,
    const std::function<void()> &check_header)
  {
    using Key = CellId::binary_type;
    const unsigned int dofs_per_cell
      = problem.discretisation.fe.max_dofs_per_cell();
    const unsigned int n_q = problem.discretisation.n_stress_points();
    const std::size_t  bytes_per_record = record_size(problem);
    const unsigned int n_doubles
      = (bytes_per_record - sizeof(Key)) / sizeof(double);

    // Where the record of each owned cell goes: its place in
    // stress_points.cells().
    std::unordered_map<std::string, unsigned int> place_of;
    std::vector<std::string> requests(problem.stress_points.cells().size());
    for (unsigned int k = 0; k < problem.stress_points.cells().size(); ++k)
      {
        const Key key
          = problem.stress_points.cells()[k]->id().template to_binary<dim>();
        requests[k].assign(reinterpret_cast<const char *>(&key), sizeof(Key));
        place_of.emplace(requests[k], k);
      }
    const MPITools::RecordRouter router(requests, problem.mpi_communicator);
    requests = std::vector<std::string>();

    std::vector<VectorType *> targets{&problem.solution,
                                      &vectors.contact_state,
                                      &vectors.start_displacement,
                                      &vectors.node_history,
                                      &vectors.friction_state};
    for (auto *fields : {&vectors.histories, &vectors.weakening_state})
      for (VectorType &field : *fields)
        targets.push_back(&field);
    const unsigned int n_vectors = targets.size();
    AssertDimension(n_vectors, n_record_vectors(problem));
    for (VectorType *target : targets)
      *target = 0;
    std::vector<unsigned int> times_found(problem.stress_points.cells().size(),
                                          0);
    std::vector<types::global_dof_index> dof_indices;
    bool                                 complete = true;
    const auto                           restore
      = [&](const std::string &key, const std::vector<double> &values) {
          const auto entry = place_of.find(key);
          if (entry == place_of.end() || values.size() != n_doubles)
            {
              complete = false;
              return;
            }
          const unsigned int k = entry->second;
          ++times_found[k];
          const auto &cell = problem.stress_points.cells()[k];
          dof_indices.resize(cell->get_fe().n_dofs_per_cell());
          cell->get_dof_indices(dof_indices);
          for (unsigned int i = 0; i < dof_indices.size(); ++i)
            if (problem.locally_owned_dofs.is_element(dof_indices[i]))
              for (unsigned int v = 0; v < n_vectors; ++v)
                (*targets[v])(dof_indices[i]) = values[v * dofs_per_cell + i];
          // The stress-point records go back to their place k * n_q + q, byte
          // for byte.
          std::memcpy(&problem.quadrature_point_history[std::size_t(k) * n_q],
                      values.data() + n_vectors * dofs_per_cell,
                      n_q * sizeof(QuadraturePointHistory<dim>));
        };
    read_record_file(
      file,
      header,
      bytes_per_record,
      [&](const std::vector<char> &piece) {
        std::vector<MPITools::Record> records(piece.size() / bytes_per_record);
        for (std::size_t r = 0; r < records.size(); ++r)
          {
            const char *in = piece.data() + r * bytes_per_record;
            records[r].first.assign(in, sizeof(Key));
            records[r].second.resize(n_doubles);
            std::memcpy(records[r].second.data(),
                        in + sizeof(Key),
                        n_doubles * sizeof(double));
          }
        for (const auto &[key, values] : router.deliver(records))
          restore(key, values);
      },
      problem.mpi_communicator,
      check_header);
    for (const unsigned int n : times_found)
      complete = complete && (n == 1);
    return complete;
  }



  // @sect4{Checkpoints::restore_contact_nodes}
  //
  // The contact nodes, on the rank that owns them now: the piece and the
  // force from the values at their own dofs (the piece was stored + 1, so
  // that 0 means "no contact node"), r = u.nu_i from the restored
  // displacement. The next active set then starts from the pieces of the
  // interrupted run. A piece out of range means a file of another scene;
  // that is decided over all ranks, like the cells, so that all throw
  // together.
  template <int dim>
  void
  Checkpoints<dim>::restore_contact_nodes(ViscoplasticContact<dim> &problem,
                                          const CellVectors        &vectors,
                                          const ByteReader         &header)
  {
    // The laws' histories as the interrupted run left them, and their laws
    // of its last step (memory pressures, bonding, worn depths: the gaps
    // below include them).
    restore_from_nodal_fields(problem.contact_histories.all(),
                              problem.contact_set,
                              vectors.histories);
    bool                                  pieces_valid = true;
    std::vector<ContactNodes::Tangential> tangential_forces(
      problem.contact_set.size(),
      ContactNodes::Tangential{{0, 0}});
    for (unsigned int i = 0; i < problem.contact_set.size(); ++i)
      {
        const auto  &dofs  = problem.contact_set.node(i).local_dofs;
        const double piece = vectors.contact_state.local_element(dofs[0]) - 1.;
        // A piece of the node's own zone's law.
        if (!(piece >= 0 && piece < problem.contact_set.laws().n_pieces())
            || problem.contact_set.laws().zone_of_piece(
                 static_cast<unsigned int>(piece + 0.5))
                 != problem.contact_set.zone(i))
          {
            pieces_valid = false;
            continue;
          }
        problem.contact_set.set_piece(i,
                                      static_cast<unsigned int>(piece + 0.5));
        problem.contact_set.z[i] = vectors.contact_state.local_element(dofs[1]);
        problem.contact_set.r[i]
          = problem.contact_set.normal_component(problem.solution, i)
            - problem.contact_set.gap(i);
        const double state = vectors.friction_state.local_element(dofs[0]);
        if (!(state >= 0 && state <= 2))
          {
            pieces_valid = false;
            continue;
          }
        problem.contact_set.set_friction_state(
          i,
          static_cast<ContactNodes::FrictionState>(
            static_cast<unsigned int>(state + 0.5)));
        for (unsigned int j = 0; j < problem.contact_set.n_tangential(i); ++j)
          tangential_forces[i][j]
            = vectors.friction_state.local_element(dofs[1 + j]);
      }
    // The weakening variables first: the bounds that reset_slip() sets follow
    // them.
    for (const VectorType &field : vectors.weakening_state)
      problem.contact_set.set_weakening_from(field);
    // The slip of the next step is measured from the restored displacement;
    // a slipping node's bound and direction follow from its forces, as in
    // the interrupted run (ContactNodes::accept_slip()).
    problem.contact_set.reset_slip(problem.contact_set.tangential_displacements(
                                     problem.solution),
                                   tangential_forces);
    header.check(
      Utilities::MPI::min(pieces_valid ? 1 : 0, problem.mpi_communicator) == 1);
  }



  // @sect4{Checkpoints::restore_prediction_start}
  //
  // The start of the checkpoint's step, for the prediction of the next one,
  // unless the interrupted run had none (its step was the first on its
  // mesh). The back ends keep nothing across a checkpoint
  // (ContactSolver::forget_kept_state()).
  template <int dim>
  void
  Checkpoints<dim>::restore_prediction_start(ViscoplasticContact<dim> &problem,
                                             const CellVectors        &vectors,
                                             const Flags              &flags)
  {
    if (flags.has_step_start)
      {
        VectorType displacement = vectors.start_displacement;
        displacement.update_ghost_values();
        std::vector<double> contact_forces;
        for (unsigned int i = 0;
             i < problem.contact_set.size() && problem.contact_enabled;
             ++i)
          contact_forces.push_back(vectors.node_history.local_element(
            problem.contact_set.node(i).local_dofs[0]));
        problem.predicted_start.remember(std::move(displacement),
                                         std::move(contact_forces));
      }
  }



  // @sect4{Checkpoints::stop_if_signalled}
  //
  // A scheduler's signal (SIGTERM, SIGINT, SIGUSR1) on any rank: every rank
  // learns of it here, once per step, through the maximum over the ranks, so
  // that all stop after this same step. The step is complete and written; a
  // checkpoint of it is written if none was, and the run ends with status
  // 128 + signal (main()). After the last step there is nothing left to save
  // the run for: it ends normally.
  template <int dim>
  void
  Checkpoints<dim>::stop_if_signalled(ViscoplasticContact<dim> &problem,
                                      const bool   checkpoint_written,
                                      const double wall_time)
  {
    const int signal
      = Utilities::MPI::max(StopSignals::received(), problem.mpi_communicator);
    if (signal == 0 || problem.schedule.is_at_end())
      return;
    if (problem.parameters.resumable && !checkpoint_written)
      write(problem, wall_time);
    problem.pcout << "Stopped after step " << problem.schedule.step_number()
                  << " (t = " << problem.schedule.current_time() << ") on "
                  << StopSignals::name(signal);
    if (problem.parameters.resumable)
      problem.pcout
        << "; the checkpoint of step " << problem.schedule.step_number()
        << " is in " << problem.output.folder().path(checkpoint_folder)
        << ".\nTo continue the run, set Resume = true in subsection "
           "<Checkpoint> and run the same parameter file again (on any "
           "number of MPI ranks)."
        << std::endl;
    else
      problem.pcout << "; a convergence study cannot be resumed: run it again."
                    << std::endl;
    throw StopSignals::Stopped{signal};
  }



  template class Checkpoints<2>;
  template class Checkpoints<3>;
} // namespace ViscoContact
