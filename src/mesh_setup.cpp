#include "mesh_setup.hpp"

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstring>
#include <map>
#include <random>
#include <stdexcept>
#include <vector>

#include "kernels/hex.hpp"

namespace lagremap {
namespace {

template <class HostView, class DeviceViewT>
void upload(const HostView& host, DeviceViewT& device) {
  device =
      DeviceViewT(Kokkos::view_alloc(Kokkos::WithoutInitializing, host.label()), host.extent(0));
  Kokkos::deep_copy(device, host);
}

template <class T>
IndexView uploadList(const std::string& label, const std::vector<T>& list) {
  Kokkos::View<Index*, HostSpace> host(label, list.size());
  for (std::size_t i = 0; i < list.size(); ++i) host(i) = static_cast<Index>(list[i]);
  IndexView device(Kokkos::view_alloc(Kokkos::WithoutInitializing, label), list.size());
  Kokkos::deep_copy(device, host);
  return device;
}

// The part of the block a mesh holds: a rank's, or the whole block as the one
// part of a single rank (its held box is the block).
BlockPart partOf(const BlockSpec& spec) {
  if (!spec.part) return blockPart(spec.nx, spec.ny, spec.nz, 1, 0);
  if (spec.part->dims != std::array<int, 3>{spec.nx, spec.ny, spec.nz}) {
    throw std::logic_error("buildBlockMesh: the part is of another block");
  }
  return *spec.part;
}

// The block's arrays on the host, filled step by step, then uploaded at once.
struct HostBlockMesh {
  Vec3View::HostMirror x;
  CellNodesView::HostMirror nodes;
  CellFacesView::HostMirror neighbors, side, neighbor_face;
  std::vector<Index> corner_offsets, corners;           // node -> corner CRS
  Kokkos::View<int*, HostSpace> projector_id;           // -1: free; else its row of projectors
  std::vector<SymMat3> projectors;                      // the distinct ones
  std::vector<Index> traction_offsets, traction_faces;  // node -> traction face CRS
};

// Node coordinates of the held nodes: block, random interior perturbation,
// then the mapping. The draws go in the whole block's node order, three per
// interior node, so a part's nodes are where the whole block puts them; an
// unperturbed part visits its own nodes only.
Vec3View::HostMirror nodeCoordinates(const BlockSpec& spec, const BlockPart& part) {
  Vec3View::HostMirror x_host("lagremap::mesh::x_n", part.heldNodes());
  const double dx = (spec.hi.x - spec.lo.x) / spec.nx;
  const double dy = (spec.hi.y - spec.lo.y) / spec.ny;
  const double dz = (spec.hi.z - spec.lo.z) / spec.nz;
  std::mt19937 rng(spec.seed);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  const bool perturbed = spec.perturbation > 0.0;
  std::array<int, 3> first = part.held.lo, last = part.held.hi;  // node ranges, inclusive
  if (perturbed) first = {0, 0, 0}, last = part.dims;
  for (int k = first[2]; k <= last[2]; ++k)
    for (int j = first[1]; j <= last[1]; ++j)
      for (int i = first[0]; i <= last[0]; ++i) {
        Vec3 x{spec.lo.x + i * dx, spec.lo.y + j * dy, spec.lo.z + k * dz};
        const bool interior = i > 0 && i < spec.nx && j > 0 && j < spec.ny && k > 0 && k < spec.nz;
        if (perturbed && interior) {
          x += Vec3{spec.perturbation * dx * unit(rng), spec.perturbation * dy * unit(rng),
                    spec.perturbation * dz * unit(rng)};
        }
        const long n = part.localNode(i, j, k);
        if (n < 0) continue;
        if (spec.mapping) x = spec.mapping(x);
        storeVec3(x_host, Index(n), x);
      }
  return x_host;
}

// Cell -> node (VTK hex), cell -> neighbour and boundary side per face, for
// the held cells; no neighbour (and no side) across a part's cut.
void cellConnectivity(const BlockPart& part, HostBlockMesh& host) {
  const Index n_cells = Index(part.held.cells());
  const CellBox& held = part.held;
  host.nodes = CellNodesView::HostMirror("lagremap::mesh::cell_nodes", n_cells);
  host.neighbors = CellFacesView::HostMirror("lagremap::mesh::cell_neighbors", n_cells);
  host.side = CellFacesView::HostMirror("lagremap::mesh::cell_face_side", n_cells);
  for (int k = held.lo[2]; k < held.hi[2]; ++k)
    for (int j = held.lo[1]; j < held.hi[1]; ++j)
      for (int i = held.lo[0]; i < held.hi[0]; ++i) {
        const Index c = Index(part.localCell(i, j, k));
        const long corner_nodes[8] = {part.localNode(i, j, k),
                                      part.localNode(i + 1, j, k),
                                      part.localNode(i + 1, j + 1, k),
                                      part.localNode(i, j + 1, k),
                                      part.localNode(i, j, k + 1),
                                      part.localNode(i + 1, j, k + 1),
                                      part.localNode(i + 1, j + 1, k + 1),
                                      part.localNode(i, j + 1, k + 1)};
        for (int p = 0; p < 8; ++p) host.nodes(c, p) = Index(corner_nodes[p]);
        const int index[3] = {i, j, k};
        for (int axis = 0; axis < 3; ++axis) {
          int lo_neighbor[3] = {i, j, k}, hi_neighbor[3] = {i, j, k};
          --lo_neighbor[axis];
          ++hi_neighbor[axis];
          const bool block_lo = index[axis] == 0, block_hi = index[axis] == part.dims[axis] - 1;
          // (-1 beyond the held box: the block's boundary, or the cut)
          host.neighbors(c, 2 * axis) =
              Index(part.localCell(lo_neighbor[0], lo_neighbor[1], lo_neighbor[2]));
          host.neighbors(c, 2 * axis + 1) =
              Index(part.localCell(hi_neighbor[0], hi_neighbor[1], hi_neighbor[2]));
          host.side(c, 2 * axis) = block_lo ? 2 * axis : -1;
          host.side(c, 2 * axis + 1) = block_hi ? 2 * axis + 1 : -1;
        }
      }
}

// The neighbour's face holding the same 4 nodes, found by search so it
// holds for any cell orientation, not only the block's lo/hi pairing.
CellFacesView::HostMirror neighborFaces(const CellNodesView::HostMirror& nodes_host,
                                        const CellFacesView::HostMirror& neighbors_host,
                                        Index n_cells) {
  CellFacesView::HostMirror neighbor_face_host("lagremap::mesh::cell_neighbor_face", n_cells);
  for (Index c = 0; c < n_cells; ++c)
    for (int f = 0; f < 6; ++f) {
      const Index n = neighbors_host(c, f);
      neighbor_face_host(c, f) = -1;
      for (int g = 0; n >= 0 && g < 6 && neighbor_face_host(c, f) < 0; ++g) {
        int shared = 0;
        for (int k = 0; k < 4; ++k)
          for (int j = 0; j < 4; ++j)
            shared += nodes_host(c, hex::faceNode(f, k)) == nodes_host(n, hex::faceNode(g, j));
        if (shared == 4) neighbor_face_host(c, f) = g;
      }
      if (n >= 0 && neighbor_face_host(c, f) < 0) {
        throw std::logic_error("cell neighbours share no face");
      }
    }
  return neighbor_face_host;
}

// Node -> corner CRS, in corner-id order (deterministic gathers).
void nodeCorners(const CellNodesView::HostMirror& nodes_host, Index n_cells, Index n_nodes,
                 std::vector<Index>& corner_offsets, std::vector<Index>& corners) {
  corner_offsets.assign(n_nodes + 1, 0);
  for (Index c = 0; c < n_cells; ++c)
    for (int p = 0; p < 8; ++p) ++corner_offsets[nodes_host(c, p) + 1];
  for (Index n = 0; n < n_nodes; ++n) corner_offsets[n + 1] += corner_offsets[n];
  corners.assign(corner_offsets.back(), 0);
  std::vector<Index> fill(corner_offsets.begin(), corner_offsets.end() - 1);
  for (Index c = 0; c < n_cells; ++c)
    for (int p = 0; p < 8; ++p) corners[fill[nodes_host(c, p)]++] = 8 * c + p;
}

// Per node, the boundary sides it lies on, the outward normal of each (area
// weighted over the node's corner faces on that side) and its traction faces.
struct NodeSides {
  std::vector<std::array<Vec3, kNumSides>> normal;
  std::vector<unsigned> sides;  // bit s: on side s
  std::vector<std::vector<Index>> traction_faces;
};

NodeSides nodeSides(const HostBlockMesh& host, const SideBoundaries& boundaries, Index n_cells,
                    Index n_nodes) {
  NodeSides out;
  out.normal.resize(n_nodes);
  out.sides.assign(n_nodes, 0u);
  out.traction_faces.resize(n_nodes);
  for (Index c = 0; c < n_cells; ++c) {
    Vec3 x[8];
    for (int p = 0; p < 8; ++p) x[p] = loadVec3(host.x, host.nodes(c, p));
    for (int f = 0; f < 6; ++f) {
      const int side = host.side(c, f);
      if (side < 0) continue;
      Vec3 q[4], w[4];
      hex::faceNodes(x, f, q);
      hex::faceCornerVectors(q, w);
      for (int k = 0; k < 4; ++k) {
        const Index node = host.nodes(c, hex::faceNode(f, k));
        if ((out.sides[node] & (1u << side)) == 0) out.normal[node][side] = Vec3{0, 0, 0};
        out.sides[node] |= 1u << side;
        out.normal[node][side] += w[k];
        if (boundaries[side].kind == BoundaryKind::Traction) {
          out.traction_faces[node].push_back(6 * c + f);
        }
      }
    }
  }
  return out;
}

// The velocity projector of a node on the boundary sides `sides`, and the
// number of directions it constrains (n_constraints).
SymMat3 nodeProjector(unsigned sides, const std::array<Vec3, kNumSides>& side_normal,
                      const SideBoundaries& boundaries, int& n_constraints) {
  // Orthonormal basis of the constrained directions (Gram-Schmidt); a fixed
  // side constrains all three.
  Vec3 basis[3];
  n_constraints = 0;
  for (int side = 0; side < kNumSides; ++side) {
    if ((sides & (1u << side)) == 0) continue;
    const BoundaryKind kind = boundaries[side].kind;
    if (kind == BoundaryKind::Fixed) {
      n_constraints = 3;
      break;
    }
    if (kind != BoundaryKind::Wall) continue;
    Vec3 normal = side_normal[side];
    for (int b = 0; b < n_constraints; ++b) normal -= dot(normal, basis[b]) * basis[b];
    const double length = norm(normal);
    // Parallel planes (a node on both sides of a one-cell slab cannot happen;
    // nearly coplanar sides of a mapped block can) add no new constraint.
    if (length > 1e-8 * norm(side_normal[side]) && n_constraints < 3) {
      basis[n_constraints++] = (1.0 / length) * normal;
    }
  }
  SymMat3 projector = identitySym();
  if (n_constraints == 3) {
    projector = identitySym(0.0);
  } else {
    for (int b = 0; b < n_constraints; ++b) projector += outerSelf(basis[b], -1.0);
  }
  return projector;
}

// Boundary constraints (each constrained node's projector, one row per
// distinct projector: a wall's nodes share theirs, the bits decide) and the
// node -> traction face CRS of every node.
void boundaryConstraints(const SideBoundaries& boundaries, Index n_cells, Index n_nodes,
                         HostBlockMesh& host) {
  const NodeSides node_sides = nodeSides(host, boundaries, n_cells, n_nodes);
  host.projector_id = Kokkos::View<int*, HostSpace>("lagremap::mesh::node_projector_id", n_nodes);
  host.projectors.clear();
  std::map<std::array<std::uint64_t, 6>, int> row_of;  // by bits: -0 is not +0
  host.traction_offsets.assign(n_nodes + 1, 0);
  host.traction_faces.clear();
  for (Index n = 0; n < n_nodes; ++n) {
    int n_constraints = 0;
    const SymMat3 projector =
        nodeProjector(node_sides.sides[n], node_sides.normal[n], boundaries, n_constraints);
    host.projector_id(n) = -1;
    if (n_constraints > 0) {
      const double entries[6] = {projector.xx, projector.yy, projector.zz,
                                 projector.xy, projector.yz, projector.xz};
      std::array<std::uint64_t, 6> key;
      std::memcpy(key.data(), entries, sizeof entries);
      const auto [row, added] = row_of.try_emplace(key, int(host.projectors.size()));
      if (added) host.projectors.push_back(projector);
      host.projector_id(n) = row->second;
    }
    const std::vector<Index>& faces = node_sides.traction_faces[n];
    host.traction_offsets[n + 1] = host.traction_offsets[n] + Index(faces.size());
    host.traction_faces.insert(host.traction_faces.end(), faces.begin(), faces.end());
  }
}

// Per side, the traction stress and the boundary kind, on the device.
void uploadSides(const SideBoundaries& boundaries, Mesh& mesh) {
  decltype(mesh.side_traction)::HostMirror traction_host("lagremap::mesh::side_traction");
  for (int side = 0; side < kNumSides; ++side) {
    const SymMat3& s = boundaries[side].traction_stress;
    const double comps[6] = {s.xx, s.yy, s.zz, s.xy, s.yz, s.xz};
    for (int i = 0; i < 6; ++i) traction_host(side, i) = comps[i];
  }
  mesh.side_traction = decltype(mesh.side_traction)("lagremap::mesh::side_traction");
  Kokkos::deep_copy(mesh.side_traction, traction_host);
  Kokkos::View<int[kNumSides], HostSpace> kind_host("lagremap::mesh::side_kind");
  for (int side = 0; side < kNumSides; ++side) kind_host(side) = int(boundaries[side].kind);
  mesh.side_kind = decltype(mesh.side_kind)("lagremap::mesh::side_kind");
  Kokkos::deep_copy(mesh.side_kind, kind_host);
}

// The host arrays on the device.
void uploadMesh(const HostBlockMesh& host, Mesh& mesh) {
  upload(host.x, mesh.x_n);
  upload(host.nodes, mesh.cell_nodes);
  upload(host.neighbors, mesh.cell_neighbors);
  upload(host.side, mesh.cell_face_side);
  upload(host.neighbor_face, mesh.cell_neighbor_face);
  upload(host.projector_id, mesh.node_projector_id);
  Sym6View::HostMirror projectors("lagremap::mesh::projectors", host.projectors.size());
  for (std::size_t i = 0; i < host.projectors.size(); ++i)
    storeSym(projectors, i, host.projectors[i]);
  upload(projectors, mesh.projectors);
  mesh.node_corner_offsets = uploadList("lagremap::mesh::node_corner_offsets", host.corner_offsets);
  mesh.node_corners = uploadList("lagremap::mesh::node_corners", host.corners);
  orderNodesByFirstCorner(mesh);
  mesh.node_traction_offsets =
      uploadList("lagremap::mesh::node_traction_offsets", host.traction_offsets);
  mesh.node_traction_faces = uploadList("lagremap::mesh::node_traction_faces", host.traction_faces);
}

}  // namespace

void orderNodesByFirstCorner(Mesh& mesh) {
  const auto offsets = Kokkos::create_mirror_view_and_copy(HostSpace(), mesh.node_corner_offsets);
  const auto corners = Kokkos::create_mirror_view_and_copy(HostSpace(), mesh.node_corners);
  // a corner belongs to one node: the first corners are distinct
  std::vector<std::pair<Index, Index>> first_corner(std::size_t(mesh.n_nodes));
  for (Index n = 0; n < mesh.n_nodes; ++n) {
    const Index first = offsets(n) < offsets(n + 1) ? corners(offsets(n)) : 8 * mesh.n_cells + n;
    first_corner[std::size_t(n)] = {first, n};
  }
  std::sort(first_corner.begin(), first_corner.end());
  std::vector<Index> order(first_corner.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = first_corner[i].second;
  mesh.node_solve_order = uploadList("lagremap::mesh::node_solve_order", order);
}

namespace {

// The partner across axis a of local node p of a VTK hexahedron, and
// whether p is on the axis's minus side.
int partnerAcross(int axis, int p) {
  return axis == 0 ? p ^ 1 : axis == 1 ? p ^ 3 : p ^ 4;
}
// Whether every cell of a mesh thin along z (twins across it sharing x and
// y) has its 4 bottom nodes on one z plane and its 4 top nodes on another
// above it: then it is a right prism along z (hex::prismGeometry).
template <class Nodes, class Coordinates>
bool zPrisms(const Nodes& nodes, const Coordinates& x, Index n_cells) {
  for (Index c = 0; c < n_cells; ++c) {
    const double bottom = x(nodes(c, 0), 2), top = x(nodes(c, 4), 2);
    if (!(top > bottom)) return false;
    for (int p = 1; p < 4; ++p) {
      if (x(nodes(c, p), 2) != bottom || x(nodes(c, p + 4), 2) != top) return false;
    }
  }
  return true;
}
bool onMinusSide(int axis, int p) {
  if (axis == 0) return ((p ^ (p >> 1)) & 1) == 0;  // x-: 0, 3, 4, 7
  if (axis == 1) return (p & 2) == 0;               // y-: 0, 1, 4, 5
  return (p & 4) == 0;                              // z-: 0, 1, 2, 3
}

}  // namespace

void findNodeTwins(Mesh& mesh) {
  const auto nodes = Kokkos::create_mirror_view_and_copy(HostSpace(), mesh.cell_nodes);
  const auto neighbors = Kokkos::create_mirror_view_and_copy(HostSpace(), mesh.cell_neighbors);
  const auto face_side = Kokkos::create_mirror_view_and_copy(HostSpace(), mesh.cell_face_side);
  const auto side_kind = Kokkos::create_mirror_view_and_copy(HostSpace(), mesh.side_kind);
  const auto x = Kokkos::create_mirror_view_and_copy(HostSpace(), mesh.x_n);
  std::vector<Index> source(std::size_t(mesh.n_nodes));
  std::vector<int> flip(std::size_t(mesh.n_nodes), 0);
  for (Index n = 0; n < mesh.n_nodes; ++n) source[std::size_t(n)] = n;
  bool any = false;
  mesh.z_prisms = false;
  for (int axis = 0; axis < 3; ++axis) {
    const auto between_walls = [&](Index c, int f) {
      return neighbors(c, f) < 0 && face_side(c, f) >= 0 &&
             side_kind(face_side(c, f)) == int(BoundaryKind::Wall);
    };
    bool thin = mesh.n_cells > 0;
    for (Index c = 0; c < mesh.n_cells && thin; ++c) {
      thin = between_walls(c, 2 * axis) && between_walls(c, 2 * axis + 1);
      for (int p = 0; p < 8 && thin; ++p) {
        const Index a = nodes(c, p), b = nodes(c, partnerAcross(axis, p));
        for (int d = 0; d < 3; ++d) thin = thin && (d == axis || x(a, d) == x(b, d));
      }
    }
    if (!thin) continue;
    any = true;
    if (axis == 2) mesh.z_prisms = zPrisms(nodes, x, mesh.n_cells);
    // the plus side's node takes its minus partner's source (composed over
    // the axes: a bar's four nodes of a station take the (-, -) one's)
    for (Index c = 0; c < mesh.n_cells; ++c) {
      for (int p = 0; p < 8; ++p) {
        if (!onMinusSide(axis, p)) continue;
        const Index minus = nodes(c, p), plus = nodes(c, partnerAcross(axis, p));
        source[std::size_t(plus)] = minus;
        flip[std::size_t(plus)] = 1 << axis;
      }
    }
    for (Index n = 0; n < mesh.n_nodes; ++n) {  // follow the chain to its end
      Index s = source[std::size_t(n)];
      int mirrored = flip[std::size_t(n)];
      while (source[std::size_t(s)] != s) {
        mirrored ^= flip[std::size_t(s)];
        s = source[std::size_t(s)];
      }
      source[std::size_t(n)] = s;
      flip[std::size_t(n)] = mirrored;
    }
  }
  if (!any) {
    mesh.node_twin_source = IndexView();
    mesh.node_twin_flip = DeviceView<int*>();
    mesh.node_twin_offsets = IndexView();
    mesh.node_twins = IndexView();
    return;
  }
  mesh.node_twin_source = uploadList("lagremap::mesh::node_twin_source", source);
  // each source's twins (CRS, in node order)
  std::vector<Index> offsets(std::size_t(mesh.n_nodes) + 1, 0), twins;
  for (Index n = 0; n < mesh.n_nodes; ++n) {
    if (source[std::size_t(n)] != n) ++offsets[std::size_t(source[std::size_t(n)]) + 1];
  }
  for (std::size_t n = 0; n < std::size_t(mesh.n_nodes); ++n) offsets[n + 1] += offsets[n];
  twins.resize(std::size_t(offsets.back()));
  std::vector<Index> filled(offsets.begin(), offsets.end() - 1);
  for (Index n = 0; n < mesh.n_nodes; ++n) {
    const Index s = source[std::size_t(n)];
    if (s != n) twins[std::size_t(filled[std::size_t(s)]++)] = n;
  }
  mesh.node_twin_offsets = uploadList("lagremap::mesh::node_twin_offsets", offsets);
  mesh.node_twins = uploadList("lagremap::mesh::node_twins", twins);
  Kokkos::View<int*, HostSpace> flip_host("lagremap::mesh::node_twin_flip", flip.size());
  for (std::size_t n = 0; n < flip.size(); ++n) flip_host(n) = flip[n];
  mesh.node_twin_flip = DeviceView<int*>("lagremap::mesh::node_twin_flip", flip.size());
  Kokkos::deep_copy(mesh.node_twin_flip, flip_host);
}

namespace {

// The mesh's global ids and owners (BlockPart, computed from (i, j, k); the
// whole block's single part owns everything, with global id = local id).
void ownPart(const BlockPart& part, Mesh& mesh) {
  Kokkos::View<int*, HostSpace> cell_owned("lagremap::mesh::cell_owned", mesh.n_cells);
  Kokkos::View<int*, HostSpace> node_owned("lagremap::mesh::node_owned", mesh.n_nodes);
  mesh.cell_global = Kokkos::View<long*, HostSpace>("lagremap::mesh::cell_global", mesh.n_cells);
  mesh.node_global = Kokkos::View<long*, HostSpace>("lagremap::mesh::node_global", mesh.n_nodes);
  mesh.n_owned_cells = mesh.n_owned_nodes = 0;
  const CellBox& held = part.held;
  for (int k = held.lo[2]; k <= held.hi[2]; ++k)
    for (int j = held.lo[1]; j <= held.hi[1]; ++j)
      for (int i = held.lo[0]; i <= held.hi[0]; ++i) {
        const Index n = Index(part.localNode(i, j, k));
        mesh.node_global(n) = part.globalNode(i, j, k);
        node_owned(n) = part.nodeOwner(i, j, k) == part.rank;
        mesh.n_owned_nodes += node_owned(n);
        if (i == held.hi[0] || j == held.hi[1] || k == held.hi[2]) continue;
        const Index c = Index(part.localCell(i, j, k));
        mesh.cell_global(c) = part.globalCell(i, j, k);
        cell_owned(c) = part.cellOwner(i, j, k) == part.rank;
        mesh.n_owned_cells += cell_owned(c);
      }
  upload(cell_owned, mesh.cell_owned);
  upload(node_owned, mesh.node_owned);
  mesh.n_global_cells = long(part.dims[0]) * part.dims[1] * part.dims[2];
  mesh.n_global_nodes = long(part.dims[0] + 1) * (part.dims[1] + 1) * (part.dims[2] + 1);
}

}  // namespace

Mesh buildBlockMesh(const BlockSpec& spec, const SideBoundaries& boundaries) {
  if (spec.nx < 1 || spec.ny < 1 || spec.nz < 1) {
    throw std::invalid_argument("mesh needs at least one cell in each direction");
  }
  const BlockPart part = partOf(spec);
  Mesh mesh;
  mesh.nx = spec.nx;
  mesh.ny = spec.ny;
  mesh.nz = spec.nz;
  // (local ids, and corner ids 8 c + p, are 32-bit; global ids are long)
  const long n_nodes = part.heldNodes();
  if (n_nodes >= (1L << 31) / 8) {
    throw std::invalid_argument("mesh too large for 32-bit indices on one rank (use more ranks)");
  }
  mesh.n_nodes = Index(n_nodes);
  mesh.n_cells = Index(part.held.cells());

  HostBlockMesh host;
  host.x = nodeCoordinates(spec, part);
  cellConnectivity(part, host);
  host.neighbor_face = neighborFaces(host.nodes, host.neighbors, mesh.n_cells);
  nodeCorners(host.nodes, mesh.n_cells, mesh.n_nodes, host.corner_offsets, host.corners);
  boundaryConstraints(boundaries, mesh.n_cells, mesh.n_nodes, host);
  uploadMesh(host, mesh);
  uploadSides(boundaries, mesh);
  ownPart(part, mesh);
  findNodeTwins(mesh);  // (a part's z_prisms: its own cells'; makeHalo settles it for the block)
  return mesh;
}

HostMesh copyToHost(const Mesh& mesh) {
  HostMesh host;
  host.x_n = Kokkos::create_mirror_view_and_copy(HostSpace(), mesh.x_n);
  host.cell_nodes = Kokkos::create_mirror_view_and_copy(HostSpace(), mesh.cell_nodes);
  return host;
}

}  // namespace lagremap
