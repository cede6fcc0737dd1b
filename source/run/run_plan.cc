// The plan of a run (run/run_plan.h): the memory check, nested iteration
// (initial and step cycles), the back end of each mesh, and the bounds on
// the output and the steps.

#include <deal.II/base/exceptions.h>
#include <deal.II/base/utilities.h>

#include "mesh/mesh.h"
#include "robustness/file_output.h"
#include "mesh/mesh_checks.h"
#include "run/run_plan.h"
#include "time_schedule.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <limits>
#include <sstream>
#include <sys/statvfs.h>

namespace ViscoContact
{
  template <int dim>
  RunPlan<dim>::RunPlan(const Parameters::AllParameters &parameters,
                        const MPI_Comm                   communicator,
                        const bool                       mesh_group_root)
    : parameters(parameters)
    , communicator(communicator)
    , mesh_group_root(mesh_group_root)
  {}



  template <int dim>
  unsigned int
  RunPlan<dim>::initial_cycles() const
  {
    return first_step_cycles;
  }



  template <int dim>
  const std::string &
  RunPlan<dim>::initial_cycles_reason() const
  {
    return initial_reason;
  }



  template <int dim>
  unsigned int
  RunPlan<dim>::step_cycles() const
  {
    return n_step_cycles;
  }



  template <int dim>
  const std::string &
  RunPlan<dim>::step_cycles_reason() const
  {
    return step_reason;
  }



  template <int dim>
  const MethodChoice &
  RunPlan<dim>::back_end() const
  {
    return method;
  }



  // @sect4{RunPlan::estimate_scene}
  //
  // The size of the parameter file's mesh, before it is built, for the
  // decisions taken before the mesh exists. The generated box of N
  // Subdivisions and r Global refinements has (N 2^r)^dim squares (cubes),
  // each cut into the simplices of its pattern, and (N 2^r + 1)^dim vertices
  // (the five-tetrahedra pattern has no more; crossed adds a centre per
  // square). A Gmsh file is known by the node count V at the head of its
  // $Nodes section (read by rank 0, a few lines): a mesh of V vertices has at
  // least V - dim simplices or V / 2^(dim-1) - 1 hypercubes, refinement
  // multiplies the cells by 2^dim per level, and a fine mesh has about 2
  // triangles, 6.5 tetrahedra or 1 hypercube per vertex. Each contact
  // boundary part is taken as one side of the body: V^((dim-1)/dim)
  // vertices. Collective (rank 0 reads the file).
  template <int dim>
  SceneSize
  RunPlan<dim>::estimate_scene(double &cells) const
  {
    const bool simplex
      = (parameters.cell_type != Parameters::CellType::hypercube);
    double vertices = 0;
    if (parameters.mesh_file.empty())
      {
        const double edge = parameters.subdivisions
                            * std::pow(2., parameters.global_refinements);
        vertices = std::pow(edge + 1, dim);
        cells    = std::pow(edge, dim);
        if (simplex)
          switch (parameters.simplex_pattern)
            {
              case Parameters::SimplexPattern::crossed:
                vertices += cells;
                cells *= 4;
                break;
              case Parameters::SimplexPattern::five_tetrahedra:
                cells *= 5;
                break;
              default:
                cells *= (dim == 2 ? 2 : 6);
            }
      }
    else
      {
        // Rank 0 is a group root: it opens the file anyway.
        const double file_vertices = Utilities::MPI::broadcast(
          communicator,
          Utilities::MPI::this_mpi_process(communicator) == 0
            ? gmsh_node_count(parameters.mesh_file)
            : 0.);
        const double file_cells = simplex
                                    ? file_vertices - dim
                                    : file_vertices / std::pow(2., dim - 1) - 1;
        cells                   = std::max(0., file_cells)
                * std::pow(2., dim * parameters.global_refinements);
        vertices = cells / (simplex ? (dim == 2 ? 2 : 6.5) : 1);
      }
    SceneSize scene     = scene_of_run();
    scene.dofs          = dim * vertices;
    scene.contact_nodes = parameters.all_contact_ids().size()
                          * std::pow(vertices, (dim - 1.) / dim);
    return scene;
  }



