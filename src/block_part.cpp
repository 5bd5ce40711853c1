#include "block_part.hpp"

#include <algorithm>
#include <limits>
#include <stdexcept>
#include <string>

#include "parallel.hpp"

namespace lagremap {

std::array<int, 3> chooseProcessGrid(int nx, int ny, int nz, int n_ranks) {
  std::array<int, 3> best{0, 0, 0};
  double best_cut = std::numeric_limits<double>::infinity();
  for (int px = 1; px <= n_ranks; ++px) {
    if (n_ranks % px != 0 || px > nx) continue;
    for (int py = 1; py <= n_ranks / px; ++py) {
      if ((n_ranks / px) % py != 0 || py > ny) continue;
      const int pz = n_ranks / (px * py);
      if (pz > nz) continue;
      // Faces cut by the partition planes.
      const double cut =
          double(px - 1) * ny * nz + double(py - 1) * nx * nz + double(pz - 1) * nx * ny;
      if (cut < best_cut) {
        best_cut = cut;
        best = {px, py, pz};
      }
    }
  }
  if (best[0] == 0) {
    throw std::invalid_argument("cannot split a " + std::to_string(nx) + " x " +
                                std::to_string(ny) + " x " + std::to_string(nz) + " mesh over " +
                                std::to_string(n_ranks) + " ranks (fewer cells than ranks)");
  }
  return best;
}

namespace {
// Start of part `part` of `parts` balanced parts of n items.
int splitStart(int n, int parts, int part) {
  return int((long(n) * part) / parts);
}
// The part holding item i: the largest p with splitStart(n, parts, p) <= i,
// i.e. n p / parts < i + 1.
int partOf(int n, int parts, int i) {
  return int((long(i + 1) * parts - 1) / n);
}
}  // namespace

CellBox ownedBox(int nx, int ny, int nz, const std::array<int, 3>& grid, int rank) {
  const int n[3] = {nx, ny, nz};
  const int coord[3] = {rank % grid[0], (rank / grid[0]) % grid[1], rank / (grid[0] * grid[1])};
  CellBox box;
  for (int d = 0; d < 3; ++d) {
    box.lo[d] = splitStart(n[d], grid[d], coord[d]);
    box.hi[d] = splitStart(n[d], grid[d], coord[d] + 1);
  }
  return box;
}

int BlockPart::cellOwner(int i, int j, int k) const {
  return partOf(dims[0], grid[0], i) +
         grid[0] * (partOf(dims[1], grid[1], j) + grid[1] * partOf(dims[2], grid[2], k));
}

// The rank numbering increases with the part along each axis, and the part
// with the cell index: the lowest owner of the (up to) eight cells round a
// node is the owner of the one with the smallest indices.
int BlockPart::nodeOwner(int i, int j, int k) const {
  return cellOwner(std::max(i - 1, 0), std::max(j - 1, 0), std::max(k - 1, 0));
}

int BlockPart::ghostLayer(int i, int j, int k) const {
  const int index[3] = {i, j, k};
  int layer = 0;
  for (int d = 0; d < 3; ++d) {
    layer = std::max({layer, owned.lo[d] - index[d], index[d] - (owned.hi[d] - 1)});
  }
  return layer;
}

long BlockPart::localCell(int i, int j, int k) const {
  if (!held.contains(i, j, k)) return -1;
  const long nx = held.hi[0] - held.lo[0], ny = held.hi[1] - held.lo[1];
  return (i - held.lo[0]) + nx * ((j - held.lo[1]) + ny * (k - held.lo[2]));
}

long BlockPart::localNode(int i, int j, int k) const {
  const int index[3] = {i, j, k};
  for (int d = 0; d < 3; ++d) {
    if (index[d] < held.lo[d] || index[d] > held.hi[d]) return -1;
  }
  const long nx = held.hi[0] - held.lo[0] + 1, ny = held.hi[1] - held.lo[1] + 1;
  return (i - held.lo[0]) + nx * ((j - held.lo[1]) + ny * (k - held.lo[2]));
}

BlockPart blockPart(int nx, int ny, int nz, int n_ranks, int rank) {
  BlockPart part;
  part.dims = {nx, ny, nz};
  part.grid = chooseProcessGrid(nx, ny, nz, n_ranks);
  part.rank = rank;
  part.owned = ownedBox(nx, ny, nz, part.grid, rank);
  for (int d = 0; d < 3; ++d) {
    part.held.lo[d] = std::max(part.owned.lo[d] - kGhostLayers, 0);
    part.held.hi[d] = std::min(part.owned.hi[d] + kGhostLayers, part.dims[d]);
  }
  return part;
}

std::optional<BlockPart> thisRanksPart(int nx, int ny, int nz) {
  if (parallel::size() == 1) return std::nullopt;
  return blockPart(nx, ny, nz, parallel::size(), parallel::rank());
}

}  // namespace lagremap
