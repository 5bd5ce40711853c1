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

  // Remaps the state of the Lagrangian mesh onto the target mesh and moves the
  // mesh back; returns what crossed the outer boundary (mass, momentum,
  // total energy). The geometry of the state is stale afterwards.
  RemapBoundaryFlux apply() { return apply(state_.x_n0); }
  // The same onto another mesh of the same connectivity, a small displacement
  // from the Lagrangian one (ALE mode's relaxed mesh, src/mesh_relaxation.hpp),
  // where the mesh then stays.
  RemapBoundaryFlux apply(const Vec3View& target);
  // Puts back the masses of the start of the last apply(), which the
  // Lagrangian step does not change and so does not keep (its
  // restoreStartOfStep puts back the rest of the state, volume fractions
  // included).
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
  MatRealView m_ck_saved_;
  std::vector<FieldRef> remapped_fields_;  // the halo's list, made once (src/fields.hpp)
};

}  // namespace lagremap
