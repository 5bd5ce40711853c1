#include "diagnostics.hpp"

#include "kokkos_events.hpp"
#include "parallel.hpp"

namespace lagremap {

void sumAudit(const Mesh& mesh, const State& state, const ReportView<SumArray<6>>& totals,
              const ReportView<SumArray<4>>& boundary) {
  const auto s = state;
  const auto cell_owned = mesh.cell_owned;
  const auto node_owned = mesh.node_owned;
  Kokkos::parallel_reduce(
      "lagremap::diagnostics::cell_totals", Kokkos::RangePolicy<ExecSpace>(0, mesh.n_cells),
      KOKKOS_LAMBDA(const Index c, SumArray<6>& acc) {
        if (!cell_owned(c)) return;
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
      Kokkos::Sum<SumArray<6>, ReportSpace>(totals));
  Kokkos::parallel_reduce(
      "lagremap::diagnostics::boundary_power", Kokkos::RangePolicy<ExecSpace>(0, mesh.n_nodes),
      KOKKOS_LAMBDA(const Index n, SumArray<4>& acc) {
        if (!node_owned(n)) return;
        const Vec3 f = loadVec3(s.f_ext_n, n);
        acc.v[0] += f.x;
        acc.v[1] += f.y;
        acc.v[2] += f.z;
        acc.v[3] += dot(f, loadVec3(s.v_n, n));
      },
      Kokkos::Sum<SumArray<4>, ReportSpace>(boundary));
}

Audit auditOf(SumArray<6> totals, SumArray<4> boundary) {
  parallel::sum(totals.v, 6);
  parallel::sum(boundary.v, 4);
  Audit audit;
  audit.totals.mass = totals.v[0];
  audit.totals.momentum = {totals.v[1], totals.v[2], totals.v[3]};
  audit.totals.kinetic = totals.v[4];
  audit.totals.internal = totals.v[5];
  audit.boundary = {{boundary.v[0], boundary.v[1], boundary.v[2]}, boundary.v[3]};
  return audit;
}

namespace {
Audit waitedAudit(const Mesh& mesh, const State& state) {
  const ReportView<SumArray<6>> totals("lagremap::diagnostics::totals");
  const ReportView<SumArray<4>> boundary("lagremap::diagnostics::boundary_power");
  sumAudit(mesh, state, totals, boundary);
  fenceFor("lagremap::diagnostics: the audit");
  return auditOf(totals(), boundary());
}
}  // namespace

Totals computeTotals(const Mesh& mesh, const State& state) {
  return waitedAudit(mesh, state).totals;
}

BoundaryPower computeBoundaryPower(const Mesh& mesh, const State& state) {
  return waitedAudit(mesh, state).boundary;
}

}  // namespace lagremap
