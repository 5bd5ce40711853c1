// The materials' update in the staged form (KernelForm::Staged,
// docs/method.md §7.6): the fused form's arithmetic (material_update.hpp)
// laid out for a GPU, a cell to each thread of a team (cell_teams.hpp) and
// its corners, matrix entries or materials in the lanes of a vector. Its two
// parts ride on two kernels of the staged cell update (cell_update.hpp): a
// mixed cell's budget and energies on the cell motion (detail::
// CellMotionOnLanes), which has just formed the cell's new energy, and the
// deviators in a kernel of their own (StagedDeviators).
#pragma once

#include "../data/mesh.hpp"
#include "../data/state.hpp"
#include "cell_teams.hpp"
#include "cell_thermo.hpp"
#include "hex.hpp"
#include "material_update.hpp"

namespace lagremap {

namespace detail {

// A cell's row of its team's scratch memory. Lane p leaves corner p's node
// velocity and corner vector and, in a cell holding a Neo-Hookean material,
// its terms of the stage deformation; lane e then sums entry e of the
// velocity gradient and of F in corner order with addOuter's arithmetic, so
// the bits are the fused form's. A mixed cell's budget follows: its own
// volume ratios by one lane, each material's work by its lane, the sums by
// one lane in material order. The budget's columns come first (the cell
// motion's row holds them alone).
namespace material_lanes {
// (enumerators, not constexpr variables: device code takes them by reference)
enum : int {
  kVelocity = 0,        // 8 x 3: V_p, the node's new velocity
  kCornerVector = 24,   // 8 x 3: A_cp, the stage start's corner vector
  kGradient = 48,       // 9: L, row by row
  kOwnRatio = 57,       // kMaxMaterials: each material's own volume ratio
  kWork = 65,           // kMaxMaterials: each material's work W^k (a trace's not formed)
  kBudget = 73,         // 5: D, the present and condensed masses, alpha, the gases' heat
  kBudgetColumns = 78,  // (the budget's)
  kStartVector = 78,    // 8 x 3: the step start's corner vector (stageDeformation)
  kMoved = 102,         // 8 x 3: x_p - x_0 at the new positions
  kStartVolume = 126,   // 8: corner p's term of 3 v^n (Euler's theorem)
  kDeformation = 134,   // 9: F, row by row
  kTrial = 143,         // kMaxMaterials x 6: a hypo-elastic solid's trial deviator
  kColumns = 191,
};
}  // namespace material_lanes

using cell_teams::ScratchRow;

// What the lanes of a cell's materials read: the mesh's connectivity and
// positions, the state, the stage's length.
struct MaterialLanes {
  CellNodesView cell_nodes;
  Vec3View x_n;
  State s;
  double dt_stage;

  // How many materials cell c holds, and the last of them.
  KOKKOS_INLINE_FUNCTION int presentMaterials(Index c, int& last) const {
    int present = 0;
    LAGREMAP_NO_UNROLL
    for (int k = 0; k < s.n_materials; ++k) {
      if (s.alpha_ck(c, k) > 0.0) {
        ++present;
        last = k;
      }
    }
    return present;
  }

  // Corner p's terms of the velocity gradient.
  KOKKOS_INLINE_FUNCTION static void storeVelocityTerms(const ScratchRow& row, int p,
                                                        const Vec3& v_node,
                                                        const Vec3& corner_vector) {
    row.store(material_lanes::kVelocity + 3 * p, v_node);
    row.store(material_lanes::kCornerVector + 3 * p, corner_vector);
  }

  // Lane p: corner p's terms of the gradient and (`deforms`) of F.
  template <class Member>
  KOKKOS_INLINE_FUNCTION void corners(const Member& team, Index c, const ScratchRow& row,
                                      bool deforms) const {
    Kokkos::parallel_for(Kokkos::ThreadVectorRange(team, 8), [&](const int p) {
      storeVelocityTerms(row, p, loadVec3(s.v_n, cell_nodes(c, p)), loadVec3(s.A_cp, 8 * c + p));
      if (!deforms) return;
      const NodesOfCell start{cell_nodes, s.x_n0, c};
      const Vec3 start_vector = hex::cornerVector(start, p);
      row.store(material_lanes::kStartVector + 3 * p, start_vector);
      row(material_lanes::kStartVolume + p) = dot(start(p) - start(0), start_vector);
      row.store(material_lanes::kMoved + 3 * p,
                loadVec3(x_n, cell_nodes(c, p)) - loadVec3(x_n, cell_nodes(c, 0)));
    });
  }

