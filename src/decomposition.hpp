// MPI domain decomposition (docs/method.md §7.5): each rank builds only its part of
// the generated block (BlockPart, src/block_part.hpp: its owned box of cells
// plus kGhostLayers layers round it, and their nodes, numbered in increasing
// global id), and the halo links the parts. After each nodal solve the ghost
// nodes, and after each cell update or remap the ghost cells, receive their
// owners' values (the lean lists of src/fields.hpp), so every stage starts
// with what it reads exact.
#pragma once

#include <array>
#include <vector>

#include "block_part.hpp"
#include "data/mesh.hpp"
#include "fields.hpp"

namespace lagremap {

class Halo {
 public:
  Halo() = default;  // one rank: nothing to exchange

  // Ghost cells (resp. nodes) get their owners' values of `fields`.
  void exchangeCells(const std::vector<FieldRef>& fields) const;
  void exchangeNodes(const std::vector<FieldRef>& fields) const;
  // Only the ghost cells of the outer layer (kGhostLayers cells from the
  // owned box): what the first layer does not compute itself
  // (docs/method.md §7.4).
  void exchangeOuterCells(const std::vector<FieldRef>& fields) const;

  struct Link {
    int rank = 0;
    IndexView send, recv;  // local ids, in the order both sides agree on (global id)
  };
  std::vector<Link> cell_links, node_links;
  std::vector<Link> outer_cell_links;  // the outer ghost layer's cells only

  // What this rank has sent so far, in cell and in node exchanges.
  struct Traffic {
    long messages = 0;
    double bytes = 0.0;
  };
  const Traffic& cellTraffic() const { return cell_traffic_; }
  const Traffic& nodeTraffic() const { return node_traffic_; }

 private:
  void exchange(const std::vector<Link>& links, const std::vector<FieldRef>& fields,
                Traffic& traffic) const;
  mutable Traffic cell_traffic_, node_traffic_;
  mutable RealView send_buffer_, recv_buffer_;
  mutable RealView::HostMirror send_host_, recv_host_;  // the same Views on host backends
};

// The halo of this rank's part (a mesh built with BlockSpec::part =
// thisRanksPart(...)): which ghost cells and nodes each other rank owns, and
// which of ours it holds, agreed by exchanging global ids. It also takes the
// decisions that must be the whole block's: Mesh::z_prisms, a prism where
// every part's cells are (the prism formulas differ from the general ones in
// round-off, and results may not depend on the rank count). Collective (the
// generators are not: an error one rank finds in its part cannot leave the
// others waiting); one rank: no links. Throws std::logic_error for a mesh
// that is not this rank's part (a generator that built the whole block).
Halo makeHalo(Mesh& mesh);

// Every rank's owned rows (global id, `components` doubles each) on every rank.
void allgatherRows(const std::vector<long>& ids, const std::vector<double>& rows, int components,
                   std::vector<long>& all_ids, std::vector<double>& all_rows);

// A host copy of a per-cell (cells = true) or per-node field of a decomposed
// run, indexed by global id: every rank's owned rows, on every rank.
template <class HostViewT>
HostViewT gatherGlobal(const HostViewT& local, const Mesh& mesh, bool cells) {
  constexpr int rank = int(HostViewT::rank);
  const int n1 = rank >= 2 ? int(local.extent(1)) : 1;
  const int n2 = rank >= 3 ? int(local.extent(2)) : 1;
  const int components = n1 * n2;
  const auto owned =
      Kokkos::create_mirror_view_and_copy(HostSpace(), cells ? mesh.cell_owned : mesh.node_owned);
  const auto& global_id = cells ? mesh.cell_global : mesh.node_global;
  const long n_global = cells ? mesh.n_global_cells : mesh.n_global_nodes;
  const detail::RowAccess<HostViewT> element{local, n2};
  std::vector<long> ids, all_ids;
  std::vector<double> rows, all_rows;
  if (local.extent(0) > 0) {
    for (std::size_t e = 0; e < owned.extent(0); ++e) {
      if (!owned(e)) continue;
      ids.push_back(global_id(e));
      for (int j = 0; j < components; ++j) rows.push_back(element(Index(e), j));
    }
  }
  allgatherRows(ids, rows, components, all_ids, all_rows);
  const std::size_t n_rows = local.extent(0) > 0 ? std::size_t(n_global) : 0;
  HostViewT global;
  if constexpr (HostViewT::rank_dynamic == 1) {
    global = HostViewT(local.label(), n_rows);
  } else {
    static_assert(HostViewT::rank_dynamic == 2,
                  "gatherGlobal: (entity) or (entity, material) Views");
    global = HostViewT(local.label(), n_rows, local.extent(1));
  }
  const detail::RowAccess<HostViewT> out{global, n2};
  for (std::size_t i = 0; i < all_ids.size(); ++i)
    for (int j = 0; j < components; ++j) out(Index(all_ids[i]), j) = all_rows[i * components + j];
  return global;
}

}  // namespace lagremap
