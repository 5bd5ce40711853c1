// The state a step starts from, kept: what a failed step puts back (the last
// good state) and what the stages of a step start from (docs/method.md §A5:
// the corrector carries t^n to t^{n+1}; a mixed cell shares its volume change
// from the step-start fractions). A cell's part (copyCellStart) and a node's
// (copyNodeStart), which the first stage's corner kernel and nodal solve call
// on the cells and nodes they visit (StepStartSave: no kernel of its own in a
// step), and copyStepStart (src/state_setup.hpp) in a kernel of its own.
#pragma once

#include "../data/state.hpp"

namespace lagremap {

// Which way the copy goes: the state a step starts from saved, or put back.
enum class StepStart { Save, Restore };

namespace detail {
// One value of the copy: saved (now -> start) or put back.
KOKKOS_FORCEINLINE_FUNCTION void copyOne(StepStart direction, double& now, double& start) {
  if (direction == StepStart::Save) {
    start = now;
  } else {
    now = start;
  }
}
}  // namespace detail

// Cell c's part: velocity, total and material energies; with several
// materials their volume fractions (and, saved, the pressures, volume weights
// and cell volume the stages start from); the deviators and plastic strains
// of the materials in `solids` (bit k: material k has strength; a fluid's are
// zero throughout: nothing writes them); B where the state has it; saved, the
// material masses where it keeps them (State::m_ck0: RemapStep puts them back).
KOKKOS_INLINE_FUNCTION void copyCellStart(const State& s, Index c, unsigned solids,
                                          StepStart direction) {
  using detail::copyOne;
  const bool save = direction == StepStart::Save;
  const bool mixed = s.n_materials > 1;
  for (int d = 0; d < 3; ++d) copyOne(direction, s.v_c(c, d), s.v_c0(c, d));
  copyOne(direction, s.E_c(c), s.E_c0(c));
  if (mixed && save) s.vol_c0(c) = s.vol_c(c);
  for (int k = 0; k < s.n_materials; ++k) {
    copyOne(direction, s.e_ck(c, k), s.e_ck0(c, k));
    if (mixed) copyOne(direction, s.alpha_ck(c, k), s.alpha_ck0(c, k));
    if (mixed && save) {
      s.w_ck0(c, k) = s.w_ck(c, k);
      s.p_ck0(c, k) = s.p_ck(c, k);
    }
    if (save && s.m_ck0.extent(0) > 0) s.m_ck0(c, k) = s.m_ck(c, k);
    if (s.B_ck.extent(0) > 0) {
      for (int j = 0; j < 6; ++j) copyOne(direction, s.B_ck(c, k, j), s.B_ck0(c, k, j));
    }
    if ((solids >> k & 1u) == 0) continue;
    for (int j = 0; j < 6; ++j) copyOne(direction, s.S_ck(c, k, j), s.S_ck0(c, k, j));
    if (s.eps_ck.extent(0) > 0) copyOne(direction, s.eps_ck(c, k), s.eps_ck0(c, k));
  }
}

// Node n's part: its position x_n (the mesh's) and x_n0.
KOKKOS_FORCEINLINE_FUNCTION void copyNodeStart(const State& s, const Vec3View& x_n, Index n,
                                               StepStart direction) {
  for (int d = 0; d < 3; ++d) detail::copyOne(direction, x_n(n, d), s.x_n0(n, d));
}

// What the first stage of a step saves as it goes (LagrangeStep::launch):
// the cells' part in the corner kernel, which reads the cells of t^n and
// writes none of it, before any cell update; the nodes' positions in the
// nodal solve, which then moves them from x_n (what x_n0 becomes) rather
// than from x_n0. A later stage saves nothing.
struct StepStartSave {
  bool cells = false;
  bool nodes = false;   // (not where x_n0 holds the step's start: remap mode)
  unsigned solids = 0;  // copyCellStart's
};

}  // namespace lagremap
