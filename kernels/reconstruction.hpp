// Piecewise-linear reconstruction (docs/method.md §A5, §A10): least-squares
// gradients over face neighbours and the Barth-Jespersen family of limiters.
//
// Across a wall/symmetry face the missing neighbour is replaced by the mirror
// image of the cell (reflected centroid, reflected velocity, same pressure): the
// least-squares system stays well posed in the thin directions of 1D/2D runs,
// and the reconstruction respects the symmetry exactly.
#pragma once

#include "../data/math.hpp"

namespace lagremap {

// The functions below are written for a scalar Real, a double (one cell) or
// a pack of cells (CellPack: kCellLanes cells in the lanes of a vector,
// computeCornerTerms): tests are selections (`?:`), made the same way in
// every lane, so a cell's numbers are the same bits either way.

// Accumulates the normal equations  sum dx (x) dx  g = sum dx dpsi.
template <class Real>
struct LeastSquaresOf {
  SymMat3Of<Real> normal_matrix{Real{}, Real{}, Real{}, Real{}, Real{}, Real{}};

  KOKKOS_INLINE_FUNCTION void addOffset(const Vec3Of<Real>& dx) {
    normal_matrix += outerSelf(dx, 1.0);
  }

  // Inverse of the normal matrix on the directions the offsets span, zero on
  // the others: a direction without neighbours (a one-cell-thick slab, a 1D
  // bar) gets a zero gradient. The matrix is factored as L D L^T and a pivot
  // below kDegeneratePivot of the trace is dropped (D^+), with its column of
  // L. Not a small regularisation: a slab's neighbour centroids are coplanar
  // only to round-off, and a regularised z-gradient grows to many times the
  // in-plane one (docs/method.md §2.1).
  KOKKOS_INLINE_FUNCTION SymMat3Of<Real> solver() const {
    constexpr double kDegeneratePivot = 1e-8;
    const SymMat3Of<Real>& m = normal_matrix;
    const Real tol = kDegeneratePivot * trace(m);
    // m = L D L^T, L unit lower triangular
    const Real d0 = m.xx;
    const auto kept0 = d0 > tol;
    const Real l10 = kept0 ? m.xy / d0 : Real{};
    const Real l20 = kept0 ? m.xz / d0 : Real{};
    const Real d1 = m.yy - l10 * l10 * d0;
    const auto kept1 = d1 > tol;
    const Real l21 = kept1 ? (m.yz - l20 * l10 * d0) / d1 : Real{};
    const Real d2 = m.zz - l20 * l20 * d0 - l21 * l21 * d1;
    const auto kept2 = d2 > tol;
    // m^+ = L^-T D^+ L^-1, with the rows of L^-1 = [[1,0,0],[a,1,0],[b,c,1]]
    const Real a = -l10, c = -l21, b = l10 * l21 - l20;
    const Real inv0 = kept0 ? 1.0 / d0 : Real{};
    const Real inv1 = kept1 ? 1.0 / d1 : Real{};
    const Real inv2 = kept2 ? 1.0 / d2 : Real{};
    // (m^+)_ij = sum_k (L^-1)_ki d_k (L^-1)_kj
    return {inv0 + a * a * inv1 + b * b * inv2,
            inv1 + c * c * inv2,
            inv2,
            a * inv1 + b * c * inv2,
            c * inv2,
            b * inv2};
  }
};
using LeastSquares = LeastSquaresOf<double>;

// Running min/max of a scalar over a stencil.
template <class Real>
struct BoundsOf {
  Real lo, hi;
  KOKKOS_INLINE_FUNCTION explicit BoundsOf(Real value) : lo(value), hi(value) {}
  KOKKOS_INLINE_FUNCTION void include(Real value) {
    lo = value < lo ? value : lo;
    hi = value > hi ? value : hi;
  }
};
using Bounds = BoundsOf<double>;

// Largest rise and fall of the unlimited reconstruction over a cell's vertices.
template <class Real>
struct VertexExcursionOf {
  Real rise{}, fall{};  // max(psi_p - psi_c, 0), min(psi_p - psi_c, 0)
  KOKKOS_INLINE_FUNCTION void include(Real delta) {
    rise = delta > rise ? delta : rise;
    fall = delta < fall ? delta : fall;
  }
};
using VertexExcursion = VertexExcursionOf<double>;

// min over the vertices of vertexLimiter() below, with two divisions instead of
// one per vertex: the ratio (bound - psi_c) / delta is smallest for the largest
// rise (resp. fall), so only the extreme vertices matter.
template <class Real>
KOKKOS_INLINE_FUNCTION Real cellLimiter(const VertexExcursionOf<Real>& excursion, Real center,
                                        const BoundsOf<Real>& bounds, double beta) {
  Real limiter = splat<Real>(beta);
  if constexpr (std::is_same_v<Real, double>) {  // (a division only where it is needed)
    if (excursion.rise > 0.0) {
      const double ratio = (bounds.hi - center) / excursion.rise;
      limiter = ratio < limiter ? ratio : limiter;
    }
    if (excursion.fall < 0.0) {
      const double ratio = (bounds.lo - center) / excursion.fall;
      limiter = ratio < limiter ? ratio : limiter;
    }
  } else {
    const Real up = (bounds.hi - center) / excursion.rise;
    limiter = excursion.rise > Real{} && up < limiter ? up : limiter;
    const Real down = (bounds.lo - center) / excursion.fall;
    limiter = excursion.fall < Real{} && down < limiter ? down : limiter;
  }
  return limiter;
}

// Limiter factor of one vertex (docs/method.md §A10):
//   min((psi_max - psi_c)/(psi_p - psi_c), beta) if psi_p > psi_c, min((psi_min - psi_c)/..., beta)
//   if psi_p < psi_c, beta otherwise. beta = 1: Barth-Jespersen; beta = 2: compressive.
KOKKOS_INLINE_FUNCTION double vertexLimiter(double delta, double center, const Bounds& bounds,
                                            double beta) {
  double ratio = beta;
  if (delta > 0.0) {
    ratio = (bounds.hi - center) / delta;
  } else if (delta < 0.0) {
    ratio = (bounds.lo - center) / delta;
  }
  return ratio < beta ? ratio : beta;
}

// Frame-independent limiter of a vector or tensor field psi (docs/method.md §A10 for a
// field that is not a scalar; docs/method.md §2.3). At each vertex p the
// unlimited excursion delta_p = G d_p (G the least-squares gradient,
// d_p = x_p - x_c) is measured against the jumps j = psi_nb - psi_c projected
// on it (Frobenius inner product ":"), over the face neighbours and, with
// vertex_sums, standing for the edge and corner neighbours at the vertex, the
// sums of the jumps of the faces holding p (exact for a linear field on a
// parallelepiped mesh):
//   toward = max_j max(j : delta_p, 0),  away = max_j max(-j : delta_p, 0);
// phi is the largest value <= 1 with phi |delta_p|^2 <= f toward at every
// vertex. Built from inner products only, a rotated field gets the same phi;
// for a field along one fixed direction (a 1D run, transverse components at
// round-off or not) it is Barth-Jespersen on that component exactly. With
// face neighbours alone, a field whose jumps along x, y and z are orthogonal
// (any smooth 3D velocity field) is limited to 2/3 even where linear.
//   f = 1: Barth-Jespersen (the vertex value may reach the neighbour's).
//   plateau_guard: f = (1 + r^2)/2 with r = toward / away < 1. A cell whose
//     value sits next to one neighbour's and far from the other's (a one-cell
//     plateau, r -> 0) keeps its vertex value on its own side of the
//     midpoint, so the node's Riemann problem still sees half of the small
//     jump; with f = 1 it sees none, and the elastic precursor of a two-wave
//     solid never leaves the plastic front. f -> 1 as r -> 1: smooth profiles
//     are limited as by Barth-Jespersen (in 1D, not at all for r > 0.59; the
//     1D limiter function is r + r^3 near r = 0).
// Arguments: j : delta_p = dot(jumps[f], directions[p]) for the neighbour
// across local face f (VTK order: 0 x-, 1 x+, 2 y-, 3 y+, 4 z-, 5 z+; a
// missing neighbour is a zero jump, which changes nothing) and
// length2[p] = |delta_p|^2. A vector passes its jumps and excursions
// (directions = delta_p); a tensor passes the pulled-back jumps of pullBack()
// with directions = d_p, whose cost does not grow with its six components.
// Every vertex's measures are computed in lanes (VertexVectors); only the
// final minimum over the vertices is a scalar loop, in vertex order.
// kVertices = 4: the bottom vertices of a z prism alone, where the top ones
// would repeat their numbers (computeCornerTerms; the same minimum).
template <bool plateau_guard, bool vertex_sums, int kVertices = kHexVertices, class Real>
KOKKOS_INLINE_FUNCTION Real projectedLimiter(const Vec3Of<Real> jumps[6],
                                             const VertexVectorsOf<Real>& directions,
                                             const Real length2[8]) {
  // (the faces holding vertex p in the VTK hexahedron: x+ for p = 1, 2, 5, 6,
  // y+ for p & 2, z+ for p & 4)
  constexpr bool kOnXPlus[kHexVertices] = {false, true, true, false, false, true, true, false};
  Real toward[kHexVertices], away[kHexVertices];
  for (int p = 0; p < kVertices; ++p) toward[p] = away[p] = Real{};
  Real along[6][kHexVertices];
  for (int f = 0; f < 6; ++f) {
    dotEach<kVertices>(jumps[f], directions, along[f]);
    LAGREMAP_LANES
    for (int p = 0; p < kVertices; ++p) {
      toward[p] = along[f][p] > toward[p] ? along[f][p] : toward[p];
      if (plateau_guard) away[p] = -along[f][p] > away[p] ? -along[f][p] : away[p];
    }
  }
  if (vertex_sums) {
    LAGREMAP_LANES
    for (int p = 0; p < kVertices; ++p) {
      const Real fx = kOnXPlus[p] ? along[1][p] : along[0][p];
      const Real fy = (p & 2) ? along[3][p] : along[2][p];
      const Real fz = (p & 4) ? along[5][p] : along[4][p];
      const Real sums[4] = {fx + fy, fy + fz, fx + fz, fx + fy + fz};
      for (const Real& sum : sums) {
        toward[p] = sum > toward[p] ? sum : toward[p];
        if (plateau_guard) away[p] = -sum > away[p] ? -sum : away[p];
      }
    }
  }
  // phi <= reach / length2, with the guard's f = (1 + r^2)/2 multiplied
  // out (r = toward/away): one division, and only where a vertex lowers
  // phi (never for length2 = 0)
  Real reach[kHexVertices], length2_scaled[kHexVertices];
  LAGREMAP_LANES
  for (int p = 0; p < kVertices; ++p) {
    if constexpr (plateau_guard) {
      const auto guarded = toward[p] < away[p];
      reach[p] =
          guarded ? 0.5 * toward[p] * (away[p] * away[p] + toward[p] * toward[p]) : toward[p];
      length2_scaled[p] = guarded ? length2[p] * (away[p] * away[p]) : length2[p];
    } else {
      reach[p] = toward[p];
      length2_scaled[p] = length2[p];
    }
  }
  Real limiter = splat<Real>(1.0);
  for (int p = 0; p < kVertices; ++p) {
    if constexpr (std::is_same_v<Real, double>) {
      if (reach[p] < limiter * length2_scaled[p]) limiter = reach[p] / length2_scaled[p];
    } else {
      limiter = reach[p] < limiter * length2_scaled[p] ? reach[p] / length2_scaled[p] : limiter;
    }
  }
  return limiter;
}

// The same for directions given vertex by vertex.
template <bool plateau_guard, bool vertex_sums>
KOKKOS_INLINE_FUNCTION double projectedLimiter(const Vec3 jumps[6], const Vec3 directions[8],
                                               const double length2[8]) {
  VertexVectors lanes;
  for (int p = 0; p < kHexVertices; ++p) lanes.set(p, directions[p]);
  return projectedLimiter<plateau_guard, vertex_sums>(jumps, lanes, length2);
}

// Pulled-back jumps of a symmetric tensor field for projectedLimiter: with
// G's rows the gradients of the components xx, yy, zz, xy, yz, xz (the
// off-diagonal ones count twice in the Frobenius product),
// j : delta_p = (G^T j) . d_p; returns w = G^T j. (|delta_p|^2, the limiter's
// length2, is the Frobenius square of the excursion delta_p = G d_p itself,
// which the caller has at hand.)
template <class Real>
KOKKOS_INLINE_FUNCTION void pullBack(const Vec3Of<Real> gradients[6],
                                     const SymMat3Of<Real> jumps[6], Vec3Of<Real> pulled[6]) {
  for (int j = 0; j < 6; ++j) {
    const SymMat3Of<Real>& t = jumps[j];
    pulled[j] = t.xx * gradients[0] + t.yy * gradients[1] + t.zz * gradients[2] +
                (2.0 * t.xy) * gradients[3] + (2.0 * t.yz) * gradients[4] +
                (2.0 * t.xz) * gradients[5];
  }
}

// Jump of a symmetric tensor to its mirror image across a plane of unit normal
// n (the wall ghost of the stencil): R T R - T with R = I - 2 n (x) n, i.e.
//   -2 (n (x) Tn + Tn (x) n) + 4 (n.Tn) n (x) n.
template <class Real>
KOKKOS_INLINE_FUNCTION SymMat3Of<Real> mirrorJump(const SymMat3Of<Real>& t, const Vec3Of<Real>& n) {
  const Vec3Of<Real> tn = t * n;
  const Real nn4 = 4.0 * dot(n, tn);
  return {nn4 * n.x * n.x - 4.0 * n.x * tn.x,
          nn4 * n.y * n.y - 4.0 * n.y * tn.y,
          nn4 * n.z * n.z - 4.0 * n.z * tn.z,
          nn4 * n.x * n.y - 2.0 * (n.x * tn.y + tn.x * n.y),
          nn4 * n.y * n.z - 2.0 * (n.y * tn.z + tn.y * n.z),
          nn4 * n.x * n.z - 2.0 * (n.x * tn.z + tn.x * n.z)};
}

}  // namespace lagremap
