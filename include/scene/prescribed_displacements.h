#ifndef viscoplastic_contact_prescribed_displacements_h
#define viscoplastic_contact_prescribed_displacements_h

#include <deal.II/base/index_set.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/point.h>
#include <deal.II/base/smartpointer.h>
#include <deal.II/base/symmetric_tensor.h>
#include <deal.II/base/tensor.h>

#include <deal.II/dofs/dof_handler.h>

#include <deal.II/hp/mapping_collection.h>

#include <deal.II/lac/affine_constraints.h>

#include "back_ends/linear_algebra.h"
#include "contact_set.h"
#include "scene/dirichlet_parts.h"
#include "parameters.h"
#include "stress_points.h"
#include "time_schedule.h"

#include <array>
#include <functional>
#include <string>
#include <utility>
#include <vector>

namespace ViscoContact
{
  using namespace dealii;

  // @sect3{Prescribed displacements and their reactions}
  //
  // The Dirichlet parts of the scene (clamped, or a displacement prescribed
  // in some components as a function of x and t) and the planes of symmetry:
  // their constraints, their values g_n in each step, and the forces they
  // exert on the body.
  //
  // A prescribed displacement g_n does not change which dofs are
  // constrained, only their values. So K is assembled and factorised once,
  // with the homogeneous constraints (u_D = 0), and every step splits u_n =
  // u_0 + g_n: g_n carries the prescribed values (and the hanging nodes and
  // symmetry constraints that depend on them), u_0 solves the step problem
  // with the right-hand side b_n - K g_n. K assembled with the constraints
  // has lost its columns of the Dirichlet dofs, so K g_n is not a product
  // with K: it is the lifting load (E eps(g_n), eps(v)), integrated over the
  // cells where g_n is not zero, at the stress points (the quadrature K was
  // assembled with, so that the two are the same bilinear form).
  template <int dim>
  class PrescribedDisplacements
  {
  public:
    explicit PrescribedDisplacements(
      const Parameters::AllParameters &parameters,
      const MPI_Comm                   communicator = MPI_COMM_WORLD);

    const DirichletParts<dim> &
    parts() const
    {
      return dirichlet;
    }
    // Whether any part prescribes a value that is not zero (else u = u_0
    // and there is no lifting).
    bool
    has_values() const
    {
      return dirichlet.has_values();
    }

    // @sect4{Per mesh}
    //
    // The homogeneous constraints of the displacement (the Dirichlet parts,
    // the planes of symmetry, the hanging nodes), kept open for the values of
    // each step.
    void
    make_constraints(const hp::MappingCollection<dim> &mapping,
                     const DoFHandler<dim>            &dof_handler,
                     const IndexSet                   &locally_relevant_dofs,
                     AffineConstraints<double>        &constraints);
    // A scene whose constraints leave a rigid motion of a body free (of
    // each connected component of the mesh) is refused on every rank,
    // naming the bodies and the motions (collective).
    void
    check_rigid_motions(const hp::MappingCollection<dim> &mapping,
                        const DoFHandler<dim>            &dof_handler,
                        const AffineConstraints<double>  &constraints) const;
    // The owned and ghost dofs of every part with their support points, the
    // owned vertices of the planes of symmetry, and the owned cells the
    // lifting and the reactions integrate over (collective). layout gives
    // the partition of the displacement vectors.
    void
    reinit(const hp::MappingCollection<dim> &mapping,
           const DoFHandler<dim>            &dof_handler,
           const IndexSet                   &locally_relevant_dofs,
           const StressPointGeometry<dim>   &stress_points,
           const VectorType                 &layout);
    // The hanging nodes alone (the contact nodes and the transfers of
    // nodal fields need them apart from the Dirichlet constraints).
    const AffineConstraints<double> &
    hanging_node_constraints() const
    {
      return hanging_nodes;
    }

