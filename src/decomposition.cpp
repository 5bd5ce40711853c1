#include "decomposition.hpp"

#include <mpi.h>

#include <algorithm>
#include <limits>
#include <stdexcept>
#include <utility>

#include "mesh_setup.hpp"
#include "parallel.hpp"
#include "problem.hpp"

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

// --- halo exchange

void Halo::exchangeCells(const std::vector<FieldRef>& fields) const {
  exchange(cell_links, fields, cell_traffic_);
}
void Halo::exchangeNodes(const std::vector<FieldRef>& fields) const {
  exchange(node_links, fields, node_traffic_);
}
void Halo::exchangeOuterCells(const std::vector<FieldRef>& fields) const {
  exchange(outer_cell_links, fields, cell_traffic_);
}

void Halo::exchange(const std::vector<Link>& links, const std::vector<FieldRef>& fields,
                    Traffic& traffic) const {
  if (links.empty()) return;
  int row = 0;  // doubles per entity
  for (const FieldRef& field : fields) row += field.components;
  std::size_t send_size = 0, recv_size = 0;
  for (const Link& link : links) {
    send_size += link.send.extent(0) * std::size_t(row);
    recv_size += link.recv.extent(0) * std::size_t(row);
  }
  traffic.messages += long(links.size());
  traffic.bytes += double(send_size * sizeof(double));
  // Buffers grow to the largest message set and stay (no allocation per step).
  if (send_buffer_.extent(0) < send_size) {
    send_buffer_ = RealView(Kokkos::view_alloc(Kokkos::WithoutInitializing, "lagremap::halo::send"),
                            send_size);
    send_host_ = Kokkos::create_mirror_view(send_buffer_);
  }
  if (recv_buffer_.extent(0) < recv_size) {
    recv_buffer_ = RealView(Kokkos::view_alloc(Kokkos::WithoutInitializing, "lagremap::halo::recv"),
                            recv_size);
    recv_host_ = Kokkos::create_mirror_view(recv_buffer_);
  }
  // Each link's message: field after field, entity-major within a field.
  std::size_t offset = 0;
  for (const Link& link : links) {
    for (const FieldRef& field : fields) {
      field.pack(link.send, send_buffer_, Index(offset));
      offset += link.send.extent(0) * std::size_t(field.components);
    }
  }
  Kokkos::fence();
  // MPI reads host memory: a device build stages the buffers through host mirrors.
  Kokkos::deep_copy(send_host_, send_buffer_);
  // (kept from one exchange to the next: no allocation in the time step;
  // exchanges run one at a time, on the thread that calls MPI)
  static thread_local std::vector<MPI_Request> requests;
  requests.clear();
  std::size_t send_offset = 0, recv_offset = 0;
  for (const Link& link : links) {
    const int recv_count = int(link.recv.extent(0)) * row;
    const int send_count = int(link.send.extent(0)) * row;
    requests.emplace_back();
    MPI_Irecv(recv_host_.data() + recv_offset, recv_count, MPI_DOUBLE, link.rank, 0, MPI_COMM_WORLD,
              &requests.back());
    requests.emplace_back();
    MPI_Isend(send_host_.data() + send_offset, send_count, MPI_DOUBLE, link.rank, 0, MPI_COMM_WORLD,
              &requests.back());
    recv_offset += std::size_t(recv_count);
    send_offset += std::size_t(send_count);
  }
  MPI_Waitall(int(requests.size()), requests.data(), MPI_STATUSES_IGNORE);
  Kokkos::deep_copy(recv_buffer_, recv_host_);
  offset = 0;
  for (const Link& link : links) {
    for (const FieldRef& field : fields) {
      field.unpack(link.recv, recv_buffer_, Index(offset));
      offset += link.recv.extent(0) * std::size_t(field.components);
    }
  }
  Kokkos::fence();
}

