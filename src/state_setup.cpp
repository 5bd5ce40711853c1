#include "state_setup.hpp"

#include "fields.hpp"

namespace lagremap {

State allocateState(const Mesh& mesh, bool with_atomics_gather, bool own_corner_arrays) {
  const Index nc = mesh.n_cells, nn = mesh.n_nodes, ncorner = 8 * mesh.n_cells;
  State s;
  auto cells = [&](const char* name) {
    return RealView(std::string("lagremap::state::") + name, nc);
  };
  auto cells3 = [&](const char* name) {
    return Vec3View(std::string("lagremap::state::") + name, nc);
  };
  s.m_c = cells("m_c");
  s.v_c = cells3("v_c");
  s.E_c = cells("E_c");
  s.S_c = Sym6View("lagremap::state::S_c", nc);
  s.vol_c = cells("vol_c");
  s.rho_c = cells("rho_c");
  s.e_c = cells("e_c");
  s.p_c = cells("p_c");
  s.aL_c = cells("aL_c");
  s.aT_c = cells("aT_c");
  s.len_c = cells("len_c");
  s.x_c = cells3("x_c");
  s.dvdt_c = cells("dvdt_c");
  s.x_n0 = Vec3View("lagremap::state::x_n0", nn);
  s.v_c0 = cells3("v_c0");
  s.E_c0 = cells("E_c0");
  if (own_corner_arrays) {
    s.A_cp = Vec3View("lagremap::state::A_cp", ncorner);
    s.M_cp = Sym6View("lagremap::state::M_cp", ncorner);
    s.B_cp = Vec3View("lagremap::state::B_cp", ncorner);
  }
  s.v_n = Vec3View("lagremap::state::v_n", nn);
  s.x_n_next = Vec3View("lagremap::state::x_n_next", nn);
  s.f_ext_n = Vec3View("lagremap::state::f_ext_n", nn);
  if (with_atomics_gather) {
    s.M_n = Sym6View("lagremap::state::M_n", nn);
    s.B_n = Vec3View("lagremap::state::B_n", nn);
  }
  return s;
}

namespace {
// `carved` takes the place of `view`, with its values when it had any.
template <class ViewType>
void moveInto(ViewType& view, const ViewType& carved) {
  if (view.size() > 0) Kokkos::deep_copy(carved, view);
  view = carved;
}
}  // namespace

void carveCornerArrays(State& s, Index n_cells, WorkArena& arena) {
  const Index ncorner = 8 * n_cells;
  moveInto(s.A_cp, arena.carve<Vec3View>(ncorner));
  moveInto(s.M_cp, arena.carve<Sym6View>(ncorner));
  moveInto(s.B_cp, arena.carve<Vec3View>(ncorner));
}

void allocateMaterialState(State& s, Index n_cells, int n_materials, bool has_solids,
                           bool has_neo_hookean, bool has_plastic_strain) {
  auto scalars = [&](const char* name) {
    return MatRealView(std::string("lagremap::state::") + name, n_cells, n_materials);
  };
  // Tensors exist only when some material has strength: a gas run carries none.
  const Index tensor_cells = has_solids ? n_cells : 0;
  auto tensors = [&](const char* name, Index cells) {
    return MatSym6View(std::string("lagremap::state::") + name, cells, n_materials);
  };
  s.n_materials = n_materials;
  s.has_solids = has_solids;
  s.alpha_ck = scalars("alpha_ck");
  s.m_ck = scalars("m_ck");
  s.e_ck = scalars("e_ck");
  s.e_ck0 = scalars("e_ck0");
  s.p_ck = scalars("p_ck");
  s.w_ck = scalars("w_ck");
  s.w_ck0 = scalars("w_ck0");
  s.p_ck0 = scalars("p_ck0");
  s.alpha_ck0 = scalars("alpha_ck0");
  s.vol_c0 = RealView("lagremap::state::vol_c0", n_cells);
  s.S_ck = tensors("S_ck", tensor_cells);
  s.S_ck0 = tensors("S_ck0", tensor_cells);
  const Index left_cauchy_green_cells = has_neo_hookean ? n_cells : 0;
  s.B_ck = tensors("B_ck", left_cauchy_green_cells);
  s.B_ck0 = tensors("B_ck0", left_cauchy_green_cells);
  const Index plastic_cells = has_plastic_strain ? n_cells : 0;
  s.eps_ck = MatRealView("lagremap::state::eps_ck", plastic_cells, n_materials);
  s.eps_ck0 = MatRealView("lagremap::state::eps_ck0", plastic_cells, n_materials);
  s.n_ck = MatVec3View("lagremap::state::n_ck", has_solids && n_materials > 1 ? n_cells : 0,
                       n_materials);
}

namespace {
// Tensors exist only in runs with solids (extent 0 otherwise): nothing to move.
template <class ViewType>
void addIfAllocated(std::vector<FieldRef>& list, const std::string& name, const ViewType& view) {
  if (view.extent(0) > 0 && view.size() > 0) list.push_back(fieldRef(name, view));
}

// The tensors the materials evolve, for the halo: S^k (hypo-elastic) and
// B^k (Neo-Hookean; its S^k follows from B^k in the closure), both when the
// state does not say (State::has_hypo_elastic, has_neo_hookean).
void addEvolvedTensors(std::vector<FieldRef>& list, const State& s) {
  const bool known = s.has_hypo_elastic || s.has_neo_hookean;
  if (s.has_hypo_elastic || !known) {
    addIfAllocated(list, "S_ck", s.S_ck);
    addIfAllocated(list, "eps_ck", s.eps_ck);
  }
  if (s.has_neo_hookean || !known) addIfAllocated(list, "B_ck", s.B_ck);
}

// The evolved state (what a checkpoint holds): every tensor View, or
// (halo) only the tensors the materials evolve.
void addEvolvedFields(std::vector<FieldRef>& list, const State& s, bool every_tensor) {
  addIfAllocated(list, "m_c", s.m_c);
  addIfAllocated(list, "v_c", s.v_c);
  addIfAllocated(list, "E_c", s.E_c);
  addIfAllocated(list, "dvdt_c", s.dvdt_c);
  addIfAllocated(list, "alpha_ck", s.alpha_ck);
  addIfAllocated(list, "m_ck", s.m_ck);
  addIfAllocated(list, "e_ck", s.e_ck);
  if (every_tensor) {
    addIfAllocated(list, "S_ck", s.S_ck);
    addIfAllocated(list, "B_ck", s.B_ck);
    addIfAllocated(list, "eps_ck", s.eps_ck);
  } else {
    addEvolvedTensors(list, s);
  }
  addIfAllocated(list, "n_ck", s.n_ck);  // interface normals of the last remap
}
}  // namespace

std::vector<FieldRef> evolvedCellFields(const State& s) {
  std::vector<FieldRef> list;
  addEvolvedFields(list, s, true);
  return list;
}

std::vector<FieldRef> cellStateFields(const State& s) {
  std::vector<FieldRef> list = evolvedCellFields(s);
  addIfAllocated(list, "p_ck", s.p_ck);
  addIfAllocated(list, "w_ck", s.w_ck);
  addIfAllocated(list, "vol_c", s.vol_c);
  addIfAllocated(list, "rho_c", s.rho_c);
  addIfAllocated(list, "e_c", s.e_c);
  addIfAllocated(list, "p_c", s.p_c);
  addIfAllocated(list, "aL_c", s.aL_c);
  addIfAllocated(list, "aT_c", s.aT_c);
  addIfAllocated(list, "len_c", s.len_c);
  addIfAllocated(list, "S_c", s.S_c);
  addIfAllocated(list, "x_c", s.x_c);
  return list;
}

std::vector<FieldRef> stageEndCellFields(const State& s) {
  // (what the first layer's corner terms read of their neighbours in the
  // second: the first layer's own stage was complete, see src/fields.hpp)
  std::vector<FieldRef> list;
  addIfAllocated(list, "v_c", s.v_c);
  addIfAllocated(list, "p_c", s.p_c);
  addIfAllocated(list, "S_c", s.S_c);
  return list;
}

std::vector<FieldRef> stageEndCellFieldsForRemap(const State& s) {
  // (what the first layer's remap gradients read of the second layer's
  // primitives: the rest of them, m_c and m^k, only the remap changes; vol_c
  // and x_c are the cells' shapes)
  std::vector<FieldRef> list;
  addIfAllocated(list, "v_c", s.v_c);
  addIfAllocated(list, "alpha_ck", s.alpha_ck);
  addIfAllocated(list, "e_ck", s.e_ck);
  addEvolvedTensors(list, s);
  return list;
}

std::vector<FieldRef> remappedCellFields(const State& s) {
  std::vector<FieldRef> list;
  addEvolvedFields(list, s, false);
  return list;
}

void copyStepStart(const State& state, const Vec3View& x_n, StepStart direction, unsigned solids,
                   bool nodes) {
  const auto s = state;
  const Index n_cells = Index(s.v_c.extent(0));
  const Index n_nodes = nodes ? Index(x_n.extent(0)) : 0;
  Kokkos::parallel_for(
      direction == StepStart::Save ? "lagremap::lagrange::save_step_start"
                                   : "lagremap::lagrange::restore_step_start",
      Kokkos::RangePolicy<ExecSpace>(0, n_cells > n_nodes ? n_cells : n_nodes),
      KOKKOS_LAMBDA(const Index i) {
        if (i < n_nodes) copyNodeStart(s, x_n, i, direction);
        if (i < n_cells) copyCellStart(s, i, solids, direction);
      });
}

}  // namespace lagremap
