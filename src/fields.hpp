// Per-cell and per-node Views of any shape seen as (entity, component) rows,
// so the halo exchange and the checkpoint move "every field of the state"
// without naming each View's type (docs/method.md §7.5).
// Its kernel launchers are `static` (internal linkage: docs/method.md §7.2).
#pragma once

#include <functional>
#include <string>
#include <type_traits>
#include <vector>

#include "data/state.hpp"

namespace lagremap {

// pack: buffer(offset + i * components + j) = field(ids(i), component j);
// unpack: the reverse. Components are numbered row-major over the View's
// trailing extents ((material, tensor component) for a MatSym6View).
struct FieldRef {
  std::string name;
  int components = 0;
  std::function<void(const IndexView&ids, const RealView&buffer, Index offset)> pack, unpack;
};

namespace detail {
// Element (row e, component j) of a View of rank 1 to 3, by reference.
template <class ViewType>
struct RowAccess {
  ViewType view;
  int n2 = 1;  // last extent of a rank-3 View
  KOKKOS_INLINE_FUNCTION typename ViewType::reference_type operator()(Index e, int j) const {
    if constexpr (ViewType::rank == 1) {
      return view(e);
    } else if constexpr (ViewType::rank == 2) {
      return view(e, j);
    } else {
      return view(e, j / n2, j % n2);
    }
  }
};
}  // namespace detail

template <class ViewType>
static FieldRef fieldRef(const std::string& name, const ViewType& view) {
  constexpr int rank = int(ViewType::rank);
  static_assert(rank >= 1 && rank <= 3, "fieldRef: Views of rank 1 to 3");
  const int n1 = rank >= 2 ? int(view.extent(1)) : 1;
  const int n2 = rank >= 3 ? int(view.extent(2)) : 1;
  const detail::RowAccess<ViewType> element{view, n2};
  const int components = n1 * n2;
  FieldRef ref;
  ref.name = name;
  ref.components = components;
  ref.pack = [element, components](const IndexView& ids, const RealView& buffer, Index offset) {
    Kokkos::parallel_for(
        "lagremap::halo::pack", Kokkos::RangePolicy<ExecSpace>(0, ids.extent(0)),
        KOKKOS_LAMBDA(const Index i) {
          for (int j = 0; j < components; ++j) {
            buffer(offset + i * components + j) = element(ids(i), j);
          }
        });
  };
  ref.unpack = [element, components](const IndexView& ids, const RealView& buffer, Index offset) {
    Kokkos::parallel_for(
        "lagremap::halo::unpack", Kokkos::RangePolicy<ExecSpace>(0, ids.extent(0)),
        KOKKOS_LAMBDA(const Index i) {
          for (int j = 0; j < components; ++j) {
            element(ids(i), j) = buffer(offset + i * components + j);
          }
        });
  };
  return ref;
}

// Every per-cell field of the state (evolved and derived): after a halo
// exchange of these a ghost cell holds its owner's bits.
std::vector<FieldRef> cellStateFields(const State& state);
// The per-cell fields a checkpoint must hold: the derived ones follow from
// them through computeGeometry (dv/dt is kept for the time-step candidate).
std::vector<FieldRef> evolvedCellFields(const State& state);

// The halo's cell exchanges (docs/method.md §7.4): each moves the
// fields that kernels read in ghost cells, for owned results, before the
// next exchange, and that the ghosts cannot compute themselves. A ghost
// cell's geometry follows from its nodes, whose velocities its owners send
// (the node exchange), so it is computed, not sent. A stage is complete on
// the first ghost layer (its corner terms read the second layer's V, p and
// S, which are sent; its nodes' velocities are sent), so the first layer
// ends a stage with its owner's bits; the second layer's corner terms miss
// their outer neighbours, and its state is wrong until the remap's exchange
// (in lagrange mode for good: only its own kernels read it, and their results
// go to ghost nodes and to itself).
// - after the remap: the evolved state to both layers (evolvedCellFields
//   less the tensor the materials do not evolve; the next step's geometry and
//   closure derive the rest on every cell, as a restart does);
// - at the end of a stage with the closure (the predictor, a lagrange-mode
//   corrector), to the second layer only (Halo::exchangeOuterCells): V, p
//   and S_c, what the first layer's corner terms read of their neighbours;
// - at the end of a remap-mode corrector, to the second layer only: the
//   primitives the first layer's remap gradients read of their neighbours
//   that the stage changed (velocity, volume fractions, material energies,
//   the tensors the materials evolve).
std::vector<FieldRef> stageEndCellFields(const State& state);
std::vector<FieldRef> stageEndCellFieldsForRemap(const State& state);
std::vector<FieldRef> remappedCellFields(const State& state);

}  // namespace lagremap
