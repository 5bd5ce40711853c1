// The corner terms in the fused form (KernelForm::Fused, docs/method.md §7.6):
// per cell, V and sigma reconstructed at its nodes (corner_stencil.hpp), then
// B_cp = M_cp V_c(p) - sigma_c(p) A_cp (docs/method.md §A4), in one kernel,
// kCellLanes cells in the lanes of a vector where their stencils have one
// shape. Launched by computeCornerTerms (corner_terms.hpp).
#pragma once

#include "../data/mesh.hpp"
#include "../data/state.hpp"
#include "cell_lanes.hpp"
#include "corner_stencil.hpp"
#include "hex.hpp"
#include "step_start.hpp"

namespace lagremap {

namespace detail {

// The corner terms of one stage (computeCornerTerms, corner_terms.hpp) for the cells of
// the lanes of a Real.
struct CornerTerms {
  CellNodesView cell_nodes;
  CellFacesView neighbors;
  CellFacesView face_side;
  DeviceView<int[kNumSides]> side_kind;
  Vec3View x_n;
  State s;
  bool z_prisms, second_order, atomics;
  StepStartSave start;  // the first stage's: the cells' step start kept

  // The cells' stencils have one shape: the same StencilFace across each
  // face, and all solid or all fluid (what the lanes of a pack must share).
  KOKKOS_INLINE_FUNCTION bool lanesShareStencilShape(Index first, int count) const {
    const bool solid = s.aT_c(first) > 0.0;
    for (int i = 1; i < count; ++i) {
      if ((s.aT_c(first + i) > 0.0) != solid) return false;
    }
    for (int f = 0; f < 6; ++f) {
      const StencilFace face = stencilFace(neighbors, face_side, side_kind, first, f);
      for (int i = 1; i < count; ++i) {
        if (stencilFace(neighbors, face_side, side_kind, first + i, f) != face) return false;
      }
    }
    return true;
  }

  // Per cell: V and sigma reconstructed at its nodes, then B_cp = M_cp
  // V_c(p) - sigma_c(p) A_cp (computeCornerTerms). The lanes hold the cells
  // first, first + 1, ...
  template <class Real>
  KOKKOS_INLINE_FUNCTION void ofCells(Index first) const {
    CellLanes<Real> cells;
    for (int i = 0; i < kLanesOf<Real>; ++i) cells.cell[i] = first + i;
    const Vec3Of<Real> v_cell = loadVec3Lanes(s.v_c, cells);
    const Real p_cell = loadLanes(s.p_c, cells);
    const bool solid = s.aT_c(first) > 0.0;  // some material with strength in the cell
    const SymMat3Of<Real> sigma_cell =
        solid ? loadSymLanes(s.S_c, cells) + identitySym(-p_cell) : identitySym(-p_cell);
    VertexVectorsOf<Real> v_node;
    Real p_node[kHexVertices];       // fluid: sigma = -p I
    VertexTensors<Real> sigma_node;  // solid
    if (!second_order) {
      for (int p = 0; p < kHexVertices; ++p) {
        v_node.set(p, v_cell);
        p_node[p] = p_cell;
        sigma_node.set(p, sigma_cell);
      }
    } else {
      Vec3Of<Real> x[8];
      for (int p = 0; p < 8; ++p) {
        CellLanes<Real> node;
        for (int i = 0; i < kLanesOf<Real>; ++i) node.cell[i] = cell_nodes(cells.cell[i], p);
        x[p] = loadVec3Lanes(x_n, node);
      }
      Index nb[6][kLanesOf<Real>];
      StencilFace faces[6];
      for (int f = 0; f < 6; ++f) {
        faces[f] = stencilFace(neighbors, face_side, side_kind, first, f);
        for (int i = 0; i < kLanesOf<Real>; ++i) nb[f][i] = neighbors(cells.cell[i], f);
      }
      const Vec3Of<Real> centroid = loadVec3Lanes(s.x_c, cells);
      CornerStencil<Real> stencil(p_cell);
      gatherStencil(s, nb, faces, z_prisms, centroid, x, v_cell, p_cell, sigma_cell, solid,
                    stencil);
      const SymMat3Of<Real> inv = stencil.lsq.solver();
      VertexVectorsOf<Real> offsets;
      LAGREMAP_LANES
      for (int p = 0; p < kHexVertices; ++p) offsets.set(p, x[p] - centroid);
      const Real sound_speed = loadLanes(s.aL_c, cells);
      const Real stress_scale = loadLanes(s.rho_c, cells) * sound_speed * sound_speed;
      if (z_prisms) {  // the bottom vertices, then the top ones repeat them
        reconstructAtVertices<4>(stencil, inv, offsets, v_cell, p_cell, sigma_cell, sound_speed,
                                 stress_scale, solid, v_node, p_node, sigma_node);
        repeatBottomVertices(solid, v_node, p_node, sigma_node);
      } else {
        reconstructAtVertices<kHexVertices>(stencil, inv, offsets, v_cell, p_cell, sigma_cell,
                                            sound_speed, stress_scale, solid, v_node, p_node,
                                            sigma_node);
      }
    }

    // B_cp = M_cp V_c(p) - sigma_c(p) A_cp (a loop per case: the compiler
    // does not take the tests out of the loop by itself)
    const auto storeRhs = [&](int p, const CellLanes<Real>& corners,
                              const Vec3Of<Real>& stress_force) {
      storeVec3Lanes(s.B_cp, corners, loadSymLanes(s.M_cp, corners) * v_node[p] + stress_force);
    };
    for (int p = 0; p < 8; ++p) {
      CellLanes<Real> corners;
      for (int i = 0; i < kLanesOf<Real>; ++i) corners.cell[i] = 8 * cells.cell[i] + p;
      if (solid) {
        storeRhs(p, corners, -(sigma_node[p] * loadVec3Lanes(s.A_cp, corners)));
      } else {
        storeRhs(p, corners, p_node[p] * loadVec3Lanes(s.A_cp, corners));
      }
    }
    if (atomics) {
      for (int i = 0; i < kLanesOf<Real>; ++i) {
        for (int p = 0; p < 8; ++p) {
          const Index corner = 8 * cells.cell[i] + p, node = cell_nodes(cells.cell[i], p);
          for (int j = 0; j < 6; ++j) Kokkos::atomic_add(&s.M_n(node, j), s.M_cp(corner, j));
          for (int j = 0; j < 3; ++j) Kokkos::atomic_add(&s.B_n(node, j), s.B_cp(corner, j));
        }
      }
    }
  }
};

}  // namespace detail

}  // namespace lagremap
