// Geometry phase (DESIGN §2-3): from the node positions, every cell's volume,
// centroid, length and corner vectors A_cp; then its density, internal energy,
// pressure and sound speeds, and the corner impedance of the nodal solver
//   M_cp = sum_f s_pf Q_cfp,  s_pf Q_cfp = rho [aL s n (x) n + aT s (I - n (x) n)];
// all need only cell-local data, so one sweep does them while the 24
// corner-face vectors are at hand. The cell's time-step candidates are reduced
// to the most restrictive.
#pragma once

#include "../src/mesh.hpp"
#include "../src/state.hpp"
#include "constitutive.hpp"
#include "hex.hpp"
#include "time_step.hpp"

namespace lagremap {

KOKKOS_INLINE_FUNCTION void gatherCellNodes(const CellNodesView& cell_nodes, const Vec3View& x_n,
                                            Index c, Vec3 x[8]) {
  for (int p = 0; p < 8; ++p) x[p] = loadVec3(x_n, cell_nodes(c, p));
}

// Geometry, thermodynamic closure and corner impedance of one cell, and its
// time-step candidates folded into `best` (DESIGN §2-3).
KOKKOS_INLINE_FUNCTION void cellGeometryAndThermo(const CellNodesView& cell_nodes,
                                                  const Vec3View& x_n, const State& s,
                                                  const TimeStepControls& controls, Index c,
                                                  StepLimit& best) {
  Vec3 x[8];
  gatherCellNodes(cell_nodes, x_n, c, x);
  hex::CellGeometry geo;
  hex::cellGeometry(x, geo);
  const double volume = geo.shape.volume;
  s.vol_c(c) = volume;
  storeVec3(s.x_c, c, geo.shape.centroid);
  const double length = volume / geo.shape.max_face_area;
  s.len_c(c) = length;

  const Vec3 v = loadVec3(s.v_c, c);
  const double rho = s.m_c(c) / volume;
  const double e = s.E_c(c) - 0.5 * dot(v, v);
  const MaterialParams& material = s.materials(s.mat_c(c));
  const ThermoState thermo = evaluateEos(material, rho, e);
  // Solids: aT^2 = mu / rho, aL^2 = a^2 + 4/3 aT^2 (DESIGN §3); fluids: aT = 0.
  const double mu = shearModulus(material);
  const double aT2 = mu > 0.0 ? transverseSoundSpeed2(mu, rho) : 0.0;
  const double aL2 = thermo.sound_speed2 + (4.0 / 3.0) * aT2;
  const double aL = aL2 > 0.0 ? math::sqrt(aL2) : 0.0;
  const double aT = math::sqrt(aT2);
  if (material.strength == StrengthKind::NeoHookean) {
    // Hyper-elastic deviator from B (DESIGN §4), J = rho0 / rho.
    storeSym(s.S_c, c, neoHookeanDeviator(loadSym(s.B_c, c), material.rho0 / rho, mu));
  }
  s.rho_c(c) = rho;
  s.e_c(c) = e;
  s.p_c(c) = thermo.pressure;
  s.aL_c(c) = aL;
  s.aT_c(c) = aT;

  // Corner impedance (DESIGN §3, nodal solver) from the corner-face sums.
  const double rho_aL = rho * aL, rho_aT = rho * aT;
  for (int p = 0; p < 8; ++p) {
    SymMat3 impedance = (rho_aL - rho_aT) * geo.normal_moment[p];
    impedance += identitySym(rho_aT * geo.corner_face_area[p]);
    storeVec3(s.A_cp, 8 * c + p, geo.corner[p]);
    storeSym(s.M_cp, 8 * c + p, impedance);
  }

  const bool finite_state =
      math::isfinite(e) && math::isfinite(thermo.pressure) && math::isfinite(rho);
  cellStepLimit(best, controls, c, volume, length,
                thermo.sound_speed2 > 0.0 ? aL2 : thermo.sound_speed2, s.dvdt_c(c), finite_state,
                thermo.valid);
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
        cellGeometryAndThermo(cell_nodes, x_n, s, controls, c, best);
      },
      StepLimitReducer(limit));
  return limit;
}

}  // namespace lagremap
