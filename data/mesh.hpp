// Unstructured hexahedral mesh in flat SoA Views (docs/method.md §7.5): what the kernels
// read. Built once on the host and mirrored to the device (src/mesh_setup.hpp).
#pragma once

#include "boundary.hpp"
#include "types.hpp"

namespace lagremap {

struct Mesh {
  Index n_nodes = 0, n_cells = 0;
  int nx = 0, ny = 0, nz = 0;  // block dimensions (cell id = i + nx (j + ny k))

  // Domain decomposition (docs/method.md §7.5, src/decomposition.hpp). A rank holds the
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
  // sides of an interior face find the same swept triangles (remap, docs/method.md §A9).
  CellFacesView cell_neighbor_face;

  // node -> corner CRS; corner id = 8 * cell + local node. Sorted by corner id,
  // so every node sum is taken in the same order whatever the thread count.
  IndexView node_corner_offsets, node_corners;
  // The nodes in the order of their first corner (orderNodesByFirstCorner):
  // the nodal solve visits them so, which reads the corner records nearly in
  // storage order (a one-cell slab's two node layers alternate: each cell's
  // eight corners are read in one pass, not half of them a layer later).
  IndexView node_solve_order;
  // Twin nodes of a one-cell-thick slab or bar between symmetry planes
  // (findNodeTwins): the two nodes across the thin direction see mirror-image
  // corner terms and both have a zero velocity normal to the planes, so they
  // move alike; the nodal solve solves the first and gives its velocity to
  // the other (and mirrors its external force). node_twin_source(n): the
  // node whose solution n takes (n itself if n is solved); node_twin_flip(n):
  // the axes (bit 0 x, 1 y, 2 z) its external force is mirrored across.
  // node_twins, from node_twin_offsets(n) to node_twin_offsets(n + 1): the
  // nodes that take n's solution (its thread writes theirs: no second
  // kernel). Empty when the mesh has no twins.
  IndexView node_twin_source;
  DeviceView<int*> node_twin_flip;
  IndexView node_twin_offsets, node_twins;
  // Every cell is a right prism along z, at all times (hex::prismGeometry):
  // a one-cell slab between two z wall/symmetry planes (its z twins share x
  // and y, its nodes have no z velocity), whose bottom nodes lie on one z
  // plane and top nodes on another. Set by findNodeTwins, the same on every
  // rank.
  bool z_prisms = false;

  // Boundary data of the nodal solver.
  // Projector of each node's velocity on its allowed subspace: -1 for a free
  // node, else its row of `projectors` (the distinct ones: a wall's nodes
  // share one).
  DeviceView<int*> node_projector_id;
  Sym6View projectors;
  // node -> boundary faces with an imposed traction (face id = 6 * cell + face).
  IndexView node_traction_offsets, node_traction_faces;
  DeviceView<Real[kNumSides][6]> side_traction;  // sigma^b of each side (Sym6 order)
  DeviceView<int[kNumSides]> side_kind;          // BoundaryKind of each side
};

}  // namespace lagremap
