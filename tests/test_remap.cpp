// Remap phase (docs/method.md §A9-A11): a whole remap step from a randomly moved
// "Lagrangian" mesh back onto the initial one, on two-material states.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <map>
#include <random>
#include <set>

#include "src/diagnostics.hpp"
#include "src/lagrange_step.hpp"
#include "src/materials.hpp"
#include "src/remap_step.hpp"
#include "test_support.hpp"

namespace lagremap {
namespace {

constexpr int kNx = 8, kNy = 6, kNz = 5;

// Two ideal gases in a walled, perturbed box; the fields are set per test.
struct TwoGasBox {
  ProblemSetup setup;
  State state;
  PhaseTimers timers;
  Numerics numerics;

  // heavy_solid: the heavy gas has strength (hypo-elastic: it carries S^k
  // and the plastic strain eps_p^k)
  explicit TwoGasBox(bool heavy_solid = false) {
    BlockSpec block;
    block.nx = kNx;
    block.ny = kNy;
    block.nz = kNz;
    block.hi = {1.6, 1.2, 1.0};
    block.perturbation = 0.15;
    SideBoundaries sides;
    for (auto& side : sides) side.kind = BoundaryKind::Wall;
    setup.mesh = buildBlockMesh(block, sides);
    MaterialParams light, heavy;
    light.gamma = 1.4;
    heavy.gamma = 1.67;
    if (heavy_solid) {
      heavy.strength = StrengthKind::HypoElastic;
      heavy.mu = 1.0;
      heavy.yield_stress = 1.0;
      heavy.hardening = HardeningKind::Linear;  // (a hardening solid carries eps_p)
    }
    setup.materials = {light, heavy};
    const Index n = setup.mesh.n_cells;
    setup.cells.alpha_k.assign(2 * std::size_t(n), 0.5);
    setup.cells.rho_k.assign(2 * std::size_t(n), 1.0);
    setup.cells.e_k.assign(2 * std::size_t(n), 1.0);
    setup.cells.v.assign(n, Vec3{0, 0, 0});
    state = allocateState(setup.mesh, false);
    initializeState(setup, state);
    hostCellShapes(copyToHost(setup.mesh), target_volume, target_centroid);
    geometry();
  }

  // Volumes and centroids of the initial mesh, the remap's target.
  std::vector<double> target_volume;
  std::vector<Vec3> target_centroid;

  // Moves interior nodes by up to `amplitude` of a cell in a random direction:
  // the "Lagrangian" mesh (walls do not move, so nothing crosses them).
  void moveInteriorNodes(double amplitude, unsigned seed) {
    auto x = Kokkos::create_mirror(setup.mesh.x_n);
    Kokkos::deep_copy(x, setup.mesh.x_n);
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    const double h[3] = {1.6 / kNx, 1.2 / kNy, 1.0 / kNz};
    const double hi[3] = {1.6, 1.2, 1.0};
    for (Index node = 0; node < Index(x.extent(0)); ++node) {
      bool interior = true;
      for (int d = 0; d < 3; ++d) {
        interior = interior && x(node, d) > 1e-12 && x(node, d) < hi[d] - 1e-12;
      }
      if (!interior) continue;
      for (int d = 0; d < 3; ++d) x(node, d) += amplitude * h[d] * unit(rng);
    }
    Kokkos::deep_copy(setup.mesh.x_n, x);
  }

  // Geometry (volumes, centroids) of the current node positions.
  void geometry() {
    LagrangeStep lagrange(setup.mesh, state, numerics, timers);
    const StepLimit limit = lagrange.computeGeometry();
    ASSERT_GT(limit.val, 0.0);
  }

