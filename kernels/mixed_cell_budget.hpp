// The energy budget of a mixed cell over a stage (docs/method.md §4, §A8):
// each material's own volume ratio, its pdV and deviatoric work W^k, and its
// share of the cell's dissipation D = m (e_new - e^n) - sum_k W^k. Read by
// updateMaterials (material_update.hpp).
#pragma once

#include "../data/material_params.hpp"
#include "../data/state.hpp"
#include "cell_thermo.hpp"

namespace lagremap {

// Power of material k's stress per unit cell volume (stage-start pressure and
// deviator): -p^k share^k tr(L) + alpha^k S^k : L, with share^k its part of
// the cell's volume change (shareVolumeChange; alpha^k under equal strain)
// and the deviatoric strain rate common to all materials.
KOKKOS_FORCEINLINE_FUNCTION double stressPower(const State& s, Index c, int k, const Mat3& L,
                                               double volume_share) {
  double power = -s.p_ck(c, k) * volume_share * (L.m[0][0] + L.m[1][1] + L.m[2][2]);
  if (s.materials(k).strength != StrengthKind::None) {
    const SymMat3 S = loadSym(s.S_ck, c, k);
    power += s.alpha_ck(c, k) * (S.xx * L.m[0][0] + S.yy * L.m[1][1] + S.zz * L.m[2][2] +
                                 S.xy * (L.m[0][1] + L.m[1][0]) + S.yz * (L.m[1][2] + L.m[2][1]) +
                                 S.xz * (L.m[0][2] + L.m[2][0]));
  }
  return power;
}

// A material with less than this fraction of its cell's mass does no pdV work
// of its own: it takes the cell's specific heat (its share of D by mass). A
// trace by mass has no say in the cell's energy; its volume still yields to
// the others' (relaxation), as a void's would. Without it the `ball`'s
// near-vacuum gas ratchets up in temperature, compressed adiabatically by
// every Lagrangian stage and re-expanded by the remap without work
// (docs/method.md §4.6).
constexpr double kMassTrace = 1e-6;

namespace detail {

// What a mixed cell's materials share over a stage (docs/method.md §4): each
// material's own volume ratio (end over start of step), the cell's energy
// budget D = m (e_new - e^n) - sum_k W^k, and the masses that share it.
struct MixedCellBudget {
  double own_ratio[kMaxMaterials];
  double dissipation = 0.0;
  double present_mass = 0.0, present_alpha = 0.0;
  double condensed_mass = 0.0;  // not of the gas family: their energy may go negative, in tension
  double gas_heat = 0.0;        // the gases' positive internal energy
};

// Each material's volume ratio over the step: dV^k = share^k dt v tr L +
// relax^k, as shareVolumeChange makes it, and like it never below
// kMinVolumeKept of the start volume (the pdV work stops where the volume
// does; what the cap leaves out goes to D, shared by mass).
KOKKOS_FORCEINLINE_FUNCTION void ownVolumeRatios(const State& s, Index c, double volume_change,
                                                 double own_ratio[], StageRelaxation& relaxation) {
  const bool equal_strain = s.closure == MixtureClosure::EqualStrain;
  double weight_sum = 0.0;  // compressibility weights of the step start
  LAGREMAP_NO_UNROLL
  for (int k = 0; k < s.n_materials && !equal_strain; ++k) {
    if (s.alpha_ck(c, k) > 0.0) weight_sum += s.w_ck0(c, k);
  }
  double* relax = relaxation.volume;
  if (equal_strain) {
    for (int k = 0; k < kMaxMaterials; ++k) relax[k] = 0.0;
  } else {
    relaxationVolumes(s, c, relax);
    relaxation.known = true;
  }
  LAGREMAP_NO_UNROLL
  for (int k = 0; k < s.n_materials; ++k) {
    if (!(s.alpha_ck(c, k) > 0.0)) continue;
    // (equal strain: alpha^k of the volume change, the cell's rate)
    const double share = weight_sum > 0.0 ? s.w_ck0(c, k) / weight_sum : s.alpha_ck(c, k);
    const double start_volume = s.alpha_ck0(c, k) * s.vol_c0(c);
    const double own_change = share * volume_change + relax[k];
    own_ratio[k] = own_change < -(1.0 - kMinVolumeKept) * start_volume
                       ? kMinVolumeKept
                       : 1.0 + own_change / start_volume;
  }
}

// A Neo-Hookean body's velocity gradient in a mixed cell (isSolidBody,
// geometry.hpp): the cell's plus the normal stretch rate that makes its
// volume rate its own; the gas beside it takes the cell's compression.
KOKKOS_FORCEINLINE_FUNCTION Mat3 materialGradient(const State& s, Index c, int k, bool mixed,
                                                  const Mat3& gradient, double own_ratio,
                                                  double dt_stage) {
  Vec3 n;
  if (!(mixed && isSolidBody(s, c, k, n))) return gradient;
  Mat3 own = gradient;
  addOuter(own, (own_ratio - 1.0) / dt_stage - trace(gradient), n, n);
  return own;
}

// W^k = -p^k dV^k + dt v alpha^k S^k : L^k (zero for a trace by mass).
KOKKOS_FORCEINLINE_FUNCTION double materialWork(const State& s, Index c, int k,
                                                const Mat3& gradient_k, double own_ratio,
                                                double dt_stage) {
  if (s.closure == MixtureClosure::Relaxation && s.m_ck(c, k) < kMassTrace * s.m_c(c)) return 0.0;
  const double start_volume = s.alpha_ck0(c, k) * s.vol_c0(c);
  return -s.p_ck(c, k) * (own_ratio - 1.0) * start_volume +
         dt_stage * s.vol_c(c) * stressPower(s, c, k, gradient_k, 0.0);
}

// Material k's share of D: by mass for D >= 0 (kinetic energy of the cell's
// one velocity turned into heat: the mass carries it; by volume fraction, as
// method.md §A8 says, a gas beside a solid got half the heat for 1e-9 of the
// mass). D < 0 is an error of the second-order corner velocities, which a gas
// cannot afford below zero energy: it goes to the condensed materials by
// mass, and only without them to the gases by their internal energies.
KOKKOS_FORCEINLINE_FUNCTION double dissipationShare(const State& s, Index c, int k,
                                                    const MixedCellBudget& budget) {
  // the paper's split (docs/method.md §A8): by volume fraction
  if (s.closure == MixtureClosure::EqualStrain) return s.alpha_ck(c, k) / budget.present_alpha;
  const bool condensed = !isGasFamily(s.materials(k));
  if (budget.dissipation < 0.0 && budget.condensed_mass > 0.0) {
    return condensed ? s.m_ck(c, k) / budget.condensed_mass : 0.0;
  }
  if (budget.dissipation < 0.0 && budget.gas_heat > 0.0) {
    return s.e_ck0(c, k) > 0.0 ? s.m_ck(c, k) * s.e_ck0(c, k) / budget.gas_heat : 0.0;
  }
  return s.m_ck(c, k) / budget.present_mass;
}

// Material k's work W^k over the stage at its own volume ratio (a solid
// body's velocity gradient its own, materialGradient).
KOKKOS_FORCEINLINE_FUNCTION double stageWork(const State& s, Index c, int k, const Mat3& gradient,
                                             double own_ratio, double dt_stage) {
  return materialWork(s, c, k, materialGradient(s, c, k, true, gradient, own_ratio, dt_stage),
                      own_ratio, dt_stage);
}

// The budget's sums of a mixed cell whose specific internal energy is now
// e_new, in material order: D less each material's work (`work(k)`: W^k of
// a material that is no trace) and the masses that share it.
template <class Work>
KOKKOS_FORCEINLINE_FUNCTION void sumBudget(const State& s, Index c, double e_new, const Work& work,
                                           MixedCellBudget& budget) {
  const Vec3 v0 = loadVec3(s.v_c0, c);
  budget.dissipation = s.m_c(c) * (e_new - (s.E_c0(c) - 0.5 * dot(v0, v0)));
  const bool holds_elastic = cellHoldsElasticBody(s, s.alpha_ck, c);
  LAGREMAP_NO_UNROLL
  for (int k = 0; k < s.n_materials; ++k) {
    const double alpha = s.alpha_ck(c, k);
    if (!(alpha > 0.0)) continue;
    budget.present_mass += s.m_ck(c, k);
    budget.present_alpha += alpha;
    if (!isGasFamily(s.materials(k))) {
      budget.condensed_mass += s.m_ck(c, k);
    } else if (s.e_ck0(c, k) > 0.0) {
      budget.gas_heat += s.m_ck(c, k) * s.e_ck0(c, k);
    }
    if (alpha >= traceFraction(s, k, holds_elastic)) budget.dissipation -= work(k);
  }
}

// The budget of a mixed cell whose specific internal energy is now e_new.
KOKKOS_FORCEINLINE_FUNCTION void mixedCellBudget(const State& s, Index c, double e_new,
                                                 const Mat3& gradient, double dt_stage,
                                                 MixedCellBudget& budget,
                                                 StageRelaxation& relaxation) {
  ownVolumeRatios(s, c, dt_stage * s.vol_c(c) * trace(gradient), budget.own_ratio, relaxation);
  sumBudget(
      s, c, e_new,
      [&](int k) { return stageWork(s, c, k, gradient, budget.own_ratio[k], dt_stage); }, budget);
}

}  // namespace detail

}  // namespace lagremap
