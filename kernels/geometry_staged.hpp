// The geometry at the end of a stage in the staged form (KernelForm::Staged,
// docs/method.md §7.6): the fused form's arithmetic (geometry.hpp) laid out
// for a GPU, one kernel, a cell to each thread of a team and its faces and
// corners in the lanes of a vector (cell_teams.hpp: 8 on a GPU, four cells a
// warp). Launched by stepLimitOverCellNodes below.
#pragma once

#include "../data/mesh.hpp"
#include "../data/state.hpp"
#include "cell_teams.hpp"
#include "cell_thermo.hpp"
#include "hex.hpp"
#include "time_step.hpp"

namespace lagremap {

namespace detail {

// A cell's row of its team's scratch memory. Lane f leaves face f's terms of
// the shape's sums (hex::sweptShape) and its 4 corner-face vectors; every
// lane then adds the first in the sweep's order, and lane p the 3 of corner p
// in face order, so the bits are the fused form's. The closure (one lane)
// leaves the corner impedance's coefficients for the corners' lanes.
namespace geometry_lanes {
// (enumerators, not constexpr variables: device code takes them by reference)
enum : int {
  kWeight = 0,        // 24: each triangle's weight q_k . T_k (hex::detail::addFaceToShape)
  kWeighted = 24,     // 24 x 3: ... times q_k + q_k+1 + fp
  kArea2 = 96,        // 6: each face's squared area
  kCornerFace = 102,  // 24 x 3: each face's corner-face vectors s_pf n_pf, in its node order
  kImpedance = 174,   // 2: CornerImpedance
  kColumns = 176,
};
}  // namespace geometry_lanes

using cell_teams::ScratchRow;
// A GPU's block of 128 threads, no spill on sm_90: the full stage end 5 an
// SM, at most 96 registers, 20 warps (a cell to a thread held 124, 16; at 80
// the closure spills 100 B); the remap's shape and checks 6 an SM, 80
// registers, 24 warps (118 and 16).
template <StageEnd kWhat>
using GeometryTeams =
    Kokkos::TeamPolicy<ExecSpace, Kokkos::LaunchBounds<128, kWhat == StageEnd::Full ? 5 : 6>>;
using GeometryMember = GeometryTeams<StageEnd::Full>::member_type;

// The stage end `kWhat` (StageEnd) of a mesh's cells, their time-step
// candidates reduced (a ghost cell's are its owner's to propose).
// `end_of_stage`: the nodes have just moved in a Lagrangian stage, so the
// closure's lane shares a mixed cell's volume change among its materials
// first (shareVolumeChange, as the fused form's closure does).
template <StageEnd kWhat>
struct StagedGeometry {
  CellNodesView cell_nodes;
  Vec3View x_n;
  DeviceView<int*> owned;
  State s;
  TimeStepControls controls;
  bool z_prisms;
  Index n_cells;
  bool end_of_stage;

  // The cell's shape, in every lane: a z prism's in closed form, a general
  // hexahedron's from the terms its face lanes leave (and with kWhat Full
  // their corner-face vectors).
  KOKKOS_INLINE_FUNCTION hex::CellShape shape(const GeometryMember& team, const NodesOfCell& nodes,
                                              const ScratchRow& row) const {
    using hex::detail::Point;
    if (z_prisms) {
      hex::PrismBase base;
      return hex::prismBase(nodes, base);
    }
    const auto point = [&](int n) { return hex::detail::nodePoint(nodes, n); };
    Kokkos::parallel_for(Kokkos::ThreadVectorRange(team, 6), [&](const int f) {
      hex::detail::FaceSweep<double> face;
      hex::detail::sweepFace(point, point(0), f, face);
      for (int k = 0; k < 4; ++k) {
        const int t = 4 * f + k;
        const double weight = hex::detail::triangleWeight(face, k);
        const Point<double> weighted = hex::detail::weightedTrianglePoint(face, k, weight);
        row(geometry_lanes::kWeight + t) = weight;
        row.store(geometry_lanes::kWeighted + 3 * t, Vec3{weighted.x, weighted.y, weighted.z});
      }
      row(geometry_lanes::kArea2 + f) = hex::detail::faceArea2(face);
      // (a loop of its own: in the one above, the closure spilled at 96
      // registers)
      if constexpr (kWhat == StageEnd::Full) {
        for (int k = 0; k < 4; ++k) {
          const Point<double> w = hex::detail::cornerFaceVector(face, k);
          row.store(geometry_lanes::kCornerFace + 3 * (4 * f + k), Vec3{w.x, w.y, w.z});
        }
      }
    });
    double six_volume = 0.0, max_area2 = 0.0;
    Point<double> weighted_sum{0.0, 0.0, 0.0};
    LAGREMAP_NO_UNROLL
    for (int t = 0; t < 24; ++t) {
      six_volume += row(geometry_lanes::kWeight + t);
      const Vec3 weighted = row.vec3(geometry_lanes::kWeighted + 3 * t);
      weighted_sum = weighted_sum + Point<double>{weighted.x, weighted.y, weighted.z};
    }
    LAGREMAP_NO_UNROLL
    for (int f = 0; f < 6; ++f) {
      const double area2 = row(geometry_lanes::kArea2 + f);
      max_area2 = area2 > max_area2 ? area2 : max_area2;
    }
    return hex::detail::shapeOfSums(point(0), six_volume, weighted_sum, max_area2);
  }

