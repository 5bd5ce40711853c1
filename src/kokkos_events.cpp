#include "kokkos_events.hpp"

#include <algorithm>
#include <atomic>

#include <Kokkos_Core.hpp>

namespace lagremap {
namespace {

namespace tools = Kokkos::Tools::Experimental;

// (callbacks arrive from the host thread that launches; atomics keep the
// counts whole if a program ever launches from several)
std::atomic<long> launches{0};
std::atomic<long> deep_copies{0};
std::atomic<long> copied_bytes{0};
std::atomic<long> host_syncs{0};
std::atomic<bool> work_since_sync{false};
std::atomic<uint64_t> next_id{1};

// A synchronisation counts when the device had something to finish.
void noteSynchronisation() {
  if (work_since_sync.exchange(false)) ++host_syncs;
}

void beginKernel(const char*, const uint32_t, uint64_t* id) {
  ++launches;
  work_since_sync = true;
  *id = next_id++;
}
void endKernel(uint64_t) {}

void beginDeepCopy(Kokkos_Profiling_SpaceHandle, const char*, const void*,
                   Kokkos_Profiling_SpaceHandle, const char*, const void*, uint64_t bytes) {
  ++deep_copies;
  copied_bytes += long(bytes);
  work_since_sync = true;
  noteSynchronisation();  // (every global deep_copy fences the execution space)
}
void endDeepCopy() {}

void beginFence(const char*, const uint32_t, uint64_t* id) {
  noteSynchronisation();
  *id = next_id++;
}
void endFence(uint64_t) {}

// The counter needs no fence around its callbacks (Kokkos' default for a
// tool is one before each).
void requestSettings(const uint32_t, Kokkos_Tools_ToolSettings* settings) {
  settings->requires_global_fencing = false;
}

bool isCounterInstalled(const tools::EventSet& events) {
  return events.begin_parallel_for == &beginKernel && events.begin_deep_copy == &beginDeepCopy &&
         events.begin_fence == &beginFence;
}

}  // namespace

void StepEvents::add(const KokkosEventCounts& step) {
  ++steps;
  total.launches += step.launches;
  total.deep_copies += step.deep_copies;
  total.copied_bytes += step.copied_bytes;
  total.host_syncs += step.host_syncs;
  most.launches = std::max(most.launches, step.launches);
  most.deep_copies = std::max(most.deep_copies, step.deep_copies);
  most.copied_bytes = std::max(most.copied_bytes, step.copied_bytes);
  most.host_syncs = std::max(most.host_syncs, step.host_syncs);
}

void installKokkosEventCounter() {
  tools::EventSet events = tools::get_callbacks();
  events.begin_parallel_for = &beginKernel;
  events.end_parallel_for = &endKernel;
  events.begin_parallel_reduce = &beginKernel;
  events.end_parallel_reduce = &endKernel;
  events.begin_parallel_scan = &beginKernel;
  events.end_parallel_scan = &endKernel;
  events.begin_deep_copy = &beginDeepCopy;
  events.end_deep_copy = &endDeepCopy;
  events.begin_fence = &beginFence;
  events.end_fence = &endFence;
  events.request_tool_settings = &requestSettings;
  tools::set_callbacks(events);
}

bool kokkosEventsCounted() {
  return isCounterInstalled(tools::get_callbacks());
}

KokkosEventCounts kokkosEventCounts() {
  return {launches.load(), deep_copies.load(), copied_bytes.load(), host_syncs.load()};
}

}  // namespace lagremap
