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

// One corner's part of it (the staged form computes a cell's corners one at a
// time, docs/method.md §7).
struct CornerSums {
  Vec3 vector;  // A_cp
  SymMat3 normal_moment;
  double area;
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
// One face of the sweep: its 4 nodes q_k relative to the cell's node 0, its
// face point, the doubled triangle area vectors
// T_k = (q_k+1 - q_k) x (face point - q_k) = 2 s_t n_t and their sum.
template <class Real>
struct FaceSweep {
  Point<Real> q[4], face_point, doubled[4], doubled_face;
};
template <class Real, class NodeAt>
KOKKOS_FORCEINLINE_FUNCTION void sweepFace(const NodeAt& node, const Point<Real>& origin, int f,
                                           FaceSweep<Real>& face) {
  for (int k = 0; k < 4; ++k) face.q[k] = node(faceNode(f, k)) - origin;
  face.face_point = 0.25 * (face.q[0] + face.q[1] + face.q[2] + face.q[3]);
  for (int k = 0; k < 4; ++k) {
    face.doubled[k] = cross(face.q[(k + 1) & 3] - face.q[k], face.face_point - face.q[k]);
  }
  face.doubled_face = face.doubled[0] + face.doubled[1] + face.doubled[2] + face.doubled[3];
}
// What a face adds to the sums of the cell's shape: with the doubled
// triangle area vectors T_k, the tetrahedron (origin, q_k, q_k+1, face point)
// has volume q_k . T_k / 6 and centroid (q_k + q_k+1 + face point) / 4, so
//   volume = sum(q_k . T_k) / 6,
//   centroid = sum((q_k . T_k)(q_k + q_k+1 + fp)) / (4 sum(q_k . T_k))
// (the constant factors folded out of the 24-triangle loop).
// Triangle k's terms, its weight q_k . T_k and weighted point, and the face's
// squared area, are also taken one at a time (the staged form's lanes).
template <class Real>
KOKKOS_FORCEINLINE_FUNCTION Real triangleWeight(const FaceSweep<Real>& face, int k) {
  return dot(face.q[k], face.doubled[k]);
}
template <class Real>
KOKKOS_FORCEINLINE_FUNCTION Point<Real> weightedTrianglePoint(const FaceSweep<Real>& face, int k,
                                                              const Real& weight) {
  return weight * (face.q[k] + face.q[(k + 1) & 3] + face.face_point);
}
template <class Real>
KOKKOS_FORCEINLINE_FUNCTION Real faceArea2(const FaceSweep<Real>& face) {
  return 0.25 * dot(face.doubled_face, face.doubled_face);
}
template <class Real>
KOKKOS_FORCEINLINE_FUNCTION void addFaceToShape(const FaceSweep<Real>& face, Real& six_volume,
                                                Point<Real>& weighted_sum, Real& max_area2) {
  LAGREMAP_UNROLL
  for (int k = 0; k < 4; ++k) {
    const Real weight = triangleWeight(face, k);
    six_volume += weight;
    weighted_sum = weighted_sum + weightedTrianglePoint(face, k, weight);
  }
  const Real area2 = faceArea2(face);
  max_area2 = area2 > max_area2 ? area2 : max_area2;
}
// The shape from those sums (six_volume and weighted_sum relative to the
// cell's node 0, `origin`).
KOKKOS_INLINE_FUNCTION CellShape shapeOfSums(const Point<double>& origin, double six_volume,
                                             const Point<double>& weighted_sum, double max_area2) {
  const Point<double> centroid = origin + (0.25 / six_volume) * weighted_sum;
  return {six_volume / 6.0, Vec3{centroid.x, centroid.y, centroid.z}, math::sqrt(max_area2)};
}
// The corner-face vector of the face's node k:
//   s_pf n_pf = 1/3 (t_k-1 + t_k + 1/4 face) = 1/6 (T_k-1 + T_k + 1/4 sum T).
template <class Real>
KOKKOS_FORCEINLINE_FUNCTION Point<Real> cornerFaceVector(const FaceSweep<Real>& face, int k) {
  return (1.0 / 6.0) * (face.doubled[(k + 3) & 3] + face.doubled[k] + 0.25 * face.doubled_face);
}
// What one corner face adds to its corner's sums: its vector w, normal moment
// w (x) w / |w| and area |w|. A degenerate corner face has no normal and adds
// nothing (a sum that is never -0 is unchanged by adding +0).
template <class Real>
KOKKOS_FORCEINLINE_FUNCTION void addCornerFace(const Point<Real>& w, Point<Real>& corner,
                                               Real moment[6], Real& area) {
  corner = corner + w;
  const Real area2 = dot(w, w);
  const auto has_area = area2 > Real{};
  const Real size = laneSqrt(area2);
  const Point<Real> n = (1.0 / size) * w;
  moment[0] += has_area ? n.x * w.x : Real{};
  moment[1] += has_area ? n.y * w.y : Real{};
  moment[2] += has_area ? n.z * w.z : Real{};
  moment[3] += has_area ? n.x * w.y : Real{};
  moment[4] += has_area ? n.y * w.z : Real{};
  moment[5] += has_area ? n.x * w.z : Real{};
  area += has_area ? size : Real{};
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
  const auto node = [&](int n) -> const Point<Real>& { return x[n]; };
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
    FaceSweep<Real> face;
    sweepFace(node, origin, f, face);
    addFaceToShape(face, six_volume, weighted_sum, max_area2);
    if constexpr (kCornerSums) {
      LAGREMAP_UNROLL
      for (int k = 0; k < 4; ++k) {
        const int p = faceNode(f, k);
        addCornerFace(cornerFaceVector(face, k), g.corner[p], g.moment[p], g.area[p]);
      }
    }
  }
  g.volume = six_volume / 6.0;
  g.centroid = origin + (0.25 / six_volume) * weighted_sum;
  g.max_face_area = laneSqrt(max_area2);
}

