#include "decomposition.hpp"

#include <mpi.h>

#include <algorithm>
#include <limits>
#include <stdexcept>
#include <utility>

#include "kokkos_events.hpp"
#include "parallel.hpp"

namespace lagremap {

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
  fenceFor("lagremap::halo: the packed buffers");
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
  fenceFor("lagremap::halo: the unpacked fields");
}

namespace {

IndexView uploadIndices(const std::string& label, const std::vector<Index>& list) {
  Kokkos::View<Index*, HostSpace> host(label, list.size());
  for (std::size_t i = 0; i < list.size(); ++i) host(i) = list[i];
  IndexView device(Kokkos::view_alloc(Kokkos::WithoutInitializing, label), list.size());
  Kokkos::deep_copy(device, host);
  return device;
}

// Ghost entities grouped by owner rank (recv), and what each rank asks of
// this one (send), agreed by exchanging the global ids. `local_of`: the local
// id of a global id (a formula over the held box, no global table).
template <class LocalOf>
std::vector<Halo::Link> makeLinks(const std::vector<long>& local_global,
                                  const std::vector<int>& local_owner, const LocalOf& local_of,
                                  const char* what) {
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
      const Index local = local_of(asked[std::size_t(i)]);
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

// (i, j, k) of a global id on a block with n[0] x n[1] x n[2] entities
std::array<int, 3> blockIndex(long id, const std::array<long, 3>& n) {
  return {int(id % n[0]), int((id / n[0]) % n[1]), int(id / (n[0] * n[1]))};
}

}  // namespace

Halo makeHalo(Mesh& mesh) {
  const std::optional<BlockPart> found = thisRanksPart(mesh.nx, mesh.ny, mesh.nz);
  if (!found) return Halo();
  const BlockPart& part = *found;
  if (long(mesh.n_cells) != part.held.cells() ||
      mesh.n_global_cells != part.dims[0] * long(part.dims[1]) * part.dims[2]) {
    throw std::logic_error(
        "makeHalo: the mesh is not this rank's part of its block (a generator must build "
        "BlockSpec::part = thisRanksPart(...))");
  }
  const std::array<long, 3> cells{part.dims[0], part.dims[1], part.dims[2]};
  const std::array<long, 3> nodes{cells[0] + 1, cells[1] + 1, cells[2] + 1};
  // local ids from global ids, by the held box's formula
  const auto local_cell = [&](long id) {
    const std::array<int, 3> at = blockIndex(id, cells);
    return Index(part.localCell(at[0], at[1], at[2]));
  };
  const auto local_node = [&](long id) {
    const std::array<int, 3> at = blockIndex(id, nodes);
    return Index(part.localNode(at[0], at[1], at[2]));
  };

  std::vector<long> cell_ids(std::size_t(mesh.n_cells)), node_ids(std::size_t(mesh.n_nodes));
  std::vector<int> cell_owner(cell_ids.size()), node_owner(node_ids.size());
  std::vector<int> outer_owner(cell_ids.size());  // the first layer's owners masked as this rank
  for (Index c = 0; c < mesh.n_cells; ++c) {
    const long id = mesh.cell_global(c);
    const std::array<int, 3> at = blockIndex(id, cells);
    cell_ids[std::size_t(c)] = id;
    cell_owner[std::size_t(c)] = part.cellOwner(at[0], at[1], at[2]);
    outer_owner[std::size_t(c)] = part.ghostLayer(at[0], at[1], at[2]) < kGhostLayers
                                      ? part.rank
                                      : cell_owner[std::size_t(c)];
  }
  for (Index n = 0; n < mesh.n_nodes; ++n) {
    const long id = mesh.node_global(n);
    const std::array<int, 3> at = blockIndex(id, nodes);
    node_ids[std::size_t(n)] = id;
    node_owner[std::size_t(n)] = part.nodeOwner(at[0], at[1], at[2]);
  }
  mesh.z_prisms = !parallel::any(!mesh.z_prisms);
  Halo halo;
  halo.cell_links = makeLinks(cell_ids, cell_owner, local_cell, "cell");
  // the outer layer's cells alone
  halo.outer_cell_links = makeLinks(cell_ids, outer_owner, local_cell, "outer_cell");
  halo.node_links = makeLinks(node_ids, node_owner, local_node, "node");
  return halo;
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

}  // namespace lagremap
