// Pieces shared by the Google Benchmark drivers of perf/.
#pragma once

#include <benchmark/benchmark.h>

#include <Kokkos_Core.hpp>
#include <cstdlib>
#include <cstring>
#include <stdexcept>

#include "src/kokkos_events.hpp"
#include "src/lagrange_step.hpp"

namespace lagremap::bench {

// Whole steps run from the warm snapshot before it is put back (untimed), so
// the timed steps never drift far from the developed state.
constexpr long kStepsBetweenRestores = 50;

// The time loop of run.cpp (initial dt factor, growth limit), no outputs, for
// `steps` steps from the current state; returns the time advanced and leaves
// the next step's dt candidate in `limit`.
inline double warmUp(LagrangeStep& lagrange, const Numerics& numerics, long steps,
                     StepLimit& limit) {
  limit = lagrange.computeGeometry();
  if (limit.val < 0.0) throw std::runtime_error(describeInvalidCell(limit, 0, "set-up"));
  double time = 0.0, dt_prev = 0.0;
  for (long step = 0; step < steps; ++step) {
    double dt = limit.val;
    if (step == 0) {
      dt *= numerics.dt_initial_factor;
    } else if (numerics.dt_growth * dt_prev < dt) {
      dt = numerics.dt_growth * dt_prev;
    }
    limit = lagrange.advance(dt, step + 1);
    if (limit.val < 0.0) {
      throw std::runtime_error(describeInvalidCell(limit, step + 1, "warm-up"));
    }
    time += dt;
    dt_prev = dt;
  }
  return time;
}

// The Kokkos events of a benchmark's steps as its counters, per step.
inline void setEventCounters(benchmark::State& state, const StepEvents& events) {
  const double per_step = events.steps > 0 ? 1.0 / double(events.steps) : 0.0;
  state.counters["launches"] = double(events.total.launches) * per_step;
  state.counters["deep_copies"] = double(events.total.deep_copies) * per_step;
  state.counters["host_syncs"] = double(events.total.host_syncs) * per_step;
}

// One whole step per iteration as the driver takes it: advance(dt) at the
// benchmark's fixed dt, whose last sweep also gives the next step's geometry
// and dt candidates. `Warm` has restore(), mesh(), state(), timers(),
// numerics() and dtBench().
template <class Warm>
void timedFullSteps(benchmark::State& state, Warm& b, int order) {
  b.restore();
  Numerics numerics = b.numerics();
  numerics.order = order;
  LagrangeStep lagrange(b.mesh(), b.state(), numerics, b.timers());
  const double dt = b.dtBench();
  StepLimit limit = lagrange.computeGeometry();
  StepEvents events;
  long step = 0;
  for (auto _ : state) {
    if (step > 0 && step % kStepsBetweenRestores == 0) {  // untimed
      b.restore();
      limit = lagrange.computeGeometry();
    }
    ++step;
    if (limit.val < dt) {
      state.SkipWithError("the fixed benchmark dt exceeds the stable dt");
      break;
    }
    const KokkosEventCounts before = kokkosEventCounts();
    Kokkos::Timer timer;
    try {
      limit = lagrange.advance(dt, step);
    } catch (const RunFailure& failure) {
      state.SkipWithError(failure.what());
      break;
    }
    Kokkos::fence();
    state.SetIterationTime(timer.seconds());
    events.add(kokkosEventCounts() - before);
  }
  setEventCounters(state, events);
}

// Removes `<prefix>N` (e.g. "--n=") from argv before benchmark::Initialize
// sees it; returns N, 0 if absent.
inline long takeFlag(int& argc, char* argv[], const char* prefix) {
  const std::size_t length = std::strlen(prefix);
  long value = 0;
  int kept = 1;
  for (int i = 1; i < argc; ++i) {
    if (std::strncmp(argv[i], prefix, length) == 0) {
      value = std::atol(argv[i] + length);
    } else {
      argv[kept++] = argv[i];
    }
  }
  argc = kept;
  argv[argc] = nullptr;
  return value;
}

}  // namespace lagremap::bench
