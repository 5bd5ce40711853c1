// A cell's closure at the end of a stage (docs/method.md §A3-A4, §4.2-4.6):
// from its shape (volume, centroid, largest face), its density, internal
// energy, the mixture's pressure and sound speeds, its materials' volume
// shares, the coefficients of its corner impedances
//   M_cp = sum_f s_pf Q_cfp,  s_pf Q_cfp = rho [aL s n (x) n + aT s (I - n (x) n)]
// and its time-step candidates: the per-cell functions of the geometry's
// kernels (geometry.hpp, geometry_staged.hpp) and of the cell update's.
#pragma once

#include "../data/mesh.hpp"
#include "../data/state.hpp"
#include "constitutive.hpp"
#include "hex.hpp"
#include "time_step.hpp"

namespace lagremap {

KOKKOS_INLINE_FUNCTION void gatherCellNodes(const CellNodesView& cell_nodes, const Vec3View& x_n,
                                            Index c, Vec3 x[8]) {
  for (int p = 0; p < 8; ++p) x[p] = loadVec3(x_n, cell_nodes(c, p));
}

// Mixture closure of one cell (docs/method.md §A3): each present material's density
// rho^k = m^k / (alpha^k v), pressure, sound speeds and deviator, combined into
//   p = sum alpha^k p^k,  S = sum alpha^k S^k,
//   aL^2 = sum (m^k/m) aL_k^2,  aT^2 = sum (m^k/m) aT_k^2,
// with aT_k^2 = mu_k / rho^k and aL_k^2 = a_k^2 + 4/3 aT_k^2 for a solid,
// aL_k = a_k and aT_k = 0 for a fluid. A pure cell's material energy is the
// cell's e = E - |V|^2/2 itself (no round-off drift between the two). Traces
// (alpha^k < State::alpha_trace in a mixed cell) are left out and the weights
// renormalised over the other materials; a trace's pressure is set to the
// mixture's (pressure equilibrium).
struct CellThermo {
  double pressure = 0.0, aL2 = 0.0, aT2 = 0.0;
  double min_sound_speed2 = 1e300;  // smallest a_k^2 of the present materials (<= 0: invalid)
  bool valid = true;                // some material present, every one inside its EOS's domain
};

// Volume fractions of a mixed cell at the end of a Lagrangian stage
// (docs/method.md §4.2-4.4, departures from §A3's equal strain):
// - shared volume change: the cell's change since the start of the step goes
//   to its materials in proportion to their compressibility w^k = alpha^k /
//   (rho^k a_k^2), alpha^k v = alpha^k_n v_n + (w^k_n / sum w_n) (v - v_n);
// - pressure relaxation: each material's volume also changes by
//   relax^k = v_n w^k_n (P^k - P_mean), P_mean = sum w_n P / sum w_n (sum 0),
//   so that to first order the P^k equalise within the step; its work
//   -p^k relax^k (updateMaterials) is irreversible. P^k = p^k for a fluid,
//   p^k - n^k . S^k . n^k for a solid body (isSolidBody; n^k its interface
//   normal from the last remap), whose own normal stretch enters its B or
//   Jaumann rate (updateMaterials) and whose weight uses the longitudinal
//   modulus rho (a^2 + 4/3 a_T^2); a solid fragment below kSolidBodyAlpha
//   meets the gas with its pressure alone.
// p^k are the stage-start pressures, S^k the step-start deviators (the same
// numbers in updateMaterials and here). Summed as
// v_n (w^k / sum w) sum_m w^m (P^k - P^m): the mean itself loses the
// differences to round-off when one weight (a near-vacuum gas) dwarfs the
// others. Traces (no say in the stress, w = 0) take no part. The
// linearisation holds for small volume changes only, so no material changes
// its volume by more than kMaxRelaxation of it per step (all scaled alike).
constexpr double kMaxRelaxation = 0.1;
// No material of a mixed cell is squeezed below this fraction of its volume at
// the start of the step (shareVolumeChange; updateMaterials stops its pdV work
// there too).
constexpr double kMinVolumeKept = 1e-3;
// A hypo-elastic solid filling at least this fraction of a mixed cell is a
// body of its own (see above).
constexpr double kSolidBodyAlpha = 0.5;
// The volume fraction below which material k of mixed cell c is a trace
// (docs/method.md §4.6): State::alpha_trace, and State::alpha_tail for a fluid
// in a cell that also holds a Neo-Hookean solid. Such a fluid is the remap's
// diffusion tail of a gas inside an elastic body, cells within the
// interface, not a layer beside it: its gradient (a hundredth a cell) gives
// no interface normal, and met as a layer it took the body's normal stress
// across that noise. Where the body was in tension (the `beam`'s plate at
// --scale 2, 20 GPa along the plate) the tail took the cell's expansion and
// the relaxation inflated it 10% a step, the body's tension relaxed along
// the tilted normal and the plate opened into cracks. A hypo-elastic body's
// deviator is bounded by its yield stress; beside it a tail keeps its say
// (the `ball`'s near-vacuum tails are where its crater's lips open).
// `holds_elastic`: cellHoldsElasticBody.
KOKKOS_INLINE_FUNCTION double traceFraction(const State& s, int k, bool holds_elastic) {
  return holds_elastic && s.materials(k).strength == StrengthKind::None ? s.alpha_tail
                                                                        : s.alpha_trace;
}
// Whether cell c holds a Neo-Hookean solid, by its fractions `alpha` (the
// current or the step-start ones).
template <class Alpha>
KOKKOS_INLINE_FUNCTION bool cellHoldsElasticBody(const State& s, const Alpha& alpha, Index c) {
  LAGREMAP_NO_UNROLL
  for (int m = 0; m < s.n_materials; ++m) {
    if (alpha(c, m) > 0.0 && s.materials(m).strength == StrengthKind::NeoHookean) return true;
  }
  return false;
}
// A solid body of a mixed cell (see above): its normal stretch is its own.
KOKKOS_INLINE_FUNCTION bool takesOwnNormalStretch(const MaterialParams& material, double alpha,
                                                  double alpha_trace) {
  if (!(alpha > 0.0)) return false;
  if (material.strength == StrengthKind::NeoHookean) return alpha >= alpha_trace;
  if (material.strength == StrengthKind::HypoElastic) return alpha >= kSolidBodyAlpha;
  return false;
}
// ... and its interface normal, known from the last remap.
KOKKOS_FORCEINLINE_FUNCTION bool isSolidBody(const State& s, Index c, int k, Vec3& normal) {
  if (s.closure == MixtureClosure::EqualStrain) return false;  // all at the cell's strain
  if (!takesOwnNormalStretch(s.materials(k), s.alpha_ck0(c, k), s.alpha_trace)) return false;
  if (c >= Index(s.n_ck.extent(0))) return false;
  normal = Vec3{s.n_ck(c, k, 0), s.n_ck(c, k, 1), s.n_ck(c, k, 2)};
  return dot(normal, normal) > 0.5;  // zero where alpha^k had no gradient
}

// Material m's normal stress across its interface in cell c, tension
// positive: -P^m, plus n.S^m.n for a solid body with an interface normal
// (isSolidBody). What the relaxation balances between a mixed cell's
// materials; `alpha`, `p` and `S` are the step start's there, the current
// state's for the mixed_cells check (docs/method.md §4.9).
template <class Alpha, class Pressure, class Deviator>
KOKKOS_FORCEINLINE_FUNCTION double interfaceNormalStress(const State& s, const Alpha& alpha,
                                                         const Pressure& p, const Deviator& S,
                                                         Index c, int m) {
  const double sigma = -p(c, m);
  if (s.closure == MixtureClosure::EqualStrain) return sigma;
  if (!takesOwnNormalStretch(s.materials(m), alpha(c, m), s.alpha_trace)) return sigma;
  if (c >= Index(s.n_ck.extent(0))) return sigma;
  const Vec3 normal{s.n_ck(c, m, 0), s.n_ck(c, m, 1), s.n_ck(c, m, 2)};
  if (!(dot(normal, normal) > 0.5)) return sigma;  // zero where alpha^m had no gradient
  return sigma + dot(normal, loadSym(S, c, m) * normal);
}

// relax^k of every material of cell c at once (zero for those that take no
// part): each normal stress -P^m once, not once per pair and per caller.
KOKKOS_INLINE_FUNCTION void relaxationVolumes(const State& s, Index c,
                                              double relax[kMaxMaterials]) {
  const int n_materials = s.n_materials;
  bool relaxes[kMaxMaterials];
  double sigma[kMaxMaterials];  // -P^m
  double weight_sum = 0.0;
  for (int m = 0; m < kMaxMaterials; ++m) relax[m] = 0.0;
  const bool holds_elastic = cellHoldsElasticBody(s, s.alpha_ck0, c);
  LAGREMAP_NO_UNROLL
  for (int m = 0; m < n_materials; ++m) {
    relaxes[m] = s.alpha_ck0(c, m) > 0.0 &&
                 s.alpha_ck0(c, m) >= traceFraction(s, m, holds_elastic) && s.w_ck0(c, m) > 0.0;
    if (!relaxes[m]) continue;
    weight_sum += s.w_ck0(c, m);
    sigma[m] = interfaceNormalStress(s, s.alpha_ck0, s.p_ck0, s.S_ck0, c, m);
  }
  double scale = 1.0;
  LAGREMAP_NO_UNROLL
  for (int m = 0; m < n_materials; ++m) {
    if (!relaxes[m]) continue;
    double pull = 0.0;
    LAGREMAP_NO_UNROLL
    for (int n = 0; n < n_materials; ++n) {
      if (n != m && relaxes[n]) pull += s.w_ck0(c, n) * (sigma[n] - sigma[m]);
    }
    relax[m] = s.vol_c0(c) * (s.w_ck0(c, m) / weight_sum) * pull;
    const double change = math::fabs(relax[m]);
    const double allowed = kMaxRelaxation * s.alpha_ck0(c, m) * s.vol_c0(c);
    if (change * scale > allowed) scale = allowed / change;
  }
  LAGREMAP_NO_UNROLL
  for (int m = 0; m < n_materials; ++m) relax[m] *= scale;
}

// A mixed cell's relaxation volumes, computed once a stage: the cell update
// (updateMaterials) fills them, and the geometry of the same sweep
// (shareVolumeChange) takes them instead of computing them again; both read
// the same step-start state.
struct StageRelaxation {
  bool known = false;
  double volume[kMaxMaterials] = {};
};

KOKKOS_INLINE_FUNCTION double relaxationVolume(const State& s, Index c, int k) {
  double relax[kMaxMaterials];
  relaxationVolumes(s, c, relax);
  return relax[k];
}

KOKKOS_FORCEINLINE_FUNCTION void shareVolumeChange(const State& s, Index c, double volume,
                                                   const StageRelaxation* known = nullptr) {
  if (s.closure == MixtureClosure::EqualStrain) return;  // alpha^k unchanged
  double weight_sum = 0.0;
  int present = 0;
  LAGREMAP_NO_UNROLL
  for (int k = 0; k < s.n_materials; ++k) {
    if (!(s.alpha_ck0(c, k) > 0.0)) continue;  // an absent material's w is stale
    ++present;
    weight_sum += s.w_ck0(c, k);
  }
  if (present < 2 || !(weight_sum > 0.0)) return;
  const double volume_start = s.vol_c0(c);
  double computed[kMaxMaterials];
  if (!(known && known->known)) relaxationVolumes(s, c, computed);
  const double* relax = known && known->known ? known->volume : computed;
  double alpha_sum = 0.0;
  LAGREMAP_NO_UNROLL
  for (int k = 0; k < s.n_materials; ++k) {
    const double alpha_start = s.alpha_ck0(c, k);
    if (!(alpha_start > 0.0)) continue;
    const double material_volume = alpha_start * volume_start +
                                   (s.w_ck0(c, k) / weight_sum) * (volume - volume_start) +
                                   relax[k];
    // a material cannot be squeezed out: keep a sliver of its start volume
    const double kept = kMinVolumeKept * alpha_start * volume_start;
    const double alpha = (material_volume > kept ? material_volume : kept) / volume;
    s.alpha_ck(c, k) = alpha;
    alpha_sum += alpha;
  }
  LAGREMAP_NO_UNROLL
  for (int k = 0; k < s.n_materials; ++k) s.alpha_ck(c, k) /= alpha_sum;
}

KOKKOS_INLINE_FUNCTION CellThermo cellThermo(const State& s, Index c, double volume,
                                             double e_cell) {
  CellThermo mix;
  int present = 0;
  LAGREMAP_NO_UNROLL
  for (int k = 0; k < s.n_materials; ++k) present += s.alpha_ck(c, k) > 0.0;
  // a trace below its threshold (none in a pure cell)
  const bool holds_elastic = present > 1 && cellHoldsElasticBody(s, s.alpha_ck, c);
  const auto threshold = [&](int k) {
    return present > 1 ? traceFraction(s, k, holds_elastic) : 0.0;
  };
  double active_alpha = 0.0, active_mass = 0.0;
  LAGREMAP_NO_UNROLL
  for (int k = 0; k < s.n_materials; ++k) {
    const double alpha = s.alpha_ck(c, k);
    if (alpha > 0.0 && alpha >= threshold(k)) {
      active_alpha += alpha;
      active_mass += s.m_ck(c, k);
    }
  }
  const double inv_mass = 1.0 / active_mass;
  mix.valid = present > 0;
  SymMat3 deviator = identitySym(0.0);
  LAGREMAP_NO_UNROLL
  for (int k = 0; k < s.n_materials; ++k) {
    const double alpha = s.alpha_ck(c, k);
    if (!(alpha > 0.0 && alpha >= threshold(k))) continue;
    const MaterialParams& material = s.materials(k);
    const double mass = s.m_ck(c, k);
    const double rho = mass / (alpha * volume);
    const double e = present == 1 ? e_cell : s.e_ck(c, k);
    const ThermoState thermo = evaluateEos(material, rho, e);
    const double mu = shearModulus(material);
    const double aT2 = mu > 0.0 ? transverseSoundSpeed2(mu, rho) : 0.0;
    const double mass_fraction = present == 1 ? 1.0 : mass * inv_mass;
    mix.pressure += alpha * thermo.pressure;
    // In a mixed cell a material stretched past its sound speed (a solid
    // dragged into tension by the gas it shares the cell with, equal strain)
    // adds no stiffness; the cell is only invalid if the mixture has none.
    const double a2 = present == 1 || thermo.sound_speed2 > 0.0 ? thermo.sound_speed2 : 0.0;
    mix.aL2 += mass_fraction * (a2 + (4.0 / 3.0) * aT2);
    mix.aT2 += mass_fraction * aT2;
    mix.valid = mix.valid && thermo.valid;
    mix.min_sound_speed2 = a2 < mix.min_sound_speed2 ? a2 : mix.min_sound_speed2;
    s.p_ck(c, k) = thermo.pressure;
    // a solid body's compressibility under uniaxial strain (its normal
    // stretch is its own: takesOwnNormalStretch, relaxationVolume); the
    // bulk one otherwise
    const double longitudinal2 =
        thermo.sound_speed2 + (present > 1 && takesOwnNormalStretch(material, alpha, s.alpha_trace)
                                   ? (4.0 / 3.0) * aT2
                                   : 0.0);
    s.w_ck(c, k) = thermo.sound_speed2 > 0.0 ? alpha / (rho * longitudinal2) : 0.0;
    if (material.strength == StrengthKind::NeoHookean) {
      // Hyper-elastic deviator from B (docs/method.md §A7), J = rho0 / rho^k.
      const SymMat3 S = neoHookeanDeviator(loadSym(s.B_ck, c, k), material.rho0 / rho, mu);
      storeSym(s.S_ck, c, k, S);
      deviator += alpha * S;
    } else if (material.strength == StrengthKind::HypoElastic) {
      deviator += alpha * loadSym(s.S_ck, c, k);
    }
  }
  if (present > 1) {  // traces left out: renormalise
    // (a trace at alpha ~ 1e-16 leaves active_alpha at 1 to the bit: it still
    // takes the mixture's pressure, not a stale or zero one)
    const double scale = active_alpha != 1.0 ? 1.0 / active_alpha : 1.0;
    mix.pressure *= scale;
    deviator = scale * deviator;
    LAGREMAP_NO_UNROLL
    for (int k = 0; k < s.n_materials; ++k) {
      const double alpha = s.alpha_ck(c, k);
      if (alpha > 0.0 && alpha < threshold(k)) {
        s.p_ck(c, k) = mix.pressure;
        // no say in the volume change either: the gas trace in an aluminium
        // cell kept the w = alpha / (gamma p) of its near-vacuum past and took
        // the whole cell's compression
        s.w_ck(c, k) = 0.0;
      }
    }
  }
  if (s.has_solids) storeSym(s.S_c, c, deviator);
  if (present > 1) mix.min_sound_speed2 = mix.aL2;
  return mix;
}

// What the geometry at the end of a Lagrangian stage computes.
enum class StageEnd {
  // Everything the next stage reads: shape, thermodynamics, corner vectors
  // and impedances, time-step candidates.
  Full,
  // The last stage of a step the remap follows (LagrangeStep::
  // remapFollowsEveryStep): what the remap reads (volume, centroid, the
  // materials' volume shares) and the checks of the Lagrangian state. The
  // thermodynamics, corner terms and time step are those of the remapped
  // state (computeGeometry on the target mesh): nothing reads the Lagrangian
  // ones, so they are not computed (the 24 corner-face normals, one EOS
  // evaluation per material). Same bits as Full for everything that is read.
  ForRemap,
};

// The two coefficients of a cell's corner impedances (docs/method.md §A4):
//   M_cp = rho (aL - aT) sum_f s_pf n_pf (x) n_pf + rho aT (sum_f s_pf) I.
struct CornerImpedance {
  double normal_part, transverse;  // rho (aL - aT), rho aT
};

// Thermodynamic closure of one cell of known shape (volume, centroid, largest
// face) and its time-step candidates folded into `best` (docs/method.md
// §A3-A4, §A6); returns its corner-impedance coefficients, also given to
// `store_corners` before the time-step candidates are formed. (Where the
// corners are stored changes what a GPU thread holds at once: the fused form
// stores its geometry's there, the staged form computes them afterwards.)
// `end_of_stage`: the nodes have just moved in a Lagrangian stage, so a mixed
// cell's volume change is shared among its materials first.
template <class StoreCorners>
KOKKOS_INLINE_FUNCTION CornerImpedance cellThermoOnShape(const hex::CellShape& shape,
                                                         const State& s,
                                                         const TimeStepControls& controls, Index c,
                                                         StepLimit& best, bool end_of_stage,
                                                         const StageRelaxation* relaxation,
                                                         const StoreCorners& store_corners) {
  const double volume = shape.volume;
  s.vol_c(c) = volume;
  storeVec3(s.x_c, c, shape.centroid);
  const double length = volume / shape.max_face_area;
  s.len_c(c) = length;

  const Vec3 v = loadVec3(s.v_c, c);
  const double rho = s.m_c(c) / volume;
  const double e = s.E_c(c) - 0.5 * dot(v, v);
  if (end_of_stage && s.n_materials > 1) shareVolumeChange(s, c, volume, relaxation);
  const CellThermo thermo = cellThermo(s, c, volume, e);
  const double aL = thermo.aL2 > 0.0 ? math::sqrt(thermo.aL2) : 0.0;
  const double aT = math::sqrt(thermo.aT2);
  s.rho_c(c) = rho;
  s.e_c(c) = e;
  s.p_c(c) = thermo.pressure;
  s.aL_c(c) = aL;
  s.aT_c(c) = aT;

  const double rho_aL = rho * aL, rho_aT = rho * aT;
  const CornerImpedance coefficients{rho_aL - rho_aT, rho_aT};
  store_corners(coefficients);

  const bool finite_state =
      math::isfinite(e) && math::isfinite(thermo.pressure) && math::isfinite(rho);
  cellStepLimit(best, controls, c, volume, length,
                thermo.min_sound_speed2 > 0.0 ? thermo.aL2 : thermo.min_sound_speed2, s.dvdt_c(c),
                finite_state, thermo.valid);
  return coefficients;
}

// One corner's vector A_cp and impedance M_cp from its corner-face sums.
KOKKOS_INLINE_FUNCTION void storeCorner(const State& s, Index corner,
                                        const CornerImpedance& coefficients,
                                        const hex::CornerSums& sums) {
  SymMat3 impedance = coefficients.normal_part * sums.normal_moment;
  impedance += identitySym(coefficients.transverse * sums.area);
  storeVec3(s.A_cp, corner, sums.vector);
  storeSym(s.M_cp, corner, impedance);
}

// The above for a cell whose geometry is at hand (the fused form).
KOKKOS_INLINE_FUNCTION void cellThermoOnGeometry(const hex::CellGeometry& geo, const State& s,
                                                 const TimeStepControls& controls, Index c,
                                                 StepLimit& best, bool end_of_stage,
                                                 const StageRelaxation* relaxation = nullptr) {
  cellThermoOnShape(geo.shape, s, controls, c, best, end_of_stage, relaxation,
                    [&](const CornerImpedance& coefficients) {
                      for (int p = 0; p < 8; ++p) {
                        storeCorner(s, 8 * c + p, coefficients,
                                    {geo.corner[p], geo.normal_moment[p], geo.corner_face_area[p]});
                      }
                    });
}

// The positions of one cell's nodes, read from the mesh when asked for (the
// staged form: a GPU thread does not hold all 8).
struct NodesOfCell {
  CellNodesView cell_nodes;
  Vec3View x_n;
  Index c;
  KOKKOS_INLINE_FUNCTION Vec3 operator()(int n) const { return loadVec3(x_n, cell_nodes(c, n)); }
};

// StageEnd::ForRemap's part of the closure at the end of a stage: volume,
// centroid and volume shares (`share`: a mixed cell's new volume shared
// among its materials, shareVolumeChange), and the checks that need no equation of state (a
// tangled cell, a non-finite energy or density). Proposes no time step.
KOKKOS_INLINE_FUNCTION void cellShapeForRemap(const hex::CellShape& shape, const State& s, Index c,
                                              StepLimit& best,
                                              const StageRelaxation* relaxation = nullptr,
                                              bool share = true) {
  const double volume = shape.volume;
  s.vol_c(c) = volume;
  storeVec3(s.x_c, c, shape.centroid);
  if (share && s.n_materials > 1) shareVolumeChange(s, c, volume, relaxation);
  if (!(volume > 0.0)) return proposeStepLimit(best, -1.0, c, kBadVolume);
  const Vec3 v = loadVec3(s.v_c, c);
  const double e = s.E_c(c) - 0.5 * dot(v, v);
  const bool finite_state = math::isfinite(e) && math::isfinite(s.m_c(c) / volume);
  if (!finite_state) proposeStepLimit(best, -1.0, c, kBadState);
}

}  // namespace lagremap
