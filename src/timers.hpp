// Phase timers and profiling regions (CONTRIBUTING.md style 7-8): each
// phase of the step is a Kokkos Tools region `lagremap::<phase>` and
// accumulates wall time. Asked to (--profile-phases), timing a phase fences
// the execution space at its start and its end, so the time is the phase's
// own even on asynchronous backends (work launched before it is not
// counted, its own kernels are); otherwise it does not wait, and a GPU's
// phase times are those of the launches (a host back-end's kernels finish
// before their launch returns: its times are the phases' own either way).
#pragma once

#include <array>
#include <string>

#include <Kokkos_Core.hpp>

#include "kokkos_events.hpp"

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
      if (timers_.fence_) fenceFor("lagremap::timers: a phase's start");
      timer_.reset();
    }
    ~Scope() {
      if (timers_.fence_) fenceFor("lagremap::timers: a phase's end");
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
  // Whether each phase waits for the device at its ends (--profile-phases).
  void fenceEachPhase(bool fence) { fence_ = fence; }
  bool fencesEachPhase() const { return fence_; }

 private:
  std::array<double, int(Phase::Count)> seconds_{};
  bool fence_ = false;
};

}  // namespace lagremap
