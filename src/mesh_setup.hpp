// Building the mesh of a generated block (docs/method.md §7.5): connectivity and
// boundary data on the host, mirrored to the device once.
#pragma once

#include <functional>
#include <optional>

#include "block_part.hpp"
#include "data/mesh.hpp"

namespace lagremap {

struct BlockSpec {
  int nx = 1, ny = 1, nz = 1;
  Vec3 lo{0.0, 0.0, 0.0}, hi{1.0, 1.0, 1.0};
  // Smooth map applied to the block's node positions (e.g. a polar shell); identity if empty.
  std::function<Vec3(const Vec3&)> mapping;
  // Random displacement of interior nodes, as a fraction of the local cell size (tests).
  double perturbation = 0.0;
  unsigned seed = 12345;
  // A decomposed run's part (thisRanksPart): only its held box is built, the
  // cells and nodes numbered in increasing global id, with their global ids
  // and owners; none: the whole block, owned by the calling rank.
  std::optional<BlockPart> part;
};

// Builds the mesh of a block, or of a rank's part of it, with the side
// boundary conditions. Each node and cell is computed from its (i, j, k)
// alone (the perturbation's draws excepted: they follow the whole block's
// node order, so a part of a perturbed block costs the whole block's draws in
// time, not in memory). A part's outer ghost layer has no neighbours across
// the cut (cell_neighbors and cell_face_side -1 there), and the nodes on the
// cut miss the corners, normals and traction faces of the cells beyond it:
// their solution is their owner's (the halo's node exchange).
Mesh buildBlockMesh(const BlockSpec& spec, const SideBoundaries& boundaries);
// Mesh::node_solve_order from the node -> corner CRS.
void orderNodesByFirstCorner(Mesh& mesh);
// Mesh::node_twin_source and node_twin_flip: along each axis on which every
// cell is one cell thick between two wall/symmetry sides (and its nodes
// across it share their other two coordinates), the nodes of the plus side
// take the solution of their partner on the minus side. Needs the mesh's
// connectivity, boundary sides and node positions.
void findNodeTwins(Mesh& mesh);

// Host copies of coordinates and connectivity, for output and checks.
struct HostMesh {
  Vec3View::HostMirror x_n;
  CellNodesView::HostMirror cell_nodes;
};
HostMesh copyToHost(const Mesh& mesh);

}  // namespace lagremap
