// What a run asks of the device (docs/performance.md §8): kernel launches,
// deep copies and host synchronisations, counted by Kokkos Tools callbacks
// the program registers itself, on any back-end. On a GPU each launch costs
// some microseconds and each synchronisation idles the device, so these
// counts, not the CPU's wall time, say whether a small problem's step can be
// fast there.
//
// A host synchronisation is a point where the host waits for the device with
// work outstanding: a fence, or a deep copy (which fences), after at least
// one launch or copy since the last one. A second fence with nothing launched
// between costs nothing and is not counted. Kokkos 4 reports every fence it
// makes (those of deep copies and of reductions into a host value included);
// Kokkos 3.4 reports none, so lagremap's own fences go through fenceFor()
// (data/fence.hpp), which reports them on either, and the step makes no reduction into a host
// value (its reductions write the step report: src/step_report.hpp).
#pragma once

#include <cstdint>

#include "data/fence.hpp"

namespace lagremap {

struct KokkosEventCounts {
  long launches = 0;     // parallel_for, parallel_reduce, parallel_scan
  long deep_copies = 0;  // Kokkos::deep_copy calls (fills by a value included)
  long copied_bytes = 0;
  long host_syncs = 0;

  KokkosEventCounts operator-(const KokkosEventCounts& earlier) const {
    return {launches - earlier.launches, deep_copies - earlier.deep_copies,
            copied_bytes - earlier.copied_bytes, host_syncs - earlier.host_syncs};
  }
};

// The counts of a run's steps: their sum and each count's largest in a step.
struct StepEvents {
  long steps = 0;
  KokkosEventCounts total, most;

  void add(const KokkosEventCounts& step);
};

// Registers the counter's callbacks. Called before Kokkos::initialize (so
// that Kokkos asks the counter's tool settings: no global fences around
// each callback); a tool library the user loads (KOKKOS_TOOLS_LIBS) takes
// the callbacks' places instead, and kokkosEventsCounted() then says false.
void installKokkosEventCounter();

// Whether the counter's callbacks are the ones Kokkos calls.
bool kokkosEventsCounted();

// The counts since installKokkosEventCounter().
KokkosEventCounts kokkosEventCounts();

}  // namespace lagremap
