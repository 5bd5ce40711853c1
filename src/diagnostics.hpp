// Conservation audit (docs/method.md §A4, §2.9): totals over cells and the impulse and work
// the boundaries put in, so drift = change of a total - what came in.
#pragma once

#include "data/mesh.hpp"
#include "data/state.hpp"
#include "data/types.hpp"
#include "kernels/sum_array.hpp"

namespace lagremap {

struct Totals {
  double mass = 0.0;
  Vec3 momentum{0, 0, 0};
  double kinetic = 0.0, internal = 0.0;
  double total() const { return kinetic + internal; }
};

struct BoundaryPower {
  Vec3 force{0, 0, 0};  // sum over nodes of the external force (wall reactions, tractions)
  double power = 0.0;   // sum over nodes of f_ext . V
};

// Mass, momentum, kinetic and internal energy of the cells, waited for.
Totals computeTotals(const Mesh& mesh, const State& state);
// The boundary nodes' force and power from the last nodal solve (the
// corrector's, whose velocities moved the mesh), waited for.
BoundaryPower computeBoundaryPower(const Mesh& mesh, const State& state);

// A step's audit in one reduction over the cells and the nodes: both the
// above and, asked to, the smallest scaled Jacobian of the owned cells at the
// present nodes (kernels/mesh_quality.hpp; 1 at most). This rank's values
// are left in `into` without waiting; auditOf reads them after a fence
// (collective: over the ranks).
struct AuditSums {
  double v[10];           // the totals (6), the boundary's force (3) and power
  double lowest_quality;  // a reduction's += keeps the smaller
  KOKKOS_INLINE_FUNCTION AuditSums() : lowest_quality(1.0) {
    for (int i = 0; i < 10; ++i) v[i] = 0.0;
  }
  KOKKOS_INLINE_FUNCTION AuditSums& operator+=(const AuditSums& other) {
    for (int i = 0; i < 10; ++i) v[i] += other.v[i];
    lowest_quality = other.lowest_quality < lowest_quality ? other.lowest_quality : lowest_quality;
    return *this;
  }
  KOKKOS_INLINE_FUNCTION void operator+=(const volatile AuditSums& other) volatile {
    for (int i = 0; i < 10; ++i) v[i] += other.v[i];
    lowest_quality = other.lowest_quality < lowest_quality ? other.lowest_quality : lowest_quality;
  }
};
struct Audit {
  Totals totals;
  BoundaryPower boundary;
  double mesh_quality = 1.0;  // where asked for
};
void sumAudit(const Mesh& mesh, const State& state, bool with_mesh_quality,
              const ReportView<AuditSums>& into);
Audit auditOf(AuditSums sums, bool with_mesh_quality);

}  // namespace lagremap

namespace Kokkos {
template <>
struct reduction_identity<lagremap::AuditSums> {
  KOKKOS_FORCEINLINE_FUNCTION static lagremap::AuditSums sum() { return {}; }
};
}  // namespace Kokkos
