// The relaxation phase of ALE mode (docs/method.md §8) as the time loop calls
// it: every ale.every steps, after the Lagrangian step, the target mesh the
// remap then carries the state onto
//   rule's positions (Winslow or initial) -> limited moves -> ghost nodes
//   -> quality guard (cells it would worsen keep their Lagrangian nodes).
#pragma once

#include "data/mesh.hpp"
#include "decomposition.hpp"
#include "kernels/mesh_relaxation.hpp"
#include "timers.hpp"

namespace lagremap {

class MeshRelaxation {
 public:
  // Keeps the mesh's present node positions as its initial ones (the
  // initial rule's; a restart's mesh is the generator's until the
  // checkpoint is read).
  MeshRelaxation(const Mesh& mesh, const RelaxationControls& controls, long every,
                 PhaseTimers& timers, const Halo* halo = nullptr);

  // Whether step `step` ends with a relaxation and remap (every ale.every
  // steps; never at weight 0, where ALE mode is lagrange mode).
  bool due(long step) const { return controls_.weight > 0.0 && step % every_ == 0; }
  // The target mesh of the Lagrangian mesh's present positions, every node
  // of this rank's part (ghosts from their owners). Valid until the next call.
  const Vec3View& target();

  const RelaxationControls& controls() const { return controls_; }
  // Quality-guard passes of the last target() (1: no cell was worsened).
  int guardPasses() const { return guard_passes_; }
  // The smallest scaled Jacobian of the last target() over every rank's
  // cells (kernels/mesh_quality.hpp): the mesh quality after its remap.
  double targetQuality() const { return target_quality_; }

 private:
  void exchangeGhostTargets();

  const Mesh& mesh_;
  RelaxationControls controls_;
  long every_;
  PhaseTimers& timers_;
  const Halo* halo_;
  Vec3View x_initial_, x_target_;
  NodeStencilView node_stencils_;
  DeviceView<int*> node_freedom_, worsened_cells_;
  RealView target_quality_c_;            // each cell's target scaled Jacobian (the guard's)
  std::vector<FieldRef> target_fields_;  // the halo's list, made once (src/fields.hpp)
  int guard_passes_ = 0;
  double target_quality_ = 1.0;
};

}  // namespace lagremap
