// A fixed-size sum as one Kokkos reduction value (several totals in one
// parallel_reduce), on Kokkos 3.x and 4.x.
#pragma once

#include "../data/math.hpp"

namespace lagremap {

// Fixed-size sum usable as a Kokkos reduction value on Kokkos 3.x and 4.x.
template <int N>
struct SumArray {
  double v[N];
  KOKKOS_INLINE_FUNCTION SumArray() {
    for (int i = 0; i < N; ++i) v[i] = 0.0;
  }
  KOKKOS_INLINE_FUNCTION SumArray& operator+=(const SumArray& other) {
    for (int i = 0; i < N; ++i) v[i] += other.v[i];
    return *this;
  }
  KOKKOS_INLINE_FUNCTION void operator+=(const volatile SumArray& other) volatile {
    for (int i = 0; i < N; ++i) v[i] += other.v[i];
  }
};

}  // namespace lagremap

namespace Kokkos {
template <int N>
struct reduction_identity<lagremap::SumArray<N>> {
  KOKKOS_FORCEINLINE_FUNCTION static lagremap::SumArray<N> sum() { return lagremap::SumArray<N>(); }
};
}  // namespace Kokkos
