// A cell's kinematics over a stage: its velocity gradient L from the node
// velocities and corner vectors (docs/method.md §A2), and its incremental
// deformation gradient F from the start-of-step geometry (docs/method.md
// §A7, §3.3). Read by the materials' update (material_update.hpp,
// mixed_cell_budget.hpp; the staged form sums the same terms from its corner
// lanes, material_update_staged.hpp).
#pragma once

#include "../data/state.hpp"
#include "cell_thermo.hpp"
#include "hex.hpp"

namespace lagremap {

// Velocity gradient of the stage, L = (1/v) sum_p V_p (x) A_cp (docs/method.md §A2).
KOKKOS_INLINE_FUNCTION Mat3 velocityGradient(const CellNodesView& cell_nodes, const State& s,
                                             Index c) {
  Mat3 gradient = zeroMat();
  const double inv_volume = 1.0 / s.vol_c(c);
  for (int p = 0; p < 8; ++p) {
    addOuter(gradient, inv_volume, loadVec3(s.v_n, cell_nodes(c, p)), loadVec3(s.A_cp, 8 * c + p));
  }
  return gradient;
}

// Incremental deformation gradient over the stage, exact for affine motion
// (docs/method.md §A7, §3.3): F = (1/v^n) sum_p x_p^new (x) A_cp^n, with the geometry of the
// start of the step recomputed from x_n0.
KOKKOS_INLINE_FUNCTION Mat3 stageDeformation(const CellNodesView& cell_nodes, const Vec3View& x_n,
                                             const State& s, Index c) {
  Vec3 x_start[8], corner_start[8];
  for (int p = 0; p < 8; ++p) x_start[p] = loadVec3(s.x_n0, cell_nodes(c, p));
  hex::cornerVectors(x_start, corner_start);
  double volume_start = 0.0;  // Euler's theorem for the cubic volume
  for (int p = 0; p < 8; ++p) volume_start += dot(x_start[p] - x_start[0], corner_start[p]);
  volume_start /= 3.0;
  Mat3 deformation = zeroMat();
  for (int p = 0; p < 8; ++p) {
    // relative to node 0 (sum_p A_cp = 0), to keep round-off small
    addOuter(deformation, 1.0 / volume_start,
             loadVec3(x_n, cell_nodes(c, p)) - loadVec3(x_n, cell_nodes(c, 0)), corner_start[p]);
  }
  return deformation;
}

}  // namespace lagremap
