#ifndef viscoplastic_contact_test_scenes_h
#define viscoplastic_contact_test_scenes_h

// What several unit tests set up: parameters parsed from a text as main()
// reads a file, and the unit square with a contact zone on its bottom edge.

#include <deal.II/base/index_set.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/quadrature_lib.h>

#include <deal.II/distributed/tria.h>

#include <deal.II/dofs/dof_handler.h>
#include <deal.II/dofs/dof_tools.h>

#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/fe/mapping_q.h>

#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/grid_tools.h>

#include <deal.II/lac/affine_constraints.h>

#include "contact_set.h"
#include "parameters.h"

#include <string>

namespace ViscoContact
{
  namespace TestScenes
  {
    // The parameters of a text, the numbered subsections sized first (the
    // further contact zones as main() sizes them: at least one).
    inline Parameters::AllParameters
    parse_parameters(const std::string &text,
                     const unsigned int n_prescribed    = 0,
                     const unsigned int n_surface_loads = 0,
                     const unsigned int n_zones         = 1)
    {
      Parameters::AllParameters parameters;
      parameters.prescribed_displacements.resize(n_prescribed);
      parameters.surface_loads.resize(n_surface_loads);
      parameters.further_contact_zones.resize(n_zones);
      ParameterHandler prm;
      parameters.add_parameters(prm);
      prm.parse_input_from_string(text);
      parameters.check_parameters(prm);
      return parameters;
    }

    // The unit square turned by angle, refined twice, Q1, without
    // constraints, and one contact zone with the given entries on its
    // bottom edge (boundary id 2): 5 contact nodes.
    struct SquareWithContactZone
    {
      SquareWithContactZone(const Parameters::Contact &entries,
                            const double               angle = 0)
        : triangulation(MPI_COMM_WORLD)
        , fe(FE_Q<2>(1), 2)
        , scalar_fe(1)
      {
        GridGenerator::hyper_cube(triangulation, 0, 1, true);
        GridTools::rotate(angle, triangulation);
        triangulation.refine_global(2);
        dof_handler.reinit(triangulation);
        dof_handler.distribute_dofs(fe);
        scalar_dofs.reinit(triangulation);
        scalar_dofs.distribute_dofs(scalar_fe);
        IndexSet relevant;
        DoFTools::extract_locally_relevant_dofs(dof_handler, relevant);
        constraints.reinit(relevant);
        constraints.close();
        layout.reinit(dof_handler.locally_owned_dofs(),
                      relevant,
                      MPI_COMM_WORLD);
        const std::vector<ContactZoneDescription<2>> zones{
          {1,
           "Contact",
           ContactLaw::from_parameters(entries),
           {2},
           std::nullopt,
           TangentialLaw::from_parameters(entries),
           {}}};
        contact.setup(zones,
                      hp::MappingCollection<2>(MappingQ<2>(1)),
                      dof_handler,
                      scalar_dofs,
                      hp::QCollection<1>(QGauss<1>(2)),
                      constraints,
                      constraints,
                      layout);
      }

      parallel::distributed::Triangulation<2> triangulation;
      const FESystem<2>                       fe;
      const FE_Q<2>                           scalar_fe;
      DoFHandler<2>                           dof_handler, scalar_dofs;
      AffineConstraints<double>               constraints;
      VectorType                              layout;
      ContactSet<2>                           contact;
    };
  } // namespace TestScenes
} // namespace ViscoContact

#endif
