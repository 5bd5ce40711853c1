// Geometry phase (docs/method.md §A2-A4): from the node positions, every cell's volume,
// centroid, length and corner vectors A_cp; then its density, internal energy,
// pressure and sound speeds, and the corner impedance of the nodal solver
// (cell_thermo.hpp); all need only cell-local data, so one sweep does them
// while the 24 corner-face vectors are at hand. The cell's time-step
// candidates are reduced to the most restrictive. The fused form's kernel is
// here, the staged form's in geometry_staged.hpp.
// Its kernel launchers are `static` (internal linkage: docs/method.md §7.2).
#pragma once

#include "../data/fence.hpp"
#include "../data/mesh.hpp"
#include "../data/state.hpp"
#include "cell_thermo.hpp"
#include "geometry_staged.hpp"
#include "hex.hpp"
#include "kernel_form.hpp"
#include "time_step.hpp"

namespace lagremap {

// The geometry of the cells first .. first + count - 1 of a mesh (count <=
// hex::kCellLanes) at once (hex::cellGeometries, in the lanes of a vector on
// CPU builds; a z prism's in closed form, Mesh::z_prisms); the spare lanes
// of a mesh's last, shorter chunk repeat its first cell.
template <bool kCornerSums>
KOKKOS_INLINE_FUNCTION void chunkGeometry(const CellNodesView& cell_nodes, const Vec3View& x_n,
                                          bool z_prisms, Index first, int count,
                                          hex::CellGeometry geometry[hex::kCellLanes]) {
  if (z_prisms) {
    for (int i = 0; i < count; ++i) {
      Vec3 x[8];
      gatherCellNodes(cell_nodes, x_n, first + i, x);
      hex::prismGeometry<kCornerSums>(x, geometry[i]);
    }
    return;
  }
  Vec3 x[hex::kCellLanes][8];
  for (int i = 0; i < hex::kCellLanes; ++i) {
    gatherCellNodes(cell_nodes, x_n, first + (i < count ? i : 0), x[i]);
  }
  hex::cellGeometries<kCornerSums>(x, geometry);
}

// Chunks of hex::kCellLanes cells covering a mesh, and the cells of chunk k.
inline Index cellChunks(const Mesh& mesh) {
  return (mesh.n_cells + hex::kCellLanes - 1) / hex::kCellLanes;
}
KOKKOS_INLINE_FUNCTION int chunkCells(Index n_cells, Index first) {
  return n_cells - first < hex::kCellLanes ? int(n_cells - first) : hex::kCellLanes;
}

// The smallest time-step candidate over a mesh's cells, left in `into`
// without waiting: `cell(c, geometry, best)` updates cell c and folds its
// candidates into `best` (a ghost cell's go to a scratch value: they are its
// owner's to propose), its geometry computed from the mesh's nodes a chunk at
// a time (chunkGeometry), kCornerSums as for hex::cellGeometry.
template <bool kCornerSums, class CellUpdate>
static void stepLimitOverCellGeometries(const char* label, const Mesh& mesh, const CellUpdate& cell,
                                        const StepLimitView& into) {
  const auto owned = mesh.cell_owned;
  const auto cell_nodes = mesh.cell_nodes;
  const auto x_n = mesh.x_n;
  const bool z_prisms = mesh.z_prisms;
  const Index n_cells = mesh.n_cells;
  Kokkos::parallel_reduce(
      label, Kokkos::RangePolicy<ExecSpace>(0, cellChunks(mesh)),
      KOKKOS_LAMBDA(const Index chunk, StepLimit& best) {
        const Index first = chunk * hex::kCellLanes;
        const int count = chunkCells(n_cells, first);
        hex::CellGeometry geometry[hex::kCellLanes];
        chunkGeometry<kCornerSums>(cell_nodes, x_n, z_prisms, first, count, geometry);
        for (int i = 0; i < count; ++i) {
          StepLimit ghost{};
          cell(first + i, geometry[i], owned(first + i) ? best : ghost);
        }
      },
      StepLimitIntoView(into));
}

// The smallest time-step candidate (or a negative value and the failure
// code for an invalid cell), left in `into` without waiting.
static inline void computeGeometry(const Mesh& mesh, const State& state,
                                   const TimeStepControls& controls, const StepLimitView& into,
                                   KernelForm form = defaultKernelForm()) {
  const auto s = state;
  if constexpr (kFusedKernelsBuilt) {
    if (form == KernelForm::Fused) {
      return stepLimitOverCellGeometries<true>(
          "lagremap::geometry::cells", mesh,
          KOKKOS_LAMBDA(const Index c, const hex::CellGeometry& geometry, StepLimit& best) {
            cellThermoOnGeometry(geometry, s, controls, c, best, false);
          },
          into);
    }
  }
  stepLimitOverCellNodes<StageEnd::Full>("lagremap::geometry::cells", mesh, state, controls, into,
                                         false);
}

// The same, waited for (set-up, tests: it allocates its result).
static inline StepLimit computeGeometry(const Mesh& mesh, const State& state,
                                        const TimeStepControls& controls,
                                        KernelForm form = defaultKernelForm()) {
  const StepLimitView limit("lagremap::geometry::limit");
  computeGeometry(mesh, state, controls, limit, form);
  fenceFor("lagremap::geometry: the step limit");
  return limit();
}

}  // namespace lagremap
