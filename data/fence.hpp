// Kokkos::fence(), reported to Kokkos Tools as a fence named `why` on every
// Kokkos version: Kokkos 4 reports its fences itself, 3.4 reports none, so a
// tool (lagremap's own counter, src/kokkos_events.hpp) would not see the
// host wait for the device.
#pragma once

#include <cstdint>

#include <Kokkos_Core.hpp>

namespace lagremap {

inline void fenceFor(const char* why) {
#if KOKKOS_VERSION >= 40000
  Kokkos::fence(why);
#else
  uint64_t handle = 0;
  Kokkos::Tools::beginFence(why, 0, &handle);
  Kokkos::fence();
  Kokkos::Tools::endFence(handle);
#endif
}

}  // namespace lagremap
