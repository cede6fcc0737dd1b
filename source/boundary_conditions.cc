// ViscoplasticContact<dim>: the prescribed displacements of each step and
// the reactions of the parts that carry them (the dofs, values and sums are
// PrescribedDisplacements', scene/prescribed_displacements.h), and the gaps of
// the contact nodes.

#include <deal.II/base/exceptions.h>
#include <deal.II/base/mpi.h>

#include <deal.II/lac/vector.h>

#include <deal.II/hp/fe_values.h>

#include "robustness/file_output.h"
#include "time_schedule.h"
#include "viscoplastic_contact.h"

#include <algorithm>
#include <cstdint>

namespace ViscoContact
{
  // @sect4{ViscoplasticContact::check_scene_values}
  //
  // A load, a prescribed value or a gap that is not finite somewhere (1/0,
  // sqrt(t - 0.5) at t = 0) would only show as a displacement that is not
  // finite in some step, after files have been written and without naming
  // the entry. So before anything is written: every load at the points the
  // assembly evaluates (Loads::first_non_finite_value()), every prescribed
  // value at the dofs of its part, and the obstacle's gap at the contact
  // nodes, at the times of the run (the levels of Time step and End time; at
  // a stride beyond about 2e7 evaluations per rank). The message names the
  // entry, the point and the time, on every rank; the loads are decided
  // first.
  template <int dim>
  void
  ViscoplasticContact<dim>::check_scene_values()
  {
    FileOutput::agree_on_problem(
      loads.first_non_finite_value(stress_points.cells(),
                                   discretisation.mapping,
                                   discretisation.fe,
                                   discretisation.load_quadrature,
                                   discretisation.face_quadrature,
                                   schedule),
      mpi_communicator);
    std::string problem = prescribed.first_non_finite_value(schedule);
    // The obstacle's gap at the contact nodes, at every level (or every
    // stride-th on long runs with many nodes), then again at the current
    // time.
    if (contact_zones.has_gap() && contact_enabled)
      {
        const std::uint64_t n_gap_levels
          = contact_zones.gap_depends_on_time() ? schedule.n_grid_levels() : 1;
        const std::uint64_t gap_stride
          = std::max<std::uint64_t>(1,
                                    std::uint64_t(double(contact_set.size())
                                                  * n_gap_levels / 2e7));
        for (std::uint64_t m = 0; m < n_gap_levels && problem.empty();
             m += gap_stride)
          problem = contact_set.set_gaps(contact_zones.gaps(),
                                         schedule.grid_level(m));
        if (problem.empty())
          problem = contact_set.set_gaps(contact_zones.gaps(),
                                         schedule.current_time());
      }
    FileOutput::agree_on_problem(problem, mpi_communicator);
  }



  // @sect4{ViscoplasticContact::set_dirichlet_values}
  //
  // g_n at time, and for the explicit update the lifting load with the
  // elasticity of each cell's material. The implicit update's Newton
  // iteration has g_n in its iterate, and so in its internal force: it needs
  // no lifting load.
  template <int dim>
  void
  ViscoplasticContact<dim>::set_dirichlet_values(const double time)
  {
    if (!prescribed.has_values())
      return;
    TimerOutput::Scope t(report.timer(), "Assemble prescribed displacement");
    prescribed.set_time(
      time,
      !parameters.implicit_update(),
      [this](const unsigned int k) -> const SymmetricTensor<4, dim> & {
        return materials.of_cell(k).elasticity_tensor();
      });
  }



  // @sect4{ViscoplasticContact::set_gaps}
  template <int dim>
  void
  ViscoplasticContact<dim>::set_gaps(const double time)
  {
    if (!contact_zones.has_gap() || !contact_enabled)
      return;
    FileOutput::agree_on_problem(contact_set.set_gaps(contact_zones.gaps(),
                                                      time),
                                 mpi_communicator);
  }


  // @sect4{ViscoplasticContact::reaction_forces}
  //
  // The force a Dirichlet part exerts on the body is the residual of the
  // equilibrium equations at its dofs, (sigma_n, eps(v)) - (f_n, v). The
  // cells around the Dirichlet dofs add their terms without the constraints
  // (which would drop exactly these rows), into the ghosts too; the owners
  // sum them, and PrescribedDisplacements::reactions() sums the parts.
  template <int dim>
  std::vector<Tensor<1, dim>>
  ViscoplasticContact<dim>::reaction_forces(const double time)
  {
    std::vector<Tensor<1, dim>> forces(prescribed.n_reactions());
    if (forces.empty())
      return forces;
    VectorType residual(solution);
    residual                    = 0;
    const unsigned int  n_q     = discretisation.n_stress_points();
    const unsigned int  n_local = stress_points.n_vertices() * dim;
    std::vector<double> cell_vector(n_local);
    Vector<double>      cell_load;
    LoadValues<dim>     load_values(discretisation);
    loads.set_time(time);
    std::string problem;
    double     *values = residual.get_values(); // owned entries, then ghosts
    for (const unsigned int k : prescribed.reaction_cells())
      {
        std::fill(cell_vector.begin(), cell_vector.end(), 0.);
        for (unsigned int q = 0; q < n_q; ++q)
          stress_points.add_load(
            quadrature_point_history[std::size_t(k) * n_q + q].stress,
            k,
            q,
            make_array_view(cell_vector));
        const auto &cell = stress_points.cells()[k];
        if (loads.cell_load(cell,
                            load_values.cell,
                            load_values.face,
                            cell_load,
                            problem))
          for (unsigned int a = 0; a < cell->n_vertices(); ++a)
            for (unsigned int c = 0; c < dim; ++c)
              cell_vector[a * dim + c]
                -= cell_load(cell->get_fe().component_to_system_index(c, a));
        for (unsigned int i = 0; i < n_local; ++i)
          values[stress_points.local_dofs(k)[i]] += cell_vector[i];
      }
    residual.compress(VectorOperation::add);
    FileOutput::agree_on_problem(problem, mpi_communicator);
    return prescribed.reactions(residual,
                                contact_enabled ? &contact_set : nullptr);
  }



  template class ViscoplasticContact<2>;
  template class ViscoplasticContact<3>;
} // namespace ViscoContact
