// The corner terms of a stage (docs/method.md §A4, §A5), computeCornerTerms:
// per cell, V and sigma reconstructed at its nodes and B_cp = M_cp V_c(p) -
// sigma_c(p) A_cp (the corner vectors A_cp and impedances M_cp come from
// computeGeometry), in the fused form (corner_terms_fused.hpp) or the staged
// one (corner_terms_staged.hpp); with `Gather::Atomics` it also scatters the
// node sums M_n, B_n. The node solve (nodal_solver.hpp) follows.
// Its kernel launchers are `static` (internal linkage: docs/method.md §7.2).
#pragma once

#include "../data/mesh.hpp"
#include "../data/state.hpp"
#include "corner_controls.hpp"
#include "corner_terms_fused.hpp"
#include "corner_terms_staged.hpp"
#include "geometry.hpp"
#include "hex.hpp"
#include "kernel_form.hpp"

namespace lagremap {

namespace detail {

// The corner terms of a mesh's cells under `controls`.
inline CornerTerms cornerTerms(const Mesh& mesh, const State& state, const CornerControls& controls,
                               const StepStartSave& start = {}) {
  return {mesh.cell_nodes,
          mesh.cell_neighbors,
          mesh.cell_face_side,
          mesh.side_kind,
          mesh.x_n,
          state,
          mesh.z_prisms,
          controls.order >= 2,
          controls.gather == Gather::Atomics,
          start};
}

}  // namespace detail

// The fused form: one kernel, cells in the lanes of a vector where they can.
// (a template: instantiated where it is called, never in a device build)
template <class Terms>
static void computeFusedCornerTerms(const Mesh& mesh, const Terms& terms) {
  const Index n_cells = mesh.n_cells;
  Kokkos::parallel_for(
      "lagremap::corners::reconstruct_and_impedance",
      Kokkos::RangePolicy<ExecSpace>(0, cellChunks(mesh)), KOKKOS_LAMBDA(const Index chunk) {
        const Index first = chunk * hex::kCellLanes;
        const int count = chunkCells(n_cells, first);
        if (terms.start.cells) {
          for (int i = 0; i < count; ++i) {
            copyCellStart(terms.s, first + i, terms.start.solids, StepStart::Save);
          }
        }
#if LAGREMAP_CELL_PACKS
        if (count == hex::kCellLanes && terms.second_order &&
            terms.lanesShareStencilShape(first, count)) {
          terms.template ofCells<hex::CellPack>(first);
          return;
        }
#endif
        for (int i = 0; i < count; ++i) terms.template ofCells<double>(first + i);
      });
}

// Per cell: V and sigma reconstructed at its nodes (docs/method.md §A5: piecewise
// constant at first order; second order: least-squares gradients limited by
// one frame-independent factor each, a solid's whole Cauchy stress as a
// tensor, a fluid's pressure as a scalar), then B_cp = M_cp V_c(p) -
// sigma_c(p) A_cp. In the fused form (built on CPU backends only) the cells
// go kCellLanes at a time in the lanes of a vector where their stencils have
// one shape; in the staged form a cell's faces, vertices and corners go in
// the lanes of a vector (the same bits either way, docs/method.md §7.1, §7.6).
// `start`: a step's first stage also keeps the cells' step start
// (StepStartSave), which the cell update then reads.
static inline void computeCornerTerms(const Mesh& mesh, const State& state,
                                      const CornerControls& controls,
                                      KernelForm form = defaultKernelForm(),
                                      const StepStartSave& start = {}) {
  const detail::CornerTerms terms = detail::cornerTerms(mesh, state, controls, start);
  if (terms.atomics) {
    Kokkos::deep_copy(state.M_n, 0.0);
    Kokkos::deep_copy(state.B_n, 0.0);
  }
  if constexpr (kFusedKernelsBuilt) {
    if (form == KernelForm::Fused) return computeFusedCornerTerms(mesh, terms);
  }
  const detail::StagedCorners staged{
      terms.cell_nodes, terms.neighbors,    terms.face_side, terms.side_kind, terms.x_n,  terms.s,
      terms.z_prisms,   terms.second_order, terms.atomics,   mesh.n_cells,    terms.start};
  Kokkos::parallel_for("lagremap::corners::reconstruct_and_impedance", staged.policy(), staged);
}

}  // namespace lagremap
