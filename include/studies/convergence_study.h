#ifndef viscoplastic_contact_convergence_study_h
#define viscoplastic_contact_convergence_study_h

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/mpi.h>

#include "parameters.h"
#include "robustness/mpi_tools.h"
#include "robustness/output_folder.h"
#include "viscoplastic_contact.h"

#include <memory>
#include <ostream>
#include <string>
#include <vector>

namespace ViscoContact
{
  using namespace dealii;

  // @sect3{The convergence study}
  //
  // Runs the scene at a sequence of resolutions (h_i, k_i) and at a
  // reference resolution, and measures the error of doc/model.md,
  // section 1,
  //   max_n ( ||u_n - u_n^ref||_V + ||sigma_n - sigma_n^ref||_Q ),
  //   ||v||_V = ||eps(v)||_L2, ||tau||_Q = ||tau||_L2,
  // with its displacement and stress parts, the observed orders in h + k,
  // the number of unknowns and steps and the wall time of each run; on any
  // number of ranks, for simplex and hypercube boxes.
  //
  // The comparison is exact, on the reference mesh and at the common time
  // levels. The meshes are nested boxes: every reference stress point lies
  // inside one coarse cell, in the square (cube) of the coarse box that
  // contains it. Every coarse run records, per cell, its vertices and, at
  // each time level, grad u and sigma at its stress points; a coarse run's
  // cells are then sent to the ranks of the reference mesh that need them,
  // keyed by their square (MPITools::exchange_records). There, grad u_h and
  // sigma_h are evaluated at the reference stress points: on simplices they
  // are constant per cell (P1 displacement, piecewise-constant stress); on
  // hypercubes grad u_h is the Q1 gradient and sigma_h the polynomial of
  // degree one in each variable through the values at the 2^dim Gauss
  // points, which represents the Q1 gradient exactly and is the natural
  // reading of stresses stored at Gauss points. The reference quadrature
  // then integrates the squared differences exactly on simplices and on
  // the reference's Gauss points on hypercubes.
  template <int dim>
  class ConvergenceStudy
  {
  public:
    ConvergenceStudy(const Parameters::AllParameters &parameters,
                     const MPI_Comm                   communicator);

    void
    run();

  private:
    struct Run
    {
      unsigned int subdivisions;
      double       time_step;
      // The time of every step the observer saw (the levels compared).
      std::vector<double>     observed_times;
      types::global_dof_index n_dofs = 0;
      // The cells of this rank (key: its square), growing by one level of
      // grad u and sigma at every step.
      std::vector<MPITools::Record> cells;
      double                        wall_time = 0;

      // Per reference stress point (locally owned reference cells): the
      // coarse cell containing it (its payload) and the point in that
      // cell's unit coordinates.
      std::vector<std::vector<double>> located_cells;
      std::vector<unsigned int>        point_cell;
      std::vector<Point<dim>>          unit_points;

      double       max_error_u       = 0;
      double       max_error_sigma   = 0;
      double       max_error         = 0;
      unsigned int n_compared_levels = 0;
      // A run that stopped (iteration limit, blow-up) is kept in the table
      // with infinite error, so that a stability sweep shows where a
      // method fails instead of aborting the study.
      bool        failed = false;
      std::string failure;
    };

    Parameters::AllParameters
    parameters_for(const unsigned int subdivisions,
                   const double       time_step,
                   const std::string &name) const;
    std::string
    square_key(const Point<dim> &point, const unsigned int subdivisions) const;
    void
    record_state(Run &run, const ViscoplasticContact<dim> &problem) const;
    // Coarse run r, recording its states; a run that fails is marked as
    // failed in runs[r] and the study goes on.
    void
    run_coarse(const unsigned int r);
    // After a step of the reference run: compare() for every coarse run
    // with a time level at that time.
    void
    compare_at_time(const double                    time,
                    const ViscoplasticContact<dim> &reference);
    void
    locate(Run &run, const ViscoplasticContact<dim> &reference) const;
    // The real locations of this rank's reference stress points, and the
    // keys of the squares of the coarse box that contain them.
    void
    reference_stress_points(const ViscoplasticContact<dim> &reference,
                            const unsigned int              subdivisions,
                            std::vector<Point<dim>>        &points,
                            std::vector<std::string>       &keys) const;
    void
    compare(Run                            &run,
            const unsigned int              level,
            const ViscoplasticContact<dim> &reference) const;
    void
    write_table(const types::global_dof_index reference_dofs,
                const unsigned int            reference_steps,
                const double                  reference_wall_time) const;
    // A wall time as the tables show it ("-" without the timing summary).
    std::string
    wall_time_text(const double seconds) const;
    // The observed order of the error member of Run between runs r - 1 and
    // r, NaN where it is not defined.
    double
    observed_order(const unsigned int r, const double Run::*member) const;
    // Run r's row of convergence.csv (into csv) and of the terminal table.
    void
    write_table_row(const unsigned int r, std::ostream &csv) const;

    const Parameters::AllParameters parameters;
    const MPI_Comm                  communicator;
    ConditionalOStream              pcout;
    // The study's folder: convergence.csv and runs/, one folder per run.
    std::unique_ptr<OutputFolder> folder;
    std::vector<Run>              runs;
  };
} // namespace ViscoContact

#endif
