// Nodal solver (docs/method.md §A4): per node, M_p V_p = B_p + external load
// under the velocity constraints, and the node's new position (into
// x_n_next: x_n is still read for the traction load of neighbouring nodes;
// the caller swaps them); a decomposed run's ghost nodes then move with
// their owners' velocities. The corner terms M_cp, B_cp come from
// computeCornerTerms (corner_terms.hpp); the cell update (cell_update.hpp)
// follows. The node sums use the node->corner CRS by default (race-free,
// bit-for-bit reproducible for any thread count); `Gather::Atomics` reads
// the sums the corner kernel scattered instead.
// Its kernel launchers are `static` (internal linkage: docs/method.md §7.2).
#pragma once

#include "../data/mesh.hpp"
#include "../data/state.hpp"
#include "audit_sums.hpp"
#include "corner_controls.hpp"
#include "hex.hpp"
#include "step_start.hpp"

namespace lagremap {

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
KOKKOS_FORCEINLINE_FUNCTION bool isAxisProjector(const SymMat3& projector) {
  return projector.xy == 0.0 && projector.yz == 0.0 && projector.xz == 0.0;
}
KOKKOS_FORCEINLINE_FUNCTION SymMat3 constrainedMatrix(const SymMat3& projector, const SymMat3& m) {
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
KOKKOS_FORCEINLINE_FUNCTION Vec3 project(const SymMat3& projector, const Vec3& v) {
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

// One node's solve (nodalSolve), the Views it reads, not the whole Mesh
// (whose global ids live on the host).
struct NodeSolver {
  CellFacesView cell_face_side;
  CellNodesView cell_nodes;
  DeviceView<int*> node_projector_id;
  IndexView node_corner_offsets, node_corners, node_solve_order;
  Sym6View projectors;
  IndexView node_traction_faces, node_traction_offsets;
  DeviceView<Real[kNumSides][6]> side_traction;
  Vec3View x_n;
  IndexView twin_source;
  DeviceView<int*> twin_flip;
  IndexView twin_offsets, node_twins;
  DeviceView<int*> node_owned;
  State s;
  Vec3View x_start;  // where the nodes were at t^n: x_n0, or x_n in a first stage that saves
  double dt_stage;
  bool twins, atomics, save_start;

  NodeSolver(const Mesh& mesh, const State& state, const CornerControls& controls, double dt_stage,
             bool save_start)
      : cell_face_side(mesh.cell_face_side),
        cell_nodes(mesh.cell_nodes),
        node_projector_id(mesh.node_projector_id),
        node_corner_offsets(mesh.node_corner_offsets),
        node_corners(mesh.node_corners),
        node_solve_order(mesh.node_solve_order),
        projectors(mesh.projectors),
        node_traction_faces(mesh.node_traction_faces),
        node_traction_offsets(mesh.node_traction_offsets),
        side_traction(mesh.side_traction),
        x_n(mesh.x_n),
        twin_source(mesh.node_twin_source),
        twin_flip(mesh.node_twin_flip),
        twin_offsets(mesh.node_twin_offsets),
        node_twins(mesh.node_twins),
        node_owned(mesh.node_owned),
        s(state),
        x_start(save_start ? mesh.x_n : state.x_n0),
        dt_stage(dt_stage),
        twins(mesh.node_twin_source.extent(0) > 0),
        atomics(controls.gather == Gather::Atomics),
        save_start(save_start) {}

  // M_p and B_p: the node's corner sums (the CRS gather), or what the corner
  // kernel scattered (Gather::Atomics). (Summed in locals, returned by value:
  // sums kept in a caller's references are stored and reloaded at every
  // corner, which may alias the corner records.)
  struct Sums {
    SymMat3 impedance;
    Vec3 rhs;
  };
  KOKKOS_FORCEINLINE_FUNCTION Sums nodeSums(Index n) const {
    if (atomics) return {loadSym(s.M_n, n), loadVec3(s.B_n, n)};
    SymMat3 impedance = identitySym(0.0);
    Vec3 rhs{0, 0, 0};
    for (Index i = node_corner_offsets(n); i < node_corner_offsets(n + 1); ++i) {
      const Index corner = node_corners(i);
      impedance += loadSym(s.M_cp, corner);
      rhs += loadVec3(s.B_cp, corner);
    }
    return {impedance, rhs};
  }

  // External load of node n's traction faces: sum_bf s_pf sigma^b n_pf.
  KOKKOS_FORCEINLINE_FUNCTION Vec3 tractionLoad(Index n) const {
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
      const SymMat3 sigma_b{side_traction(side, 0), side_traction(side, 1), side_traction(side, 2),
                            side_traction(side, 3), side_traction(side, 4), side_traction(side, 5)};
      load += sigma_b * w[local];
    }
    return load;
  }

  // The node's new velocity, position and external force (and its twins'),
  // their force and power added to `power` (force xyz, F . V) where owned.
  KOKKOS_FORCEINLINE_FUNCTION void solve(Index visit, BoundaryPowerSums& power) const {
    const Index n = node_solve_order(visit);
    if (!atomics) {
      detail::prefetchCornerRecords(s, node_solve_order, node_corner_offsets, node_corners,
                                    twin_source, visit);
    }
    if (save_start) copyNodeStart(s, x_n, n, StepStart::Save);
    if (twins && twin_source(n) != n) return;  // its source writes its solution (below)
    const Sums sums = nodeSums(n);
    const SymMat3& impedance = sums.impedance;
    const Vec3& rhs = sums.rhs;
    const Vec3 load = tractionLoad(n);
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
    // External force on the node (sum_c F_cp up to round-off): wall reaction
    // plus traction load, for the conservation audit.
    const Vec3 force = reaction + load;
    store(n, velocity, force, power);
    if (!twins) return;
    // A slab's or bar's twin nodes (Mesh::node_twins): this node's velocity
    // (its components normal to the planes are zero) and its external force
    // mirrored.
    for (Index i = twin_offsets(n); i < twin_offsets(n + 1); ++i) {
      const Index twin = node_twins(i);
      const int flip = twin_flip(twin);
      store(twin, velocity,
            Vec3{flip & 1 ? -force.x : force.x, flip & 2 ? -force.y : force.y,
                 flip & 4 ? -force.z : force.z},
            power);
    }
  }

  // Node n's velocity, external force and new position; its force and power
  // added to `power` where this rank owns it.
  KOKKOS_FORCEINLINE_FUNCTION void store(Index n, const Vec3& velocity, const Vec3& force,
                                         BoundaryPowerSums& power) const {
    storeVec3(s.v_n, n, velocity);
    storeVec3(s.f_ext_n, n, force);
    storeVec3(s.x_n_next, n, loadVec3(x_start, n) + dt_stage * velocity);
    if (node_owned(n)) addBoundaryPower(force, velocity, power);
  }
};

}  // namespace detail

// Solves every node and finds where it moves: x_n_next = x_n0 + dt_stage V_n.
// `save_start`: a step's first stage, whose nodes start at x_n, which x_n0
// keeps (StepStartSave); `power`: also sums the boundary's power into it
// (the last stage's, a reduction).
static inline void nodalSolve(const Mesh& mesh, const State& state, const CornerControls& controls,
                              double dt_stage, bool save_start = false,
                              const BoundaryPowerView& power = {}) {
  const detail::NodeSolver solver(mesh, state, controls, dt_stage, save_start);
  const char* label =
      solver.atomics ? "lagremap::nodal_solve::atomics_sum" : "lagremap::nodal_solve::crs_gather";
  const auto visits = Kokkos::RangePolicy<ExecSpace>(0, mesh.n_nodes);
  if (power.data() != nullptr) {
    Kokkos::parallel_reduce(
        label, visits,
        KOKKOS_LAMBDA(const Index visit, BoundaryPowerSums& sum) { solver.solve(visit, sum); },
        Kokkos::Sum<BoundaryPowerSums, ReportSpace>(power));
    return;
  }
  Kokkos::parallel_for(
      label, visits, KOKKOS_LAMBDA(const Index visit) {
        BoundaryPowerSums unused;
        solver.solve(visit, unused);
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

}  // namespace lagremap