  // Lane e: entry (i, j) = e of the velocity gradient L = (1/v) sum_p V_p
  // (x) A_cp (velocityGradient) and (`deforms`) of the stage deformation F =
  // (1/v^n) sum_p (x_p - x_0) (x) A_cp^n (stageDeformation), from the corner
  // lanes' terms in corner order and addOuter's arithmetic.
  template <class Member>
  KOKKOS_INLINE_FUNCTION void sums(const Member& team, Index c, const ScratchRow& row,
                                   bool deforms) const {
    using namespace material_lanes;
    Kokkos::parallel_for(Kokkos::ThreadVectorRange(team, 9), [&](const int e) {
      const int i = e / 3, j = e % 3;
      const double inv_volume = 1.0 / s.vol_c(c);
      double entry = 0.0;
      LAGREMAP_NO_UNROLL
      for (int p = 0; p < 8; ++p) {
        entry += (inv_volume * row(kVelocity + 3 * p + i)) * row(kCornerVector + 3 * p + j);
      }
      row(kGradient + e) = entry;
      if (!deforms) return;
      double volume_start = 0.0;  // Euler's theorem for the cubic volume
      LAGREMAP_NO_UNROLL
      for (int p = 0; p < 8; ++p) volume_start += row(kStartVolume + p);
      volume_start /= 3.0;
      entry = 0.0;
      LAGREMAP_NO_UNROLL
      for (int p = 0; p < 8; ++p) {
        entry += ((1.0 / volume_start) * row(kMoved + 3 * p + i)) * row(kStartVector + 3 * p + j);
      }
      row(kDeformation + e) = entry;
    });
  }

  KOKKOS_INLINE_FUNCTION static Mat3 matrix(const ScratchRow& row, int column) {
    Mat3 m;
    for (int e = 0; e < 9; ++e) m.m[e / 3][e % 3] = row(column + e);
    return m;
  }

  // One lane: a mixed cell's own volume ratios.
  template <class Member>
  KOKKOS_INLINE_FUNCTION void ownRatios(const Member& team, Index c, const ScratchRow& row) const {
    Kokkos::single(Kokkos::PerThread(team), [&] {
      StageRelaxation relaxation;
      const Mat3 gradient = matrix(row, material_lanes::kGradient);
      ownVolumeRatios(s, c, dt_stage * s.vol_c(c) * trace(gradient),
                      &row(material_lanes::kOwnRatio), relaxation);
    });
  }

  // The energies of cell c's materials, its new specific internal energy
  // e_new (docs/method.md §4): a pure cell's material takes it; a mixed
  // cell's budget takes its gradient (from the corner lanes' velocity terms
  // in the row), its own volume ratios (one lane), each material's work (its
  // lane) and the sums (one lane), then each material its energy (its lane).
  template <class Member>
  KOKKOS_INLINE_FUNCTION void energies(const Member& team, Index c, const ScratchRow& row,
                                       double e_new) const {
    int last = 0;
    if (presentMaterials(c, last) < 2) {
      Kokkos::single(Kokkos::PerThread(team), [&] { s.e_ck(c, last) = e_new; });
      return;
    }
    sums(team, c, row, false);
    ownRatios(team, c, row);
    const bool holds_elastic = cellHoldsElasticBody(s, s.alpha_ck, c);
    Kokkos::parallel_for(Kokkos::ThreadVectorRange(team, s.n_materials), [&](const int k) {
      const double alpha = s.alpha_ck(c, k);
      if (!(alpha > 0.0 && alpha >= traceFraction(s, k, holds_elastic))) return;  // (a trace: none)
      row(material_lanes::kWork + k) = stageWork(s, c, k, matrix(row, material_lanes::kGradient),
                                                 row(material_lanes::kOwnRatio + k), dt_stage);
    });
    Kokkos::single(Kokkos::PerThread(team), [&] {
      MixedCellBudget budget;
      sumBudget(
          s, c, e_new, [&](int k) { return row(material_lanes::kWork + k); }, budget);
      const double sums[5] = {budget.dissipation, budget.present_mass, budget.condensed_mass,
                              budget.present_alpha, budget.gas_heat};
      for (int i = 0; i < 5; ++i) row(material_lanes::kBudget + i) = sums[i];
    });
    Kokkos::parallel_for(Kokkos::ThreadVectorRange(team, s.n_materials), [&](const int k) {
      const double alpha = s.alpha_ck(c, k);
      if (!(alpha > 0.0)) return;
      MixedCellBudget budget;
      budget.dissipation = row(material_lanes::kBudget);
      budget.present_mass = row(material_lanes::kBudget + 1);
      budget.condensed_mass = row(material_lanes::kBudget + 2);
      budget.present_alpha = row(material_lanes::kBudget + 3);
      budget.gas_heat = row(material_lanes::kBudget + 4);
      const bool trace = alpha < traceFraction(s, k, holds_elastic);
      mixedMaterialEnergy(s, c, k, trace ? 0.0 : row(material_lanes::kWork + k), budget);
    });
  }

