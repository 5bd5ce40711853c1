// The corner terms in the staged form (KernelForm::Staged, docs/method.md
// §7.6): the fused form's arithmetic (corner_terms_fused.hpp) split into
// kernels that each hold a part of it, through a row of gradients and
// limiter factors per cell. Launched by computeCornerTerms (corner_terms.hpp).
#pragma once

#include "../data/mesh.hpp"
#include "../data/state.hpp"
#include "corner_stencil.hpp"
#include "geometry.hpp"
#include "hex.hpp"
#include "reconstruction.hpp"

namespace lagremap {

namespace detail {

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

}  // namespace detail

}  // namespace lagremap
