// ALE mode (docs/method.md §8): the mesh-quality measure, the Winslow
// relaxation's properties (an affine mesh is its own relaxed mesh, a rough
// one is smoothed, boundary nodes keep their sides, moves are limited, the
// quality guard holds), and the mode's two limits bit for bit: a target at
// the initial mesh is remap mode, no relaxation is lagrange mode.
#include <gtest/gtest.h>

#include <cmath>

#include "kernels/mesh_quality.hpp"
#include "kernels/mesh_relaxation.hpp"
#include "random_draws.hpp"
#include "test_support.hpp"

namespace lagremap {
namespace {

void unitCube(Vec3 x[8]) {
  const Vec3 cube[8] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
                        {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
  for (int p = 0; p < 8; ++p) x[p] = cube[p];
}

Vec3 rotated(const Vec3& a) {  // a rotation by 0.7 rad about (1, 2, 3) / |(1, 2, 3)|
  const Vec3 axis = (1.0 / std::sqrt(14.0)) * Vec3{1.0, 2.0, 3.0};
  const double c = std::cos(0.7), s = std::sin(0.7);
  return c * a + s * cross(axis, a) + (1.0 - c) * dot(axis, a) * axis;
}

TEST(MeshQuality, ACubeIsOneAndTheMeasureIgnoresPlaceOrientationAndSize) {
  Vec3 x[8];
  unitCube(x);
  for (int p = 0; p < 8; ++p) EXPECT_NEAR(cornerScaledJacobian(x, p), 1.0, 1e-15) << p;
  // a box of unequal sides still has right angles
  for (int p = 0; p < 8; ++p) x[p] = Vec3{3.0 * x[p].x, 0.5 * x[p].y, 7.0 * x[p].z};
  EXPECT_NEAR(cellScaledJacobian(x), 1.0, 1e-15);
  // a randomly distorted cell: the same value moved, rotated and scaled
  unitCube(x);
  for (int p = 0; p < 8; ++p) x[p] += randomVec(0.2);
  const double quality = cellScaledJacobian(x);
  EXPECT_LT(quality, 0.99);
  // the cell's edges shared by its corners: the corners' own numbers, bit for bit
  double smallest = 1.0;
  for (int p = 0; p < 8; ++p) smallest = std::min(smallest, cornerScaledJacobian(x, p));
  EXPECT_EQ(quality, smallest);
  Vec3 moved[8];
  for (int p = 0; p < 8; ++p) moved[p] = 4.5 * rotated(x[p]) + Vec3{10.0, -3.0, 2.0};
  EXPECT_NEAR(cellScaledJacobian(moved), quality, 1e-13);
}

TEST(MeshQuality, AShearedCubeHasTheCosineOfItsAngleAndAnInvertedOneIsNegative) {
  // x += tan(theta) z: the corners' edges along x and z meet at 90 deg -/+ theta
  const double theta = 0.4;
  Vec3 x[8];
  unitCube(x);
  for (int p = 0; p < 8; ++p) x[p].x += std::tan(theta) * x[p].z;
  EXPECT_NEAR(cellScaledJacobian(x), std::cos(theta), 1e-14);
  // the top face pushed through the bottom one
  unitCube(x);
  for (int p = 4; p < 8; ++p) x[p].z = -0.5;
  EXPECT_LT(cellScaledJacobian(x), 0.0);
  // a collapsed edge: no angle, quality 0
  unitCube(x);
  x[1] = x[0];
  EXPECT_EQ(cornerScaledJacobian(x, 0), 0.0);
}

// The targets of every node of a mesh whose nodes are at x (host copies).
std::vector<Vec3> targetsOf(const Mesh& mesh, const RelaxationControls& controls,
                            const Vec3View& x_initial) {
  Vec3View x_target("x_target", mesh.n_nodes);
  relaxedTargets(mesh, nodeStencils(mesh), mesh.x_n, x_initial, nodeFreedom(mesh), controls,
                 x_target);
  const auto host = Kokkos::create_mirror_view_and_copy(HostSpace(), x_target);
  std::vector<Vec3> targets(std::size_t(mesh.n_nodes));
  for (Index n = 0; n < mesh.n_nodes; ++n) targets[n] = loadVec3(host, n);
  return targets;
}

std::vector<Vec3> positionsOf(const Mesh& mesh) {
  const auto host = Kokkos::create_mirror_view_and_copy(HostSpace(), mesh.x_n);
  std::vector<Vec3> x(std::size_t(mesh.n_nodes));
  for (Index n = 0; n < mesh.n_nodes; ++n) x[n] = loadVec3(host, n);
  return x;
}

TEST(Winslow, AnAffineImageOfAUniformBlockIsItsOwnRelaxedMesh) {
  // any uniform deformation of the material leaves the mesh where it is
  BlockSpec block;
  block.nx = 6;
  block.ny = 5;
  block.nz = 4;
  block.mapping = [](const Vec3& a) {
    return Vec3{1.3 * a.x + 0.4 * a.y - 0.2 * a.z + 1.0, 0.1 * a.x + 0.8 * a.y + 0.3 * a.z,
                -0.3 * a.x + 0.2 * a.y + 1.1 * a.z - 2.0};
  };
  SideBoundaries sides = testing::allWalls();
  sides[1].kind = BoundaryKind::Free;  // free and wall nodes alike
  const Mesh mesh = buildBlockMesh(block, sides);
  RelaxationControls controls;
  controls.max_move = 1.0;
  const std::vector<Vec3> x = positionsOf(mesh), target = targetsOf(mesh, controls, mesh.x_n);
  for (Index n = 0; n < mesh.n_nodes; ++n) {
    EXPECT_LT(norm(target[n] - x[n]), 1e-14) << n;
  }
}

TEST(Winslow, ARoughMeshIsSmoothedAndNoNodeMovesMoreThanItsLimit) {
  // interior nodes displaced at random from a uniform block: the relaxed
  // positions are nearer the uniform ones, each move within the limit
  const BlockSpec uniform = testing::perturbedBlock(8, 8, 8, {0, 0, 0}, {1, 1, 1}, 0.0);
  const BlockSpec rough = testing::perturbedBlock(8, 8, 8, {0, 0, 0}, {1, 1, 1}, 0.25);
  const Mesh mesh = buildBlockMesh(rough, testing::allWalls());
  const std::vector<Vec3> x_uniform = positionsOf(buildBlockMesh(uniform, testing::allWalls()));
  const std::vector<Vec3> x = positionsOf(mesh);
  RelaxationControls controls;
  controls.max_move = 1.0;
  const std::vector<Vec3> relaxed = targetsOf(mesh, controls, mesh.x_n);
  double before = 0.0, after = 0.0;
  for (Index n = 0; n < mesh.n_nodes; ++n) {
    before += norm(x[n] - x_uniform[n]);
    after += norm(relaxed[n] - x_uniform[n]);
  }
  EXPECT_LT(after, 0.6 * before);
  controls.max_move = 0.05;
  const std::vector<Vec3> limited = targetsOf(mesh, controls, mesh.x_n);
  const double h = 1.0 / 8.0, shortest = (1.0 - 2.0 * 0.25) * h;  // perturbation bound
  int moved = 0;
  for (Index n = 0; n < mesh.n_nodes; ++n) {
    const double move = norm(limited[n] - x[n]);
    EXPECT_LE(move, 0.05 * 1.5 * h * (1.0 + 1e-12)) << n;
    if (move > 0.05 * 0.5 * shortest) ++moved;
  }
  EXPECT_GT(moved, mesh.n_nodes / 4);
}

TEST(Winslow, WallNodesSlideInTheirPlanesAndFreeSurfaceNodesStay) {
  // a graded block: its boundary nodes want to move towards even spacing;
  // the x-, y- and z- sides are symmetry planes, z+ is free
  BlockSpec block = testing::perturbedBlock(6, 6, 6, {0, 0, 0}, {1, 1, 1}, 0.0);
  block.mapping = [](const Vec3& a) {
    return Vec3{a.x * (1.0 + a.x), a.y * (1.0 + a.y), a.z * (1.0 + 0.5 * a.z)};
  };
  SideBoundaries sides = testing::allWalls();
  sides[5].kind = BoundaryKind::Free;
  const Mesh mesh = buildBlockMesh(block, sides);
  RelaxationControls controls;
  controls.max_move = 1.0;
  const std::vector<Vec3> x = positionsOf(mesh), target = targetsOf(mesh, controls, mesh.x_n);
  int slid = 0;
  for (Index n = 0; n < mesh.n_nodes; ++n) {
    if (x[n].z == 1.5) {  // free side: not moved at all
      EXPECT_EQ(target[n].x, x[n].x) << n;
      EXPECT_EQ(target[n].y, x[n].y) << n;
      EXPECT_EQ(target[n].z, x[n].z) << n;
      continue;
    }
    // on a plane x = 0, y = 0 or z = 0: still on it, to round-off of the
    // projection (as the nodal solve's own velocities)
    const double plane = 1e-15;
    if (x[n].x == 0.0) {
      EXPECT_LE(std::abs(target[n].x), plane) << n;
    }
    if (x[n].y == 0.0) {
      EXPECT_LE(std::abs(target[n].y), plane) << n;
    }
    if (x[n].z == 0.0) {
      EXPECT_LE(std::abs(target[n].z), plane) << n;
    }
    if ((x[n].x == 0.0 || x[n].y == 0.0) && norm(target[n] - x[n]) > 1e-4) ++slid;
  }
  EXPECT_GT(slid, 10);  // (they did move, within their planes)
}

TEST(Winslow, TheQualityGuardKeepsEveryCellAboveItsBound) {
  // a uniform Lagrangian mesh relaxed towards a rough "initial" one, whose
  // cells fall below the floor: every cell ends at least as good as
  // min(its Lagrangian quality, floor)
  const Mesh mesh = buildBlockMesh(testing::perturbedBlock(10, 10, 10, {0, 0, 0}, {1, 1, 1}, 0.0),
                                   testing::allWalls());
  const Mesh rough = buildBlockMesh(testing::perturbedBlock(10, 10, 10, {0, 0, 0}, {1, 1, 1}, 0.2),
                                    testing::allWalls());
  RelaxationControls controls;
  controls.rule = RelaxationRule::Initial;
  controls.max_move = 1.0;
  controls.quality_floor = 0.75;
  Vec3View x_target("x_target", mesh.n_nodes);
  DeviceView<int*> worsened("worsened", mesh.n_cells);
  relaxedTargets(mesh, nodeStencils(mesh), mesh.x_n, rough.x_n, nodeFreedom(mesh), controls,
                 x_target);
  int passes = 0;
  long marked = 0, first = -1;
  RealView quality("quality", mesh.n_cells);
  for (;;) {
    targetCellQualities(mesh, x_target, controls.quality_floor, quality);
    marked = markWorsenedCells(mesh, mesh.x_n, quality, controls.quality_floor, worsened);
    if (marked == 0) break;
    if (first < 0) first = marked;
    holdNodesOfWorsenedCells(mesh, mesh.x_n, worsened, x_target);
    ASSERT_LT(++passes, 50);
  }
  EXPECT_GT(first, 0);  // the guard had work to do
  const auto x_l = Kokkos::create_mirror_view_and_copy(HostSpace(), mesh.x_n);
  const auto x_t = Kokkos::create_mirror_view_and_copy(HostSpace(), x_target);
  const auto cell_nodes = Kokkos::create_mirror_view_and_copy(HostSpace(), mesh.cell_nodes);
  int relaxed_cells = 0;
  for (Index c = 0; c < mesh.n_cells; ++c) {
    Vec3 a[8], b[8];
    for (int p = 0; p < 8; ++p) {
      a[p] = loadVec3(x_l, cell_nodes(c, p));
      b[p] = loadVec3(x_t, cell_nodes(c, p));
    }
    const double bound = std::min(cellScaledJacobian(a), controls.quality_floor);
    EXPECT_GE(cellScaledJacobian(b), bound) << c;
    if (cellScaledJacobian(b) < cellScaledJacobian(a)) ++relaxed_cells;
  }
  EXPECT_GT(relaxed_cells, 0);  // (and it did not just hold every node)
}

TEST(AleMode, ATargetAtTheInitialMeshIsRemapModeBitForBit) {
  // advection starts from the remap set-up in both modes: a solid moving
  // through the gas, mixed cells, stresses and plastic strain remapped
  const std::vector<std::string> keys = {"t_end=2e-4"};
  const RunResult remap = runProblem(testing::problemOptions("advection", keys, 0.5, "remap"));
  std::vector<std::string> ale_keys = keys;
  ale_keys.insert(ale_keys.end(), {"ale.rule=initial", "ale.weight=1", "ale.max_move=1",
                                   "remap.parcel_fractions=free"});
  const RunResult ale = runProblem(testing::problemOptions("advection", ale_keys, 0.5, "ale"));
  ASSERT_FALSE(remap.failed) << remap.failure;
  ASSERT_FALSE(ale.failed) << ale.failure;
  EXPECT_EQ(ale.steps, remap.steps);
  EXPECT_EQ(testing::maxRelativeDifference(ale.fields, remap.fields), 0.0);
}

TEST(AleMode, NoRelaxationIsLagrangeModeBitForBit) {
  const std::vector<std::string> keys = {"t_end=2e-4"};
  const RunResult lagrange = runProblem(testing::problemOptions("taylor", keys, 0.25, "lagrange"));
  std::vector<std::string> ale_keys = keys;
  ale_keys.push_back("ale.weight=0");
  const RunResult ale = runProblem(testing::problemOptions("taylor", ale_keys, 0.25, "ale"));
  ASSERT_FALSE(ale.failed) << ale.failure;
  EXPECT_EQ(ale.steps, lagrange.steps);
  EXPECT_EQ(testing::maxRelativeDifference(ale.fields, lagrange.fields), 0.0);
}

TEST(AleMode, BoundedParcelFractionsKeepTheBallsTraceCellsPositive) {
  // the ball from its remap mesh: the relaxation moves faces into near-vacuum
  // cells holding an aluminium trace; a parcel whose lever reaches the far
  // side of the ball's cell would carry a negative volume of aluminium
  // (free: the trace cell's gas mass goes negative within three steps)
  const std::vector<std::string> keys = {"t_end=3e-9"};
  std::vector<std::string> free_keys = keys;
  free_keys.push_back("remap.parcel_fractions=free");
  const RunResult free = runProblem(testing::problemOptions("ball", free_keys, 1.0, "ale"));
  EXPECT_TRUE(free.failed);
  const RunResult bounded = runProblem(testing::problemOptions("ball", keys, 1.0, "ale"));
  ASSERT_FALSE(bounded.failed) << bounded.failure;
  EXPECT_LT(bounded.drift_mass, 1e-12);  // (round-off: the near-vacuum gas beside GPa solids)
  EXPECT_LT(bounded.drift_energy, 1e-12);
}

TEST(AleMode, ConservesMassMomentumAndEnergyAndMovesTheMesh) {
  // taylor from its lagrange mesh, relaxed every second step
  const RunResult lagrange =
      runProblem(testing::problemOptions("taylor", {"t_end=5e-4"}, 0.25, "lagrange"));
  const RunResult ale =
      runProblem(testing::problemOptions("taylor", {"t_end=5e-4", "ale.every=2"}, 0.25, "ale"));
  ASSERT_FALSE(ale.failed) << ale.failure;
  EXPECT_LT(ale.drift_mass, 1e-13);
  EXPECT_LT(ale.drift_momentum, 1e-12);
  EXPECT_LT(ale.drift_energy, 1e-12);
  // the relaxed mesh is another mesh than the material's
  double moved = 0.0;
  for (std::size_t i = 0; i < ale.fields.mesh.x_n.size(); ++i) {
    moved = std::max(moved,
                     std::abs(ale.fields.mesh.x_n.data()[i] - lagrange.fields.mesh.x_n.data()[i]));
  }
  EXPECT_GT(moved, 1e-3);
}

}  // namespace
}  // namespace lagremap
