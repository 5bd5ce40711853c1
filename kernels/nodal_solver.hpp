// Nodal solver and corner forces (docs/method.md §A4), in three kernels per stage (the
// corner vectors A_cp and impedances M_cp come from computeGeometry):
//   computeCornerTerms: per cell, reconstruct V and sigma at the nodes and
//                       B_cp = M_cp V_c(p) - sigma_c(p) A_cp;
//   nodalSolve:         per node, M_p V_p = B_p + external load under the
//                       velocity constraints, and the node's new position
//                       (into x_n_next: x_n is still read for the traction
//                       load of neighbouring nodes; the caller swaps them);
//   updateCells:        per cell, F_cp = M_cp V_p - B_cp, momentum and energy.
// The node sums use the node->corner CRS by default (race-free, bit-for-bit
// reproducible for any thread count); `Gather::Atomics` scatters instead.
// Its kernel launchers are `static` (internal linkage: docs/method.md §7.2).
#pragma once

#include "../data/mesh.hpp"
#include "../data/state.hpp"
#include "constitutive.hpp"
#include "geometry.hpp"
#include "hex.hpp"
#include "reconstruction.hpp"

namespace lagremap {

enum class Gather { Crs, Atomics };

struct CornerControls {
  int order = 2;  // 1: piecewise constant, 2: limited linear reconstruction
  Gather gather = Gather::Crs;
};

namespace detail {

// The corner kernel is written for a scalar Real (reconstruction.hpp): a
// double, one cell, or on CPU builds a CellPack, kCellLanes consecutive cells
// whose stencils have the same shape (lanesShareStencilShape), in the lanes of
// one vector. Its loads and stores go lane by lane.
template <class Real>
constexpr int kLanesOf = 1;
#if LAGREMAP_CELL_PACKS
template <>
constexpr int kLanesOf<hex::CellPack> = hex::kCellLanes;
#endif

// The lanes' cells: cell[i] of lane i.
template <class Real>
struct CellLanes {
  Index cell[kLanesOf<Real>];
};

// value(i) of every lane i.
template <class Real, class Value>
KOKKOS_FORCEINLINE_FUNCTION Real gatherLanes(const Value& value) {
  if constexpr (kLanesOf<Real> == 1) {
    return value(0);
  } else {
    Real lanes;
    for (int i = 0; i < kLanesOf<Real>; ++i) lanes[i] = value(i);
    return lanes;
  }
}
template <class Real>
KOKKOS_FORCEINLINE_FUNCTION double laneOf(const Real& value, int i) {
  if constexpr (kLanesOf<Real> == 1) {
    return value;
  } else {
    return value[i];
  }
}
template <class Real, class View>
KOKKOS_FORCEINLINE_FUNCTION Real loadLanes(const View& v, const CellLanes<Real>& at) {
  return gatherLanes<Real>([&](int i) { return v(at.cell[i]); });
}
template <class Real, class View>
KOKKOS_FORCEINLINE_FUNCTION Vec3Of<Real> loadVec3Lanes(const View& v, const CellLanes<Real>& at) {
  return {gatherLanes<Real>([&](int i) { return v(at.cell[i], 0); }),
          gatherLanes<Real>([&](int i) { return v(at.cell[i], 1); }),
          gatherLanes<Real>([&](int i) { return v(at.cell[i], 2); })};
}
template <class Real, class View>
KOKKOS_FORCEINLINE_FUNCTION SymMat3Of<Real> loadSymLanes(const View& v, const CellLanes<Real>& at) {
  SymMat3Of<Real> m;
  Real* entries[6] = {&m.xx, &m.yy, &m.zz, &m.xy, &m.yz, &m.xz};
  for (int j = 0; j < 6; ++j)
    *entries[j] = gatherLanes<Real>([&](int i) { return v(at.cell[i], j); });
  return m;
}
template <class Real, class View>
KOKKOS_FORCEINLINE_FUNCTION void storeVec3Lanes(const View& v, const CellLanes<Real>& at,
                                                const Vec3Of<Real>& a) {
  for (int i = 0; i < kLanesOf<Real>; ++i) {
    v(at.cell[i], 0) = laneOf(a.x, i);
    v(at.cell[i], 1) = laneOf(a.y, i);
    v(at.cell[i], 2) = laneOf(a.z, i);
  }
}

KOKKOS_FORCEINLINE_FUNCTION double magnitude(double v) {
  return math::fabs(v);
}
#if LAGREMAP_CELL_PACKS
KOKKOS_FORCEINLINE_FUNCTION hex::CellPack magnitude(hex::CellPack v) {
  return v < 0.0 ? -v : v;
}
#endif

// What stands across face f of a cell in its reconstruction stencil
// (docs/method.md §A5, §2.1): a neighbour; across a wall, the cell's mirror image; nothing
// (a free side: a zero jump).
enum class StencilFace : unsigned char { Neighbour, Mirror, None };

template <class Neighbors, class FaceSide, class SideKind>
KOKKOS_FORCEINLINE_FUNCTION StencilFace stencilFace(const Neighbors& neighbors,
                                                    const FaceSide& face_side,
                                                    const SideKind& side_kind, Index c, int f) {
  if (neighbors(c, f) >= 0) return StencilFace::Neighbour;
  const int side = face_side(c, f);
  return side >= 0 && side_kind(side) == int(BoundaryKind::Wall) ? StencilFace::Mirror
                                                                 : StencilFace::None;
}

// Mirror image across a wall face: offset to the ghost centroid, the jump of
// the velocity (normal component reversed) and the face's unit normal (for the
// stress's mirror jump); the pressure is continuous.
// (node(n): the position of the cell's node n)
template <class Real, class NodeAt>
KOKKOS_INLINE_FUNCTION void mirrorAcrossFace(const NodeAt& node, int f,
                                             const Vec3Of<Real>& centroid,
                                             const Vec3Of<Real>& velocity, Vec3Of<Real>& offset,
                                             Vec3Of<Real>& velocity_jump, Vec3Of<Real>& normal) {
  Vec3Of<Real> q[4];
  for (int k = 0; k < 4; ++k) q[k] = node(hex::faceNode(f, k));
  const Vec3Of<Real> area = 0.5 * cross(q[2] - q[0], q[3] - q[1]);  // hex::faceArea
  normal = (1.0 / hex::detail::laneSqrt(dot(area, area))) * area;
  const Vec3Of<Real> face_point = 0.25 * (q[0] + q[1] + q[2] + q[3]);
  offset = (2.0 * dot(face_point - centroid, normal)) * normal;
  velocity_jump = (-2.0 * dot(velocity, normal)) * normal;
}

template <class Real>
KOKKOS_FORCEINLINE_FUNCTION Vec3Of<Real> zeroVec3() {
  return {Real{}, Real{}, Real{}};
}

// The limiters' jump across an open side (StencilFace::None: a free,
// traction or fixed boundary, no value beyond it) is the linear
// continuation of the field: the opposite face's jump reversed (faces f and
// f ^ 1 are opposite). With no jump there, a field varying along the
// boundary normal was limited to first order in every boundary cell (phi = 0
// for a linear one: its boundary vertices lie beyond every neighbour's
// value), and the velocity jumps at the node then dissipated the rod's
// radial flow (docs/method.md §2.3). `open(f)`: face f is an open side.
template <class Jump, class IsOpen>
KOKKOS_FORCEINLINE_FUNCTION void continueAcrossOpenSides(const IsOpen& open, Jump jumps[6]) {
  for (int f = 0; f < 6; ++f) {
    if (open(f) && !open(f ^ 1)) jumps[f] = -1.0 * jumps[f ^ 1];
  }
}

// The face-neighbour stencil of a cell for the reconstruction (docs/method.md §A5):
// the least-squares normal matrix, the right-hand sides of V and of the
// pressure (a fluid) or the Cauchy stress (a solid), and the neighbour jumps
// the limiters measure against. Across a wall the neighbour is the cell's
// mirror image; a free side leaves a zero jump.
template <class Real>
struct CornerStencil {
  LeastSquaresOf<Real> lsq;
  Vec3Of<Real> rhs_v[3] = {zeroVec3<Real>(), zeroVec3<Real>(), zeroVec3<Real>()};
  Vec3Of<Real> rhs_p = zeroVec3<Real>();
  Vec3Of<Real> rhs_sigma[6];  // (a solid's only)
  Vec3Of<Real> dv_nb[6];
  SymMat3Of<Real> dsigma_nb[6];
  BoundsOf<Real> pb;
  KOKKOS_INLINE_FUNCTION explicit CornerStencil(Real p_cell) : pb(p_cell) {}
};

// The stencil of the lanes' cells, whose faces f all have the same
// `faces[f]`. `z_prism`: the cells are prisms along z (Mesh::z_prisms),
// whose z faces lie in the planes z_0 and z_0 + h: their mirror images are h
// away along -+e_z.
template <class Real>
KOKKOS_FORCEINLINE_FUNCTION void gatherStencil(
    const State& s, const Index nb[6][kLanesOf<Real>], const StencilFace faces[6], bool z_prism,
    const Vec3Of<Real>& centroid, const Vec3Of<Real> x[8], const Vec3Of<Real>& v_cell,
    const Real& p_cell, const SymMat3Of<Real>& sigma_cell, bool solid, CornerStencil<Real>& st) {
  for (int i = 0; i < (solid ? 6 : 0); ++i) st.rhs_sigma[i] = zeroVec3<Real>();
  for (int f = 0; f < 6; ++f) {
    Vec3Of<Real> dx, dv, normal;
    Real dp{};
    SymMat3Of<Real> dsigma = identitySym(Real{});
    if (faces[f] == StencilFace::Neighbour) {
      CellLanes<Real> across;
      for (int i = 0; i < kLanesOf<Real>; ++i) across.cell[i] = nb[f][i];
      dx = loadVec3Lanes(s.x_c, across) - centroid;
      dv = loadVec3Lanes(s.v_c, across) - v_cell;
      const Real p_across = loadLanes(s.p_c, across);
      dp = p_across - p_cell;
      // a fluid neighbour's S_c is zero
      if (solid) dsigma = loadSymLanes(s.S_c, across) + identitySym(-p_across) - sigma_cell;
    } else if (faces[f] == StencilFace::Mirror) {
      if (z_prism && f >= 4) {
        const double side = f == 4 ? -1.0 : 1.0;
        normal = Vec3Of<Real>{Real{}, Real{}, splat<Real>(side)};
        dx = Vec3Of<Real>{Real{}, Real{}, side * (x[4].z - x[0].z)};
        dv = Vec3Of<Real>{Real{}, Real{}, -2.0 * v_cell.z};
      } else {
        mirrorAcrossFace([&](int n) { return x[n]; }, f, centroid, v_cell, dx, dv, normal);
      }
      if (solid) dsigma = mirrorJump(sigma_cell, normal);
    } else {
      st.dv_nb[f] = zeroVec3<Real>();
      if (solid) st.dsigma_nb[f] = identitySym(Real{});
      continue;
    }
    st.lsq.addOffset(dx);
    st.rhs_v[0] += dv.x * dx;
    st.rhs_v[1] += dv.y * dx;
    st.rhs_v[2] += dv.z * dx;
    st.dv_nb[f] = dv;
    if (solid) {
      st.rhs_sigma[0] += dsigma.xx * dx;
      st.rhs_sigma[1] += dsigma.yy * dx;
      st.rhs_sigma[2] += dsigma.zz * dx;
      st.rhs_sigma[3] += dsigma.xy * dx;
      st.rhs_sigma[4] += dsigma.yz * dx;
      st.rhs_sigma[5] += dsigma.xz * dx;
      st.dsigma_nb[f] = dsigma;
    } else {
      st.rhs_p += dp * dx;
      st.pb.include(p_cell + dp);
    }
  }
  const auto open = [&](int f) { return faces[f] == StencilFace::None; };
  continueAcrossOpenSides(open, st.dv_nb);
  if (solid) continueAcrossOpenSides(open, st.dsigma_nb);
}

// Node velocities: the least-squares gradient, limited as a vector by one
// frame-independent factor (projectedLimiter, docs/method.md §2.3; edge and
// corner neighbours for V only) and by the acoustic bound |dV| <= aL: a
// larger excursion is a discontinuity the linear profile cannot hold, which
// a near-vacuum gas cannot afford in its dissipation (docs/method.md §2.5).
// Squared norms compared: one square root per cell. The vertices' values
// are computed in lanes (VertexVectors), the same numbers as vertex by vertex.
// kVertices = 4: a z prism's bottom vertices only (computeCornerTerms).
template <int kVertices, class Real>
KOKKOS_FORCEINLINE_FUNCTION void limitedNodeVelocities(const CornerStencil<Real>& st,
                                                       const SymMat3Of<Real>& inv,
                                                       const VertexVectorsOf<Real>& offsets,
                                                       const Vec3Of<Real>& v_cell,
                                                       const Real& sound_speed, bool solid,
                                                       VertexVectorsOf<Real>& v_node) {
  const Vec3Of<Real> grad_v[3] = {inv * st.rhs_v[0], inv * st.rhs_v[1], inv * st.rhs_v[2]};
  VertexVectorsOf<Real> dv_node;
  dotEach<kVertices>(grad_v[0], offsets, dv_node.x);
  dotEach<kVertices>(grad_v[1], offsets, dv_node.y);
  dotEach<kVertices>(grad_v[2], offsets, dv_node.z);
  Real length2[kHexVertices];
  dotEach<kVertices>(dv_node, dv_node, length2);
  const Real phi_v = solid ? projectedLimiter<true, true, kVertices>(st.dv_nb, dv_node, length2)
                           : projectedLimiter<false, true, kVertices>(st.dv_nb, dv_node, length2);
  Real longest2{};
  for (int p = 0; p < kVertices; ++p) longest2 = length2[p] > longest2 ? length2[p] : longest2;
  const Real phi = phi_v * phi_v * longest2 > sound_speed * sound_speed
                       ? sound_speed / hex::detail::laneSqrt(longest2)
                       : phi_v;
  LAGREMAP_LANES
  for (int p = 0; p < kVertices; ++p) {
    v_node.x[p] = v_cell.x + phi * dv_node.x[p];
    v_node.y[p] = v_cell.y + phi * dv_node.y[p];
    v_node.z[p] = v_cell.z + phi * dv_node.z[p];
  }
}

// The six components xx, yy, zz, xy, yz, xz of a symmetric tensor at the 8
// vertices, in lanes.
template <class Real>
struct VertexTensors {
  Real c[6][kHexVertices];
  KOKKOS_INLINE_FUNCTION SymMat3Of<Real> operator[](int p) const {
    return {c[0][p], c[1][p], c[2][p], c[3][p], c[4][p], c[5][p]};
  }
  KOKKOS_INLINE_FUNCTION void set(int p, const SymMat3Of<Real>& t) {
    c[0][p] = t.xx;
    c[1][p] = t.yy;
    c[2][p] = t.zz;
    c[3][p] = t.xy;
    c[4][p] = t.yz;
    c[5][p] = t.xz;
  }
};

// A solid's node stresses: the whole Cauchy stress limited as a tensor by one
// factor (pulled-back jumps, projectedLimiter with the plateau guard) and the
// acoustic bound |d sigma| <= rho aL^2; the unlimited excursions G d_p give
// both the node values and the limiter's lengths.
template <int kVertices, class Real>
KOKKOS_FORCEINLINE_FUNCTION void limitedNodeStresses(
    const CornerStencil<Real>& st, const SymMat3Of<Real>& inv, const VertexVectorsOf<Real>& offsets,
    const SymMat3Of<Real>& sigma_cell, const Real& stress_scale, VertexTensors<Real>& sigma_node) {
  Vec3Of<Real> grad_sigma[6];
  for (int i = 0; i < 6; ++i) grad_sigma[i] = inv * st.rhs_sigma[i];
  VertexTensors<Real> excursion;
  for (int i = 0; i < 6; ++i) dotEach<kVertices>(grad_sigma[i], offsets, excursion.c[i]);
  Real length2[kHexVertices], largest2{};
  LAGREMAP_LANES
  for (int p = 0; p < kVertices; ++p) {  // ddot(excursion_p, excursion_p)
    const Real(&e)[6][kHexVertices] = excursion.c;
    length2[p] = e[0][p] * e[0][p] + e[1][p] * e[1][p] + e[2][p] * e[2][p] +
                 2.0 * (e[3][p] * e[3][p] + e[4][p] * e[4][p] + e[5][p] * e[5][p]);
  }
  for (int p = 0; p < kVertices; ++p) largest2 = length2[p] > largest2 ? length2[p] : largest2;
  Vec3Of<Real> pulled[6];
  pullBack(grad_sigma, st.dsigma_nb, pulled);
  Real phi_sigma = projectedLimiter<true, false, kVertices>(pulled, offsets, length2);
  phi_sigma = phi_sigma * phi_sigma * largest2 > stress_scale * stress_scale
                  ? stress_scale / hex::detail::laneSqrt(largest2)
                  : phi_sigma;
  const Real cell[6] = {sigma_cell.xx, sigma_cell.yy, sigma_cell.zz,
                        sigma_cell.xy, sigma_cell.yz, sigma_cell.xz};
  for (int i = 0; i < 6; ++i) {
    LAGREMAP_LANES
    for (int p = 0; p < kVertices; ++p) {
      sigma_node.c[i][p] = cell[i] + phi_sigma * excursion.c[i][p];
    }
  }
}

// A fluid's node pressures: Barth-Jespersen in its two-division form (the
// same phi as projectedLimiter<false, false>) and the acoustic bound
// |dp| <= rho aL^2.
template <int kVertices, class Real>
KOKKOS_FORCEINLINE_FUNCTION void limitedNodePressures(const CornerStencil<Real>& st,
                                                      const SymMat3Of<Real>& inv,
                                                      const VertexVectorsOf<Real>& offsets,
                                                      const Real& p_cell, const Real& stress_scale,
                                                      Real p_node[kHexVertices]) {
  const Vec3Of<Real> grad_p = inv * st.rhs_p;
  Real dp_node[kHexVertices];
  dotEach<kVertices>(grad_p, offsets, dp_node);
  VertexExcursionOf<Real> excursion;
  Real largest{};
  for (int p = 0; p < kVertices; ++p) {
    excursion.include(dp_node[p]);
    const Real size = magnitude(dp_node[p]);
    largest = size > largest ? size : largest;
  }
  Real phi_p = cellLimiter(excursion, p_cell, st.pb, 1.0);
  phi_p = phi_p * largest > stress_scale ? stress_scale / largest : phi_p;
  LAGREMAP_LANES
  for (int p = 0; p < kVertices; ++p) p_node[p] = p_cell + phi_p * dp_node[p];
}

// V and sigma at the vertices p < kVertices: the limited reconstructions
// above from the cell's stencil.
template <int kVertices, class Real>
KOKKOS_FORCEINLINE_FUNCTION void reconstructAtVertices(
    const CornerStencil<Real>& stencil, const SymMat3Of<Real>& inv,
    const VertexVectorsOf<Real>& offsets, const Vec3Of<Real>& v_cell, const Real& p_cell,
    const SymMat3Of<Real>& sigma_cell, const Real& sound_speed, const Real& stress_scale,
    bool solid, VertexVectorsOf<Real>& v_node, Real p_node[kHexVertices],
    VertexTensors<Real>& sigma_node) {
  limitedNodeVelocities<kVertices>(stencil, inv, offsets, v_cell, sound_speed, solid, v_node);
  if (solid) {
    limitedNodeStresses<kVertices>(stencil, inv, offsets, sigma_cell, stress_scale, sigma_node);
  } else {
    limitedNodePressures<kVertices>(stencil, inv, offsets, p_cell, stress_scale, p_node);
  }
}

// A z prism's top vertices (4-7) take the values of the bottom ones below
// them (0-3). Its stencil is symmetric across the mid-plane: its in-plane
// neighbours' centroids are on the cell's, and its two z faces are walls, so
// the gradients' z components are exactly zero (the two mirror images' jumps
// cancel in the least-squares right-hand sides, and the normal matrix has no
// xz, yz entries): the top vertices' excursions g . (d_p + h e_z) are the
// bottom ones' to the bit, and every limiter is a minimum over the same
// numbers. Computing the bottom four alone gives the same values for half
// the vertex lanes (performance.md §3.1).
template <class Real>
KOKKOS_FORCEINLINE_FUNCTION void repeatBottomVertices(bool solid, VertexVectorsOf<Real>& v_node,
                                                      Real p_node[kHexVertices],
                                                      VertexTensors<Real>& sigma_node) {
  for (int p = 0; p < 4; ++p) {
    v_node.x[p + 4] = v_node.x[p];
    v_node.y[p + 4] = v_node.y[p];
    v_node.z[p + 4] = v_node.z[p];
    if (solid) {
      for (int i = 0; i < 6; ++i) sigma_node.c[i][p + 4] = sigma_node.c[i][p];
    } else {
      p_node[p + 4] = p_node[p];
    }
  }
}

// The corner terms of one stage (computeCornerTerms below) for the cells of
// the lanes of a Real.
struct CornerTerms {
  CellNodesView cell_nodes;
  CellFacesView neighbors;
  CellFacesView face_side;
  DeviceView<int[kNumSides]> side_kind;
  Vec3View x_n;
  State s;
  bool z_prisms, second_order, atomics;

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

// The staged form of the corner terms (KernelForm::Staged, docs/method.md
// §7.6): the fused form's arithmetic in three kernels that each hold a part
// of it. The velocity limiter, then the stress (or pressure) limiter, each
// from its own pass over the stencil, store a cell's gradients and limiter
// factors in a row of CornerRows; the corner kernel then forms each node's
// values and B_cp one corner at a time. The limiters visit one vertex at a
// time (projectedLimiterByVertex) in the fused form's vertex order, so every
// minimum and maximum is over the same numbers: the same bits.
namespace corner_rows {
// (enumerators, not constexpr variables: device code takes them by reference)
enum : int {
  kGradV = 0,    // 3 x 3: the gradients of V_x, V_y, V_z
  kPhiV = 9,     // the velocity's limiter factor
  kPhiS = 10,    // the stress's (a solid) or the pressure's (a fluid)
  kGradS = 11,   // 6 x 3 (a solid: xx, yy, zz, xy, yz, xz) or 3 (a fluid: grad p)
  kPulled = 29,  // 6 x 3: a solid's pulled-back jumps (pullBack), the limiter's
  kColumns = 47,
};
}  // namespace corner_rows

KOKKOS_FORCEINLINE_FUNCTION Vec3 loadRowVec3(const MatRealView& rows, Index c, int column) {
  return {rows(c, column), rows(c, column + 1), rows(c, column + 2)};
}
KOKKOS_FORCEINLINE_FUNCTION void storeRowVec3(const MatRealView& rows, Index c, int column,
                                              const Vec3& v) {
  rows(c, column) = v.x;
  rows(c, column + 1) = v.y;
  rows(c, column + 2) = v.z;
}

// projectedLimiter (reconstruction.hpp) one vertex at a time:
// `vertex(p, direction, length2)` gives vertex p's direction and |delta_p|^2.
template <bool plateau_guard, bool vertex_sums, class VertexOf>
KOKKOS_INLINE_FUNCTION double projectedLimiterByVertex(const Vec3 jumps[6], int n_vertices,
                                                       const VertexOf& vertex) {
  double limiter = 1.0;
  LAGREMAP_NO_UNROLL
  for (int p = 0; p < n_vertices; ++p) {
    Vec3 direction;
    double length2;
    vertex(p, direction, length2);
    double toward = 0.0, away = 0.0, along[6];
    for (int f = 0; f < 6; ++f) {
      along[f] = jumps[f].x * direction.x + jumps[f].y * direction.y + jumps[f].z * direction.z;
      toward = along[f] > toward ? along[f] : toward;
      if (plateau_guard) away = -along[f] > away ? -along[f] : away;
    }
    if (vertex_sums) {
      const bool on_x_plus = p == 1 || p == 2 || p == 5 || p == 6;
      const double fx = on_x_plus ? along[1] : along[0];
      const double fy = (p & 2) ? along[3] : along[2];
      const double fz = (p & 4) ? along[5] : along[4];
      const double sums[4] = {fx + fy, fy + fz, fx + fz, fx + fy + fz};
      for (const double sum : sums) {
        toward = sum > toward ? sum : toward;
        if (plateau_guard) away = -sum > away ? -sum : away;
      }
    }
    double reach = toward, length2_scaled = length2;
    if (plateau_guard && toward < away) {
      reach = 0.5 * toward * (away * away + toward * toward);
      length2_scaled = length2 * (away * away);
    }
    if (reach < limiter * length2_scaled) limiter = reach / length2_scaled;
  }
  return limiter;
}

struct StagedCorners {
  CellNodesView cell_nodes;
  CellFacesView neighbors;
  CellFacesView face_side;
  DeviceView<int[kNumSides]> side_kind;
  Vec3View x_n;
  State s;
  bool z_prisms, second_order, atomics;
  MatRealView rows;  // (cell, corner_rows::kColumns)

