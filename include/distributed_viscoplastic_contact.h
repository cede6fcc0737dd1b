#ifndef viscoplastic_contact_distributed_viscoplastic_contact_h
#define viscoplastic_contact_distributed_viscoplastic_contact_h

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/function_parser.h>
#include <deal.II/base/index_set.h>
#include <deal.II/base/quadrature.h>
#include <deal.II/base/timer.h>

#include <deal.II/distributed/tria_base.h>

#include <deal.II/dofs/dof_handler.h>

#include <deal.II/fe/fe.h>
#include <deal.II/fe/mapping.h>

#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/trilinos_precondition.h>
#include <deal.II/lac/trilinos_solver.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>

#include "active_set_solver.h"
#include "contact_law.h"
#include "material.h"
#include "parameters.h"

#include <array>
#include <fstream>
#include <memory>
#include <optional>
#include <string>
#include <vector>

class Epetra_MultiVector;

namespace ViscoContact
{
  using namespace dealii;

  // A contact node owned by this MPI rank: its dofs, the outward normal nu,
  // the lumped weight w, the active-set parameter c, its piece of the
  // contact law, and the normal displacement r = u.nu and nodal normal
  // force z of the last solve.
  template <int dim>
  struct DistributedContactNode
  {
    Point<dim>                               location;
    Tensor<1, dim>                           normal;
    double                                   weight;
    double                                   c;
    std::array<types::global_dof_index, dim> dofs;
    unsigned int                             piece = 0;
    double                                   r     = 0;
    double                                   z     = 0;
  };

  // @sect3{The DistributedViscoplasticContact class}
  //
  // The same algorithm as ViscoplasticContact<dim> (model.md, section 2:
  // per step the right-hand side, the active-set solve, the explicit stress
  // update, output), built for many MPI ranks as step-40 and step-42 are:
  //  - the mesh is a p4est mesh (quadrilaterals, hexahedra) or a fully
  //    distributed one (triangles, tetrahedra; p4est cannot hold them);
  //  - the elastic operator K is a Trilinos matrix, assembled once, and its
  //    preconditioner (ML smoothed aggregation with the rigid-body modes, or
  //    a MUMPS factorisation) is built once per run;
  //  - the active set works in the full space: each iteration solves the
  //    step problem on the current pieces by CG on the operator
  //      P (K + N^T D N) P + (I - P),
  //    where P removes the normal component at the nodes on vertical pieces
  //    (u.nu fixed: a constraint among the components of a node, for any
  //    normal) and D holds w s at the nodes on sloped pieces. The operator
  //    is applied matrix-free around K, so K and its preconditioner never
  //    change;
  //  - every loop runs over locally owned cells and nodes; only scalars are
  //    reduced across ranks; output is one .pvtu per step.
  template <int dim>
  class DistributedViscoplasticContact
  {
  public:
    explicit DistributedViscoplasticContact(
      const Parameters::AllParameters &parameters);
    ~DistributedViscoplasticContact();

    void
    run();

  private:
    // Setup.
    void
    make_grid();
    void
    setup_system();
    void
    assemble_elastic_operator();
    void
    setup_preconditioner();
    void
    setup_contact();
    void
    setup_stress_points();
    double
    time_reference_elastic_solve();

    // One time step.
    void
    assemble_external_load(const double time);
    void
    assemble_history_load();
    ContactActiveSetSolver::Result
    solve_step_with_recovery(const unsigned int n, std::vector<double> &times);
    ContactActiveSetSolver::Result
    solve_time_step();
    void
    rescale_history_increment(const double old_step, const double new_step);
    void
    apply_preconditioner(TrilinosWrappers::MPI::Vector       &dst,
                         const TrilinosWrappers::MPI::Vector &src) const;
    unsigned int
    solve_step_problem(const TrilinosWrappers::MPI::Vector &rhs,
                       TrilinosWrappers::MPI::Vector       &displacement);
    void
    update_stresses(const double next_time_step);

    // Output.
    void
    prepare_output_directory();
    void
    output_results(const unsigned int step,
                   const double       time,
                   const std::string &stem = "solution");

    // Checkpoints (checkpoint.h), keyed by cell id and node location.
    void
    write_checkpoint(const unsigned int         step,
                     const std::vector<double> &times,
                     const double               wall_time);
    unsigned int
    resume_from_checkpoint(std::vector<double> &times);
    std::array<unsigned int, 3>
    count_contact_states() const;
    double
    total_contact_force() const;
    void
    print_run_summary(const double reference_solve_time);

    // Run control, console and timing.
    MPI_Comm                        mpi_communicator;
    const Parameters::AllParameters parameters;
    ConditionalOStream              pcout;
    TimerOutput                     computing_timer;

    // Mesh, finite element, quadratures, degrees of freedom.
    std::unique_ptr<parallel::DistributedTriangulationBase<dim>> triangulation;
    ReferenceCell                                                reference_cell;
    const Mapping<dim>                                          *mapping;
    std::unique_ptr<FiniteElement<dim>>                          fe;
    DoFHandler<dim>                                              dof_handler;
    Quadrature<dim>           stress_quadrature;
    Quadrature<dim>           load_quadrature;
    Quadrature<dim - 1>       face_quadrature;
    IndexSet                  locally_owned_dofs;
    IndexSet                  locally_relevant_dofs;
    AffineConstraints<double> constraints;

    // The elastic operator and its preconditioner, built once per run.
    TrilinosWrappers::SparseMatrix                  stiffness_matrix;
    TrilinosWrappers::PreconditionAMG               amg_preconditioner;
    std::unique_ptr<Epetra_MultiVector>             rigid_body_modes;
    SolverControl                                   direct_solver_control;
    std::unique_ptr<TrilinosWrappers::SolverDirect> direct_solver;
    unsigned int                                    n_operator_assemblies   = 0;
    unsigned int                                    n_preconditioner_setups = 0;
    unsigned int                                    total_cg_iterations     = 0;
    unsigned int                                    n_cg_solves             = 0;
    std::string cg_failure; // why the last CG solve failed, if it did

    // Vectors: u_n (owned and ghosted), f_n, -(H_n, eps(v)), their sum.
    TrilinosWrappers::MPI::Vector solution;
    TrilinosWrappers::MPI::Vector ghosted_solution;
    TrilinosWrappers::MPI::Vector external_load;
    TrilinosWrappers::MPI::Vector history_load;
    TrilinosWrappers::MPI::Vector system_rhs;

    // Material, loads, and the state at the stress points of the locally
    // owned cells (indexed by active cell index).
    PerzynaMaterial<dim>                     material;
    FunctionParser<dim>                      body_force;
    FunctionParser<dim>                      surface_traction;
    bool                                     loads_depend_on_time;
    bool                                     external_load_assembled = false;
    std::vector<QuadraturePointHistory<dim>> quadrature_point_history;
    double                                   max_von_mises = 0;

    // Contact: the law and the locally owned contact nodes.
    bool                                     contact_enabled = false;
    std::optional<ContactLaw>                contact_law;
    std::vector<DistributedContactNode<dim>> contact_nodes;
    types::global_dof_index                  n_global_contact_nodes      = 0;
    unsigned int                             total_active_set_iterations = 0;

    // Output records.
    std::vector<std::pair<double, std::string>> times_and_names;
    std::ofstream                               time_series;
    double                                      time_loop_compute_time = 0;
    unsigned int                                n_time_steps           = 0;
    double       loop_time_offset     = 0; // of the run a resumed run continues
    unsigned int last_checkpoint_step = numbers::invalid_unsigned_int;
  };
} // namespace ViscoContact

#endif