namespace {

template <class T>
IndexView uploadIndices(const std::string& label, const std::vector<T>& list) {
  Kokkos::View<Index*, HostSpace> host(label, list.size());
  for (std::size_t i = 0; i < list.size(); ++i) host(i) = Index(list[i]);
  IndexView device(Kokkos::view_alloc(Kokkos::WithoutInitializing, label), list.size());
  Kokkos::deep_copy(device, host);
  return device;
}

template <class DeviceViewT, class HostViewT>
DeviceViewT upload(const HostViewT& host) {
  DeviceViewT device(Kokkos::view_alloc(Kokkos::WithoutInitializing, host.label()), host.extent(0));
  Kokkos::deep_copy(device, host);
  return device;
}

// Ghost entities grouped by owner rank (recv), and what each rank asks of
// this one (send), agreed by exchanging the global ids.
std::vector<Halo::Link> makeLinks(const std::vector<long>& local_global,
                                  const std::vector<int>& local_owner,
                                  const std::vector<Index>& global_to_local, const char* what) {
  const int n_ranks = parallel::size(), me = parallel::rank();
  std::vector<std::vector<long>> wanted(n_ranks);
  std::vector<std::vector<Index>> recv_ids(n_ranks);
  for (std::size_t i = 0; i < local_global.size(); ++i) {
    if (local_owner[i] == me) continue;
    wanted[local_owner[i]].push_back(local_global[i]);
    recv_ids[local_owner[i]].push_back(Index(i));
  }
  std::vector<int> send_counts(n_ranks), recv_counts(n_ranks);
  for (int r = 0; r < n_ranks; ++r) send_counts[r] = int(wanted[r].size());
  MPI_Alltoall(send_counts.data(), 1, MPI_INT, recv_counts.data(), 1, MPI_INT, MPI_COMM_WORLD);
  std::vector<int> send_displs(n_ranks + 1, 0), recv_displs(n_ranks + 1, 0);
  for (int r = 0; r < n_ranks; ++r) {
    send_displs[r + 1] = send_displs[r] + send_counts[r];
    recv_displs[r + 1] = recv_displs[r] + recv_counts[r];
  }
  std::vector<long> wanted_flat;
  std::vector<long> asked(static_cast<std::size_t>(recv_displs[n_ranks]));
  for (int r = 0; r < n_ranks; ++r)
    wanted_flat.insert(wanted_flat.end(), wanted[r].begin(), wanted[r].end());
  MPI_Alltoallv(wanted_flat.data(), send_counts.data(), send_displs.data(), MPI_LONG, asked.data(),
                recv_counts.data(), recv_displs.data(), MPI_LONG, MPI_COMM_WORLD);
  std::vector<Halo::Link> links;
  for (int r = 0; r < n_ranks; ++r) {
    if (recv_counts[r] == 0 && wanted[r].empty()) continue;
    std::vector<Index> send_ids;
    for (int i = recv_displs[r]; i < recv_displs[r + 1]; ++i) {
      const Index local = global_to_local[std::size_t(asked[std::size_t(i)])];
      if (local < 0) throw std::logic_error(std::string("halo: asked for a ") + what + " not held");
      send_ids.push_back(local);
    }
    Halo::Link link;
    link.rank = r;
    link.send = uploadIndices(std::string("lagremap::halo::send_") + what, send_ids);
    link.recv = uploadIndices(std::string("lagremap::halo::recv_") + what, recv_ids[r]);
    links.push_back(link);
  }
  return links;
}

// A device View's host copy, as create_mirror_view_and_copy returns it.
template <class ViewT>
using HostCopy = decltype(Kokkos::create_mirror_view_and_copy(HostSpace(), std::declval<ViewT>()));

// Owner rank of every global cell of the block, from the split points along each axis.
struct CellOwner {
  int nx, ny;
  std::array<int, 3> grid;
  std::array<std::vector<int>, 3> part_of;  // per axis: the part of each cell index
  int operator()(long c) const {
    const int i = int(c % nx), j = int((c / nx) % ny), k = int(c / (long(nx) * ny));
    return part_of[0][i] + grid[0] * (part_of[1][j] + grid[1] * part_of[2][k]);
  }
};

CellOwner cellOwners(int nx, int ny, int nz, const std::array<int, 3>& grid) {
  CellOwner owner{nx, ny, grid, {}};
  const int n[3] = {nx, ny, nz};
  for (int d = 0; d < 3; ++d) {
    owner.part_of[d].resize(std::size_t(n[d]));
    for (int p = 0; p < grid[d]; ++p)
      for (int i = splitStart(n[d], grid[d], p); i < splitStart(n[d], grid[d], p + 1); ++i) {
        owner.part_of[d][std::size_t(i)] = p;
      }
  }
  return owner;
}

// Owner rank of every global node: the lowest rank owning one of its cells.
std::vector<int> nodeOwners(const Mesh& global, const HostCopy<CellNodesView>& nodes_g,
                            const CellOwner& cell_owner, int n_ranks) {
  std::vector<int> node_owner(std::size_t(global.n_nodes), n_ranks);
  for (Index c = 0; c < global.n_cells; ++c) {
    const int owner = cell_owner(c);
    for (int p = 0; p < 8; ++p) {
      int& o = node_owner[std::size_t(nodes_g(c, p))];
      o = std::min(o, owner);
    }
  }
  return node_owner;
}

// This rank's cells and nodes: their global ids in increasing order, their
// owners, and the global -> local maps (-1: not held here).
struct LocalEntities {
  std::vector<long> cells, nodes;
  std::vector<int> cell_owner, node_owner;
  std::vector<Index> cell_local, node_local;
  std::vector<int> cell_layer;  // 0 owned, else the ghost layer (1 or 2)
};

// Local cells: the owned box grown by the ghost layers, in global order.
void localCells(const Mesh& global, const CellOwner& cell_owner, const std::array<int, 3>& grid,
                int me, LocalEntities& local) {
  const int nx = global.nx, ny = global.ny, nz = global.nz;
  const CellBox box = ownedBox(nx, ny, nz, grid, me);
  for (int k = std::max(box.lo[2] - kGhostLayers, 0); k < std::min(box.hi[2] + kGhostLayers, nz);
       ++k)
    for (int j = std::max(box.lo[1] - kGhostLayers, 0); j < std::min(box.hi[1] + kGhostLayers, ny);
         ++j)
      for (int i = std::max(box.lo[0] - kGhostLayers, 0);
           i < std::min(box.hi[0] + kGhostLayers, nx); ++i) {
        const long c = i + long(nx) * (j + long(ny) * k);
        local.cells.push_back(c);
        local.cell_owner.push_back(cell_owner(c));
        // layer: the cell's distance (in cells, along the worst axis) from the owned box
        const int index[3] = {i, j, k};
        int layer = 0;
        for (int d = 0; d < 3; ++d) {
          layer = std::max({layer, box.lo[d] - index[d], index[d] - (box.hi[d] - 1)});
        }
        local.cell_layer.push_back(layer);
      }
  local.cell_local.assign(std::size_t(global.n_cells), -1);
  for (std::size_t i = 0; i < local.cells.size(); ++i) {
    local.cell_local[std::size_t(local.cells[i])] = Index(i);
  }
}

// Local nodes: those of the local cells, in global order.
void localNodes(const Mesh& global, const HostCopy<CellNodesView>& nodes_g,
                const std::vector<int>& node_owner, LocalEntities& local) {
  std::vector<Index>& node_local = local.node_local;
  std::vector<long>& nodes = local.nodes;
  node_local.assign(std::size_t(global.n_nodes), -1);
  for (long c : local.cells)
    for (int p = 0; p < 8; ++p) {
      const Index node = nodes_g(Index(c), p);
      if (node_local[std::size_t(node)] < 0) {
        node_local[std::size_t(node)] = 0;
        nodes.push_back(node);
      }
    }
  std::sort(nodes.begin(), nodes.end());
  local.node_owner.resize(nodes.size());
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    node_local[std::size_t(nodes[i])] = Index(i);
    local.node_owner[i] = node_owner[std::size_t(nodes[i])];
  }
}

