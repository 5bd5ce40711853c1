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

// A right prism along z (Mesh::z_prisms, a one-cell slab between symmetry
// planes): top node p + 4 straight above bottom node p (same x and y), the
// bottom nodes on one z plane, the top ones on another. Its 24-facet
// polyhedron is the prism over the planar bottom quad P_0..P_3, and the sums
// of cellGeometry have closed forms (docs/method.md §2.6), from the quad's 4
// triangles (P_k, P_k+1, F) around its mean point F, of doubled areas
//   T_k = (P_k+1 - P_k) x (F - P_k) (2D cross products),
// and its 4 side faces, rectangles of area vector S_k = h (e_k.y, -e_k.x, 0)
// over the edges e_k = P_k+1 - P_k (h the height):
//  - a side face's 4 triangles are a quarter of it each, so each of its 4
//    nodes gets the corner-face vector S_k / 4 (area |S_k| / 4, normal
//    S_k / |S_k|);
//  - the top face gives node p + 4 the vector w_p e_z and the bottom face
//    gives node p -w_p e_z, w_p = 1/6 (T_p-1 + T_p + 1/4 sum T);
//  - volume h sum T / 2, centroid (sum T_k (P_k + P_k+1 + F) / (3 sum T),
//    z_0 + h / 2), faces of area |sum T| / 2 and |S_k|.
// The same numbers as cellGeometry up to round-off (test_geometry), with 4
// square roots and 4 divisions instead of 24 each. Same template argument.
template <bool kCornerSums = true>
KOKKOS_INLINE_FUNCTION void prismGeometry(const Vec3 x[8], CellGeometry& g) {
  const Vec3 origin = x[0];
  const double height = x[4].z - origin.z;
  double px[4], py[4];  // the bottom quad relative to node 0
  for (int k = 0; k < 4; ++k) {
    px[k] = x[k].x - origin.x;
    py[k] = x[k].y - origin.y;
  }
  const double fx = 0.25 * (px[0] + px[1] + px[2] + px[3]);
  const double fy = 0.25 * (py[0] + py[1] + py[2] + py[3]);
  double doubled[4], edge_x[4], edge_y[4], edge2[4];
  double twice_area = 0.0, weighted_x = 0.0, weighted_y = 0.0, longest2 = 0.0;
  for (int k = 0; k < 4; ++k) {
    const int next = (k + 1) & 3;
    edge_x[k] = px[next] - px[k];
    edge_y[k] = py[next] - py[k];
    doubled[k] = edge_x[k] * (fy - py[k]) - edge_y[k] * (fx - px[k]);
    twice_area += doubled[k];
    weighted_x += doubled[k] * (px[k] + px[next] + fx);
    weighted_y += doubled[k] * (py[k] + py[next] + fy);
    edge2[k] = edge_x[k] * edge_x[k] + edge_y[k] * edge_y[k];
    longest2 = edge2[k] > longest2 ? edge2[k] : longest2;
  }
  const double quad_area = 0.5 * twice_area;
  const double side2 = height * height * longest2;
  const double max_area2 = quad_area * quad_area > side2 ? quad_area * quad_area : side2;
  const double third_over_area = 1.0 / (3.0 * twice_area);
  g.shape = {
      quad_area * height,
      origin + Vec3{third_over_area * weighted_x, third_over_area * weighted_y, 0.5 * height},
      math::sqrt(max_area2)};
  if constexpr (!kCornerSums) return;
  // a side face's quarter: vector, area and normal moment S (x) S / (4 |S|)
  // (in the xy block; a degenerate face adds no moment or area)
  double quarter_x[4], quarter_y[4], quarter_area[4], moment_xx[4], moment_yy[4], moment_xy[4];
  for (int k = 0; k < 4; ++k) {
    quarter_x[k] = 0.25 * height * edge_y[k];
    quarter_y[k] = -0.25 * height * edge_x[k];
    const double length = math::sqrt(edge2[k]);
    const double scale = length > 0.0 && height > 0.0 ? 0.25 * height / length : 0.0;
    quarter_area[k] = 0.25 * height * length;
    moment_xx[k] = scale * (edge_y[k] * edge_y[k]);
    moment_yy[k] = scale * (edge_x[k] * edge_x[k]);
    moment_xy[k] = -scale * (edge_x[k] * edge_y[k]);
  }
  for (int p = 0; p < 4; ++p) {
    const int before = (p + 3) & 3;  // the side faces of node p: edges p - 1 and p
    const double w = (1.0 / 6.0) * (doubled[before] + doubled[p] + 0.25 * twice_area);
    const double w_size = math::fabs(w);
    const double in_plane_x = quarter_x[before] + quarter_x[p];
    const double in_plane_y = quarter_y[before] + quarter_y[p];
    const SymMat3 moment{moment_xx[before] + moment_xx[p],
                         moment_yy[before] + moment_yy[p],
                         w_size,
                         moment_xy[before] + moment_xy[p],
                         0.0,
                         0.0};
    const double area = quarter_area[before] + quarter_area[p] + w_size;
    g.corner[p] = Vec3{in_plane_x, in_plane_y, -w};
    g.corner[p + 4] = Vec3{in_plane_x, in_plane_y, w};
    g.normal_moment[p] = moment;
    g.normal_moment[p + 4] = moment;
    g.corner_face_area[p] = area;
    g.corner_face_area[p + 4] = area;
  }
}

// The geometry of a cell, in closed form when it is a z prism.
template <bool kCornerSums = true>
KOKKOS_INLINE_FUNCTION void cellGeometry(const Vec3 x[8], bool z_prism, CellGeometry& g) {
  if (z_prism) {
    prismGeometry<kCornerSums>(x, g);
  } else {
    cellGeometry<kCornerSums>(x, g);
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
