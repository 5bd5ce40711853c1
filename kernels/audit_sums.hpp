// The conservation audit's sums (docs/method.md §2.9), each taken in a kernel
// that reads them anyway where one does: the cells' totals (the remap's last
// kernel, or a kernel of their own: src/diagnostics.cpp), what crossed the
// outer boundary in a remap (its last kernel) and the boundary's force and
// power (the last nodal solve of a step, nodal_solver.hpp). Left for the host
// without waiting (StepReport).
#pragma once

#include "../data/state.hpp"
#include "sum_array.hpp"

namespace lagremap {

// Mass, momentum xyz, kinetic and internal energy.
using CellTotalSums = SumArray<6>;
using CellTotalSumsView = ReportView<CellTotalSums>;
// Force xyz and power F . V of the external forces on the nodes.
using BoundaryPowerSums = SumArray<4>;
using BoundaryPowerView = ReportView<BoundaryPowerSums>;

// Cell c's part of the totals, added to sum[0 .. 5] (CellTotalSums' order).
KOKKOS_FORCEINLINE_FUNCTION void addCellTotals(const State& s, Index c, double* sum) {
  const double m = s.m_c(c);
  const Vec3 v = loadVec3(s.v_c, c);
  const double kinetic = 0.5 * m * dot(v, v);
  sum[0] += m;
  sum[1] += m * v.x;
  sum[2] += m * v.y;
  sum[3] += m * v.z;
  sum[4] += kinetic;
  sum[5] += m * s.E_c(c) - kinetic;
}

// Quantities the outer boundary exchanged in a remap's sweep (mass, momentum
// xyz, total energy): zero for walls, which sweep no volume; a moving
// traction face books here what crossed it (docs/verification.md §8.4, pile).
using RemapBoundaryFlux = SumArray<5>;

// What a remap leaves for the host, this rank's sums: what crossed the outer
// boundary (RemapBoundaryFlux), then the remapped cells' totals
// (CellTotalSums), in one View (remapAuditAndMoveNodes, kernels/remap.hpp).
constexpr int kRemapAuditSums = 11;
using RemapAuditView = Kokkos::View<double*, ReportSpace>;
struct RemapAudit {
  RemapBoundaryFlux crossed;
  CellTotalSums totals;
};
// The View's sums (read after a fence).
inline RemapAudit remapAuditOf(const RemapAuditView& sums) {
  RemapAudit audit;
  for (int i = 0; i < 5; ++i) audit.crossed.v[i] = sums(i);
  for (int i = 0; i < 6; ++i) audit.totals.v[i] = sums(5 + i);
  return audit;
}

// A node's part of the boundary's: its external force and power.
KOKKOS_FORCEINLINE_FUNCTION void addBoundaryPower(const Vec3& force, const Vec3& velocity,
                                                  BoundaryPowerSums& sum) {
  sum.v[0] += force.x;
  sum.v[1] += force.y;
  sum.v[2] += force.z;
  sum.v[3] += dot(force, velocity);
}

// N sums of a kernel as one Kokkos array reduction (value_type double[]): a
// GPU keeps each thread's partial sums in shared memory, where a struct of
// sums (SumArray) takes a stack frame of about 32 bytes a sum on sm_90 (the
// remap's 11: past the 256-byte bound, perf/gpu_resource_bounds.txt).
// `terms(i, sums)` adds index i's terms to sums[0 .. N - 1].
template <int N, class Terms>
struct SumsInArray {
  using value_type = double[];
  unsigned value_count = N;
  Terms terms;
  explicit SumsInArray(const Terms& terms_of) : terms(terms_of) {}
  KOKKOS_INLINE_FUNCTION void operator()(const Index i, value_type sums) const { terms(i, sums); }
  KOKKOS_INLINE_FUNCTION void init(value_type sums) const {
    for (int j = 0; j < N; ++j) sums[j] = 0.0;
  }
  KOKKOS_INLINE_FUNCTION void join(value_type into, const value_type from) const {
    for (int j = 0; j < N; ++j) into[j] += from[j];
  }
  KOKKOS_INLINE_FUNCTION void join(volatile value_type into, const volatile value_type from) const {
    for (int j = 0; j < N; ++j) into[j] += from[j];
  }
};

}  // namespace lagremap
