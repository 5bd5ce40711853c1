// The run's ranks (docs/method.md §7.5): MPI_COMM_WORLD when MPI is initialised (the
// lagremap executable and the MPI tests), a single rank otherwise (unit tests
// that build a mesh directly). Collective reductions of the time loop: dt and
// its location, totals, probes; every rank returns the same value.
#pragma once

#include <cstdint>
#include <ostream>
#include <stdexcept>
#include <string>
#include <vector>

#include "kernels/time_step.hpp"

namespace lagremap::parallel {

int rank();
int size();
inline bool isRoot() {
  return rank() == 0;
}

// In-place sums over the ranks of n doubles (totals, boundary work, probes).
void sum(double* values, int n);
// In-place sums over the ranks of n 64-bit integers (ExactSum's digits).
void sum(std::int64_t* values, int n);
// In-place sums modulo 2^64 over the ranks of n unsigned words (checksums).
void sum(std::uint64_t* values, int n);
double sum(double value);
double min(double value);
double max(double value);
// Collective reductions (sum, min, max, minLoc, any) this process has taken
// part in on more than one rank: the latency-bound part of a step
// (summary.json, the scaling model of docs/performance.md).
long reductionCount();
// Smallest time-step candidate over the ranks; ties go to the lowest location.
// `loc` must already be global (cell global id * kLimitCodes + code).
StepLimit minLoc(StepLimit limit);
// Logical or of a per-rank condition (e.g. "this rank failed to read its part").
bool any(bool condition);
// Rank 0's string on every rank.
std::string broadcast(const std::string& text);
// The message of the lowest rank whose `message` is not empty, on every rank
// ("" if none): an error found by one rank becomes every rank's error.
std::string firstMessage(const std::string& message);
void barrier();
// An error every rank throws with the same message (after firstMessage):
// reported once, by rank 0.
struct AgreedError : std::runtime_error {
  using std::runtime_error::runtime_error;
};
// A number addressed by a key (a global id), for deliver().
struct KeyedValue {
  long key = 0;
  double value = 0.0;
};
// Sends items[i] to rank to[i]; returns what this rank receives, in rank
// order (collective; one rank: the items themselves).
std::vector<KeyedValue> deliver(const std::vector<KeyedValue>& items, const std::vector<int>& to);
// Every rank's `values`, one after the other in rank order, on every rank
// (collective; one rank: `values`). For the few cells a check reads along a
// line, never for a field.
std::vector<double> gatherOnAll(const std::vector<double>& values);
// Writes every rank's `text` to `out` on rank 0, in rank order, one rank's
// at a time (rank 0 never holds more than one rank's text); `out` is only
// read on rank 0. Collective.
void writeOnRoot(const std::string& text, std::ostream* out);
// A line of text with its place in a file (a global cell id).
struct KeyedLine {
  long key = 0;
  std::string text;  // without its newline
};
// Writes every rank's lines to `out` on rank 0, one line each, in the order
// of their keys over all ranks; each rank's `lines` must be in key order.
// Rank 0 merges them as it writes, taking each rank's lines in pieces of
// about kMergePieceBytes when it needs them: it never holds more than a piece
// per rank (a layer of cells written in cell order from any rank count).
// Collective; `out` is only read on rank 0.
void writeMergedOnRoot(const std::vector<KeyedLine>& lines, std::ostream* out);
constexpr std::size_t kMergePieceBytes = 16384;
// How many of the run's ranks share this machine's memory (1 on one rank).
int ranksOnThisMachine();

// The smallest, mean and largest of a per-rank value over the ranks.
struct Spread {
  double min = 0.0, mean = 0.0, max = 0.0;
};
Spread spread(double value);

// While alive, this process runs as a single rank (size() == 1, no MPI
// calls): the MPI tests compute single-rank references next to their
// decomposed runs. Not for use while a decomposed run is under way.
class SerialScope {
 public:
  SerialScope();
  ~SerialScope();
  SerialScope(const SerialScope&) = delete;
  SerialScope& operator=(const SerialScope&) = delete;
};

// MPI_Init for the executable (threads: funneled; Kokkos threads never call MPI)
// and MPI_Finalize at scope exit.
class Session {
 public:
  Session(int& argc, char**& argv);
  ~Session();
  Session(const Session&) = delete;
  Session& operator=(const Session&) = delete;
};

}  // namespace lagremap::parallel
