#ifndef viscoplastic_contact_mortar_h
#define viscoplastic_contact_mortar_h

#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>

#include <array>
#include <limits>
#include <map>
#include <vector>

namespace ViscoContact
{
  using namespace dealii;

  // @sect3{Mortar coupling of two sides}
  //
  // The building block of contact between two deformable bodies
  // (doc/model.md, section 8): the weighted gap of every vertex of one side
  // (the slave side) against the other (the master side), on meshes whose
  // vertices do not match. With the dual (biorthogonal) basis psi_j of the
  // slave side's linear faces (int psi_j N_k = delta_jk int N_k, N_k the
  // face's linear or bilinear shape functions; psi_1 = 2 N_1 - N_2 on a
  // segment),
  //   D_j  = sum over the faces of j of int psi_j,
  //   M_jk = int psi_j (N_k^m o pi),
  // pi the projection of a slave point onto the master side along the
  // normal of its slave face. The weighted gap of vertex j is then
  //   g_j = n_j . (sum_k M_jk x_k - D_j x_j),
  // n_j the vertex's normal (the mean of its faces'), a row over the
  // dofs of vertex j and of the master vertices k, and the constraint of
  // the vertex stays nodal (g_j >= 0), which the active set of today
  // handles node by node.
  //
  // The integrals are segment-based: each pair of a slave and a master face
  // is integrated over the part of the slave face that the master face
  // covers. In 2D that part is an interval where pi is affine, and Gauss's
  // two-point rule is exact. In 3D both faces are projected along the slave
  // face's normal onto its plane (the auxiliary plane of Puso and Laursen),
  // the master polygon clips the slave polygon (both convex), and the
  // clipped polygon is cut into triangles from its first vertex, each
  // integrated by a rule of degree 5 (exact for triangles and
  // parallelograms, whose shape functions are then polynomials of the
  // plane's coordinates). On a slave face that the master side covers only
  // in part, the dual basis is taken biorthogonal on the covered part
  // (below 1% coverage the standard basis psi_j = N_j), so that D_j is the
  // covered integral of N_j, never negative. What this guarantees
  // (tests/unit/mortar.cc): sum_k M_jk = D_j at every vertex (a rigid
  // translation has no weighted gap), and on a flat interface
  // sum_k M_jk x_k = D_j x_j wherever the faces around j are covered, in
  // part or whole (a linear field is reproduced: the patch test on
  // non-matching meshes), because the same quadrature points make the basis
  // biorthogonal and integrate M.
  namespace Mortar
  {
    // A side as faces between vertices: in 2D segments of two vertices,
    // each oriented so that its normal (the tangent turned clockwise,
    // (t_y, -t_x)) points out of the body, towards the other side; in 3D
    // triangles or quadrilaterals, their vertices in cyclic order
    // counterclockwise seen from outside the body (the normal
    // (x_1 - x_0) x (x_2 - x_0) points out of it). The shape functions of
    // a quadrilateral x_0 x_1 x_2 x_3 are (1 - s)(1 - t), s (1 - t), s t and
    // (1 - s) t.
    template <int dim>
    struct Side
    {
      std::vector<Point<dim>>                vertices;
      std::vector<std::vector<unsigned int>> faces;
    };

    template <int dim>
    struct Coupling
    {
      // D_j per slave vertex, M_jk per slave vertex j over master vertices
      // k (only the nonzero ones), and the normal n_j of every slave
      // vertex.
      std::vector<double>                         D;
      std::vector<std::map<unsigned int, double>> M;
      std::vector<Tensor<1, dim>>                 normals;
      // The smallest distance along a slave normal between a slave face and
      // a master face that faces it and overlaps it, within the search
      // distance or not (infinity: none). In 3D only the master faces whose
      // boxes come within the search distance of the slave face's box are
      // looked at: all of them with an infinite search distance.
      double closest_distance = std::numeric_limits<double>::infinity();
    };

    // The mortar coupling of slave against master. Master faces are
    // projected onto each slave face along its normal; a master face that
    // faces the same way as the slave face (it cannot be the other side of
    // a contact), that does not overlap it, or that lies farther than
    // search_distance from it along its normal (in front of it or behind
    // it) is left out.
    Coupling<2>
    couple(const Side<2> &slave,
           const Side<2> &master,
           const double   search_distance
           = std::numeric_limits<double>::infinity());

    Coupling<3>
    couple(const Side<3> &slave,
           const Side<3> &master,
           const double   search_distance
           = std::numeric_limits<double>::infinity());

    // The weighted gap g_j of every slave vertex at the current positions
    // (the vertices moved by a displacement u_s, u_m of each side):
    // n_j . (sum_k M_jk (x_k + u_k) - D_j (x_j + u_j)).
    template <int dim>
    std::vector<double>
    weighted_gaps(const Coupling<dim>               &coupling,
                  const Side<dim>                   &slave,
                  const Side<dim>                   &master,
                  const std::vector<Tensor<1, dim>> &slave_displacement,
                  const std::vector<Tensor<1, dim>> &master_displacement);
  } // namespace Mortar
} // namespace ViscoContact

#endif
