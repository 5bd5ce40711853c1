// Swept-face geometry of the remap (docs/method.md §A9), the first kernel of the remap
// phase. Every face triangle of docs/method.md §A2, (q_k, q_k+1, face point) oriented out
// of its cell, moves on straight paths from its Lagrangian position (a, b, c) to
// its position on the initial mesh (a', b', c'). The region it sweeps is bounded
// by the two triangles and three ruled (bilinear) side patches, each fixed by
// the two end points of its edge alone, so neighbouring triangles of the same
// face, of the next face of the cell and of the neighbouring cell share them
// exactly and the regions of a cell telescope:
//
//   V_new = V_lag + sum_{t in T(c)} dV_t,   (V x_c)_new = (V x_c)_lag + sum_{t in T(c)} M_t.
//
// Sign: dV_t > 0 when the triangle moves outward, i.e. cell c gains the region
// from its neighbour across the face.
// Its kernel launchers are `static` (internal linkage: docs/method.md §7.2).
#pragma once

#include "../data/mesh.hpp"
#include "../data/work_arena.hpp"
#include "hex.hpp"
#include "kernel_form.hpp"

namespace lagremap {

namespace swept {

// Signed volume and first moment (integral of x, absolute coordinates) of one
// swept region.
struct SweptRegion {
  double volume;
  Vec3 moment;
};

// dV_t = 1/18 (d_a + d_b + d_c) . [e1 x e2 + e1' x e2' + 1/2 (e1 x e2' + e1' x e2)]
// (docs/method.md §A9): the exact integral of d(xi) . J(tau) over xi in the triangle and
// tau in [0, 1] for the map x(xi, tau) below. Only differences of positions
// enter, so it keeps its relative accuracy far from the origin.
KOKKOS_INLINE_FUNCTION double sweptVolume(const Vec3& a, const Vec3& b, const Vec3& c,
                                          const Vec3& a_target, const Vec3& b_target,
                                          const Vec3& c_target) {
  const Vec3 e1 = b - a, e2 = c - a;
  const Vec3 e1_target = b_target - a_target, e2_target = c_target - a_target;
  const Vec3 d_sum = (a_target - a) + (b_target - b) + (c_target - c);
  const Vec3 twice_mean_area = cross(e1, e2) + cross(e1_target, e2_target) +
                               0.5 * (cross(e1, e2_target) + cross(e1_target, e2));
  return dot(d_sum, twice_mean_area) / 18.0;
}

// Tensor rule of docs/method.md §A9 for x(xi, tau) = X(xi) + tau d(xi), X on the
// Lagrangian triangle, d(xi) = X'(xi) - X(xi), Jacobian d(xi) . J(tau) with
// J(tau) = (e1 + tau de1) x (e2 + tau de2). The integrand x d.J has degree 2 in
// xi (edge-midpoint rule, exact for degree 2) and 3 in tau (2-point Gauss,
// exact for degree 3); weights 1/6 (triangle area 1/2 over 3 points) times 1/2.
// At an edge midpoint X and d are the midpoints of the edge and of its two
// displacements. Summed relative to a and shifted by a * volume at the end, so
// the round-off of the sum scales with the triangle, not with |a|.
KOKKOS_INLINE_FUNCTION SweptRegion sweptTensorRule(const Vec3& a, const Vec3& b, const Vec3& c,
                                                   const Vec3& a_target, const Vec3& b_target,
                                                   const Vec3& c_target) {
  const Vec3 e1 = b - a, e2 = c - a;
  const Vec3 d_a = a_target - a, d_b = b_target - b, d_c = c_target - c;
  const Vec3 de1 = d_b - d_a, de2 = d_c - d_a;
  // Edge midpoints xi = (1/2, 0), (1/2, 1/2), (0, 1/2): X - a and d(xi).
  const Vec3 x_mid[3] = {0.5 * e1, 0.5 * (e1 + e2), 0.5 * e2};
  const Vec3 d_mid[3] = {0.5 * (d_a + d_b), 0.5 * (d_b + d_c), 0.5 * (d_c + d_a)};
  // Gauss points tau = 1/2 -+ 1/(2 sqrt 3) on [0, 1].
  constexpr double kGaussOffset = 0.28867513459481288225457439025098;
  const double taus[2] = {0.5 - kGaussOffset, 0.5 + kGaussOffset};
  double volume = 0.0;
  Vec3 moment{0.0, 0.0, 0.0};  // relative to a
  for (const double tau : taus) {
    const Vec3 jacobian = cross(e1 + tau * de1, e2 + tau * de2);
    for (int m = 0; m < 3; ++m) {
      const double weight = dot(d_mid[m], jacobian);
      volume += weight;
      moment += weight * (x_mid[m] + tau * d_mid[m]);
    }
  }
  volume *= 1.0 / 12.0;
  return {volume, a * volume + (1.0 / 12.0) * moment};
}

// What the kernels use: the tensor rule's volume and first moment, from the
// same sums (the closed formula sweptVolume agrees to round-off, and costs
// three more cross products).
KOKKOS_INLINE_FUNCTION SweptRegion sweptTriangle(const Vec3& a, const Vec3& b, const Vec3& c,
                                                 const Vec3& a_target, const Vec3& b_target,
                                                 const Vec3& c_target) {
  return sweptTensorRule(a, b, c, a_target, b_target, c_target);
}

// The 4 triangles of a face in lanes, one per triangle (structure of arrays).
struct FaceLanes {
  double x[4], y[4], z[4];
  KOKKOS_INLINE_FUNCTION Vec3 operator[](int k) const { return {x[k], y[k], z[k]}; }
  KOKKOS_INLINE_FUNCTION void set(int k, const Vec3& v) {
    x[k] = v.x;
    y[k] = v.y;
    z[k] = v.z;
  }
};

// The 4 swept triangles of one face: q_lag / q_target are its 4 nodes in
// outward order (hex::faceNode) on each mesh, and each polygon is split around
// its own face point (docs/method.md §A2), which moves on a straight path like a node.
// swept[k] belongs to triangle (q_k, q_k+1, face point). The triangles are
// evaluated in lanes (triangle k in lane k: the same operations of
// sweptTriangle in the same order on each lane, so the same bits), which the
// compiler vectorises across the 4 triangles (forced inline: as a call it
// cost the kernel more).
KOKKOS_FORCEINLINE_FUNCTION void sweptFace(const Vec3 q_lag[4], const Vec3 q_target[4],
                                           SweptRegion swept[4]) {
  const Vec3 face_point_lag = 0.25 * (q_lag[0] + q_lag[1] + q_lag[2] + q_lag[3]);
  const Vec3 face_point_target = 0.25 * (q_target[0] + q_target[1] + q_target[2] + q_target[3]);
  FaceLanes a, b, a_target, b_target;
  for (int k = 0; k < 4; ++k) {
    const int next = (k + 1) & 3;
    a.set(k, q_lag[k]);
    b.set(k, q_lag[next]);
    a_target.set(k, q_target[k]);
    b_target.set(k, q_target[next]);
  }
  double volume[4];
  FaceLanes moment;
  for (int k = 0; k < 4; ++k) {
    const SweptRegion region =
        sweptTriangle(a[k], b[k], face_point_lag, a_target[k], b_target[k], face_point_target);
    volume[k] = region.volume;
    moment.set(k, region.moment);
  }
  for (int k = 0; k < 4; ++k) swept[k] = {volume[k], moment[k]};
}

// The 4 swept triangles of a side face of a z prism (Mesh::z_prisms), in
// closed form (docs/method.md §5.2). The face is the rectangle over the
// bottom edge from a to b (cell order, so that e x e_z points out of the
// cell) and its height h; its nodes move in the xy plane only, so at every
// tau it is still a rectangle over the edge A(tau) B(tau). With s along the
// edge, z up the face and tau in time, the swept region is
// x(s, z, tau) = A(tau) + s E(tau) + z e_z, whose Jacobian is
//   sigma(s, tau) = D(s) . (E(tau) x e_z) = alpha + beta s + gamma tau,
// D(s) = d_a + s (d_b - d_a) the displacement, E(tau) = e + tau (d_b - d_a).
// Each of the face's 4 triangles around its centre covers, at s, a z range
// [z_lo(s), z_hi(s)] of width h w_t(s): the bottom and top triangles the tent
// w = min(s, 1 - s), the side triangles 2 s - 1 (s > 1/2) and 1 - 2 s
// (s < 1/2). So dV_t = h int w_t sigma and M_t = int (x, y) h w_t sigma and
// int (z_hi^2 - z_lo^2) / 2 sigma, polynomial integrals in s and tau, from
// the moments mu_i = int w_t s^i ds of each weight (tent 1/4, 1/8, 7/96;
// right 1/4, 5/24, 17/96; left 1/4, 1/24, 1/96) and nu_i = int min(s, 1 -
// s)^2 s^i ds = 1/12, 1/24 for the z moments of the bottom and top
// triangles. The same regions as sweptFace's, to round-off (test_swept_face).
KOKKOS_INLINE_FUNCTION void sweptPrismSide(const Vec3& a, const Vec3& b, const Vec3& a_target,
                                           const Vec3& b_target, double height,
                                           SweptRegion swept[4]) {
  auto cross2 = [](double ux, double uy, double vx, double vy) { return ux * vy - uy * vx; };
  const double ex = b.x - a.x, ey = b.y - a.y;
  const double dax = a_target.x - a.x, day = a_target.y - a.y;
  const double dex = (b_target.x - b.x) - dax, dey = (b_target.y - b.y) - day;
  // sigma = D(s) . (E(tau) x e_z) = cross2(D, E)
  const double alpha = cross2(dax, day, ex, ey);
  const double beta = cross2(dex, dey, ex, ey);
  const double gamma = cross2(dax, day, dex, dey);
  constexpr double kMu[3][3] = {{1.0 / 4.0, 1.0 / 8.0, 7.0 / 96.0},    // bottom and top
                                {1.0 / 4.0, 5.0 / 24.0, 17.0 / 96.0},  // side at b
                                {1.0 / 4.0, 1.0 / 24.0, 1.0 / 96.0}};  // side at a
  const double z_bottom = a.z, z_middle = a.z + 0.5 * height;
  // (z_hi^2 - z_lo^2) / 2 of the bottom triangle relative to z_bottom: h^2 w^2 / 2
  const double bottom_z =
      0.5 * height * height * (alpha * (1.0 / 12.0) + beta * (1.0 / 24.0) + gamma * (1.0 / 24.0));
  for (int t = 0; t < 3; ++t) {
    const double* mu = kMu[t];
    // int w sigma, int w tau sigma, int w s sigma, int w s tau sigma
    const double w_sigma = alpha * mu[0] + beta * mu[1] + 0.5 * gamma * mu[0];
    const double w_tau = 0.5 * alpha * mu[0] + 0.5 * beta * mu[1] + (1.0 / 3.0) * gamma * mu[0];
    const double w_s = alpha * mu[1] + beta * mu[2] + 0.5 * gamma * mu[1];
    const double w_s_tau = 0.5 * alpha * mu[1] + 0.5 * beta * mu[2] + (1.0 / 3.0) * gamma * mu[1];
    const double volume = height * w_sigma;
    // int (a + tau d_a + s e + s tau d_e) h w sigma, relative to a
    const double moment_x = height * (w_tau * dax + w_s * ex + w_s_tau * dex);
    const double moment_y = height * (w_tau * day + w_s * ey + w_s_tau * dey);
    const Vec3 in_plane{a.x * volume + moment_x, a.y * volume + moment_y, 0.0};
    if (t == 0) {  // bottom and top: the same volume and xy moment
      swept[0] = {volume, Vec3{in_plane.x, in_plane.y, z_bottom * volume + bottom_z}};
      swept[2] = {volume,
                  Vec3{in_plane.x, in_plane.y, z_bottom * volume + height * volume - bottom_z}};
    } else {
      swept[t == 1 ? 1 : 3] = {volume, Vec3{in_plane.x, in_plane.y, z_middle * volume}};
    }
  }
}

// The bottom edge (k, k + 1) of side face f (0 x-, 1 x+, 2 y-, 3 y+) of a
// hexahedron, in the order that puts the cell on its left.
KOKKOS_INLINE_FUNCTION int prismSideEdge(int f) {
  return f == 0 ? 3 : (f == 1 ? 1 : (f == 2 ? 0 : 2));
}

// Whether the 4 points q_lag, q_target share coordinate `axis` (0, 1, 2: x,
// y, z) with q_lag[0], stopping at the first that does not.
KOKKOS_INLINE_FUNCTION bool sharesCoordinate(const Vec3 q_lag[4], const Vec3 q_target[4],
                                             int axis) {
  auto coordinate = [axis](const Vec3& q) { return axis == 0 ? q.x : (axis == 1 ? q.y : q.z); };
  const double plane = coordinate(q_lag[0]);
  for (int k = 0; k < 4; ++k) {
    if (!(coordinate(q_lag[k]) == plane && coordinate(q_target[k]) == plane)) return false;
  }
  return true;
}

// True when a face's Lagrangian and target positions all lie in one plane
// normal to a coordinate axis: a wall or symmetry plane along x, y or z, in
// which the nodes slide (their projected velocity has an exact zero normal
// component). The region it sweeps is flat, so dV_t = 0 and the tensor rule
// gives exactly 0 too (every cross product is normal to the plane, every
// displacement in it): a one-cell slab's two faces on its symmetry planes,
// half of its swept faces, need no swept-region computation.
KOKKOS_INLINE_FUNCTION bool staysInOneAxisPlane(const Vec3 q_lag[4], const Vec3 q_target[4]) {
  // (one axis after the other, each stopping at its first difference: a face
  // normal to z costs a few comparisons along x and along y)
  return sharesCoordinate(q_lag, q_target, 0) || sharesCoordinate(q_lag, q_target, 1) ||
         sharesCoordinate(q_lag, q_target, 2);
}

}  // namespace swept

// Storage of the swept regions, by face side: the 4 triangles of a face are
// summed, by the side they take their region from, into two regions,
//   gained (side 0): the triangles with dV_t > 0, which cell c takes from its
//                    neighbour (upwind: the neighbour);
//   given  (side 1): those with dV_t < 0 (upwind: c itself),
// and a triangle with dV_t = 0 joins the side of the lower cell id, the
// upwind choice of method.md §A9 for a tie. A region's flux is linear in its
// volume and first moment (F = dV q_up + grad(q)_up . (M - x_up dV)), so the
// sum of the triangles' fluxes is the flux of the sum: the remap evaluates
// one or two fluxes a face instead of four (docs/method.md §5.2, on the
// guards that are not linear). Slot r = 12 c + 2 f + side, oriented out of
// cell c. Every interior face is computed once, by its owner (the cell with
// the lower id), which writes its own 2 slots and the exact negatives into
// the neighbour's 2 slots of the same face, sides exchanged, so both sides
// hold the same bits up to sign; boundary faces are computed by their only
// cell. A cell then finds all its regions in its own 12 contiguous slots.
constexpr int kSweptRegionsPerCell = kFacesPerCell * 2;
constexpr int kGainedSide = 0, kGivenSide = 1;

KOKKOS_INLINE_FUNCTION Index sweptRegionId(Index c, int f, int side) {
  return kSweptRegionsPerCell * c + 2 * f + side;
}

struct SweptFaces {
  RealView dvol_r;    // signed swept volume dV (>= 0 gained, <= 0 given)
  Vec3View moment_r;  // first moment M, absolute coordinates
  RealView memory;    // what holds them (allocateSweptFaces; empty when carved from a RemapStep's)
};

// The swept regions carved out of `arena`: computeSweptFaces writes every
// region, so the memory may hold anything before.
inline SweptFaces carveSweptFaces(const Mesh& mesh, WorkArena& arena) {
  const Index n_regions = kSweptRegionsPerCell * mesh.n_cells;
  SweptFaces swept;
  swept.dvol_r = arena.carve<RealView>(n_regions);
  swept.moment_r = arena.carve<Vec3View>(n_regions);
  return swept;
}

// The same in memory of their own (label lagremap::remap::swept_faces).
inline SweptFaces allocateSweptFaces(const Mesh& mesh) {
  WorkArena size;
  carveSweptFaces(mesh, size);
  const RealView memory("lagremap::remap::swept_faces", size.used());
  WorkArena arena(memory);
  SweptFaces swept = carveSweptFaces(mesh, arena);
  swept.memory = memory;
  return swept;
}

namespace swept {

// The swept regions of cell c's faces (computeSweptFaces). kHold: the cell's
// 16 node positions are loaded once and held (the fused form); else each
// face loads its own (the staged form: a GPU thread holds 4 positions at a
// time, not 16). The triangles are summed into the face's two sides by
// selection (a triangle adds +0 to the other side, which leaves a sum that is
// never -0 unchanged): the same bits as a branch, and no indexed pair.
template <bool kHold>
KOKKOS_FORCEINLINE_FUNCTION void cellSweptFaces(const CellNodesView& cell_nodes,
                                                const CellFacesView& cell_neighbors,
                                                const CellFacesView& cell_neighbor_face,
                                                const Vec3View& x_lag, const Vec3View& x_target,
                                                const RealView& dvol_r, const Vec3View& moment_r,
                                                bool z_prisms, Index c) {
  Vec3 held_lag[kHold ? 8 : 1], held_target[kHold ? 8 : 1];
  if constexpr (kHold) {
    for (int p = 0; p < 8; ++p) {
      const Index node = cell_nodes(c, p);
      held_lag[p] = loadVec3(x_lag, node);
      held_target[p] = loadVec3(x_target, node);
    }
  }
  const auto lag = [&](int p) {
    if constexpr (kHold) {
      return held_lag[p];
    } else {
      return loadVec3(x_lag, cell_nodes(c, p));
    }
  };
  const auto target = [&](int p) {
    if constexpr (kHold) {
      return held_target[p];
    } else {
      return loadVec3(x_target, cell_nodes(c, p));
    }
  };
  LAGREMAP_NO_UNROLL
  for (int f = 0; f < 6; ++f) {
    const Index neighbor = cell_neighbors(c, f);
    if (neighbor >= 0 && neighbor < c) continue;  // the neighbour owns this face
    Vec3 q_lag[4], q_target[4];
    for (int k = 0; k < 4; ++k) {
      q_lag[k] = lag(hex::faceNode(f, k));
      q_target[k] = target(hex::faceNode(f, k));
    }
    // (the owner has the lower id: a tie goes to its given side)
    SweptRegion gained{0.0, Vec3{0.0, 0.0, 0.0}}, given{0.0, Vec3{0.0, 0.0, 0.0}};
    if (!(neighbor < 0 && staysInOneAxisPlane(q_lag, q_target))) {
      const Vec3 nothing{0.0, 0.0, 0.0};
      const auto add = [&](const SweptRegion& region) {
        const bool gains = region.volume > 0.0;
        gained.volume += gains ? region.volume : 0.0;
        gained.moment += gains ? region.moment : nothing;
        given.volume += gains ? 0.0 : region.volume;
        given.moment += gains ? nothing : region.moment;
      };
      SweptRegion swept[4];
      if (z_prisms && f < 4) {  // a side face of a prism: closed form
        const int k = prismSideEdge(f), next = (k + 1) & 3;
        sweptPrismSide(lag(k), lag(next), target(k), target(next), lag(4).z - lag(0).z, swept);
        for (int t = 0; t < 4; ++t) add(swept[t]);
      } else if (kHold) {  // the 4 triangles in lanes
        sweptFace(q_lag, q_target, swept);
        for (int t = 0; t < 4; ++t) add(swept[t]);
      } else {  // one triangle at a time, its nodes reloaded
        const Vec3 face_point_lag = 0.25 * (q_lag[0] + q_lag[1] + q_lag[2] + q_lag[3]);
        const Vec3 face_point_target =
            0.25 * (q_target[0] + q_target[1] + q_target[2] + q_target[3]);
        LAGREMAP_NO_UNROLL
        for (int t = 0; t < 4; ++t) {
          const int a = hex::faceNode(f, t), b = hex::faceNode(f, (t + 1) & 3);
          add(sweptTriangle(lag(a), lag(b), face_point_lag, target(a), target(b),
                            face_point_target));
        }
      }
    }
    dvol_r(sweptRegionId(c, f, kGainedSide)) = gained.volume;
    storeVec3(moment_r, sweptRegionId(c, f, kGainedSide), gained.moment);
    dvol_r(sweptRegionId(c, f, kGivenSide)) = given.volume;
    storeVec3(moment_r, sweptRegionId(c, f, kGivenSide), given.moment);
    if (neighbor < 0) continue;
    // the neighbour gives what we gain and gains what we give
    const int g = cell_neighbor_face(c, f);
    dvol_r(sweptRegionId(neighbor, g, kGivenSide)) = -gained.volume;
    storeVec3(moment_r, sweptRegionId(neighbor, g, kGivenSide), -gained.moment);
    dvol_r(sweptRegionId(neighbor, g, kGainedSide)) = -given.volume;
    storeVec3(moment_r, sweptRegionId(neighbor, g, kGainedSide), -given.moment);
  }
}

// What cellSweptFaces reads and writes: the mesh's connectivity, the two
// node sets and the regions (a kernel's captures).
struct CellSweeper {
  CellNodesView cell_nodes;
  CellFacesView cell_neighbors, cell_neighbor_face;
  Vec3View x_lag, x_target;
  RealView dvol_r;
  Vec3View moment_r;
  bool z_prisms;

