#ifndef viscoplastic_contact_viscoplastic_contact_h
#define viscoplastic_contact_viscoplastic_contact_h

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/function_parser.h>
#include <deal.II/base/quadrature.h>
#include <deal.II/base/symmetric_tensor.h>
#include <deal.II/base/timer.h>

#include <deal.II/dofs/dof_handler.h>

#include <deal.II/fe/fe.h>
#include <deal.II/fe/mapping.h>

#include <deal.II/grid/tria.h>

#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/lapack_full_matrix.h>
#include <deal.II/lac/sparse_direct.h>
#include <deal.II/lac/sparse_matrix.h>
#include <deal.II/lac/sparsity_pattern.h>
#include <deal.II/lac/vector.h>

#include "active_set_solver.h"
#include "material.h"
#include "parameters.h"
#include "sparse_cholesky.h"

#include <array>
#include <fstream>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace ViscoContact
{
  using namespace dealii;

  // A node of Gamma_3 that is free to move: its displacement dofs, the
  // outward normal nu (the weighted mean of the adjacent faces' normals) and
  // the lumped weight w = int_Gamma3 phi.
  template <int dim>
  struct ContactNode
  {
    Point<dim>                               location;
    Tensor<1, dim>                           normal;
    double                                   weight;
    std::array<types::global_dof_index, dim> dofs;
    types::global_dof_index                  scalar_dof;
  };

  // Lumped weights w_i = int_Gamma3 phi_i and mean outward normals of the
  // vertices on the given boundary parts, keyed by vertex index. Exposed for
  // the tests: the weights sum to the measure of Gamma_3.
  template <int dim>
  struct BoundaryVertexData
  {
    Point<dim>     location;
    Tensor<1, dim> normal;
    double         weight = 0;
  };

  template <int dim>
  std::map<unsigned int, BoundaryVertexData<dim>>
  lumped_boundary_weights(const Mapping<dim>        &mapping,
                          const DoFHandler<dim>     &dof_handler,
                          const Quadrature<dim - 1> &face_quadrature,
                          const std::vector<types::boundary_id> &boundary_ids);

  // @sect3{The ViscoplasticContact class}
  //
  // The program in the structure of step-18 (quasistatic time loop, history
  // at the stress points) and step-41/42 (active set on the contact nodes).
  // run() reads as the algorithm of model.md, section 2:
  //   setup; for n = 1..N: assemble the right-hand side,
  //   solve the contact problem by the active-set method,
  //   update the stresses and the history, write output.
  template <int dim>
  class ViscoplasticContact
  {
  public:
    explicit ViscoplasticContact(const Parameters::AllParameters &parameters);

    void
    run();

    // For studies that compare runs (the convergence study): a function
    // called after every time step with the step number and time, and read
    // access to the state it may inspect then.
    void
    set_step_observer(
      const std::function<void(const unsigned int, const double)> &observer);
    const Triangulation<dim> &
    get_triangulation() const;
    const DoFHandler<dim> &
    get_dof_handler() const;
    const Mapping<dim> &
    get_mapping() const;
    const Vector<double> &
    get_displacement() const;
    // sigma_n at the stress points of cell number active_cell_index.
    const SymmetricTensor<2, dim> &
    get_stress(const unsigned int active_cell_index,
               const unsigned int stress_point) const;

  private:
    // Setup.
    void
    make_grid();
    void
    setup_system();
    void
    assemble_elastic_operator();
    void
    setup_contact();
    void
    setup_quadrature_point_history();
    void
    report_scheme_limits() const;

    // One time step.
    void
    assemble_right_hand_side(const double time);
    void
    assemble_external_load(const double time);
    void
    assemble_history_load();
    ContactActiveSetSolver::Result
    solve_step_with_recovery(const unsigned int n, std::vector<double> &times);
    ContactActiveSetSolver::Result
    solve_time_step();
    ContactActiveSetSolver::Result
    solve_implicit_time_step(const double time_step);
    void
    rescale_history_increment(const double old_step, const double new_step);
    void
    assemble_tangent_system(const Vector<double> &displacement, const double a);
    bool
    implicit_newton(const double                    a,
                    Vector<double>                 &iterate,
                    ContactActiveSetSolver::Result &result);
    ContactActiveSetSolver::Result
    solve_contact_with(SparseDirectUMFPACK  &factorization,
                       const Vector<double> &rhs,
                       Vector<double>       &displacement);
    void
    update_stresses(const double current_time_step,
                    const double next_time_step);

    // Output.
    void
    prepare_output_directory();
    void
    output_results(const unsigned int step,
                   const double       time,
                   const std::string &stem = "solution");
    // Checkpoints (checkpoint.h): write after step n; read the last one and
    // return its step.
    void
    write_checkpoint(const unsigned int         step,
                     const std::vector<double> &times,
                     const double               wall_time);
    unsigned int
    resume_from_checkpoint(std::vector<double> &times);
    void
    write_contact_profile(const unsigned int step, const double time) const;
    void
    write_time_series_row(const unsigned int                    step,
                          const double                          time,
                          const ContactActiveSetSolver::Result &result,
                          const double                          wall_time);
    void
    print_run_summary();

    // Solves with the factorised elastic operator, one or n_columns
    // right-hand sides (column-major) at once.
    void
    solve_elastic(Vector<double> &rhs_and_solution);
    void
    solve_elastic(std::vector<double> &columns, const unsigned int n_columns);

    // Helpers.
    void
    subtract_stress_point_load(const SymmetricTensor<2, dim> &H,
                               const unsigned int             cell,
                               const unsigned int             q,
                               Vector<double>                &target) const;
    Tensor<2, dim>
    displacement_gradient_at(const Vector<double> &displacement,
                             const unsigned int    cell,
                             const unsigned int    q) const;
    std::array<unsigned int, 3>
    count_contact_states() const;
    unsigned int
    contact_status(const unsigned int node) const;
    double
    total_contact_force() const;

    // Run control, console and timing.
    const Parameters::AllParameters parameters;
    ConditionalOStream              pcout;
    TimerOutput                     computing_timer;

    // Mesh, finite element, quadratures, degrees of freedom.
    Triangulation<dim>                  triangulation;
    ReferenceCell                       reference_cell;
    const Mapping<dim>                 *mapping;
    std::unique_ptr<FiniteElement<dim>> fe;
    std::unique_ptr<FiniteElement<dim>> scalar_fe; // nodal output fields
    DoFHandler<dim>                     dof_handler;
    DoFHandler<dim>                     scalar_dof_handler;
    Quadrature<dim>                     stress_quadrature;
    Quadrature<dim>                     load_quadrature;
    Quadrature<dim - 1>                 face_quadrature;
    AffineConstraints<double>           constraints;

    // The elastic operator: assembled and factorised once per run.
    SparsityPattern      sparsity_pattern;
    SparseMatrix<double> stiffness_matrix;
    SparseCholesky       cholesky_factorization;
    // The implicit scheme's tangent stiffness, re-assembled and factorised
    // (LU: the consistent tangent is unsymmetric) per Newton iteration.
    SparseMatrix<double> tangent_matrix;
    SparseDirectUMFPACK  tangent_factorization;
    Vector<double>       internal_force;
    unsigned int         total_newton_iterations = 0;
    SparseDirectUMFPACK  lu_factorization;
    unsigned int         n_operator_assemblies      = 0;
    unsigned int         n_operator_factorizations  = 0;
    unsigned int         n_elastic_solves           = 0;
    unsigned int         n_external_load_assemblies = 0;

    // Vectors: the displacement u_n, the external load f_n, the history load
    // -(H_n, eps(v)) and their sum.
    Vector<double> solution;
    Vector<double> external_load;
    Vector<double> history_load;
    Vector<double> system_rhs;
    Vector<double>
      contact_response; // -(displacement due to the contact forces)

    // Material, loads and the state at the stress points.
    PerzynaMaterial<dim>                     material;
    FunctionParser<dim>                      body_force;
    FunctionParser<dim>                      surface_traction;
    bool                                     body_force_is_zero;
    bool                                     loads_depend_on_time;
    std::vector<QuadraturePointHistory<dim>> quadrature_point_history;
    double                                   max_von_mises = 0;

    // The geometry of the stress points, computed once (the mesh does not
    // move), so that the cell loops of the time loop need no FEValues: per
    // cell its dofs in the order (vertex a, component c), and per stress
    // point JxW and the gradients of the scalar shape functions N_a; the
    // strain is sym(sum_a u_a (x) grad N_a).
    unsigned int                         n_cell_vertices = 0;
    std::vector<types::global_dof_index> cell_dof_indices;
    std::vector<Tensor<1, dim>>          stress_point_gradients;
    std::vector<double>                  stress_point_JxW;

    // Contact: the nodes of Gamma_3 and the condensed active-set solver.
    bool                          contact_enabled;
    std::vector<ContactNode<dim>> contact_nodes;
    ContactActiveSetSolver        active_set_solver;
    // The smallest generalised eigenvalue of (stiffness, lumped normal
    // boundary mass), model.md section 4: the step problem is strongly
    // convex iff it exceeds the steepest softening of the contact law.
    double uniqueness_eigenvalue = 0;
    // W = K^{-1} N^T, the displacement response to unit normal forces at
    // the contact nodes (n_dofs x m, column-major), kept when it fits in
    // memory: then u = K^{-1} b - W z needs one solve per step, not two.
    LAPACKFullMatrix<double> contact_responses;
    bool                     contact_responses_stored    = false;
    unsigned int             total_active_set_iterations = 0;

    std::function<void(const unsigned int, const double)> step_observer;

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