  // Writes per-cell fields from functions of the cell centroid (current mesh).
  template <class AlphaFn, class VelocityFn>
  void setFields(AlphaFn alpha_of, VelocityFn velocity_of, double rho_heavy, double e_heavy) {
    auto x_c = Kokkos::create_mirror_view_and_copy(HostSpace(), state.x_c);
    auto vol = Kokkos::create_mirror_view_and_copy(HostSpace(), state.vol_c);
    auto alpha = Kokkos::create_mirror_view(state.alpha_ck);
    auto m_k = Kokkos::create_mirror_view(state.m_ck);
    auto e_k = Kokkos::create_mirror_view(state.e_ck);
    auto m = Kokkos::create_mirror_view(state.m_c);
    auto v = Kokkos::create_mirror_view(state.v_c);
    auto E = Kokkos::create_mirror_view(state.E_c);
    const double rho_k[2] = {1.0, rho_heavy}, e_of[2] = {2.0, e_heavy};
    for (Index c = 0; c < Index(vol.extent(0)); ++c) {
      const Vec3 x = loadVec3(x_c, c);
      const double a0 = alpha_of(x);
      alpha(c, 0) = a0;
      alpha(c, 1) = 1.0 - a0;
      double mass = 0.0, internal = 0.0;
      for (int k = 0; k < 2; ++k) {
        m_k(c, k) = alpha(c, k) * rho_k[k] * vol(c);
        e_k(c, k) = alpha(c, k) > 0.0 ? e_of[k] : 0.0;
        mass += m_k(c, k);
        internal += m_k(c, k) * e_k(c, k);
      }
      const Vec3 velocity = velocity_of(x);
      m(c) = mass;
      storeVec3(v, c, velocity);
      E(c) = internal / mass + 0.5 * dot(velocity, velocity);
    }
    Kokkos::deep_copy(state.alpha_ck, alpha);
    Kokkos::deep_copy(state.m_ck, m_k);
    Kokkos::deep_copy(state.e_ck, e_k);
    Kokkos::deep_copy(state.m_c, m);
    Kokkos::deep_copy(state.v_c, v);
    Kokkos::deep_copy(state.E_c, E);
  }
};

struct MaterialTotals {
  double mass[2] = {0, 0}, volume[2] = {0, 0};
  Vec3 momentum{0, 0, 0};
  double energy = 0.0;
};

MaterialTotals totalsOf(const State& state, const std::vector<double>& cell_volume) {
  auto alpha = Kokkos::create_mirror_view_and_copy(HostSpace(), state.alpha_ck);
  auto m_k = Kokkos::create_mirror_view_and_copy(HostSpace(), state.m_ck);
  auto m = Kokkos::create_mirror_view_and_copy(HostSpace(), state.m_c);
  auto v = Kokkos::create_mirror_view_and_copy(HostSpace(), state.v_c);
  auto E = Kokkos::create_mirror_view_and_copy(HostSpace(), state.E_c);
  MaterialTotals totals;
  for (Index c = 0; c < Index(m.extent(0)); ++c) {
    for (int k = 0; k < 2; ++k) {
      totals.mass[k] += m_k(c, k);
      totals.volume[k] += alpha(c, k) * cell_volume[c];
    }
    totals.momentum += m(c) * loadVec3(v, c);
    totals.energy += m(c) * E(c);
  }
  return totals;
}

std::vector<double> volumesOf(const State& state) {
  auto vol = Kokkos::create_mirror_view_and_copy(HostSpace(), state.vol_c);
  return std::vector<double>(vol.data(), vol.data() + vol.extent(0));
}

Vec3 linearVelocity(const Vec3& x) {
  return {0.3 + 0.5 * x.x - 0.2 * x.y + 0.1 * x.z, -0.1 + 0.2 * x.x + 0.4 * x.z,
          0.05 - 0.3 * x.y + 0.2 * x.z};
}
double linearAlpha(const Vec3& x) {
  return 0.5 + 0.12 * x.x - 0.08 * x.y + 0.1 * x.z;
}

// The paper's slabs (one cell thick between z symmetry planes, in both
// modes: the shell's polar mesh too) take the prism geometry
// (Mesh::z_prisms); the beam, a 3D block, does not.
TEST(Remap, PaperSlabsArePrismMeshesAndTheBeamIsNot) {
  const std::pair<const char*, const char*> slabs[] = {{"taylor", "remap"},
                                                       {"shell", "remap"},
                                                       {"ball", "remap"},
                                                       {"taylor", "lagrange"},
                                                       {"shell", "lagrange"}};
  for (const auto& [problem, mode] : slabs) {
    const RunOptions options = testing::problemOptions(problem, {}, 0.25, mode);
    EXPECT_TRUE(findProblem(problem).setup(options.config).mesh.z_prisms) << problem << " " << mode;
  }
  const RunOptions beam = testing::problemOptions("beam", {}, 0.25, "remap");
  EXPECT_FALSE(findProblem("beam").setup(beam.config).mesh.z_prisms);
}

// The end of a step the remap follows (StageEnd::ForRemap) computes only what
// the remap reads: after one Lagrangian step of the taylor bar in gas, the
// volumes, centroids, volume fractions, velocities, energies and deviators are
// the full end-of-stage computation's, bit for bit; and it still stops a
// tangled cell.
TEST(Remap, StageEndForRemapLeavesWhatTheRemapReadsBitForBit) {
  RunOptions options = testing::problemOptions("taylor", {}, 0.3, "remap");
  const Numerics numerics = readNumerics(options.config);
  struct Run {
    ProblemSetup setup;
    State state;
    StepLimit limit;
  };
  auto advanceOneStep = [&](bool remap_follows) {
    Run run{findProblem("taylor").setup(options.config), {}, {}};
    run.state = allocateState(run.setup.mesh, false);
    initializeState(run.setup, run.state);
    PhaseTimers timers;
    LagrangeStep lagrange(run.setup.mesh, run.state, numerics, timers);
    if (remap_follows) lagrange.remapFollowsEveryStep();
    const StepLimit start = lagrange.computeGeometry();
    run.limit = lagrange.advance(0.5 * start.val, 1);
    return run;
  };
  const Run full = advanceOneStep(false), for_remap = advanceOneStep(true);
  EXPECT_GT(full.limit.val, 0.0);
  EXPECT_GT(for_remap.limit.val, 0.0);  // valid, and no time step proposed
  auto bits = [](const auto& view) {
    const auto host = Kokkos::create_mirror_view_and_copy(HostSpace(), view);
    return std::vector<double>(host.data(), host.data() + host.size());
  };
  EXPECT_EQ(bits(full.state.vol_c), bits(for_remap.state.vol_c));
  EXPECT_EQ(bits(full.state.x_c), bits(for_remap.state.x_c));
  EXPECT_EQ(bits(full.state.alpha_ck), bits(for_remap.state.alpha_ck));
  EXPECT_EQ(bits(full.state.v_c), bits(for_remap.state.v_c));
  EXPECT_EQ(bits(full.state.E_c), bits(for_remap.state.E_c));
  EXPECT_EQ(bits(full.state.e_ck), bits(for_remap.state.e_ck));
  EXPECT_EQ(bits(full.state.S_ck), bits(for_remap.state.S_ck));
  EXPECT_EQ(bits(full.setup.mesh.x_n), bits(for_remap.setup.mesh.x_n));

  // A node pushed through its cell: the shape-only end of stage reports it.
  const Mesh& mesh = for_remap.setup.mesh;
  auto x = Kokkos::create_mirror_view_and_copy(HostSpace(), mesh.x_n);
  auto cell_nodes = Kokkos::create_mirror_view_and_copy(HostSpace(), mesh.cell_nodes);
  const Index node = cell_nodes(0, 6), opposite = cell_nodes(0, 0);
  storeVec3(x, node, loadVec3(x, opposite) - 0.5 * (loadVec3(x, node) - loadVec3(x, opposite)));
  Kokkos::deep_copy(mesh.x_n, x);
  const StepLimit tangled =
      updateCellsAndGeometry(mesh, for_remap.state, 0.0, numerics.step, StageEnd::ForRemap);
  EXPECT_LT(tangled.val, 0.0);
  EXPECT_EQ(tangled.loc % kLimitCodes, int(kBadVolume));
}

// The remap's work arrays and the state's corner arrays share one allocation
// (RemapStep::sharedWork): each phase writes what it reads, so a run whose
// shared memory is filled with NaN after the Lagrangian step and after the
// remap is the same, bit for bit, as one left alone (taylor at a third of its
// resolution: gas, solid and mixed cells), in both kernel forms.
TEST(Remap, SharedWorkMemoryCarriesNothingFromOnePhaseToTheNext) {
  const RunOptions options = testing::problemOptions("taylor", {}, 0.3, "remap");
  auto run = [&](KernelForm form, bool poison) {
    ProblemSetup setup = findProblem("taylor").setup(options.config);
    State state = allocateState(setup.mesh, false, false);
    initializeState(setup, state);
    Numerics numerics = readNumerics(options.config);
    numerics.kernels = form;
    RemapControls controls = readRemapControls(options.config, state);
    controls.kernels = form;
    PhaseTimers timers;
    LagrangeStep lagrange(setup.mesh, state, numerics, timers);
    RemapStep remap(setup.mesh, state, controls, timers);
    lagrange.remapFollowsEveryStep();
    StepLimit limit = lagrange.computeGeometry();
    const double nan = std::numeric_limits<double>::quiet_NaN();
    for (long step = 1; step <= 6; ++step) {
      EXPECT_GT(lagrange.advance(0.5 * limit.val, step).val, 0.0);
      if (poison) Kokkos::deep_copy(remap.sharedWork(), nan);
      remap.apply();
      if (poison) Kokkos::deep_copy(remap.sharedWork(), nan);
      limit = lagrange.computeGeometry();
      EXPECT_GT(limit.val, 0.0);
    }
    std::vector<double> bits;
    auto append = [&bits](const auto& view) {
      const auto host = Kokkos::create_mirror_view_and_copy(HostSpace(), view);
      bits.insert(bits.end(), host.data(), host.data() + host.size());
    };
    append(state.m_ck);
    append(state.alpha_ck);
    append(state.e_ck);
    append(state.S_ck);
    append(state.v_c);
    append(state.E_c);
    append(state.p_c);
    append(state.M_cp);
    bits.push_back(limit.val);
    return bits;
  };
  for (const KernelForm form : {KernelForm::Fused, KernelForm::Staged}) {
    if (form == KernelForm::Fused && !kFusedKernelsBuilt) continue;
    const std::vector<double> clean = run(form, false), poisoned = run(form, true);
    ASSERT_EQ(clean.size(), poisoned.size());
    EXPECT_EQ(0, std::memcmp(clean.data(), poisoned.data(), clean.size() * sizeof(double)))
        << (form == KernelForm::Fused ? "fused" : "staged");
  }
}

// Views carved end to end whose sizes are whole 4 KiB pages start at
// different places within a page (no two at one index share a cache set's
// offset: the 4K-aliasing stall, data/work_arena.hpp), at 128-byte
// boundaries, inside the memory; the sizing pass counts what carving takes.
TEST(WorkArena, ViewsOfWholePagesStartAtDifferentPlacesInAPage) {
  WorkArena sizing;
  for (int k = 0; k < 6; ++k) sizing.carve<MatRealView>(Index(1024), 4);
  const RealView memory("lagremap::test::arena", sizing.used());
  WorkArena arena(memory);
  std::set<std::size_t> places;
  for (int k = 0; k < 6; ++k) {
    const MatRealView view = arena.carve<MatRealView>(Index(1024), 4);  // 32 KiB
    const std::size_t offset = std::size_t(view.data() - memory.data()) * sizeof(Real);
    EXPECT_EQ(offset % 128, 0u);
    EXPECT_LE(offset + view.span() * sizeof(Real), memory.span() * sizeof(Real));
    places.insert(offset % 4096);
  }
  EXPECT_EQ(places.size(), 6u);
  EXPECT_EQ(arena.used(), sizing.used());
  EXPECT_THROW(arena.carve<RealView>(Index(1)), std::logic_error);
}

// A step that fails after its remap (an invalid geometry on the target)
// puts back the state of its start: the remap its masses, the Lagrangian
// step the rest (volume fractions included). Bit for bit, on taylor's gas,
// solid and mixed cells, after a few steps (so the masses are the remap's).
// (Not p^k: the geometry's mixed-cell pressures read the last stage's
// volume rate, which is not restored.)
TEST(Remap, RestoringAStepAfterItsRemapGivesTheStartOfStepBits) {
  const RunOptions options = testing::problemOptions("taylor", {}, 0.3, "remap");
  ProblemSetup setup = findProblem("taylor").setup(options.config);
  State state = allocateState(setup.mesh, false, false);
  initializeState(setup, state);
  const Numerics numerics = readNumerics(options.config);
  PhaseTimers timers;
  LagrangeStep lagrange(setup.mesh, state, numerics, timers);
  RemapStep remap(setup.mesh, state, readRemapControls(options.config, state), timers);
  lagrange.remapFollowsEveryStep();
  StepLimit limit = lagrange.computeGeometry();
  using Fields = std::map<std::string, std::vector<double>>;
  auto fields = [&] {
    Fields all;
    auto add = [&all](const char* name, const auto& view) {
      const auto host = Kokkos::create_mirror_view_and_copy(HostSpace(), view);
      all[name].assign(host.data(), host.data() + host.size());
    };
    add("m_c", state.m_c);
    add("m_ck", state.m_ck);
    add("alpha_ck", state.alpha_ck);
    add("e_ck", state.e_ck);
    add("S_ck", state.S_ck);
    add("v_c", state.v_c);
    add("E_c", state.E_c);
    add("vol_c", state.vol_c);
    add("x_n", setup.mesh.x_n);
    return all;
  };
  Fields start;
  for (long step = 1; step <= 4; ++step) {
    start = fields();
    lagrange.saveStartOfStep();
    ASSERT_GT(lagrange.advance(0.5 * limit.val, step).val, 0.0);
    remap.apply();
    limit = lagrange.computeGeometry();
    ASSERT_GT(limit.val, 0.0);
  }
  EXPECT_NE(start["m_ck"], fields()["m_ck"]);  // the last step changed the state
  EXPECT_NE(start["alpha_ck"], fields()["alpha_ck"]);
  remap.restoreStartOfStep();
  lagrange.restoreStartOfStep();
  for (const auto& [name, restored] : fields()) {
    const std::vector<double>& saved = start[name];
    ASSERT_EQ(saved.size(), restored.size()) << name;
    EXPECT_EQ(0, std::memcmp(saved.data(), restored.data(), saved.size() * sizeof(double))) << name;
  }
}

TEST(Remap, UnlimitedReconstructionRemapsLinearFieldsExactly) {
  for (bool mixed : {true, false}) {
    TwoGasBox box;
    RemapControls controls;
    controls.limit = false;
    RemapStep remap(box.setup.mesh, box.state, controls, box.timers);
    box.moveInteriorNodes(0.2, 7);
    box.geometry();
    // Equal material densities: rho V is then linear too (cell means of
    // linear fields are their centroid values on any polyhedron).
    box.setFields([mixed](const Vec3& x) { return mixed ? linearAlpha(x) : 1.0; }, linearVelocity,
                  1.0, 3.0);
    remap.apply();
    auto alpha = Kokkos::create_mirror_view_and_copy(HostSpace(), box.state.alpha_ck);
    auto v = Kokkos::create_mirror_view_and_copy(HostSpace(), box.state.v_c);
    double alpha_error = 0.0, velocity_error = 0.0;
    for (Index c = 0; c < box.setup.mesh.n_cells; ++c) {
      const Vec3 x = box.target_centroid[c];
      alpha_error = std::max(alpha_error, std::abs(alpha(c, 0) - (mixed ? linearAlpha(x) : 1.0)));
      velocity_error = std::max(velocity_error, norm(loadVec3(v, c) - linearVelocity(x)));
    }
    EXPECT_LT(alpha_error, 1e-13) << "mixed " << mixed;
    if (!mixed) {
      EXPECT_LT(velocity_error, 1e-13);
    }
  }
}

TEST(Remap, ConservesEveryMaterialMomentumAndTotalEnergyWithTheKineticEnergyFix) {
  for (bool fix : {true, false}) {
    TwoGasBox box;
    RemapControls controls;
    controls.kinetic_energy_fix = fix;
    RemapStep remap(box.setup.mesh, box.state, controls, box.timers);
    box.moveInteriorNodes(0.25, 11);
    box.geometry();
    // A disc-like blob of the heavy gas, swirling non-linear velocity.
    box.setFields(
        [](const Vec3& x) {
          const double r = std::hypot(x.x - 0.8, x.y - 0.6);
          return r < 0.4 ? 0.05 : 0.95;
        },
        [](const Vec3& x) {
          return Vec3{std::sin(3 * x.y), std::cos(2 * x.x) * x.z, 0.5 * x.x * x.y};
        },
        4.0, 0.7);
    const MaterialTotals before = totalsOf(box.state, volumesOf(box.state));
    const RemapBoundaryFlux crossed = remap.apply();
    const MaterialTotals after = totalsOf(box.state, box.target_volume);
    for (int i = 0; i < 5; ++i) EXPECT_EQ(crossed.v[i], 0.0);  // walls: nothing crosses
    for (int k = 0; k < 2; ++k) {
      EXPECT_NEAR(after.mass[k], before.mass[k], 1e-14 * before.mass[k]);
      EXPECT_NEAR(after.volume[k], before.volume[k], 1e-13 * before.volume[k]);
    }
    const double scale = std::sqrt(2.0 * (before.mass[0] + before.mass[1]) * before.energy);
    EXPECT_LT(norm(after.momentum - before.momentum), 1e-14 * scale);
    const double energy_error = std::abs(after.energy - before.energy) / before.energy;
    if (fix) {
      EXPECT_LT(energy_error, 1e-14);
    } else {
      // The remapped momentum's kinetic energy is smaller than the remapped
      // kinetic energy (Jensen): without the fix that difference is lost.
      EXPECT_GT(energy_error, 1e-7);
      EXPECT_LT(after.energy, before.energy);
    }
  }
}

// The plastic strain rides on its material's mass: sum m^k eps_p^k is
// remapped conservatively, and the limited fluxes make no new extrema.
TEST(Remap, PlasticStrainIsRemappedWithItsMaterialsMassWithoutNewExtrema) {
  TwoGasBox box(true);
  RemapStep remap(box.setup.mesh, box.state, RemapControls{}, box.timers);
  box.moveInteriorNodes(0.25, 11);
  box.geometry();
  box.setFields([](const Vec3& x) { return std::hypot(x.x - 0.8, x.y - 0.6) < 0.4 ? 0.05 : 0.95; },
                [](const Vec3& x) {
                  return Vec3{std::sin(3 * x.y), 0.5 * x.x, 0.2};
                },
                4.0, 0.7);
  auto eps = Kokkos::create_mirror_view(box.state.eps_ck);
  auto x_c = Kokkos::create_mirror_view_and_copy(HostSpace(), box.state.x_c);
  const Index n_cells = box.setup.mesh.n_cells;
  for (Index c = 0; c < n_cells; ++c) {  // smooth, with a step across x = 0.7
    const Vec3 x = loadVec3(x_c, c);
    eps(c, 0) = 0.0;
    eps(c, 1) = 0.1 + 0.2 * x.y * x.z + (x.x < 0.7 ? 0.5 : 0.0);
  }
  Kokkos::deep_copy(box.state.eps_ck, eps);
  auto strain_of = [&](double& total, double& lo, double& hi) {
    auto m_k = Kokkos::create_mirror_view_and_copy(HostSpace(), box.state.m_ck);
    auto alpha = Kokkos::create_mirror_view_and_copy(HostSpace(), box.state.alpha_ck);
    Kokkos::deep_copy(eps, box.state.eps_ck);
    total = 0.0;
    lo = 1e300;
    hi = -1e300;
    for (Index c = 0; c < n_cells; ++c) {
      EXPECT_EQ(eps(c, 0), 0.0) << "a fluid has no plastic strain";
      if (!(alpha(c, 1) > 0.0)) continue;
      total += m_k(c, 1) * eps(c, 1);
      lo = std::min(lo, eps(c, 1));
      hi = std::max(hi, eps(c, 1));
    }
  };
  double total0, lo0, hi0, total1, lo1, hi1;
  strain_of(total0, lo0, hi0);
  remap.apply();
  strain_of(total1, lo1, hi1);
  EXPECT_NEAR(total1, total0, 1e-14 * total0);
  EXPECT_GE(lo1, lo0 - 1e-14);
  EXPECT_LE(hi1, hi0 + 1e-14);
  EXPECT_LT(lo1, hi1);  // (it moved: not all cells kept their value)
}

TEST(Remap, LimitedRemapOfAStepCreatesNoNewExtrema) {
  for (double beta : {1.0, 2.0}) {
    TwoGasBox box;
    RemapControls controls;
    controls.beta_alpha = beta;
    RemapStep remap(box.setup.mesh, box.state, controls, box.timers);
    box.moveInteriorNodes(0.3, 5);
    box.geometry();
    box.setFields([](const Vec3& x) { return x.x + 0.3 * x.y < 0.9 ? 1.0 : 0.0; },
                  [](const Vec3& x) {
                    return Vec3{x.x < 0.8 ? 1.0 : -0.5, 0.0, 0.0};
                  },
                  2.0, 1.5);
    remap.apply();
    auto alpha = Kokkos::create_mirror_view_and_copy(HostSpace(), box.state.alpha_ck);
    auto v = Kokkos::create_mirror_view_and_copy(HostSpace(), box.state.v_c);
    for (Index c = 0; c < box.setup.mesh.n_cells; ++c) {
      for (int k = 0; k < 2; ++k) {
        EXPECT_GE(alpha(c, k), 0.0);
        EXPECT_LE(alpha(c, k), 1.0);
      }
      EXPECT_NEAR(alpha(c, 0) + alpha(c, 1), 1.0, 1e-14);
      EXPECT_GE(v(c, 0), -0.5 - 1e-12) << "cell " << c;
      EXPECT_LE(v(c, 0), 1.0 + 1e-12) << "cell " << c;
    }
  }
}

TEST(Remap, SodInRemapModeConvergesToTheExactSolution) {
  for (int nx : {100, 200}) {
    RunOptions options =
        testing::problemOptions("sod", {"mesh.nx=" + std::to_string(nx)}, 1.0, "remap");
    const RunResult result = runProblem(options);
    ASSERT_FALSE(result.failed) << result.failure;
    EXPECT_TRUE(result.checksPass());
    EXPECT_LT(result.drift_mass, 1e-13);
    EXPECT_LT(result.drift_energy, 1e-13);
    for (const Check& check : result.checks) {
      // Bound 0.65/nx, the lagrange tests' style; measured 5.9e-3 (100 cells)
      // and 2.9e-3 (200 cells), first order overall as the shock dominates.
      if (check.name == "l1_density") {
        EXPECT_LT(check.value, 0.65 / nx) << nx;
      }
    }
  }
}

TEST(Remap, PileInRemapModeMatchesItsChecks) {
  RunOptions options = testing::problemOptions("pile", {}, 0.5, "remap");
  const RunResult result = runProblem(options);
  ASSERT_FALSE(result.failed) << result.failure;
  for (const Check& check : result.checks) EXPECT_TRUE(check.pass()) << check.name;
  EXPECT_LT(result.drift_mass, 1e-12);
  EXPECT_LT(result.drift_energy, 1e-12);
}

// `wilkins` in remap mode (docs/method.md §6.1): the flyer with light gas behind it, walls
// at both ends of the fixed mesh. Nothing may enter it: the final totals are
// compared with the initial cells themselves, not through the audit (which
// subtracts what it books as crossing a moving outer face, and passed when
// the flyer's free back face swept aluminium into the mesh: +3.3% of mass,
// 760 m/s at the left end). Walls do no work; their impulses (p0 on the gas
// at one end, p0 on the aluminium at the other; no wave reaches them) cancel.
TEST(Remap, WilkinsInRemapModeTakesInNoMassAndMatchesItsChecks) {
  RunOptions options = testing::problemOptions("wilkins", {}, 0.5, "remap");
  const ProblemSetup setup = findProblem("wilkins").setup(options.config);
  ASSERT_EQ(setup.materials.size(), 2u);  // aluminium, gas
  const testing::StateTotals before = testing::initialTotals(setup);
  const RunResult result = runProblem(options);
  ASSERT_FALSE(result.failed) << result.failure;
  const testing::StateTotals after = testing::finalTotals(result.fields);
  const double mass = before.mass_k[0] + before.mass_k[1];
  EXPECT_NEAR(after.mass_k[0] + after.mass_k[1], mass, 1e-14 * mass);
  // Per material to 1e-12 of the total: the clean-up folds gas traces below
  // remap.alpha_floor into the aluminium (measured 4e-19 kg, 1e-14 of the total).
  for (int k = 0; k < 2; ++k) EXPECT_NEAR(after.mass_k[k], before.mass_k[k], 1e-12 * mass) << k;
  EXPECT_NEAR(after.momentum_x, before.momentum_x, 1e-12 * std::abs(before.momentum_x));
  EXPECT_NEAR(after.energy(), before.energy(), 1e-12 * before.energy());
  EXPECT_LT(result.drift_mass, 1e-14);
  EXPECT_LT(result.drift_energy, 1e-12);
  // The gas at the left wall is still at rest (the rarefaction behind the
  // flyer runs at 374 m/s and covers 1 mm of the 30).
  EXPECT_LT(std::abs(result.fields.v(0, 0)), 1e-6);
  std::vector<std::string> names;
  for (const Check& check : result.checks) {
    names.push_back(check.name);
    EXPECT_TRUE(check.pass()) << check.name << " = " << check.value;
  }
  // (mixed_cells: the flyer's back face meets its gas, src/mixed_cells.hpp)
  EXPECT_EQ(names, (std::vector<std::string>{"plastic_velocity", "plastic_sigma_xx",
                                             "plastic_density", "mixed_cells"}));
}

}  // namespace
}  // namespace lagremap

