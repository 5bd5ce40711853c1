// Mesh relaxation of ALE mode (docs/method.md §8): from the Lagrangian node
// positions x_L, each node's target x_T = (1 - w) x_L + w x_R, where x_R is
//  - winslow: the node's equipotential (Winslow) position, one Jacobi sweep of
//      sum_ij a_ij x_{xi_i xi_j} = 0,  a = adj(g),  g_ij = x_{xi_i} . x_{xi_j},
//    on the node's logical 3x3x3 stencil (docs/method.md §8.1): an affine
//    image of a uniform block is its own relaxed mesh, so the mesh follows
//    any uniform deformation of the material and is moved only where the
//    deformation bends it;
//  - initial: the node's initial position (remap mode's target at w = 1).
// Winslow targets keep the boundary: a node on wall or symmetry sides only
// moves within them (its velocity projector), a node on a free, traction or
// fixed side stays where the material took it (its normal motion is the
// material's), and the Winslow sums use only the logical directions in
// which the node has neighbours on both sides. Each move is limited to
// ale.max_move of the node's shortest edge (the swept-face remap needs
// small displacements), and a cell the targets would turn worse than
// min(its Lagrangian quality, ale.quality_floor) gets its owned nodes back
// at x_L (markWorsenedCells, holdNodesOfWorsenedCells), until no such cell
// remains.
// Its kernel launchers are `static` (internal linkage: docs/method.md §7.2).
#pragma once

#include "../data/fence.hpp"
#include "../data/mesh.hpp"
#include "mesh_quality.hpp"

