#ifndef viscoplastic_contact_rigid_body_modes_h
#define viscoplastic_contact_rigid_body_modes_h

#include <deal.II/base/point.h>

#include <array>

namespace ViscoContact
{
  using namespace dealii;

  // @sect3{The rigid-body modes of elasticity}
  //
  // Component c at the point x of each rigid-body mode, the near-null space
  // that smoothed aggregation needs for elasticity: the dim translations
  // e_c, then the infinitesimal rotations. In 2D the rotation is the field
  // (-x_2, x_1) = cross(e_3, x). In 3D mode 3 + d is the rotation about
  // e_d, the field cross(x, e_d) (the sign of a null-space vector does not
  // matter to ML); its component c is x_{c+1} for d = c + 2, -x_{c+2} for
  // d = c + 1 and 0 for d = c, indices mod 3.
  template <int dim>
  std::array<double, (dim == 2 ? 3 : 6)>
  rigid_body_mode_components(const unsigned int c, const Point<dim> &x)
  {
    std::array<double, (dim == 2 ? 3 : 6)> modes{};
    modes[c] = 1.;
    if constexpr (dim == 2)
      modes[2] = (c == 0 ? -x[1] : x[0]);
    else
      {
        const unsigned int c1 = (c + 1) % 3, c2 = (c + 2) % 3;
        for (unsigned int d = 0; d < 3; ++d)
          modes[3 + d] = (d == c2 ? x[c1] : (d == c1 ? -x[c2] : 0.));
      }
    return modes;
  }
} // namespace ViscoContact

#endif