  // What stands across face f: the offset dx to it, the velocity jump dv and
  // (a mirror) the wall's normal; false for a free side (no jump).
  KOKKOS_INLINE_FUNCTION bool across(Index c, int f, const NodesOfCell& nodes, const Vec3& centroid,
                                     const Vec3& v_cell, StencilFace& face, Vec3& dx, Vec3& dv,
                                     Vec3& normal) const {
    face = stencilFace(neighbors, face_side, side_kind, c, f);
    if (face == StencilFace::Neighbour) {
      const Index nb = neighbors(c, f);
      dx = loadVec3(s.x_c, nb) - centroid;
      dv = loadVec3(s.v_c, nb) - v_cell;
      return true;
    }
    if (face == StencilFace::None) return false;
    if (z_prisms && f >= 4) {
      const double side = f == 4 ? -1.0 : 1.0;
      normal = Vec3{0.0, 0.0, side};
      dx = Vec3{0.0, 0.0, side * (nodes(4).z - nodes(0).z)};
      dv = Vec3{0.0, 0.0, -2.0 * v_cell.z};
    } else {
      mirrorAcrossFace(nodes, f, centroid, v_cell, dx, dv, normal);
    }
    return true;
  }

  // The stress jump across face f (zero for a free side) and the offset to it.
  KOKKOS_INLINE_FUNCTION SymMat3 stressJump(Index c, int f, const NodesOfCell& nodes,
                                            const Vec3& centroid, const Vec3& v_cell,
                                            const SymMat3& sigma_cell, Vec3& dx) const {
    StencilFace face;
    Vec3 dv, normal;
    if (!across(c, f, nodes, centroid, v_cell, face, dx, dv, normal)) return identitySym(0.0);
    if (face == StencilFace::Mirror) return mirrorJump(sigma_cell, normal);
    const Index nb = neighbors(c, f);
    return loadSym(s.S_c, nb) + identitySym(-s.p_c(nb)) - sigma_cell;
  }