  template <int dim>
  SceneSize
  RunPlan<dim>::scene_of_run() const
  {
    SceneSize scene;
    scene.dim     = dim;
    scene.simplex = parameters.cell_type != Parameters::CellType::hypercube;
    scene.implicit_update = parameters.implicit_update();
    for (const auto &zone : parameters.used_contact_zones())
      {
        if (zone.contact->tangential_law
            != Parameters::TangentialLawType::frictionless)
          scene.node_unknowns = dim;
        if (zone.contact->adhesion_stiffness > 0
            || zone.contact->cohesive_strength > 0)
          scene.bonded_interface = true;
      }
    scene.ranks = Utilities::MPI::n_mpi_processes(communicator);
    scene.steps
      = std::max(1.,
                 fixed_step_count(parameters.end_time,
                                  std::max(parameters.time_step, 1e-300)));
    scene.coarser_meshes = parameters.uniform_coarsenings() > 0
                           || parameters.contact_refinements > 0
                           || parameters.adaptive_refinement
                           || parameters.initial_refinement
                                == Parameters::InitialRefinement::adaptive;
    scene.distinct_cells  = !parameters.box_map.empty();
    scene.memory_per_rank = memory_per_rank;
    return scene;
  }



  // @sect4{RunPlan::check_memory}
  //
  // A lower estimate of the memory a run needs on each compute node, so that
  // a mesh is refused only if it certainly does not fit, from the size
  // estimate_scene() expects.
  //
  // What a rank needs for the run is the cost model's estimate
  // (cost_model.h: the libraries, and the rank's share of the dofs times the
  // bytes per dof of the back end, measured on the benchmark scenes), for
  // the back end the run will use; with Method = auto for the one of least
  // memory that auto may take, which it takes when the faster ones do
  // not fit. A group root of a simplex mesh (mesh.cc) holds the whole
  // refined mesh during set-up, before the run's data exist: about 400 bytes
  // per cell (405 to 444 measured on tetrahedra, doc/scaling.md). The set-up
  // and the run are summed over the ranks of each node apart, and the larger
  // sum is compared with the node's physical memory (MemTotal of
  // /proc/meminfo). A node's memory divided by its ranks is kept for the
  // cost model's choices (memory_per_rank).
  template <int dim>
  void
  RunPlan<dim>::check_memory()
  {
    double    cells = 0;
    SceneSize scene = estimate_scene(cells);
    // A lower estimate: no dense problem (the contact nodes of a Gmsh mesh
    // are a guess) and a factor no fuller per dof than measured.
    scene.contact_nodes  = 0;
    scene.lower_estimate = true;
    // Step cycles set by hand (auto chooses later, from the memory found
    // here, and a lower estimate need not count them).
    scene.step_cycles             = parameters.step_cycles().value_or(0);
    const bool         simplex    = scene.simplex;
    const double       dofs       = scene.dofs;
    const unsigned int n_ranks    = scene.ranks;
    double             rank_bytes = std::numeric_limits<double>::max();
    // The named method, or the least of those auto may take.
    for (const BackEndCost &cost : estimate_costs(scene))
      if (parameters.method == cost.method
          || (parameters.method == Parameters::Method::automatic
              && cost.automatic_may_take()))
        rank_bytes = std::min(rank_bytes, cost.bytes_per_rank);
    const double libraries  = library_bytes_per_rank;
    const double root_bytes = libraries + cells * 400;

    // The physical memory of this rank's node, and the set-up and run
    // estimates of the ranks on it.
    double node_memory = 0;
    {
      std::ifstream meminfo("/proc/meminfo");
      std::string   key;
      double        kilobytes = 0;
      while (meminfo >> key >> kilobytes)
        {
          if (key == "MemTotal:")
            {
              node_memory = kilobytes * 1024;
              break;
            }
          meminfo.ignore(std::numeric_limits<std::streamsize>::max(), '\n');
        }
    }
    MPI_Comm node_communicator;
    MPI_Comm_split_type(communicator,
                        MPI_COMM_TYPE_SHARED,
                        0,
                        MPI_INFO_NULL,
                        &node_communicator);
    const double setup_need
      = Utilities::MPI::sum(mesh_group_root ? root_bytes : libraries,
                            node_communicator);
    const double run_need = Utilities::MPI::sum(rank_bytes, node_communicator);
    // The least memory per rank of any node (nodes may differ, and so may
    // their rank counts): every rank must see the same number, since the
    // choices made from it must agree. Nodes that do not know theirs do
    // not count; if none does, 0.
    const double rank_share = Utilities::MPI::min(
      node_memory > 0
        ? node_memory / Utilities::MPI::n_mpi_processes(node_communicator)
        : std::numeric_limits<double>::max(),
      communicator);
    memory_per_rank
      = rank_share < std::numeric_limits<double>::max() ? rank_share : 0;
    MPI_Comm_free(&node_communicator);
    // The node that lacks most; without /proc/meminfo (not Linux) there is
    // nothing to compare with.
    const double shortfall
      = Utilities::MPI::max(node_memory > 0
                              ? std::max(setup_need, run_need) - node_memory
                              : -1.,
                            communicator);
    if (shortfall <= 0)
      return;

    std::ostringstream message;
    message << std::setprecision(3) << "Invalid parameter <"
            << (parameters.mesh_file.empty() ? "Subdivisions" : "Mesh file")
            << "> in subsection <Geometry>: value <"
            << (parameters.mesh_file.empty()
                  ? std::to_string(parameters.subdivisions)
                  : parameters.mesh_file)
            << ">";
    if (parameters.global_refinements > 0)
      message << " with <Global refinements> = "
              << parameters.global_refinements;
    message << "; the mesh would have about " << dofs
            << " displacement dofs and need at least " << rank_bytes / 1e9
            << " GB of memory per rank (" << n_ranks
            << (n_ranks == 1 ? " rank)" : " ranks)");
    if (simplex)
      message << ", and " << root_bytes / 1e9
              << " GB on each group root while it builds the whole mesh "
                 "(<Mesh group size>)";
    message << "; a compute node of this run lacks " << shortfall / 1e9
            << " GB; accepted: a mesh that fits (fewer "
            << (parameters.mesh_file.empty() ? "Subdivisions or " : "")
            << "Global refinements, or more nodes).";
    AssertThrow(false, ExcMessage(message.str()));
  }



