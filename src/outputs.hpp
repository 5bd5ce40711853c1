// Outputs of a run as observers of the time loop (src/simulation.hpp):
// history.csv, HDF5 + XDMF snapshots, checkpoints and the progress line. Rank
// 0 writes the text files; snapshots and checkpoints are collective.
#pragma once

#include <chrono>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include "io/snapshot_writer.hpp"
#include "simulation.hpp"

namespace lagremap {

// Host copies of the fields of this rank's mesh, or with `gather` (a
// decomposed run) of the whole block: every rank's owned rows, and the
// connectivity in global node ids, on every rank.
FinalFields copyFields(const Mesh& mesh, bool gather, const State& state, double time);

// Every material's normal stress across its interface in every cell of the
// current state (interfaceNormalStress), for the mixed_cells check.
MatRealView interfaceNormalStresses(const State& state);

// Writes `text` to `path` whole, or throws naming the file and why (a
// directory standing there, a full disk or no inodes left): a result file is
// never silently missing or cut.
void writeTextFile(const std::string& path, const std::string& text);

// history.csv: the totals and the mesh quality (the smallest scaled Jacobian,
// kernels/mesh_quality.hpp) of every step, after the initial state's line. A
// restart keeps the lines of the steps it does not redo. Creates the output
// directory; a directory or file that cannot be written is ConfigError
// (collective: every rank throws rank 0's message). Each line goes to disk
// with its step, so a run killed or stopped by a full disk leaves the lines
// of its steps so far; a line the disk cannot take is cut off, the file
// ends with the last whole line, and the run fails at its end.
class HistoryFile : public LoopObserver {
 public:
  HistoryFile(const RunOptions& options, const Simulation& simulation);
  void start(const Simulation& simulation) override;
  void afterStep(const Simulation& simulation, const TimeStepChoice& choice) override;
  // Throws (every rank) if a line could not be written.
  void finish(const Simulation& simulation) override;

 private:
  void writeLine(long step, double t, double dt, const char* reason, const Totals& totals,
                 double mesh_quality);
  // Sends what the stream holds to disk; on failure cuts the file back to
  // its last whole line and stops writing.
  void flush();
  std::string path_;
  std::ofstream file_;
  std::streamoff written_ = 0;  // bytes on disk, whole lines
  std::string error_;
};

// Snapshots: the initial state, each requested output time, every
// `--output-every` steps, and the final (or last good) state.
class SnapshotOutput : public LoopObserver {
 public:
  SnapshotOutput(const RunOptions& options, const Simulation& simulation);
  void start(const Simulation& simulation) override;
  void afterStep(const Simulation& simulation, const TimeStepChoice& choice) override;
  void finish(const Simulation& simulation) override;
  std::vector<double> times() const { return series_.times(); }

 private:
  void write(const Simulation& simulation);
  io::SnapshotSeries series_;
  long every_ = 0;
};

// checkpoint.h5 every `--checkpoint-every` steps and when a run fails (its
// last good state, to restart from); replaced atomically.
class CheckpointOutput : public LoopObserver {
 public:
  CheckpointOutput(const RunOptions& options, const SnapshotOutput& snapshots);
  void afterStep(const Simulation& simulation, const TimeStepChoice& choice) override;
  void finish(const Simulation& simulation) override;

 private:
  void write(const Simulation& simulation);
  std::string path_;
  long every_ = 0;
  const SnapshotOutput& snapshots_;
};

// A progress line on stderr at most every 3 s (rank 0): percentage, step,
// time, dt and its reason, and the time left.
class ProgressLine : public LoopObserver {
 public:
  void start(const Simulation& simulation) override;
  void afterStep(const Simulation& simulation, const TimeStepChoice& choice) override;

 private:
  std::chrono::steady_clock::time_point start_, last_;
};

}  // namespace lagremap
