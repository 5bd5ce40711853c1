// Small aggregate value types for device code (CONTRIBUTING.md style 6): Vec3, Mat3 (full
// 3x3, row-major) and SymMat3 (xx, yy, zz, xy, yz, xz). All operations are
// KOKKOS_INLINE_FUNCTION and allocation-free so they run on any backend.
#pragma once

#include <type_traits>

#include "kokkos_compat.hpp"

namespace lagremap {

// Vec3 and SymMat3 are the double cases of Vec3Of / SymMat3Of, whose
// component type may also be a pack of cells (CellPack, kokkos_compat.hpp):
// the kernels written for a scalar Real then compute kCellLanes cells in the
// lanes of one vector, with the same operations in the same order, so a
// cell's numbers are the same bits either way (docs/method.md §7.1).
template <class Real>
struct Vec3Of {
  Real x, y, z;
};
using Vec3 = Vec3Of<double>;

// The scalar factor of a product: the component type itself (an int or a
// float converts to a double), or a double for a pack of cells.
template <class Real>
struct ScalarOf {
  using type = Real;
};
template <class Real>
using NotDouble = std::enable_if_t<!std::is_same_v<Real, double>, int>;

// v in every lane of a Real (a double: v itself).
template <class Real>
KOKKOS_INLINE_FUNCTION Real splat(double v) {
  if constexpr (std::is_same_v<Real, double>) {
    return v;
  } else {
    Real lanes;
    for (int i = 0; i < int(sizeof(Real) / sizeof(double)); ++i) lanes[i] = v;
    return lanes;
  }
}

template <class Real>
KOKKOS_INLINE_FUNCTION Vec3Of<Real> operator+(const Vec3Of<Real>& a, const Vec3Of<Real>& b) {
  return {a.x + b.x, a.y + b.y, a.z + b.z};
}
template <class Real>
KOKKOS_INLINE_FUNCTION Vec3Of<Real> operator-(const Vec3Of<Real>& a, const Vec3Of<Real>& b) {
  return {a.x - b.x, a.y - b.y, a.z - b.z};
}
template <class Real>
KOKKOS_INLINE_FUNCTION Vec3Of<Real> operator-(const Vec3Of<Real>& a) {
  return {-a.x, -a.y, -a.z};
}
template <class Real>
KOKKOS_FORCEINLINE_FUNCTION Vec3Of<Real> operator*(const typename ScalarOf<Real>::type& s,
                                                   const Vec3Of<Real>& a) {
  return {s * a.x, s * a.y, s * a.z};
}
template <class Real, NotDouble<Real> = 0>
KOKKOS_INLINE_FUNCTION Vec3Of<Real> operator*(double s, const Vec3Of<Real>& a) {
  return {s * a.x, s * a.y, s * a.z};
}
KOKKOS_INLINE_FUNCTION Vec3 operator*(const Vec3& a, double s) {
  return s * a;
}
template <class Real>
KOKKOS_INLINE_FUNCTION Vec3Of<Real>& operator+=(Vec3Of<Real>& a, const Vec3Of<Real>& b) {
  a.x += b.x;
  a.y += b.y;
  a.z += b.z;
  return a;
}
KOKKOS_INLINE_FUNCTION Vec3& operator-=(Vec3& a, const Vec3& b) {
  a.x -= b.x;
  a.y -= b.y;
  a.z -= b.z;
  return a;
}
template <class Real>
KOKKOS_INLINE_FUNCTION Real dot(const Vec3Of<Real>& a, const Vec3Of<Real>& b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}
template <class Real>
KOKKOS_INLINE_FUNCTION Vec3Of<Real> cross(const Vec3Of<Real>& a, const Vec3Of<Real>& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
KOKKOS_INLINE_FUNCTION double norm(const Vec3& a) {
  return math::sqrt(dot(a, a));
}

// One vector per vertex of a hexahedron, in lanes (structure of arrays): a
// loop over the 8 vertices compiles to a few vector instructions (two AVX2
// registers a component) where an array of Vec3 takes 8 scalar dot products.
// The lane functions do the same operations in the same order as their Vec3
// counterparts, so the results are the same bits.
constexpr int kHexVertices = 8;
template <class Real>
struct VertexVectorsOf {
  Real x[kHexVertices], y[kHexVertices], z[kHexVertices];
  KOKKOS_INLINE_FUNCTION Vec3Of<Real> operator[](int p) const { return {x[p], y[p], z[p]}; }
  KOKKOS_INLINE_FUNCTION void set(int p, const Vec3Of<Real>& v) {
    x[p] = v.x;
    y[p] = v.y;
    z[p] = v.z;
  }
};
using VertexVectors = VertexVectorsOf<double>;
// out_p = dot(g, d_p) at every vertex p < kVertices (4: a z prism's bottom
// vertices, whose top ones repeat them).
template <int kVertices = kHexVertices, class Real>
KOKKOS_INLINE_FUNCTION void dotEach(const Vec3Of<Real>& g, const VertexVectorsOf<Real>& d,
                                    Real out[8]) {
  LAGREMAP_LANES
  for (int p = 0; p < kVertices; ++p) out[p] = g.x * d.x[p] + g.y * d.y[p] + g.z * d.z[p];
}
// out_p = dot(a_p, b_p) at every vertex p < kVertices.
template <int kVertices = kHexVertices, class Real>
KOKKOS_INLINE_FUNCTION void dotEach(const VertexVectorsOf<Real>& a, const VertexVectorsOf<Real>& b,
                                    Real out[8]) {
  LAGREMAP_LANES
  for (int p = 0; p < kVertices; ++p) {
    out[p] = a.x[p] * b.x[p] + a.y[p] * b.y[p] + a.z[p] * b.z[p];
  }
}

// Symmetric 3x3 tensor, Voigt-like order xx, yy, zz, xy, yz, xz.
template <class Real>
struct SymMat3Of {
  Real xx, yy, zz, xy, yz, xz;
};
using SymMat3 = SymMat3Of<double>;

template <class Real>
KOKKOS_INLINE_FUNCTION SymMat3Of<Real> operator+(const SymMat3Of<Real>& a,
                                                 const SymMat3Of<Real>& b) {
  return {a.xx + b.xx, a.yy + b.yy, a.zz + b.zz, a.xy + b.xy, a.yz + b.yz, a.xz + b.xz};
}
template <class Real>
KOKKOS_INLINE_FUNCTION SymMat3Of<Real>& operator+=(SymMat3Of<Real>& a, const SymMat3Of<Real>& b) {
  a = a + b;
  return a;
}
template <class Real>
KOKKOS_INLINE_FUNCTION SymMat3Of<Real> operator*(const typename ScalarOf<Real>::type& s,
                                                 const SymMat3Of<Real>& a) {
  return {s * a.xx, s * a.yy, s * a.zz, s * a.xy, s * a.yz, s * a.xz};
}
template <class Real, NotDouble<Real> = 0>
KOKKOS_INLINE_FUNCTION SymMat3Of<Real> operator*(double s, const SymMat3Of<Real>& a) {
  return {s * a.xx, s * a.yy, s * a.zz, s * a.xy, s * a.yz, s * a.xz};
}
template <class Real>
KOKKOS_INLINE_FUNCTION Vec3Of<Real> operator*(const SymMat3Of<Real>& m, const Vec3Of<Real>& v) {
  return {m.xx * v.x + m.xy * v.y + m.xz * v.z, m.xy * v.x + m.yy * v.y + m.yz * v.z,
          m.xz * v.x + m.yz * v.y + m.zz * v.z};
}
template <class Real = double>
KOKKOS_INLINE_FUNCTION SymMat3Of<Real> identitySym(Real s = Real(1.0)) {
  return {s, s, s, Real{}, Real{}, Real{}};
}
// a (x) a / scale
template <class Real>
KOKKOS_INLINE_FUNCTION SymMat3Of<Real> outerSelf(const Vec3Of<Real>& a, double scale) {
  return {scale * a.x * a.x, scale * a.y * a.y, scale * a.z * a.z,
          scale * a.x * a.y, scale * a.y * a.z, scale * a.x * a.z};
}
template <class Real>
KOKKOS_INLINE_FUNCTION Real trace(const SymMat3Of<Real>& m) {
  return m.xx + m.yy + m.zz;
}
KOKKOS_INLINE_FUNCTION double det(const SymMat3& m) {
  return m.xx * (m.yy * m.zz - m.yz * m.yz) - m.xy * (m.xy * m.zz - m.yz * m.xz) +
         m.xz * (m.xy * m.yz - m.yy * m.xz);
}
KOKKOS_INLINE_FUNCTION SymMat3 dev(const SymMat3& m) {
  const double third_trace = trace(m) / 3.0;
  return {m.xx - third_trace, m.yy - third_trace, m.zz - third_trace, m.xy, m.yz, m.xz};
}
// Inverse by cofactors; the caller guarantees det != 0.
KOKKOS_INLINE_FUNCTION SymMat3 inverse(const SymMat3& m) {
  const double c_xx = m.yy * m.zz - m.yz * m.yz;
  const double c_xy = m.xz * m.yz - m.xy * m.zz;
  const double c_xz = m.xy * m.yz - m.yy * m.xz;
  const double inv_det = 1.0 / (m.xx * c_xx + m.xy * c_xy + m.xz * c_xz);
  return {
      inv_det * c_xx, inv_det * (m.xx * m.zz - m.xz * m.xz), inv_det * (m.xx * m.yy - m.xy * m.xy),
      inv_det * c_xy, inv_det * (m.xy * m.xz - m.xx * m.yz), inv_det * c_xz};
}
KOKKOS_INLINE_FUNCTION double ddot(const SymMat3& a, const SymMat3& b) {
  return a.xx * b.xx + a.yy * b.yy + a.zz * b.zz + 2.0 * (a.xy * b.xy + a.yz * b.yz + a.xz * b.xz);
}
template <class Real>
KOKKOS_INLINE_FUNCTION SymMat3Of<Real> operator-(const SymMat3Of<Real>& a,
                                                 const SymMat3Of<Real>& b) {
  return {a.xx - b.xx, a.yy - b.yy, a.zz - b.zz, a.xy - b.xy, a.yz - b.yz, a.xz - b.xz};
}
// Frobenius norm sqrt(a : a), the von Mises measure of a deviator (docs/method.md §A7).
KOKKOS_INLINE_FUNCTION double norm(const SymMat3& a) {
  return math::sqrt(ddot(a, a));
}

// General 3x3 tensor, row-major: m[i][j].
struct Mat3 {
  double m[3][3];
};

KOKKOS_INLINE_FUNCTION Mat3 zeroMat() {
  return {{{0, 0, 0}, {0, 0, 0}, {0, 0, 0}}};
}
// a (x) b accumulated with weight s: m_ij += s a_i b_j
KOKKOS_FORCEINLINE_FUNCTION void addOuter(Mat3& m, double s, const Vec3& a, const Vec3& b) {
  const double as[3] = {s * a.x, s * a.y, s * a.z};
  const double bs[3] = {b.x, b.y, b.z};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) m.m[i][j] += as[i] * bs[j];
}
KOKKOS_INLINE_FUNCTION Vec3 operator*(const Mat3& a, const Vec3& v) {
  return {a.m[0][0] * v.x + a.m[0][1] * v.y + a.m[0][2] * v.z,
          a.m[1][0] * v.x + a.m[1][1] * v.y + a.m[1][2] * v.z,
          a.m[2][0] * v.x + a.m[2][1] * v.y + a.m[2][2] * v.z};
}
KOKKOS_INLINE_FUNCTION double trace(const Mat3& a) {
  return a.m[0][0] + a.m[1][1] + a.m[2][2];
}
KOKKOS_INLINE_FUNCTION SymMat3 symPart(const Mat3& a) {
  return {a.m[0][0],
          a.m[1][1],
          a.m[2][2],
          0.5 * (a.m[0][1] + a.m[1][0]),
          0.5 * (a.m[1][2] + a.m[2][1]),
          0.5 * (a.m[0][2] + a.m[2][0])};
}
// (a - a^T)/2, e.g. the spin W of a velocity gradient.
KOKKOS_INLINE_FUNCTION Mat3 skewPart(const Mat3& a) {
  Mat3 w;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) w.m[i][j] = 0.5 * (a.m[i][j] - a.m[j][i]);
  return w;
}
KOKKOS_INLINE_FUNCTION Mat3 identityMat(double s = 1.0) {
  return {{{s, 0, 0}, {0, s, 0}, {0, 0, s}}};
}
KOKKOS_INLINE_FUNCTION Mat3 fullMat(const SymMat3& a) {
  return {{{a.xx, a.xy, a.xz}, {a.xy, a.yy, a.yz}, {a.xz, a.yz, a.zz}}};
}
KOKKOS_INLINE_FUNCTION Mat3 transpose(const Mat3& a) {
  Mat3 t;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) t.m[i][j] = a.m[j][i];
  return t;
}
KOKKOS_INLINE_FUNCTION Mat3 operator+(const Mat3& a, const Mat3& b) {
  Mat3 c;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) c.m[i][j] = a.m[i][j] + b.m[i][j];
  return c;
}
KOKKOS_INLINE_FUNCTION Mat3 operator-(const Mat3& a, const Mat3& b) {
  Mat3 c;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) c.m[i][j] = a.m[i][j] - b.m[i][j];
  return c;
}
KOKKOS_INLINE_FUNCTION Mat3 operator*(double s, const Mat3& a) {
  Mat3 c;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) c.m[i][j] = s * a.m[i][j];
  return c;
}
KOKKOS_INLINE_FUNCTION Mat3 operator*(const Mat3& a, const Mat3& b) {
  Mat3 c;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      c.m[i][j] = a.m[i][0] * b.m[0][j] + a.m[i][1] * b.m[1][j] + a.m[i][2] * b.m[2][j];
  return c;
}
KOKKOS_INLINE_FUNCTION double det(const Mat3& a) {
  return a.m[0][0] * (a.m[1][1] * a.m[2][2] - a.m[1][2] * a.m[2][1]) -
         a.m[0][1] * (a.m[1][0] * a.m[2][2] - a.m[1][2] * a.m[2][0]) +
         a.m[0][2] * (a.m[1][0] * a.m[2][1] - a.m[1][1] * a.m[2][0]);
}

