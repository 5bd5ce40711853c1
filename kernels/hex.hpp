// Geometry of one 8-node hexahedron (VTK_HEXAHEDRON order), docs/method.md §A2: each
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

// Corner-face area vectors from the triangles (docs/method.md §A2):
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
// nodal impedance is made of (docs/method.md §A4),
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

#if LAGREMAP_CELL_PACKS
// kCellLanes cells in the lanes of one vector (GCC vector extensions).
constexpr int kCellLanes = 4;
using CellPack = double __attribute__((vector_size(kCellLanes * sizeof(double))));
#else
constexpr int kCellLanes = 1;
#endif

namespace detail {

KOKKOS_FORCEINLINE_FUNCTION double laneSqrt(double v) {
  return math::sqrt(v);
}
#if LAGREMAP_CELL_PACKS
inline CellPack laneSqrt(CellPack v) {
  CellPack root;
  for (int i = 0; i < kCellLanes; ++i) root[i] = __builtin_sqrt(v[i]);
  return root;
}
#endif

// The scalar of the sweep below: a double (one cell), or on CPU builds a pack
// of kCellLanes doubles (kCellLanes cells in the lanes of one vector
// register). Both take the same arithmetic, comparisons and `?:` selections,
// lane by lane, so a cell's numbers are the same bits either way.
template <class Real>
struct Point {
  Real x, y, z;
};
template <class Real>
KOKKOS_FORCEINLINE_FUNCTION Point<Real> operator+(const Point<Real>& a, const Point<Real>& b) {
  return {a.x + b.x, a.y + b.y, a.z + b.z};
}
template <class Real>
KOKKOS_FORCEINLINE_FUNCTION Point<Real> operator-(const Point<Real>& a, const Point<Real>& b) {
  return {a.x - b.x, a.y - b.y, a.z - b.z};
}
template <class Real, class Scale>
KOKKOS_FORCEINLINE_FUNCTION Point<Real> operator*(const Scale& s, const Point<Real>& a) {
  return {s * a.x, s * a.y, s * a.z};
}
template <class Real>
KOKKOS_FORCEINLINE_FUNCTION Real dot(const Point<Real>& a, const Point<Real>& b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}
template <class Real>
KOKKOS_FORCEINLINE_FUNCTION Point<Real> cross(const Point<Real>& a, const Point<Real>& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
// What the sweep accumulates, in the scalar of the sweep.
template <class Real>
struct Sums {
  Point<Real> corner[8];
  Real moment[8][6];  // xx, yy, zz, xy, yz, xz
  Real area[8];
  Real volume, max_face_area;
  Point<Real> centroid;
};

// The 24-triangle sweep of cellGeometry below, for a scalar Real.
template <bool kCornerSums, class Real>
KOKKOS_FORCEINLINE_FUNCTION void sweepTriangles(const Point<Real> x[8], Sums<Real>& g) {
  const Point<Real> origin = x[0];
  // Constant factors are folded out of the 24-triangle loop: with the doubled
  // triangle area vectors T_k = (q_k+1 - q_k) x (face point - q_k) = 2 s_t n_t,
  // the tetrahedron (origin, q_k, q_k+1, face point) has volume q_k . T_k / 6
  // and centroid (q_k + q_k+1 + face point) / 4, so
  //   volume = sum(q_k . T_k) / 6,
  //   centroid = sum((q_k . T_k)(q_k + q_k+1 + fp)) / (4 sum(q_k . T_k)).
  Real six_volume = Real{}, max_area2 = Real{};
  Point<Real> weighted_sum{Real{}, Real{}, Real{}};  // relative to origin
  if constexpr (kCornerSums) {
    for (int p = 0; p < 8; ++p) {
      g.corner[p] = Point<Real>{Real{}, Real{}, Real{}};
      for (int i = 0; i < 6; ++i) g.moment[p][i] = Real{};
      g.area[p] = Real{};
    }
  }
  LAGREMAP_UNROLL
  for (int f = 0; f < 6; ++f) {
    Point<Real> q[4];
    for (int k = 0; k < 4; ++k) q[k] = x[faceNode(f, k)] - origin;
    const Point<Real> face_point = 0.25 * (q[0] + q[1] + q[2] + q[3]);
    Point<Real> doubled[4];  // T_k = 2 s_t n_t
    for (int k = 0; k < 4; ++k) doubled[k] = cross(q[(k + 1) & 3] - q[k], face_point - q[k]);
    const Point<Real> doubled_face = doubled[0] + doubled[1] + doubled[2] + doubled[3];
    LAGREMAP_UNROLL
    for (int k = 0; k < 4; ++k) {
      const Real weight = dot(q[k], doubled[k]);
      six_volume += weight;
      weighted_sum = weighted_sum + weight * (q[k] + q[(k + 1) & 3] + face_point);
      if constexpr (!kCornerSums) continue;
      // s_pf n_pf = 1/3 (t_k-1 + t_k + 1/4 face) = 1/6 (T_k-1 + T_k + 1/4 sum T)
      const Point<Real> w = (1.0 / 6.0) * (doubled[(k + 3) & 3] + doubled[k] + 0.25 * doubled_face);
      const int p = faceNode(f, k);
      g.corner[p] = g.corner[p] + w;
      // a degenerate corner face has no normal and adds nothing (a sum that
      // is never -0 is unchanged by adding +0)
      const Real area2 = dot(w, w);
      const auto has_area = area2 > Real{};
      const Real area = laneSqrt(area2);
      const Point<Real> n = (1.0 / area) * w;
      Real* m = g.moment[p];
      m[0] += has_area ? n.x * w.x : Real{};
      m[1] += has_area ? n.y * w.y : Real{};
      m[2] += has_area ? n.z * w.z : Real{};
      m[3] += has_area ? n.x * w.y : Real{};
      m[4] += has_area ? n.y * w.z : Real{};
      m[5] += has_area ? n.x * w.z : Real{};
      g.area[p] += has_area ? area : Real{};
    }
    const Real area2 = 0.25 * dot(doubled_face, doubled_face);
    max_area2 = area2 > max_area2 ? area2 : max_area2;
  }
  g.volume = six_volume / 6.0;
  g.centroid = origin + (0.25 / six_volume) * weighted_sum;
  g.max_face_area = laneSqrt(max_area2);
}

// Lane i of the sums into g (the corner arrays only with kCornerSums).
template <bool kCornerSums, class Real, class Lane>
KOKKOS_FORCEINLINE_FUNCTION void storeSums(const Sums<Real>& sums, const Lane& lane,
                                           CellGeometry& g) {
  g.shape = {lane(sums.volume),
             Vec3{lane(sums.centroid.x), lane(sums.centroid.y), lane(sums.centroid.z)},
             lane(sums.max_face_area)};
  if constexpr (kCornerSums) {
    for (int p = 0; p < 8; ++p) {
      g.corner[p] = Vec3{lane(sums.corner[p].x), lane(sums.corner[p].y), lane(sums.corner[p].z)};
      const Real* m = sums.moment[p];
      g.normal_moment[p] =
          SymMat3{lane(m[0]), lane(m[1]), lane(m[2]), lane(m[3]), lane(m[4]), lane(m[5])};
      g.corner_face_area[p] = lane(sums.area[p]);
    }
  }
}

}  // namespace detail

// kCornerSums = false: g.shape only (the corner arrays are left as they are),
// with the same arithmetic, so the same bits, as the full sweep.
template <bool kCornerSums = true>
KOKKOS_INLINE_FUNCTION void cellGeometry(const Vec3 x[8], CellGeometry& g) {
  detail::Point<double> points[8];
  for (int p = 0; p < 8; ++p) points[p] = {x[p].x, x[p].y, x[p].z};
  detail::Sums<double> sums;
  detail::sweepTriangles<kCornerSums>(points, sums);
  detail::storeSums<kCornerSums>(
      sums, [](double v) { return v; }, g);
}

// The geometry of kCellLanes cells at once (the general sweep in the lanes of
// a vector: the same bits as cellGeometry cell by cell); x[i]: the 8 nodes of
// cell i.
template <bool kCornerSums = true>
KOKKOS_INLINE_FUNCTION void cellGeometries(const Vec3 x[kCellLanes][8],
                                           CellGeometry g[kCellLanes]) {
#if LAGREMAP_CELL_PACKS
  detail::Point<CellPack> points[8];
  for (int p = 0; p < 8; ++p) {
    for (int i = 0; i < kCellLanes; ++i) {
      points[p].x[i] = x[i][p].x;
      points[p].y[i] = x[i][p].y;
      points[p].z[i] = x[i][p].z;
    }
  }
  detail::Sums<CellPack> sums;
  detail::sweepTriangles<kCornerSums>(points, sums);
  for (int i = 0; i < kCellLanes; ++i) {
    detail::storeSums<kCornerSums>(
        sums, [i](const CellPack& v) { return v[i]; }, g[i]);
  }
#else
  for (int i = 0; i < kCellLanes; ++i) cellGeometry<kCornerSums>(x[i], g[i]);
#endif
}

// The corner sums of prismGeometry: from the height, the bottom edges e_k and
// their squared lengths, the quad's doubled triangle areas T_k and their sum.
KOKKOS_INLINE_FUNCTION void prismCornerSums(double height, const double edge_x[4],
                                            const double edge_y[4], const double edge2[4],
                                            const double doubled[4], double twice_area,
                                            CellGeometry& g) {
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
  if constexpr (kCornerSums) prismCornerSums(height, edge_x, edge_y, edge2, doubled, twice_area, g);
}

// The 8 corner vectors A_cp = sum_f s_pf n_pf = d v_c / d x_p (GCL, docs/method.md §A2).
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
