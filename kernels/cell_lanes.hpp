// Cells in the lanes of a vector: loads and stores of a cell's values for a
// scalar Real that is a double (one cell) or, on CPU builds, a CellPack of
// kCellLanes cells (the fused corner kernel, corner_terms_fused.hpp; the same
// bits as cell by cell, docs/method.md §7.1).
#pragma once

#include "../data/math.hpp"
#include "../data/types.hpp"
#include "hex.hpp"

namespace lagremap {

namespace detail {

// The corner kernel is written for a scalar Real (reconstruction.hpp): a
// double, one cell, or on CPU builds a CellPack, kCellLanes consecutive cells
// whose stencils have the same shape (lanesShareStencilShape), in the lanes of
// one vector. Its loads and stores go lane by lane.
template <class Real>
constexpr int kLanesOf = 1;
#if LAGREMAP_CELL_PACKS
template <>
constexpr int kLanesOf<hex::CellPack> = hex::kCellLanes;
#endif

// The lanes' cells: cell[i] of lane i.
template <class Real>
struct CellLanes {
  Index cell[kLanesOf<Real>];
};

// value(i) of every lane i.
template <class Real, class Value>
KOKKOS_FORCEINLINE_FUNCTION Real gatherLanes(const Value& value) {
  if constexpr (kLanesOf<Real> == 1) {
    return value(0);
  } else {
    Real lanes;
    for (int i = 0; i < kLanesOf<Real>; ++i) lanes[i] = value(i);
    return lanes;
  }
}
template <class Real>
KOKKOS_FORCEINLINE_FUNCTION double laneOf(const Real& value, int i) {
  if constexpr (kLanesOf<Real> == 1) {
    return value;
  } else {
    return value[i];
  }
}
template <class Real, class View>
KOKKOS_FORCEINLINE_FUNCTION Real loadLanes(const View& v, const CellLanes<Real>& at) {
  return gatherLanes<Real>([&](int i) { return v(at.cell[i]); });
}
template <class Real, class View>
KOKKOS_FORCEINLINE_FUNCTION Vec3Of<Real> loadVec3Lanes(const View& v, const CellLanes<Real>& at) {
  return {gatherLanes<Real>([&](int i) { return v(at.cell[i], 0); }),
          gatherLanes<Real>([&](int i) { return v(at.cell[i], 1); }),
          gatherLanes<Real>([&](int i) { return v(at.cell[i], 2); })};
}
template <class Real, class View>
KOKKOS_FORCEINLINE_FUNCTION SymMat3Of<Real> loadSymLanes(const View& v, const CellLanes<Real>& at) {
  SymMat3Of<Real> m;
  Real* entries[6] = {&m.xx, &m.yy, &m.zz, &m.xy, &m.yz, &m.xz};
  for (int j = 0; j < 6; ++j)
    *entries[j] = gatherLanes<Real>([&](int i) { return v(at.cell[i], j); });
  return m;
}
template <class Real, class View>
KOKKOS_FORCEINLINE_FUNCTION void storeVec3Lanes(const View& v, const CellLanes<Real>& at,
                                                const Vec3Of<Real>& a) {
  for (int i = 0; i < kLanesOf<Real>; ++i) {
    v(at.cell[i], 0) = laneOf(a.x, i);
    v(at.cell[i], 1) = laneOf(a.y, i);
    v(at.cell[i], 2) = laneOf(a.z, i);
  }
}

KOKKOS_FORCEINLINE_FUNCTION double magnitude(double v) {
  return math::fabs(v);
}
#if LAGREMAP_CELL_PACKS
KOKKOS_FORCEINLINE_FUNCTION hex::CellPack magnitude(hex::CellPack v) {
  return v < 0.0 ? -v : v;
}
#endif

}  // namespace detail

}  // namespace lagremap
