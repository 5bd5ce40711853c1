// Time-step candidates of one cell (docs/method.md §A6) and the failure
// codes found while evaluating them. The reduction packs (cell, reason) into
// the location of a Kokkos::MinLoc so one parallel_reduce returns both.
#pragma once

#include "../data/math.hpp"
#include "../data/types.hpp"

namespace lagremap {

enum StepLimitCode : int {
  kLimitCfl = 0,       // C_cfl l_c / aL_c
  kLimitVolume = 1,    // C_vol v_c / |dv_c/dt|
  kBadVolume = 4,      // v_c <= 0 (tangled cell)
  kBadState = 5,       // NaN or infinite mass, energy or velocity
  kBadSoundSpeed = 6,  // a^2 <= 0 (negative internal energy / pressure)
  kBadEos = 7,         // outside the EOS's domain (Mie-Gruneisen: eta - s (eta - 1) <= 0)
};
constexpr int kLimitCodes = 8;

struct TimeStepControls {
  double cfl = 0.4;
  double c_vol = 0.1;
};

using StepLimitReducer = Kokkos::MinLoc<double, int>;
using StepLimit = StepLimitReducer::value_type;
// A limit a kernel leaves for the host to read after a fence (StepReport):
// the reduction writes it without waiting.
using StepLimitView = ReportView<StepLimit>;
using StepLimitIntoView = Kokkos::MinLoc<double, int, ReportSpace>;

KOKKOS_INLINE_FUNCTION void proposeStepLimit(StepLimit& best, double dt, int cell, int code) {
  if (dt < best.val) {
    best.val = dt;
    best.loc = cell * kLimitCodes + code;
  }
}

// Invalid states propose a negative dt so they win the min reduction.
KOKKOS_INLINE_FUNCTION void cellStepLimit(StepLimit& best, const TimeStepControls& controls,
                                          int cell, double volume, double length,
                                          double sound_speed2, double dvdt, bool finite_state,
                                          bool eos_valid) {
  if (!(volume > 0.0)) return proposeStepLimit(best, -1.0, cell, kBadVolume);
  if (!eos_valid) return proposeStepLimit(best, -1.0, cell, kBadEos);
  if (!finite_state) return proposeStepLimit(best, -1.0, cell, kBadState);
  if (!(sound_speed2 > 0.0)) return proposeStepLimit(best, -1.0, cell, kBadSoundSpeed);
  proposeStepLimit(best, controls.cfl * length / math::sqrt(sound_speed2), cell, kLimitCfl);
  if (dvdt != 0.0) {
    proposeStepLimit(best, controls.c_vol * volume / math::fabs(dvdt), cell, kLimitVolume);
  }
}

}  // namespace lagremap
