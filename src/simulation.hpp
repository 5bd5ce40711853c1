// The time loop of the paper's Fig. 2 (docs/method.md §A5, §A9): each step is the
// Lagrangian phase (predictor, corrector), then in remap mode the remap onto
// the initial mesh (densities, gradients, swept regions, fluxes, energy fix),
// then the diagnostics (conservation audit, probe). Outputs (history,
// snapshots, checkpoints, progress) are observers of the loop
// (src/outputs.hpp); set-up is src/setup.hpp.
#pragma once

#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "checkpoint.hpp"
#include "kokkos_events.hpp"
#include "lagrange_step.hpp"
#include "mesh_relaxation.hpp"
#include "problem.hpp"
#include "remap_step.hpp"
#include "run.hpp"
#include "step_report.hpp"
#include "timers.hpp"

namespace lagremap {

// The time step a step takes and what limited it ("cfl", "volume",
// "initial", "growth", "output", "end").
struct TimeStepChoice {
  double dt = 0.0;
  const char* reason = "";
  bool lands_on_output() const;
  bool lands_on_end() const;
};

class Simulation;

// Something that follows the loop: told once before the first step (of a
// fresh run or a restart), after every step, and once at the end (the run
// completed or failed; the state is then the last good one). Observers are
// told in the order they were added, and at the end in the reverse order.
class LoopObserver {
 public:
  virtual ~LoopObserver() = default;
  virtual void start(const Simulation&) {}
  virtual void afterStep(const Simulation&, const TimeStepChoice&) {}
  virtual void finish(const Simulation&) {}
};

class Simulation {
 public:
  // Set-up: the problem's mesh and initial state (this rank's part of it),
  // the Lagrangian and remap steps, and the state of a checkpoint to restart
  // from. Bad input throws ConfigError.
  Simulation(const RunOptions& options, const Problem& problem);

  void observe(LoopObserver& observer) { observers_.push_back(&observer); }

  // Steps to t_end, or until a step fails (failed()); then tells the observers.
  void run();

  // --- what the observers and the report read
  const RunOptions& options() const { return options_; }
  const Problem& problem() const { return problem_; }
  const Mesh& mesh() const { return setup_.mesh; }
  const State& state() const { return state_; }
  const std::vector<MaterialParams>& materials() const { return setup_.materials; }
  const Numerics& numerics() const { return numerics_; }
  PhaseTimers& timers() const { return timers_; }
  double time() const { return loop_.time; }
  long step() const { return loop_.step; }
  double tEnd() const { return t_end_; }
  bool restarted() const { return restarted_; }
  // The loop's counters and audit, as a checkpoint stores them.
  const LoopState& loopState() const { return loop_; }
  const LoopState& startState() const { return start_; }  // at the first step of this process
  const Totals& totals() const { return totals_; }
  // The smallest scaled Jacobian of the present mesh's cells
  // (kernels/mesh_quality.hpp); the run's lowest is loopState()'s.
  double meshQuality() const { return mesh_quality_; }
  bool failed() const { return !failure_.empty(); }
  const std::string& failure() const { return failure_; }
  // The signal that stopped the run at the end of a step (installStopSignals),
  // 0 for none; such a run has failed() too, its reason the signal.
  int stoppedBy() const { return stopped_by_; }
  double wallSeconds() const { return wall_seconds_; }
  // This rank's set-up: wall time per phase, and its peak memory at the end.
  const SetupSeconds& setupSeconds() const { return setup_seconds_; }
  long setupPeakBytes() const { return setup_peak_bytes_; }
  const Halo* halo() const { return halo_.get(); }  // null on one rank
  // Collective reductions the time loop took (parallel::reductionCount), and
  // what its steps (this process's, outputs aside) asked of the device.
  long loopReductions() const { return loop_reductions_; }
  const StepEvents& stepEvents() const { return step_events_; }
  // Relative drifts of mass, momentum and total energy, less what came in.
  double driftMass() const;
  double driftMomentum() const;
  double driftEnergy() const;

 private:
  // dt = min(stable dt, growth * dt_prev, next output time, t_end) (docs/method.md §A6).
  TimeStepChoice chooseTimeStep() const;
  // Why the loop cannot take this step ("" if it can): step limit, dt collapse.
  bool stopAsked();
  std::string stopReason(const TimeStepChoice& choice) const;
  // Throws ConfigError when a fresh run's first step is below numerics.dt_min.
  void refuseAFirstStepBelowTheFloor() const;
  // One step of Fig. 2, launched, then waited for once; RunFailure: the caller
  // restores the start. checkedStepLimit: its dt candidate over every rank
  // (an invalid state throws, the remap's part of the state restored).
  void advance(const TimeStepChoice& choice);
  StepLimit checkedStepLimit(long step, bool remapped);
  // The diagnostics' reductions into the report, then read: boundary work,
  // totals, mesh quality, probe (`remapped`: the step ended with a remap).
  void launchDiagnostics(bool remapped);
  void diagnose(double dt, bool remapped);
  // The smallest scaled Jacobian of the present mesh (every rank's cells);
  // its record as the present and the run's lowest.
  double measuredMeshQuality() const;
  void noteMeshQuality(double quality);
  double energyScale() const;  // of the drifts

  const RunOptions& options_;
  const Problem& problem_;
  Numerics numerics_;
  double t_end_ = 0.0;
  ProblemSetup setup_;
  std::unique_ptr<Halo> halo_;
  State state_;
  mutable PhaseTimers timers_;
  std::unique_ptr<LagrangeStep> lagrange_;
  std::unique_ptr<RemapStep> remap_;
  std::unique_ptr<MeshRelaxation> relaxation_;  // ALE mode
  StepLimit limit_;                             // the next step's stable time step
  LoopState loop_, start_;
  bool restarted_ = false;
  SetupSeconds setup_seconds_;
  long setup_peak_bytes_ = 0;
  long loop_reductions_ = 0;
  mutable StepReport report_;  // what a step's kernels leave for the host
  StepEvents step_events_;
  std::vector<double> pending_outputs_;  // snapshot times still ahead, sorted, each once
  Totals totals_;
  double mesh_quality_ = 1.0;
  std::string failure_;
  int stopped_by_ = 0;
  double wall_seconds_ = 0.0;
  std::vector<LoopObserver*> observers_;
};

}  // namespace lagremap
