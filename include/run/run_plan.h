#ifndef viscoplastic_contact_run_plan_h
#define viscoplastic_contact_run_plan_h

#include <deal.II/base/mpi.h>

#include "back_ends/cost_model.h"
#include "parameters.h"

#include <cstdint>
#include <string>

namespace ViscoContact
{
  using namespace dealii;

  // @sect3{The plan of a run}
  //
  // The decisions about how a run is carried out that follow from its size,
  // taken before the mesh exists and again on every mesh: whether the mesh
  // fits the memory of the machine (check_memory()), on how many coarser
  // meshes the first step (initial cycles) and every later step (step
  // cycles) are solved first (nested iteration), which back end solves the
  // step problems (Method = auto: the cost model of back_ends/cost_model.h),
  // whether the .vtu records fit on the disk, and whether the steps stay
  // within Maximum number of steps and the bound on .vtu records. Every
  // choice auto makes keeps its reason for the header of the run. The
  // decisions before the mesh come from the size the parameter file's mesh
  // will have (estimate_scene()), those on a mesh from its own.
  //
  // Every rank takes the same decisions: what they depend on is reduced
  // over the ranks.
  template <int dim>
  class RunPlan
  {
  public:
    // mesh_group_root: whether this rank builds the whole mesh of its group
    // (simplex meshes), which the memory check counts.
    RunPlan(const Parameters::AllParameters &parameters,
            const MPI_Comm                   communicator,
            const bool                       mesh_group_root);

    // @sect4{Before the mesh}
    //
    // Collective. A mesh that certainly does not fit is refused, naming the
    // entry; the memory found per rank is kept for the choices of Method =
    // auto. Then the initial and the step cycles (the latter on simplices
    // or not).
    void
    check_memory();
    void
    choose_initial_cycles();
    void
    choose_step_cycles(const bool simplex);

    unsigned int
    initial_cycles() const;
    const std::string &
    initial_cycles_reason() const;
    unsigned int
    step_cycles() const;
    const std::string &
    step_cycles_reason() const;
    // Step cycles that auto chose from its estimate, dropped because auto
    // then took the condensed back end for the mesh of the run.
    bool
    step_cycles_dropped() const;

    // @sect4{On each mesh}
    //
    // Method = auto from the mesh's dofs and contact nodes (collective sums
    // of the caller), the share of those expected in contact at one time,
    // the steps left in the run (0: the run's from the
    // parameter file), and whether the mesh is a coarser mesh of the
    // initial cycles (which solves the first step only) and how many of
    // them have been solved.
    void
    choose_back_end(const double       dofs,
                    const double       contact_nodes,
                    const double       contact_fraction,
                    const double       steps_left,
                    const bool         cycle_mesh,
                    const unsigned int initial_cycles_done);
    const MethodChoice &
    back_end() const;
    // The matrix-free back end: no matrix of K is assembled; the back end
    // applies it cell by cell.
    bool
    matrix_free() const
    {
      return back_end().method == Parameters::Method::matrix_free;
    }

    // @sect4{Output and steps}
    //
    // Collective: the .vtu records of n_steps steps of a mesh of n_cells
    // cells of n_cell_vertices vertices fit on the disk of the output
    // folder (a lower estimate of their size), or all ranks stop naming
    // the entries that make them. And step n (from time) is within
    // Maximum number of steps, its record within the bound on .vtu
    // records (adaptive and cut steps, whose number is not known before).
    void
    check_output_volume(const double        n_cells,
                        const unsigned int  n_cell_vertices,
                        const std::uint64_t n_steps) const;
    void
    check_step_count(const unsigned int n, const double time) const;

  private:
    // What the cost model knows of the run apart from the mesh, and the
    // same with the estimated size of the parameter file's mesh (cells as
    // well; collective: rank 0 reads a mesh file's node count).
    SceneSize
    scene_of_run() const;
    SceneSize
    estimate_scene(double &cells) const;

    const Parameters::AllParameters parameters;
    MPI_Comm                        communicator;
    const bool                      mesh_group_root;
    double                          memory_per_rank   = 0;
    unsigned int                    first_step_cycles = 0;
    std::string                     initial_reason;
    unsigned int                    n_step_cycles = 0;
    std::string                     step_reason;
    MethodChoice                    method;
  };
} // namespace ViscoContact

#endif