namespace lagremap {
namespace {

// docs/method.md §A8 energy split in one mixed cell under a uniform compression (the
// cell's energy change is exactly the compression work): each material gets
// its own -p^k dv^k, not a share of the total, with dv^k its part of the
// volume change, in proportion to w^k = alpha^k / (rho^k a_k^2) (docs/method.md §4.2:
// shared volume changes; alpha^k dv under equal strain), plus the pressure
// relaxation relax^k = v w^k (p^k - p_mean) (at most kMaxRelaxation of the
// material's volume) with its own work -p^k relax^k;
// the relaxation's dissipation sum_k p^k relax^k >= 0 is heat, shared by mass.
// updateMaterials (kernels/geometry.hpp) of cell 0, whose cell energy is e_cell.
// (A free function: nvcc's device lambdas may not live in a test body, and
// only the Views they read are captured.)
void updateMaterialsOfFirstCell(const Mesh& mesh, const State& state, double dt, double e_cell) {
  const auto cell_nodes = mesh.cell_nodes;
  const auto x_n = mesh.x_n;
  const State device_state = state;
  Kokkos::parallel_for(
      "test::update_materials", Kokkos::RangePolicy<ExecSpace>(0, 1), KOKKOS_LAMBDA(const Index c) {
        StageRelaxation relaxation;
        updateMaterials(cell_nodes, x_n, device_state, dt, c, e_cell, relaxation);
      });
  Kokkos::fence();
}

// One free cell (0.5 x 0.4 x 0.3: not of unit volume, the work carries v) of
// two gases out of pressure equilibrium: alpha 0.3 / 0.7, gamma 1.4 / 5/3,
// p_a = 2.4, p_b = 1/3, moving at `velocity`.
ProblemSetup twoGasCell(const Vec3& velocity) {
  BlockSpec block;
  block.hi = {0.5, 0.4, 0.3};
  SideBoundaries sides;
  for (auto& side : sides) side.kind = BoundaryKind::Free;
  ProblemSetup setup;
  setup.mesh = buildBlockMesh(block, sides);
  MaterialParams gas_a, gas_b;
  gas_a.gamma = 1.4;
  gas_b.gamma = 5.0 / 3.0;
  setup.materials = {gas_a, gas_b};
  setup.cells.alpha_k = {0.3, 0.7};
  setup.cells.rho_k = {2.0, 0.5};
  setup.cells.e_k = {3.0, 1.0};  // p_a = 2.4, p_b = 1/3: out of pressure equilibrium
  setup.cells.v = {velocity};
  return setup;
}

TEST(MixedCell, EachMaterialWorksByItsOwnPressureAndPressuresRelax) {
  ProblemSetup setup = twoGasCell(Vec3{0, 0, 0});
  State state = allocateState(setup.mesh, false);
  initializeState(setup, state);
  PhaseTimers timers;
  LagrangeStep lagrange(setup.mesh, state, Numerics(), timers);
  ASSERT_GT(lagrange.computeGeometry().val, 0.0);
  lagrange.saveStartOfStep();

  // Node velocities of a uniform compression V = -rate x: tr L = -3 rate.
  const double rate = 0.01, dt = 0.1;
  auto x = Kokkos::create_mirror_view_and_copy(HostSpace(), setup.mesh.x_n);
  auto v_n = Kokkos::create_mirror_view(state.v_n);
  for (Index n = 0; n < Index(x.extent(0)); ++n) storeVec3(v_n, n, -rate * loadVec3(x, n));
  Kokkos::deep_copy(state.v_n, v_n);
  auto m_k = Kokkos::create_mirror_view_and_copy(HostSpace(), state.m_ck);
  auto p_k = Kokkos::create_mirror_view_and_copy(HostSpace(), state.p_ck);
  auto e0 = Kokkos::create_mirror(state.e_ck);  // a true copy (host mirrors alias on host backends)
  Kokkos::deep_copy(e0, state.e_ck);
  const double volume = 0.5 * 0.4 * 0.3, trace_L = -3.0 * rate;
  double reversible = 0.0;  // sum_k -p^k share^k v tr(L) dt
  double work[2];
  const double alpha[2] = {0.3, 0.7}, gamma[2] = {1.4, 5.0 / 3.0};
  double weight[2], weight_sum = 0.0;  // alpha / (rho a^2) = alpha / (gamma p)
  for (int k = 0; k < 2; ++k) {
    weight[k] = alpha[k] / (gamma[k] * p_k(0, k));
    weight_sum += weight[k];
  }
  const double p_mean = (weight[0] * p_k(0, 0) + weight[1] * p_k(0, 1)) / weight_sum;
  double relax[2], heat = 0.0;
  // the relaxation, capped at kMaxRelaxation of each material's volume
  double cap = 1.0;
  for (int k = 0; k < 2; ++k) {
    relax[k] = volume * weight[k] * (p_k(0, k) - p_mean);
    cap = std::min(cap, kMaxRelaxation * alpha[k] * volume / std::abs(relax[k]));
  }
  for (int k = 0; k < 2; ++k) {
    work[k] = -p_k(0, k) * (weight[k] / weight_sum) * volume * trace_L * dt;
    reversible += work[k];
    relax[k] *= cap;
    heat += p_k(0, k) * relax[k];
  }
  const double mass = m_k(0, 0) + m_k(0, 1);
  const double e_cell = (m_k(0, 0) * e0(0, 0) + m_k(0, 1) * e0(0, 1)) / mass;
  updateMaterialsOfFirstCell(setup.mesh, state, dt, e_cell + reversible / mass);
  auto e = Kokkos::create_mirror_view_and_copy(HostSpace(), state.e_ck);
  for (int k = 0; k < 2; ++k) {
    const double expected = work[k] - p_k(0, k) * relax[k] + m_k(0, k) / mass * heat;
    EXPECT_NEAR(m_k(0, k) * (e(0, k) - e0(0, k)), expected, 1e-14) << "material " << k;
  }
  // The gas at the higher pressure expands into the other, volume is only
  // exchanged, and the exchange is irreversible (heat >= 0).
  EXPECT_GT(relax[0], 0.0);
  EXPECT_NEAR(relax[0] + relax[1], 0.0, 1e-16);
  EXPECT_GT(heat, 0.0);
  // and the two changes differ (a share of the total would give the gas at
  // the lower pressure part of the other's work)
  EXPECT_GT(std::abs(work[0] - reversible * alpha[0]), 1e-6);  // 3.2e-6 here
}

}  // namespace
}  // namespace lagremap

