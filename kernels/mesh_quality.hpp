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
#include "cell_thermo.hpp"

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

// One corner's scaled Jacobian from its three edges and their lengths.
KOKKOS_FORCEINLINE_FUNCTION double scaledJacobianOfEdges(const Vec3& e1, double l1, const Vec3& e2,
                                                         double l2, const Vec3& e3, double l3) {
  const double lengths = l1 * l2 * l3;
  return lengths > 0.0 ? dot(cross(e1, e2), e3) / lengths : 0.0;
}

// The smallest of the 8 corners' scaled Jacobians of one cell, the same
// numbers as cornerScaledJacobian with each of the 12 edges and its length
// computed once: x_a runs along xi at the (eta, zeta) position a (bit 0
// eta, bit 1 zeta), y_a along eta at (xi, zeta), z_a along zeta at (xi,
// eta), each to its + end; corner (i, j, k) takes x_{j+2k}, y_{i+2k},
// z_{i+2j}. The zeta edges serve both layers of corners, the others one
// layer each, taken in turn (fewer values live at once: a GPU thread's
// registers). `node(p)`: the position of local node p.
template <class Nodes>
KOKKOS_INLINE_FUNCTION double cellScaledJacobianOf(const Nodes& node) {
  const Vec3 z0 = node(4) - node(0), z1 = node(5) - node(1);
  const Vec3 z2 = node(7) - node(3), z3 = node(6) - node(2);
  const double lz0 = norm(z0), lz1 = norm(z1), lz2 = norm(z2), lz3 = norm(z3);
  double smallest = 1.0;
  const auto keep = [&](double corner) { smallest = corner < smallest ? corner : smallest; };
  {  // the bottom layer's corners, k = 0
    const Vec3 x0 = node(1) - node(0), x1 = node(2) - node(3);
    const Vec3 y0 = node(3) - node(0), y1 = node(2) - node(1);
    const double lx0 = norm(x0), lx1 = norm(x1), ly0 = norm(y0), ly1 = norm(y1);
    keep(scaledJacobianOfEdges(x0, lx0, y0, ly0, z0, lz0));
    keep(scaledJacobianOfEdges(x0, lx0, y1, ly1, z1, lz1));
    keep(scaledJacobianOfEdges(x1, lx1, y1, ly1, z3, lz3));
    keep(scaledJacobianOfEdges(x1, lx1, y0, ly0, z2, lz2));
  }
  {  // the top layer's, k = 1
    const Vec3 x2 = node(5) - node(4), x3 = node(6) - node(7);
    const Vec3 y2 = node(7) - node(4), y3 = node(6) - node(5);
    const double lx2 = norm(x2), lx3 = norm(x3), ly2 = norm(y2), ly3 = norm(y3);
    keep(scaledJacobianOfEdges(x2, lx2, y2, ly2, z0, lz0));
    keep(scaledJacobianOfEdges(x2, lx2, y3, ly3, z1, lz1));
    keep(scaledJacobianOfEdges(x3, lx3, y3, ly3, z3, lz3));
    keep(scaledJacobianOfEdges(x3, lx3, y2, ly2, z2, lz2));
  }
  return smallest;
}

// The same of a cell whose nodes are held in an array.
struct NodesOfArray8 {
  const Vec3* x;
  KOKKOS_INLINE_FUNCTION Vec3 operator()(int p) const { return x[p]; }
};
KOKKOS_INLINE_FUNCTION double cellScaledJacobian(const Vec3 x[8]) {
  return cellScaledJacobianOf(NodesOfArray8{x});
}

// The smallest scaled Jacobian of this rank's owned cells at node positions
// x_n, left in `into` without waiting (the reducer's identity for a mesh
// without owned cells: read it through meshQualityOf); the caller reduces
// over ranks.
static inline void smallestScaledJacobian(const Mesh& mesh, const Vec3View& x_n,
                                          const ReportView<double>& into) {
  const auto cell_nodes = mesh.cell_nodes;
  const auto owned = mesh.cell_owned;
  Kokkos::parallel_reduce(
      "lagremap::mesh_quality::smallest_scaled_jacobian",
      Kokkos::RangePolicy<ExecSpace>(0, mesh.n_cells),
      KOKKOS_LAMBDA(const Index c, double& lowest) {
        if (!owned(c)) return;
        const double quality = cellScaledJacobianOf(NodesOfCell{cell_nodes, x_n, c});
        lowest = quality < lowest ? quality : lowest;
      },
      Kokkos::Min<double, ReportSpace>(into));
}
// A mesh's quality from what smallestScaledJacobian left: 1 at most.
inline double meshQualityOf(double smallest) {
  return smallest < 1.0 ? smallest : 1.0;
}

}  // namespace lagremap