// The local nodes' arrays: the global ones restricted and renumbered, and
// the traction faces that are on local cells.
void restrictNodes(const Mesh& global, const LocalEntities& local, int me, Mesh& mesh) {
  const auto x_g = Kokkos::create_mirror_view_and_copy(HostSpace(), global.x_n);
  const auto constrained_g =
      Kokkos::create_mirror_view_and_copy(HostSpace(), global.node_constrained);
  const auto projector_g = Kokkos::create_mirror_view_and_copy(HostSpace(), global.node_projector);
  const auto traction_offsets_g =
      Kokkos::create_mirror_view_and_copy(HostSpace(), global.node_traction_offsets);
  const auto traction_faces_g =
      Kokkos::create_mirror_view_and_copy(HostSpace(), global.node_traction_faces);
  Vec3View::HostMirror x_host("lagremap::mesh::x_n", mesh.n_nodes);
  Kokkos::View<int*, HostSpace> constrained_host("lagremap::mesh::node_constrained", mesh.n_nodes);
  Sym6View::HostMirror projector_host("lagremap::mesh::node_projector", mesh.n_nodes);
  Kokkos::View<int*, HostSpace> node_owned_host("lagremap::mesh::node_owned", mesh.n_nodes);
  mesh.node_global = Kokkos::View<long*, HostSpace>("lagremap::mesh::node_global", mesh.n_nodes);
  std::vector<Index> traction_offsets(std::size_t(mesh.n_nodes) + 1, 0), traction_faces;
  for (Index n = 0; n < mesh.n_nodes; ++n) {
    const Index g = Index(local.nodes[std::size_t(n)]);
    for (int d = 0; d < 3; ++d) x_host(n, d) = x_g(g, d);
    for (int d = 0; d < 6; ++d) projector_host(n, d) = projector_g(g, d);
    constrained_host(n) = constrained_g(g);
    node_owned_host(n) = local.node_owner[std::size_t(n)] == me;
    mesh.node_global(n) = g;
    for (Index i = traction_offsets_g(g); i < traction_offsets_g(g + 1); ++i) {
      const Index face = traction_faces_g(i);
      const Index cell = local.cell_local[std::size_t(face / 6)];
      if (cell >= 0) traction_faces.push_back(6 * cell + face % 6);  // (a ghost node may miss some)
    }
    traction_offsets[std::size_t(n) + 1] = Index(traction_faces.size());
  }
  mesh.x_n = upload<Vec3View>(x_host);
  mesh.node_constrained = upload<DeviceView<int*>>(constrained_host);
  mesh.node_projector = upload<Sym6View>(projector_host);
  mesh.node_owned = upload<DeviceView<int*>>(node_owned_host);
  mesh.node_traction_offsets =
      uploadIndices("lagremap::mesh::node_traction_offsets", traction_offsets);
  mesh.node_traction_faces = uploadIndices("lagremap::mesh::node_traction_faces", traction_faces);
}

