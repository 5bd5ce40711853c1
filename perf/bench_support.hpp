// Pieces shared by the Google Benchmark drivers of perf/.
#pragma once

#include <benchmark/benchmark.h>

#include <Kokkos_Core.hpp>
#include <cstdlib>
#include <cstring>

#include "src/lagrange_step.hpp"

namespace lagremap::bench {

// Whole steps run from the warm snapshot before it is put back (untimed), so
// the timed steps never drift far from the developed state.
constexpr long kStepsBetweenRestores = 50;

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
    Kokkos::Timer timer;
    try {
      limit = lagrange.advance(dt, step);
    } catch (const RunFailure& failure) {
      state.SkipWithError(failure.what());
      break;
    }
    Kokkos::fence();
    state.SetIterationTime(timer.seconds());
  }
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
