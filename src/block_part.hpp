// A rank's part of a generated nx x ny x nz block (docs/method.md §7.5): the process
// grid, the box of cells the rank owns and the box it holds (the owned box
// grown by kGhostLayers), and the owner of any cell or node, all computed
// from (i, j, k) with no table over the block. The generators build only the
// held box (BlockSpec::part, src/mesh_setup.hpp); the halo links it to the
// other ranks' parts (src/decomposition.hpp).
//
// Two ghost layers suffice for one stage: a node of an owned cell gathers the
// corners of layer-1 cells, whose limited reconstruction reads their face
// neighbours (layer 2); the remap's upwind cells are face neighbours too.
#pragma once

#include <array>
#include <optional>

namespace lagremap {

constexpr int kGhostLayers = 2;

// Ranks along x, y, z: the factorisation of n_ranks that cuts the fewest
// faces of an nx x ny x nz block (no direction gets more ranks than cells).
// Throws std::invalid_argument when the block has fewer cells than ranks.
std::array<int, 3> chooseProcessGrid(int nx, int ny, int nz, int n_ranks);

// Cell box [lo, hi) of the block, per axis.
struct CellBox {
  std::array<int, 3> lo{0, 0, 0}, hi{0, 0, 0};
  long cells() const { return long(hi[0] - lo[0]) * (hi[1] - lo[1]) * (hi[2] - lo[2]); }
  bool contains(int i, int j, int k) const {
    return i >= lo[0] && i < hi[0] && j >= lo[1] && j < hi[1] && k >= lo[2] && k < hi[2];
  }
};
// Cell box of `rank` on the process grid (balanced split of each direction).
CellBox ownedBox(int nx, int ny, int nz, const std::array<int, 3>& grid, int rank);

struct BlockPart {
  std::array<int, 3> dims{1, 1, 1};  // the whole block's nx, ny, nz
  std::array<int, 3> grid{1, 1, 1};  // ranks along each axis
  int rank = 0;
  CellBox owned, held;  // held: owned grown by kGhostLayers, clipped to the block

  // Owner rank of global cell (i, j, k), and of global node (i, j, k): the
  // lowest rank owning one of its cells (every rank agrees on both).
  int cellOwner(int i, int j, int k) const;
  int nodeOwner(int i, int j, int k) const;
  // How many layers a held cell lies outside the owned box (0: owned; the
  // largest distance along one axis).
  int ghostLayer(int i, int j, int k) const;
  // The local id of held cell (i, j, k), of held node (i, j, k): (i, j, k)
  // order within the held box, which is increasing global id; -1 if not held.
  long localCell(int i, int j, int k) const;
  long localNode(int i, int j, int k) const;
  long heldNodes() const {
    return long(held.hi[0] - held.lo[0] + 1) * (held.hi[1] - held.lo[1] + 1) *
           (held.hi[2] - held.lo[2] + 1);
  }
  // Global ids: cell i + nx (j + ny k), node i + (nx + 1) (j + (ny + 1) k).
  long globalCell(int i, int j, int k) const { return i + long(dims[0]) * (j + long(dims[1]) * k); }
  long globalNode(int i, int j, int k) const {
    return i + long(dims[0] + 1) * (j + long(dims[1] + 1) * k);
  }
};

// `rank`'s part of the block on n_ranks ranks (chooseProcessGrid, ownedBox).
BlockPart blockPart(int nx, int ny, int nz, int n_ranks, int rank);
// This rank's part on a decomposed run (parallel::size() > 1); none on one rank.
std::optional<BlockPart> thisRanksPart(int nx, int ny, int nz);

}  // namespace lagremap