  // @sect4{RunPlan::choose_initial_cycles}
  //
  // Initial cycles = auto. Nested iteration pays where an active-set
  // iteration is a Krylov solve on the whole mesh (the full space and
  // matrix-free back ends): a cold first step takes 9 to 12 of them on the
  // fine mesh and 2 after the cycles, whose meshes cost a quarter (an eighth
  // in 3D) of the next one (doc/performance.md, "Nested iteration"). With
  // the condensed back end an iteration is a dense solve on the contact
  // nodes, and the coarse meshes' set-ups cost what the cycles save. So the
  // cycles run when the cost model expects an iterative back end for the
  // parameter file's mesh (from estimate_scene(); the back end of each mesh
  // is chosen again from its own size), down to a mesh of about 2000 dofs
  // (below that a cold step is cheap anyway) and at most 4 levels. None on a
  // resumed run (its first step is not a cold start), without contact, and
  // where the cycles' meshes would not be the parameter file's mesh
  // coarsened: graded and adaptive meshes, convergence studies.
  template <int dim>
  void
  RunPlan<dim>::choose_initial_cycles()
  {
    if (const std::optional<unsigned int> set = parameters.initial_cycles())
      {
        // A resumed simplex run starts on the checkpoint's mesh, the last
        // of the cycles, which the parameter file describes (p4est meshes
        // are rebuilt from the first one: Checkpoints::restore_mesh()).
        first_step_cycles
          = (parameters.resume
             && parameters.cell_type != Parameters::CellType::hypercube)
              ? 0
              : *set;
        return;
      }
    first_step_cycles = 0;
    if (parameters.resume || parameters.used_contact_zones().empty())
      return;
    if (parameters.adaptive_refinement
        || parameters.initial_refinement
             != Parameters::InitialRefinement::global)
      {
        initial_reason = "the mesh adapts; set Initial cycles to run "
                         "them";
        return;
      }
    if (parameters.cell_type == Parameters::CellType::mixed)
      {
        initial_reason = "the coarser meshes carry one element, and the "
                         "mesh has two (Cell type = mixed)";
        return;
      }
    if (parameters.contact_refinements > 0
        || parameters.uniform_coarsenings() == 0)
      {
        initial_reason = "they need a mesh that can be coarsened "
                         "uniformly (Global refinements, or a "
                         "generated box with even Subdivisions, no "
                         "Contact refinement levels)";
        return;
      }
    double    cells = 0;
    SceneSize scene = estimate_scene(cells);
    // The iterative back ends' estimate with the cycles they would run.
    scene.nested_iteration    = true;
    const MethodChoice choice = choose_method(parameters.method, scene);
    if (choice.method == Parameters::Method::condensed)
      {
        initial_reason = "the condensed back end is expected, whose "
                         "active-set iterations are dense solves on the "
                         "contact nodes";
        return;
      }
    const unsigned int most_levels
      = std::min(parameters.uniform_coarsenings(), 4u);
    while (first_step_cycles < most_levels
           && scene.dofs / std::pow(2., dim * (first_step_cycles + 1)) >= 2000)
      ++first_step_cycles;
    if (first_step_cycles == 0)
      {
        initial_reason = "a coarser mesh would have fewer than about "
                         "2000 dofs, where a cold step is cheap";
        return;
      }
    initial_reason
      = "the "
        + std::string(choice.method == Parameters::Method::matrix_free
                        ? "matrix-free"
                        : "full space")
        + " back end is expected, and the coarsest mesh "
          "keeps about 2000 dofs or more";
  }