  KOKKOS_INLINE_FUNCTION int vertices() const { return z_prisms ? 4 : kHexVertices; }

  // The velocity's gradient and limiter factor (limitedNodeVelocities).
  KOKKOS_INLINE_FUNCTION void velocityLimiter(Index c) const {
    const NodesOfCell nodes{cell_nodes, x_n, c};
    const Vec3 v_cell = loadVec3(s.v_c, c), centroid = loadVec3(s.x_c, c);
    const bool solid = s.aT_c(c) > 0.0;
    LeastSquares lsq;
    Vec3 rhs_v[3] = {Vec3{0.0, 0.0, 0.0}, Vec3{0.0, 0.0, 0.0}, Vec3{0.0, 0.0, 0.0}};
    for (int f = 0; f < 6; ++f) {
      StencilFace face;
      Vec3 dx, dv, normal;
      if (!across(c, f, nodes, centroid, v_cell, face, dx, dv, normal)) continue;
      lsq.addOffset(dx);
      rhs_v[0] += dv.x * dx;
      rhs_v[1] += dv.y * dx;
      rhs_v[2] += dv.z * dx;
    }
    const SymMat3 inv = lsq.solver();
    const Vec3 grad_v[3] = {inv * rhs_v[0], inv * rhs_v[1], inv * rhs_v[2]};
    // the jumps again, from a second pass (not held through the first)
    Vec3 dv_nb[6];
    int open_sides = 0;  // bit f: face f is an open side (one register, not six)
    for (int f = 0; f < 6; ++f) {
      StencilFace face;
      Vec3 dx, normal;
      if (!across(c, f, nodes, centroid, v_cell, face, dx, dv_nb[f], normal)) {
        dv_nb[f] = Vec3{0.0, 0.0, 0.0};
        open_sides |= 1 << f;
      }
    }
    continueAcrossOpenSides([open_sides](int f) { return ((open_sides >> f) & 1) != 0; }, dv_nb);
    double longest2 = 0.0;
    const auto vertex = [&](int p, Vec3& direction, double& length2) {
      const Vec3 offset = nodes(p) - centroid;
      direction = Vec3{grad_v[0].x * offset.x + grad_v[0].y * offset.y + grad_v[0].z * offset.z,
                       grad_v[1].x * offset.x + grad_v[1].y * offset.y + grad_v[1].z * offset.z,
                       grad_v[2].x * offset.x + grad_v[2].y * offset.y + grad_v[2].z * offset.z};
      length2 = direction.x * direction.x + direction.y * direction.y + direction.z * direction.z;
      longest2 = length2 > longest2 ? length2 : longest2;
    };
    const double phi_v = solid ? projectedLimiterByVertex<true, true>(dv_nb, vertices(), vertex)
                               : projectedLimiterByVertex<false, true>(dv_nb, vertices(), vertex);
    const double sound_speed = s.aL_c(c);
    const double phi = phi_v * phi_v * longest2 > sound_speed * sound_speed
                           ? sound_speed / math::sqrt(longest2)
                           : phi_v;
    for (int i = 0; i < 3; ++i) storeRowVec3(rows, c, corner_rows::kGradV + 3 * i, grad_v[i]);
    rows(c, corner_rows::kPhiV) = phi;
  }

