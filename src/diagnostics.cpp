#include "diagnostics.hpp"

#include "parallel.hpp"

namespace lagremap {

Totals computeTotals(const Mesh& mesh, const State& state) {
  const auto s = state;
  const auto owned = mesh.cell_owned;
  SumArray<6> sums;
  Kokkos::parallel_reduce(
      "lagremap::diagnostics::cell_totals", Kokkos::RangePolicy<ExecSpace>(0, mesh.n_cells),
      KOKKOS_LAMBDA(const Index c, SumArray<6>& acc) {
        if (!owned(c)) return;
        const double m = s.m_c(c);
        const Vec3 v = loadVec3(s.v_c, c);
        const double kinetic = 0.5 * m * dot(v, v);
        acc.v[0] += m;
        acc.v[1] += m * v.x;
        acc.v[2] += m * v.y;
        acc.v[3] += m * v.z;
        acc.v[4] += kinetic;
        acc.v[5] += m * s.E_c(c) - kinetic;
      },
      Kokkos::Sum<SumArray<6>>(sums));
  parallel::sum(sums.v, 6);
  Totals totals;
  totals.mass = sums.v[0];
  totals.momentum = {sums.v[1], sums.v[2], sums.v[3]};
  totals.kinetic = sums.v[4];
  totals.internal = sums.v[5];
  return totals;
}

BoundaryPower computeBoundaryPower(const Mesh& mesh, const State& state) {
  const auto s = state;
  const auto owned = mesh.node_owned;
  SumArray<4> sums;
  Kokkos::parallel_reduce(
      "lagremap::diagnostics::boundary_power", Kokkos::RangePolicy<ExecSpace>(0, mesh.n_nodes),
      KOKKOS_LAMBDA(const Index n, SumArray<4>& acc) {
        if (!owned(n)) return;
        const Vec3 f = loadVec3(s.f_ext_n, n);
        acc.v[0] += f.x;
        acc.v[1] += f.y;
        acc.v[2] += f.z;
        acc.v[3] += dot(f, loadVec3(s.v_n, n));
      },
      Kokkos::Sum<SumArray<4>>(sums));
  parallel::sum(sums.v, 4);
  return {{sums.v[0], sums.v[1], sums.v[2]}, sums.v[3]};
}

}  // namespace lagremap