// A node's position as a Point of the staged form's sweep.
template <class NodeAt>
KOKKOS_FORCEINLINE_FUNCTION Point<double> nodePoint(const NodeAt& node, int n) {
  const Vec3 x = node(n);
  return {x.x, x.y, x.z};
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

// The shape alone, in the sweep's order and arithmetic, so the same bits as
// cellGeometry (the staged form, docs/method.md §7.6). `node(n)` gives the
// position of the cell's node n (a GPU thread reads it from the mesh,
// through the cache, rather than hold all 8).
template <class NodeAt>
KOKKOS_INLINE_FUNCTION CellShape sweptShape(const NodeAt& node) {
  using detail::Point;
  const Point<double> origin = detail::nodePoint(node, 0);
  const auto point = [&](int n) { return detail::nodePoint(node, n); };
  double six_volume = 0.0, max_area2 = 0.0;
  Point<double> weighted_sum{0.0, 0.0, 0.0};  // relative to origin
  LAGREMAP_NO_UNROLL
  for (int f = 0; f < 6; ++f) {
    detail::FaceSweep<double> face;
    detail::sweepFace(point, origin, f, face);
    detail::addFaceToShape(face, six_volume, weighted_sum, max_area2);
  }
  return detail::shapeOfSums(origin, six_volume, weighted_sum, max_area2);
}

// Node p (VTK order: x bit set for 1, 2, 5, 6, y bit for 2, 3, 6, 7, z bit
// for 4..7) lies on faces x-/x+ (0/1), y-/y+ (2/3) and z-/z+ (4/5): its i-th
// face in increasing order, the sweep's.
KOKKOS_INLINE_FUNCTION int faceOfNode(int p, int i) {
  const int q = p & 3;
  const int side = i == 0 ? (q == 1 || q == 2) : i == 1 ? (q >= 2) : (p >= 4);
  return 2 * i + side;
}

// Corner p's sums from its 3 corner-face vectors, added in the sweep's
// (face) order, so the same bits as cellGeometry's: `face_vector(f, k)` gives
// the corner-face vector of node k of face f (detail::cornerFaceVector; the
// staged form's face lanes leave them in scratch memory).
template <class FaceVector>
KOKKOS_INLINE_FUNCTION CornerSums cornerOfFaces(const FaceVector& face_vector, int p) {
  detail::Point<double> vector{0.0, 0.0, 0.0};
  double moment[6] = {0.0, 0.0, 0.0, 0.0, 0.0, 0.0}, area = 0.0;
  LAGREMAP_NO_UNROLL
  for (int i = 0; i < 3; ++i) {
    const int f = faceOfNode(p, i);
    int k = 0;  // p's place on face f
    for (int j = 1; j < 4; ++j) k = faceNode(f, j) == p ? j : k;
    detail::addCornerFace(face_vector(f, k), vector, moment, area);
  }
  return {Vec3{vector.x, vector.y, vector.z},
          SymMat3{moment[0], moment[1], moment[2], moment[3], moment[4], moment[5]}, area};
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
// What the corners of a z prism (prismGeometry) need besides its nodes:
// node 0 (the origin of the bottom quad's coordinates), the quad's mean point
// F, the height and the doubled area sum T.
struct PrismBase {
  double origin_x, origin_y, fx, fy, height, twice_area;
};

// Edge k of the base, P_k+1 - P_k, its squared length and its triangle's
// doubled area T_k = e_k x (F - P_k), for the bottom node coordinates px, py
// (relative to node 0).
struct PrismEdge {
  double x, y, length2, doubled;
};
KOKKOS_INLINE_FUNCTION PrismEdge prismEdge(double px, double py, double px_next, double py_next,
                                           double fx, double fy) {
  const double edge_x = px_next - px, edge_y = py_next - py;
  return {edge_x, edge_y, edge_x * edge_x + edge_y * edge_y,
          edge_x * (fy - py) - edge_y * (fx - px)};
}

// The base of the prism whose node n is at node(n), and its shape; its 4
// edges too where `edges` is given.
template <class NodeAt>
KOKKOS_INLINE_FUNCTION CellShape prismBase(const NodeAt& node, PrismBase& base,
                                           PrismEdge* edges = nullptr) {
  const Vec3 origin = node(0);
  const double height = node(4).z - origin.z;
  double px[4], py[4];  // the bottom quad relative to node 0
  for (int k = 0; k < 4; ++k) {
    const Vec3 x = node(k);
    px[k] = x.x - origin.x;
    py[k] = x.y - origin.y;
  }
  const double fx = 0.25 * (px[0] + px[1] + px[2] + px[3]);
  const double fy = 0.25 * (py[0] + py[1] + py[2] + py[3]);
  double twice_area = 0.0, weighted_x = 0.0, weighted_y = 0.0, longest2 = 0.0;
  for (int k = 0; k < 4; ++k) {
    const int next = (k + 1) & 3;
    const PrismEdge edge = prismEdge(px[k], py[k], px[next], py[next], fx, fy);
    if (edges) edges[k] = edge;
    twice_area += edge.doubled;
    weighted_x += edge.doubled * (px[k] + px[next] + fx);
    weighted_y += edge.doubled * (py[k] + py[next] + fy);
    longest2 = edge.length2 > longest2 ? edge.length2 : longest2;
  }
  base = {origin.x, origin.y, fx, fy, height, twice_area};
  const double quad_area = 0.5 * twice_area;
  const double side2 = height * height * longest2;
  const double max_area2 = quad_area * quad_area > side2 ? quad_area * quad_area : side2;
  const double third_over_area = 1.0 / (3.0 * twice_area);
  return {quad_area * height,
          origin + Vec3{third_over_area * weighted_x, third_over_area * weighted_y, 0.5 * height},
          math::sqrt(max_area2)};
}

// What the side face over an edge gives each of its 4 nodes: a quarter of it,
// vector S_k / 4 (in the xy plane), area |S_k| / 4 and normal moment
// S (x) S / (4 |S|) (a degenerate face adds no moment or area).
struct PrismQuarter {
  double x, y, area, moment_xx, moment_yy, moment_xy;
};
KOKKOS_INLINE_FUNCTION PrismQuarter prismQuarter(const PrismEdge& edge, double height) {
  const double length = math::sqrt(edge.length2);
  const double scale = length > 0.0 && height > 0.0 ? 0.25 * height / length : 0.0;
  return {0.25 * height * edge.y,    -0.25 * height * edge.x,   0.25 * height * length,
          scale * (edge.y * edge.y), scale * (edge.x * edge.x), -scale * (edge.x * edge.y)};
}

// Corner p's sums of a prism (p + 4 straight above p): its two side faces
// (edges p - 1 and p of the base, and their quarters) and the bottom (p < 4)
// or top face.
KOKKOS_INLINE_FUNCTION CornerSums prismCornerOfEdges(const PrismEdge& edge_before,
                                                     const PrismEdge& edge, const PrismQuarter& a,
                                                     const PrismQuarter& b, double twice_area,
                                                     int p) {
  const double w = (1.0 / 6.0) * (edge_before.doubled + edge.doubled + 0.25 * twice_area);
  const double w_size = math::fabs(w);
  return {Vec3{a.x + b.x, a.y + b.y, p < 4 ? -w : w},
          SymMat3{a.moment_xx + b.moment_xx, a.moment_yy + b.moment_yy, w_size,
                  a.moment_xy + b.moment_xy, 0.0, 0.0},
          a.area + b.area + w_size};
}

// The same from the nodes (the staged form: bottom nodes p - 1, p, p + 1).
template <class NodeAt>
KOKKOS_INLINE_FUNCTION CornerSums prismCorner(const NodeAt& node, const PrismBase& base, int p) {
  const int q = p & 3, before = (q + 3) & 3, next = (q + 1) & 3;
  const Vec3 x_before = node(before), x_q = node(q), x_next = node(next);
  const double px_before = x_before.x - base.origin_x, py_before = x_before.y - base.origin_y;
  const double px = x_q.x - base.origin_x, py = x_q.y - base.origin_y;
  const double px_next = x_next.x - base.origin_x, py_next = x_next.y - base.origin_y;
  const PrismEdge edge_before = prismEdge(px_before, py_before, px, py, base.fx, base.fy);
  const PrismEdge edge = prismEdge(px, py, px_next, py_next, base.fx, base.fy);
  return prismCornerOfEdges(edge_before, edge, prismQuarter(edge_before, base.height),
                            prismQuarter(edge, base.height), base.twice_area, p);
}

template <bool kCornerSums = true>
KOKKOS_INLINE_FUNCTION void prismGeometry(const Vec3 x[8], CellGeometry& g) {
  PrismBase base;
  PrismEdge edges[4];
  g.shape = prismBase([&](int n) { return x[n]; }, base, edges);
  if constexpr (kCornerSums) {
    PrismQuarter quarters[4];
    for (int k = 0; k < 4; ++k) quarters[k] = prismQuarter(edges[k], base.height);
    for (int p = 0; p < 4; ++p) {
      const int before = (p + 3) & 3;
      const CornerSums corner = prismCornerOfEdges(edges[before], edges[p], quarters[before],
                                                   quarters[p], base.twice_area, p);
      // node p + 4 above: the same sums, the top face's vector up (-(-w) = w)
      g.corner[p] = corner.vector;
      g.corner[p + 4] = Vec3{corner.vector.x, corner.vector.y, -corner.vector.z};
      g.normal_moment[p] = g.normal_moment[p + 4] = corner.normal_moment;
      g.corner_face_area[p] = g.corner_face_area[p + 4] = corner.area;
    }
  }
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

// Corner vector p alone, from its 3 faces in cornerVectors' order and
// arithmetic (the same bits), the two triangles of node p kept by selection:
// the staged form of cornerVectors, `node(n)` the position of node n.
template <class NodeAt>
KOKKOS_INLINE_FUNCTION Vec3 cornerVector(const NodeAt& node, int p) {
  Vec3 corner{0.0, 0.0, 0.0};
  LAGREMAP_NO_UNROLL
  for (int i = 0; i < 3; ++i) {
    const int f = faceOfNode(p, i);
    int k = 0;  // p's place on face f
    for (int j = 1; j < 4; ++j) k = faceNode(f, j) == p ? j : k;
    const int before = (k + 3) & 3;
    Vec3 q[4];
    LAGREMAP_UNROLL
    for (int j = 0; j < 4; ++j) q[j] = node(faceNode(f, j));
    const Vec3 face_point = 0.25 * (q[0] + q[1] + q[2] + q[3]);
    Vec3 face_area{}, own{}, previous{};
    LAGREMAP_UNROLL
    for (int j = 0; j < 4; ++j) {
      const Vec3 triangle = 0.5 * cross(q[(j + 1) & 3] - q[j], face_point - q[j]);
      face_area = j == 0 ? triangle : face_area + triangle;
      own = j == k ? triangle : own;
      previous = j == before ? triangle : previous;
    }
    corner += (1.0 / 3.0) * (previous + own + 0.25 * face_area);
  }
  return corner;
}

}  // namespace lagremap::hex
