// Swept-face geometry of the remap (DESIGN §5), the first kernel of the remap
// phase. Every face triangle of DESIGN §2, (q_k, q_k+1, face point) oriented out
// of its cell, moves on straight paths from its Lagrangian position (a, b, c) to
// its position on the initial mesh (a', b', c'). The region it sweeps is bounded
// by the two triangles and three ruled (bilinear) side patches, each fixed by
// the two end points of its edge alone, so neighbouring triangles of the same
// face, of the next face of the cell and of the neighbouring cell share them
// exactly and the regions of a cell telescope:
//
//   V_new = V_lag + sum_{t in T(c)} dV_t,   (V x_c)_new = (V x_c)_lag + sum_{t in T(c)} M_t.
//
// Sign: dV_t > 0 when the triangle moves outward, i.e. cell c gains the region
// from its neighbour across the face.
#pragma once

#include "../src/mesh.hpp"
#include "hex.hpp"

namespace lagremap {

namespace swept {

// Signed volume and first moment (integral of x, absolute coordinates) of one
// swept region.
struct SweptRegion {
  double volume;
  Vec3 moment;
};

// dV_t = 1/18 (d_a + d_b + d_c) . [e1 x e2 + e1' x e2' + 1/2 (e1 x e2' + e1' x e2)]
// (DESIGN §5): the exact integral of d(xi) . J(tau) over xi in the triangle and
// tau in [0, 1] for the map x(xi, tau) below. Only differences of positions
// enter, so it keeps its relative accuracy far from the origin.
KOKKOS_INLINE_FUNCTION double sweptVolume(const Vec3& a, const Vec3& b, const Vec3& c,
                                          const Vec3& a_target, const Vec3& b_target,
                                          const Vec3& c_target) {
  const Vec3 e1 = b - a, e2 = c - a;
  const Vec3 e1_target = b_target - a_target, e2_target = c_target - a_target;
  const Vec3 d_sum = (a_target - a) + (b_target - b) + (c_target - c);
  const Vec3 twice_mean_area = cross(e1, e2) + cross(e1_target, e2_target) +
                               0.5 * (cross(e1, e2_target) + cross(e1_target, e2));
  return dot(d_sum, twice_mean_area) / 18.0;
}

// Tensor rule of DESIGN §5 for x(xi, tau) = X(xi) + tau d(xi), X on the
// Lagrangian triangle, d(xi) = X'(xi) - X(xi), Jacobian d(xi) . J(tau) with
// J(tau) = (e1 + tau de1) x (e2 + tau de2). The integrand x d.J has degree 2 in
// xi (edge-midpoint rule, exact for degree 2) and 3 in tau (2-point Gauss,
// exact for degree 3); weights 1/6 (triangle area 1/2 over 3 points) times 1/2.
// At an edge midpoint X and d are the midpoints of the edge and of its two
// displacements. Summed relative to a and shifted by a * volume at the end, so
// the round-off of the sum scales with the triangle, not with |a|.
KOKKOS_INLINE_FUNCTION SweptRegion sweptTensorRule(const Vec3& a, const Vec3& b, const Vec3& c,
                                                   const Vec3& a_target, const Vec3& b_target,
                                                   const Vec3& c_target) {
  const Vec3 e1 = b - a, e2 = c - a;
  const Vec3 d_a = a_target - a, d_b = b_target - b, d_c = c_target - c;
  const Vec3 de1 = d_b - d_a, de2 = d_c - d_a;
  // Edge midpoints xi = (1/2, 0), (1/2, 1/2), (0, 1/2): X - a and d(xi).
  const Vec3 x_mid[3] = {0.5 * e1, 0.5 * (e1 + e2), 0.5 * e2};
  const Vec3 d_mid[3] = {0.5 * (d_a + d_b), 0.5 * (d_b + d_c), 0.5 * (d_c + d_a)};
  // Gauss points tau = 1/2 -+ 1/(2 sqrt 3) on [0, 1].
  constexpr double kGaussOffset = 0.28867513459481288225457439025098;
  const double taus[2] = {0.5 - kGaussOffset, 0.5 + kGaussOffset};
  double volume = 0.0;
  Vec3 moment{0.0, 0.0, 0.0};  // relative to a
  for (const double tau : taus) {
    const Vec3 jacobian = cross(e1 + tau * de1, e2 + tau * de2);
    for (int m = 0; m < 3; ++m) {
      const double weight = dot(d_mid[m], jacobian);
      volume += weight;
      moment += weight * (x_mid[m] + tau * d_mid[m]);
    }
  }
  volume *= 1.0 / 12.0;
  return {volume, a * volume + (1.0 / 12.0) * moment};
}

// What the kernels use: the closed-formula volume of DESIGN §5 (the rule's own
// volume agrees to round-off) and the tensor-rule first moment.
KOKKOS_INLINE_FUNCTION SweptRegion sweptTriangle(const Vec3& a, const Vec3& b, const Vec3& c,
                                                 const Vec3& a_target, const Vec3& b_target,
                                                 const Vec3& c_target) {
  const SweptRegion rule = sweptTensorRule(a, b, c, a_target, b_target, c_target);
  return {sweptVolume(a, b, c, a_target, b_target, c_target), rule.moment};
}

// The 4 swept triangles of one face: q_lag / q_target are its 4 nodes in
// outward order (hex::faceNode) on each mesh, and each polygon is split around
// its own face point (DESIGN §2), which moves on a straight path like a node.
// swept[k] belongs to triangle (q_k, q_k+1, face point).
KOKKOS_INLINE_FUNCTION void sweptFace(const Vec3 q_lag[4], const Vec3 q_target[4],
                                      SweptRegion swept[4]) {
  const Vec3 face_point_lag = 0.25 * (q_lag[0] + q_lag[1] + q_lag[2] + q_lag[3]);
  const Vec3 face_point_target = 0.25 * (q_target[0] + q_target[1] + q_target[2] + q_target[3]);
  for (int k = 0; k < 4; ++k) {
    const int next = (k + 1) & 3;
    swept[k] = sweptTriangle(q_lag[k], q_lag[next], face_point_lag, q_target[k], q_target[next],
                             face_point_target);
  }
}

// True when a face's Lagrangian and target positions all lie in one plane
// normal to a coordinate axis: a wall or symmetry plane along x, y or z, in
// which the nodes slide (their projected velocity has an exact zero normal
// component). The region it sweeps is flat, so dV_t = 0 and sweptVolume gives
// exactly 0 too (every cross product is normal to the plane, every
// displacement in it): a one-cell slab's two faces on its symmetry planes,
// half of its swept faces, need no swept-region computation.
KOKKOS_INLINE_FUNCTION bool staysInOneAxisPlane(const Vec3 q_lag[4], const Vec3 q_target[4]) {
  bool same[3] = {true, true, true};
  for (int k = 0; k < 4; ++k) {
    same[0] = same[0] && q_lag[k].x == q_lag[0].x && q_target[k].x == q_lag[0].x;
    same[1] = same[1] && q_lag[k].y == q_lag[0].y && q_target[k].y == q_lag[0].y;
    same[2] = same[2] && q_lag[k].z == q_lag[0].z && q_target[k].z == q_lag[0].z;
  }
  return same[0] || same[1] || same[2];
}

}  // namespace swept

// Storage of the swept regions: one slot per (cell, face, triangle),
//   t = 24 c + 4 f + k  (f: hex face, k: triangle (q_k, q_k+1, face point) of hex::faceNode),
// both oriented out of cell c. Every interior face is computed once, by its
// owner (the cell with the lower id), which writes its own 4 slots and the
// exact negatives into the 4 matching slots of the neighbour, so both sides hold
// the same bits up to sign; boundary faces are computed by their only cell. A
// cell then finds all its regions in its own 24 contiguous slots.
constexpr int kSweptTrianglesPerCell = kFacesPerCell * 4;

KOKKOS_INLINE_FUNCTION Index sweptTriangleId(Index c, int f, int k) {
  return kSweptTrianglesPerCell * c + 4 * f + k;
}

struct SweptFaces {
  RealView dvol_t;    // signed swept volume dV_t (> 0: the cell gains from its neighbour)
  Vec3View moment_t;  // first moment M_t, absolute coordinates
};

inline SweptFaces allocateSweptFaces(const Mesh& mesh) {
  const Index n_triangles = kSweptTrianglesPerCell * mesh.n_cells;
  return {RealView("lagremap::remap::dvol_t", n_triangles),
          Vec3View("lagremap::remap::moment_t", n_triangles)};
}

// Swept volumes and first moments of every face triangle, moving from the
// Lagrangian node positions x_lag to the remap target x_target (the initial
// mesh), DESIGN §5.
inline void computeSweptFaces(const Mesh& mesh, const Vec3View& x_lag, const Vec3View& x_target,
                              const SweptFaces& swept_faces) {
  const auto cell_nodes = mesh.cell_nodes;
  const auto cell_neighbors = mesh.cell_neighbors;
  const auto cell_neighbor_face = mesh.cell_neighbor_face;
  const auto dvol_t = swept_faces.dvol_t;
  const auto moment_t = swept_faces.moment_t;
  Kokkos::parallel_for(
      "lagremap::remap::swept_faces", Kokkos::RangePolicy<ExecSpace>(0, mesh.n_cells),
      KOKKOS_LAMBDA(const Index c) {
        Index node[8];
        Vec3 x_cell_lag[8], x_cell_target[8];
        for (int p = 0; p < 8; ++p) {
          node[p] = cell_nodes(c, p);
          x_cell_lag[p] = loadVec3(x_lag, node[p]);
          x_cell_target[p] = loadVec3(x_target, node[p]);
        }
        for (int f = 0; f < 6; ++f) {
          const Index neighbor = cell_neighbors(c, f);
          if (neighbor >= 0 && neighbor < c) continue;  // the neighbour owns this face
          Vec3 q_lag[4], q_target[4];
          hex::faceNodes(x_cell_lag, f, q_lag);
          hex::faceNodes(x_cell_target, f, q_target);
          swept::SweptRegion swept[4];
          if (neighbor < 0 && swept::staysInOneAxisPlane(q_lag, q_target)) {
            for (int k = 0; k < 4; ++k) swept[k] = {0.0, Vec3{0.0, 0.0, 0.0}};
          } else {
            swept::sweptFace(q_lag, q_target, swept);
          }
          for (int k = 0; k < 4; ++k) {
            const Index t = sweptTriangleId(c, f, k);
            dvol_t(t) = swept[k].volume;
            storeVec3(moment_t, t, swept[k].moment);
          }
          if (neighbor < 0) continue;
          // The neighbour's face g lists the same nodes in the opposite
          // direction, r_{j0 + m} = q_{-m} with r_{j0} = q_0, so our triangle
          // (q_k, q_k+1) is its triangle (r_j, r_j+1) with j = j0 - k - 1.
          const int g = cell_neighbor_face(c, f);
          const Index q0_node = node[hex::faceNode(f, 0)];
          int j0 = 0;
          for (int j = 1; j < 4; ++j) {
            if (cell_nodes(neighbor, hex::faceNode(g, j)) == q0_node) j0 = j;
          }
          for (int k = 0; k < 4; ++k) {
            const Index t = sweptTriangleId(neighbor, g, (j0 + 3 - k) & 3);
            dvol_t(t) = -swept[k].volume;
            storeVec3(moment_t, t, -swept[k].moment);
          }
        }
      });
}

}  // namespace lagremap
