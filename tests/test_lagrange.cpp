// Physics of the Lagrangian phase (docs/method.md §A4-A5): free-stream preservation on a
// distorted mesh, conservation to round-off with walls and free surfaces, 1D
// problems stay 1D, Sod against the exact solution at two resolutions for both
// orders, the Sedov blast radius and symmetry, and thread-count independence.
#include <gtest/gtest.h>
#include <hdf5.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <limits>
#include <map>

#include "src/diagnostics.hpp"
#include "src/kokkos_session.hpp"
#include "src/lagrange_step.hpp"
#include "src/materials.hpp"
#include "test_support.hpp"

namespace lagremap {
namespace {

using testing::problemOptions;

double checkValue(const RunResult& result, const std::string& name) {
  for (const auto& check : result.checks)
    if (check.name == name) return check.value;
  ADD_FAILURE() << "no check named " << name;
  return NAN;
}

// A moving gas at uniform state on a randomly distorted mesh, held by an
// imposed traction equal to its own stress on every side: the exact solution
// is a uniform translation, which the scheme must keep to round-off.
TEST(Lagrange, FreeStreamIsPreservedOnADistortedMesh) {
  const double p0 = 2.5, rho0 = 1.3, gamma = 1.4;
  const Vec3 velocity{3.0, -2.0, 1.0};
  for (int order : {1, 2}) {
    BlockSpec block;
    block.nx = 6;
    block.ny = 5;
    block.nz = 4;
    block.perturbation = 0.35;
    SideBoundaries sides;
    for (auto& side : sides) {
      side.kind = BoundaryKind::Traction;
      side.traction_stress = identitySym(-p0);
    }
    auto [setup, state] =
        testing::uniformBlock(block, sides, MaterialParams{EosKind::IdealGas, gamma}, rho0,
                              p0 / ((gamma - 1) * rho0), velocity);
    const Index n_cells = setup.mesh.n_cells;
    // A true copy: on host backends a mirror view would alias x_n, whose buffer
    // the step reuses (docs/method.md §2.8: Mesh::x_n and State::x_n_next trade places).
    auto x_start = Kokkos::create_mirror(setup.mesh.x_n);
    Kokkos::deep_copy(x_start, setup.mesh.x_n);

    Numerics numerics;
    numerics.order = order;
    PhaseTimers timers;
    LagrangeStep lagrange(setup.mesh, state, numerics, timers);
    double t = 0.0;
    for (int step = 1; step <= 20; ++step) {
      const StepLimit limit = lagrange.computeGeometry();
      ASSERT_GT(limit.val, 0.0);
      lagrange.advance(limit.val, step);
      t += limit.val;
    }
    lagrange.computeGeometry();
    auto v = Kokkos::create_mirror_view_and_copy(HostSpace(), state.v_c);
    auto p = Kokkos::create_mirror_view_and_copy(HostSpace(), state.p_c);
    auto x = Kokkos::create_mirror_view_and_copy(HostSpace(), setup.mesh.x_n);
    for (Index c = 0; c < n_cells; ++c) {
      EXPECT_LT(norm(loadVec3(v, c) - velocity), 1e-13 * norm(velocity)) << "order " << order;
      EXPECT_NEAR(p(c), p0, 1e-13 * p0) << "order " << order;
    }
    for (Index n = 0; n < setup.mesh.n_nodes; ++n) {
      const Vec3 moved = loadVec3(x, n) - loadVec3(x_start, n);
      EXPECT_LT(norm(moved - t * velocity), 1e-13) << "order " << order;
    }
  }
}

// A one-cell slab between symmetry planes (and a bar, thin in two
// directions): findNodeTwins pairs each node with its partner across the
// thin direction, and the nodal solve that copies the partner's solution
// gives what every node's own solve gives, to round-off; so does the prism
// geometry of a slab's cells against the general one.
TEST(Lagrange, SlabTwinNodesMoveAsTheirOwnSolveWouldMoveThem) {
  SideBoundaries walls;  // every side a wall (symmetry)
  const auto twinsOf = [&](int nx, int ny, int nz, const SideBoundaries& sides) {
    BlockSpec block;
    block.nx = nx;
    block.ny = ny;
    block.nz = nz;
    return buildBlockMesh(block, sides);
  };
  {  // slab: node p + 4 of every cell takes node p's solution, its force mirrored in z
    const Mesh slab = twinsOf(3, 2, 1, walls);
    ASSERT_EQ(slab.node_twin_source.extent(0), std::size_t(slab.n_nodes));
    const auto source = Kokkos::create_mirror_view_and_copy(HostSpace(), slab.node_twin_source);
    const auto flip = Kokkos::create_mirror_view_and_copy(HostSpace(), slab.node_twin_flip);
    const auto nodes = Kokkos::create_mirror_view_and_copy(HostSpace(), slab.cell_nodes);
    for (Index c = 0; c < slab.n_cells; ++c) {
      for (int p = 0; p < 4; ++p) {
        EXPECT_EQ(source(nodes(c, p)), nodes(c, p));
        EXPECT_EQ(source(nodes(c, p + 4)), nodes(c, p));
        EXPECT_EQ(flip(nodes(c, p + 4)), 4);
      }
    }
  }
  {  // bar along x: the four nodes of a station take the (y-, z-) one's
    const Mesh bar = twinsOf(4, 1, 1, walls);
    const auto source = Kokkos::create_mirror_view_and_copy(HostSpace(), bar.node_twin_source);
    const auto flip = Kokkos::create_mirror_view_and_copy(HostSpace(), bar.node_twin_flip);
    const auto nodes = Kokkos::create_mirror_view_and_copy(HostSpace(), bar.cell_nodes);
    for (Index c = 0; c < bar.n_cells; ++c) {
      EXPECT_EQ(source(nodes(c, 6)), nodes(c, 1));  // (x+, y+, z+) -> (x+, y-, z-)
      EXPECT_EQ(flip(nodes(c, 6)), 6);
      EXPECT_EQ(source(nodes(c, 3)), nodes(c, 0));  // (x-, y+, z-) -> (x-, y-, z-)
      EXPECT_EQ(flip(nodes(c, 3)), 2);
      EXPECT_EQ(source(nodes(c, 4)), nodes(c, 0));
      EXPECT_EQ(flip(nodes(c, 4)), 4);
    }
  }
  // no twins in a block two cells thick, or with a free side
  EXPECT_EQ(twinsOf(3, 2, 2, walls).node_twin_source.extent(0), 0u);
  SideBoundaries open_top = walls;
  open_top[5].kind = BoundaryKind::Free;
  EXPECT_EQ(twinsOf(3, 2, 1, open_top).node_twin_source.extent(0), 0u);
  // ... and cells that are z prisms (hex::prismGeometry) in the slab and the
  // bar only
  EXPECT_TRUE(twinsOf(3, 2, 1, walls).z_prisms);
  EXPECT_TRUE(twinsOf(4, 1, 1, walls).z_prisms);
  EXPECT_FALSE(twinsOf(3, 2, 2, walls).z_prisms);
  EXPECT_FALSE(twinsOf(3, 2, 1, open_top).z_prisms);
  EXPECT_FALSE(twinsOf(1, 2, 3, walls).z_prisms);  // thin along x: not along z

  // a hot corner of a gas slab expands for 15 steps, with and without twins
  // and prism geometry (the prisms' corner terms reconstructed at their
  // bottom vertices alone); then a sheared aluminium slab, whose stresses
  // take the tensor limiter's path
  const auto run = [&](bool twins, bool solid) {
    BlockSpec block;
    block.nx = 8;
    block.ny = 6;
    block.nz = 1;
    block.hi = Vec3{1.0, 0.75, 0.125};
    const MaterialParams material =
        solid ? materialPreset("Al") : MaterialParams{EosKind::IdealGas, 1.4};
    auto [setup, state] = testing::uniformBlock(block, walls, material, solid ? material.rho0 : 1.0,
                                                solid ? 1e4 : 2.5, Vec3{0.0, 0.0, 0.0});
    auto e = Kokkos::create_mirror_view_and_copy(HostSpace(), state.E_c);
    auto v = Kokkos::create_mirror_view_and_copy(HostSpace(), state.v_c);
    for (Index c = 0; c < setup.mesh.n_cells; ++c) {
      if (solid) {  // a shear flow: v_x growing with the row, v_y with the column
        v(c, 0) = 20.0 * double(c / 8);
        v(c, 1) = -10.0 * double(c % 8);
        e(c) += 0.5 * (v(c, 0) * v(c, 0) + v(c, 1) * v(c, 1));
      }
    }
    e(0) = e(1) = e(8) = solid ? 1e6 : 250.0;
    Kokkos::deep_copy(state.E_c, e);
    Kokkos::deep_copy(state.v_c, v);
    EXPECT_TRUE(setup.mesh.z_prisms);
    if (!twins) {
      setup.mesh.node_twin_source = IndexView();
      setup.mesh.z_prisms = false;
    }
    Numerics numerics;
    PhaseTimers timers;
    LagrangeStep lagrange(setup.mesh, state, numerics, timers);
    for (int step = 1; step <= 15; ++step) {
      const StepLimit limit = lagrange.computeGeometry();
      lagrange.advance(0.5 * limit.val, step);
    }
    return std::make_pair(Kokkos::create_mirror_view_and_copy(HostSpace(), state.v_n),
                          Kokkos::create_mirror_view_and_copy(HostSpace(), state.v_c));
  };
  for (const bool solid : {false, true}) {
    const auto [v_node, v_cell] = run(true, solid);
    const auto [v_node_own, v_cell_own] = run(false, solid);
    double largest = 0.0;
    for (std::size_t n = 0; n < v_node.extent(0); ++n)
      largest = std::max(largest, norm(loadVec3(v_node_own, n)));
    ASSERT_GT(largest, 0.1);  // it moved
    for (std::size_t n = 0; n < v_node.extent(0); ++n) {
      EXPECT_LT(norm(loadVec3(v_node, n) - loadVec3(v_node_own, n)), 1e-12 * largest)
          << (solid ? "solid" : "gas") << " node " << n;
      EXPECT_EQ(v_node(n, 2), 0.0) << "node " << n;
    }
    for (std::size_t c = 0; c < v_cell.extent(0); ++c) {
      EXPECT_LT(norm(loadVec3(v_cell, c) - loadVec3(v_cell_own, c)), 1e-12 * largest)
          << (solid ? "solid" : "gas") << " cell " << c;
    }
  }
}

// A Mie-Gruneisen solid compressed past eta = s / (s - 1) has no state: the
// geometry phase reports the cell with that reason instead of carrying on.
TEST(Lagrange, MieGruneisenLimitingCompressionIsAClearFailure) {
  const MaterialParams aluminium = materialPreset("Al");
  for (double eta : {1.2, 4.0}) {
    BlockSpec block;
    block.nx = 3;
    auto [setup, state] = testing::uniformBlock(block, SideBoundaries{}, aluminium,
                                                eta * aluminium.rho0, 1e4, Vec3{0, 0, 0});
    const StepLimit limit = computeGeometry(setup.mesh, state, TimeStepControls{});
    if (eta < 2.0) {
      // valid: CFL step from the longitudinal sound speed of the solid,
      // aL^2 = a^2 (Mie-Gruneisen) + 4/3 mu / rho
      const double rho = eta * aluminium.rho0;
      const ThermoState thermo = evaluateEos(aluminium, rho, 1e4);
      const double aL = std::sqrt(thermo.sound_speed2 + 4.0 / 3.0 * aluminium.mu / rho);
      EXPECT_NEAR(limit.val, 0.4 * (1.0 / 3.0) / aL, 1e-12);
    } else {
      EXPECT_LT(limit.val, 0.0);
      EXPECT_EQ(limit.loc % kLimitCodes, kBadEos);
      EXPECT_NE(describeInvalidCell(limit, 7, "test").find("Mie-Gruneisen"), std::string::npos);
    }
  }
}

// A solid problem (Mie-Gruneisen, hypo-elastic, plastic shock, free surface):
// the plastic state of the exact two-wave solution, and mass, momentum and
// total energy to round-off (plastic work goes to internal energy, none lost).
TEST(Lagrange, FlyerPlatePlasticStateAndConservation) {
  const RunResult result = runProblem(problemOptions("wilkins"));
  ASSERT_FALSE(result.failed) << result.failure;
  for (const auto& check : result.checks) EXPECT_TRUE(check.pass()) << check.name;
  EXPECT_NEAR(checkValue(result, "plastic_velocity"), 400.0, 1.0);
  EXPECT_EQ(result.drift_mass, 0.0);
  EXPECT_LT(result.drift_momentum, 1e-12);
  EXPECT_LT(result.drift_energy, 1e-12);
  EXPECT_LT(result.max_transverse_velocity, 1e-12);
}

// Neo-Hookean bar driven by an end traction: the wall stress follows the exact
// square wave (0 / -1e8 / 0), no lateral motion for nu = 0, and the energy the
// traction puts in is all there (drift with the boundary work subtracted).
TEST(Lagrange, PileWallStressSquareWaveAndEnergyBalance) {
  const RunResult result = runProblem(problemOptions("pile"));
  ASSERT_FALSE(result.failed) << result.failure;
  ASSERT_EQ(result.checks.size(), 5u);
  for (const auto& check : result.checks) {
    EXPECT_TRUE(check.pass()) << check.name << " = " << check.value;
  }
  EXPECT_NEAR(checkValue(result, "wall_stress_plateau"), -1e8, 1e6);
  EXPECT_NEAR(checkValue(result, "arrival_time"), 2e-3, 5e-5);
  EXPECT_EQ(result.drift_mass, 0.0);
  EXPECT_LT(result.drift_momentum, 1e-12);
  EXPECT_LT(result.drift_energy, 1e-12);
}

// A `fixed` end holds its nodes at rest (all three directions): on the 1D bar,
// whose nodes move only along x, it must give exactly the wall's answer, and
// the end nodes must not have moved.
TEST(Lagrange, FixedBoundaryHoldsItsNodes) {
  const RunResult wall = runProblem(problemOptions("sod", {"t_end=0.05"}));
  const RunResult fixed =
      runProblem(problemOptions("sod", {"t_end=0.05", "bc.xmin=fixed", "bc.xmax=fixed"}));
  ASSERT_FALSE(wall.failed);
  ASSERT_FALSE(fixed.failed);
  ASSERT_EQ(wall.steps, fixed.steps);
  const Index n_cells = Index(wall.fields.rho.extent(0));
  for (Index c = 0; c < n_cells; ++c) {
    EXPECT_NEAR(fixed.fields.rho(c), wall.fields.rho(c), 1e-12) << c;
  }
  const auto& x = fixed.fields.mesh.x_n;
  int end_nodes = 0;
  for (Index n = 0; n < Index(x.extent(0)); ++n) {
    end_nodes += (x(n, 0) == 0.0 || x(n, 0) == 1.0) ? 1 : 0;
  }
  EXPECT_EQ(end_nodes, 8);  // 4 nodes at each end, exactly where they started
}

// Walls on three sides, free surfaces on the other three: mass exactly, and
// momentum and total energy to round-off once the wall impulse and work (zero
// for slip walls) are accounted for.
TEST(Lagrange, ConservesMassMomentumAndEnergyWithWallsAndFreeSurfaces) {
  for (const char* gather : {"crs", "atomics"}) {
    for (const char* order : {"1", "2"}) {
      RunOptions options =
          problemOptions("sedov", {"mesh.nx=10", "mesh.ny=9", "mesh.nz=8", "bc.xmax=free",
                                   "bc.ymax=free", "bc.zmax=free", "ambient.p=0.05", "t_end=0.2",
                                   std::string("numerics.gather=") + gather,
                                   std::string("numerics.order=") + order});
      const RunResult result = runProblem(options);
      ASSERT_FALSE(result.failed) << result.failure;
      EXPECT_GT(result.steps, 20);
      EXPECT_EQ(result.drift_mass, 0.0);
      EXPECT_LT(result.drift_momentum, 1e-12) << gather << " order " << order;
      EXPECT_LT(result.drift_energy, 1e-12) << gather << " order " << order;
    }
  }
}

TEST(Lagrange, OneDimensionalProblemStaysOneDimensional) {
  for (const char* order : {"1", "2"}) {
    const RunResult result =
        runProblem(problemOptions("sod", {std::string("numerics.order=") + order}));
    ASSERT_FALSE(result.failed);
    EXPECT_LT(result.max_transverse_velocity, 1e-14) << "order " << order;
  }
}

// L1 density error against the exact Riemann solution at 100 and 200 cells;
// bounds are the measured errors (docs/verification.md §2) with a 30% margin.
TEST(Lagrange, SodConvergesToTheExactSolution) {
  struct Case {
    int order;
    double bound_100, bound_200, min_rate;
  };
  for (const Case& c : {Case{1, 0.0246, 0.0157, 0.5}, Case{2, 0.0069, 0.0035, 0.8}}) {
    double error[2];
    int index = 0;
    for (int nx : {100, 200}) {
      const RunResult result = runProblem(problemOptions(
          "sod", {"mesh.nx=" + std::to_string(nx), "numerics.order=" + std::to_string(c.order)}));
      ASSERT_FALSE(result.failed);
      error[index++] = checkValue(result, "l1_density");
    }
    const double rate = std::log2(error[0] / error[1]);
    std::printf("sod order %d: L1(rho) = %.4e (100 cells), %.4e (200 cells), observed order %.2f\n",
                c.order, error[0], error[1], rate);
    EXPECT_LT(error[0], c.bound_100);
    EXPECT_LT(error[1], c.bound_200);
    EXPECT_GT(rate, c.min_rate);
  }
}

TEST(Lagrange, SedovShockRadiusAndOctantSymmetry) {
  const RunResult result = runProblem(problemOptions("sedov", {}, 2.0 / 3.0));  // 20^3
  ASSERT_FALSE(result.failed);
  ASSERT_EQ(result.cells, 20 * 20 * 20);
  for (const auto& check : result.checks) {
    EXPECT_TRUE(check.pass()) << check.name << " = " << check.value << " vs " << check.reference
                              << " +- " << check.tolerance;
  }
  EXPECT_NEAR(checkValue(result, "shock_radius"), 1.0, 0.03);
  EXPECT_LT(checkValue(result, "octant_symmetry"), 1e-10);
  // L1 errors against the exact solution (docs/verification.md §8.8), measured
  // at 20^3: 0.1219, 6.72e-3, 2.55e-3; each check applies with its built-in bound
  int l1_checks = 0;
  for (const auto& check : result.checks) {
    if (check.name.rfind("l1_", 0) != 0) continue;
    ++l1_checks;
    EXPECT_TRUE(check.applies) << check.name << ": " << check.not_applicable;
  }
  EXPECT_EQ(l1_checks, 3);
  EXPECT_NEAR(checkValue(result, "l1_density"), 0.1219, 0.005);
  EXPECT_NEAR(checkValue(result, "l1_velocity"), 6.72e-3, 3e-4);
  EXPECT_NEAR(checkValue(result, "l1_pressure"), 2.55e-3, 1e-4);
}

// The CRS gather makes every node sum in corner order: results are bit for bit
// the same for 1 and 2 OpenMP threads (two processes, final snapshots compared).
std::vector<double> readDataset(const std::string& file, const std::string& name) {
  const hid_t h5 = H5Fopen(file.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  EXPECT_GE(h5, 0) << file;
  const hid_t dataset = H5Dopen2(h5, name.c_str(), H5P_DEFAULT);
  const hid_t space = H5Dget_space(dataset);
  std::vector<double> values(H5Sget_simple_extent_npoints(space));
  H5Dread(dataset, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data());
  H5Sclose(space);
  H5Dclose(dataset);
  H5Fclose(h5);
  return values;
}

// Both spellings of the thread-count flag reach this Kokkos as its own.
TEST(Lagrange, ThreadCountFlagTakesBothKokkosSpellings) {
  const std::string flag = kokkosThreadsFlag();
  EXPECT_EQ(withKokkosThreadsSpelling("--kokkos-threads=3"), flag + "=3");
  EXPECT_EQ(withKokkosThreadsSpelling("--kokkos-num-threads=3"), flag + "=3");
  EXPECT_EQ(withKokkosThreadsSpelling("--kokkos-threads-x=3"), "--kokkos-threads-x=3");
  EXPECT_EQ(withKokkosThreadsSpelling("--threads=3"), "--threads=3");
  EXPECT_EQ(withKokkosThreadsSpelling("--kokkos-numa=3"), "--kokkos-numa=3");
}

// The two kernel forms (numerics.kernels, kernels/geometry.hpp) give the same
// bits: a 3D hexahedral run (sedov), a one-solid run (taylor), a remap run on z prisms with mixed
// cells (taylor), a Neo-Hookean remap run on hexahedra (beam) and one through a moving traction
// face (pile), mixed cells of two gases (air_helium) and of a hardening solid (rod), an ALE run
// (taylor), to their final fields. On a GPU build only the staged form exists and asking for the
// fused one is an error.
TEST(KernelForms, FusedAndStagedRunsAreBitIdentical) {
  struct Case {
    const char* problem;
    const char* mode;
    double scale;
    std::vector<std::string> set;
  };
  const Case cases[] = {
      {"sedov", "lagrange", 0.3, {"t_end=0.1"}},
      {"taylor", "lagrange", 0.25, {"t_end=2e-4"}},  // one solid: no energies kernel, no sharing
      {"taylor", "remap", 0.25, {"t_end=2e-4"}},
      {"beam", "remap", 0.3, {"t_end=1e-6"}},
      {"pile", "remap", 0.5, {"t_end=1e-5"}},   // a traction face: mass and energy cross it
      {"air_helium", "remap", 0.5, {}},         // the staged energies kernel shares the volumes
      {"rod", "remap", 0.25, {"t_end=2e-6"}},   // energies and hardening deviators, one kernel
      {"taylor", "ale", 0.25, {"t_end=2e-4"}},  // the relaxed mesh's remap, bounded parcels
  };
  for (const Case& c : cases) {
    FinalFields fields[2];
    long steps[2] = {0, 0};
    int i = 0;
    for (const char* form : {"fused", "staged"}) {
      std::vector<std::string> set = c.set;
      set.push_back(std::string("numerics.kernels=") + form);
      const RunOptions options = problemOptions(c.problem, set, c.scale, c.mode);
      if (!kFusedKernelsBuilt && std::string(form) == "fused") {
        EXPECT_THROW(runProblem(options), ConfigError);
        continue;
      }
      const RunResult result = runProblem(options);
      ASSERT_FALSE(result.failed) << c.problem << " " << form << ": " << result.failure;
      // (the audit's sums are taken in other orders than the fields': it
      // still closes)
      EXPECT_LT(result.drift_mass, 1e-13) << c.problem << " " << form;
      EXPECT_LT(result.drift_energy, 1e-12) << c.problem << " " << form;
      steps[i] = result.steps;
      fields[i++] = result.fields;
    }
    if (!kFusedKernelsBuilt) continue;
    ASSERT_GT(steps[0], 5) << c.problem;
    EXPECT_EQ(steps[0], steps[1]) << c.problem;
    const auto same = [](const auto& a, const auto& b) {
      return a.span() == b.span() && a.span() > 0 &&
             std::memcmp(a.data(), b.data(), a.span() * sizeof(double)) == 0;
    };
    EXPECT_TRUE(same(fields[0].rho, fields[1].rho)) << c.problem;
    EXPECT_TRUE(same(fields[0].e, fields[1].e)) << c.problem;
    EXPECT_TRUE(same(fields[0].p, fields[1].p)) << c.problem;
    EXPECT_TRUE(same(fields[0].v, fields[1].v)) << c.problem;
    EXPECT_TRUE(same(fields[0].mesh.x_n, fields[1].mesh.x_n)) << c.problem;
    if (std::string(c.mode) == "remap") {
      EXPECT_TRUE(same(fields[0].alpha, fields[1].alpha)) << c.problem;
      EXPECT_TRUE(same(fields[0].m_k, fields[1].m_k)) << c.problem;
      EXPECT_TRUE(same(fields[0].e_k, fields[1].e_k)) << c.problem;
    }
  }
}

// The fields a step changes (and the nodes), copied to the host.
testing::HostFields stepFields(const Mesh& mesh, const State& state) {
  testing::HostFields all;
  for (const auto& [name, view] : {std::pair{"v_c", state.v_c}, {"x_n", mesh.x_n}}) {
    testing::addHostCopy(all, name, view);
  }
  for (const auto& [name, view] : {std::pair{"E_c", state.E_c}, {"m_c", state.m_c}}) {
    testing::addHostCopy(all, name, view);
  }
  for (const auto& [name, view] :
       {std::pair{"e_ck", state.e_ck}, {"alpha_ck", state.alpha_ck}, {"eps_ck", state.eps_ck}}) {
    testing::addHostCopy(all, name, view);
  }
  testing::addHostCopy(all, "S_ck", state.S_ck);
  return all;
}

// A step keeps the state it starts from as it goes (its first stage's corner
// kernel and nodal solve: kernels/step_start.hpp). With every start-of-step
// copy spoiled (NaN) beforehand, a step gives the bits it gives after a save
// of its own (nothing read a copy before the step had made it), and putting
// the start back gives the state before the step, bit for bit. Both kernel
// forms; taylor's mixed solid cells, sedov's general hexahedra, the nodes.
TEST(Lagrange, AStepKeepsItsOwnStartOfStep) {
  std::vector<std::string> forms{"staged"};
  if (kFusedKernelsBuilt) forms.push_back("fused");
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (const char* problem : {"taylor", "sedov"}) {
    for (const std::string& form : forms) {
      const std::string what = std::string(problem) + " " + form;
      testing::HostFields stepped[2], before, restored;
      for (const bool spoil : {false, true}) {
        const RunOptions options = problemOptions(problem, {"numerics.kernels=" + form}, 0.25);
        ProblemSetup setup = findProblem(problem).setup(options.config);
        State state = allocateState(setup.mesh, false);
        initializeState(setup, state);
        PhaseTimers timers;
        LagrangeStep lagrange(setup.mesh, state, readNumerics(options.config), timers);
        const StepLimit limit = lagrange.computeGeometry();
        ASSERT_GT(limit.val, 0.0) << what;
        before = stepFields(setup.mesh, state);
        if (spoil) {
          for (const auto& view : {state.E_c0, state.vol_c0}) Kokkos::deep_copy(view, nan);
          for (const auto& view : {state.x_n0, state.v_c0}) Kokkos::deep_copy(view, nan);
          for (const auto& view :
               {state.e_ck0, state.alpha_ck0, state.w_ck0, state.p_ck0, state.eps_ck0}) {
            if (view.span() > 0) Kokkos::deep_copy(view, nan);
          }
          for (const auto& view : {state.S_ck0, state.B_ck0}) {
            if (view.span() > 0) Kokkos::deep_copy(view, nan);
          }
        } else {
          lagrange.saveStartOfStep();
        }
        ASSERT_GT(lagrange.advance(0.5 * limit.val, 1).val, 0.0) << what;
        stepped[spoil] = stepFields(setup.mesh, state);
        lagrange.restoreStartOfStep();
        restored = stepFields(setup.mesh, state);
      }
      for (const auto& [name, values] : before) {
        EXPECT_TRUE(testing::sameBits(stepped[0][name], stepped[1][name])) << what << " " << name;
        EXPECT_TRUE(testing::sameBits(values, restored[name])) << what << " " << name;
      }
      for (const char* changed : {"x_n", "v_c", "E_c"}) {  // (what is put back moved)
        EXPECT_FALSE(testing::sameBits(before[changed], stepped[1][changed]))
            << what << " " << changed;
      }
    }
  }
}

// The boundary's force and power that a step's last nodal solve sums (the
// audit's work, kernels/audit_sums.hpp) are those of the forces and
// velocities it leaves: the separate sum over the nodes agrees to round-off.
// pile: a traction does work on its end face.
TEST(Lagrange, TheLastNodalSolveSumsTheBoundaryPower) {
  const RunOptions options = problemOptions("pile", {}, 0.5);
  ProblemSetup setup = findProblem("pile").setup(options.config);
  State state = allocateState(setup.mesh, false);
  initializeState(setup, state);
  PhaseTimers timers;
  LagrangeStep lagrange(setup.mesh, state, readNumerics(options.config), timers);
  const StepLimit limit = lagrange.computeGeometry();
  ASSERT_GT(limit.val, 0.0);
  StepReport report;
  for (int step = 0; step < 3; ++step) {
    Kokkos::deep_copy(report.boundary, BoundaryPowerSums());
    lagrange.launch(0.5 * limit.val, report);
    Kokkos::fence();
    const BoundaryPower separate = computeBoundaryPower(setup.mesh, state);
    const BoundaryPowerSums& solved = report.boundary();
    const double force_scale = norm(separate.force);
    ASSERT_GT(force_scale, 0.0);
    ASSERT_GT(std::abs(separate.power), 0.0);
    EXPECT_NEAR(solved.v[0], separate.force.x, 1e-12 * force_scale);
    EXPECT_NEAR(solved.v[1], separate.force.y, 1e-12 * force_scale);
    EXPECT_NEAR(solved.v[2], separate.force.z, 1e-12 * force_scale);
    EXPECT_NEAR(solved.v[3], separate.power, 1e-12 * std::abs(separate.power));
  }
}

TEST(Lagrange, CrsGatherIsBitIdenticalForOneAndTwoThreads) {
  const std::string dir = testing::scratchDir("determinism");
  // One run with each spelling of the flag (Kokkos 3.x and 4.x).
  for (int threads : {1, 2}) {
    const std::string flag = threads == 1 ? "--kokkos-threads=" : "--kokkos-num-threads=";
    const auto result = testing::runLagremap(
        "--problem sedov --scale 0.4 --t-end 0.3 --set check.radius_tolerance=0.2 --quiet " + flag +
        std::to_string(threads) + " --output " + dir + "/t" + std::to_string(threads));
    ASSERT_EQ(result.exit_code, 0) << result.output;
  }
  for (const char* name :
       {"/fields/density", "/fields/velocity", "/fields/internal_energy", "/mesh/coordinates"}) {
    const auto one = readDataset(dir + "/t1/fields_00001.h5", name);
    const auto two = readDataset(dir + "/t2/fields_00001.h5", name);
    ASSERT_EQ(one.size(), two.size());
    ASSERT_FALSE(one.empty());
    EXPECT_EQ(0, std::memcmp(one.data(), two.data(), one.size() * sizeof(double))) << name;
  }
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace lagremap
