// Building the mesh of a generated block (DESIGN §6): connectivity and
// boundary data on the host, mirrored to the device once.
#pragma once

#include <functional>

#include "../data/mesh.hpp"

namespace lagremap {

struct BlockSpec {
  int nx = 1, ny = 1, nz = 1;
  Vec3 lo{0.0, 0.0, 0.0}, hi{1.0, 1.0, 1.0};
  // Smooth map applied to the block's node positions (e.g. a polar shell); identity if empty.
  std::function<Vec3(const Vec3&)> mapping;
  // Random displacement of interior nodes, as a fraction of the local cell size (tests).
  double perturbation = 0.0;
  unsigned seed = 12345;
};

// Builds the mesh of a block with the side boundary conditions (all of it
// owned by the calling rank).
Mesh buildBlockMesh(const BlockSpec& spec, const SideBoundaries& boundaries);
// Marks every cell and node of the mesh owned, with global id = local id.
void ownEverything(Mesh& mesh);
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
