#ifndef viscoplastic_contact_convergence_study_h
#define viscoplastic_contact_convergence_study_h

#include <deal.II/base/symmetric_tensor.h>

#include <deal.II/lac/vector.h>

#include "parameters.h"
#include "viscoplastic_contact.h"

#include <array>
#include <memory>
#include <vector>

namespace ViscoContact
{
  using namespace dealii;

  // @sect3{The convergence study}
  //
  // Runs the scene at a sequence of resolutions (h_i, k_i) and at a
  // reference resolution, and measures the error of model.md, section 1,
  //   max_n ( ||u_n - u_n^ref||_V + ||sigma_n - sigma_n^ref||_Q ),
  //   ||v||_V = ||eps(v)||_L2, ||tau||_Q = ||tau||_L2,
  // together with its displacement and stress parts, the observed orders in
  // h + k, the number of unknowns and steps and the wall time of each run.
  //
  // The comparison is exact, on the reference mesh and at the common time
  // levels: the meshes are nested, so a coarse P1 displacement is a P1
  // function on the reference mesh (its values at the reference vertices,
  // by barycentric coordinates in the coarse cell that contains them) and a
  // coarse piecewise-constant stress is piecewise constant on the reference
  // cells. The coarse runs keep their states at all their time levels; the
  // reference run compares against them while it runs, so no reference
  // state is stored.
  template <int dim>
  class ConvergenceStudy
  {
  public:
    explicit ConvergenceStudy(const Parameters::AllParameters &parameters);

    void
    run();

  private:
    struct Run
    {
      unsigned int                                      subdivisions;
      double                                            time_step;
      std::unique_ptr<ViscoplasticContact<dim>>         problem;
      std::vector<double>                               times;
      std::vector<Vector<double>>                       displacements;
      std::vector<std::vector<SymmetricTensor<2, dim>>> stresses;
      double                                            wall_time = 0;

      // For every reference vertex: the coarse dofs (vertex a, component c)
      // of the coarse cell containing it and its barycentric coordinates;
      // for every reference cell: the coarse cell containing it.
      std::vector<std::array<types::global_dof_index, (dim + 1) * dim>>
                                               vertex_dofs;
      std::vector<std::array<double, dim + 1>> vertex_weights;
      std::vector<unsigned int>                cell_map;

      double       max_error_u       = 0;
      double       max_error_sigma   = 0;
      double       max_error         = 0;
      unsigned int n_compared_levels = 0;
      // A run that stopped (iteration limit, blow-up) is kept in the table
      // with infinite error, so that a stability sweep shows where a method
      // fails instead of aborting the study.
      bool        failed = false;
      std::string failure;
    };

    Parameters::AllParameters
    parameters_for(const unsigned int subdivisions,
                   const double       time_step,
                   const std::string &name) const;
    void
    build_transfer(Run &run, const ViscoplasticContact<dim> &reference) const;
    void
    compare(Run                            &run,
            const unsigned int              level,
            const ViscoplasticContact<dim> &reference) const;
    void
    write_table(const unsigned int reference_dofs,
                const unsigned int reference_steps,
                const double       reference_wall_time) const;

    const Parameters::AllParameters parameters;
    std::vector<Run>                runs;
  };
} // namespace ViscoContact

#endif