  // @sect4{RunPlan::step_cycles_dropped}
  //
  // Step cycles = auto chose them from the cost model's estimate of the
  // scene, but Method = auto chose the condensed back end for the mesh of the
  // run from its actual size: then none run.
  template <int dim>
  bool
  RunPlan<dim>::step_cycles_dropped() const
  {
    return n_step_cycles > 0 && !parameters.step_cycles().has_value()
           && method.method == Parameters::Method::condensed;
  }



  // @sect4{RunPlan::choose_step_cycles}
  //
  // Step cycles = auto. As for the initial cycles, the coarser solve pays
  // where an active-set iteration is a Krylov solve on the whole mesh, and
  // only on large meshes. On the cube at k = 1/32 one coarser mesh took the
  // eight steps in which the contact zone forms from 3.5 to 2.5 active-set
  // iterations per step at 353k dofs and from 4.1 to 2.9 at 824k, 1.2 and
  // 1.35 times faster (doc/performance.md, "Step cycles"); but over the
  // shipped run's 32 steps, most of them after the zone formed, where the
  // predicted start is right and the coarser solve is pure cost, they were
  // 6 to 8% slower at 20k, 47k and 108k dofs. So auto takes a coarser mesh
  // where it keeps 40000 dofs or more (320k on the mesh of the run in 3D),
  // and only one: a second saved no further iteration. None with the
  // condensed back end (an iteration is a dense solve on the contact
  // nodes), and none where the coarser problem would not be the step
  // problem restricted (see
  // Parameters::AllParameters::check_step_cycles()). None with friction:
  // on the cube with Coulomb friction (mu = 0.3, k = 1/32, 8 steps) they
  // took 5.88 and 8.00 active-set iterations per step at 15k and 108k dofs
  // against 5.88 and 7.38 without, where the stick/slip changes, not the
  // front, make the iterations (doc/performance.md, "Step cycles"). None
  // with a law with a history, where they run when asked for but were not
  // timed. None on simplices: on
  // the tetrahedral cube refined once the prolongated zone was wrong at
  // more nodes, and the iterations fell by a fifth only (27 to 23 at 108k
  // dofs, 31 to 25 at 353k), for no gain in time.
  template <int dim>
  void
  RunPlan<dim>::choose_step_cycles(const bool simplex)
  {
    constexpr unsigned int smallest_coarser_dofs = 40000;
    const std::string      smallest = std::to_string(smallest_coarser_dofs);
    if (const std::optional<unsigned int> set = parameters.step_cycles())
      {
        n_step_cycles = *set;
        return;
      }
    n_step_cycles = 0;
    if (parameters.used_contact_zones().empty() || parameters.study_enabled)
      return;
    const auto frictional = [](const Parameters::ContactZone &zone) {
      return zone.contact->tangential_law
             != Parameters::TangentialLawType::frictionless;
    };
    const auto zones = parameters.used_contact_zones();
    if (simplex)
      step_reason = "on simplices they saved a fifth of the "
                    "iterations and no time where measured; set "
                    "Step cycles to run them";
    else if (parameters.adaptive_refinement
             || parameters.contact_refinements > 0
             || parameters.nested_coarsenings() == 0
             || (first_step_cycles > 0
                 && parameters.initial_refinement
                      == Parameters::InitialRefinement::adaptive))
      step_reason = "they need a mesh that can be coarsened uniformly "
                    "(Global refinements, or a generated box with "
                    "even Subdivisions, no Contact refinement levels, "
                    "no Adaptive refinement or adaptive Initial "
                    "refinement)";
    else if (parameters.implicit_update())
      step_reason = "the implicit update";
    else if (std::any_of(zones.begin(), zones.end(), frictional))
      step_reason = "friction: on the frictional cube they saved no "
                    "active-set iteration; set Step cycles to run them";
    else if (std::any_of(zones.begin(),
                         zones.end(),
                         [](const Parameters::ContactZone &zone) {
                           return !zone.contact->memory_weights.empty()
                                  || zone.contact->adhesion_stiffness > 0
                                  || zone.contact->cohesive_strength > 0;
                         }))
      step_reason = "a contact law with a history: not measured with it; "
                    "set Step cycles to run them";
    if (!step_reason.empty())
      return;
    double    cells           = 0;
    SceneSize scene           = estimate_scene(cells);
    scene.nested_iteration    = first_step_cycles > 0;
    const MethodChoice choice = choose_method(parameters.method, scene);
    if (choice.method == Parameters::Method::condensed)
      step_reason = "the condensed back end is expected, whose "
                    "active-set iterations are dense solves on the "
                    "contact nodes";
    else if (scene.dofs / std::pow(2., dim) < smallest_coarser_dofs)
      step_reason = "the coarser mesh would have fewer than " + smallest
                    + " dofs; below that they cost more in the steps "
                      "after the contact zone formed than they save "
                      "while it forms";
    else
      {
        n_step_cycles = 1;
        step_reason
          = "the "
            + std::string(choice.method == Parameters::Method::matrix_free
                            ? "matrix-free"
                            : "full space")
            + " back end is expected, and the coarser mesh keeps " + smallest
            + " dofs or more";
      }
  }