  // A solid's stress gradient and limiter factor (limitedNodeStresses), a
  // fluid's pressure's (limitedNodePressures).
  KOKKOS_INLINE_FUNCTION void stressGradient(Index c) const {
    const NodesOfCell nodes{cell_nodes, x_n, c};
    const Vec3 v_cell = loadVec3(s.v_c, c), centroid = loadVec3(s.x_c, c);
    const double p_cell = s.p_c(c);
    const bool solid = s.aT_c(c) > 0.0;
    const double sound_speed = s.aL_c(c);
    const double stress_scale = s.rho_c(c) * sound_speed * sound_speed;
    LeastSquares lsq;
    if (!solid) {
      Vec3 rhs_p{0.0, 0.0, 0.0};
      Bounds pb(p_cell);
      for (int f = 0; f < 6; ++f) {
        StencilFace face;
        Vec3 dx, dv, normal;
        if (!across(c, f, nodes, centroid, v_cell, face, dx, dv, normal)) continue;
        const double dp = face == StencilFace::Neighbour ? s.p_c(neighbors(c, f)) - p_cell : 0.0;
        lsq.addOffset(dx);
        rhs_p += dp * dx;
        pb.include(p_cell + dp);
      }
      const Vec3 grad_p = lsq.solver() * rhs_p;
      VertexExcursion excursion;
      double largest = 0.0;
      for (int p = 0; p < vertices(); ++p) {
        const Vec3 offset = nodes(p) - centroid;
        const double dp = grad_p.x * offset.x + grad_p.y * offset.y + grad_p.z * offset.z;
        excursion.include(dp);
        const double size = math::fabs(dp);
        largest = size > largest ? size : largest;
      }
      double phi_p = cellLimiter(excursion, p_cell, pb, 1.0);
      phi_p = phi_p * largest > stress_scale ? stress_scale / largest : phi_p;
      storeRowVec3(rows, c, corner_rows::kGradS, grad_p);
      rows(c, corner_rows::kPhiS) = phi_p;
      return;
    }
    const SymMat3 sigma_cell = loadSym(s.S_c, c) + identitySym(-p_cell);
    const auto jump = [&](int f, Vec3& dx) {
      return stressJump(c, f, nodes, centroid, v_cell, sigma_cell, dx);
    };
    Vec3 rhs[6];
    for (int i = 0; i < 6; ++i) rhs[i] = Vec3{0.0, 0.0, 0.0};
    for (int f = 0; f < 6; ++f) {
      Vec3 dx;
      const SymMat3 dsigma = jump(f, dx);
      if (stencilFace(neighbors, face_side, side_kind, c, f) == StencilFace::None) continue;
      lsq.addOffset(dx);
      rhs[0] += dsigma.xx * dx;
      rhs[1] += dsigma.yy * dx;
      rhs[2] += dsigma.zz * dx;
      rhs[3] += dsigma.xy * dx;
      rhs[4] += dsigma.yz * dx;
      rhs[5] += dsigma.xz * dx;
    }
    const SymMat3 inv = lsq.solver();
    Vec3 grad[6];
    for (int i = 0; i < 6; ++i) grad[i] = inv * rhs[i];
    for (int i = 0; i < 6; ++i) storeRowVec3(rows, c, corner_rows::kGradS + 3 * i, grad[i]);
  }

  // ... and a solid's limiter factor, from the stored gradients: the
  // excursions' squares, the pulled-back jumps from a second pass over the
  // stencil (into the row), then the vertex by vertex limiter.
  KOKKOS_INLINE_FUNCTION void stressLimiter(Index c) const {
    if (!(s.aT_c(c) > 0.0)) return;  // (a fluid's is done)
    const NodesOfCell nodes{cell_nodes, x_n, c};
    const Vec3 v_cell = loadVec3(s.v_c, c), centroid = loadVec3(s.x_c, c);
    const double p_cell = s.p_c(c);
    const double sound_speed = s.aL_c(c);
    const double stress_scale = s.rho_c(c) * sound_speed * sound_speed;
    const SymMat3 sigma_cell = loadSym(s.S_c, c) + identitySym(-p_cell);
    const auto jump = [&](int f, Vec3& dx) {
      return stressJump(c, f, nodes, centroid, v_cell, sigma_cell, dx);
    };
    // |delta_p|^2, the Frobenius square of the excursion G d_p, at each vertex
    // first (the gradients), then the pulled-back jumps (pullBack) from a
    // second pass over the stencil: the two are never held at once
    double length2[kHexVertices], largest2 = 0.0;
    LAGREMAP_NO_UNROLL
    for (int p = 0; p < vertices(); ++p) {
      const Vec3 d = nodes(p) - centroid;
      double e[6];
      for (int i = 0; i < 6; ++i) {
        const Vec3 g = loadRowVec3(rows, c, corner_rows::kGradS + 3 * i);
        e[i] = g.x * d.x + g.y * d.y + g.z * d.z;
      }
      length2[p] =
          e[0] * e[0] + e[1] * e[1] + e[2] * e[2] + 2.0 * (e[3] * e[3] + e[4] * e[4] + e[5] * e[5]);
      largest2 = length2[p] > largest2 ? length2[p] : largest2;
    }
    // the gradients from the row, a face at a time
    const auto gradient = [&](int i) { return loadRowVec3(rows, c, corner_rows::kGradS + 3 * i); };
    int open_sides = 0;  // bit f: face f is an open side
    for (int f = 0; f < 6; ++f) {
      Vec3 dx;
      const SymMat3 t = jump(f, dx);
      if (stencilFace(neighbors, face_side, side_kind, c, f) == StencilFace::None) {
        open_sides |= 1 << f;
      }
      storeRowVec3(rows, c, corner_rows::kPulled + 3 * f,
                   t.xx * gradient(0) + t.yy * gradient(1) + t.zz * gradient(2) +
                       (2.0 * t.xy) * gradient(3) + (2.0 * t.yz) * gradient(4) +
                       (2.0 * t.xz) * gradient(5));
    }
    // an open side's jump is the opposite one reversed, and so is its
    // pulled-back jump, to the bit (continueAcrossOpenSides on the row)
    for (int f = 0; f < 6; ++f) {
      if (((open_sides >> f) & 1) != 0 && ((open_sides >> (f ^ 1)) & 1) == 0) {
        storeRowVec3(rows, c, corner_rows::kPulled + 3 * f,
                     -1.0 * loadRowVec3(rows, c, corner_rows::kPulled + 3 * (f ^ 1)));
      }
    }
    Vec3 pulled[6];
    for (int f = 0; f < 6; ++f) pulled[f] = loadRowVec3(rows, c, corner_rows::kPulled + 3 * f);
    const auto vertex = [&](int p, Vec3& direction, double& vertex_length2) {
      direction = nodes(p) - centroid;
      vertex_length2 = length2[p];
    };
    double phi = projectedLimiterByVertex<true, false>(pulled, vertices(), vertex);
    phi = phi * phi * largest2 > stress_scale * stress_scale ? stress_scale / math::sqrt(largest2)
                                                             : phi;
    rows(c, corner_rows::kPhiS) = phi;
  }

