// Checkpoint and resume of DistributedViscoplasticContact<dim>: one file
// per rank, with the data keyed by what does not depend on the partition.

#include <deal.II/base/exceptions.h>
#include <deal.II/base/mpi.h>

#include <deal.II/grid/cell_id.h>

#include "checkpoint.h"
#include "distributed_viscoplastic_contact.h"

#include <map>

namespace ViscoContact
{
  namespace
  {
    constexpr std::uint32_t distributed_checkpoint_version = 1;
  } // namespace



  // @sect4{DistributedViscoplasticContact::write_checkpoint}
  //
  // deal.II 9.4 cannot reliably save and load fully distributed meshes on
  // several ranks, so no mesh is saved: the resumed run rebuilds it from
  // the parameter file (the same generator or Gmsh file, the same
  // refinements, the same partition) and finds its data by cell id. Each
  // rank writes, per locally owned cell, the cell id, the displacement dofs
  // of the cell and the states of its stress points; per owned contact node
  // its location, piece, r and z; rank 0 also the .pvd record.
  template <int dim>
  void
  DistributedViscoplasticContact<dim>::write_checkpoint(
    const unsigned int         step,
    const std::vector<double> &times,
    const double               wall_time)
  {
    TimerOutput::Scope t(computing_timer, "Checkpoint");
    const unsigned int rank
      = Utilities::MPI::this_mpi_process(mpi_communicator);
    if (rank == 0)
      std::filesystem::create_directories(
        checkpoint_directory(parameters.directory));
    const int error = MPI_Barrier(mpi_communicator);
    AssertThrowMPI(error);

    CheckpointWriter out(checkpoint_file(parameters.directory, step, rank));
    CheckpointHeader header;
    header.version      = distributed_checkpoint_version;
    header.dimension    = dim;
    header.step         = step;
    header.times        = times;
    header.wall_time    = wall_time;
    header.compute_time = time_loop_compute_time;
    header.write(out);
    out.write<std::uint32_t>(total_active_set_iterations);
    out.write<std::uint32_t>(total_cg_iterations);
    out.write<std::uint32_t>(n_cg_solves);
    out.write(max_von_mises);

    const unsigned int                   n_q = stress_quadrature.size();
    std::vector<types::global_dof_index> dof_indices(fe->n_dofs_per_cell());
    std::vector<double>                  values(fe->n_dofs_per_cell());
    out.write<std::uint64_t>(triangulation->n_locally_owned_active_cells());
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          out.write(cell->id().template to_binary<dim>());
          cell->get_dof_indices(dof_indices);
          for (unsigned int i = 0; i < dof_indices.size(); ++i)
            values[i] = ghosted_solution[dof_indices[i]];
          out.write_vector(values);
          for (unsigned int q = 0; q < n_q; ++q)
            out.write(quadrature_point_history
                        [std::size_t(cell->active_cell_index()) * n_q + q]);
        }
    out.write<std::uint64_t>(contact_nodes.size());
    for (const DistributedContactNode<dim> &node : contact_nodes)
      {
        out.write(node.location);
        out.write<std::uint32_t>(node.piece);
        out.write(node.r);
        out.write(node.z);
      }
    write_output_records(out, times_and_names);
    out.finish();