  // The deviators of cell c's materials of the kinds kKinds asks for: the
  // corner terms and their sums, a mixed cell's own volume ratios (one
  // lane; recomputed, the same numbers as the energies', rather than kept in
  // a View of their own across the two kernels), then lane k material k's (updateDeviator), a
  // hypo-elastic solid's trial left in the row and returned to its yield surface in a pass of its
  // own (after the Jaumann update in one pass, the return spilled on sm_90).
  template <int kKinds, class Member>
  KOKKOS_INLINE_FUNCTION void deviators(const Member& team, Index c, const ScratchRow& row) const {
    int last = 0;
    const bool mixed = presentMaterials(c, last) > 1;
    // a pure fluid cell has no deviator to update (whatever its neighbours)
    if (!mixed && s.materials(last).strength == StrengthKind::None) return;
    const bool deforms =
        (kKinds & kNeoHookeanDeviators) != 0 && cellHoldsElasticBody(s, s.alpha_ck, c);
    corners(team, c, row, deforms);
    sums(team, c, row, deforms);
    if (mixed) ownRatios(team, c, row);
    const bool holds_elastic = mixed && cellHoldsElasticBody(s, s.alpha_ck, c);
    Kokkos::parallel_for(Kokkos::ThreadVectorRange(team, s.n_materials), [&](const int k) {
      const double alpha = s.alpha_ck(c, k);
      if (!(alpha > 0.0)) return;
      const bool trace = mixed && alpha < traceFraction(s, k, holds_elastic);
      updateDeviator<kKinds>(
          s, c, {k, mixed, trace, mixed ? row(material_lanes::kOwnRatio + k) : 1.0}, dt_stage,
          matrix(row, material_lanes::kGradient),
          [&]() { return matrix(row, material_lanes::kDeformation); },
          [&](const SymMat3& trial) { row.store(material_lanes::kTrial + 6 * k, trial); });
    });
    if constexpr ((kKinds & kHypoElasticDeviators) != 0) {
      Kokkos::parallel_for(Kokkos::ThreadVectorRange(team, s.n_materials), [&](const int k) {
        const double alpha = s.alpha_ck(c, k);
        if (!(alpha > 0.0 && s.materials(k).strength == StrengthKind::HypoElastic)) return;
        if (mixed && alpha < traceFraction(s, k, holds_elastic)) return;
        returnToYield(s, c, k, row.sym(material_lanes::kTrial + 6 * k), dt_stage);
      });
    }
  }
};

// The deviators' kernel: the deviators of the kinds kKinds (DeviatorKinds)
// of a mesh's cells (MaterialLanes::deviators). A GPU's
// block of 128 threads: the hypo-elastic ones 5 an SM, at most 96
// registers, 20 warps (at 80 the Jaumann update spilled 108 B), the
// Neo-Hookean ones 6, 80 registers, 24 warps (a cell to a thread held
// 126-128, 16 warps).
template <int kKinds>
struct StagedDeviators {
  static constexpr unsigned kBlocks = kKinds == kNeoHookeanDeviators ? 6 : 5;
  using Teams = Kokkos::TeamPolicy<ExecSpace, Kokkos::LaunchBounds<128, kBlocks>>;
  MaterialLanes lanes;
  Index n_cells;

  KOKKOS_INLINE_FUNCTION void operator()(const typename Teams::member_type& team) const {
    cell_teams::forCellsOfTeam(
        team, n_cells, material_lanes::kColumns,
        [&](Index c, const ScratchRow& row) { lanes.deviators<kKinds>(team, c, row); });
  }
};

}  // namespace detail

}  // namespace lagremap
