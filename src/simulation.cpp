#include "simulation.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>

#include "diagnostics.hpp"
#include "kernels/mesh_quality.hpp"
#include "kokkos_events.hpp"
#include "parallel.hpp"
#include "setup.hpp"
#include "stop_signals.hpp"

namespace lagremap {

bool TimeStepChoice::lands_on_output() const {
  return std::strcmp(reason, "output") == 0;
}
bool TimeStepChoice::lands_on_end() const {
  return std::strcmp(reason, "end") == 0;
}

namespace {

// The keys a restart keeps, "key=value" lines: all but those of the loop's
// end and numerics (t_end, numerics.*: a restart may run on further, or past
// a difficulty with a smaller CFL) and of the final checks (check.*).
std::string restartKeys(const Config& config) {
  std::string keys;
  for (const auto& [key, param] : config.params()) {
    if (key == "t_end" || key.rfind("numerics.", 0) == 0 || key.rfind("check.", 0) == 0) continue;
    keys += key + "=" + param.value + "\n";
  }
  return keys;
}

const char* limitReason(const StepLimit& limit) {
  return limit.loc % kLimitCodes == kLimitVolume ? "volume" : "cfl";
}

std::string shortNumber(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3g", value);
  return text;
}

// The snapshot times after `now`, sorted, each once: a time less than
// `resolution` (the run's dt_min) after the one before it, or after `now`,
// is that one's snapshot. The step to it would be shorter than dt_min, and
// the growth limit would hold the step after it below dt_min too: a time
// given twice would stop the run with a time step collapse.
std::vector<double> snapshotTimesAhead(std::vector<double> times, double now, double resolution) {
  std::sort(times.begin(), times.end());
  std::vector<double> ahead;
  for (double t : times) {
    const double last = ahead.empty() ? now : ahead.back();
    if (t > last && t - last >= resolution) ahead.push_back(t);
  }
  return ahead;
}

}  // namespace

Simulation::Simulation(const RunOptions& options, const Problem& problem)
    : options_(options),
      problem_(problem),
      numerics_(readNumerics(options.config)),
      t_end_(options.config.real("t_end")) {
  const Config& config = options.config;
  timers_.fenceEachPhase(options.profile_phases);
  checkMemoryFits(config);
  Kokkos::Timer phase;
  // (each rank builds its own part: an error in one is every rank's)
  collectively([&] { setup_ = setUpProblem(problem, config, options.problem); });
  setup_seconds_.generate = phase.seconds() - setup_.sample_seconds;
  setup_seconds_.sample_materials = setup_.sample_seconds;
  phase.reset();
  // decomposition (docs/method.md §7.5): the generator built this rank's part of the
  // block (its cells, their ghosts and nodes); the halo links it to the others
  if (parallel::size() > 1) halo_ = std::make_unique<Halo>(makeHalo(setup_.mesh));
  setup_seconds_.decompose = phase.seconds();
  phase.reset();
  Mesh& mesh = setup_.mesh;
  // (in remap and ALE modes the remap step gives the corner arrays their memory)
  state_ = allocateState(mesh, numerics_.gather == Gather::Atomics, !config.remaps());
  collectively([&] { initializeState(setup_, state_); });
  setup_.cells = InitialCells();  // uploaded: its host copy goes (72 bytes a cell of taylor)

  lagrange_ = std::make_unique<LagrangeStep>(mesh, state_, numerics_, timers_, halo_.get());
  if (config.remaps()) {
    RemapControls controls = readRemapControls(config, state_);
    controls.kernels = numerics_.kernels;
    remap_ = makeRemapStep(mesh, state_, controls, timers_, halo_.get(), options.problem);
  }
  if (config.aleMode()) {  // (before a restart moves the nodes: the initial mesh)
    relaxation_ = std::make_unique<MeshRelaxation>(
        mesh, readRelaxationControls(config), config.integer("ale.every"), timers_, halo_.get());
  } else if (remap_) {
    lagrange_->remapFollowsEveryStep();
  }
  limit_ = lagrange_->computeGeometry();
  if (limit_.val < 0.0) {
    throw ConfigError("initial state is invalid: " + describeInvalidCell(limit_, 0, "set-up"));
  }

  // restart (docs/method.md §7.5): the evolved state and the loop's counters of a
  // checkpoint; the derived fields follow from the same geometry kernel.
  loop_.problem = options.problem;
  loop_.mode = options.mode;
  loop_.keys = restartKeys(options.config);
  restarted_ = !options.restart_file.empty();
  if (restarted_) {
    const std::string keys = loop_.keys;
    collectively([&] {
      loop_ =
          readCheckpoint(options.restart_file, mesh, state_, options.problem, options.mode, keys);
    });
    loop_.keys = keys;
    if (!(loop_.time < t_end_)) {
      throw ConfigError("checkpoint '" + options.restart_file +
                        "' is at t = " + std::to_string(loop_.time) + ", not before t_end");
    }
    limit_ = lagrange_->computeGeometry();
    if (limit_.val < 0.0) {
      throw ConfigError("checkpoint '" + options.restart_file + "' holds an invalid state: " +
                        describeInvalidCell(limit_, loop_.step, "restart"));
    }
  } else {
    if (problem.probe) loop_.probe.emplace_back(0.0, problem.probe.measure(mesh, state_));
    loop_.initial = computeTotals(mesh, state_);
  }
  totals_ = loop_.initial;
  noteMeshQuality(measuredMeshQuality());
  start_ = loop_;
  pending_outputs_ = snapshotTimesAhead(options.output_times, loop_.time, numerics_.dt_min);
  refuseAFirstStepBelowTheFloor();
  Kokkos::fence();
  setup_seconds_.initialize = phase.seconds();
  setup_peak_bytes_ = peakResidentBytes();
}

void Simulation::run() {
  for (LoopObserver* observer : observers_) observer->start(*this);
  const auto wall_start = std::chrono::steady_clock::now();
  const long reductions_start = parallel::reductionCount();
  while (loop_.time < t_end_) {
    if (stopAsked()) break;
    const TimeStepChoice choice = chooseTimeStep();
    failure_ = stopReason(choice);
    if (failed()) break;
    const KokkosEventCounts before = kokkosEventCounts();
    try {
      advance(choice);
      step_events_.add(kokkosEventCounts() - before);
    } catch (const RunFailure& failure) {
      lagrange_->restoreStartOfStep();
      failure_ = failure.what();
      break;
    }
    for (LoopObserver* observer : observers_) observer->afterStep(*this, choice);
  }
  wall_seconds_ =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  loop_reductions_ = parallel::reductionCount() - reductions_start;
  // in the reverse order (a checkpoint of a failed run lists the snapshots
  // before the final one, which a restart then rewrites)
  for (auto it = observers_.rbegin(); it != observers_.rend(); ++it) (*it)->finish(*this);
}

TimeStepChoice Simulation::chooseTimeStep() const {
  TimeStepChoice choice{limit_.val, limitReason(limit_)};
  if (loop_.step == 0) {
    choice = {choice.dt * numerics_.dt_initial_factor, "initial"};
  } else if (numerics_.dt_growth * loop_.dt_prev < choice.dt) {
    choice = {numerics_.dt_growth * loop_.dt_prev, "growth"};
  }
  if (!pending_outputs_.empty() && loop_.time + choice.dt >= pending_outputs_.front()) {
    choice = {pending_outputs_.front() - loop_.time, "output"};
  }
  if (loop_.time + choice.dt >= t_end_) choice = {t_end_ - loop_.time, "end"};
  return choice;
}

// A first step already below numerics.dt_min would stop the run at once with a
// time step collapse, which is the input's doing: a t_end (1e300 s) longer
// than dt_min_fraction resolves, or a dt_min_fraction too large for t_end;
// after a restart, a floor the checkpoint's state is already below.
void Simulation::refuseAFirstStepBelowTheFloor() const {
  const TimeStepChoice first = chooseTimeStep();
  if (!(first.dt < numerics_.dt_min) || first.lands_on_end() || first.lands_on_output()) return;
  const double fraction = options_.config.real("numerics.dt_min_fraction");
  if (restarted_) {
    throw ConfigError("checkpoint '" + options_.restart_file + "': the first step after it, " +
                      shortNumber(first.dt) + " s, is below numerics.dt_min_fraction x t_end = " +
                      shortNumber(numerics_.dt_min) + " s (dt_min_fraction " +
                      shortNumber(fraction) + ")");
  }
  throw ConfigError(
      "t_end = " + shortNumber(t_end_) + " s: the first step, " + shortNumber(first.dt) +
      " s, is below numerics.dt_min_fraction x t_end = " + shortNumber(numerics_.dt_min) +
      " s; at dt_min_fraction " + shortNumber(fraction) + ", t_end can be at most " +
      shortNumber(first.dt / fraction) + " s");
}

// A stop signal on any rank stops every rank at the end of the same step
// (one reduction a step on several ranks, none on one).
bool Simulation::stopAsked() {
  const int signal = int(parallel::max(double(stopSignal())));
  if (signal == 0) return false;
  stopped_by_ = signal;
  failure_ = "step " + std::to_string(loop_.step) + ": stopped by " + stopSignalName(signal) +
             " at t = " + shortNumber(loop_.time);
  return true;
}

std::string Simulation::stopReason(const TimeStepChoice& choice) const {
  if (loop_.step >= numerics_.max_steps) {
    return "step " + std::to_string(loop_.step) +
           ": numerics.max_steps reached at t = " + std::to_string(loop_.time);
  }
  if (choice.dt < numerics_.dt_min && !choice.lands_on_end() && !choice.lands_on_output()) {
    return "step " + std::to_string(loop_.step + 1) +
           ": time step collapse, dt = " + shortNumber(choice.dt) + " (" + choice.reason +
           " limited, cell " + std::to_string(limit_.loc / kLimitCodes) + ")";
  }
  if (limit_.val < numerics_.dt_drop_fraction * loop_.dt_stable_max) {
    return "step " + std::to_string(loop_.step + 1) +
           ": time step collapse at t = " + shortNumber(loop_.time) + ", stable dt " +
           shortNumber(limit_.val) + " s below " + shortNumber(numerics_.dt_drop_fraction) +
           " of the run's largest, " + shortNumber(loop_.dt_stable_max) + " s (" +
           limitReason(limit_) + " limited, cell " + std::to_string(limit_.loc / kLimitCodes) +
           "; numerics.dt_drop_fraction)";
  }
  return "";
}

void Simulation::advance(const TimeStepChoice& choice) {
  const long next = loop_.step + 1;
  // remap mode remaps after every step; ALE mode every ale.every steps
  const bool remaps = remap_ && (!relaxation_ || relaxation_->due(next));
  if (relaxation_) lagrange_->remapFollowsNextStep(remaps);
  // Lagrangian phase: predictor and corrector (docs/method.md §A5), with the next
  // step's time-step candidates
  lagrange_->launch(choice.dt, report_);
  if (remaps) {
    // remap onto the initial mesh (docs/method.md §A9), or in ALE mode onto the
    // relaxed one (§8): densities, gradients, swept regions, fluxes, energy
    // fix; then the time step of the remapped state
    if (relaxation_) {
      remap_->launch(relaxation_->target(), report_.remap);
    } else {
      remap_->launch(report_.remap);
    }
    lagrange_->computeGeometry(report_.after_remap);
  }
  launchDiagnostics(remaps);
  // The step's one host synchronisation: its kernels have left their time-step
  // candidates, boundary crossings and diagnostics in the report.
  fenceFor("lagremap::step: the step's report");
  limit_ = checkedStepLimit(next, remaps);
  loop_.time = choice.lands_on_end() ? t_end_ : loop_.time + choice.dt;
  loop_.dt_prev = choice.dt;
  // (from the first step on: the set-up's candidate has no volume-rate limit
  // yet, sedov's is 8 times the next one)
  loop_.dt_stable_max = std::max(loop_.dt_stable_max, limit_.val);
  loop_.step = next;
  if (choice.lands_on_output()) {
    loop_.time = pending_outputs_.front();
    pending_outputs_.erase(pending_outputs_.begin());
  }
  diagnose(choice.dt, remaps);
}

StepLimit Simulation::checkedStepLimit(long step, bool remapped) {
  const auto fail = [&](const StepLimit& limit, const char* when) {
    if (remapped) remap_->restoreStartOfStep();  // (the caller restores the rest)
    throw RunFailure(describeInvalidCell(limit, step, when));
  };
  if (numerics_.order == 2) {
    const StepLimit half_step = lagrange_->overAllRanks(report_.predictor());
    if (half_step.val < 0.0) fail(half_step, "predictor");
  }
  const StepLimit end = lagrange_->overAllRanks(report_.end_of_step());
  if (end.val < 0.0) fail(end, "end of step");
  if (!remapped) return end;
  const StepLimit after = lagrange_->overAllRanks(report_.after_remap());
  if (after.val < 0.0) fail(after, "after the remap");
  return after;
}

void Simulation::launchDiagnostics(bool remapped) {
  auto scope = timers_.scope(Phase::Diagnostics);
  // the audit's sums: the boundary's from the step's last nodal solve, the
  // cells' totals from the remap's update where it ran
  if (!remapped) sumTotals(setup_.mesh, state_, report_.totals);
  // (remap mode: the initial mesh again, the quality the set-up measured; ALE
  // mode: the relaxation's guard measured its target)
  if (!remapped) smallestScaledJacobian(setup_.mesh, setup_.mesh.x_n, report_.mesh_quality);
  if (problem_.probe) problem_.probe.sample(setup_.mesh, state_, report_.probe);
}

void Simulation::diagnose(double dt, bool remapped) {
  const RemapAudit remap = remapped ? remapAuditOf(report_.remap) : RemapAudit();
  const Audit audit = auditOf(remapped ? remap.totals : report_.totals(), report_.boundary());
  const BoundaryPower& boundary = audit.boundary;
  RemapBoundaryFlux crossed = remap.crossed;
  if (remapped) parallel::sum(crossed.v, 5);
  loop_.impulse += dt * boundary.force + Vec3{crossed.v[1], crossed.v[2], crossed.v[3]};
  loop_.work += dt * boundary.power + crossed.v[4];
  loop_.mass_in += crossed.v[0];
  totals_ = audit.totals;
  if (remapped && relaxation_) {
    noteMeshQuality(relaxation_->targetQuality());
  } else if (!remapped) {
    noteMeshQuality(parallel::min(meshQualityOf(report_.mesh_quality())));
  }
  if (problem_.probe) {
    loop_.probe.emplace_back(loop_.time, problem_.probe.value(setup_.mesh, state_, report_.probe));
  }
}

double Simulation::measuredMeshQuality() const {
  smallestScaledJacobian(setup_.mesh, setup_.mesh.x_n, report_.mesh_quality);
  fenceFor("lagremap::mesh_quality: the smallest scaled Jacobian");
  return parallel::min(meshQualityOf(report_.mesh_quality()));
}

void Simulation::noteMeshQuality(double quality) {
  mesh_quality_ = quality;
  loop_.lowest_mesh_quality = std::min(loop_.lowest_mesh_quality, quality);
}

// The largest energy the run held or received (a body at rest driven by a
// traction starts with zero energy).
double Simulation::energyScale() const {
  return std::max(
      {std::abs(loop_.initial.total()), std::abs(totals_.total()), std::abs(loop_.work), 1e-300});
}
double Simulation::driftMass() const {
  return std::abs(totals_.mass - loop_.initial.mass - loop_.mass_in) / loop_.initial.mass;
}
double Simulation::driftEnergy() const {
  return std::abs(totals_.total() - loop_.initial.total() - loop_.work) / energyScale();
}
double Simulation::driftMomentum() const {
  const double scale = std::max(std::sqrt(2.0 * loop_.initial.mass * energyScale()), 1e-300);
  return norm(totals_.momentum - loop_.initial.momentum - loop_.impulse) / scale;
}

}  // namespace lagremap