  // @sect4{RunPlan::choose_back_end}
  //
  // Method = auto on a mesh: the cost model with the mesh's size. Every mesh
  // after the first of the initial cycles has its cold step warm-started;
  // cycles of adaptive meshes may stop early, on a mesh that then runs
  // every step, so their meshes are costed for the whole run. The mesh of
  // the run holds the coarser problems of the step cycles too.
  template <int dim>
  void
  RunPlan<dim>::choose_back_end(const double       dofs,
                                const double       contact_nodes,
                                const double       contact_fraction,
                                const double       steps_left,
                                const bool         cycle_mesh,
                                const unsigned int initial_cycles_done)
  {
    SceneSize scene        = scene_of_run();
    scene.dofs             = dofs;
    scene.contact_nodes    = contact_nodes;
    scene.contact_fraction = contact_fraction;
    if (steps_left > 0)
      scene.steps = steps_left;
    if (cycle_mesh)
      scene.steps = 1;
    scene.nested_iteration
      = first_step_cycles > 0 && (!cycle_mesh || initial_cycles_done > 0);
    scene.step_cycles = cycle_mesh ? 0 : n_step_cycles;
    method            = choose_method(parameters.method, scene);
  }



  // @sect4{RunPlan::check_output_volume}
  //
  // Before anything is written: do the .vtu records of the run fit on the
  // disk? Their size follows from the mesh: deal.II writes every field at
  // every vertex of every cell (3 coordinates, the displacement, two stress
  // tensors, five scalar fields and the contact status, as 4-byte floats),
  // plus the connectivity. zlib compresses that by a factor 1.5 to 3 on
  // these fields; a quarter of the raw size is taken as a lower estimate, so
  // that only output that certainly does not fit is refused. With adaptive
  // steps the number of records is not known before the run.
  template <int dim>
  void
  RunPlan<dim>::check_output_volume(const double        n_cells,
                                    const unsigned int  n_cell_vertices,
                                    const std::uint64_t n_steps) const
  {
    if (!parameters.write_vtu
        || parameters.time_step_control
             == Parameters::TimeStepControl::adaptive)
      return;
    const double records
      = 2 + std::floor(n_steps / double(parameters.interval));
    const double cells     = n_cells;
    const double per_point = 3 + dim + dim * (dim + 1) + 6;
    const double raw_bytes
      = cells * n_cell_vertices * (4 * per_point + 8) + 9 * cells;
    const double bytes = records * raw_bytes / 4;

    std::string problem;
    if (Utilities::MPI::this_mpi_process(communicator) == 0)
      {
        // The file system of the folder, or of its nearest existing parent.
        std::filesystem::path folder
          = std::filesystem::absolute(parameters.directory);
        std::error_code error;
        while (!std::filesystem::exists(folder, error)
               && folder.has_parent_path() && folder != folder.parent_path())
          folder = folder.parent_path();
        struct statvfs status;
        if (::statvfs(folder.c_str(), &status) == 0)
          {
            const double available
              = double(status.f_bavail) * double(status.f_frsize);
            if (bytes > available)
              {
                std::ostringstream message;
                message << std::setprecision(3)
                        << "Invalid parameter <Output interval> in subsection "
                           "<Output>: value <"
                        << parameters.interval
                        << ">; with Time step = " << parameters.time_step
                        << " and End time = " << parameters.end_time
                        << " the run writes " << records
                        << " .vtu records of at least " << raw_bytes / 4e6
                        << " MB each, " << bytes / 1e9
                        << " GB, but the file system of <"
                        << parameters.directory << "> has " << available / 1e9
                        << " GB free; accepted: output that fits (a larger "
                           "Output interval, or Write vtu = false).";
                problem = message.str();
              }
          }
      }
    FileOutput::agree_on_problem(problem, communicator);
  }