namespace lagremap {

enum class RelaxationRule { Winslow, Initial };

struct RelaxationControls {
  RelaxationRule rule = RelaxationRule::Winslow;
  double weight = 1.0;         // w: 0 keeps the Lagrangian mesh, 1 the rule's positions
  double max_move = 0.2;       // largest move, a fraction of the node's shortest edge
  double quality_floor = 0.2;  // ale.quality_floor (scaled Jacobian)
};

// How a node may move (nodeFreedom): not at all, or freely within its
// velocity projector (none: anywhere).
enum NodeFreedom : int { kNodeHeld = 0, kNodeRelaxed = 1 };

// Stencil index of logical offset (a, b, c) in {-1, 0, 1}^3 from a node.
KOKKOS_INLINE_FUNCTION int stencilIndex(int a, int b, int c) {
  return (a + 1) + 3 * (b + 1) + 9 * (c + 1);
}

// Each node's logical stencil as node ids, (node, stencil index), -1 where
// there is none: face and edge neighbours only (Winslow reads no body
// diagonal), and the node itself. Built once (nodeStencils).
using NodeStencilView = DeviceView<Index* [27]>;

// The stencils of every node from their corners: the cells round a node,
// each placed by the node's logical position in it (every cell of a block
// has the same orientation).
static inline NodeStencilView nodeStencils(const Mesh& mesh) {
  NodeStencilView stencils("lagremap::ale::node_stencils", mesh.n_nodes);
  const auto offsets = mesh.node_corner_offsets;
  const auto corners = mesh.node_corners;
  const auto cell_nodes = mesh.cell_nodes;
  Kokkos::parallel_for(
      "lagremap::ale::node_stencils", Kokkos::RangePolicy<ExecSpace>(0, mesh.n_nodes),
      KOKKOS_LAMBDA(const Index n) {
        for (int s = 0; s < 27; ++s) stencils(n, s) = -1;
        for (Index q = offsets(n); q < offsets(n + 1); ++q) {
          const Index c = corners(q) / 8;
          const int p = corners(q) % 8;
          const int i = hexLogicalI(p), j = hexLogicalJ(p), k = hexLogicalK(p);
          for (int r = 0; r < 8; ++r) {
            const int a = hexLogicalI(r) - i, b = hexLogicalJ(r) - j, cc = hexLogicalK(r) - k;
            if (a != 0 && b != 0 && cc != 0) continue;
            stencils(n, stencilIndex(a, b, cc)) = cell_nodes(c, r);
          }
        }
      });
  return stencils;
}

// Node n's stencil as the kernels read it: the neighbours' positions loaded
// when used, not held (a GPU thread keeps no 27-position array).
struct NodeStencil {
  const NodeStencilView& ids;
  const Vec3View& x_n;
  Index n;
  KOKKOS_INLINE_FUNCTION bool has(int s) const { return ids(n, s) >= 0; }
  KOKKOS_INLINE_FUNCTION Vec3 x(int s) const { return loadVec3(x_n, ids(n, s)); }
};

// Offset of logical direction d (0, 1, 2), sign +1 or -1, as a stencil index.
KOKKOS_INLINE_FUNCTION int stencilAlong(int d, int sign) {
  return stencilIndex(d == 0 ? sign : 0, d == 1 ? sign : 0, d == 2 ? sign : 0);
}
KOKKOS_INLINE_FUNCTION int stencilAlong2(int d, int sign_d, int e, int sign_e) {
  int o[3] = {0, 0, 0};
  o[d] = sign_d;
  o[e] = sign_e;
  return stencilIndex(o[0], o[1], o[2]);
}

// One Jacobi sweep of the Winslow equations at the stencil's centre
// (docs/method.md §8.1), over the logical directions with neighbours on
// both sides: with x_{xi_d} = (x_{+d} - x_{-d}) / 2, g = (x_{xi_d} . x_{xi_e}),
// a = adj(g),
//   x = [sum_d a_dd (x_{+d} + x_{-d}) + 2 sum_{d<e} a_de X_de] / (2 sum_d a_dd),
//   X_de = (x_{+d+e} - x_{+d-e} - x_{-d+e} + x_{-d-e}) / 4.
// No such direction, or a degenerate metric: the centre itself.
KOKKOS_INLINE_FUNCTION Vec3 winslowPosition(const NodeStencil& s) {
  const Vec3 centre = s.x(stencilIndex(0, 0, 0));
  int dirs[3];
  int m = 0;
  for (int d = 0; d < 3; ++d) {
    if (s.has(stencilAlong(d, 1)) && s.has(stencilAlong(d, -1))) dirs[m++] = d;
  }
  if (m == 0) return centre;
  Vec3 tangent[3];
  for (int a = 0; a < m; ++a) {
    tangent[a] = 0.5 * (s.x(stencilAlong(dirs[a], 1)) - s.x(stencilAlong(dirs[a], -1)));
  }
  double g[3][3];
  for (int a = 0; a < m; ++a)
    for (int b = 0; b < m; ++b) g[a][b] = dot(tangent[a], tangent[b]);
  double adj[3][3];
  if (m == 1) {
    adj[0][0] = 1.0;
  } else if (m == 2) {
    adj[0][0] = g[1][1];
    adj[1][1] = g[0][0];
    adj[0][1] = adj[1][0] = -g[0][1];
  } else {
    for (int a = 0; a < 3; ++a) {
      for (int b = 0; b < 3; ++b) {  // cofactor (b, a) of g: g is symmetric
        const int a1 = (a + 1) % 3, a2 = (a + 2) % 3, b1 = (b + 1) % 3, b2 = (b + 2) % 3;
        adj[a][b] = g[b1][a1] * g[b2][a2] - g[b1][a2] * g[b2][a1];
      }
    }
  }
  Vec3 sum{0.0, 0.0, 0.0};
  double weight = 0.0;
  for (int a = 0; a < m; ++a) {
    const int d = dirs[a];
    sum += adj[a][a] * (s.x(stencilAlong(d, 1)) + s.x(stencilAlong(d, -1)));
    weight += 2.0 * adj[a][a];
    for (int b = a + 1; b < m; ++b) {
      const int e = dirs[b];
      const Vec3 cross_difference =
          (s.x(stencilAlong2(d, 1, e, 1)) - s.x(stencilAlong2(d, 1, e, -1))) -
          (s.x(stencilAlong2(d, -1, e, 1)) - s.x(stencilAlong2(d, -1, e, -1)));
      sum += 0.5 * adj[a][b] * cross_difference;
    }
  }
  return weight > 0.0 ? (1.0 / weight) * sum : centre;
}

// The shortest edge from the stencil's centre to a face neighbour.
KOKKOS_INLINE_FUNCTION double shortestEdge(const NodeStencil& s) {
  const Vec3 centre = s.x(stencilIndex(0, 0, 0));
  double shortest = 1e300;
  for (int d = 0; d < 3; ++d) {
    for (int sign = -1; sign <= 1; sign += 2) {
      const int i = stencilAlong(d, sign);
      if (!s.has(i)) continue;
      const double length = norm(s.x(i) - centre);
      shortest = length < shortest ? length : shortest;
    }
  }
  return shortest;
}

// What a node may do under the Winslow rule: kNodeRelaxed unless it lies on a
// free, traction or fixed side of the block (faces on box side f are face f
// of their cells, kernels/hex.hpp).
static inline DeviceView<int*> nodeFreedom(const Mesh& mesh) {
  DeviceView<int*> freedom("lagremap::ale::node_freedom", mesh.n_nodes);
  const auto offsets = mesh.node_corner_offsets;
  const auto corners = mesh.node_corners;
  const auto neighbors = mesh.cell_neighbors;
  const auto face_side = mesh.cell_face_side;
  const auto side_kind = mesh.side_kind;
  Kokkos::parallel_for(
      "lagremap::ale::node_freedom", Kokkos::RangePolicy<ExecSpace>(0, mesh.n_nodes),
      KOKKOS_LAMBDA(const Index n) {
        int free = kNodeRelaxed;
        for (Index q = offsets(n); q < offsets(n + 1); ++q) {
          const Index c = corners(q) / 8;
          const int p = corners(q) % 8;
          const int faces[3] = {hexLogicalI(p), 2 + hexLogicalJ(p), 4 + hexLogicalK(p)};
          for (int f : faces) {
            const int side = face_side(c, f);
            if (neighbors(c, f) >= 0 || side < 0) continue;
            if (side_kind(side) != int(BoundaryKind::Wall)) free = kNodeHeld;
          }
        }
        freedom(n) = free;
      });
  return freedom;
}

// The targets of the owned nodes (ghost nodes: the caller exchanges them).
static inline void relaxedTargets(const Mesh& mesh, const NodeStencilView& stencils,
                                  const Vec3View& x_lagrange, const Vec3View& x_initial,
                                  const DeviceView<int*>& freedom,
                                  const RelaxationControls& controls, const Vec3View& x_target) {
  const auto owned = mesh.node_owned;
  const auto projector_id = mesh.node_projector_id;
  const auto projectors = mesh.projectors;
  const RelaxationControls ctl = controls;
  Kokkos::parallel_for(
      "lagremap::ale::relaxed_targets", Kokkos::RangePolicy<ExecSpace>(0, mesh.n_nodes),
      KOKKOS_LAMBDA(const Index n) {
        if (!owned(n)) return;
        const Vec3 x_l = loadVec3(x_lagrange, n);
        if (ctl.rule == RelaxationRule::Initial) {
          // every node, boundaries included, towards where it started
          const Vec3 blend = (1.0 - ctl.weight) * x_l + ctl.weight * loadVec3(x_initial, n);
          const NodeStencil s{stencils, x_lagrange, n};
          const Vec3 move = blend - x_l;
          const double reach = ctl.max_move * shortestEdge(s), length = norm(move);
          storeVec3(x_target, n, length > reach ? x_l + (reach / length) * move : blend);
          return;
        }
        if (freedom(n) == kNodeHeld) {
          storeVec3(x_target, n, x_l);
          return;
        }
        const NodeStencil s{stencils, x_lagrange, n};
        Vec3 move = ctl.weight * (winslowPosition(s) - x_l);
        const int projector = projector_id(n);
        if (projector >= 0) move = loadSym(projectors, projector) * move;
        const double reach = ctl.max_move * shortestEdge(s), length = norm(move);
        if (length > reach) move = (reach / length) * move;
        storeVec3(x_target, n, x_l + move);
      });
}

// One pass of the quality guard (docs/method.md §8.2), in three sweeps so that
// no thread reads a target another one rewrites (and each holds one cell's
// quality sweep at a time: a GPU thread's registers):
// 1. every cell's target quality; returns how many owned cells are below
//    the floor and the smallest of the owned cells' (after a pass that
//    marks none: the new mesh's, the step's mesh quality); the caller
//    reduces over ranks;
struct GuardTally {
  long below_floor = 0;
  double lowest = 1.0;  // (a cell's scaled Jacobian is at most 1)
  // (a sum of the counts, a minimum of the qualities: Kokkos::Sum's join)
  KOKKOS_INLINE_FUNCTION GuardTally& operator+=(const GuardTally& other) {
    below_floor += other.below_floor;
    lowest = other.lowest < lowest ? other.lowest : lowest;
    return *this;
  }
  KOKKOS_INLINE_FUNCTION void operator+=(const volatile GuardTally& other) volatile {
    below_floor += other.below_floor;
    lowest = other.lowest < lowest ? other.lowest : lowest;
  }
};

}  // namespace lagremap

