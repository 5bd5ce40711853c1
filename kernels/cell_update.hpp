// The cell update at the end of a stage (docs/method.md §A4): the corner
// forces F_cp = M_cp V_p - B_cp from the solved node velocities
// (nodal_solver.hpp), each cell's momentum and total energy, then its
// materials (material_update.hpp); and updateCellsAndGeometry, which follows
// it with the cell's geometry and closure at the new node positions
// (geometry.hpp) in one sweep, or in separate kernels in the staged form.
// Its kernel launchers are `static` (internal linkage: docs/method.md §7.2).
#pragma once

#include "../data/mesh.hpp"
#include "../data/state.hpp"
#include "cell_teams.hpp"
#include "geometry.hpp"
#include "hex.hpp"
#include "kernel_form.hpp"
#include "material_update.hpp"
#include "material_update_staged.hpp"
#include "time_step.hpp"

namespace lagremap {

// The update of one cell from the start-of-step state (docs/method.md §A4)
// by the sums over its corners of F_cp, F_cp . V_p and A_cp . V_p:
//   m_c dV_c/dt = sum_p F_cp,  m_c dE_c/dt = sum_p F_cp . V_p,
// and dv_c/dt = sum_p A_cp . V_p for the next time step.
// Returns the cell's new specific internal energy.
KOKKOS_FORCEINLINE_FUNCTION double moveCell(const State& s, double dt_stage, Index c,
                                            const Vec3& force, double power, double dvdt) {
  const double dt_over_m = dt_stage / s.m_c(c);
  const Vec3 velocity = loadVec3(s.v_c0, c) + dt_over_m * force;
  const double total_energy = s.E_c0(c) + dt_over_m * power;
  storeVec3(s.v_c, c, velocity);
  s.E_c(c) = total_energy;
  s.dvdt_c(c) = dvdt;
  return total_energy - 0.5 * dot(velocity, velocity);
}

// Corner p's force F_cp = M_cp V_p - B_cp, and the node's velocity.
KOKKOS_FORCEINLINE_FUNCTION Vec3 cornerForce(const CellNodesView& cell_nodes, const State& s,
                                             Index c, int p, Vec3& v_node) {
  const Index corner = 8 * c + p;
  v_node = loadVec3(s.v_n, cell_nodes(c, p));
  return loadSym(s.M_cp, corner) * v_node - loadVec3(s.B_cp, corner);
}

// Corner forces and the update of one cell (moveCell), its corners in turn.
KOKKOS_FORCEINLINE_FUNCTION double updateCellMotion(const CellNodesView& cell_nodes, const State& s,
                                                    double dt_stage, Index c) {
  Vec3 force{0, 0, 0};
  double power = 0.0, dvdt = 0.0;
  for (int p = 0; p < 8; ++p) {
    Vec3 v_node;
    const Vec3 f_corner = cornerForce(cell_nodes, s, c, p, v_node);
    force += f_corner;
    power += dot(f_corner, v_node);
    dvdt += dot(loadVec3(s.A_cp, 8 * c + p), v_node);
  }
  return moveCell(s, dt_stage, c, force, power, dvdt);
}

namespace detail {
// The same in the staged form: corner p's terms by lane p (cell_teams.hpp),
// then their sums in corner order, the same bits. kOneMaterial: the cell's
// one material takes e^k = e_new (what updateMaterials sets); with several,
// the materials share e_new out (MaterialLanes::energies: a mixed cell's
// budget from the velocity terms the corner lanes leave in the row, the
// budget's columns before the motion's).
template <bool kOneMaterial>
struct CellMotionOnLanes {
  enum : int {
    kBase = kOneMaterial ? 0 : int(material_lanes::kBudgetColumns),
    kForce = kBase,
    kPower = kBase + 24,
    kDvdt = kBase + 32,
    kColumns = kBase + 40,
  };
  using Teams = Kokkos::TeamPolicy<ExecSpace>;

  MaterialLanes lanes;
  Index n_cells;

