// Conservation audit (docs/method.md §A4, §2.9): totals over cells and the impulse and work
// the boundaries put in, so drift = change of a total - what came in.
#pragma once

#include "data/mesh.hpp"
#include "data/state.hpp"
#include "data/types.hpp"
#include "kernels/audit_sums.hpp"

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
// corrector's, whose velocities moved the mesh), waited for. (A step's
// comes from that solve itself: nodalSolve's `power`.)
BoundaryPower computeBoundaryPower(const Mesh& mesh, const State& state);

// A step's audit: this rank's cell totals left in `totals` without waiting
// (the boundary's sums in `boundary` by the step's last nodal solve);
// auditOf reads both after a fence (collective: sums over the ranks).
struct Audit {
  Totals totals;
  BoundaryPower boundary;
};
void sumTotals(const Mesh& mesh, const State& state, const CellTotalSumsView& totals);
Audit auditOf(CellTotalSums totals, BoundaryPowerSums boundary);

}  // namespace lagremap