namespace lagremap {
namespace {

// One 1 mm cell of a solid at its reference density and gas (5 kg/m^3, gamma
// 1.4, specific energy e_gas) at rest, with the given outer boundaries.
ProblemSetup solidBesideGas(const MaterialParams& solid, double alpha_solid, double e_solid,
                            double e_gas, BoundaryKind boundary) {
  BlockSpec block;
  block.hi = {1e-3, 1e-3, 1e-3};
  SideBoundaries sides;
  for (auto& side : sides) side.kind = boundary;
  ProblemSetup setup;
  setup.mesh = buildBlockMesh(block, sides);
  MaterialParams gas;
  gas.gamma = 1.4;
  setup.materials = {solid, gas};
  setup.cells.alpha_k = {alpha_solid, 1.0 - alpha_solid};
  setup.cells.rho_k = {solid.rho0, 5.0};
  setup.cells.e_k = {e_solid, e_gas};
  setup.cells.v = {Vec3{0, 0, 0}};
  return setup;
}

// relaxationVolume of the solid (material 0) in the state's first cell
double solidRelaxationVolume(const State& state) {
  Kokkos::View<double> device_result("relax");
  Kokkos::parallel_for(
      "test::relaxation", Kokkos::RangePolicy<ExecSpace>(0, 1),
      KOKKOS_LAMBDA(const Index c) { device_result() = relaxationVolume(state, c, 0); });
  auto result = Kokkos::create_mirror_view_and_copy(HostSpace(), device_result);
  return result();
}

// A solid beside gas in one free cell (solidBesideGas), its interface normal
// along `normal_axis`, squeezed along y at `rate` through one Lagrangian stage
// of length dt (V = -rate y e_y on the nodes, which move with it), and its
// materials updated. own_ratio: the solid's volume ratio over the stage, from
// the formula of shareVolumeChange (its share of the cell's change plus its
// pressure relaxation).
struct SqueezedSolid {
  State state;
  double own_ratio = NAN;
};
SqueezedSolid squeezeSolidBesideGas(const MaterialParams& solid, double alpha_solid,
                                    int normal_axis, double rate, double dt) {
  ProblemSetup setup =
      solidBesideGas(solid, alpha_solid, 0.0, 1e5 / (0.4 * 5.0), BoundaryKind::Free);
  SqueezedSolid squeezed{allocateState(setup.mesh, false)};
  State& state = squeezed.state;
  initializeState(setup, state);
  state.alpha_trace = 1e-3;
  auto normal = Kokkos::create_mirror_view(state.n_ck);
  Kokkos::deep_copy(normal, 0.0);
  normal(0, 0, normal_axis) = 1.0;
  Kokkos::deep_copy(state.n_ck, normal);
  PhaseTimers timers;
  LagrangeStep lagrange(setup.mesh, state, Numerics(), timers);
  EXPECT_GT(lagrange.computeGeometry().val, 0.0);
  lagrange.saveStartOfStep();
  auto x = Kokkos::create_mirror_view_and_copy(HostSpace(), setup.mesh.x_n);
  auto v_n = Kokkos::create_mirror_view(state.v_n);
  for (Index n = 0; n < Index(x.extent(0)); ++n) {
    const Vec3 velocity{0.0, -rate * x(n, 1), 0.0};
    storeVec3(v_n, n, velocity);
    storeVec3(x, n, loadVec3(x, n) + dt * velocity);
  }
  Kokkos::deep_copy(state.v_n, v_n);
  Kokkos::deep_copy(setup.mesh.x_n, x);
  const double relax = solidRelaxationVolume(state);
  auto w0 = Kokkos::create_mirror_view_and_copy(HostSpace(), state.w_ck0);
  auto vol = Kokkos::create_mirror_view_and_copy(HostSpace(), state.vol_c);
  const double share = w0(0, 0) / (w0(0, 0) + w0(0, 1));
  squeezed.own_ratio = 1.0 + (share * vol(0) * (-rate * dt) + relax) / (alpha_solid * vol(0));
  updateMaterialsOfFirstCell(setup.mesh, state, dt, 0.0);
  return squeezed;
}

// Stress relaxation of a solid beside gas (kernels/geometry.hpp): what is
// equalised is the solid's normal stress across its interface, -p + S_nn, not
// its pressure. A beryllium layer at the stress of a free surface
// (p = p_gas + S_nn) hardly relaxes, the same layer with its interface along
// the other axis (sigma_nn = -p - s) expands into the gas; both by the formula.
TEST(MixedCell, SolidRelaxesItsNormalStressNotItsPressure) {
  const MaterialParams be = materialPreset("Be-hypo");
  // s small enough for the gas's 0.1% of the volume to take the relaxation
  // uncapped (kMaxRelaxation)
  const double p_gas = 1e5, s = 1e6, alpha_solid = 0.999;
  // Mie-Gruneisen at rho0: p = rho0 Gamma0 e
  ProblemSetup setup = solidBesideGas(be, alpha_solid, (p_gas + s) / (be.rho0 * be.Gamma0),
                                      p_gas / (0.4 * 5.0), BoundaryKind::Wall);
  State state = allocateState(setup.mesh, false);
  initializeState(setup, state);
  state.alpha_trace = 1e-3;
  auto S = Kokkos::create_mirror_view(state.S_ck);
  Kokkos::deep_copy(S, state.S_ck);
  storeSym(S, 0, 0, SymMat3{s, -s, 0.0, 0.0, 0.0, 0.0});
  Kokkos::deep_copy(state.S_ck, S);
  PhaseTimers timers;
  LagrangeStep lagrange(setup.mesh, state, Numerics(), timers);
  ASSERT_GT(lagrange.computeGeometry().val, 0.0);
  lagrange.saveStartOfStep();
  auto p_k = Kokkos::create_mirror_view_and_copy(HostSpace(), state.p_ck);
  auto w_k = Kokkos::create_mirror_view_and_copy(HostSpace(), state.w_ck);
  auto vol = Kokkos::create_mirror_view_and_copy(HostSpace(), state.vol_c);
  ASSERT_NEAR(p_k(0, 0), p_gas + s, 1e-6 * s);
  ASSERT_NEAR(p_k(0, 1), p_gas, 1e-6 * p_gas);
  double relax[2];
  for (int axis : {0, 1}) {
    auto normal = Kokkos::create_mirror_view(state.n_ck);
    Kokkos::deep_copy(normal, 0.0);
    normal(0, 0, axis) = 1.0;
    Kokkos::deep_copy(state.n_ck, normal);
    relax[axis] = solidRelaxationVolume(state);
    const double s_nn = axis == 0 ? s : -s;
    const double expected =
        vol(0) * w_k(0, 0) * w_k(0, 1) / (w_k(0, 0) + w_k(0, 1)) * ((p_k(0, 0) - s_nn) - p_k(0, 1));
    EXPECT_NEAR(relax[axis], expected, 1e-12 * std::abs(expected) + 1e-30) << "axis " << axis;
  }
  std::printf("relaxation volume / cell: free-surface stress %.2e, other axis %.2e\n",
              relax[0] / vol(0), relax[1] / vol(0));
  EXPECT_GT(relax[1], 0.0);
  EXPECT_LT(std::abs(relax[0]), 0.01 * relax[1]);
}

// A Neo-Hookean solid beside gas (kernels/geometry.hpp isSolidBody),
// compressed along y within one stage: the gas takes the cell's
// compression, and the solid's left Cauchy-Green tensor is stretched along
// its interface normal n to its own volume ratio J^k (its volume share plus
// its pressure relaxation), F_s = (I + (J^k / J - 1) n n) F: with n along
// the compression B_yy = (J^k)^2 and B_xx = B_zz = 1; with n along x the
// cell's compression stays in B_yy and B_xx = (J^k / J)^2. Either way
// det B = (J^k)^2, the solid's density and its deviator agree, at any
// volume fraction (equal strain, the rule before, gave B_yy = J^2).
TEST(MixedCell, NeoHookeanBodyStretchesAlongItsNormalToItsOwnVolume) {
  const double rate = 1e4, dt = 1e-6;  // 1% compression along y in the stage
  struct Case {
    double alpha_solid;
    int normal_axis;
  };
  for (const Case& test : {Case{0.8, 1}, Case{0.8, 0}, Case{0.3, 1}}) {
    const SqueezedSolid squeezed = squeezeSolidBesideGas(
        materialPreset("Be-hyper"), test.alpha_solid, test.normal_axis, rate, dt);
    const State& state = squeezed.state;
    const double J = 1.0 - rate * dt;
    const double J_solid = squeezed.own_ratio;
    auto B = Kokkos::create_mirror_view_and_copy(HostSpace(), state.B_ck);
    const SymMat3 b = loadSym(B, 0, 0);
    std::printf("alpha %.1f, n along %c: J %.6f, J_solid %.6f, B = diag(%.6f %.6f %.6f)\n",
                test.alpha_solid, "xyz"[test.normal_axis], J, J_solid, b.xx, b.yy, b.zz);
    // the solid takes almost none of the compression (gas 1e6 times softer)
    EXPECT_GT(J_solid, 1.0 - 1e-4);
    const double expected_xx = test.normal_axis == 0 ? (J_solid / J) * (J_solid / J) : 1.0;
    const double expected_yy = test.normal_axis == 1 ? J_solid * J_solid : J * J;
    EXPECT_NEAR(b.xx, expected_xx, 1e-12);
    EXPECT_NEAR(b.yy, expected_yy, 1e-12);
    EXPECT_NEAR(b.zz, 1.0, 1e-12);
    EXPECT_NEAR(b.xy, 0.0, 1e-12);
    EXPECT_NEAR(b.xx * b.yy * b.zz, J_solid * J_solid, 1e-12);
  }
}

// A hypo-elastic solid filling at least kSolidBodyAlpha of a cell beside gas
// is a body of its own too: its Jaumann rate sees the cell's strain rate
// plus the normal stretch that makes its volume rate its own, so a cell
// squeezed along the interface normal (the gas takes it) leaves the solid's
// deviator almost untouched, and squeezed along the interface the solid is
// in plane strain (its normal stretch makes up the lost volume). Below
// kSolidBodyAlpha the solid keeps the cell's strain rate. (With the cell's
// strain rate the `shell`'s surface cells were in uniaxial compression along
// the hoop at yield, with half the hoop stress of the interior.)
TEST(MixedCell, HypoElasticBodyStrainsAlongItsNormalToItsOwnVolume) {
  const double rate = 1e2, dt = 1e-6;  // 1e-4 compression along y: elastic
  struct Case {
    double alpha_solid;
    int normal_axis;
  };
  for (const Case& test : {Case{0.8, 1}, Case{0.8, 0}, Case{0.3, 1}}) {
    const MaterialParams be = materialPreset("Be-hypo");
    const SqueezedSolid squeezed =
        squeezeSolidBesideGas(be, test.alpha_solid, test.normal_axis, rate, dt);
    const State& state = squeezed.state;
    const double own_rate = (squeezed.own_ratio - 1.0) / dt;
    const SymMat3 S = loadSym(Kokkos::create_mirror_view_and_copy(HostSpace(), state.S_ck), 0, 0);
    // the solid's strain rate: the cell's diag(0, -rate, 0), its normal
    // component replaced by what makes the trace own_rate (a body only)
    double D[3] = {0.0, -rate, 0.0};
    if (test.alpha_solid >= 0.5) D[test.normal_axis] += own_rate - (-rate);
    const double mean = (D[0] + D[1] + D[2]) / 3.0;
    const double scale = 2.0 * be.mu * dt * rate;
    std::printf("alpha %.1f, n along %c: own volume rate %.3e / rate, S = diag(%.4e %.4e %.4e)\n",
                test.alpha_solid, "xyz"[test.normal_axis], own_rate / rate, S.xx, S.yy, S.zz);
    // the gas takes the compression (the solid's own rate is the pressure
    // relaxation towards the gas's 1e5 Pa, 0.2% of it)
    EXPECT_LT(std::abs(own_rate), 0.01 * rate);
    EXPECT_NEAR(S.xx, 2.0 * be.mu * dt * (D[0] - mean), 1e-9 * scale);
    EXPECT_NEAR(S.yy, 2.0 * be.mu * dt * (D[1] - mean), 1e-9 * scale);
    EXPECT_NEAR(S.zz, 2.0 * be.mu * dt * (D[2] - mean), 1e-9 * scale);
  }
}

// Two ideal gases of different gamma and density at the same pressure and
// velocity, in remap mode: the contact moves through the fixed mesh, its
// cells become mixed, and pressure and velocity must stay uniform across it
// (the classic test of a mixed-cell closure).
// With either closure (MixtureClosure): a contact between two gases in
// pressure equilibrium moving through the fixed mesh keeps p and u uniform,
// and each gas its density, the one receding from a cell as the one entering.
void expectUniformMovingContact(MixtureClosure closure) {
  BlockSpec block;
  block.nx = 100;
  SideBoundaries sides;
  for (auto& side : sides) side.kind = BoundaryKind::Wall;
  ProblemSetup setup;
  setup.mesh = buildBlockMesh(block, sides);
  MaterialParams left, right;
  left.gamma = 1.4;
  right.gamma = 5.0 / 3.0;
  setup.materials = {left, right};
  MaterialRegions regions;
  regions.material_at = [](const Vec3& x) { return x.x < 0.5 ? 0 : 1; };
  regions.rho = {1.0, 0.125};
  regions.e = {1.0 / (0.4 * 1.0), 1.0 / ((2.0 / 3.0) * 0.125)};  // p = 1 on both sides
  regions.velocity = [](int, const Vec3&) { return Vec3{1.0, 0.0, 0.0}; };
  fillMaterialRegions(setup, regions);
  State state = allocateState(setup.mesh, false);
  initializeState(setup, state);
  state.closure = closure;
  PhaseTimers timers;
  Numerics numerics;
  LagrangeStep lagrange(setup.mesh, state, numerics, timers);
  StepLimit limit = lagrange.computeGeometry();
  RemapStep remap(setup.mesh, state, RemapControls(), timers);
  double t = 0.0;
  long step = 0;
  // The walls send waves in: a rarefaction from x = 0 (c = 1.18) and a shock
  // from x = 1 into the light gas (c = 3.65); by t_end they stay outside
  // [0.3, 0.72], where the contact (0.5 -> 0.55) is checked.
  const double t_end = 0.05;
  while (t < t_end) {
    const double dt = std::min(0.5 * limit.val, t_end - t);
    limit = lagrange.advance(dt, ++step);
    ASSERT_GT(limit.val, 0.0);
    remap.apply();
    limit = lagrange.computeGeometry();
    ASSERT_GT(limit.val, 0.0) << "step " << step;
    t += dt;
  }
  auto p = Kokkos::create_mirror_view_and_copy(HostSpace(), state.p_c);
  auto v = Kokkos::create_mirror_view_and_copy(HostSpace(), state.v_c);
  auto alpha = Kokkos::create_mirror_view_and_copy(HostSpace(), state.alpha_ck);
  auto x = Kokkos::create_mirror_view_and_copy(HostSpace(), state.x_c);
  auto m_k = Kokkos::create_mirror_view_and_copy(HostSpace(), state.m_ck);
  auto volume = Kokkos::create_mirror_view_and_copy(HostSpace(), state.vol_c);
  double p_error = 0.0, u_error = 0.0, rho_error = 0.0;
  int mixed = 0;
  for (Index c = 0; c < setup.mesh.n_cells; ++c) {
    if (x(c, 0) < 0.3 || x(c, 0) > 0.72) continue;  // away from the wall waves
    p_error = std::max(p_error, std::abs(p(c) - 1.0));
    u_error = std::max(u_error, std::abs(v(c, 0) - 1.0));
    mixed += alpha(c, 0) > 1e-6 && alpha(c, 0) < 1.0 - 1e-6;
    // each material keeps its own density, the receding left gas in the
    // cells it leaves as much as the right gas in the cells it enters
    for (int k = 0; k < 2; ++k) {
      if (!(alpha(c, k) > 1e-6)) continue;
      const double rho_k = m_k(c, k) / (alpha(c, k) * volume(c));
      rho_error = std::max(rho_error, std::abs(rho_k / regions.rho[k] - 1.0));
    }
  }
  EXPECT_GT(mixed, 0);  // the contact did smear into mixed cells
  // measured 1.1e-14 .. 1.3e-14 for all three with either closure: it keeps
  // the two gases in pressure equilibrium, the remap keeps the velocity
  // uniform and moves each material's mass with its volume
  EXPECT_LT(p_error, 1e-12);
  EXPECT_LT(u_error, 1e-12);
  EXPECT_LT(rho_error, 1e-12);
  std::printf(
      "moving contact (%s): %d mixed cells, max |p - 1| = %.3g, max |u - 1| = %.3g, max "
      "|rho^k / rho^k_0 - 1| = %.3g\n",
      closure == MixtureClosure::EqualStrain ? "equal strain" : "relaxation", mixed, p_error,
      u_error, rho_error);
}

TEST(MixedCell, MovingContactKeepsPressureAndVelocityUniform) {
  expectUniformMovingContact(MixtureClosure::Relaxation);
  expectUniformMovingContact(MixtureClosure::EqualStrain);
}

// Under equal strain (the paper's closure) the volume fractions of a mixed
// cell do not change in the Lagrangian phase, whatever its materials'
// pressures, so each material's volume changes at the cell's rate; and its
// energies follow the paper's split: m^k de^k = -p^k alpha^k dv + (alpha^k /
// sum alpha) D, D the cell's energy change less the reversible work.
TEST(MixedCell, EqualStrainKeepsVolumeFractionsAndSplitsEnergyByVolume) {
  ProblemSetup setup = twoGasCell(Vec3{0.2, -0.1, 0.05});
  State state = allocateState(setup.mesh, false);
  initializeState(setup, state);
  state.closure = MixtureClosure::EqualStrain;
  PhaseTimers timers;
  LagrangeStep lagrange(setup.mesh, state, Numerics(), timers);
  ASSERT_GT(lagrange.computeGeometry().val, 0.0);
  lagrange.saveStartOfStep();
  // a whole step (free faces: the cell expands under its own pressure)
  ASSERT_GT(lagrange.advance(1e-3, 1).val, 0.0);
  auto alpha = Kokkos::create_mirror_view_and_copy(HostSpace(), state.alpha_ck);
  auto volume = Kokkos::create_mirror_view_and_copy(HostSpace(), state.vol_c);
  EXPECT_EQ(alpha(0, 0), 0.3);
  EXPECT_EQ(alpha(0, 1), 0.7);
  EXPECT_GT(volume(0), 0.5 * 0.4 * 0.3);  // it did expand
  // a material's density is m^k / (alpha^k v): both at the cell's rate
  auto m_k = Kokkos::create_mirror_view_and_copy(HostSpace(), state.m_ck);
  EXPECT_NEAR(m_k(0, 0) / (alpha(0, 0) * volume(0)) / (m_k(0, 1) / (alpha(0, 1) * volume(0))),
              2.0 / 0.5, 1e-13);

  // The energy split on a uniform compression of the start state, with a
  // dissipation D = 1e-4 added to the cell's energy change.
  lagrange.restoreStartOfStep();
  ASSERT_GT(lagrange.computeGeometry().val, 0.0);
  lagrange.saveStartOfStep();
  const double rate = 0.01, dt = 0.1, v0 = 0.5 * 0.4 * 0.3, trace_L = -3.0 * rate;
  auto x = Kokkos::create_mirror_view_and_copy(HostSpace(), setup.mesh.x_n);
  auto v_n = Kokkos::create_mirror_view(state.v_n);
  for (Index n = 0; n < Index(x.extent(0)); ++n) storeVec3(v_n, n, -rate * loadVec3(x, n));
  Kokkos::deep_copy(state.v_n, v_n);
  m_k = Kokkos::create_mirror_view_and_copy(HostSpace(), state.m_ck);
  auto p_k = Kokkos::create_mirror_view_and_copy(HostSpace(), state.p_ck);
  auto e0 = Kokkos::create_mirror(state.e_ck);
  Kokkos::deep_copy(e0, state.e_ck);
  auto E0 = Kokkos::create_mirror_view_and_copy(HostSpace(), state.E_c0);
  auto V0 = Kokkos::create_mirror_view_and_copy(HostSpace(), state.v_c0);
  const double mass = m_k(0, 0) + m_k(0, 1);
  const double e_start = E0(0) - 0.5 * dot(loadVec3(V0, 0), loadVec3(V0, 0));
  const double alphas[2] = {0.3, 0.7};
  double work[2], reversible = 0.0;
  for (int k = 0; k < 2; ++k) {
    work[k] = -p_k(0, k) * alphas[k] * v0 * trace_L * dt;
    reversible += work[k];
  }
  const double dissipation = 1e-4;
  updateMaterialsOfFirstCell(setup.mesh, state, dt, e_start + (reversible + dissipation) / mass);
  auto e = Kokkos::create_mirror_view_and_copy(HostSpace(), state.e_ck);
  for (int k = 0; k < 2; ++k) {
    EXPECT_NEAR(m_k(0, k) * (e(0, k) - e0(0, k)), work[k] + alphas[k] * dissipation, 1e-15)
        << "material " << k;
  }
}

}  // namespace
}  // namespace lagremap

