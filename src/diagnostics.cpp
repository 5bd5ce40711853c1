#include "diagnostics.hpp"

#include "kokkos_events.hpp"
#include "parallel.hpp"

namespace lagremap {

void sumAudit(const Mesh& mesh, const State& state, const ReportView<AuditSums>& into) {
  const auto s = state;
  const auto cell_owned = mesh.cell_owned;
  const auto node_owned = mesh.node_owned;
  const Index n_cells = mesh.n_cells, n_nodes = mesh.n_nodes;
  Kokkos::parallel_reduce(
      "lagremap::diagnostics::audit",
      Kokkos::RangePolicy<ExecSpace>(0, n_cells > n_nodes ? n_cells : n_nodes),
      KOKKOS_LAMBDA(const Index i, AuditSums& acc) {
        if (i < n_cells && cell_owned(i)) {
          const double m = s.m_c(i);
          const Vec3 v = loadVec3(s.v_c, i);
          const double kinetic = 0.5 * m * dot(v, v);
          acc.v[0] += m;
          acc.v[1] += m * v.x;
          acc.v[2] += m * v.y;
          acc.v[3] += m * v.z;
          acc.v[4] += kinetic;
          acc.v[5] += m * s.E_c(i) - kinetic;
        }
        if (i < n_nodes && node_owned(i)) {
          const Vec3 f = loadVec3(s.f_ext_n, i);
          acc.v[6] += f.x;
          acc.v[7] += f.y;
          acc.v[8] += f.z;
          acc.v[9] += dot(f, loadVec3(s.v_n, i));
        }
      },
      Kokkos::Sum<AuditSums, ReportSpace>(into));
}

Audit auditOf(AuditSums sums) {
  parallel::sum(sums.v, 10);
  Audit audit;
  audit.totals.mass = sums.v[0];
  audit.totals.momentum = {sums.v[1], sums.v[2], sums.v[3]};
  audit.totals.kinetic = sums.v[4];
  audit.totals.internal = sums.v[5];
  audit.boundary = {{sums.v[6], sums.v[7], sums.v[8]}, sums.v[9]};
  return audit;
}

namespace {
Audit waitedAudit(const Mesh& mesh, const State& state) {
  const ReportView<AuditSums> sums("lagremap::diagnostics::audit");
  sumAudit(mesh, state, sums);
  fenceFor("lagremap::diagnostics: the audit");
  return auditOf(sums());
}
}  // namespace

Totals computeTotals(const Mesh& mesh, const State& state) {
  return waitedAudit(mesh, state).totals;
}

BoundaryPower computeBoundaryPower(const Mesh& mesh, const State& state) {
  return waitedAudit(mesh, state).boundary;
}

}  // namespace lagremap
