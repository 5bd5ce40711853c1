// The remap phase of docs/method.md §A9-A11 as the time loop calls it: after each
// Lagrangian step, the state is swept back onto the initial mesh
//   densities -> limited gradients (Lagrangian mesh) -> swept regions
//   -> upwind fluxes, clean-up, kinetic-energy fix -> mesh back to x_initial
// and the caller recomputes the geometry (the next step's time step).
#pragma once

#include "data/mesh.hpp"
#include "data/state.hpp"
#include "decomposition.hpp"
#include "kernels/geometry.hpp"
#include "kernels/remap.hpp"
#include "step_report.hpp"
#include "timers.hpp"

namespace lagremap {

// Columns of the remapped quantities for the state's materials (a tensor
// block per solid); throws beyond kMaxMaterials materials. RemapStep's own
// layout; public so that the benchmarks size their work arrays alike.
RemapLayout makeRemapLayout(const State& state);

class RemapStep {
 public:
  // Keeps the mesh's current node positions as the remap target (in
  // State::x_n0, where every step starts: the caller's LagrangeStep is told
  // remapFollowsEveryStep, or saves the start of each step). Moves the
  // state's corner arrays into the memory of its work arrays (their values
  // kept): the caller computes the geometry after each apply().
  RemapStep(Mesh& mesh, State& state, const RemapControls& controls, PhaseTimers& timers,
            const Halo* halo = nullptr);

  // Remaps the state of the Lagrangian mesh onto `target` and moves the mesh
  // there, without waiting: what crossed this rank's outer boundary (mass,
  // momentum, total energy) and the remapped cells' totals (the audit's) are
  // left in `audit` (RemapAudit). The target is the initial mesh
  // (State::x_n0) or another of the same connectivity, a small displacement
  // from the Lagrangian one (ALE mode's relaxed mesh,
  // src/mesh_relaxation.hpp). The geometry of the state is stale afterwards.
  void launch(const Vec3View& target, const RemapAuditView& audit);
  void launch(const RemapAuditView& audit) { launch(state_.x_n0, audit); }
  // The same, waited for: returns what crossed every rank's outer boundary.
  RemapBoundaryFlux apply() { return apply(state_.x_n0); }
  RemapBoundaryFlux apply(const Vec3View& target);
  // Puts back the masses of the start of the step (State::m_ck0, which the
  // Lagrangian step saves but does not put back: its restoreStartOfStep puts
  // back the rest of the state, volume fractions included).
  void restoreStartOfStep();

  const RemapLayout& layout() const { return layout_; }
  // The memory of the work arrays and the state's corner arrays.
  const RealView& sharedWork() const { return shared_work_; }

 private:
  Mesh& mesh_;
  State& state_;
  RemapControls controls_;
  PhaseTimers& timers_;
  const Halo* halo_;
  RemapLayout layout_;
  RealView shared_work_;
  RemapFields fields_;
  SweptFaces swept_;
  RemapAuditView audit_{"lagremap::remap::audit", kRemapAuditSums};  // apply()'s
  std::vector<FieldRef> remapped_fields_;  // the halo's list, made once (src/fields.hpp)
};

}  // namespace lagremap
