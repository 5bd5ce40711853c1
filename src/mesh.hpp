// Unstructured hexahedral mesh in flat SoA Views (DESIGN §6), generated from a
// block. Connectivity is built once on the host and mirrored to the device.
#pragma once

#include <functional>
#include <string>

#include "boundary.hpp"
#include "types.hpp"

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

struct Mesh {
  Index n_nodes = 0, n_cells = 0;
  int nx = 0, ny = 0, nz = 0;  // block dimensions (cell id = i + nx (j + ny k))

  // Domain decomposition (DESIGN §6, src/decomposition.hpp). A rank holds the
  // cells it owns and ghost cells round them, and their nodes, numbered in
  // increasing global id: node sums, upwind ties and face owners then pick the
  // same cells as on one rank, so results do not depend on the rank count.
  // Reductions (time step, totals, probes) count owned entities only. One
  // rank: everything owned, local id = global id.
  DeviceView<int*> cell_owned, node_owned;                  // 1 if this rank owns it
  Kokkos::View<long*, HostSpace> cell_global, node_global;  // global ids
  Index n_owned_cells = 0, n_owned_nodes = 0;
  long n_global_cells = 0, n_global_nodes = 0;

  Vec3View x_n;              // node coordinates (moved by the Lagrangian phase)
  CellNodesView cell_nodes;  // 8 nodes per cell, VTK_HEXAHEDRON order
  // Neighbour across each face, -1 on the boundary (and, on a rank's outer
  // ghost layer, across the cut, where cell_face_side is -1 too).
  CellFacesView cell_neighbors;
  CellFacesView cell_face_side;  // box side of a boundary face, -1 for interior faces
  // The neighbour's local face that is face f of the cell, -1 on the boundary: both
  // sides of an interior face find the same swept triangles (remap, DESIGN §5).
  CellFacesView cell_neighbor_face;

  // node -> corner CRS; corner id = 8 * cell + local node. Sorted by corner id,
  // so every node sum is taken in the same order whatever the thread count.
  IndexView node_corner_offsets, node_corners;

  // Boundary data of the nodal solver.
  DeviceView<int*> node_constrained;  // 1 if the node has a velocity constraint
  Sym6View node_projector;            // projector on the allowed velocity subspace
  // node -> boundary faces with an imposed traction (face id = 6 * cell + face).
  IndexView node_traction_offsets, node_traction_faces;
  DeviceView<Real[kNumSides][6]> side_traction;  // sigma^b of each side (Sym6 order)
  DeviceView<int[kNumSides]> side_kind;          // BoundaryKind of each side
};

// Builds the mesh of a block with the side boundary conditions (all of it
// owned by the calling rank).
Mesh buildBlockMesh(const BlockSpec& spec, const SideBoundaries& boundaries);
// Marks every cell and node of the mesh owned, with global id = local id.
void ownEverything(Mesh& mesh);

// Host copies of coordinates and connectivity, for output and checks.
struct HostMesh {
  Vec3View::HostMirror x_n;
  CellNodesView::HostMirror cell_nodes;
};
HostMesh copyToHost(const Mesh& mesh);

}  // namespace lagremap
