#ifndef viscoplastic_contact_vtu_record_h
#define viscoplastic_contact_vtu_record_h

#include <deal.II/base/data_out_base.h>
#include <deal.II/base/mpi.h>

#include <deal.II/dofs/dof_handler.h>

#include <deal.II/hp/mapping_collection.h>

#include <deal.II/numerics/data_out.h>

#include "robustness/output_folder.h"

#include <string>
#include <vector>

namespace ViscoContact
{
  using namespace dealii;

  // @sect3{A .pvtu record written through the output folder}
  //
  // What DataOut::write_vtu_with_pvtu_record() does, with deal.II's file
  // names, but through the output folder: deal.II's writes the files under
  // their final names (with MPI I/O) and throws on the rank that sees an
  // I/O error, while the others wait in the next collective call (a hang on
  // a full disk), and it leaves a truncated file behind.
  //
  // The ranks form at most 8 groups of consecutive ranks; each group writes
  // one .vtu file (OutputFolder::stage_collectively(): the XML header from
  // the group's first rank, the patches of every rank, the footer from the
  // last rank), and the pieces are committed together. Then rank 0 stages
  // the .pvtu record that lists them (the caller commits it). The patches
  // are those of the given cells (the rank's owned cells), placed with
  // mapping. Returns the record's name, stem_SSSS.pvtu. Collective.
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
    const MPI_Comm communicator);
} // namespace ViscoContact

#endif