  // Corner p's sums: a z prism's from its nodes (each lane forms the base
  // again, 5 node loads, rather than pass it through scratch), a general
  // hexahedron's from its 3 corner-face vectors, added in the sweep's (face)
  // order.
  KOKKOS_INLINE_FUNCTION hex::CornerSums corner(const NodesOfCell& nodes, const ScratchRow& row,
                                                int p) const {
    using hex::detail::Point;
    if (z_prisms) {
      hex::PrismBase base;
      hex::prismBase(nodes, base);
      return hex::prismCorner(nodes, base, p);
    }
    return hex::cornerOfFaces(
        [&](int f, int k) {
          const Vec3 w = row.vec3(geometry_lanes::kCornerFace + 3 * (4 * f + k));
          return Point<double>{w.x, w.y, w.z};
        },
        p);
  }

  // Lane p: corner p's A_cp and M_cp.
  KOKKOS_INLINE_FUNCTION void corners(const GeometryMember& team, const NodesOfCell& nodes,
                                      const ScratchRow& row) const {
    Kokkos::parallel_for(Kokkos::ThreadVectorRange(team, 8), [&](const int p) {
      const CornerImpedance coefficients{row(geometry_lanes::kImpedance),
                                         row(geometry_lanes::kImpedance + 1)};
      storeCorner(s, 8 * nodes.c + p, coefficients, corner(nodes, row, p));
    });
  }

  // Cell c: its shape, then (one lane) its closure or the remap's checks,
  // then its corners. (Out of line on the host, where the staged form only
  // runs to be compared: inlined, it took the unit's inlining budget, and
  // GCC left hot functions of the fused kernels out of line.)
  LAGREMAP_OUT_OF_LINE KOKKOS_INLINE_FUNCTION void ofCell(const GeometryMember& team, Index c,
                                                          const ScratchRow& row,
                                                          StepLimit& best) const {
    const NodesOfCell nodes{cell_nodes, x_n, c};
    const hex::CellShape cell_shape = shape(team, nodes, row);
    // (one lane proposes: a team thread's lanes share one reduction value on
    // a GPU, Kokkos' CUDA team reduce)
    Kokkos::single(Kokkos::PerThread(team), [&] {
      StepLimit ghost{};
      StepLimit& proposed = owned(c) ? best : ghost;
      if constexpr (kWhat == StageEnd::Full) {
        const CornerImpedance coefficients =
            cellThermoOnShape(cell_shape, s, controls, c, proposed, end_of_stage, nullptr,
                              [](const CornerImpedance&) {});
        row(geometry_lanes::kImpedance) = coefficients.normal_part;
        row(geometry_lanes::kImpedance + 1) = coefficients.transverse;
      } else {
        cellShapeForRemap(cell_shape, s, c, proposed, nullptr, end_of_stage);
      }
    });
    if constexpr (kWhat == StageEnd::Full) corners(team, nodes, row);
  }

  KOKKOS_INLINE_FUNCTION void operator()(const GeometryMember& team, StepLimit& best) const {
    cell_teams::forCellsOfTeam(team, n_cells, kColumns,
                               [&](Index c, const ScratchRow& row) { ofCell(team, c, row, best); });
  }

  // (the remap's needs no corners)
  static constexpr int kColumns =
      kWhat == StageEnd::Full ? geometry_lanes::kColumns : geometry_lanes::kCornerFace;
  GeometryTeams<kWhat> policy() const {
    return cell_teams::overCells<GeometryTeams<kWhat>>(n_cells, kColumns);
  }
};

}  // namespace detail

// The stage end `kWhat` of a mesh's cells in the staged form
// (detail::StagedGeometry; `end_of_stage` there), the smallest time-step
// candidate left in `into` without waiting.
template <StageEnd kWhat>
static void stepLimitOverCellNodes(const char* label, const Mesh& mesh, const State& state,
                                   const TimeStepControls& controls, const StepLimitView& into,
                                   bool end_of_stage) {
  const detail::StagedGeometry<kWhat> staged{
      mesh.cell_nodes, mesh.x_n,      mesh.cell_owned, state,
      controls,        mesh.z_prisms, mesh.n_cells,    end_of_stage && state.n_materials > 1};
  Kokkos::parallel_reduce(label, staged.policy(), staged, StepLimitIntoView(into));
}

}  // namespace lagremap
