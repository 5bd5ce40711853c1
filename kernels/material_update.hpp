// The materials' update of one cell over a stage (docs/method.md §A7-A8),
// updateMaterials: internal energies (a mixed cell's through its budget,
// mixed_cell_budget.hpp), hypo-elastic deviators (Jaumann rate and radial
// return) and Neo-Hookean B, whole (the fused form) or a part at a time (the
// staged form). Called by the cell update (cell_update.hpp).
#pragma once

#include "../data/state.hpp"
#include "cell_thermo.hpp"
#include "constitutive.hpp"
#include "mixed_cell_budget.hpp"
#include "velocity_gradients.hpp"

namespace lagremap {

namespace detail {

// A hardening solid's return and its new plastic strain (the temperature of
// the step start: both stages return at the same T*). Out of line on the
// host: inlined, Johnson-Cook's iteration grew updateMaterials' frame and
// prologue for every cell (+10-22 instructions a cell-step of sedov and
// shell, which never harden).
LAGREMAP_OUT_OF_LINE KOKKOS_INLINE_FUNCTION void hardeningReturn(const State& s, Index c, int k,
                                                                 const SymMat3& trial,
                                                                 const MaterialParams& material,
                                                                 double dt_stage) {
  const PlasticUpdate plastic = plasticReturn(trial, material, s.eps_ck0(c, k), dt_stage,
                                              homologousTemperature(material, s.e_ck0(c, k)));
  storeSym(s.S_ck, c, k, plastic.S);
  s.eps_ck(c, k) = plastic.eps_p;
}
}  // namespace detail

// The materials of one cell over the stage (docs/method.md §A7-A8), given the cell's new
// specific internal energy e_new = E - |V|^2/2:
// - internal energies: a pure cell's material takes e_new; in a mixed cell
//   m^k (e^k - e^k,n) = W^k + share^k D (detail::dissipationShare), which
//   sums to the cell's change; a trace (State::alpha_trace) does no work but
//   takes its share of D, and so does a trace by mass (kMassTrace);
// - hypo-elastic deviators: objective Jaumann update of S^k with L, then
//   radial return, a hardening solid's with its plastic strain (the plastic
//   work is already in the total energy);
// - Neo-Hookean B^k = F B^k,n F^T (SPD kept), stretched along a solid body's
//   interface normal to its own volume ratio.
// A trace's deviator is not driven by the cell's strain rate (it has no say in
// the stress): it keeps its value until it is a material again.
// `relaxation`: a mixed cell's relaxation volumes, for the geometry of the same
// sweep (StageRelaxation).
// The kinds of deviator a call of updateDeviator updates: both in the fused
// form (updateMaterials); in the staged form (material_update_staged.hpp)
// the kinds a run has, a kernel each, after a mixed cell's energies (the
// cell motion's): the budget's work takes the start-of-stage deviators.
enum DeviatorKinds : int {
  kHypoElasticDeviators = 1,  // hypo-elastic S
  kNeoHookeanDeviators = 2,   // Neo-Hookean B
  kBothDeviators = 3,
};

// Material k's energy in a mixed cell: m^k (e^k - e^k,n) = W^k + share^k D
// (`work`: W^k, detail::stageWork, 0 for a trace).
KOKKOS_FORCEINLINE_FUNCTION void mixedMaterialEnergy(const State& s, Index c, int k, double work,
                                                     const detail::MixedCellBudget& budget) {
  const double share = detail::dissipationShare(s, c, k, budget);
  s.e_ck(c, k) = s.e_ck0(c, k) + (work + share * budget.dissipation) / s.m_ck(c, k);
}

// What material k of a cell brings to its deviator's update over the stage.
struct MaterialStage {
  int k;
  bool mixed;        // the cell holds several materials
  bool trace;        // ... and k is a trace (traceFraction)
  double own_ratio;  // k's own volume ratio (1 in a pure cell)
};

// A hypo-elastic solid's deviator returned to its yield surface from the
// trial deviator, a hardening solid's with its plastic strain.
KOKKOS_FORCEINLINE_FUNCTION void returnToYield(const State& s, Index c, int k, const SymMat3& trial,
                                               double dt_stage) {
  const MaterialParams& material = s.materials(k);
  if (hasPlasticStrain(material)) {
    detail::hardeningReturn(s, c, k, trial, material, dt_stage);
  } else {  // perfectly plastic: no strain to carry
    storeSym(s.S_ck, c, k, radialReturn(trial, material.yield_stress).S);
  }
}

// The deviator of material k (present: alpha^k > 0) of cell c over the
// stage, of the kinds kKinds asks for, given the cell's velocity gradient.
// `deformation()`: the cell's stage deformation F, asked for by a
// Neo-Hookean material alone; `to_yield(trial)`: a hypo-elastic solid's
// return from its trial deviator (returnToYield).
template <int kKinds, class Deformation, class ToYield>
KOKKOS_FORCEINLINE_FUNCTION void updateDeviator(const State& s, Index c, const MaterialStage& m,
                                                double dt_stage, const Mat3& gradient,
                                                const Deformation& deformation,
                                                const ToYield& to_yield) {
  constexpr bool kHypo = (kKinds & kHypoElasticDeviators) != 0;
  constexpr bool kNeo = (kKinds & kNeoHookeanDeviators) != 0;
  const int k = m.k;
  const MaterialParams& material = s.materials(k);
  if (m.trace) {
    if (kHypo && material.strength == StrengthKind::HypoElastic) {
      storeSym(s.S_ck, c, k, loadSym(s.S_ck0, c, k));
      if (hasPlasticStrain(material)) s.eps_ck(c, k) = s.eps_ck0(c, k);
    } else if (kNeo && material.strength == StrengthKind::NeoHookean) {
      storeSym(s.B_ck, c, k, loadSym(s.B_ck0, c, k));
    }
  } else if (kHypo && material.strength == StrengthKind::HypoElastic) {
    const Mat3 gradient_k =
        detail::materialGradient(s, c, k, m.mixed, gradient, m.own_ratio, dt_stage);
    to_yield(jaumannUpdate(loadSym(s.S_ck0, c, k), gradient_k, material.mu, dt_stage));
  } else if (kNeo && material.strength == StrengthKind::NeoHookean) {
    const Mat3 cell_deformation = deformation();
    Mat3 own = cell_deformation;
    Vec3 n;
    if (m.mixed && isSolidBody(s, c, k, n)) {
      // stretched along n to its own volume ratio: det(F_s) = J^k
      Mat3 normal_stretch = identityMat();
      addOuter(normal_stretch, m.own_ratio / det(cell_deformation) - 1.0, n, n);
      own = normal_stretch * cell_deformation;
    }
    storeSym(s.B_ck, c, k, pushForward(own, loadSym(s.B_ck0, c, k)));
  }
}

// The materials of cell c, all parts (the fused form): which are present,
// a pure cell's energy, a mixed cell's budget, then each present material's
// energy and deviator.
KOKKOS_INLINE_FUNCTION void updateMaterials(const CellNodesView& cell_nodes, const Vec3View& x_n,
                                            const State& s, double dt_stage, Index c, double e_new,
                                            StageRelaxation& relaxation) {
  int present = 0, last = 0;
  LAGREMAP_NO_UNROLL
  for (int k = 0; k < s.n_materials; ++k) {
    if (s.alpha_ck(c, k) > 0.0) {
      ++present;
      last = k;
    }
  }
  const bool mixed = present > 1;
  if (!mixed) s.e_ck(c, last) = e_new;
  // a pure fluid cell has no deviator to update (whatever its neighbours)
  if (!mixed && s.materials(last).strength == StrengthKind::None) return;
  const Mat3 gradient = velocityGradient(cell_nodes, s, c);
  detail::MixedCellBudget budget;
  if (mixed) detail::mixedCellBudget(s, c, e_new, gradient, dt_stage, budget, relaxation);
  bool deformation_known = false;  // (computed once, by the first Neo-Hookean material)
  Mat3 deformation = zeroMat();
  const auto cell_deformation = [&]() {
    if (!deformation_known) deformation = stageDeformation(cell_nodes, x_n, s, c);
    deformation_known = true;
    return deformation;
  };
  const bool holds_elastic = mixed && cellHoldsElasticBody(s, s.alpha_ck, c);
  LAGREMAP_NO_UNROLL
  for (int k = 0; k < s.n_materials; ++k) {
    const double alpha = s.alpha_ck(c, k);
    if (!(alpha > 0.0)) continue;
    const bool trace = mixed && alpha < traceFraction(s, k, holds_elastic);
    const double own_ratio = mixed ? budget.own_ratio[k] : 1.0;
    if (mixed) {
      mixedMaterialEnergy(
          s, c, k, trace ? 0.0 : detail::stageWork(s, c, k, gradient, own_ratio, dt_stage), budget);
    }
    updateDeviator<kBothDeviators>(
        s, c, {k, mixed, trace, own_ratio}, dt_stage, gradient, cell_deformation,
        [&](const SymMat3& trial) { returnToYield(s, c, k, trial, dt_stage); });
  }
}

}  // namespace lagremap
