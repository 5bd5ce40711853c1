#include "remap_step.hpp"

#include <algorithm>
#include <stdexcept>

#include "kokkos_events.hpp"
#include "parallel.hpp"
#include "state_setup.hpp"

namespace lagremap {

RemapLayout makeRemapLayout(const State& state) {
  if (state.n_materials > kMaxMaterials) {
    throw std::invalid_argument("remap: at most " + std::to_string(kMaxMaterials) + " materials");
  }
  const auto materials = Kokkos::create_mirror_view_and_copy(HostSpace(), state.materials);
  RemapLayout layout;
  layout.n_materials = state.n_materials;
  for (int k = 0; k < kMaxMaterials; ++k) layout.tensor_column[k] = -1;
  for (int k = 0; k < kMaxMaterials; ++k) layout.plastic_column[k] = -1;
  for (int v = 0; v < kMaxRemapVariables; ++v) layout.column_material[v] = -1;
  int column = 3 * state.n_materials;  // the plastic strains after the energies
  for (int k = 0; k < state.n_materials; ++k) {
    if (!hasPlasticStrain(materials(k))) continue;
    layout.plastic_column[k] = column;
    layout.column_material[column] = k;
    ++column;
  }
  layout.momentum_begin = column;
  column += 4;  // momentum and kinetic energy
  for (int k = 0; k < state.n_materials; ++k) {
    layout.column_material[layout.mass(k)] = k;
    layout.column_material[layout.energy(k)] = k;
    if (materials(k).strength == StrengthKind::None) continue;
    layout.tensor_column[k] = column;
    for (int i = 0; i < 6; ++i) layout.column_material[column + i] = k;
    column += 6;
  }
  layout.n_variables = column;
  return layout;
}

RemapStep::RemapStep(Mesh& mesh, State& state, const RemapControls& controls, PhaseTimers& timers,
                     const Halo* halo)
    : mesh_(mesh),
      state_(state),
      controls_(controls),
      timers_(timers),
      halo_(halo),
      layout_(makeRemapLayout(state)) {
  const Index n_cells = mesh.n_cells;
  // The target, the mesh's current nodes, is where every step starts: the
  // state's start-of-step positions hold it (LagrangeStep::remapFollowsEveryStep).
  Kokkos::deep_copy(state.x_n0, mesh.x_n);
  // The remap's work arrays live within apply(); the state's corner arrays
  // from a computeGeometry to the end of the next Lagrangian step, and the
  // caller computes the geometry after each apply(): one allocation holds both.
  WorkArena corners_size, work_size;
  State sized;
  carveCornerArrays(sized, n_cells, corners_size);
  carveRemapFields(n_cells, layout_, controls.kernels, work_size);
  carveSweptFaces(mesh, work_size);
  shared_work_ =
      RealView("lagremap::remap::shared_work", std::max(corners_size.used(), work_size.used()));
  WorkArena corners(shared_work_), work(shared_work_);
  carveCornerArrays(state, n_cells, corners);
  fields_ = carveRemapFields(n_cells, layout_, controls.kernels, work);
  swept_ = carveSweptFaces(mesh, work);
  state.m_ck0 = MatRealView("lagremap::state::m_ck0", n_cells, state.n_materials);
  if (halo_) remapped_fields_ = remappedCellFields(state);
}

void RemapStep::launch(const Vec3View& target, const RemapAuditView& audit) {
  {
    auto scope = timers_.scope(Phase::Remap);
    remapDensitiesAndSweptFaces(mesh_, state_, layout_, fields_, mesh_.x_n, target, swept_,
                                controls_.kernels);
    remapGradients(mesh_, state_, layout_, controls_, fields_);
    if (!controls_.reconstruct) Kokkos::deep_copy(fields_.gradient, 0.0);
    remapUpdate(mesh_, state_, layout_, controls_, fields_, swept_, audit);
    remapAuditAndMoveNodes(mesh_, state_, layout_, fields_, swept_, {mesh_.x_n, target}, audit,
                           controls_.kernels);
  }
  if (halo_) {  // ghost cells: their owners' remapped state (docs/method.md §7.4, src/fields.hpp)
    auto scope = timers_.scope(Phase::Halo);
    halo_->exchangeCells(remapped_fields_);
  }
}

RemapBoundaryFlux RemapStep::apply(const Vec3View& target) {
  launch(target, audit_);
  fenceFor("lagremap::remap: the boundary crossings");
  RemapBoundaryFlux crossed = remapAuditOf(audit_).crossed;
  parallel::sum(crossed.v, 5);
  return crossed;
}

void RemapStep::restoreStartOfStep() {
  // a cell's mass is the sum of its materials' in every state (the set-up's,
  // the remap's, storeRemappedCell): the same sum gives the same bits
  const auto m_c = state_.m_c;
  const auto m_ck = state_.m_ck;
  const auto m_ck0 = state_.m_ck0;
  const int n_materials = state_.n_materials;
  Kokkos::parallel_for(
      "lagremap::remap::restore_masses", Kokkos::RangePolicy<ExecSpace>(0, m_c.extent(0)),
      KOKKOS_LAMBDA(const Index c) {
        double mass = 0.0;
        for (int k = 0; k < n_materials; ++k) {
          m_ck(c, k) = m_ck0(c, k);
          mass += m_ck(c, k);
        }
        m_c(c) = mass;
      });
}

}  // namespace lagremap