  // @sect4{RunPlan::check_step_count}
  //
  // Adaptive steps and cut steps make schedules whose length is only known
  // as the run goes; they are held to the same bounds as fixed schedules.
  // Every rank has the same n, so all ranks throw together.
  template <int dim>
  void
  RunPlan<dim>::check_step_count(const unsigned int n, const double time) const
  {
    std::ostringstream message;
    message << std::setprecision(6);
    if (n > parameters.max_steps)
      message << "Invalid parameter <Maximum number of steps> in subsection "
                 "<Time>: value <"
              << parameters.max_steps << ">; step " << n
              << " (from t = " << time
              << ") would exceed it before End time = " << parameters.end_time
              << "; accepted: a bound the run reaches End time within (a "
                 "larger Maximum number of steps, or for adaptive steps a "
                 "larger Error tolerance or Minimum time step).";
    else if (parameters.write_vtu
             && 2 + n / parameters.interval > Parameters::max_output_records)
      message << "Invalid parameter <Output interval> in subsection "
                 "<Output>: value <"
              << parameters.interval << ">; step " << n
              << " would write more than " << Parameters::max_output_records
              << " .vtu records; accepted: at most "
              << Parameters::max_output_records
              << " records in a run (a larger Output interval, or Write vtu "
                 "= false).";
    AssertThrow(message.str().empty(), ExcMessage(message.str()));
  }



  template class RunPlan<2>;
  template class RunPlan<3>;
} // namespace ViscoContact