// Node -> corner CRS in local corner order, which is the global order.
void uploadNodeCorners(const CellNodesView::HostMirror& nodes_host, Mesh& mesh) {
  std::vector<Index> corner_offsets(std::size_t(mesh.n_nodes) + 1, 0);
  for (Index c = 0; c < mesh.n_cells; ++c)
    for (int p = 0; p < 8; ++p) ++corner_offsets[std::size_t(nodes_host(c, p)) + 1];
  for (Index i = 0; i < mesh.n_nodes; ++i) corner_offsets[i + 1] += corner_offsets[i];
  std::vector<Index> corners(std::size_t(corner_offsets.back()));
  std::vector<Index> fill(corner_offsets.begin(), corner_offsets.end() - 1);
  for (Index c = 0; c < mesh.n_cells; ++c)
    for (int p = 0; p < 8; ++p) corners[std::size_t(fill[nodes_host(c, p)]++)] = 8 * c + p;
  mesh.node_corner_offsets = uploadIndices("lagremap::mesh::node_corner_offsets", corner_offsets);
  mesh.node_corners = uploadIndices("lagremap::mesh::node_corners", corners);
  orderNodesByFirstCorner(mesh);
}

// The local cells' arrays: the global ones restricted and renumbered, and
// the node -> corner CRS.
void restrictCells(const Mesh& global, const HostCopy<CellNodesView>& nodes_g,
                   const LocalEntities& local, int me, Mesh& mesh) {
  const auto neighbors_g = Kokkos::create_mirror_view_and_copy(HostSpace(), global.cell_neighbors);
  const auto side_g = Kokkos::create_mirror_view_and_copy(HostSpace(), global.cell_face_side);
  const auto face_g = Kokkos::create_mirror_view_and_copy(HostSpace(), global.cell_neighbor_face);
  CellNodesView::HostMirror nodes_host("lagremap::mesh::cell_nodes", mesh.n_cells);
  CellFacesView::HostMirror neighbors_host("lagremap::mesh::cell_neighbors", mesh.n_cells);
  CellFacesView::HostMirror side_host("lagremap::mesh::cell_face_side", mesh.n_cells);
  CellFacesView::HostMirror face_host("lagremap::mesh::cell_neighbor_face", mesh.n_cells);
  Kokkos::View<int*, HostSpace> cell_owned_host("lagremap::mesh::cell_owned", mesh.n_cells);
  mesh.cell_global = Kokkos::View<long*, HostSpace>("lagremap::mesh::cell_global", mesh.n_cells);
  for (Index c = 0; c < mesh.n_cells; ++c) {
    const Index g = Index(local.cells[std::size_t(c)]);
    for (int p = 0; p < 8; ++p) nodes_host(c, p) = local.node_local[std::size_t(nodes_g(g, p))];
    for (int f = 0; f < 6; ++f) {
      const Index nb = neighbors_g(g, f);
      const Index nb_local = nb >= 0 ? local.cell_local[std::size_t(nb)] : -1;
      neighbors_host(c, f) = nb_local;  // -1 across the cut of the outer ghost layer
      side_host(c, f) = side_g(g, f);
      face_host(c, f) = nb_local >= 0 ? face_g(g, f) : -1;
    }
    cell_owned_host(c) = local.cell_owner[std::size_t(c)] == me;
    mesh.cell_global(c) = g;
  }
  uploadNodeCorners(nodes_host, mesh);
  mesh.cell_nodes = upload<CellNodesView>(nodes_host);
  mesh.cell_neighbors = upload<CellFacesView>(neighbors_host);
  mesh.cell_face_side = upload<CellFacesView>(side_host);
  mesh.cell_neighbor_face = upload<CellFacesView>(face_host);
  mesh.cell_owned = upload<DeviceView<int*>>(cell_owned_host);
}

}  // namespace

