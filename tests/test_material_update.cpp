// The materials' update of a mixed cell (kernels/material_update.hpp, its
// energy budget kernels/mixed_cell_budget.hpp; docs/method.md §4, §A8): each
// material's own work and share of the dissipation, the relaxation of a
// solid's normal stress, a solid body's own volume ratio, and a contact of two
// gases moving through the fixed mesh under either closure.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "kernels/material_update.hpp"
#include "src/lagrange_step.hpp"
#include "src/materials.hpp"
#include "src/remap_step.hpp"
#include "test_support.hpp"

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
// updateMaterials (kernels/material_update.hpp) of cell 0, whose cell energy is e_cell.
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
