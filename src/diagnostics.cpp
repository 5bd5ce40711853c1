#include "diagnostics.hpp"

#include "kokkos_events.hpp"
#include "parallel.hpp"

namespace lagremap {

void sumTotals(const Mesh& mesh, const State& state, const CellTotalSumsView& totals) {
  const auto s = state;
  const auto cell_owned = mesh.cell_owned;
  Kokkos::parallel_reduce(
      "lagremap::diagnostics::cell_totals", Kokkos::RangePolicy<ExecSpace>(0, mesh.n_cells),
      KOKKOS_LAMBDA(const Index c, CellTotalSums& sum) {
        if (cell_owned(c)) addCellTotals(s, c, sum.v);
      },
      Kokkos::Sum<CellTotalSums, ReportSpace>(totals));
}

namespace {
void sumBoundaryPower(const Mesh& mesh, const State& state, const BoundaryPowerView& boundary) {
  const auto s = state;
  const auto node_owned = mesh.node_owned;
  Kokkos::parallel_reduce(
      "lagremap::diagnostics::boundary_power", Kokkos::RangePolicy<ExecSpace>(0, mesh.n_nodes),
      KOKKOS_LAMBDA(const Index n, BoundaryPowerSums& sum) {
        if (node_owned(n)) addBoundaryPower(loadVec3(s.f_ext_n, n), loadVec3(s.v_n, n), sum);
      },
      Kokkos::Sum<BoundaryPowerSums, ReportSpace>(boundary));
}
}  // namespace

Audit auditOf(CellTotalSums totals, BoundaryPowerSums boundary) {
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
  const CellTotalSumsView totals("lagremap::diagnostics::totals");
  const BoundaryPowerView boundary("lagremap::diagnostics::boundary_power");
  sumTotals(mesh, state, totals);
  sumBoundaryPower(mesh, state, boundary);
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