    // @sect4{Per step}
    //
    // g_n at time and, with_lifting, the lifting load -(E eps(g_n), eps(v))
    // (elasticity(k) the tensor of owned cell k). A value that is not finite
    // stops all ranks, naming the entry, the point and the time. Values that
    // do not depend on t are set once per mesh. Nothing to do without values.
    void
    set_time(
      const double time,
      const bool   with_lifting,
      const std::function<const SymmetricTensor<4, dim> &(const unsigned int k)>
        &elasticity);
    const VectorType &
    lifting_load() const
    {
      return lifting;
    }
    // u's constrained entries from its free ones: hanging nodes, symmetry
    // constraints and the values g_n; homogeneous the constraints without
    // values. The caller updates the ghosts.
    void
    distribute(VectorType                      &u,
               const AffineConstraints<double> &homogeneous) const;
    // The first prescribed value that is not finite at the levels of the
    // schedule's grid (at a stride beyond about 2e7 evaluations per rank),
    // as a message naming the entry, the point and the time; else empty.
    std::string
    first_non_finite_value(const TimeSchedule &schedule) const;

    // @sect4{Reactions}
    //
    // The names of the reactions: every Dirichlet part ("clamped",
    // "prescribed_N"), then every plane of symmetry ("symmetry_ID").
    std::vector<std::string>
    reaction_names() const;
    unsigned int
    n_reactions() const
    {
      return dirichlet.size() + symmetry_ids.size();
    }
    // The owned cells (stress-point numbering k) whose residual the
    // reactions need.
    const std::vector<unsigned int> &
    reaction_cells() const
    {
      return reaction_cells_;
    }
    // The forces of the parts and planes from the residual of equilibrium
    // (sigma_n, eps(v)) - (f_n, v) of the reaction cells, added without
    // constraints into the owned and ghost entries and compressed; contact
    // the contact forces to take out at the vertices of the planes (nullptr
    // without contact). The residual is changed. Collective.
    std::vector<Tensor<1, dim>>
    reactions(VectorType &residual, const ContactSet<dim> *contact) const;

  private:
    void
    setup_roller_vertices(const hp::MappingCollection<dim>  &mapping,
                          const DoFHandler<dim>             &dof_handler,
                          const std::vector<bool>           &dirichlet_dof,
                          const Utilities::MPI::Partitioner &partitioner);
    void
    add_roller_reactions(VectorType                      &residual,
                         const ContactSet<dim>           *contact,
                         const ArrayView<Tensor<1, dim>> &plane_forces) const;

    const MPI_Comm                        communicator;
    const DirichletParts<dim>             dirichlet;
    const std::vector<types::boundary_id> symmetry_ids;

    // With values: the constraints before closing, and closed with the
    // values of the current step, which give the constrained entries of u.
    AffineConstraints<double> open_constraints;
    AffineConstraints<double> current_constraints;
    // Whether set_time() has set the values on this mesh (the same on every
    // rank).
    bool                      values_set = false;
    AffineConstraints<double> hanging_nodes;

    // The locally relevant dofs of the parts (a dof belongs to the first part
    // that constrains it; the values of ghost dofs enter the constraints of
    // owned hanging nodes).
    struct DirichletDof
    {
      types::global_dof_index index;
      unsigned int            local_index; // into the vectors' storage
      bool                    owned;
      unsigned int            part;
      unsigned int            component;
      Point<dim>              location;
    };
    std::vector<DirichletDof> dirichlet_dofs;
    // The owned vertices on the planes of symmetry (rollers): the vertex's
    // dofs (local storage), the components a Dirichlet part takes (its
    // reaction has them), and the planes it lies on (indices into
    // symmetry_ids and symmetry_normals).
    struct RollerVertex
    {
      std::array<unsigned int, dim> local_dofs;
      std::array<bool, dim>         dirichlet;
      std::vector<unsigned int>     planes;
    };
    std::vector<RollerVertex>   roller_vertices;
    std::vector<Tensor<1, dim>> symmetry_normals;

    SmartPointer<const StressPointGeometry<dim>> stress_points;
    std::vector<unsigned int>                    lifting_cells;
    std::vector<unsigned int>                    reaction_cells_;
    // g_n (with ghosts) and -(E eps(g_n), eps(v)) (owned entries).
    VectorType dirichlet_values;
    VectorType lifting;
  };
} // namespace ViscoContact

#endif