namespace lagremap {
namespace {

// Interface width after advecting an interface by remapping from a translated
// copy of the mesh (the remap as a transport scheme), for the volume-fraction
// limiter parameter beta: the sum over cells of 4 alpha (1 - alpha) (one cell
// at alpha = 1/2 counts 1) per cell length of interface, i.e. the mean width
// of the smeared interface in cells. `disc`: a disc of radius 0.15 on a 40 x 40
// slab moved diagonally; otherwise a plane step on a 100-cell bar.
double interfaceWidth(double beta, bool disc) {
  const int n = disc ? 40 : 100;
  BlockSpec block;
  block.nx = n;
  block.ny = disc ? n : 1;
  block.hi = {1.0, disc ? 1.0 : 1.0 / n, 1.0 / n};
  SideBoundaries sides;
  for (auto& side : sides) side.kind = BoundaryKind::Wall;
  ProblemSetup setup;
  setup.mesh = buildBlockMesh(block, sides);
  MaterialParams gas;
  setup.materials = {gas, gas};
  MaterialRegions regions;
  regions.material_at = [disc](const Vec3& x) {
    return (disc ? std::hypot(x.x - 0.35, x.y - 0.4) < 0.15 : x.x < 0.3) ? 0 : 1;
  };
  regions.rho = {1.0, 1.0};
  regions.e = {2.5, 2.5};
  regions.velocity = [](int, const Vec3&) { return Vec3{0, 0, 0}; };
  fillMaterialRegions(setup, regions);
  State state = allocateState(setup.mesh, false);
  initializeState(setup, state);
  PhaseTimers timers;
  LagrangeStep lagrange(setup.mesh, state, Numerics(), timers);
  lagrange.computeGeometry();
  RemapControls controls;
  controls.beta_alpha = beta;
  RemapStep remap(setup.mesh, state, controls, timers);
  // Interior nodes moved by 0.3 cells along x (and 0.2 along y for the disc):
  // the content of each cell is carried that far per remap.
  auto x_target = Kokkos::create_mirror(setup.mesh.x_n);
  Kokkos::deep_copy(x_target, setup.mesh.x_n);
  auto x_lag = Kokkos::create_mirror(setup.mesh.x_n);
  const Vec3 shift{0.3 / n, disc ? 0.2 / n : 0.0, 0.0};
  for (Index node = 0; node < Index(x_lag.extent(0)); ++node) {
    const Vec3 x = loadVec3(x_target, node);
    const bool interior =
        x.x > 1e-12 && x.x < 1 - 1e-12 && (!disc || (x.y > 1e-12 && x.y < 1 - 1e-12));
    storeVec3(x_lag, node, interior ? x + shift : x);
  }
  for (int step = 0; step < 50; ++step) {
    Kokkos::deep_copy(setup.mesh.x_n, x_lag);
    lagrange.computeGeometry();
    remap.apply();
  }
  auto alpha = Kokkos::create_mirror_view_and_copy(HostSpace(), state.alpha_ck);
  double smeared = 0.0;
  for (Index c = 0; c < setup.mesh.n_cells; ++c) smeared += 4.0 * alpha(c, 0) * (1.0 - alpha(c, 0));
  return smeared / (disc ? 2.0 * M_PI * 0.15 * n : 1.0);
}

TEST(Remap, CompressiveLimiterKeepsAMovingInterfaceNarrower) {
  for (bool disc : {false, true}) {
    const double barth_jespersen = interfaceWidth(1.0, disc);
    const double compressive = interfaceWidth(2.0, disc);
    std::printf("%s after 50 remaps: interface width %.3f cells (beta = 1), %.3f (beta = 2)\n",
                disc ? "disc" : "plane step", barth_jespersen, compressive);
    // measured 1.6x (plane step) and 1.1x (diagonally moving disc: the min
    // over the 8 vertices with face-neighbour bounds leaves beta little room)
    EXPECT_LT((disc ? 1.05 : 1.4) * compressive, barth_jespersen) << (disc ? "disc" : "step");
  }
}

}  // namespace
}  // namespace lagremap
