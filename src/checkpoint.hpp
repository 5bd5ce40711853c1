// Checkpoint and restart (docs/method.md §7.5): one HDF5 file holding the evolved state
// of every cell and node by global id, and the time loop's counters, written
// collectively by all ranks. The derived fields (geometry, pressures, sound
// speeds) are recomputed on restart from the evolved ones by the same kernel,
// so a restart continues the run bit for bit, on any rank count.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "data/mesh.hpp"
#include "data/state.hpp"
#include "diagnostics.hpp"

namespace lagremap {

// Everything of the time loop besides the fields.
struct LoopState {
  std::string problem, mode;
  // The run's keys a restart must keep, "key=value" lines (restartKeys); a
  // checkpoint of an older format has none.
  std::string keys;
  double time = 0.0, dt_prev = 0.0;
  double dt_stable_max = 0.0;  // largest stable dt so far (Numerics::dt_drop_fraction)
  // Lowest mesh quality so far, the smallest scaled Jacobian of any step
  // (kernels/mesh_quality.hpp).
  double lowest_mesh_quality = 1.0;
  long step = 0;
  Vec3 impulse{0, 0, 0};  // boundary impulse and work so far (conservation audit)
  double work = 0.0, mass_in = 0.0;
  Totals initial;                      // totals of the initial state
  std::vector<double> snapshot_times;  // of the snapshots already in the output directory
  std::vector<std::pair<double, double>> probe;
};

// Writes `path` atomically: a temporary file, then a rename once every rank
// has closed it, so a crash mid-write leaves the previous checkpoint intact.
// Collective. Throws std::runtime_error on an I/O failure.
void writeCheckpoint(const std::string& path, const Mesh& mesh, const State& state,
                     const LoopState& loop);

// Reads this rank's cells and nodes (owned and ghosts) of the checkpoint into
// the state and the mesh's node positions and returns the loop state.
// Collective. Throws std::runtime_error naming the file for a missing,
// truncated or corrupted file, or one of another problem, mode or mesh, or
// written with other `keys` ("key=value" lines; "" compares none).
LoopState readCheckpoint(const std::string& path, Mesh& mesh, State& state,
                         const std::string& problem, const std::string& mode,
                         const std::string& keys = "");

}  // namespace lagremap
