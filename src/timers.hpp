// Phase timers and profiling regions (CONTRIBUTING.md style 7-8): each
// phase of the step is a Kokkos Tools region `lagremap::<phase>` and
// accumulates wall time. Timing a phase fences the execution space at its
// start and its end, so the time is the phase's own even on asynchronous
// backends (work launched before it is not counted, its own kernels are).
#pragma once

#include <array>
#include <string>

#include <Kokkos_Core.hpp>

namespace lagremap {

enum class Phase : int {
  Geometry,
  Corners,
  NodalSolve,
  CellUpdate,
  Remap,
  Relaxation,
  Halo,
  Diagnostics,
  Output,
  Count
};

inline const char* phaseName(Phase phase) {
  static const char* names[] = {"geometry",   "corners", "nodal_solve", "cell_update", "remap",
                                "relaxation", "halo",    "diagnostics", "output"};
  return names[int(phase)];
}

class PhaseTimers {
 public:
  class Scope {
   public:
    Scope(PhaseTimers& timers, Phase phase) : timers_(timers), phase_(phase) {
      Kokkos::Profiling::pushRegion(std::string("lagremap::") + phaseName(phase));
      Kokkos::fence();
      timer_.reset();
    }
    ~Scope() {
      Kokkos::fence();
      timers_.seconds_[int(phase_)] += timer_.seconds();
      Kokkos::Profiling::popRegion();
    }
    Scope(const Scope&) = delete;
    Scope& operator=(const Scope&) = delete;

   private:
    PhaseTimers& timers_;
    Phase phase_;
    Kokkos::Timer timer_;
  };

  Scope scope(Phase phase) { return Scope(*this, phase); }
  double seconds(Phase phase) const { return seconds_[int(phase)]; }

 private:
  std::array<double, int(Phase::Count)> seconds_{};
};

}  // namespace lagremap
