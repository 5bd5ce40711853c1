// Mesh quality (docs/method.md §8.4): the scaled Jacobian of each corner of a
// hexahedron, the cosine-like measure of how far the corner is from a right
// angle,
//   J_p = (e_1 x e_2) . e_3 / (|e_1| |e_2| |e_3|),
// with e_1, e_2, e_3 the corner's three edges along the cell's logical
// directions xi, eta, zeta (pointing into the cell's logical +/- directions as
// the corner's position demands, so that a right-handed cube has J_p = 1 at
// every corner). 1: a right angle; 0: a flat corner; negative: an inverted
// corner. A cell's quality is the smallest of its 8 corners'; the mesh's, the
// smallest over the owned cells. The measure is invariant under translation,
// rotation and uniform scaling, and a sheared cube of angle theta has
// cos(theta) at its skewed corners. Its kernel launcher is `static` (internal
// linkage: docs/method.md §7.2).
#pragma once

#include "../data/mesh.hpp"
#include "../data/types.hpp"
#include "geometry.hpp"

namespace lagremap {

// Logical position (i, j, k) in {0, 1}^3 of VTK_HEXAHEDRON local node p and back.
KOKKOS_INLINE_FUNCTION int hexLogicalI(int p) {
  return (p & 3) == 1 || (p & 3) == 2 ? 1 : 0;
}
KOKKOS_INLINE_FUNCTION int hexLogicalJ(int p) {
  return (p & 3) >= 2 ? 1 : 0;
}
KOKKOS_INLINE_FUNCTION int hexLogicalK(int p) {
  return p >> 2;
}
KOKKOS_INLINE_FUNCTION int hexNodeAt(int i, int j, int k) {
  return 4 * k + (j == 0 ? i : 3 - i);
}

// Scaled Jacobian of corner p of the hexahedron x (VTK_HEXAHEDRON order); 0
// for a corner with an edge of zero length.
KOKKOS_INLINE_FUNCTION double cornerScaledJacobian(const Vec3 x[8], int p) {
  const int i = hexLogicalI(p), j = hexLogicalJ(p), k = hexLogicalK(p);
  // each edge towards the logical + direction: a corner on the + side of a
  // direction takes its edge with the sign flipped
  const Vec3 e1 = (i == 0 ? 1.0 : -1.0) * (x[hexNodeAt(1 - i, j, k)] - x[p]);
  const Vec3 e2 = (j == 0 ? 1.0 : -1.0) * (x[hexNodeAt(i, 1 - j, k)] - x[p]);
  const Vec3 e3 = (k == 0 ? 1.0 : -1.0) * (x[hexNodeAt(i, j, 1 - k)] - x[p]);
  const double lengths = norm(e1) * norm(e2) * norm(e3);
  return lengths > 0.0 ? dot(cross(e1, e2), e3) / lengths : 0.0;
}

// The smallest of the 8 corners' scaled Jacobians of one cell, the same
// numbers as cornerScaledJacobian with each of the 12 edges and its length
// computed once: edge_d[a] runs along logical direction d, to its + end,
// at the other two directions' positions a (bit 0 the lower direction's).
KOKKOS_INLINE_FUNCTION double cellScaledJacobian(const Vec3 x[8]) {
  Vec3 edge[3][4];
  double length[3][4];
  for (int a = 0; a < 4; ++a) {
    const int lo = a & 1, hi = a >> 1;
    edge[0][a] = x[hexNodeAt(1, lo, hi)] - x[hexNodeAt(0, lo, hi)];
    edge[1][a] = x[hexNodeAt(lo, 1, hi)] - x[hexNodeAt(lo, 0, hi)];
    edge[2][a] = x[hexNodeAt(lo, hi, 1)] - x[hexNodeAt(lo, hi, 0)];
    for (int d = 0; d < 3; ++d) length[d][a] = norm(edge[d][a]);
  }
  double smallest = 1.0;
  for (int p = 0; p < 8; ++p) {
    const int i = hexLogicalI(p), j = hexLogicalJ(p), k = hexLogicalK(p);
    const int a = j + 2 * k, b = i + 2 * k, c = i + 2 * j;
    const double lengths = length[0][a] * length[1][b] * length[2][c];
    const double corner =
        lengths > 0.0 ? dot(cross(edge[0][a], edge[1][b]), edge[2][c]) / lengths : 0.0;
    smallest = corner < smallest ? corner : smallest;
  }
  return smallest;
}

// The smallest scaled Jacobian of this rank's owned cells at node positions
// x_n (1 for a mesh without owned cells); the caller reduces over ranks.
static inline double smallestScaledJacobian(const Mesh& mesh, const Vec3View& x_n) {
  const auto cell_nodes = mesh.cell_nodes;
  const auto owned = mesh.cell_owned;
  double smallest = 1.0;
  Kokkos::parallel_reduce(
      "lagremap::mesh_quality::smallest_scaled_jacobian",
      Kokkos::RangePolicy<ExecSpace>(0, mesh.n_cells),
      KOKKOS_LAMBDA(const Index c, double& lowest) {
        if (!owned(c)) return;
        Vec3 x[8];
        gatherCellNodes(cell_nodes, x_n, c, x);
        const double quality = cellScaledJacobian(x);
        lowest = quality < lowest ? quality : lowest;
      },
      Kokkos::Min<double>(smallest));
  return smallest < 1.0 ? smallest : 1.0;  // (no owned cell: the reducer's identity)
}

}  // namespace lagremap