  CellSweeper(const Mesh& mesh, const Vec3View& lag, const Vec3View& target,
              const SweptFaces& faces)
      : cell_nodes(mesh.cell_nodes),
        cell_neighbors(mesh.cell_neighbors),
        cell_neighbor_face(mesh.cell_neighbor_face),
        x_lag(lag),
        x_target(target),
        dvol_r(faces.dvol_r),
        moment_r(faces.moment_r),
        z_prisms(mesh.z_prisms) {}

  template <bool kHold>
  KOKKOS_FORCEINLINE_FUNCTION void sweep(Index c) const {
    cellSweptFaces<kHold>(cell_nodes, cell_neighbors, cell_neighbor_face, x_lag, x_target, dvol_r,
                          moment_r, z_prisms, c);
  }
};

}  // namespace swept

// Swept volumes and first moments of every face, by side, moving from the
// Lagrangian node positions x_lag to the remap target x_target (the initial
// mesh), docs/method.md §A9. `form`: see KernelForm (the same bits).
static inline void computeSweptFaces(const Mesh& mesh, const Vec3View& x_lag,
                                     const Vec3View& x_target, const SweptFaces& swept_faces,
                                     KernelForm form = defaultKernelForm()) {
  const swept::CellSweeper sweeper(mesh, x_lag, x_target, swept_faces);
  const auto policy = Kokkos::RangePolicy<ExecSpace>(0, mesh.n_cells);
  if constexpr (kFusedKernelsBuilt) {
    if (form == KernelForm::Fused) {
      Kokkos::parallel_for(
          "lagremap::remap::swept_faces", policy,
          KOKKOS_LAMBDA(const Index c) { sweeper.sweep<true>(c); });
      return;
    }
  }
  Kokkos::parallel_for(
      "lagremap::remap::swept_faces", policy,
      KOKKOS_LAMBDA(const Index c) { sweeper.sweep<false>(c); });
}

}  // namespace lagremap
