#include "lagrange_step.hpp"

#include <utility>

#include "kernels/cell_update.hpp"
#include "kernels/corner_terms.hpp"
#include "kernels/nodal_solver.hpp"
#include "parallel.hpp"
#include "state_setup.hpp"

namespace lagremap {

std::string describeInvalidCell(const StepLimit& limit, long step, const char* when) {
  const int cell = limit.loc / kLimitCodes;
  const char* what = "invalid state";
  switch (limit.loc % kLimitCodes) {
    case kBadVolume:
      what = "non-positive volume (tangled cell)";
      break;
    case kBadState:
      what = "NaN or infinite energy or velocity";
      break;
    case kBadEos:
      what = "equation of state out of range (Mie-Gruneisen: eta - s (eta - 1) <= 0)";
      break;
    case kBadSoundSpeed:
      what = "non-positive squared sound speed (negative energy/pressure)";
      break;
    default:
      break;
  }
  return "step " + std::to_string(step) + " (" + when + "), cell " + std::to_string(cell) + ": " +
         what;
}

LagrangeStep::LagrangeStep(Mesh& mesh, State& state, const Numerics& numerics, PhaseTimers& timers,
                           const Halo* halo)
    : mesh_(mesh), state_(state), numerics_(numerics), timers_(timers), halo_(halo) {
  if (state_.has_solids) {
    const auto materials = Kokkos::create_mirror_view_and_copy(HostSpace(), state_.materials);
    for (int k = 0; k < state_.n_materials; ++k) {
      if (materials(k).strength != StrengthKind::None) solid_materials_ |= 1u << k;
    }
  }
  if (halo_) {
    node_fields_ = {fieldRef("v_n", state_.v_n)};
    stage_end_fields_ = stageEndCellFields(state_);
    stage_end_fields_for_remap_ = stageEndCellFieldsForRemap(state_);
  }
}

StepLimit LagrangeStep::overAllRanks(StepLimit limit) const {
  const int cell = limit.loc / kLimitCodes;
  if (limit.loc >= 0 && cell < mesh_.n_cells) {
    limit.loc = int(mesh_.cell_global(cell)) * kLimitCodes + limit.loc % kLimitCodes;
  }
  return parallel::minLoc(limit);
}

void LagrangeStep::computeGeometry(const StepLimitView& into) {
  auto scope = timers_.scope(Phase::Geometry);
  lagremap::computeGeometry(mesh_, state_, numerics_.step, into, numerics_.kernels);
}

StepLimit LagrangeStep::computeGeometry() {
  computeGeometry(own_report_.after_remap);
  fenceFor("lagremap::lagrange: the geometry's step limit");
  return overAllRanks(own_report_.after_remap());
}

void LagrangeStep::launch(double dt, const StepReport& report) {
  // (the first stage keeps the state of t^n as it goes: StepStartSave)
  if (numerics_.order == 1) return stage(dt, true, true, report);  // forward Euler
  // predictor: nodal velocities of t^n carry the state to t^{n+1/2}
  stage(0.5 * dt, true, false, report);
  // corrector: forces and velocities of t^{n+1/2} carry t^n to t^{n+1} (an
  // invalid half-step state is found when the host reads the report)
  stage(dt, false, true, report);
}

StepLimit LagrangeStep::advance(double dt, long step) {
  launch(dt, own_report_);
  fenceFor("lagremap::lagrange: the step's limits");
  if (numerics_.order == 2) {
    const StepLimit half_step = overAllRanks(own_report_.predictor());
    if (half_step.val < 0.0) throw RunFailure(describeInvalidCell(half_step, step, "predictor"));
  }
  return overAllRanks(own_report_.end_of_step());
}

// One stage of the predictor-corrector (docs/method.md §1.1): its five
// phases, each timed; this rank's bound on the next dt (the smallest CFL and
// volume-change candidate at the new positions, docs/method.md §2.7) left in
// the report's predictor or end_of_step, and the last stage's boundary power
// in its boundary.
void LagrangeStep::stage(double dt_stage, bool first_stage, bool last_stage,
                         const StepReport& report) {
  const StageEnd what = last_stage && remap_follows_ ? StageEnd::ForRemap : StageEnd::Full;
  computeCorners(first_stage);
  solveNodesAndMove(dt_stage, first_stage && !nodes_start_on_target_,
                    last_stage ? report.boundary : BoundaryPowerView());
  completeGhostNodes(dt_stage);
  updateCells(dt_stage, what, last_stage ? report.end_of_step : report.predictor);
  completeOuterGhostCells(what);
}

void LagrangeStep::computeCorners(bool save_cells) {
  auto scope = timers_.scope(Phase::Corners);
  computeCornerTerms(mesh_, state_, cornerControls(), numerics_.kernels,
                     {save_cells, false, solid_materials_});
}

void LagrangeStep::solveNodesAndMove(double dt_stage, bool save_nodes,
                                     const BoundaryPowerView& power) {
  auto scope = timers_.scope(Phase::NodalSolve);
  nodalSolve(mesh_, state_, cornerControls(), dt_stage, save_nodes, power);
  std::swap(mesh_.x_n, state_.x_n_next);  // the mesh moves: no copy, the Views trade places
}

void LagrangeStep::completeGhostNodes(double dt_stage) {
  if (!halo_) return;
  // ghost nodes: their owners' velocities (docs/method.md §7.4), and the positions
  // these give, computed as their owners do (the external forces are read
  // on owned nodes only: the boundary work)
  auto scope = timers_.scope(Phase::Halo);
  halo_->exchangeNodes(node_fields_);
  moveGhostNodes(mesh_, state_, dt_stage);
}

void LagrangeStep::updateCells(double dt_stage, StageEnd what, const StepLimitView& into) {
  auto scope = timers_.scope(Phase::CellUpdate);
  updateCellsAndGeometry(mesh_, state_, dt_stage, numerics_.step, into, what, numerics_.kernels);
}

void LagrangeStep::completeOuterGhostCells(StageEnd what) {
  if (!halo_) return;
  // what the next stage, or the remap, reads in the outer ghost layer (the
  // first layer has completed the stage by itself: src/fields.hpp)
  auto scope = timers_.scope(Phase::Halo);
  halo_->exchangeOuterCells(what == StageEnd::ForRemap ? stage_end_fields_for_remap_
                                                       : stage_end_fields_);
}

void LagrangeStep::remapFollowsEveryStep() {
  remap_follows_ = true;
  nodes_start_on_target_ = true;
  Kokkos::deep_copy(state_.x_n0, mesh_.x_n);
}

void LagrangeStep::saveStartOfStep() {
  // (with a remap after every step the nodes start each step on the remap's
  // target, which x_n0 holds: RemapStep)
  copyStepStart(state_, mesh_.x_n, StepStart::Save, solid_materials_, !nodes_start_on_target_);
}

void LagrangeStep::restoreStartOfStep() {
  copyStepStart(state_, mesh_.x_n, StepStart::Restore, solid_materials_, true);
  computeGeometry();
}

}  // namespace lagremap
