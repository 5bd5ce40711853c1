// Piecewise-linear reconstruction (DESIGN §3 second order, §5): least-squares
// gradients over face neighbours and the Barth-Jespersen family of limiters.
//
// Across a wall/symmetry face the missing neighbour is replaced by the mirror
// image of the cell (reflected centroid, reflected velocity, same pressure): the
// least-squares system stays well posed in the thin directions of 1D/2D runs,
// and the reconstruction respects the symmetry exactly.
#pragma once

#include "math.hpp"

namespace lagremap {

// Accumulates the normal equations  sum dx (x) dx  g = sum dx dpsi.
struct LeastSquares {
  SymMat3 normal_matrix{0, 0, 0, 0, 0, 0};

  KOKKOS_INLINE_FUNCTION void addOffset(const Vec3& dx) { normal_matrix += outerSelf(dx, 1.0); }

  // Inverse of the normal matrix, lightly regularised so a direction without
  // any neighbour (a one-cell-thick free slab) gets a zero gradient, not NaN.
  KOKKOS_INLINE_FUNCTION SymMat3 solver() const {
    SymMat3 m = normal_matrix;
    const double regularization = 1e-12 * trace(m);
    m.xx += regularization;
    m.yy += regularization;
    m.zz += regularization;
    return inverse(m);
  }
};

// Running min/max of a scalar over a stencil.
struct Bounds {
  double lo, hi;
  KOKKOS_INLINE_FUNCTION explicit Bounds(double value) : lo(value), hi(value) {}
  KOKKOS_INLINE_FUNCTION void include(double value) {
    lo = value < lo ? value : lo;
    hi = value > hi ? value : hi;
  }
};

// Largest rise and fall of the unlimited reconstruction over a cell's vertices.
struct VertexExcursion {
  double rise = 0.0, fall = 0.0;  // max(psi_p - psi_c, 0), min(psi_p - psi_c, 0)
  KOKKOS_INLINE_FUNCTION void include(double delta) {
    rise = delta > rise ? delta : rise;
    fall = delta < fall ? delta : fall;
  }
};

// min over the vertices of vertexLimiter() below, with two divisions instead of
// one per vertex: the ratio (bound - psi_c) / delta is smallest for the largest
// rise (resp. fall), so only the extreme vertices matter.
KOKKOS_INLINE_FUNCTION double cellLimiter(const VertexExcursion& excursion, double center,
                                          const Bounds& bounds, double beta) {
  double limiter = beta;
  if (excursion.rise > 0.0) {
    const double ratio = (bounds.hi - center) / excursion.rise;
    limiter = ratio < limiter ? ratio : limiter;
  }
  if (excursion.fall < 0.0) {
    const double ratio = (bounds.lo - center) / excursion.fall;
    limiter = ratio < limiter ? ratio : limiter;
  }
  return limiter;
}

// Limiter factor of one vertex (DESIGN §5):
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

}  // namespace lagremap
