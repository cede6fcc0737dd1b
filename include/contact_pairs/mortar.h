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

  // @sect3{Mortar coupling of two sides in 2D}
  //
  // The first building block of contact between two deformable bodies
  // (doc/model.md, section 8): the weighted gap of every vertex of one side
  // (the slave side) against the other (the master side), on meshes whose
  // vertices do not match. With the dual (biorthogonal) basis psi_j of the
  // slave side's linear segments (psi_1 = 2 N_1 - N_2 on a segment with the
  // linear shape functions N_1, N_2: int psi_j N_k = delta_jk int N_k),
  //   D_j  = sum over the segments of j of int psi_j,
  //   M_jk = int psi_j (N_k^m o pi),
  // pi the projection of a slave point onto the master side along the
  // normal of its slave segment. The weighted gap of vertex j is then
  //   g_j = n_j . (sum_k M_jk x_k - D_j x_j),
  // n_j the vertex's normal (the mean of its segments'), a row over the
  // dofs of vertex j and of the master vertices k, and the constraint of
  // the vertex stays nodal (g_j >= 0), which the active set of today
  // handles node by node.
  //
  // The integrals are segment-based: each pair of a slave and a master
  // segment is integrated over the part of the slave segment that the
  // master segment covers, where pi is affine, so Gauss's two-point rule is
  // exact. On a slave segment that the master side covers only in part,
  // the dual basis is taken biorthogonal on the covered part (below 1%
  // coverage the standard basis psi_j = N_j), so that D_j is the covered
  // integral of N_j, never negative. What this guarantees
  // (tests/unit/mortar.cc): sum_k M_jk = D_j at every vertex (a rigid
  // translation has no weighted gap), and on a straight interface
  // sum_k M_jk x_k = D_j x_j wherever the segments around j are covered, in
  // part or whole (a linear field is reproduced: the patch test on
  // non-matching meshes).
  namespace Mortar
  {
    // A side in 2D as segments between vertices, each segment oriented so
    // that its normal (the tangent turned clockwise, (t_y, -t_x)) points
    // out of the body, towards the other side.
    struct Side
    {
      std::vector<Point<2>>                    vertices;
      std::vector<std::array<unsigned int, 2>> segments;
    };

    struct Coupling
    {
      // D_j per slave vertex, M_jk per slave vertex j over master vertices
      // k (only the nonzero ones), and the normal n_j of every slave
      // vertex.
      std::vector<double>                         D;
      std::vector<std::map<unsigned int, double>> M;
      std::vector<Tensor<1, 2>>                   normals;
      // The smallest distance along a slave normal between a slave segment
      // and a master segment that faces it and overlaps it, within the
      // search distance or not (infinity: none).
      double closest_distance = std::numeric_limits<double>::infinity();
    };

    // The mortar coupling of slave against master. Master segments are
    // projected onto each slave segment along its normal; a master segment
    // that faces the same way as the slave segment (it cannot be the other
    // side of a contact), that does not overlap it, or that lies farther
    // than search_distance from it along its normal (in front of it or
    // behind it) is left out.
    Coupling
    couple(const Side  &slave,
           const Side  &master,
           const double search_distance
           = std::numeric_limits<double>::infinity());

    // The weighted gap g_j of every slave vertex at the current positions
    // (the vertices moved by a displacement u_s, u_m of each side):
    // n_j . (sum_k M_jk (x_k + u_k) - D_j (x_j + u_j)).
    std::vector<double>
    weighted_gaps(const Coupling                  &coupling,
                  const Side                      &slave,
                  const Side                      &master,
                  const std::vector<Tensor<1, 2>> &slave_displacement,
                  const std::vector<Tensor<1, 2>> &master_displacement);
  } // namespace Mortar
} // namespace ViscoContact

#endif
