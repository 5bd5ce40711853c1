// The corner terms in the staged form (KernelForm::Staged, docs/method.md
// §7.6): the fused form's arithmetic (corner_terms_fused.hpp) laid out for a
// GPU, one kernel, a cell to each thread of a team and its faces, rows of
// gradients, vertices and corners in the lanes of a vector (8 on a GPU: four
// cells a warp). Launched by computeCornerTerms (corner_terms.hpp).
#pragma once

#include "../data/mesh.hpp"
#include "../data/state.hpp"
#include "cell_teams.hpp"
#include "cell_thermo.hpp"
#include "corner_stencil.hpp"
#include "hex.hpp"
#include "kernel_form.hpp"
#include "reconstruction.hpp"
#include "step_start.hpp"

namespace lagremap {

namespace detail {

// The staged form of the corner terms (KernelForm::Staged, docs/method.md
// §7.6). A cell's lanes take one face, one gradient row, one vertex or one
// corner each, and leave what the others read in the team's scratch memory
// (a row of columns per cell, below, each written once a stage); the sums
// over faces and the limiters' minima over vertices are then taken by every
// lane in the fused form's order, so the bits are the fused form's.
namespace corner_lanes {
// (enumerators, not constexpr variables: device code takes them by reference)
enum : int {
  kDx = 0,         // 6 x 3: the offset across each face (zero for a free side)
  kDv = 18,        // 6 x 3: the velocity jump (an open side's continued)
  kDs = 36,        // 6 x 6: the stress jump (a solid) or the pressure jump (a fluid: first)
  kFace = 72,      // 6: StencilFace across each face
  kGrad = 78,      // 9 x 3: the gradients of V_x, V_y, V_z, then sigma's 6 (a solid) or p's
  kPulled = 105,   // 6 x 3: a solid's pulled-back jumps (pullBack)
  kReachV = 123,   // 8: the velocity limiter's reach at each vertex
  kScaledV = 131,  // 8: ... and its scaled squared length
  kLengthV = 139,  // 8: ... and |delta_p|^2
  kReachS = 147,   // 8, 8, 8: the same for the stress limiter
  kScaledS = 155,
  kLengthS = 163,
  kV = 171,  // 3, 3, 1, 6: the cell's V, centroid, p and sigma
  kCentroid = 174,
  kP = 177,
  kSigma = 178,
  kColumns = 184,
};
}  // namespace corner_lanes

using cell_teams::ScratchRow;
// (a GPU's block of 128 threads, 6 an SM: at most 80 registers, no spill on
// sm_90, 24 warps an SM where 128 registers ran 16)
using CornerTeams = Kokkos::TeamPolicy<ExecSpace, Kokkos::LaunchBounds<128, 6>>;
using TeamMember = CornerTeams::member_type;

// The face row's StencilFace across face f, and whether it is an open side.
KOKKOS_FORCEINLINE_FUNCTION StencilFace faceOf(const ScratchRow& row, int f) {
  return StencilFace(int(row(corner_lanes::kFace + f)));
}
KOKKOS_FORCEINLINE_FUNCTION bool openSide(const ScratchRow& row, int f) {
  return faceOf(row, f) == StencilFace::None;
}

// projectedLimiter (reconstruction.hpp) at one vertex: its reach and scaled
// squared length from the 6 jumps (`jump(f)`), the direction of its
// excursion and |delta_p|^2; VertexLimiter takes the minimum over vertices.
template <bool plateau_guard, bool vertex_sums, class Jump>
KOKKOS_INLINE_FUNCTION void vertexReach(const Jump& jump, int p, const Vec3& direction,
                                        double length2, double& reach, double& length2_scaled) {
  double toward = 0.0, away = 0.0, along[6];
  for (int f = 0; f < 6; ++f) {
    const Vec3 jump_f = jump(f);
    along[f] = jump_f.x * direction.x + jump_f.y * direction.y + jump_f.z * direction.z;
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
  reach = toward;
  length2_scaled = length2;
  if (plateau_guard && toward < away) {
    reach = 0.5 * toward * (away * away + toward * toward);
    length2_scaled = length2 * (away * away);
  }
}

// The smallest reach / length over the vertices, in vertex order (the
// comparison without a division, as projectedLimiter).
struct VertexLimiter {
  double limiter = 1.0;
  KOKKOS_FORCEINLINE_FUNCTION void include(double reach, double length2_scaled) {
    if (reach < limiter * length2_scaled) limiter = reach / length2_scaled;
  }
};

struct StagedCorners {
  CellNodesView cell_nodes;
  CellFacesView neighbors;
  CellFacesView face_side;
  DeviceView<int[kNumSides]> side_kind;
  Vec3View x_n;
  State s;
  bool z_prisms, second_order, atomics;
  Index n_cells;
  StepStartSave start;  // the first stage's: the cells' step start kept

  // What a cell's lanes share: its index, nodes and row of the team's
  // scratch, which holds its values (read where they are used: fewer
  // registers held through the stage).
  struct Cell {
    Index c;
    NodesOfCell nodes;
    bool solid;
    ScratchRow row;
    KOKKOS_FORCEINLINE_FUNCTION Vec3 v() const { return row.vec3(corner_lanes::kV); }
    KOKKOS_FORCEINLINE_FUNCTION Vec3 centroid() const { return row.vec3(corner_lanes::kCentroid); }
    KOKKOS_FORCEINLINE_FUNCTION double p() const { return row(corner_lanes::kP); }
    KOKKOS_FORCEINLINE_FUNCTION SymMat3 sigma() const { return row.sym(corner_lanes::kSigma); }
  };

  // Lane j: the cell's value j into its row: V, centroid, p and sigma = S - p I
  // (a fluid's -p I).
  KOKKOS_INLINE_FUNCTION void loadCell(const TeamMember& team, const Cell& cell) const {
    Kokkos::parallel_for(Kokkos::ThreadVectorRange(team, 13), [&](const int j) {
      const Index c = cell.c;
      double value;
      if (j < 3) {
        value = s.v_c(c, j);
      } else if (j < 6) {
        value = s.x_c(c, j - 3);
      } else if (j == 6) {
        value = s.p_c(c);
      } else {
        const int k = j - 7;  // (xx, yy, zz, xy, yz, xz)
        const double identity = k < 3 ? -s.p_c(c) : 0.0;
        value = cell.solid ? s.S_c(c, k) + identity : identity;
      }
      cell.row(corner_lanes::kV + j) = value;
    });
  }

  // What stands across face f: the offset dx to it, the velocity jump dv and
  // (a mirror) the wall's normal; false for a free side (no jump).
  KOKKOS_INLINE_FUNCTION bool across(const Cell& cell, int f, StencilFace& face, Vec3& dx, Vec3& dv,
                                     Vec3& normal) const {
    face = stencilFace(neighbors, face_side, side_kind, cell.c, f);
    if (face == StencilFace::Neighbour) {
      const Index nb = neighbors(cell.c, f);
      dx = loadVec3(s.x_c, nb) - cell.centroid();
      dv = loadVec3(s.v_c, nb) - cell.v();
      return true;
    }
    if (face == StencilFace::None) return false;
    if (z_prisms && f >= 4) {
      const double side = f == 4 ? -1.0 : 1.0;
      normal = Vec3{0.0, 0.0, side};
      dx = Vec3{0.0, 0.0, side * (cell.nodes(4).z - cell.nodes(0).z)};
      dv = Vec3{0.0, 0.0, -2.0 * cell.v().z};
    } else {
      mirrorAcrossFace(cell.nodes, f, cell.centroid(), cell.v(), dx, dv, normal);
    }
    return true;
  }

  KOKKOS_INLINE_FUNCTION int vertices() const { return z_prisms ? 4 : kHexVertices; }

  // Lane f: what stands across face f, its offset and its jumps of V and of
  // sigma (a solid) or p (a fluid); zero across a free side.
  KOKKOS_INLINE_FUNCTION void faces(const TeamMember& team, const Cell& cell) const {
    Kokkos::parallel_for(Kokkos::ThreadVectorRange(team, 6), [&](const int f) {
      StencilFace face;
      Vec3 dx{0.0, 0.0, 0.0}, dv{0.0, 0.0, 0.0}, normal{0.0, 0.0, 0.0};
      const bool present = across(cell, f, face, dx, dv, normal);
      cell.row.store(corner_lanes::kDx + 3 * f, dx);
      cell.row.store(corner_lanes::kDv + 3 * f, dv);
      cell.row(corner_lanes::kFace + f) = double(int(face));
      const Index nb = neighbors(cell.c, f);
      if (cell.solid) {
        const SymMat3 sigma_cell = cell.sigma();
        const SymMat3 jump = !present ? identitySym(0.0)
                             : face == StencilFace::Mirror
                                 ? mirrorJump(sigma_cell, normal)
                                 : loadSym(s.S_c, nb) + identitySym(-s.p_c(nb)) - sigma_cell;
        cell.row.store(corner_lanes::kDs + 6 * f, jump);
      } else {
        cell.row(corner_lanes::kDs + 6 * f) =
            face == StencilFace::Neighbour ? s.p_c(nb) - cell.p() : 0.0;
      }
    });
  }

  // The least-squares normal matrix's inverse (every lane, in face order).
  KOKKOS_INLINE_FUNCTION SymMat3 normalInverse(const ScratchRow& row) const {
    LeastSquares lsq;
    for (int f = 0; f < 6; ++f) {
      if (!openSide(row, f)) lsq.addOffset(row.vec3(corner_lanes::kDx + 3 * f));
    }
    return lsq.solver();
  }

  // Lane r: gradient row r, V's 3 then sigma's 6 (a solid) or p's 1, from
  // the jumps across the faces with a neighbour or a mirror.
  KOKKOS_INLINE_FUNCTION void gradients(const TeamMember& team, const Cell& cell,
                                        const SymMat3& inv) const {
    Kokkos::parallel_for(Kokkos::ThreadVectorRange(team, cell.solid ? 9 : 4), [&](const int r) {
      Vec3 rhs{0.0, 0.0, 0.0};
      for (int f = 0; f < 6; ++f) {
        if (openSide(cell.row, f)) continue;
        const double jump = r < 3 ? cell.row(corner_lanes::kDv + 3 * f + r)
                                  : cell.row(corner_lanes::kDs + 6 * f + (r - 3));
        rhs += jump * cell.row.vec3(corner_lanes::kDx + 3 * f);
      }
      cell.row.store(corner_lanes::kGrad + 3 * r, inv * rhs);
    });
  }

  // An open side's jump is the opposite one reversed (continueAcrossOpenSides),
  // lane f for face f (a lane writes only where its opposite lane does not).
  KOKKOS_INLINE_FUNCTION void continueAcrossOpenSides(const TeamMember& team, const Cell& cell,
                                                      int column) const {
    Kokkos::parallel_for(Kokkos::ThreadVectorRange(team, 6), [&](const int f) {
      if (openSide(cell.row, f) && !openSide(cell.row, f ^ 1)) {
        cell.row.store(column + 3 * f, -1.0 * cell.row.vec3(column + 3 * (f ^ 1)));
      }
    });
  }

  // The velocity's limiter factor (limitedNodeVelocities): lane p's vertex.
  KOKKOS_INLINE_FUNCTION double velocityLimiter(const TeamMember& team, const Cell& cell) const {
    continueAcrossOpenSides(team, cell, corner_lanes::kDv);
    const ScratchRow& row = cell.row;
    Kokkos::parallel_for(Kokkos::ThreadVectorRange(team, vertices()), [&](const int p) {
      const Vec3 offset = cell.nodes(p) - cell.centroid();
      Vec3 grad[3];
      for (int i = 0; i < 3; ++i) grad[i] = row.vec3(corner_lanes::kGrad + 3 * i);
      const Vec3 direction{grad[0].x * offset.x + grad[0].y * offset.y + grad[0].z * offset.z,
                           grad[1].x * offset.x + grad[1].y * offset.y + grad[1].z * offset.z,
                           grad[2].x * offset.x + grad[2].y * offset.y + grad[2].z * offset.z};
      const double length2 =
          direction.x * direction.x + direction.y * direction.y + direction.z * direction.z;
      const auto jump = [&](int f) { return row.vec3(corner_lanes::kDv + 3 * f); };
      double reach, scaled;
      if (cell.solid) {
        vertexReach<true, true>(jump, p, direction, length2, reach, scaled);
      } else {
        vertexReach<false, true>(jump, p, direction, length2, reach, scaled);
      }
      row(corner_lanes::kReachV + p) = reach;
      row(corner_lanes::kScaledV + p) = scaled;
      row(corner_lanes::kLengthV + p) = length2;
    });
    VertexLimiter phi_v;
    double longest2 = 0.0;
    for (int p = 0; p < vertices(); ++p) {
      phi_v.include(row(corner_lanes::kReachV + p), row(corner_lanes::kScaledV + p));
      const double length2 = row(corner_lanes::kLengthV + p);
      longest2 = length2 > longest2 ? length2 : longest2;
    }
    const double sound_speed = s.aL_c(cell.c);
    return phi_v.limiter * phi_v.limiter * longest2 > sound_speed * sound_speed
               ? sound_speed / math::sqrt(longest2)
               : phi_v.limiter;
  }

  // A fluid's pressure limiter factor (limitedNodePressures), every lane.
  KOKKOS_INLINE_FUNCTION double pressureLimiter(const Cell& cell, double stress_scale) const {
    Bounds pb(cell.p());
    for (int f = 0; f < 6; ++f) {
      if (!openSide(cell.row, f)) pb.include(cell.p() + cell.row(corner_lanes::kDs + 6 * f));
    }
    const Vec3 grad_p = cell.row.vec3(corner_lanes::kGrad + 9);
    VertexExcursion excursion;
    double largest = 0.0;
    for (int p = 0; p < vertices(); ++p) {
      const Vec3 offset = cell.nodes(p) - cell.centroid();
      const double dp = grad_p.x * offset.x + grad_p.y * offset.y + grad_p.z * offset.z;
      excursion.include(dp);
      const double size = math::fabs(dp);
      largest = size > largest ? size : largest;
    }
    const double phi_p = cellLimiter(excursion, cell.p(), pb, 1.0);
    return phi_p * largest > stress_scale ? stress_scale / largest : phi_p;
  }

  // A solid's stress limiter factor (limitedNodeStresses): the excursions'
  // squares at the vertices (lane p), the pulled-back jumps (lane f), then
  // each vertex's reach (lane p).
  KOKKOS_INLINE_FUNCTION double stressLimiter(const TeamMember& team, const Cell& cell,
                                              double stress_scale) const {
    const ScratchRow& row = cell.row;
    const auto gradient = [&](int i) { return row.vec3(corner_lanes::kGrad + 9 + 3 * i); };
    Kokkos::parallel_for(Kokkos::ThreadVectorRange(team, vertices()), [&](const int p) {
      const Vec3 d = cell.nodes(p) - cell.centroid();
      double e[6];
      for (int i = 0; i < 6; ++i) {
        const Vec3 g = gradient(i);
        e[i] = g.x * d.x + g.y * d.y + g.z * d.z;
      }
      row(corner_lanes::kLengthS + p) =
          e[0] * e[0] + e[1] * e[1] + e[2] * e[2] + 2.0 * (e[3] * e[3] + e[4] * e[4] + e[5] * e[5]);
    });
    Kokkos::parallel_for(Kokkos::ThreadVectorRange(team, 6), [&](const int f) {
      const SymMat3 t = row.sym(corner_lanes::kDs + 6 * f);
      row.store(corner_lanes::kPulled + 3 * f, t.xx * gradient(0) + t.yy * gradient(1) +
                                                   t.zz * gradient(2) + (2.0 * t.xy) * gradient(3) +
                                                   (2.0 * t.yz) * gradient(4) +
                                                   (2.0 * t.xz) * gradient(5));
    });
    continueAcrossOpenSides(team, cell, corner_lanes::kPulled);
    Kokkos::parallel_for(Kokkos::ThreadVectorRange(team, vertices()), [&](const int p) {
      const auto jump = [&](int f) { return row.vec3(corner_lanes::kPulled + 3 * f); };
      double reach, scaled;
      vertexReach<true, false>(jump, p, cell.nodes(p) - cell.centroid(),
                               row(corner_lanes::kLengthS + p), reach, scaled);
      row(corner_lanes::kReachS + p) = reach;
      row(corner_lanes::kScaledS + p) = scaled;
    });
    VertexLimiter phi;
    double largest2 = 0.0;
    for (int p = 0; p < vertices(); ++p) {
      const double length2 = row(corner_lanes::kLengthS + p);
      largest2 = length2 > largest2 ? length2 : largest2;
      phi.include(row(corner_lanes::kReachS + p), row(corner_lanes::kScaledS + p));
    }
    return phi.limiter * phi.limiter * largest2 > stress_scale * stress_scale
               ? stress_scale / math::sqrt(largest2)
               : phi.limiter;
  }

  // Lane p: corner p's node values and B_cp (repeatBottomVertices: a z
  // prism's top vertices take the bottom ones' values).
  KOKKOS_INLINE_FUNCTION void rightHandSides(const TeamMember& team, const Cell& cell, double phi_v,
                                             double phi_s) const {
    Kokkos::parallel_for(Kokkos::ThreadVectorRange(team, 8), [&](const int p) {
      const Vec3 v_cell = cell.v();
      const SymMat3 sigma_cell = cell.sigma();
      Vec3 v_node = v_cell;
      SymMat3 sigma_node = sigma_cell;
      double p_node = cell.p();
      if (second_order) {
        const Vec3 offset = cell.nodes(z_prisms ? p & 3 : p) - cell.centroid();
        const auto along = [&](int r) {
          const Vec3 g = cell.row.vec3(corner_lanes::kGrad + 3 * r);
          return g.x * offset.x + g.y * offset.y + g.z * offset.z;
        };
        v_node = Vec3{v_cell.x + phi_v * along(0), v_cell.y + phi_v * along(1),
                      v_cell.z + phi_v * along(2)};
        if (cell.solid) {
          sigma_node = {sigma_cell.xx + phi_s * along(3), sigma_cell.yy + phi_s * along(4),
                        sigma_cell.zz + phi_s * along(5), sigma_cell.xy + phi_s * along(6),
                        sigma_cell.yz + phi_s * along(7), sigma_cell.xz + phi_s * along(8)};
        } else {
          p_node = cell.p() + phi_s * along(3);
        }
      }
      const Index corner = 8 * cell.c + p;
      const Vec3 area = loadVec3(s.A_cp, corner);
      const Vec3 stress_force = cell.solid ? -(sigma_node * area) : p_node * area;
      storeVec3(s.B_cp, corner, loadSym(s.M_cp, corner) * v_node + stress_force);
      if (atomics) {
        const Index node = cell_nodes(cell.c, p);
        for (int j = 0; j < 6; ++j) Kokkos::atomic_add(&s.M_n(node, j), s.M_cp(corner, j));
        for (int j = 0; j < 3; ++j) Kokkos::atomic_add(&s.B_n(node, j), s.B_cp(corner, j));
      }
    });
  }

  // Cell c's corner terms, its lanes working in `row`.
  KOKKOS_INLINE_FUNCTION void ofCell(const TeamMember& team, Index c, const ScratchRow& row) const {
    const bool solid = s.aT_c(c) > 0.0;
    const Cell cell{c, NodesOfCell{cell_nodes, x_n, c}, solid, row};
    if (start.cells) {
      Kokkos::single(Kokkos::PerThread(team),
                     [&] { copyCellStart(s, c, start.solids, StepStart::Save); });
    }
    loadCell(team, cell);
    double phi_v = 0.0, phi_s = 0.0;
    if (second_order) {
      faces(team, cell);
      gradients(team, cell, normalInverse(row));
      phi_v = velocityLimiter(team, cell);
      const double sound_speed = s.aL_c(c);
      const double stress_scale = s.rho_c(c) * sound_speed * sound_speed;
      phi_s = solid ? stressLimiter(team, cell, stress_scale) : pressureLimiter(cell, stress_scale);
    }
    rightHandSides(team, cell, phi_v, phi_s);
  }

  // A team's cells, one to each of its threads.
  KOKKOS_INLINE_FUNCTION void operator()(const TeamMember& team) const {
    cell_teams::forCellsOfTeam(team, n_cells, corner_lanes::kColumns,
                               [&](Index c, const ScratchRow& row) { ofCell(team, c, row); });
  }

  CornerTeams policy() const {
    return cell_teams::overCells<CornerTeams>(n_cells, corner_lanes::kColumns);
  }
};

}  // namespace detail

}  // namespace lagremap