Subdomain decompose(const Mesh& global) {
  const int n_ranks = parallel::size(), me = parallel::rank();
  const int nx = global.nx, ny = global.ny, nz = global.nz;
  if (long(nx) * ny * nz != long(global.n_cells)) {
    throw std::logic_error("decompose: the mesh is not an nx x ny x nz block");
  }
  Subdomain sub;
  sub.grid = chooseProcessGrid(nx, ny, nz, n_ranks);

  // Owner of every global cell and node, then this rank's cells and nodes.
  const CellOwner cell_owner = cellOwners(nx, ny, nz, sub.grid);
  const auto nodes_g = Kokkos::create_mirror_view_and_copy(HostSpace(), global.cell_nodes);
  const std::vector<int> node_owner = nodeOwners(global, nodes_g, cell_owner, n_ranks);
  LocalEntities local;
  localCells(global, cell_owner, sub.grid, me, local);
  localNodes(global, nodes_g, node_owner, local);

  // --- the local mesh: the global arrays restricted and renumbered.
  Mesh& mesh = sub.mesh;
  mesh.nx = nx;
  mesh.ny = ny;
  mesh.nz = nz;
  mesh.n_cells = Index(local.cells.size());
  mesh.n_nodes = Index(local.nodes.size());
  restrictNodes(global, local, me, mesh);
  restrictCells(global, nodes_g, local, me, mesh);
  mesh.side_traction = global.side_traction;  // per box side: shared, never written
  mesh.side_kind = global.side_kind;
  mesh.n_owned_cells = Index(std::count(local.cell_owner.begin(), local.cell_owner.end(), me));
  mesh.n_owned_nodes = Index(std::count(local.node_owner.begin(), local.node_owner.end(), me));
  mesh.n_global_cells = global.n_cells;
  mesh.n_global_nodes = global.n_nodes;
  findNodeTwins(mesh);
  // one decision for every rank (the prism formulas differ from the general
  // ones in round-off, and results may not depend on the rank count): the
  // whole mesh's
  mesh.z_prisms = global.z_prisms;

  sub.halo.cell_links = makeLinks(local.cells, local.cell_owner, local.cell_local, "cell");
  // the outer layer's cells alone (the first layer's owners masked as this rank)
  std::vector<int> outer_owner = local.cell_owner;
  for (std::size_t i = 0; i < outer_owner.size(); ++i) {
    if (local.cell_layer[i] < kGhostLayers) outer_owner[i] = me;
  }
  sub.halo.outer_cell_links = makeLinks(local.cells, outer_owner, local.cell_local, "outer_cell");
  sub.halo.node_links = makeLinks(local.nodes, local.node_owner, local.node_local, "node");
  return sub;
}

