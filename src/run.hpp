// A run: set-up (src/setup.hpp), the time loop (src/simulation.hpp) with its
// outputs (src/outputs.hpp), the problem's checks and summary.json.
// Everything main() does, callable from tests.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "input/config.hpp"
#include "kokkos_events.hpp"
#include "mixed_cells.hpp"
#include "problem.hpp"
#include "resources.hpp"
#include "setup.hpp"

namespace lagremap {

struct RunOptions {
  std::string problem;
  std::string mode = "lagrange";
  Config config;  // fully resolved keys (see makeConfig)
  std::string output_dir;
  std::vector<double> output_times;  // snapshot times (besides the first and last state)
  long output_every = 0;             // snapshot every N steps (0: never)
  bool quiet = false;                // no progress line
  bool profile_phases = false;       // the phase timers fence (src/timers.hpp)
  bool write_files = true;           // false: no output directory at all (benchmarks, tests)
  long checkpoint_every = 0;         // checkpoint.h5 in the output directory every N steps
  std::string restart_file;          // continue the run of this checkpoint
  // A decomposed run's RunResult::fields: the whole block's on every rank
  // (tests compare them with one rank's), not each rank's own.
  bool gather_final_fields = false;
};

// Sharpness of material k's interface in the final state: mixed cells (0.01
// < alpha < 0.99), the area of the alpha = 1/2 surface (interior faces
// across which alpha crosses 1/2), and the smeared width sum 4 alpha (1 -
// alpha) v / area (one cell at alpha = 1/2 per cell of interface gives the
// cell size). Exact sums: the same bits on any rank count.
struct InterfaceMeasure {
  long mixed_cells = 0;
  double area = 0.0, smeared_width = 0.0;
};

struct RunResult {
  long steps = 0;
  double time = 0.0;
  double wall_seconds = 0.0;
  long cells = 0;
  double cell_steps_per_second = 0.0;
  bool failed = false;
  std::string failure;
  int stopped_by = 0;  // the signal that stopped it (Simulation::stoppedBy), 0 for none
  std::vector<Check> checks;
  std::optional<L1Errors> l1_errors;  // against the exact solution, where the problem has one
  double drift_mass = 0.0, drift_momentum = 0.0, drift_energy = 0.0;
  double max_transverse_velocity = 0.0;
  FinalFields fields;                        // host copies of the final (or last good) state
  std::vector<InterfaceMeasure> interfaces;  // per material (multi-material runs)
  // Remap runs with several materials: the state of the mixed cells (the
  // mixed_cells check where a material is condensed).
  std::optional<MixedCellReport> mixed_cells;
  RankCosts costs;  // memory, set-up time and halo traffic over the ranks
  // What the steps asked of the device (src/kokkos_events.hpp); counted:
  // the program's counter saw them (no other Kokkos tool took its place).
  StepEvents step_events;
  bool events_counted = false;
  bool checksPass() const;
};

class Simulation;
// Memory, set-up time and halo traffic of every rank over the ranks, after
// `steps_run` steps of `simulation` (collective).
RankCosts costsOverRanks(const Simulation& simulation, long steps_run);

// Runs a problem. Bad configuration throws ConfigError (exit code 2); a failure
// mid-way is returned in RunResult::failed after the last good state is written.
RunResult runProblem(const RunOptions& options);

}  // namespace lagremap
