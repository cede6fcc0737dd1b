#ifndef viscoplastic_contact_run_output_h
#define viscoplastic_contact_run_output_h

#include <deal.II/base/mpi.h>

#include <deal.II/dofs/dof_handler.h>

#include <deal.II/lac/vector.h>

#include <deal.II/numerics/data_out.h>

#include "back_ends/linear_algebra.h"
#include "contact_nodes.h"
#include "parameters.h"
#include "robustness/output_folder.h"
#include "run/run_report.h"

#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace ViscoContact
{
  using namespace dealii;

  template <int dim>
  class ViscoplasticContact;

  // @sect3{What a run writes}
  //
  // The output of a ViscoplasticContact (the problem) into its output
  // folder: the .pvtu/.vtu records with their .pvd list for ParaView, one
  // row of time_series.csv per step, the contact profiles, and at the end
  // the run summary with its cost measurements on the console. Everything
  // goes through the folder (robustness/output_folder.h), which refuses
  // another run's files, writes to temporary names and commits. What is
  // written is either reduced over the ranks (counts, forces, norms:
  // written by rank 0) or each rank's own part of one file (written
  // collectively).
  //
  // The object reads the problem's state (it is the problem's friend, as
  // StepCycles and Checkpoints are) and never changes it, apart from the
  // cost measurement after the run. It keeps the folder and the .pvd list,
  // which a checkpoint stores.
  template <int dim>
  class RunOutput
  {
  public:
    // The first thing a run does: the folder is looked at (and, if it
    // exists, locked for this run) before any work is done; nothing in it
    // changes here.
    void
    open_folder(const Parameters::AllParameters &parameters,
                const MPI_Comm                   communicator);
    // Once the input is known to be good: the folder created or cleared of
    // the earlier run's files (a resumed run's of the steps after its
    // checkpoint), the parsed parameters and the time series' header.
    void
    prepare_folder(const ViscoplasticContact<dim> &problem,
                   const unsigned int              resume_step);
    OutputFolder &
    folder() const
    {
      return *output_folder;
    }
    // The records of solution.pvd (kept on rank 0), which a checkpoint
    // stores and a resumed run restores.
    const std::vector<std::pair<double, std::string>> &
    pvd_records() const
    {
      return times_and_names;
    }
    void
    set_pvd_records(std::vector<std::pair<double, std::string>> records)
    {
      times_and_names = std::move(records);
    }

    // The run's header on the console: the size of the problem, the model,
    // the back end with the reason for the choice, the parallel layout.
    void
    print_header(const ViscoplasticContact<dim> &problem,
                 const unsigned int              n_steps) const;

    // The .pvtu record of the problem's state at step n (with another stem
    // than "solution", for inspection only and not listed in solution.pvd),
    // the row of time_series.csv and the contact profile of a step.
    void
    write_results(ViscoplasticContact<dim> &problem,
                  const unsigned int        step,
                  const double              time,
                  const std::string        &stem = "solution");
    void
    write_time_series_row(ViscoplasticContact<dim> &problem,
                          const unsigned int        step,
                          const double              time,
                          const double              time_step,
                          const ActiveSetResult    &result,
                          const double              wall_time);
    void
    write_contact_profile(const ViscoplasticContact<dim> &problem,
                          const unsigned int              step,
                          const double                    time);
    // The run summary: the final state, with Print timing summary the
    // timers, and with Measure cost ratios the reference costs, measured
    // now (collective).
    void
    print_summary(ViscoplasticContact<dim> &problem);

  private:
    // The fields of a record besides the displacement: per cell (an entry
    // per active cell, set on the owned ones; material_id and stress_zz
    // empty where not written) and at the vertices (the contact fields, and
    // with friction the friction fields; friction_state empty without),
    // with their ghosts.
    struct Fields
    {
      std::vector<Vector<float>> stress, viscoplastic;
      Vector<float>              von_mises, subdomain, material_id, stress_zz;
      std::vector<VectorType>    contact;
      VectorType                 tangential_traction, slip, friction_state;
      VectorType                 memory_pressure, bonding, wear, damage;

      void
      add_to(DataOut<dim>          &data_out,
             const DoFHandler<dim> &dof_handler,
             const DoFHandler<dim> &scalar_dof_handler) const;
    };
    static Fields
    compute_fields(const ViscoplasticContact<dim> &problem);
    // The reference costs of the run summary, measured after the run: one
    // solve with the step operator and no contact, one stress update.
    static RunReport::CostMeasurement
    measure_reference_costs(ViscoplasticContact<dim> &problem);

    std::unique_ptr<OutputFolder>               output_folder;
    std::vector<std::pair<double, std::string>> times_and_names;
  };
} // namespace ViscoContact

#endif
