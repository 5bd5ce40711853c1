// The Lagrangian step of docs/method.md §A5, as it reads in the paper:
//   geometry -> time step -> [predictor: corners, nodal solve, cell update (dt/2)]
//   -> geometry at t^{n+1/2} -> [corrector: corners, nodal solve, cell update (dt)]
//   -> geometry at t^{n+1} (the next step's time-step candidates).
// Each cell update and the geometry that follows it run as one cell sweep.
#pragma once

#include <stdexcept>
#include <string>

#include "data/mesh.hpp"
#include "data/state.hpp"
#include "decomposition.hpp"
#include "kernels/corner_controls.hpp"
#include "kernels/geometry.hpp"
#include "step_report.hpp"
#include "timers.hpp"

namespace lagremap {

struct Numerics {
  int order = 2;
  TimeStepControls step;
  double dt_growth = 1.05;         // dt <= dt_growth * dt_prev
  double dt_initial_factor = 0.1;  // first dt = factor * stable dt
  double dt_min = 0.0;             // below this the run stops (dt collapse)
  // ... and below this fraction of the largest stable dt the run has had: on
  // a fixed mesh (remap mode) the stable dt only falls where sound speeds
  // rise, and a hundredfold fall is a state the closure cannot hold, not
  // physics worth 1e5 steps (docs/method.md §4.8, the ball under equal strain)
  double dt_drop_fraction = 1e-2;
  long max_steps = 10000000;
  Gather gather = Gather::Crs;
  KernelForm kernels = defaultKernelForm();  // numerics.kernels
};

// A run that cannot go on (tangled cell, NaN, dt collapse): the driver writes
// the last good state and exits with code 3.
struct RunFailure : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Text for a failure found by the time-step reduction.
std::string describeInvalidCell(const StepLimit& limit, long step, const char* when);

class LagrangeStep {
 public:
  // `halo`: the ghost exchanges of a decomposed run (none: one rank).
  LagrangeStep(Mesh& mesh, State& state, const Numerics& numerics, PhaseTimers& timers,
               const Halo* halo = nullptr);

  // Geometry and thermodynamics of the current node positions; the
  // time-step candidate (negative for an invalid cell) of this rank's cells
  // left in `into` without waiting.
  void computeGeometry(const StepLimitView& into);
  // The same, waited for: the candidate over every rank.
  StepLimit computeGeometry();
  // One step t^n -> t^{n+1} from a state whose geometry is current, without
  // waiting: this rank's time-step candidates of the half-step state (second
  // order) and of t^{n+1} land in report.predictor and report.end_of_step
  // (negative for an invalid cell), the boundary's power in report.boundary;
  // the start-of-step copy is kept (by the first stage's kernels).
  void launch(double dt, const StepReport& report);
  // The same, waited for: throws RunFailure if the half-step state is
  // invalid; returns the candidate of t^{n+1} over every rank.
  StepLimit advance(double dt, long step);
  // The smallest candidate over every rank's owned cells, located by global
  // cell id (collective), of one this rank's kernels left.
  StepLimit overAllRanks(StepLimit limit) const;
  // Puts back the state of the start of the last step (the last good state).
  void restoreStartOfStep();
  // Copies the current state as the start of a step (in a kernel of its own;
  // a step's first stage keeps its own as it goes, StepStartSave).
  void saveStartOfStep();
  // The remap follows every step and computes the geometry and closure again
  // on its target mesh: the last stage of a step then computes only what the
  // remap reads (StageEnd::ForRemap), and advance() returns no time-step
  // candidate, only a failure (a negative value) where the state is invalid.
  // Every step then starts on the target, the nodes' present positions,
  // which State::x_n0 keeps from here on (the remap's target too, RemapStep):
  // a step's start leaves it.
  void remapFollowsEveryStep();
  // ALE mode: whether a remap follows the next step (its last stage then
  // computes only what the remap reads, as above); the nodes start each step
  // where the last one left them, which the first stage keeps in x_n0.
  void remapFollowsNextStep(bool follows) { remap_follows_ = follows; }

 private:
  // Corner terms, nodal solve, then cell update and geometry at the new
  // positions (StageEnd::ForRemap for the last stage of a step that the remap
  // follows); this rank's bound on the next dt left in `report` (the
  // predictor's or the step's end), the last stage's boundary power too. The
  // first stage keeps the state it starts from (StepStartSave).
  void stage(double dt_stage, bool first_stage, bool last_stage, const StepReport& report);
  // The reconstruction's order and the node gather, as the corner terms and
  // the node solve read them.
  CornerControls cornerControls() const { return {numerics_.order, numerics_.gather}; }
  // The stage's phases, each under its timer:
  // 1. corner forces and matrices of the present state (`save_cells`: and
  //    its cells' step start kept);
  void computeCorners(bool save_cells);
  // 2. node velocities and the new node positions (`save_nodes`: from x_n,
  //    which x_n0 keeps), the boundary's power summed into `power` if given;
  void solveNodesAndMove(double dt_stage, bool save_nodes, const BoundaryPowerView& power);
  // 3. ghost nodes from their owners (a decomposed run);
  void completeGhostNodes(double dt_stage);
  // 4. cell velocities, energies, materials and geometry at the new positions,
  //    with this rank's time-step candidate;
  void updateCells(double dt_stage, StageEnd what, const StepLimitView& into);
  // 5. the outer ghost layer's cells from their owners (a decomposed run).
  void completeOuterGhostCells(StageEnd what);

  Mesh& mesh_;
  State& state_;
  Numerics numerics_;
  PhaseTimers& timers_;
  const Halo* halo_;
  bool remap_follows_ = false;
  bool nodes_start_on_target_ = false;  // remap mode: x_n0 holds the remap's target
  // Bit k: material k has strength, a deviator to keep (State::materials).
  unsigned solid_materials_ = 0;
  // Where advance() and computeGeometry() wait for their candidates.
  StepReport own_report_;
  // The halo's lists (src/fields.hpp), made once: the Views they name are
  // the state's for the whole run.
  std::vector<FieldRef> node_fields_, stage_end_fields_, stage_end_fields_for_remap_;
};

}  // namespace lagremap
