// The corner kernel's stencil and its limited reconstruction of V and sigma
// at a cell's vertices (docs/method.md §A5, §2.1-§2.5): what stands across
// each face (a neighbour, a wall's mirror image, nothing), the least-squares
// stencil gathered over the faces, and the node velocities, stresses (a
// solid) or pressures (a fluid) limited from it. Written for a scalar Real
// (cell_lanes.hpp); the fused corner terms (corner_terms_fused.hpp) call it,
// the staged form (corner_terms_staged.hpp) the stencil's faces alone.
#pragma once

#include "../data/boundary.hpp"
#include "../data/state.hpp"
#include "cell_lanes.hpp"
#include "hex.hpp"
#include "reconstruction.hpp"

namespace lagremap {

namespace detail {

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

}  // namespace detail

}  // namespace lagremap