void allgatherRows(const std::vector<long>& ids, const std::vector<double>& rows, int components,
                   std::vector<long>& all_ids, std::vector<double>& all_rows) {
  const int n_ranks = parallel::size();
  if (n_ranks == 1) {
    all_ids = ids;
    all_rows = rows;
    return;
  }
  std::vector<int> counts(n_ranks), displs(n_ranks + 1, 0);
  const int count = int(ids.size());
  MPI_Allgather(&count, 1, MPI_INT, counts.data(), 1, MPI_INT, MPI_COMM_WORLD);
  for (int r = 0; r < n_ranks; ++r) displs[r + 1] = displs[r] + counts[r];
  all_ids.resize(std::size_t(displs[n_ranks]));
  MPI_Allgatherv(ids.data(), count, MPI_LONG, all_ids.data(), counts.data(), displs.data(),
                 MPI_LONG, MPI_COMM_WORLD);
  for (int r = 0; r <= n_ranks; ++r) {
    if (r < n_ranks) counts[r] *= components;
    displs[r] *= components;
  }
  all_rows.resize(std::size_t(displs[n_ranks]));
  MPI_Allgatherv(rows.data(), count * components, MPI_DOUBLE, all_rows.data(), counts.data(),
                 displs.data(), MPI_DOUBLE, MPI_COMM_WORLD);
}

InitialCells localInitialCells(const InitialCells& global, const Mesh& local, int n_materials) {
  InitialCells cells;
  const bool mixed = !global.alpha_k.empty();
  for (Index c = 0; c < local.n_cells; ++c) {
    const std::size_t g = std::size_t(local.cell_global(c));
    cells.v.push_back(global.v[g]);
    if (!mixed) {
      cells.rho.push_back(global.rho[g]);
      cells.e.push_back(global.e[g]);
      cells.mat.push_back(global.mat[g]);
      continue;
    }
    for (int k = 0; k < n_materials; ++k) {
      const std::size_t i = g * std::size_t(n_materials) + std::size_t(k);
      cells.alpha_k.push_back(global.alpha_k[i]);
      cells.rho_k.push_back(global.rho_k[i]);
      cells.e_k.push_back(global.e_k[i]);
    }
  }
  return cells;
}

}  // namespace lagremap