namespace Kokkos {
template <>
struct reduction_identity<lagremap::GuardTally> {
  KOKKOS_FORCEINLINE_FUNCTION static lagremap::GuardTally sum() { return {}; }
};
}  // namespace Kokkos

namespace lagremap {

static inline GuardTally targetCellQualities(const Mesh& mesh, const Vec3View& x_target,
                                             double quality_floor, const RealView& quality) {
  const auto cell_nodes = mesh.cell_nodes;
  const auto owned = mesh.cell_owned;
  GuardTally tally;
  Kokkos::parallel_reduce(
      "lagremap::ale::target_cell_qualities", Kokkos::RangePolicy<ExecSpace>(0, mesh.n_cells),
      KOKKOS_LAMBDA(const Index c, GuardTally& sum) {
        const double relaxed = cellScaledJacobianOf(NodesOfCell{cell_nodes, x_target, c});
        quality(c) = relaxed;
        if (!owned(c)) return;
        if (relaxed < quality_floor) ++sum.below_floor;
        sum.lowest = relaxed < sum.lowest ? relaxed : sum.lowest;
      },
      Kokkos::Sum<GuardTally>(tally));
  fenceFor("lagremap::ale: the target's qualities");  // (the reduction's wait, told to the tools)
  return tally;
}

// 2. below the floor, the cells the target makes worse than their Lagrangian
//    shape or the floor are marked; returns how many owned cells are;
static inline long markWorsenedCells(const Mesh& mesh, const Vec3View& x_lagrange,
                                     const RealView& quality, double quality_floor,
                                     const DeviceView<int*>& worsened) {
  const auto cell_nodes = mesh.cell_nodes;
  const auto owned = mesh.cell_owned;
  long count = 0;
  Kokkos::parallel_reduce(
      "lagremap::ale::mark_worsened_cells", Kokkos::RangePolicy<ExecSpace>(0, mesh.n_cells),
      KOKKOS_LAMBDA(const Index c, long& marked) {
        const double relaxed = quality(c);
        bool worse = false;
        if (relaxed < quality_floor) {  // (only then can the Lagrangian bound matter)
          const double lagrangian = cellScaledJacobianOf(NodesOfCell{cell_nodes, x_lagrange, c});
          worse = relaxed < (lagrangian < quality_floor ? lagrangian : quality_floor);
        }
        worsened(c) = worse ? 1 : 0;
        if (worse && owned(c)) ++marked;
      },
      count);
  fenceFor("lagremap::ale: the worsened cells");
  return count;
}

// 3. an owned node of a marked cell goes back to x_L (the caller then
//    exchanges the ghost nodes' targets).
static inline void holdNodesOfWorsenedCells(const Mesh& mesh, const Vec3View& x_lagrange,
                                            const DeviceView<int*>& worsened,
                                            const Vec3View& x_target) {
  const auto offsets = mesh.node_corner_offsets;
  const auto corners = mesh.node_corners;
  const auto owned = mesh.node_owned;
  Kokkos::parallel_for(
      "lagremap::ale::hold_nodes_of_worsened_cells",
      Kokkos::RangePolicy<ExecSpace>(0, mesh.n_nodes), KOKKOS_LAMBDA(const Index n) {
        if (!owned(n)) return;
        for (Index q = offsets(n); q < offsets(n + 1); ++q) {
          if (worsened(corners(q) / 8)) {
            storeVec3(x_target, n, loadVec3(x_lagrange, n));
            return;
          }
        }
      });
}

}  // namespace lagremap