  KOKKOS_INLINE_FUNCTION void operator()(const Teams::member_type& team) const {
    const State& s = lanes.s;
    cell_teams::forCellsOfTeam(
        team, n_cells, kColumns, [&](Index c, const cell_teams::ScratchRow& row) {
          Kokkos::parallel_for(Kokkos::ThreadVectorRange(team, 8), [&](const int p) {
            Vec3 v_node;
            const Vec3 f_corner = cornerForce(lanes.cell_nodes, s, c, p, v_node);
            const Vec3 corner_vector = loadVec3(s.A_cp, 8 * c + p);
            row.store(kForce + 3 * p, f_corner);
            row(kPower + p) = dot(f_corner, v_node);
            row(kDvdt + p) = dot(corner_vector, v_node);
            if constexpr (!kOneMaterial) {
              MaterialLanes::storeVelocityTerms(row, p, v_node, corner_vector);
            }
          });
          double e_new = 0.0;
          Kokkos::single(
              Kokkos::PerThread(team),
              [&](double& e) {
                Vec3 force{0, 0, 0};
                double power = 0.0, dvdt = 0.0;
                for (int p = 0; p < 8; ++p) {
                  force += row.vec3(kForce + 3 * p);
                  power += row(kPower + p);
                  dvdt += row(kDvdt + p);
                }
                e = moveCell(s, lanes.dt_stage, c, force, power, dvdt);
                if constexpr (kOneMaterial) s.e_ck(c, 0) = e;
              },
              e_new);
          if constexpr (!kOneMaterial) lanes.energies(team, c, row, e_new);
        });
  }
};
}  // namespace detail

// ... and its materials (updateMaterials).
KOKKOS_FORCEINLINE_FUNCTION void updateCell(const CellNodesView& cell_nodes, const Vec3View& x_n,
                                            const State& s, double dt_stage, Index c,
                                            StageRelaxation& relaxation) {
  updateMaterials(cell_nodes, x_n, s, dt_stage, c, updateCellMotion(cell_nodes, s, dt_stage, c),
                  relaxation);
}

// The staged form's cell motion (detail::CellMotionOnLanes), with a mixed
// run's energies.
template <bool kOneMaterial>
static void updateCellMotion(const Mesh& mesh, const State& state, double dt_stage) {
  using Motion = detail::CellMotionOnLanes<kOneMaterial>;
  const Motion motion{{mesh.cell_nodes, mesh.x_n, state, dt_stage}, mesh.n_cells};
  Kokkos::parallel_for(
      "lagremap::cell_update::corner_forces",
      cell_teams::overCells<typename Motion::Teams>(mesh.n_cells, Motion::kColumns), motion);
}

// The staged form's second kernel of the cell update: the deviators of the
// kinds kKinds (DeviatorKinds; detail::StagedDeviators).
template <int kKinds>
static void updateDeviators(const Mesh& mesh, const State& state, double dt_stage) {
  using Deviators = detail::StagedDeviators<kKinds>;
  const Deviators deviators{{mesh.cell_nodes, mesh.x_n, state, dt_stage}, mesh.n_cells};
  Kokkos::parallel_for("lagremap::cell_update::deviators",
                       cell_teams::overCells<typename Deviators::Teams>(
                           mesh.n_cells, detail::material_lanes::kColumns),
                       deviators);
}

// The staged form's cell update: the cells' motion and a mixed run's
// energies (detail::CellMotionOnLanes), then, with solids, their deviators
// (updateDeviators). (A mixed cell's volume sharing at its new shape is the
// stage-end geometry's, detail::StagedGeometry, as in the fused form.)
static inline void updateCellsStaged(const Mesh& mesh, const State& state, double dt_stage) {
  if (state.n_materials > 1) {
    updateCellMotion<false>(mesh, state, dt_stage);
  } else {
    updateCellMotion<true>(mesh, state, dt_stage);
  }
  // the deviators of the strengths the materials have (both where the state
  // does not say, State::has_hypo_elastic)
  const bool known = state.has_hypo_elastic || state.has_neo_hookean;
  const bool hypo = state.has_solids && (state.has_hypo_elastic || !known);
  const bool neo = state.has_solids && (state.has_neo_hookean || !known);
  // (both kinds in a kernel each: in one they spilled on sm_90)
  if (hypo) updateDeviators<kHypoElasticDeviators>(mesh, state, dt_stage);
  if (neo) updateDeviators<kNeoHookeanDeviators>(mesh, state, dt_stage);
}

// Every cell's update, in the form asked for (the volumes not shared).
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
  updateCellsStaged(mesh, state, dt_stage);
}

// The end of a stage in one sweep: each cell's update, then its geometry and
// closure at the new node positions (both cell-local, so one kernel does them
// while the cell's corner records are in cache); returns the time-step
// candidates of the new state, left in `into` without waiting. Same results
// as updateCells + computeGeometry.
// `what`: see StageEnd.
// The staged form (KernelForm) runs the cell update and the geometry as two
// kernels.
static inline void updateCellsAndGeometry(const Mesh& mesh, const State& state, double dt_stage,
                                          const TimeStepControls& controls,
                                          const StepLimitView& into, StageEnd what = StageEnd::Full,
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
            },
            into);
      }
      return stepLimitOverCellGeometries<true>(
          "lagremap::cell_update::update_and_geometry", mesh,
          KOKKOS_LAMBDA(const Index c, const hex::CellGeometry& geometry, StepLimit& best) {
            StageRelaxation relaxation;
            updateCell(cell_nodes, x_n, s, dt_stage, c, relaxation);
            cellThermoOnGeometry(geometry, s, controls, c, best, true, &relaxation);
          },
          into);
    }
  }
  // the cells' update, then the mixed cells' volume sharing and the checks
  // or the closure at the new shapes
  updateCellsStaged(mesh, state, dt_stage);
  if (what == StageEnd::ForRemap) {
    return stepLimitOverCellNodes<StageEnd::ForRemap>("lagremap::cell_update::shape", mesh, state,
                                                      controls, into, true);
  }
  stepLimitOverCellNodes<StageEnd::Full>("lagremap::cell_update::geometry", mesh, state, controls,
                                         into, true);
}

}  // namespace lagremap
