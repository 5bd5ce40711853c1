// Cells in teams, the staged form's layout of a kernel whose cells have
// parts to share out (docs/method.md §7.6): a cell to each thread of a team,
// its faces, vertices or corners in the lanes of a vector (8 on a GPU, four
// cells a warp: a cell's corner records are then read by consecutive lanes),
// which pass values through the cell's row of the team's scratch memory. On
// a CPU the lanes are a loop.
#pragma once

#include "../data/math.hpp"
#include "../data/types.hpp"
#include "kernel_form.hpp"

namespace lagremap {

namespace cell_teams {

constexpr int kCellsPerTeam = 16;  // a GPU's block: 16 cells x 8 lanes, 128 threads
constexpr int kLanes = kFusedKernelsBuilt ? 1 : 8;

using ScratchRows = Kokkos::View<double**, Kokkos::LayoutRight, ExecSpace::scratch_memory_space,
                                 Kokkos::MemoryUnmanaged>;

// One cell's row of its team's scratch memory.
struct ScratchRow {
  ScratchRows rows;
  int i;
  KOKKOS_FORCEINLINE_FUNCTION double& operator()(int column) const { return rows(i, column); }
  KOKKOS_FORCEINLINE_FUNCTION Vec3 vec3(int column) const {
    return {rows(i, column), rows(i, column + 1), rows(i, column + 2)};
  }
  KOKKOS_FORCEINLINE_FUNCTION void store(int column, const Vec3& v) const {
    rows(i, column) = v.x;
    rows(i, column + 1) = v.y;
    rows(i, column + 2) = v.z;
  }
  KOKKOS_FORCEINLINE_FUNCTION SymMat3 sym(int column) const {
    return {rows(i, column),     rows(i, column + 1), rows(i, column + 2),
            rows(i, column + 3), rows(i, column + 4), rows(i, column + 5)};
  }
  KOKKOS_FORCEINLINE_FUNCTION void store(int column, const SymMat3& m) const {
    const double entries[6] = {m.xx, m.yy, m.zz, m.xy, m.yz, m.xz};
    for (int j = 0; j < 6; ++j) rows(i, column + j) = entries[j];
  }
};

// The teams over a mesh's cells, with a scratch row of `columns` doubles a
// cell. `Policy`: a Kokkos::TeamPolicy over ExecSpace (its launch bounds).
template <class Policy>
Policy overCells(Index n_cells, int columns) {
  const int teams = (n_cells + kCellsPerTeam - 1) / kCellsPerTeam;
  Policy policy(teams, kLanes > 1 ? kCellsPerTeam : 1, kLanes);
  return policy.set_scratch_size(0,
                                 Kokkos::PerTeam(ScratchRows::shmem_size(kCellsPerTeam, columns)));
}

// `cell(c, row)` for each of the team's cells (overCells).
template <class Member, class Cell>
KOKKOS_FORCEINLINE_FUNCTION void forCellsOfTeam(const Member& team, Index n_cells, int columns,
                                                const Cell& cell) {
  const ScratchRows rows(team.team_scratch(0), int(kCellsPerTeam), columns);
  const Index first = team.league_rank() * kCellsPerTeam;
  const int count = n_cells - first < kCellsPerTeam ? int(n_cells - first) : kCellsPerTeam;
  Kokkos::parallel_for(Kokkos::TeamThreadRange(team, count), [&](const int i) {
    cell(first + i, ScratchRow{rows, i});
  });
}

}  // namespace cell_teams

}  // namespace lagremap
