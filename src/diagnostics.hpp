// Conservation audit (docs/method.md §A4, §2.9): totals over cells and the impulse and work
// the boundaries put in, so drift = change of a total - what came in.
#pragma once

#include "data/mesh.hpp"
#include "data/state.hpp"
#include "kernels/sum_array.hpp"

namespace lagremap {

struct Totals {
  double mass = 0.0;
  Vec3 momentum{0, 0, 0};
  double kinetic = 0.0, internal = 0.0;
  double total() const { return kinetic + internal; }
};

// Mass, momentum, kinetic and internal energy of the cells.
Totals computeTotals(const Mesh& mesh, const State& state);

struct BoundaryPower {
  Vec3 force{0, 0, 0};  // sum over nodes of the external force (wall reactions, tractions)
  double power = 0.0;   // sum over nodes of f_ext . V
};
// From the last nodal solve (the corrector's, whose velocities moved the mesh).
BoundaryPower computeBoundaryPower(const Mesh& mesh, const State& state);

}  // namespace lagremap