    CheckpointRecord record;
    record.step    = step;
    record.time    = times[step];
    record.n_ranks = Utilities::MPI::n_mpi_processes(mpi_communicator);
    record.n_dofs  = dof_handler.n_dofs();
    publish_checkpoint(parameters.directory,
                       record,
                       last_checkpoint_step,
                       mpi_communicator);
    last_checkpoint_step = step;
  }



  // @sect4{DistributedViscoplasticContact::resume_from_checkpoint}
  //
  // Every locally owned cell and contact node must be found in this rank's
  // file; the displacement entries of the owned dofs are taken from the
  // cells that contain them.
  template <int dim>
  unsigned int
  DistributedViscoplasticContact<dim>::resume_from_checkpoint(
    std::vector<double> &times)
  {
    const unsigned int rank
      = Utilities::MPI::this_mpi_process(mpi_communicator);
    const CheckpointRecord record
      = read_checkpoint_record(parameters.directory,
                               Utilities::MPI::n_mpi_processes(
                                 mpi_communicator),
                               dof_handler.n_dofs());
    const std::filesystem::path file
      = checkpoint_file(parameters.directory, record.step, rank);
    CheckpointReader in(file);
    const auto       damaged
      = [&](const bool ok) { check_checkpoint_content(ok, in); };
    CheckpointHeader header;
    header.read(in, distributed_checkpoint_version, dim, record.step);
    const unsigned int step     = header.step;
    times                       = header.times;
    loop_time_offset            = header.wall_time;
    time_loop_compute_time      = header.compute_time;
    total_active_set_iterations = in.read<std::uint32_t>();
    total_cg_iterations         = in.read<std::uint32_t>();
    n_cg_solves                 = in.read<std::uint32_t>();
    max_von_mises               = in.read<double>();

    // The cells of the file, by id.
    const unsigned int  n_q     = stress_quadrature.size();
    const std::uint64_t n_cells = in.read<std::uint64_t>();
    damaged(n_cells == triangulation->n_locally_owned_active_cells());
    std::map<CellId::binary_type, std::size_t> cell_index;
    std::vector<std::vector<double>>           cell_values(n_cells);
    std::vector<QuadraturePointHistory<dim>>   cell_states(n_cells * n_q);
    for (std::uint64_t c = 0; c < n_cells; ++c)
      {
        cell_index[in.read<CellId::binary_type>()] = c;
        cell_values[c]                             = in.read_vector<double>();
        for (unsigned int q = 0; q < n_q; ++q)
          cell_states[c * n_q + q] = in.read<QuadraturePointHistory<dim>>();
      }
    std::vector<types::global_dof_index> dof_indices(fe->n_dofs_per_cell());
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          const auto entry
            = cell_index.find(cell->id().template to_binary<dim>());
          damaged(entry != cell_index.end());
          const std::size_t c = entry->second;
          damaged(cell_values[c].size() == dof_indices.size());
          cell->get_dof_indices(dof_indices);
          for (unsigned int i = 0; i < dof_indices.size(); ++i)
            if (locally_owned_dofs.is_element(dof_indices[i]))
              solution[dof_indices[i]] = cell_values[c][i];
          for (unsigned int q = 0; q < n_q; ++q)
            quadrature_point_history[std::size_t(cell->active_cell_index())
                                       * n_q
                                     + q]
              = cell_states[c * n_q + q];
        }
    solution.compress(VectorOperation::insert);
    ghosted_solution = solution;

    // The contact nodes, by location.
    const std::uint64_t n_nodes = in.read<std::uint64_t>();
    damaged(n_nodes == contact_nodes.size());
    std::map<std::array<double, dim>, std::size_t> node_index;
    std::vector<DistributedContactNode<dim>>       stored(n_nodes);
    for (std::uint64_t i = 0; i < n_nodes; ++i)
      {
        stored[i].location = in.read<Point<dim>>();
        stored[i].piece    = in.read<std::uint32_t>();
        stored[i].r        = in.read<double>();
        stored[i].z        = in.read<double>();
        std::array<double, dim> key;
        for (unsigned int d = 0; d < dim; ++d)
          key[d] = stored[i].location[d];
        node_index[key] = i;
      }
    for (DistributedContactNode<dim> &node : contact_nodes)
      {
        std::array<double, dim> key;
        for (unsigned int d = 0; d < dim; ++d)
          key[d] = node.location[d];
        const auto entry = node_index.find(key);
        damaged(entry != node_index.end());
        node.piece = stored[entry->second].piece;
        node.r     = stored[entry->second].r;
        node.z     = stored[entry->second].z;
      }

    times_and_names = read_output_records(in);

    if (parameters.plasticity)
      assemble_history_load();
    if (rank == 0)
      truncate_time_series(std::filesystem::path(parameters.directory)
                             / "time_series.csv",
                           step);
    last_checkpoint_step = step;
    pcout << "Resuming from the checkpoint of step " << step
          << " (t = " << times[step] << ")\n";
    return step;
  }



  template class DistributedViscoplasticContact<2>;
  template class DistributedViscoplasticContact<3>;
} // namespace ViscoContact
