// The two layouts of the per-cell kernels (docs/method.md §7.6).
#pragma once

#include <type_traits>

#include "../data/types.hpp"

namespace lagremap {

// How the per-cell kernels lay out their work (docs/method.md §7.6), the
// same bits either way:
// - Fused: what a cell needs is computed once and held (its whole geometry,
//   hex::CellGeometry, 85 doubles, from one sweep over its 24 triangles;
//   its stencil's offsets), kCellLanes cells in the lanes of a vector on CPU
//   builds, and a stage's cell update and geometry are one kernel (the
//   cell's records are in cache once).
// - Staged: a cell to a thread of a team, its faces, corners, gradient rows
//   or vertices in the lanes of a vector, passing values through the team's
//   scratch memory (cell_teams.hpp); offsets reloaded where they are used (a
//   small part of the live state); the cell update, the volume sharing and
//   the geometry separate kernels. What a GPU thread runs in registers.
// `numerics.kernels` chooses at run time; the default is the backend's. The
// fused form is built for host execution spaces only (on a GPU its kernels
// spill), so a CPU build runs and tests both.
enum class KernelForm { Fused, Staged };
constexpr bool kFusedKernelsBuilt = std::is_same<ExecSpace::memory_space, Kokkos::HostSpace>::value;
inline KernelForm defaultKernelForm() {
  return kFusedKernelsBuilt ? KernelForm::Fused : KernelForm::Staged;
}

}  // namespace lagremap