// Inverse by cofactors (adjugate over determinant); the caller guarantees det != 0.
KOKKOS_INLINE_FUNCTION Mat3 inverse(const Mat3& a) {
  Mat3 inv;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      // cofactor of a_ji (transposed), cyclic indices give the sign
      const int r0 = (j + 1) % 3, r1 = (j + 2) % 3, c0 = (i + 1) % 3, c1 = (i + 2) % 3;
      inv.m[i][j] = a.m[r0][c0] * a.m[r1][c1] - a.m[r0][c1] * a.m[r1][c0];
    }
  const double inv_det =
      1.0 / (a.m[0][0] * inv.m[0][0] + a.m[0][1] * inv.m[1][0] + a.m[0][2] * inv.m[2][0]);
  return inv_det * inv;
}

// View accessors: read/write one entity's Vec3 / SymMat3 from SoA Views.
template <class View>
KOKKOS_INLINE_FUNCTION Vec3 loadVec3(const View& v, int i) {
  return {v(i, 0), v(i, 1), v(i, 2)};
}
template <class View>
KOKKOS_INLINE_FUNCTION void storeVec3(const View& v, int i, const Vec3& a) {
  v(i, 0) = a.x;
  v(i, 1) = a.y;
  v(i, 2) = a.z;
}
template <class View>
KOKKOS_FORCEINLINE_FUNCTION SymMat3 loadSym(const View& v, int i) {
  return {v(i, 0), v(i, 1), v(i, 2), v(i, 3), v(i, 4), v(i, 5)};
}
template <class View>
KOKKOS_FORCEINLINE_FUNCTION void storeSym(const View& v, int i, const SymMat3& a) {
  v(i, 0) = a.xx;
  v(i, 1) = a.yy;
  v(i, 2) = a.zz;
  v(i, 3) = a.xy;
  v(i, 4) = a.yz;
  v(i, 5) = a.xz;
}

// Per-material tensors: entity i, material k.
template <class View>
KOKKOS_FORCEINLINE_FUNCTION SymMat3 loadSym(const View& v, int i, int k) {
  return {v(i, k, 0), v(i, k, 1), v(i, k, 2), v(i, k, 3), v(i, k, 4), v(i, k, 5)};
}
template <class View>
KOKKOS_FORCEINLINE_FUNCTION void storeSym(const View& v, int i, int k, const SymMat3& a) {
  v(i, k, 0) = a.xx;
  v(i, k, 1) = a.yy;
  v(i, k, 2) = a.zz;
  v(i, k, 3) = a.xy;
  v(i, k, 4) = a.yz;
  v(i, k, 5) = a.xz;
}

}  // namespace lagremap
