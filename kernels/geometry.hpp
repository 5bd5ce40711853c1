// Geometry phase (DESIGN §2-3): from the node positions, every cell's volume,
// centroid and length, then its density, internal energy, pressure and sound
// speeds (the thermodynamic closure needs only cell-local data, so it is fused
// here), and the cell's time-step candidates reduced to the most restrictive.
#pragma once

#include "../src/mesh.hpp"
#include "../src/state.hpp"
#include "hex.hpp"
#include "time_step.hpp"

namespace lagremap {

KOKKOS_INLINE_FUNCTION void gatherCellNodes(const CellNodesView& cell_nodes, const Vec3View& x_n,
                                            Index c, Vec3 x[8]) {
  for (int p = 0; p < 8; ++p) x[p] = loadVec3(x_n, cell_nodes(c, p));
}

// Returns the smallest time-step candidate (or a negative value and the
// failure code for an invalid cell).
inline StepLimit computeGeometry(const Mesh& mesh, const State& state,
                                 const TimeStepControls& controls) {
  const auto cell_nodes = mesh.cell_nodes;
  const auto x_n = mesh.x_n;
  const auto s = state;
  StepLimit limit;
  Kokkos::parallel_reduce(
      "lagremap::geometry::cells", Kokkos::RangePolicy<ExecSpace>(0, mesh.n_cells),
      KOKKOS_LAMBDA(const Index c, StepLimit& best) {
        Vec3 x[8];
        gatherCellNodes(cell_nodes, x_n, c, x);
        const hex::CellShape shape = hex::cellShape(x);
        s.vol_c(c) = shape.volume;
        storeVec3(s.x_c, c, shape.centroid);
        const double length = shape.volume / shape.max_face_area;
        s.len_c(c) = length;

        const Vec3 v = loadVec3(s.v_c, c);
        const double rho = s.m_c(c) / shape.volume;
        const double e = s.E_c(c) - 0.5 * dot(v, v);
        const ThermoState thermo = evaluateEos(s.materials(s.mat_c(c)), rho, e);
        s.rho_c(c) = rho;
        s.e_c(c) = e;
        s.p_c(c) = thermo.pressure;
        s.aL_c(c) = thermo.sound_speed2 > 0.0 ? math::sqrt(thermo.sound_speed2) : 0.0;
        s.aT_c(c) = 0.0;  // fluids carry no transverse impedance

        const bool finite_state =
            math::isfinite(e) && math::isfinite(thermo.pressure) && math::isfinite(rho);
        cellStepLimit(best, controls, c, shape.volume, length, thermo.sound_speed2, s.dvdt_c(c),
                      finite_state);
      },
      StepLimitReducer(limit));
  return limit;
}

}  // namespace lagremap
