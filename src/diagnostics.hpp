// Conservation audit (DESIGN §3): totals over cells and the impulse and work
// the boundaries put in, so drift = change of a total - what came in.
#pragma once

#include "mesh.hpp"
#include "state.hpp"

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

struct Totals {
  double mass = 0.0;
  Vec3 momentum{0, 0, 0};
  double kinetic = 0.0, internal = 0.0;
  double total() const { return kinetic + internal; }
};

// Mass, momentum, kinetic and internal energy of the cells.
Totals computeTotals(const Mesh& mesh, const State& state);

struct BoundaryPower {
  Vec3 force{0, 0, 0};  // sum over nodes of the external force (wall reactions, tractions)
  double power = 0.0;   // sum over nodes of f_ext . V
};
// From the last nodal solve (the corrector's, whose velocities moved the mesh).
BoundaryPower computeBoundaryPower(const Mesh& mesh, const State& state);

}  // namespace lagremap

namespace Kokkos {
template <int N>
struct reduction_identity<lagremap::SumArray<N>> {
  KOKKOS_FORCEINLINE_FUNCTION static lagremap::SumArray<N> sum() { return lagremap::SumArray<N>(); }
};
}  // namespace Kokkos
