// Geometry of one 8-node hexahedron (VTK_HEXAHEDRON order), DESIGN §2: each
// (possibly non-planar) quadrilateral face is split into 4 triangles around its
// face point (the mean of its 4 nodes); the cell is the 24-facet polyhedron they
// bound. Everything here is a per-cell device function, reused by the kernels,
// the boundary set-up on the host, and the unit tests.
#pragma once

#include "../data/math.hpp"

namespace lagremap::hex {

// Local nodes of face f, ordered so that the right-hand rule points out of the
// cell. Face f lies on box side f of a generated block: 0 x-, 1 x+, 2 y-, 3 y+,
// 4 z-, 5 z+.
// The table {0,4,7,3}, {1,2,6,5}, {0,1,5,4}, {3,7,6,2}, {0,3,2,1}, {4,5,6,7} is
// packed 4 bits an entry into two integer constants: no memory table, so it
// folds to immediates on every backend.
KOKKOS_INLINE_FUNCTION int faceNode(int f, int k) {
  constexpr unsigned long long faces_0_to_3 = 0x2673'4510'5621'3740ULL;
  constexpr unsigned long long faces_4_to_5 = 0x7654'1230ULL;
  const unsigned long long packed = f < 4 ? faces_0_to_3 : faces_4_to_5;
  return int((packed >> (16 * (f & 3) + 4 * k)) & 0xFULL);
}

// Area vectors s_t n_t = 1/2 (b - a) x (c - a) of the 4 triangles
// (q_k, q_k+1, face point) of a face; q: the 4 face nodes in outward order.
KOKKOS_INLINE_FUNCTION void faceTriangles(const Vec3 q[4], Vec3 tri[4]) {
  const Vec3 face_point = 0.25 * (q[0] + q[1] + q[2] + q[3]);
  for (int k = 0; k < 4; ++k) tri[k] = 0.5 * cross(q[(k + 1) & 3] - q[k], face_point - q[k]);
}

// Corner-face area vectors from the triangles (DESIGN §2):
//   s_pf n_pf = 1/3 ( sum of the 2 triangles holding p + 1/4 sum of the 4 triangles )
// w[k]: vector of node q[k]. Returns the face's total area vector.
KOKKOS_INLINE_FUNCTION Vec3 cornerVectorsOfTriangles(const Vec3 tri[4], Vec3 w[4]) {
  const Vec3 face_area = tri[0] + tri[1] + tri[2] + tri[3];
  for (int k = 0; k < 4; ++k) w[k] = (1.0 / 3.0) * (tri[(k + 3) & 3] + tri[k] + 0.25 * face_area);
  return face_area;
}

KOKKOS_INLINE_FUNCTION Vec3 faceCornerVectors(const Vec3 q[4], Vec3 w[4]) {
  Vec3 tri[4];
  faceTriangles(q, tri);
  return cornerVectorsOfTriangles(tri, w);
}

// Area vector of a face, the sum of its 4 triangles' (the face point cancels
// from the sum): 1/2 (q_2 - q_0) x (q_3 - q_1), one cross product.
KOKKOS_INLINE_FUNCTION Vec3 faceArea(const Vec3 q[4]) {
  return 0.5 * cross(q[2] - q[0], q[3] - q[1]);
}

// Gathers the 4 nodes of face f from the 8 cell nodes.
KOKKOS_INLINE_FUNCTION void faceNodes(const Vec3 x[8], int f, Vec3 q[4]) {
  for (int k = 0; k < 4; ++k) q[k] = x[faceNode(f, k)];
}

struct CellShape {
  double volume;
  Vec3 centroid;
  double max_face_area;
};

// Volume and centroid of the 24-facet polyhedron: signed tetrahedra from a
// cell-local origin (node 0, to keep round-off relative to the cell size) to
// each triangle; max face area for the characteristic length.
KOKKOS_INLINE_FUNCTION CellShape cellShape(const Vec3 x[8]) {
  const Vec3 origin = x[0];
  double volume = 0.0;
  Vec3 first_moment{0.0, 0.0, 0.0};  // relative to origin
  double max_area2 = 0.0;
  for (int f = 0; f < 6; ++f) {
    Vec3 q[4];
    for (int k = 0; k < 4; ++k) q[k] = x[faceNode(f, k)] - origin;
    const Vec3 face_point = 0.25 * (q[0] + q[1] + q[2] + q[3]);
    Vec3 face_area{0.0, 0.0, 0.0};
    for (int k = 0; k < 4; ++k) {
      const Vec3& a = q[k];
      const Vec3& b = q[(k + 1) & 3];
      // tet (origin, a, b, face_point): 1/6 a . (b x face_point)
      const Vec3 b_cross_f = cross(b, face_point);
      const double tet_volume = dot(a, b_cross_f) / 6.0;
      volume += tet_volume;
      first_moment += (0.25 * tet_volume) * (a + b + face_point);
      face_area += 0.5 * cross(b - a, face_point - a);
    }
    const double area2 = dot(face_area, face_area);
    max_area2 = area2 > max_area2 ? area2 : max_area2;
  }
  const Vec3 centroid = origin + (1.0 / volume) * first_moment;
  return {volume, centroid, math::sqrt(max_area2)};
}

// Everything the Lagrangian phase needs from one cell's geometry in a single
// sweep over its 24 triangles: the corner vectors A_cp, the volume, centroid
// and max face area, and the two sums over a corner's 3 corner faces that the
// nodal impedance is made of (DESIGN §3),
//   sum_f s_pf Q_cfp = rho (aL - aT) sum_f s_pf n_pf (x) n_pf + rho aT (sum_f s_pf) I,
// so the 24 corner-face vectors never need to be stored. A tetrahedron
// (origin, a, b, face point) has volume 1/3 (a - origin) . s_t n_t, so the
// triangle area vectors serve the volume and centroid too.
struct CellGeometry {
  Vec3 corner[8];              // A_cp = sum_f s_pf n_pf
  SymMat3 normal_moment[8];    // sum_f s_pf n_pf (x) n_pf
  double corner_face_area[8];  // sum_f s_pf
  CellShape shape;
};

// kCornerSums = false: g.shape only (the corner arrays are left as they are),
// with the same arithmetic, so the same bits, as the full sweep.
template <bool kCornerSums = true>
KOKKOS_INLINE_FUNCTION void cellGeometry(const Vec3 x[8], CellGeometry& g) {
  const Vec3 origin = x[0];
  // Constant factors are folded out of the 24-triangle loop: with the doubled
  // triangle area vectors T_k = (q_k+1 - q_k) x (face point - q_k) = 2 s_t n_t,
  // the tetrahedron (origin, q_k, q_k+1, face point) has volume q_k . T_k / 6
  // and centroid (q_k + q_k+1 + face point) / 4, so
  //   volume = sum(q_k . T_k) / 6,  centroid = sum((q_k . T_k)(q_k + q_k+1 + fp)) / (4 sum(q_k .
  //   T_k)).
  double six_volume = 0.0, max_area2 = 0.0;
  Vec3 weighted_sum{0.0, 0.0,
                    0.0};  // sum (q_k . T_k)(q_k + q_k+1 + face point), relative to origin
  // The corner sums accumulate in locals, written to g once at the end: g is
  // written through a reference that, for the compiler, may alias x, so sums
  // kept in it are stored and reloaded at every triangle (4% more
  // instructions in this sweep).
  Vec3 corner[8];
  SymMat3 normal_moment[8];
  double corner_face_area[8];
  if constexpr (kCornerSums) {
    for (int p = 0; p < 8; ++p) {
      corner[p] = Vec3{0.0, 0.0, 0.0};
      normal_moment[p] = SymMat3{0.0, 0.0, 0.0, 0.0, 0.0, 0.0};
      corner_face_area[p] = 0.0;
    }
  }
  LAGREMAP_UNROLL
  for (int f = 0; f < 6; ++f) {
    Vec3 q[4];
    for (int k = 0; k < 4; ++k) q[k] = x[faceNode(f, k)] - origin;
    const Vec3 face_point = 0.25 * (q[0] + q[1] + q[2] + q[3]);
    Vec3 doubled[4];  // T_k = 2 s_t n_t
    for (int k = 0; k < 4; ++k) doubled[k] = cross(q[(k + 1) & 3] - q[k], face_point - q[k]);
    const Vec3 doubled_face = doubled[0] + doubled[1] + doubled[2] + doubled[3];
    LAGREMAP_UNROLL
    for (int k = 0; k < 4; ++k) {
      const double weight = dot(q[k], doubled[k]);
      six_volume += weight;
      weighted_sum += weight * (q[k] + q[(k + 1) & 3] + face_point);
      if constexpr (!kCornerSums) continue;
      // s_pf n_pf = 1/3 (t_k-1 + t_k + 1/4 face) = 1/6 (T_k-1 + T_k + 1/4 sum T)
      const Vec3 w = (1.0 / 6.0) * (doubled[(k + 3) & 3] + doubled[k] + 0.25 * doubled_face);
      const int p = faceNode(f, k);
      corner[p] += w;
      const double area2 = dot(w, w);
      if (area2 > 0.0) {  // a degenerate corner face has no normal and adds nothing
        const double area = math::sqrt(area2);
        const Vec3 n = (1.0 / area) * w;
        SymMat3& m = normal_moment[p];
        m.xx += n.x * w.x;
        m.yy += n.y * w.y;
        m.zz += n.z * w.z;
        m.xy += n.x * w.y;
        m.yz += n.y * w.z;
        m.xz += n.x * w.z;
        corner_face_area[p] += area;
      }
    }
    const double area2 = 0.25 * dot(doubled_face, doubled_face);
    max_area2 = area2 > max_area2 ? area2 : max_area2;
  }
  g.shape = {six_volume / 6.0, origin + (0.25 / six_volume) * weighted_sum, math::sqrt(max_area2)};
  if constexpr (kCornerSums) {
    for (int p = 0; p < 8; ++p) {
      g.corner[p] = corner[p];
      g.normal_moment[p] = normal_moment[p];
      g.corner_face_area[p] = corner_face_area[p];
    }
  }
}

// The 8 corner vectors A_cp = sum_f s_pf n_pf = d v_c / d x_p (GCL, DESIGN §2).
KOKKOS_INLINE_FUNCTION void cornerVectors(const Vec3 x[8], Vec3 corner[8]) {
  for (int p = 0; p < 8; ++p) corner[p] = Vec3{0.0, 0.0, 0.0};
  for (int f = 0; f < 6; ++f) {
    Vec3 q[4], w[4];
    faceNodes(x, f, q);
    faceCornerVectors(q, w);
    for (int k = 0; k < 4; ++k) corner[faceNode(f, k)] += w[k];
  }
}

}  // namespace lagremap::hex
