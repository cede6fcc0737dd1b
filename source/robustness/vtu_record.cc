// write_vtu_record(): the .vtu pieces and the .pvtu record of one output
// step, written by groups of ranks through the output folder
// (vtu_record.h).

#include <deal.II/base/exceptions.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/utilities.h>

#include "robustness/vtu_record.h"

#include <algorithm>
#include <limits>
#include <sstream>

namespace ViscoContact
{
  template <int dim>
  std::string
  write_vtu_record(
    DataOut<dim>                                                      &data_out,
    const DataOutBase::VtkFlags                                       &flags,
    const std::string                                                 &stem,
    const unsigned int                                                 step,
    const std::vector<typename DoFHandler<dim>::active_cell_iterator> &cells,
    const hp::MappingCollection<dim>                                  &mapping,
    OutputFolder  &output_folder,
    const MPI_Comm communicator)
  {
    // DataOut keeps its patches and field names protected; this class only
    // opens them to the writer below.
    struct Patches : public DataOut<dim>
    {
      using DataOut<dim>::get_patches;
      using DataOut<dim>::get_dataset_names;
      using DataOut<dim>::get_nonscalar_data_ranges;
    };
    const Patches &patches = static_cast<const Patches &>(data_out);

    const unsigned int n_ranks = Utilities::MPI::n_mpi_processes(communicator);
    const unsigned int rank    = Utilities::MPI::this_mpi_process(communicator);
    const unsigned int n_files = std::min(8u, n_ranks);
    const unsigned int group   = rank * n_files / n_ranks;
    const unsigned int n_digits
      = Utilities::needed_digits(std::max(0, int(n_files) - 1));
    const std::string record = stem + "_" + Utilities::int_to_string(step, 4);
    const auto        piece_name = [&](const unsigned int g) {
      return record + "." + Utilities::int_to_string(g, n_digits) + ".vtu";
    };
    std::vector<std::string> pieces;
    for (unsigned int g = 0; g < n_files; ++g)
      pieces.push_back(piece_name(g));
    output_folder.record_files(pieces);
    output_folder.record_files({record + ".pvtu"});

    // This rank's part of its group's file: the header on the group's first
    // rank, the patches, the footer on its last rank.
    MPI_Comm  group_communicator;
    const int error
      = MPI_Comm_split(communicator, group, rank, &group_communicator);
    AssertThrowMPI(error);
    const bool first_of_group
      = (Utilities::MPI::this_mpi_process(group_communicator) == 0);
    const bool last_of_group
      = (Utilities::MPI::this_mpi_process(group_communicator) + 1
         == Utilities::MPI::n_mpi_processes(group_communicator));
    std::ostringstream header, block;
    if (first_of_group)
      DataOutBase::write_vtu_header(header, flags);
    // The rank's cells in pieces of at most cells_per_piece, each written as
    // a <Piece> of the file as soon as its patches are built: DataOut's
    // patches and the reordered copy write_vtu_main() makes of them take
    // about 2 kB per hexahedron, 0.7 kB per dof, which for all of a rank's
    // cells at once would add half to the memory of a matrix-free run. The
    // patches are placed with the mapping of the cell type, the one the
    // whole program uses; the time and step go into the first piece.
    constexpr std::size_t cells_per_piece = std::size_t(1) << 18;
    using CellIterator = typename Triangulation<dim>::cell_iterator;
    const std::size_t n_pieces
      = std::max<std::size_t>(1,
                              (cells.size() + cells_per_piece - 1)
                                / cells_per_piece);
    for (std::size_t piece = 0; piece < n_pieces; ++piece)
      {
        // DataOut walks the selection from first_cell() to the end several
        // times, each walk from first_cell().
        const std::size_t begin = piece * cells_per_piece;
        const std::size_t end = std::min(cells.size(), begin + cells_per_piece);
        std::size_t       position = begin;
        const auto        cell_at  = [&](const Triangulation<dim> &mesh) {
          return position < end ? CellIterator(cells[position]) : mesh.end();
        };
        data_out.set_cell_selection(
          [&](const Triangulation<dim> &mesh) {
            position = begin;
            return cell_at(mesh);
          },
          [&](const Triangulation<dim> &mesh, const CellIterator &) {
            ++position;
            return cell_at(mesh);
          });
        data_out.build_patches(mapping);
        DataOutBase::VtkFlags piece_flags = flags;
        if (piece > 0)
          {
            piece_flags.time  = std::numeric_limits<double>::min();
            piece_flags.cycle = std::numeric_limits<unsigned int>::min();
          }
        DataOutBase::write_vtu_main(patches.get_patches(),
                                    patches.get_dataset_names(),
                                    patches.get_nonscalar_data_ranges(),
                                    piece_flags,
                                    block);
      }
    if (last_of_group)
      DataOutBase::write_vtu_footer(block);
    const std::string text = block.str();
    output_folder.stage_collectively(piece_name(group),
                                     header.str(),
                                     text.data(),
                                     text.size(),
                                     group_communicator);
    MPI_Comm_free(&group_communicator);
    output_folder.commit();

    // The .pvtu record, once every piece is in place.
    if (rank == 0)
      {
        std::ostringstream pvtu;
        data_out.write_pvtu_record(pvtu, pieces);
        output_folder.stage(record + ".pvtu", pvtu.str());
      }
    return record + ".pvtu";
  }



  template std::string
  write_vtu_record<2>(
    DataOut<2> &,
    const DataOutBase::VtkFlags &,
    const std::string &,
    const unsigned int,
    const std::vector<typename DoFHandler<2>::active_cell_iterator> &,
    const hp::MappingCollection<2> &,
    OutputFolder &,
    const MPI_Comm);
  template std::string
  write_vtu_record<3>(
    DataOut<3> &,
    const DataOutBase::VtkFlags &,
    const std::string &,
    const unsigned int,
    const std::vector<typename DoFHandler<3>::active_cell_iterator> &,
    const hp::MappingCollection<3> &,
    OutputFolder &,
    const MPI_Comm);
} // namespace ViscoContact