  // B_cp of each corner from the node values (repeatBottomVertices: a z
  // prism's top vertices take the bottom ones' values).
  KOKKOS_INLINE_FUNCTION void rightHandSides(Index c) const {
    const NodesOfCell nodes{cell_nodes, x_n, c};
    const Vec3 v_cell = loadVec3(s.v_c, c), centroid = loadVec3(s.x_c, c);
    const double p_cell = s.p_c(c);
    const bool solid = s.aT_c(c) > 0.0;
    const SymMat3 sigma_cell =
        solid ? loadSym(s.S_c, c) + identitySym(-p_cell) : identitySym(-p_cell);
    LAGREMAP_NO_UNROLL
    for (int p = 0; p < 8; ++p) {
      Vec3 v_node = v_cell;
      SymMat3 sigma_node = sigma_cell;
      double p_node = p_cell;
      if (second_order) {
        const Vec3 offset = nodes(z_prisms ? p & 3 : p) - centroid;
        const auto along = [&](int column) {
          const Vec3 g = loadRowVec3(rows, c, column);
          return g.x * offset.x + g.y * offset.y + g.z * offset.z;
        };
        const double phi_v = rows(c, corner_rows::kPhiV), phi_s = rows(c, corner_rows::kPhiS);
        v_node = Vec3{v_cell.x + phi_v * along(corner_rows::kGradV),
                      v_cell.y + phi_v * along(corner_rows::kGradV + 3),
                      v_cell.z + phi_v * along(corner_rows::kGradV + 6)};
        if (solid) {
          sigma_node = {sigma_cell.xx + phi_s * along(corner_rows::kGradS),
                        sigma_cell.yy + phi_s * along(corner_rows::kGradS + 3),
                        sigma_cell.zz + phi_s * along(corner_rows::kGradS + 6),
                        sigma_cell.xy + phi_s * along(corner_rows::kGradS + 9),
                        sigma_cell.yz + phi_s * along(corner_rows::kGradS + 12),
                        sigma_cell.xz + phi_s * along(corner_rows::kGradS + 15)};
        } else {
          p_node = p_cell + phi_s * along(corner_rows::kGradS);
        }
      }
      const Index corner = 8 * c + p;
      const Vec3 area = loadVec3(s.A_cp, corner);
      const Vec3 stress_force = solid ? -(sigma_node * area) : p_node * area;
      storeVec3(s.B_cp, corner, loadSym(s.M_cp, corner) * v_node + stress_force);
      if (atomics) {
        const Index node = cell_nodes(c, p);
        for (int j = 0; j < 6; ++j) Kokkos::atomic_add(&s.M_n(node, j), s.M_cp(corner, j));
        for (int j = 0; j < 3; ++j) Kokkos::atomic_add(&s.B_n(node, j), s.B_cp(corner, j));
      }
    }
  }
};

// The corner terms of a mesh's cells under `controls`.
inline CornerTerms cornerTerms(const Mesh& mesh, const State& state,
                               const CornerControls& controls) {
  return {mesh.cell_nodes,
          mesh.cell_neighbors,
          mesh.cell_face_side,
          mesh.side_kind,
          mesh.x_n,
          state,
          mesh.z_prisms,
          controls.order >= 2,
          controls.gather == Gather::Atomics};
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

// The staged form's rows of computeCornerTerms.
inline MatRealView allocateCornerRows(const Mesh& mesh) {
  return MatRealView("lagremap::corners::rows", mesh.n_cells, detail::corner_rows::kColumns);
}

// Per cell: V and sigma reconstructed at its nodes (docs/method.md §A5: piecewise
// constant at first order; second order: least-squares gradients limited by
// one frame-independent factor each, a solid's whole Cauchy stress as a
// tensor, a fluid's pressure as a scalar), then B_cp = M_cp V_c(p) -
// sigma_c(p) A_cp. On CPU builds the cells go kCellLanes at a time in the
// lanes of a vector where their stencils have one shape (the same bits as
// cell by cell, docs/method.md §7.1).
// `rows`: the staged form's per-cell rows (allocateCornerRows, KernelForm::
// Staged); without them the fused form runs (built on CPU backends only).
static inline void computeCornerTerms(const Mesh& mesh, const State& state,
                                      const CornerControls& controls,
                                      const MatRealView& rows = {}) {
  const detail::CornerTerms terms = detail::cornerTerms(mesh, state, controls);
  if (terms.atomics) {
    Kokkos::deep_copy(state.M_n, 0.0);
    Kokkos::deep_copy(state.B_n, 0.0);
  }
  const auto policy = Kokkos::RangePolicy<ExecSpace>(0, mesh.n_cells);
  if (!kFusedKernelsBuilt || rows.extent(0) > 0) {
    // (a caller outside the time loop may leave the rows to this call)
    const MatRealView own_rows = rows.extent(0) > 0 ? rows : allocateCornerRows(mesh);
    const detail::StagedCorners staged{
        terms.cell_nodes, terms.neighbors, terms.face_side,    terms.side_kind, terms.x_n,
        terms.s,          terms.z_prisms,  terms.second_order, terms.atomics,   own_rows};
    if (staged.second_order) {
      Kokkos::parallel_for(
          "lagremap::corners::velocity_limiter", policy,
          KOKKOS_LAMBDA(const Index c) { staged.velocityLimiter(c); });
      // (at most 128 registers a thread, 4 blocks of 128 threads an SM: it
      // needs 130 unbounded, and no spill bounded)
      Kokkos::parallel_for(
          "lagremap::corners::stress_gradient",
          Kokkos::RangePolicy<ExecSpace, Kokkos::LaunchBounds<128, 4>>(0, mesh.n_cells),
          KOKKOS_LAMBDA(const Index c) { staged.stressGradient(c); });
      if (terms.s.has_solids) {
        Kokkos::parallel_for(
            "lagremap::corners::stress_limiter", policy,
            KOKKOS_LAMBDA(const Index c) { staged.stressLimiter(c); });
      }
    }
    Kokkos::parallel_for(
        "lagremap::corners::right_hand_sides", policy,
        KOKKOS_LAMBDA(const Index c) { staged.rightHandSides(c); });
    return;
  }
  if constexpr (kFusedKernelsBuilt) computeFusedCornerTerms(mesh, terms);
}

namespace detail {

// P M P + s (I - P), s = tr(M) / 3: SPD when M is, and its solution with
// right-hand side P B lies in the range of P and satisfies P (M V - B) = 0
// (Lagrange multipliers) whatever s > 0. s is M's own scale, not 1: an
// impedance is dimensional, and a near-vacuum node's (1e-16 kg/s in the
// `ball`'s wake at `--scale 2`) vanished in M + 1 - 1, which left the solver
// singular, the node's velocity NaN and the cell tangled.
// A projector onto axis planes or axes (a wall or symmetry plane normal to x,
// y or z, or two of them) is diagonal, of zeros and ones: P M P keeps the
// entries of M in the free directions, the same numbers the general product
// gives (up to the sign of a zero), in a tenth of the operations.
KOKKOS_INLINE_FUNCTION bool isAxisProjector(const SymMat3& projector) {
  return projector.xy == 0.0 && projector.yz == 0.0 && projector.xz == 0.0;
}
KOKKOS_INLINE_FUNCTION SymMat3 constrainedMatrix(const SymMat3& projector, const SymMat3& m) {
  const double scale = (m.xx + m.yy + m.zz) * (1.0 / 3.0);
  if (isAxisProjector(projector)) {
    const SymMat3& p = projector;
    return {(p.xx * m.xx) * p.xx + scale * (1.0 - p.xx),
            (p.yy * m.yy) * p.yy + scale * (1.0 - p.yy),
            (p.zz * m.zz) * p.zz + scale * (1.0 - p.zz),
            (p.xx * m.xy) * p.yy,
            (p.yy * m.yz) * p.zz,
            (p.xx * m.xz) * p.zz};
  }
  const double P[3][3] = {{projector.xx, projector.xy, projector.xz},
                          {projector.xy, projector.yy, projector.yz},
                          {projector.xz, projector.yz, projector.zz}};
  const double M[3][3] = {{m.xx, m.xy, m.xz}, {m.xy, m.yy, m.yz}, {m.xz, m.yz, m.zz}};
  double PM[3][3];
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      PM[i][j] = P[i][0] * M[0][j] + P[i][1] * M[1][j] + P[i][2] * M[2][j];
  // (P M P)_ij = (PM)_i . P_j, symmetric: the six entries of one triangle
  auto entry = [&](int i, int j) {
    return PM[i][0] * P[0][j] + PM[i][1] * P[1][j] + PM[i][2] * P[2][j] +
           scale * ((i == j) - P[i][j]);
  };
  return {entry(0, 0), entry(1, 1), entry(2, 2), entry(0, 1), entry(1, 2), entry(0, 2)};
}

// P v, with the axis projector's shortcut of constrainedMatrix (same numbers).
KOKKOS_INLINE_FUNCTION Vec3 project(const SymMat3& projector, const Vec3& v) {
  if (isAxisProjector(projector)) {
    return {projector.xx * v.x, projector.yy * v.y, projector.zz * v.z};
  }
  return projector * v;
}

// CPU builds: the corner records (M_cp, B_cp) that the node visited
// kPrefetchAhead visits later will gather, asked for now. The nodes' corners
// are in other cells, one index list away, so the hardware prefetchers cannot
// follow: without it the gather's first loads took two thirds of the solve's
// time (performance.md §3.1). A twin node reads nothing (its source's
// solution). Nothing in device passes (LAGREMAP_PREFETCHES is 0 there), where
// the threads of a warp hide the latency.
constexpr Index kPrefetchAhead = 16;  // node visits (twins included)
template <class Order, class Offsets, class Corners, class Twins>
KOKKOS_FORCEINLINE_FUNCTION void prefetchCornerRecords(const State& s, const Order& solve_order,
                                                       const Offsets& offsets,
                                                       const Corners& corners,
                                                       const Twins& twin_source, Index visit) {
#if LAGREMAP_PREFETCHES
  const Index ahead = visit + kPrefetchAhead;
  if (ahead >= Index(solve_order.extent(0))) return;
  const Index n = solve_order(ahead);
  if (twin_source.extent(0) > 0 && twin_source(n) != n) return;
  for (Index i = offsets(n); i < offsets(n + 1); ++i) {
    const Index corner = corners(i);
    // (a 48-byte M_cp record may span two cache lines, a 24-byte B_cp one too)
    LAGREMAP_PREFETCH(&s.M_cp(corner, 0));
    LAGREMAP_PREFETCH(&s.M_cp(corner, 5));
    LAGREMAP_PREFETCH(&s.B_cp(corner, 0));
    LAGREMAP_PREFETCH(&s.B_cp(corner, 2));
  }
#else
  (void)s, (void)solve_order, (void)offsets, (void)corners, (void)twin_source, (void)visit;
#endif
}

}  // namespace detail

// Solves every node and finds where it moves: x_n_next = x_n0 + dt_stage V_n.
static inline void nodalSolve(const Mesh& mesh, const State& state, const CornerControls& controls,
                              double dt_stage) {
  // The Views it reads, not the whole Mesh (whose global ids live on the host).
  const auto cell_face_side = mesh.cell_face_side;
  const auto cell_nodes = mesh.cell_nodes;
  const auto node_projector_id = mesh.node_projector_id;
  const auto node_corner_offsets = mesh.node_corner_offsets;
  const auto node_corners = mesh.node_corners;
  const auto node_solve_order = mesh.node_solve_order;
  const auto projectors = mesh.projectors;
  const auto node_traction_faces = mesh.node_traction_faces;
  const auto node_traction_offsets = mesh.node_traction_offsets;
  const auto side_traction = mesh.side_traction;
  const auto x_n = mesh.x_n;
  const auto twin_source = mesh.node_twin_source;
  const auto twin_flip = mesh.node_twin_flip;
  const bool twins = twin_source.extent(0) > 0;
  const auto s = state;
  const bool atomics = controls.gather == Gather::Atomics;
  Kokkos::parallel_for(
      atomics ? "lagremap::nodal_solve::atomics_sum" : "lagremap::nodal_solve::crs_gather",
      Kokkos::RangePolicy<ExecSpace>(0, mesh.n_nodes), KOKKOS_LAMBDA(const Index visit) {
        const Index n = node_solve_order(visit);
        if (!atomics) {
          detail::prefetchCornerRecords(s, node_solve_order, node_corner_offsets, node_corners,
                                        twin_source, visit);
        }
        if (twins && twin_source(n) != n) return;  // its twin's solution (below)
        SymMat3 impedance = identitySym(0.0);
        Vec3 rhs{0, 0, 0};
        if (atomics) {
          impedance = loadSym(s.M_n, n);
          rhs = loadVec3(s.B_n, n);
        } else {
          for (Index i = node_corner_offsets(n); i < node_corner_offsets(n + 1); ++i) {
            const Index corner = node_corners(i);
            impedance += loadSym(s.M_cp, corner);
            rhs += loadVec3(s.B_cp, corner);
          }
        }
        // External load of traction faces: sum_bf s_pf sigma^b n_pf.
        Vec3 load{0, 0, 0};
        for (Index i = node_traction_offsets(n); i < node_traction_offsets(n + 1); ++i) {
          const Index face_id = node_traction_faces(i);
          const Index c = face_id / 6;
          const int f = face_id % 6;
          Vec3 q[4], w[4];
          int local = 0;
          for (int k = 0; k < 4; ++k) {
            const Index node = cell_nodes(c, hex::faceNode(f, k));
            q[k] = loadVec3(x_n, node);
            if (node == n) local = k;
          }
          hex::faceCornerVectors(q, w);
          const int side = cell_face_side(c, f);
          const SymMat3 sigma_b{side_traction(side, 0), side_traction(side, 1),
                                side_traction(side, 2), side_traction(side, 3),
                                side_traction(side, 4), side_traction(side, 5)};
          load += sigma_b * w[local];
        }
        Vec3 velocity;
        Vec3 reaction{0, 0, 0};  // force of the walls on the node
        const int projector_id = node_projector_id(n);
        if (projector_id >= 0) {
          const SymMat3 projector = loadSym(projectors, projector_id);
          const SymMat3 solver = inverse(detail::constrainedMatrix(projector, impedance));
          velocity = detail::project(projector, solver * detail::project(projector, rhs + load));
          // One step of iterative refinement: the tangential balance then
          // holds to the last bit, which is what the energy audit sees.
          velocity += detail::project(
              projector, solver * detail::project(projector, rhs + load - impedance * velocity));
          // The constrained directions' part of M V - B - load (the Lagrange
          // multipliers); its tangential part is the solver's round-off.
          const Vec3 residual = impedance * velocity - rhs - load;
          reaction = residual - detail::project(projector, residual);
        } else {
          const SymMat3 solver = inverse(impedance);
          velocity = solver * (rhs + load);
          velocity += solver * (rhs + load - impedance * velocity);
        }
        storeVec3(s.v_n, n, velocity);
        // External force on the node (sum_c F_cp up to round-off): wall reaction
        // plus traction load, for the conservation audit.
        storeVec3(s.f_ext_n, n, reaction + load);
        storeVec3(s.x_n_next, n, loadVec3(s.x_n0, n) + dt_stage * velocity);
      });
  if (!twins) return;
  // A slab's or bar's twin nodes (Mesh::node_twin_source): the velocity of
  // the node they mirror (its components normal to the planes are zero) and
  // its external force mirrored.
  Kokkos::parallel_for(
      "lagremap::nodal_solve::twins", Kokkos::RangePolicy<ExecSpace>(0, mesh.n_nodes),
      KOKKOS_LAMBDA(const Index n) {
        const Index source = twin_source(n);
        if (source == n) return;
        const Vec3 velocity = loadVec3(s.v_n, source);
        const Vec3 force = loadVec3(s.f_ext_n, source);
        const int flip = twin_flip(n);
        storeVec3(s.v_n, n, velocity);
        storeVec3(s.f_ext_n, n,
                  Vec3{flip & 1 ? -force.x : force.x, flip & 2 ? -force.y : force.y,
                       flip & 4 ? -force.z : force.z});
        storeVec3(s.x_n_next, n, loadVec3(s.x_n0, n) + dt_stage * velocity);
      });
}

// A decomposed run's ghost nodes after the node exchange has given them their
// owners' velocities: the positions x_n0 + dt_stage V_n, the same sum their
// owners computed (nodalSolve), so the same bits.
static inline void moveGhostNodes(const Mesh& mesh, const State& state, double dt_stage) {
  const auto owned = mesh.node_owned;
  const auto x_n = mesh.x_n;
  const auto s = state;
  Kokkos::parallel_for(
      "lagremap::nodal_solve::ghost_positions", Kokkos::RangePolicy<ExecSpace>(0, mesh.n_nodes),
      KOKKOS_LAMBDA(const Index n) {
        if (owned(n)) return;
        storeVec3(x_n, n, loadVec3(s.x_n0, n) + dt_stage * loadVec3(s.v_n, n));
      });
}

// Velocity gradient of the stage, L = (1/v) sum_p V_p (x) A_cp (docs/method.md §A2).
KOKKOS_INLINE_FUNCTION Mat3 velocityGradient(const CellNodesView& cell_nodes, const State& s,
                                             Index c) {
  Mat3 gradient = zeroMat();
  const double inv_volume = 1.0 / s.vol_c(c);
  for (int p = 0; p < 8; ++p) {
    addOuter(gradient, inv_volume, loadVec3(s.v_n, cell_nodes(c, p)), loadVec3(s.A_cp, 8 * c + p));
  }
  return gradient;
}

// Power of material k's stress per unit cell volume (stage-start pressure and
// deviator): -p^k share^k tr(L) + alpha^k S^k : L, with share^k its part of
// the cell's volume change (shareVolumeChange; alpha^k under equal strain)
// and the deviatoric strain rate common to all materials.
KOKKOS_FORCEINLINE_FUNCTION double stressPower(const State& s, Index c, int k, const Mat3& L,
                                               double volume_share) {
  double power = -s.p_ck(c, k) * volume_share * (L.m[0][0] + L.m[1][1] + L.m[2][2]);
  if (s.materials(k).strength != StrengthKind::None) {
    const SymMat3 S = loadSym(s.S_ck, c, k);
    power += s.alpha_ck(c, k) * (S.xx * L.m[0][0] + S.yy * L.m[1][1] + S.zz * L.m[2][2] +
                                 S.xy * (L.m[0][1] + L.m[1][0]) + S.yz * (L.m[1][2] + L.m[2][1]) +
                                 S.xz * (L.m[0][2] + L.m[2][0]));
  }
  return power;
}

// Incremental deformation gradient over the stage, exact for affine motion
// (docs/method.md §A7, §3.3): F = (1/v^n) sum_p x_p^new (x) A_cp^n, with the geometry of the
// start of the step recomputed from x_n0.
KOKKOS_INLINE_FUNCTION Mat3 stageDeformation(const CellNodesView& cell_nodes, const Vec3View& x_n,
                                             const State& s, Index c) {
  Vec3 x_start[8], corner_start[8];
  for (int p = 0; p < 8; ++p) x_start[p] = loadVec3(s.x_n0, cell_nodes(c, p));
  hex::cornerVectors(x_start, corner_start);
  double volume_start = 0.0;  // Euler's theorem for the cubic volume
  for (int p = 0; p < 8; ++p) volume_start += dot(x_start[p] - x_start[0], corner_start[p]);
  volume_start /= 3.0;
  Mat3 deformation = zeroMat();
  for (int p = 0; p < 8; ++p) {
    // relative to node 0 (sum_p A_cp = 0), to keep round-off small
    addOuter(deformation, 1.0 / volume_start,
             loadVec3(x_n, cell_nodes(c, p)) - loadVec3(x_n, cell_nodes(c, 0)), corner_start[p]);
  }
  return deformation;
}

// The same from one corner vector at a time (the staged form: the same
// bits, without the 16 positions and vectors held at once).
KOKKOS_INLINE_FUNCTION Mat3 stagedStageDeformation(const CellNodesView& cell_nodes,
                                                   const Vec3View& x_n, const State& s, Index c) {
  const NodesOfCell start{cell_nodes, s.x_n0, c};
  const Vec3 x_start_0 = start(0);
  double volume_start = 0.0;  // Euler's theorem for the cubic volume
  LAGREMAP_NO_UNROLL
  for (int p = 0; p < 8; ++p)
    volume_start += dot(start(p) - x_start_0, hex::cornerVector(start, p));
  volume_start /= 3.0;
  const Vec3 x_0 = loadVec3(x_n, cell_nodes(c, 0));
  Mat3 deformation = zeroMat();
  LAGREMAP_NO_UNROLL
  for (int p = 0; p < 8; ++p) {
    addOuter(deformation, 1.0 / volume_start, loadVec3(x_n, cell_nodes(c, p)) - x_0,
             hex::cornerVector(start, p));
  }
  return deformation;
}

// A material with less than this fraction of its cell's mass does no pdV work
// of its own: it takes the cell's specific heat (its share of D by mass). A
// trace by mass has no say in the cell's energy; its volume still yields to
// the others' (relaxation), as a void's would. Without it the `ball`'s
// near-vacuum gas ratchets up in temperature, compressed adiabatically by
// every Lagrangian stage and re-expanded by the remap without work
// (docs/method.md §4.6).
constexpr double kMassTrace = 1e-6;

namespace detail {

// What a mixed cell's materials share over a stage (docs/method.md §4): each
// material's own volume ratio (end over start of step), the cell's energy
// budget D = m (e_new - e^n) - sum_k W^k, and the masses that share it.
struct MixedCellBudget {
  double own_ratio[kMaxMaterials];
  double dissipation = 0.0;
  double present_mass = 0.0, present_alpha = 0.0;
  double condensed_mass = 0.0;  // not of the gas family: their energy may go negative, in tension
  double gas_heat = 0.0;        // the gases' positive internal energy
};

// Each material's volume ratio over the step: dV^k = share^k dt v tr L +
// relax^k, as shareVolumeChange makes it, and like it never below
// kMinVolumeKept of the start volume (the pdV work stops where the volume
// does; what the cap leaves out goes to D, shared by mass).
KOKKOS_FORCEINLINE_FUNCTION void ownVolumeRatios(const State& s, Index c, double volume_change,
                                                 double own_ratio[], StageRelaxation& relaxation) {
  const bool equal_strain = s.closure == MixtureClosure::EqualStrain;
  double weight_sum = 0.0;  // compressibility weights of the step start
  for (int k = 0; k < s.n_materials && !equal_strain; ++k) {
    if (s.alpha_ck(c, k) > 0.0) weight_sum += s.w_ck0(c, k);
  }
  double* relax = relaxation.volume;
  if (equal_strain) {
    for (int k = 0; k < kMaxMaterials; ++k) relax[k] = 0.0;
  } else {
    relaxationVolumes(s, c, relax);
    relaxation.known = true;
  }
  for (int k = 0; k < s.n_materials; ++k) {
    if (!(s.alpha_ck(c, k) > 0.0)) continue;
    // (equal strain: alpha^k of the volume change, the cell's rate)
    const double share = weight_sum > 0.0 ? s.w_ck0(c, k) / weight_sum : s.alpha_ck(c, k);
    const double start_volume = s.alpha_ck0(c, k) * s.vol_c0(c);
    const double own_change = share * volume_change + relax[k];
    own_ratio[k] = own_change < -(1.0 - kMinVolumeKept) * start_volume
                       ? kMinVolumeKept
                       : 1.0 + own_change / start_volume;
  }
}

// A Neo-Hookean body's velocity gradient in a mixed cell (isSolidBody,
// geometry.hpp): the cell's plus the normal stretch rate that makes its
// volume rate its own; the gas beside it takes the cell's compression.
KOKKOS_FORCEINLINE_FUNCTION Mat3 materialGradient(const State& s, Index c, int k, bool mixed,
                                                  const Mat3& gradient, double own_ratio,
                                                  double dt_stage) {
  Vec3 n;
  if (!(mixed && isSolidBody(s, c, k, n))) return gradient;
  Mat3 own = gradient;
  addOuter(own, (own_ratio - 1.0) / dt_stage - trace(gradient), n, n);
  return own;
}

// W^k = -p^k dV^k + dt v alpha^k S^k : L^k (zero for a trace by mass).
KOKKOS_FORCEINLINE_FUNCTION double materialWork(const State& s, Index c, int k,
                                                const Mat3& gradient_k, double own_ratio,
                                                double dt_stage) {
  if (s.closure == MixtureClosure::Relaxation && s.m_ck(c, k) < kMassTrace * s.m_c(c)) return 0.0;
  const double start_volume = s.alpha_ck0(c, k) * s.vol_c0(c);
  return -s.p_ck(c, k) * (own_ratio - 1.0) * start_volume +
         dt_stage * s.vol_c(c) * stressPower(s, c, k, gradient_k, 0.0);
}

// Material k's share of D: by mass for D >= 0 (kinetic energy of the cell's
// one velocity turned into heat: the mass carries it; by volume fraction, as
// method.md §A8 says, a gas beside a solid got half the heat for 1e-9 of the
// mass). D < 0 is an error of the second-order corner velocities, which a gas
// cannot afford below zero energy: it goes to the condensed materials by
// mass, and only without them to the gases by their internal energies.
KOKKOS_FORCEINLINE_FUNCTION double dissipationShare(const State& s, Index c, int k,
                                                    const MixedCellBudget& budget) {
  // the paper's split (docs/method.md §A8): by volume fraction
  if (s.closure == MixtureClosure::EqualStrain) return s.alpha_ck(c, k) / budget.present_alpha;
  const bool condensed = !isGasFamily(s.materials(k));
  if (budget.dissipation < 0.0 && budget.condensed_mass > 0.0) {
    return condensed ? s.m_ck(c, k) / budget.condensed_mass : 0.0;
  }
  if (budget.dissipation < 0.0 && budget.gas_heat > 0.0) {
    return s.e_ck0(c, k) > 0.0 ? s.m_ck(c, k) * s.e_ck0(c, k) / budget.gas_heat : 0.0;
  }
  return s.m_ck(c, k) / budget.present_mass;
}

// The budget of a mixed cell whose specific internal energy is now e_new.
KOKKOS_FORCEINLINE_FUNCTION void mixedCellBudget(const State& s, Index c, double e_new,
                                                 const Mat3& gradient, double dt_stage,
                                                 MixedCellBudget& budget,
                                                 StageRelaxation& relaxation) {
  ownVolumeRatios(s, c, dt_stage * s.vol_c(c) * trace(gradient), budget.own_ratio, relaxation);
  const Vec3 v0 = loadVec3(s.v_c0, c);
  budget.dissipation = s.m_c(c) * (e_new - (s.E_c0(c) - 0.5 * dot(v0, v0)));
  const bool holds_elastic = cellHoldsElasticBody(s, s.alpha_ck, c);
  for (int k = 0; k < s.n_materials; ++k) {
    const double alpha = s.alpha_ck(c, k);
    if (!(alpha > 0.0)) continue;
    budget.present_mass += s.m_ck(c, k);
    budget.present_alpha += alpha;
    if (!isGasFamily(s.materials(k))) {
      budget.condensed_mass += s.m_ck(c, k);
    } else if (s.e_ck0(c, k) > 0.0) {
      budget.gas_heat += s.m_ck(c, k) * s.e_ck0(c, k);
    }
    if (alpha >= traceFraction(s, k, holds_elastic)) {
      const Mat3 gradient_k =
          materialGradient(s, c, k, true, gradient, budget.own_ratio[k], dt_stage);
      budget.dissipation -= materialWork(s, c, k, gradient_k, budget.own_ratio[k], dt_stage);
    }
  }
}

// A hardening solid's return and its new plastic strain (the temperature of
// the step start: both stages return at the same T*). Out of line on the
// host: inlined, Johnson-Cook's iteration grew updateMaterials' frame and
// prologue for every cell (+10-22 instructions a cell-step of sedov and
// shell, which never harden).
LAGREMAP_OUT_OF_LINE KOKKOS_INLINE_FUNCTION void hardeningReturn(const State& s, Index c, int k,
                                                                 const SymMat3& trial,
                                                                 const MaterialParams& material,
                                                                 double dt_stage) {
  const PlasticUpdate plastic = plasticReturn(trial, material, s.eps_ck0(c, k), dt_stage,
                                              homologousTemperature(material, s.e_ck0(c, k)));
  storeSym(s.S_ck, c, k, plastic.S);
  s.eps_ck(c, k) = plastic.eps_p;
}
}  // namespace detail

// The materials of one cell over the stage (docs/method.md §A7-A8), given the cell's new
// specific internal energy e_new = E - |V|^2/2:
// - internal energies: a pure cell's material takes e_new; in a mixed cell
//   m^k (e^k - e^k,n) = W^k + share^k D (detail::dissipationShare), which
//   sums to the cell's change; a trace (State::alpha_trace) does no work but
//   takes its share of D, and so does a trace by mass (kMassTrace);
// - hypo-elastic deviators: objective Jaumann update of S^k with L, then
//   radial return, a hardening solid's with its plastic strain (the plastic
//   work is already in the total energy);
// - Neo-Hookean B^k = F B^k,n F^T (SPD kept), stretched along a solid body's
//   interface normal to its own volume ratio.
// A trace's deviator is not driven by the cell's strain rate (it has no say in
// the stress): it keeps its value until it is a material again.
// `relaxation`: a mixed cell's relaxation volumes, for the geometry of the same
// sweep (StageRelaxation).
// What updateMaterials does: the fused form all of it in one kernel, the
// staged form each part in a kernel of its own (the energies first: the
// deviators' updates read nothing they write, and they read the start-of-
// stage deviators the energies' stress power takes).
enum MaterialParts : int {
  kMaterialEnergies = 1,  // e^k (and a mixed cell's budget)
  kHypoElasticParts = 2,  // hypo-elastic deviators
  kNeoHookeanParts = 4,   // Neo-Hookean B (the stage deformation a corner vector at a time)
  kAllMaterialParts = 7,  // the fused form
};

template <int kParts = kAllMaterialParts>
KOKKOS_INLINE_FUNCTION void updateMaterials(const CellNodesView& cell_nodes, const Vec3View& x_n,
                                            const State& s, double dt_stage, Index c, double e_new,
                                            StageRelaxation& relaxation) {
  constexpr bool kEnergies = (kParts & kMaterialEnergies) != 0;
  constexpr bool kHypo = (kParts & kHypoElasticParts) != 0;
  constexpr bool kNeo = (kParts & kNeoHookeanParts) != 0;
  constexpr bool kStaged = kParts != kAllMaterialParts;
  int present = 0, last = 0;
  for (int k = 0; k < s.n_materials; ++k) {
    if (s.alpha_ck(c, k) > 0.0) {
      ++present;
      last = k;
    }
  }
  const bool mixed = present > 1;
  if (kEnergies && !mixed) s.e_ck(c, last) = e_new;
  // a pure fluid cell has no deviator to update (whatever its neighbours)
  if (!mixed && s.materials(last).strength == StrengthKind::None) return;
  if constexpr (!kHypo && !kNeo) {
    if (!mixed) return;  // (only a mixed cell's budget is left)
  }
  const Mat3 gradient = velocityGradient(cell_nodes, s, c);
  detail::MixedCellBudget budget;
  if (mixed) {
    if constexpr (kEnergies) {
      detail::mixedCellBudget(s, c, e_new, gradient, dt_stage, budget, relaxation);
    } else {  // the own volume ratios alone (the same numbers)
      detail::ownVolumeRatios(s, c, dt_stage * s.vol_c(c) * trace(gradient), budget.own_ratio,
                              relaxation);
    }
  }
  bool deformation_known = false;
  Mat3 deformation = zeroMat();
  const bool holds_elastic = mixed && cellHoldsElasticBody(s, s.alpha_ck, c);
  for (int k = 0; k < s.n_materials; ++k) {
    const double alpha = s.alpha_ck(c, k);
    if (!(alpha > 0.0)) continue;
    const bool trace = mixed && alpha < traceFraction(s, k, holds_elastic);
    const double own_ratio = mixed ? budget.own_ratio[k] : 1.0;
    if (kEnergies && mixed) {
      const double work =
          trace
              ? 0.0
              : detail::materialWork(
                    s, c, k, detail::materialGradient(s, c, k, true, gradient, own_ratio, dt_stage),
                    own_ratio, dt_stage);
      const double share = detail::dissipationShare(s, c, k, budget);
      s.e_ck(c, k) = s.e_ck0(c, k) + (work + share * budget.dissipation) / s.m_ck(c, k);
    }
    const MaterialParams& material = s.materials(k);
    if (trace) {
      if (kHypo && material.strength == StrengthKind::HypoElastic) {
        storeSym(s.S_ck, c, k, loadSym(s.S_ck0, c, k));
        if (hasPlasticStrain(material)) s.eps_ck(c, k) = s.eps_ck0(c, k);
      } else if (kNeo && material.strength == StrengthKind::NeoHookean) {
        storeSym(s.B_ck, c, k, loadSym(s.B_ck0, c, k));
      }
    } else if (kHypo && material.strength == StrengthKind::HypoElastic) {
      const Mat3 gradient_k =
          detail::materialGradient(s, c, k, mixed, gradient, own_ratio, dt_stage);
      const SymMat3 trial =
          jaumannUpdate(loadSym(s.S_ck0, c, k), gradient_k, material.mu, dt_stage);
      if (hasPlasticStrain(material)) {
        detail::hardeningReturn(s, c, k, trial, material, dt_stage);
      } else {  // perfectly plastic: no strain to carry
        storeSym(s.S_ck, c, k, radialReturn(trial, material.yield_stress).S);
      }
    } else if (kNeo && material.strength == StrengthKind::NeoHookean) {
      if (!deformation_known) {
        if constexpr (kStaged) {
          deformation = stagedStageDeformation(cell_nodes, x_n, s, c);
        } else {
          deformation = stageDeformation(cell_nodes, x_n, s, c);
        }
      }
      deformation_known = true;
      Mat3 own = deformation;
      Vec3 n;
      if (mixed && isSolidBody(s, c, k, n)) {
        // stretched along n to its own volume ratio: det(F_s) = J^k
        Mat3 normal_stretch = identityMat();
        addOuter(normal_stretch, own_ratio / det(deformation) - 1.0, n, n);
        own = normal_stretch * deformation;
      }
      storeSym(s.B_ck, c, k, pushForward(own, loadSym(s.B_ck0, c, k)));
    }
  }
}

// Corner forces and the update of one cell from the start-of-step state
// (docs/method.md §A4): F_cp = M_cp V_p - B_cp,
//   m_c dV_c/dt = sum_p F_cp,  m_c dE_c/dt = sum_p F_cp . V_p,
// and dv_c/dt = sum_p A_cp . V_p for the next time step.
// Returns the cell's new specific internal energy.
KOKKOS_FORCEINLINE_FUNCTION double updateCellMotion(const CellNodesView& cell_nodes, const State& s,
                                                    double dt_stage, Index c) {
  Vec3 force{0, 0, 0};
  double power = 0.0, dvdt = 0.0;
  for (int p = 0; p < 8; ++p) {
    const Index corner = 8 * c + p;
    const Vec3 v_node = loadVec3(s.v_n, cell_nodes(c, p));
    const Vec3 f_corner = loadSym(s.M_cp, corner) * v_node - loadVec3(s.B_cp, corner);
    force += f_corner;
    power += dot(f_corner, v_node);
    dvdt += dot(loadVec3(s.A_cp, corner), v_node);
  }
  const double dt_over_m = dt_stage / s.m_c(c);
  const Vec3 velocity = loadVec3(s.v_c0, c) + dt_over_m * force;
  const double total_energy = s.E_c0(c) + dt_over_m * power;
  storeVec3(s.v_c, c, velocity);
  s.E_c(c) = total_energy;
  s.dvdt_c(c) = dvdt;
  return total_energy - 0.5 * dot(velocity, velocity);
}

// ... and its materials (updateMaterials).
KOKKOS_INLINE_FUNCTION void updateCell(const CellNodesView& cell_nodes, const Vec3View& x_n,
                                       const State& s, double dt_stage, Index c,
                                       StageRelaxation& relaxation) {
  updateMaterials(cell_nodes, x_n, s, dt_stage, c, updateCellMotion(cell_nodes, s, dt_stage, c),
                  relaxation);
}

// One part of every cell's materials' update (the staged form), from the
// cell's stored E and V.
template <int kParts>
static void updateMaterialParts(const char* label, const Mesh& mesh, const State& state,
                                double dt_stage) {
  const auto cell_nodes = mesh.cell_nodes;
  const auto x_n = mesh.x_n;
  const auto s = state;
  Kokkos::parallel_for(
      label, Kokkos::RangePolicy<ExecSpace>(0, mesh.n_cells), KOKKOS_LAMBDA(const Index c) {
        const Vec3 velocity = loadVec3(s.v_c, c);
        StageRelaxation relaxation;
        updateMaterials<kParts>(cell_nodes, x_n, s, dt_stage, c,
                                s.E_c(c) - 0.5 * dot(velocity, velocity), relaxation);
      });
}

// Every cell's update: the staged form runs the cells' motion and their
// materials as two kernels (the materials' e_new = E - |V|^2/2 from the
// stored E and V: the same bits).
static inline void updateCells(const Mesh& mesh, const State& state, double dt_stage,
                               KernelForm form = defaultKernelForm()) {
  const auto cell_nodes = mesh.cell_nodes;
  const auto x_n = mesh.x_n;
  const auto s = state;
  if constexpr (kFusedKernelsBuilt) {
    if (form == KernelForm::Fused) {
      Kokkos::parallel_for(
          "lagremap::cell_update::corner_forces", Kokkos::RangePolicy<ExecSpace>(0, mesh.n_cells),
          KOKKOS_LAMBDA(const Index c) {
            StageRelaxation relaxation;
            updateCell(cell_nodes, x_n, s, dt_stage, c, relaxation);
          });
      return;
    }
  }
  Kokkos::parallel_for(
      "lagremap::cell_update::corner_forces", Kokkos::RangePolicy<ExecSpace>(0, mesh.n_cells),
      KOKKOS_LAMBDA(const Index c) { updateCellMotion(cell_nodes, s, dt_stage, c); });
  // the materials' energies, then their deviators (hypo-elastic S, Neo-Hookean
  // B), each a kernel of its own
  updateMaterialParts<kMaterialEnergies>("lagremap::cell_update::material_energies", mesh, state,
                                         dt_stage);
  if (state.has_solids) {
    updateMaterialParts<kHypoElasticParts>("lagremap::cell_update::hypo_elastic", mesh, state,
                                           dt_stage);
  }
  if (state.has_neo_hookean) {
    updateMaterialParts<kNeoHookeanParts>("lagremap::cell_update::neo_hookean", mesh, state,
                                          dt_stage);
  }
}

// The end of a stage in one sweep: each cell's update, then its geometry and
// closure at the new node positions (both cell-local, so one kernel does them
// while the cell's corner records are in cache); returns the time-step
// candidates of the new state. Same results as updateCells + computeGeometry.
// `what`: see StageEnd.
// The staged form (KernelForm) runs the cell update and the geometry as two
// kernels.
static inline StepLimit updateCellsAndGeometry(const Mesh& mesh, const State& state,
                                               double dt_stage, const TimeStepControls& controls,
                                               StageEnd what = StageEnd::Full,
                                               KernelForm form = defaultKernelForm()) {
  const auto cell_nodes = mesh.cell_nodes;
  const auto x_n = mesh.x_n;
  const auto s = state;
  if constexpr (kFusedKernelsBuilt) {
    if (form == KernelForm::Fused) {
      if (what == StageEnd::ForRemap) {
        return stepLimitOverCellGeometries<false>(
            "lagremap::cell_update::update_and_shape", mesh,
            KOKKOS_LAMBDA(const Index c, const hex::CellGeometry& geometry, StepLimit& best) {
              StageRelaxation relaxation;
              updateCell(cell_nodes, x_n, s, dt_stage, c, relaxation);
              cellShapeForRemap(geometry.shape, s, c, best, &relaxation);
            });
      }
      return stepLimitOverCellGeometries<true>(
          "lagremap::cell_update::update_and_geometry", mesh,
          KOKKOS_LAMBDA(const Index c, const hex::CellGeometry& geometry, StepLimit& best) {
            StageRelaxation relaxation;
            updateCell(cell_nodes, x_n, s, dt_stage, c, relaxation);
            cellThermoOnGeometry(geometry, s, controls, c, best, true, &relaxation);
          });
    }
  }
  updateCells(mesh, state, dt_stage, KernelForm::Staged);
  // the mixed cells' volume sharing, then the checks or the closure on the
  // shared volumes (a kernel each: together they held 154 registers on sm_90)
  if (state.n_materials > 1) shareVolumeChanges(mesh, state);
  const bool z_prisms = mesh.z_prisms;
  if (what == StageEnd::ForRemap) {
    return stepLimitOverCellNodes(
        "lagremap::cell_update::shape", mesh,
        KOKKOS_LAMBDA(const NodesOfCell& nodes, StepLimit& best) {
          hex::PrismBase base{};  // (read on prisms only)
          cellShapeForRemap(stagedShape(nodes, z_prisms, base), s, nodes.c, best, nullptr, false);
        });
  }
  return stepLimitOverCellNodes(
      "lagremap::cell_update::geometry", mesh,
      KOKKOS_LAMBDA(const NodesOfCell& nodes, StepLimit& best) {
        cellThermoOnNodes(nodes, z_prisms, s, controls, best, false);
      });
}

}  // namespace lagremap
