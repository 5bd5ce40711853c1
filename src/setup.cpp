#include "setup.hpp"

#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <vector>

#include <unistd.h>

#include "kernels/geometry.hpp"

namespace lagremap {

namespace {

// ALE mode's keys (docs/method.md §8, docs/running.md).
void declareAleKeys(Config& config) {
  config.addChoice("ale.rule", "winslow", {"winslow", "initial"},
                   "target mesh of the relaxation: winslow (equipotential smoothing of the "
                   "Lagrangian mesh, boundaries kept) or initial (the initial mesh: remap mode's "
                   "target at ale.weight 1); docs/method.md §8");
  config.addReal("ale.weight", 1.0, "-",
                 "fraction of the way from the Lagrangian position to the rule's (0: the "
                 "Lagrangian mesh, no remap: lagrange mode)");
  config.addInteger("ale.every", 1, "relax and remap after every this many steps");
  config.addReal("ale.max_move", 0.2, "-",
                 "largest move of a node in one relaxation, a fraction of its shortest edge");
  config.addReal("ale.quality_floor", 0.2, "-",
                 "scaled Jacobian below which the relaxation may not take a cell (nor below "
                 "its Lagrangian value): such cells keep their Lagrangian nodes");
}

}  // namespace

Config declareConfig(const Problem& problem, const std::string& mode) {
  Config config;
  config.setMode(mode);
  problem.declare(config);
  if (config.aleMode()) declareAleKeys(config);
  if (config.remaps()) {
    config.addReal(
        "remap.beta", 2.0, "-",
        "limiter parameter of the volume fractions (1: Barth-Jespersen, 2: compressive)");
    config.addReal("remap.alpha_floor", 1e-10, "-",
                   "volume fraction below which a material is dropped from a cell (mass and "
                   "energy kept)");
    config.addChoice(
        "mixture.closure", "relaxation", {"relaxation", "equal_strain"},
        "mixed cells in the Lagrangian phase: relaxation (volume changes shared by "
        "compressibility, pressures and a solid's normal stress relaxed, dissipation by "
        "mass) or equal_strain (the paper's: volume fractions constant, every material "
        "at the cell's strain rate, dissipation by volume fraction); docs/method.md §4");
    config.addChoice("remap.parcel_bound", "stencil", {"face", "stencil"},
                     "range that bounds a swept parcel's specific energy and plastic strain: "
                     "stencil (the upwind cell and its face neighbours, the range its limiter "
                     "keeps the reconstruction in: second order on a smooth oblique flow) or face "
                     "(the two cells sharing the face); docs/method.md §5.2");
    config.addChoice(
        "remap.parcel_fractions", config.aleMode() ? "bounded" : "free", {"bounded", "free"},
        "a swept parcel's volume fractions: bounded (kept in [0, 1], the default in ALE mode, "
        "whose relaxed faces sweep across trace cells) or free (the linear reconstruction's "
        "at the parcel, clipped per cell after the sweep; remap mode's default, in which its "
        "results were verified); docs/method.md §5.3");
    config.addReal("remap.alpha_trace", 1e-3, "-",
                   "volume fraction below which a material of a mixed cell is a trace: carried, "
                   "but left out of the cell's stress and sound speed");
    config.addReal(
        "remap.alpha_tail", 1e-2, "-",
        "volume fraction below which a fluid in a cell that also holds a Neo-Hookean solid is a "
        "trace (the remap's diffusion tail inside a body: it takes no part in the "
        "relaxation); docs/method.md §4.6");
  }
  config.addChoice("numerics.order", "2", {"1", "2"},
                   "1: first order; 2: limited linear reconstruction + predictor-corrector");
  config.addReal("numerics.cfl", 0.4, "-", "CFL number C_cfl of dt <= C_cfl l_c / aL_c");
  config.addReal("numerics.c_vol", 0.1, "-", "max relative volume change per step C_vol");
  config.addReal("numerics.dt_growth", 1.05, "-", "max ratio of two successive time steps");
  config.addReal("numerics.dt_initial_factor", 0.1, "-", "first dt as a fraction of the stable dt");
  config.addReal("numerics.dt_min_fraction", 1e-12, "-",
                 "the run stops when dt falls below this fraction of t_end");
  config.addReal("numerics.dt_drop_fraction", 1e-2, "-",
                 "the run stops when its stable dt falls below this fraction of the largest "
                 "stable dt it has had (a time step collapse; 0: never)");
  config.addInteger("numerics.max_steps", 10000000, "the run stops after this many steps");
  config.addChoice("numerics.gather", "crs", {"crs", "atomics"},
                   "node sums: node->corner CRS (deterministic) or atomic scatter");
  config.addChoice("numerics.kernels", "auto", {"auto", "fused", "staged"},
                   "per-cell kernel form, the same results: fused (one sweep per cell, CPU "
                   "vector lanes), staged (a cell's faces and corners in vector lanes, separate "
                   "kernels: GPU registers), auto (the backend's: fused on CPUs, staged on GPUs)");
  return config;
}

Numerics readNumerics(const Config& config) {
  Numerics numerics;
  numerics.order = int(config.integer("numerics.order"));
  numerics.step.cfl = config.real("numerics.cfl");
  numerics.step.c_vol = config.real("numerics.c_vol");
  numerics.dt_growth = config.real("numerics.dt_growth");
  numerics.dt_initial_factor = config.real("numerics.dt_initial_factor");
  numerics.dt_min = config.real("numerics.dt_min_fraction") * config.real("t_end");
  numerics.dt_drop_fraction = config.real("numerics.dt_drop_fraction");
  numerics.max_steps = config.integer("numerics.max_steps");
  numerics.gather = config.text("numerics.gather") == "atomics" ? Gather::Atomics : Gather::Crs;
  const std::string kernels = config.text("numerics.kernels");
  if (kernels != "auto")
    numerics.kernels = kernels == "staged" ? KernelForm::Staged : KernelForm::Fused;
  if (numerics.kernels == KernelForm::Fused && !kFusedKernelsBuilt) {
    throw ConfigError(
        "numerics.kernels = fused: the fused form is built for CPU backends only "
        "(this build runs on " +
        std::string(ExecSpace::name()) + ")");
  }
  if (!(numerics.step.cfl > 0.0 && numerics.step.cfl <= 1.0)) {
    throw ConfigError("numerics.cfl must be in (0, 1]");
  }
  if (!(numerics.step.c_vol > 0.0 && numerics.step.c_vol < 1.0)) {
    throw ConfigError("numerics.c_vol must be in (0, 1)");
  }
  if (!(numerics.dt_growth >= 1.0)) throw ConfigError("numerics.dt_growth must be >= 1");
  if (!(numerics.dt_initial_factor > 0.0 && numerics.dt_initial_factor <= 1.0)) {
    throw ConfigError("numerics.dt_initial_factor must be in (0, 1]");
  }
  if (!(config.real("numerics.dt_min_fraction") >= 0.0 &&
        config.real("numerics.dt_min_fraction") < 1.0)) {
    throw ConfigError("numerics.dt_min_fraction must be in [0, 1)");
  }
  if (!(numerics.dt_drop_fraction >= 0.0 && numerics.dt_drop_fraction < 1.0)) {
    throw ConfigError("numerics.dt_drop_fraction must be in [0, 1)");
  }
  if (numerics.max_steps < 1) throw ConfigError("numerics.max_steps must be >= 1");
  if (!(config.real("t_end") > 0.0)) throw ConfigError("t_end must be > 0");
  return numerics;
}

// About 1.2 kB per cell: corner records, cell and node fields, host copies
// for output. Each rank holds its part of the block (ghost layers aside), and
// the ranks on this machine share its memory. Collective.
void checkMemoryFits(const Config& config) {
  if (!config.has("mesh.nx") || !config.has("mesh.ny") || !config.has("mesh.nz")) return;
  const double cells = double(config.integer("mesh.nx")) * double(config.integer("mesh.ny")) *
                       double(config.integer("mesh.nz"));
  const int here = parallel::ranksOnThisMachine(), ranks = parallel::size();
  const double needed = 1200.0 * cells * here / ranks;
  const double available = double(sysconf(_SC_PHYS_PAGES)) * double(sysconf(_SC_PAGE_SIZE));
  if (available > 0 && needed > 0.8 * available) {
    char text[200];
    std::snprintf(text, sizeof text,
                  "mesh of %.3g cells needs about %.1f GB for the %d of %d ranks on this machine, "
                  "more than its %.1f GB",
                  cells, needed / 1e9, here, ranks, available / 1e9);
    throw ConfigError(text);
  }
}

ProblemSetup setUpProblem(const Problem& problem, const Config& config, const std::string& name) {
  try {
    return problem.setup(config);
  } catch (const std::invalid_argument& error) {  // e.g. an impossible mesh
    throw ConfigError(name + ": " + error.what());
  }
}

namespace {

// The material table, and undeformed solids: B = I (S = 0 as allocated).
void uploadMaterials(const std::vector<MaterialParams>& materials, State& state) {
  if (state.B_ck.size() > 0) {
    auto B_host = Kokkos::create_mirror_view(state.B_ck);
    for (Index c = 0; c < Index(B_host.extent(0)); ++c)
      for (int k = 0; k < state.n_materials; ++k) storeSym(B_host, c, k, identitySym());
    Kokkos::deep_copy(state.B_ck, B_host);
  }
  state.materials = MaterialView("lagremap::state::materials", materials.size());
  auto materials_host = Kokkos::create_mirror_view(state.materials);
  for (std::size_t k = 0; k < materials.size(); ++k) {
    materials_host(k) = materials[k];
    state.has_hypo_elastic |= materials[k].strength == StrengthKind::HypoElastic;
    state.has_neo_hookean |= materials[k].strength == StrengthKind::NeoHookean;
  }
  Kokkos::deep_copy(state.materials, materials_host);
}

}  // namespace

// Uploads the problem's initial cells and allocates the per-material state:
// m^k = alpha^k rho^k v (v from the same geometry kernel the run uses),
// m = sum m^k, m e = sum m^k e^k, E = e + |V|^2 / 2; undeformed solids
// (S = 0, B = I).
void initializeState(const ProblemSetup& setup, State& state) {
  const Index n_cells = setup.mesh.n_cells;
  const int n_materials = int(setup.materials.size());
  const InitialCells& cells = setup.cells;
  const bool mixed = !cells.alpha_k.empty();
  const std::size_t n_entries = std::size_t(n_cells) * std::size_t(n_materials);
  const bool sizes_ok =
      Index(cells.v.size()) == n_cells &&
      (mixed ? cells.alpha_k.size() == n_entries && cells.rho_k.size() == n_entries &&
                   cells.e_k.size() == n_entries
             : Index(cells.rho.size()) == n_cells && Index(cells.e.size()) == n_cells &&
                   Index(cells.mat.size()) == n_cells);
  if (n_materials < 1 || !sizes_ok) {
    throw std::logic_error("problem set-up gave initial data of the wrong size");
  }
  bool has_solids = false, has_neo_hookean = false, has_plastic_strain = false;
  for (const MaterialParams& material : setup.materials) {
    has_solids = has_solids || material.strength != StrengthKind::None;
    has_neo_hookean = has_neo_hookean || material.strength == StrengthKind::NeoHookean;
    has_plastic_strain = has_plastic_strain || hasPlasticStrain(material);
  }
  allocateMaterialState(state, n_cells, n_materials, has_solids, has_neo_hookean,
                        has_plastic_strain);

  std::vector<double> volume;
  std::vector<Vec3> centroid;
  hostCellShapes(copyToHost(setup.mesh), volume, centroid);
  auto m_host = Kokkos::create_mirror_view(state.m_c);
  auto v_host = Kokkos::create_mirror_view(state.v_c);
  auto E_host = Kokkos::create_mirror_view(state.E_c);
  auto alpha_host = Kokkos::create_mirror_view(state.alpha_ck);
  auto m_k_host = Kokkos::create_mirror_view(state.m_ck);
  auto e_k_host = Kokkos::create_mirror_view(state.e_ck);
  Kokkos::deep_copy(alpha_host, 0.0);
  Kokkos::deep_copy(m_k_host, 0.0);
  Kokkos::deep_copy(e_k_host, 0.0);
  for (Index c = 0; c < n_cells; ++c) {
    const std::string where = "initial state: cell " + std::to_string(c);
    if (!(volume[c] > 0.0)) throw ConfigError(where + " has a non-positive volume");
    double mass = 0.0, internal_energy = 0.0, alpha_sum = 0.0;
    for (int k = 0; k < n_materials; ++k) {
      const std::size_t i = std::size_t(c) * std::size_t(n_materials) + std::size_t(k);
      const double alpha = mixed ? cells.alpha_k[i] : double(cells.mat[c] == k);
      if (!(alpha >= 0.0 && alpha <= 1.0)) {
        throw ConfigError(where + " has a volume fraction outside [0, 1]");
      }
      if (alpha == 0.0) continue;
      const double rho = mixed ? cells.rho_k[i] : cells.rho[c];
      const double e = mixed ? cells.e_k[i] : cells.e[c];
      if (!(rho > 0.0)) throw ConfigError(where + " has a non-positive density");
      alpha_host(c, k) = alpha;
      m_k_host(c, k) = alpha * rho * volume[c];
      e_k_host(c, k) = e;
      alpha_sum += alpha;
      mass += m_k_host(c, k);
      internal_energy += m_k_host(c, k) * e;
    }
    if (!mixed && (cells.mat[c] < 0 || cells.mat[c] >= n_materials)) {
      throw std::logic_error("problem set-up gave an unknown material index");
    }
    if (!(std::fabs(alpha_sum - 1.0) <= 1e-12)) {
      throw ConfigError(where + " has volume fractions that do not sum to 1");
    }
    m_host(c) = mass;
    storeVec3(v_host, c, cells.v[c]);
    E_host(c) = internal_energy / mass + 0.5 * dot(cells.v[c], cells.v[c]);
  }
  Kokkos::deep_copy(state.m_c, m_host);
  Kokkos::deep_copy(state.v_c, v_host);
  Kokkos::deep_copy(state.E_c, E_host);
  Kokkos::deep_copy(state.alpha_ck, alpha_host);
  Kokkos::deep_copy(state.m_ck, m_k_host);
  Kokkos::deep_copy(state.e_ck, e_k_host);
  uploadMaterials(setup.materials, state);
}

RelaxationControls readRelaxationControls(const Config& config) {
  RelaxationControls controls;
  controls.rule =
      config.text("ale.rule") == "initial" ? RelaxationRule::Initial : RelaxationRule::Winslow;
  controls.weight = config.real("ale.weight");
  controls.max_move = config.real("ale.max_move");
  controls.quality_floor = config.real("ale.quality_floor");
  if (!(controls.weight >= 0.0 && controls.weight <= 1.0)) {
    throw ConfigError("ale.weight must be in [0, 1]");
  }
  if (!(controls.max_move > 0.0 && controls.max_move <= 1.0)) {
    throw ConfigError("ale.max_move must be in (0, 1]");
  }
  if (!(controls.quality_floor >= 0.0 && controls.quality_floor < 1.0)) {
    throw ConfigError("ale.quality_floor must be in [0, 1)");
  }
  if (!(config.integer("ale.every") >= 1)) throw ConfigError("ale.every must be at least 1");
  return controls;
}

RemapControls readRemapControls(const Config& config, State& state) {
  RemapControls controls;
  controls.beta_alpha = config.real("remap.beta");
  controls.alpha_floor = config.real("remap.alpha_floor");
  controls.reconstruct = config.integer("numerics.order") >= 2;  // (--order 1: first order)
  controls.stencil_parcel_bound = config.text("remap.parcel_bound") == "stencil";
  controls.bounded_parcel_fractions = config.text("remap.parcel_fractions") == "bounded";
  state.alpha_trace = config.real("remap.alpha_trace");
  state.closure = config.text("mixture.closure") == "equal_strain" ? MixtureClosure::EqualStrain
                                                                   : MixtureClosure::Relaxation;
  state.alpha_tail = config.real("remap.alpha_tail");
  if (!(state.alpha_trace >= 0.0 && state.alpha_trace < 0.5 / state.n_materials)) {
    throw ConfigError("remap.alpha_trace must be in [0, 0.5 / number of materials)");
  }
  if (!(state.alpha_tail >= state.alpha_trace && state.alpha_tail < 0.5 / state.n_materials)) {
    throw ConfigError("remap.alpha_tail must be in [remap.alpha_trace, 0.5 / number of materials)");
  }
  if (!(controls.beta_alpha >= 1.0 && controls.beta_alpha <= 2.0)) {
    throw ConfigError("remap.beta must be in [1, 2]");
  }
  if (!(controls.alpha_floor >= 0.0 && controls.alpha_floor < 0.5)) {
    throw ConfigError("remap.alpha_floor must be in [0, 0.5)");
  }
  return controls;
}

std::unique_ptr<RemapStep> makeRemapStep(Mesh& mesh, State& state, const RemapControls& controls,
                                         PhaseTimers& timers, const Halo* halo,
                                         const std::string& problem) {
  try {
    return std::make_unique<RemapStep>(mesh, state, controls, timers, halo);
  } catch (const std::invalid_argument& error) {
    throw ConfigError(problem + ": " + error.what());
  }
}

}  // namespace lagremap
