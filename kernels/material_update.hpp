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
// What updateMaterials does: the fused form all of it in one kernel, the
// staged form a part a call (kernels/cell_update.hpp; the energies first:
// the deviators' updates read nothing they write, and they write the
// start-of-stage deviators the energies' stress power takes).
enum MaterialParts : int {
  kMaterialEnergies = 1,  // e^k (and a mixed cell's budget)
  kHypoElasticParts = 2,  // hypo-elastic deviators
  kNeoHookeanParts = 4,   // Neo-Hookean B (the stage deformation a corner vector at a time)
  kAllMaterialParts = 7,  // the fused form
};

template <int kParts = kAllMaterialParts>
KOKKOS_INLINE_FUNCTION void updateMaterials(const CellNodesView& cell_nodes, const Vec3View& x_n,
                                            const State& s, double dt_stage, Index c, double e_new,
                                            StageRelaxation& relaxation) {
  constexpr bool kEnergies = (kParts & kMaterialEnergies) != 0;
  constexpr bool kHypo = (kParts & kHypoElasticParts) != 0;
  constexpr bool kNeo = (kParts & kNeoHookeanParts) != 0;
  constexpr bool kStaged = kParts != kAllMaterialParts;
  int present = 0, last = 0;
  LAGREMAP_NO_UNROLL
  for (int k = 0; k < s.n_materials; ++k) {
    if (s.alpha_ck(c, k) > 0.0) {
      ++present;
      last = k;
    }
  }
  const bool mixed = present > 1;
  if (kEnergies && !mixed) s.e_ck(c, last) = e_new;
  // a pure fluid cell has no deviator to update (whatever its neighbours)
  if (!mixed && s.materials(last).strength == StrengthKind::None) return;
  if constexpr (!kHypo && !kNeo) {
    if (!mixed) return;  // (only a mixed cell's budget is left)
  }
  const Mat3 gradient = velocityGradient(cell_nodes, s, c);
  detail::MixedCellBudget budget;
  if (mixed) {
    if constexpr (kEnergies) {
      detail::mixedCellBudget(s, c, e_new, gradient, dt_stage, budget, relaxation);
    } else {  // the own volume ratios alone (the same numbers)
      detail::ownVolumeRatios(s, c, dt_stage * s.vol_c(c) * trace(gradient), budget.own_ratio,
                              relaxation);
    }
  }
  bool deformation_known = false;
  Mat3 deformation = zeroMat();
  const bool holds_elastic = mixed && cellHoldsElasticBody(s, s.alpha_ck, c);
  LAGREMAP_NO_UNROLL
  for (int k = 0; k < s.n_materials; ++k) {
    const double alpha = s.alpha_ck(c, k);
    if (!(alpha > 0.0)) continue;
    const bool trace = mixed && alpha < traceFraction(s, k, holds_elastic);
    const double own_ratio = mixed ? budget.own_ratio[k] : 1.0;
    if (kEnergies && mixed) {
      const double work =
          trace
              ? 0.0
              : detail::materialWork(
                    s, c, k, detail::materialGradient(s, c, k, true, gradient, own_ratio, dt_stage),
                    own_ratio, dt_stage);
      const double share = detail::dissipationShare(s, c, k, budget);
      s.e_ck(c, k) = s.e_ck0(c, k) + (work + share * budget.dissipation) / s.m_ck(c, k);
    }
    const MaterialParams& material = s.materials(k);
    if (trace) {
      if (kHypo && material.strength == StrengthKind::HypoElastic) {
        storeSym(s.S_ck, c, k, loadSym(s.S_ck0, c, k));
        if (hasPlasticStrain(material)) s.eps_ck(c, k) = s.eps_ck0(c, k);
      } else if (kNeo && material.strength == StrengthKind::NeoHookean) {
        storeSym(s.B_ck, c, k, loadSym(s.B_ck0, c, k));
      }
    } else if (kHypo && material.strength == StrengthKind::HypoElastic) {
      const Mat3 gradient_k =
          detail::materialGradient(s, c, k, mixed, gradient, own_ratio, dt_stage);
      const SymMat3 trial =
          jaumannUpdate(loadSym(s.S_ck0, c, k), gradient_k, material.mu, dt_stage);
      if (hasPlasticStrain(material)) {
        detail::hardeningReturn(s, c, k, trial, material, dt_stage);
      } else {  // perfectly plastic: no strain to carry
        storeSym(s.S_ck, c, k, radialReturn(trial, material.yield_stress).S);
      }
    } else if (kNeo && material.strength == StrengthKind::NeoHookean) {
      if (!deformation_known) {
        if constexpr (kStaged) {
          deformation = stagedStageDeformation(cell_nodes, x_n, s, c);
        } else {
          deformation = stageDeformation(cell_nodes, x_n, s, c);
        }
      }
      deformation_known = true;
      Mat3 own = deformation;
      Vec3 n;
      if (mixed && isSolidBody(s, c, k, n)) {
        // stretched along n to its own volume ratio: det(F_s) = J^k
        Mat3 normal_stretch = identityMat();
        addOuter(normal_stretch, own_ratio / det(deformation) - 1.0, n, n);
        own = normal_stretch * deformation;
      }
      storeSym(s.B_ck, c, k, pushForward(own, loadSym(s.B_ck0, c, k)));
    }
  }
}

}  // namespace lagremap
