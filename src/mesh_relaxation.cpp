#include "mesh_relaxation.hpp"

#include "parallel.hpp"

namespace lagremap {

MeshRelaxation::MeshRelaxation(const Mesh& mesh, const RelaxationControls& controls, long every,
                               PhaseTimers& timers, const Halo* halo)
    : mesh_(mesh), controls_(controls), every_(every), timers_(timers), halo_(halo) {
  x_initial_ = Vec3View("lagremap::ale::x_initial", mesh.n_nodes);
  Kokkos::deep_copy(x_initial_, mesh.x_n);
  x_target_ = Vec3View("lagremap::ale::x_target", mesh.n_nodes);
  node_stencils_ = nodeStencils(mesh);
  node_freedom_ = nodeFreedom(mesh);
  worsened_cells_ = DeviceView<int*>("lagremap::ale::worsened_cells", mesh.n_cells);
  target_quality_c_ = RealView("lagremap::ale::target_quality", mesh.n_cells);
  if (halo_) target_fields_ = {fieldRef("x_target", x_target_)};
}

const Vec3View& MeshRelaxation::target() {
  auto scope = timers_.scope(Phase::Relaxation);
  relaxedTargets(mesh_, node_stencils_, mesh_.x_n, x_initial_, node_freedom_, controls_, x_target_);
  exchangeGhostTargets();
  // the quality guard: each pass sends the nodes of the cells the targets
  // worsen back to their Lagrangian positions, until none is left (a mesh
  // all at x_L worsens none: the passes end)
  guard_passes_ = 0;
  for (;;) {
    ++guard_passes_;
    const GuardTally tally =
        targetCellQualities(mesh_, x_target_, controls_.quality_floor, target_quality_c_);
    target_quality_ = parallel::min(tally.lowest);
    if (parallel::sum(double(tally.below_floor)) == 0.0) break;  // (none can be worse)
    const long worsened = markWorsenedCells(mesh_, mesh_.x_n, target_quality_c_,
                                            controls_.quality_floor, worsened_cells_);
    if (parallel::sum(double(worsened)) == 0.0) break;
    holdNodesOfWorsenedCells(mesh_, mesh_.x_n, worsened_cells_, x_target_);
    exchangeGhostTargets();
  }
  return x_target_;
}

void MeshRelaxation::exchangeGhostTargets() {
  if (!halo_) return;
  halo_->exchangeNodes(target_fields_);
}

}  // namespace lagremap
