// Swept-face geometry of the remap (docs/method.md §A9): the swept regions of a cell
// telescope to the change of its volume and first moment on a distorted mesh,
// both sides of a face hold the same numbers, their total is conserved, and
// single regions are exact on known shapes and against a high-order quadrature.
#include <gtest/gtest.h>

#include <cstring>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include "kernels/swept_face.hpp"
#include "test_support.hpp"

namespace lagremap {
namespace {

using swept::SweptRegion;

Vec3 randomVec3(std::mt19937& rng, double amplitude) {
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  return amplitude * Vec3{unit(rng), unit(rng), unit(rng)};
}

// A perturbed block as the remap target (initial mesh) and a Lagrangian mesh
// made from it by a smooth swirl plus random node jitter. A node on a box side
// keeps its coordinate normal to that side (it slides in the plane, as on a
// wall), unless the boundary is free.
struct SweptMeshCase {
  BlockSpec block;
  Mesh mesh;
  Vec3View x_lag;
  SweptFaces swept;
};

SweptMeshCase distortedCase(bool free_boundary, unsigned seed) {
  SweptMeshCase sc;
  sc.block = testing::perturbedBlock(6, 5, 4, {-1.0, 0.5, 2.0}, {1.4, 2.5, 3.6}, 0.15);
  BlockSpec& block = sc.block;
  block.seed = seed;
  sc.mesh = buildBlockMesh(block, testing::allWalls());

  const HostMesh host = copyToHost(sc.mesh);
  // A separate host View: on a host backend the mirror of x_n is x_n itself.
  Vec3View::HostMirror x_lag("lagremap::test::x_lag_host", sc.mesh.n_nodes);
  const double h[3] = {(block.hi.x - block.lo.x) / block.nx, (block.hi.y - block.lo.y) / block.ny,
                       (block.hi.z - block.lo.z) / block.nz};
  const int n_axis[3] = {block.nx, block.ny, block.nz};
  std::mt19937 rng(seed + 1);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  for (Index n = 0; n < sc.mesh.n_nodes; ++n) {
    const int ijk[3] = {n % (block.nx + 1), (n / (block.nx + 1)) % (block.ny + 1),
                        n / ((block.nx + 1) * (block.ny + 1))};
    const Vec3 x = loadVec3(host.x_n, n);
    const double swirl[3] = {0.25 * h[0] * std::sin(2.0 * x.y + x.z),
                             0.25 * h[1] * std::cos(1.5 * x.x - x.z),
                             0.25 * h[2] * std::sin(x.x + 2.5 * x.y)};
    double displaced[3] = {x.x, x.y, x.z};
    for (int axis = 0; axis < 3; ++axis) {
      const bool on_side = ijk[axis] == 0 || ijk[axis] == n_axis[axis];
      if (on_side && !free_boundary) continue;
      displaced[axis] += swirl[axis] + 0.1 * h[axis] * unit(rng);
    }
    storeVec3(x_lag, n, Vec3{displaced[0], displaced[1], displaced[2]});
  }
  sc.x_lag = Vec3View("lagremap::test::x_lag", sc.mesh.n_nodes);
  Kokkos::deep_copy(sc.x_lag, x_lag);
  sc.swept = allocateSweptFaces(sc.mesh);
  computeSweptFaces(sc.mesh, sc.x_lag, sc.mesh.x_n, sc.swept);
  return sc;
}

template <class NodeView, class CellNodeView>
void cellNodes(const NodeView& x_n, const CellNodeView& cell_nodes, Index c, Vec3 x[8]) {
  for (int p = 0; p < 8; ++p) x[p] = loadVec3(x_n, cell_nodes(c, p));
}

// docs/method.md §A9: V_new = V_lag + sum_t dV_t and (V x_c)_new = (V x_c)_lag + sum_t M_t
// for every cell, with the face points of both meshes and non-planar faces
// everywhere; boundary faces included (sliding or free).
// computeSweptFaces skips a boundary face that stays in one axis plane (a wall
// or symmetry plane the nodes slide in): it must be recognised, and the full
// computation must give exactly 0 for it (so the skip changes no bit); one
// node off the plane, or a plane not normal to an axis, is not skipped.
TEST(SweptFace, FaceSlidingInAnAxisPlaneSweepsExactlyNothing) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  for (int axis = 0; axis < 3; ++axis) {
    for (int trial = 0; trial < 50; ++trial) {
      const double plane = 10.0 * unit(rng);
      auto on_plane = [&](double amplitude) {
        Vec3 x = randomVec3(rng, amplitude);
        (axis == 0 ? x.x : axis == 1 ? x.y : x.z) = plane;
        return x;
      };
      Vec3 q_lag[4], q_target[4];
      for (int k = 0; k < 4; ++k) {
        q_target[k] = on_plane(1.0);
        q_lag[k] = q_target[k] + on_plane(0.3);  // in-plane displacement
        (axis == 0 ? q_lag[k].x : axis == 1 ? q_lag[k].y : q_lag[k].z) = plane;
      }
      ASSERT_TRUE(swept::staysInOneAxisPlane(q_lag, q_target));
      SweptRegion regions[4];
      swept::sweptFace(q_lag, q_target, regions);
      for (int k = 0; k < 4; ++k) EXPECT_EQ(regions[k].volume, 0.0) << axis << " " << trial;
      Vec3 off = q_lag[2];
      (axis == 0 ? off.x : axis == 1 ? off.y : off.z) += 1e-12;
      Vec3 q_off[4] = {q_lag[0], q_lag[1], off, q_lag[3]};
      EXPECT_FALSE(swept::staysInOneAxisPlane(q_off, q_target));
    }
  }
  // A plane x + y = 1 (not normal to an axis) is left to the full computation.
  const Vec3 q[4] = {{1, 0, 0}, {0, 1, 0}, {0, 1, 1}, {1, 0, 1}};
  EXPECT_FALSE(swept::staysInOneAxisPlane(q, q));
}

TEST(SweptFace, CellRegionsTelescopeToTheVolumeAndMomentChange) {
  for (const bool free_boundary : {false, true}) {
    const SweptMeshCase sc = distortedCase(free_boundary, 314u);
    const HostMesh target = copyToHost(sc.mesh);
    const auto x_lag = Kokkos::create_mirror_view_and_copy(HostSpace(), sc.x_lag);
    const auto dvol = Kokkos::create_mirror_view_and_copy(HostSpace(), sc.swept.dvol_r);
    const auto moment = Kokkos::create_mirror_view_and_copy(HostSpace(), sc.swept.moment_r);
    const double h = (sc.block.hi.x - sc.block.lo.x) / sc.block.nx;
    double max_volume_error = 0.0, max_moment_error = 0.0, max_change = 0.0;
    for (Index c = 0; c < sc.mesh.n_cells; ++c) {
      Vec3 x[8];
      cellNodes(target.x_n, target.cell_nodes, c, x);
      const hex::CellShape shape_target = hex::cellShape(x);
      cellNodes(x_lag, target.cell_nodes, c, x);
      const hex::CellShape shape_lag = hex::cellShape(x);
      ASSERT_GT(shape_lag.volume, 0.0) << "inverted Lagrangian cell " << c;
      double dvol_sum = 0.0;
      Vec3 moment_sum{0.0, 0.0, 0.0};
      for (int r = 0; r < kSweptRegionsPerCell; ++r) {
        dvol_sum += dvol(kSweptRegionsPerCell * c + r);
        moment_sum += loadVec3(moment, kSweptRegionsPerCell * c + r);
      }
      const double volume_error =
          std::abs(shape_target.volume - (shape_lag.volume + dvol_sum)) / shape_target.volume;
      const Vec3 moment_target = shape_target.volume * shape_target.centroid;
      const Vec3 moment_lag = shape_lag.volume * shape_lag.centroid;
      // Scale V (|x_c| + h): cells near the origin are not held to an absolute zero.
      const double moment_scale = shape_target.volume * (norm(shape_target.centroid) + h);
      const double moment_error = norm(moment_target - (moment_lag + moment_sum)) / moment_scale;
      EXPECT_LT(volume_error, 1e-14) << "cell " << c;
      EXPECT_LT(moment_error, 1e-14) << "cell " << c;
      max_volume_error = std::max(max_volume_error, volume_error);
      max_moment_error = std::max(max_moment_error, moment_error);
      max_change = std::max(max_change, std::abs(dvol_sum) / shape_target.volume);
    }
    // The mesh really moved: the identity is not 0 = 0.
    EXPECT_GT(max_change, 0.05);
    std::printf(
        "swept faces (%s boundary): max relative volume error %.2e, moment error %.2e "
        "(largest relative volume change %.2f)\n",
        free_boundary ? "free" : "sliding", max_volume_error, max_moment_error, max_change);
  }
}

// The gained and given regions of a face are the sums of its triangles by the
// sign of their swept volume (docs/method.md §A9's upwind choice), a tie (dV_t = 0) on
// the side of the lower cell id: recomputed here on the host from the face's
// nodes, triangle by triangle, with the same additions in the same order.
TEST(SweptFace, FaceSidesSumTheTrianglesByUpwindCell) {
  const SweptMeshCase sc = distortedCase(true, 99u);
  const HostMesh target = copyToHost(sc.mesh);
  const auto x_lag = Kokkos::create_mirror_view_and_copy(HostSpace(), sc.x_lag);
  const auto dvol = Kokkos::create_mirror_view_and_copy(HostSpace(), sc.swept.dvol_r);
  const auto moment = Kokkos::create_mirror_view_and_copy(HostSpace(), sc.swept.moment_r);
  const auto neighbors = Kokkos::create_mirror_view_and_copy(HostSpace(), sc.mesh.cell_neighbors);
  int mixed_faces = 0;
  for (Index c = 0; c < sc.mesh.n_cells; ++c) {
    Vec3 x_cell_lag[8], x_cell_target[8];
    cellNodes(x_lag, target.cell_nodes, c, x_cell_lag);
    cellNodes(target.x_n, target.cell_nodes, c, x_cell_target);
    for (int f = 0; f < 6; ++f) {
      const Index n = neighbors(c, f);
      if (n >= 0 && n < c) continue;  // checked from its owner (and by the next test)
      Vec3 q_lag[4], q_target[4];
      hex::faceNodes(x_cell_lag, f, q_lag);
      hex::faceNodes(x_cell_target, f, q_target);
      SweptRegion triangles[4];
      swept::sweptFace(q_lag, q_target, triangles);
      double gained = 0.0, given = 0.0;
      Vec3 gained_moment{0.0, 0.0, 0.0}, given_moment{0.0, 0.0, 0.0};
      int positive = 0;
      for (const SweptRegion& t : triangles) {
        const bool from_neighbor = t.volume > 0.0;  // a tie goes to c, the lower id
        positive += from_neighbor;
        (from_neighbor ? gained : given) += t.volume;
        (from_neighbor ? gained_moment : given_moment) += t.moment;
      }
      mixed_faces += positive > 0 && positive < 4;
      const Index r_gained = sweptRegionId(c, f, kGainedSide);
      const Index r_given = sweptRegionId(c, f, kGivenSide);
      EXPECT_EQ(dvol(r_gained), gained) << "cell " << c << " face " << f;
      EXPECT_EQ(dvol(r_given), given) << "cell " << c << " face " << f;
      EXPECT_GE(dvol(r_gained), 0.0);
      EXPECT_LE(dvol(r_given), 0.0);
      for (int d = 0; d < 3; ++d) {
        EXPECT_EQ(moment(r_gained, d), (d == 0   ? gained_moment.x
                                        : d == 1 ? gained_moment.y
                                                 : gained_moment.z));
        EXPECT_EQ(moment(r_given, d), (d == 0   ? given_moment.x
                                       : d == 1 ? given_moment.y
                                                : given_moment.z));
      }
    }
  }
  // the swirl twists faces: some have triangles on both sides
  EXPECT_GT(mixed_faces, 10);
}

// A side face of a z prism (a one-cell slab's, Mesh::z_prisms) moving in
// the xy plane: the closed form of sweptPrismSide gives the 4 regions of the
// general tensor rule to round-off, triangle by triangle (matched by volume,
// then by height), on random faces that stretch, turn and twist (some
// triangles gained, some given), thin and thick, far from the origin.
TEST(SweptFace, PrismSideFacesSweepTheGeneralRegions) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  int mixed = 0;
  for (int trial = 0; trial < 400; ++trial) {
    const double height = trial % 2 ? 0.01 : 1.0 + 0.5 * unit(rng);
    const Vec3 offset{40.0 + unit(rng), -7.0 + unit(rng), 3.0 + unit(rng)};
    const double amplitude = trial % 3 == 0 ? 0.6 : 0.15;
    Vec3 lag[8], target[8];
    const double square[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    for (int p = 0; p < 4; ++p) {
      target[p] = offset + Vec3{square[p][0] + 0.1 * unit(rng), square[p][1] + 0.1 * unit(rng), 0};
      lag[p] = target[p] + Vec3{amplitude * unit(rng), amplitude * unit(rng), 0};
      target[p + 4] = target[p] + Vec3{0, 0, height};
      lag[p + 4] = lag[p] + Vec3{0, 0, height};
    }
    for (int f = 0; f < 4; ++f) {
      Vec3 q_lag[4], q_target[4];
      hex::faceNodes(lag, f, q_lag);
      hex::faceNodes(target, f, q_target);
      SweptRegion general[4], prism[4];
      swept::sweptFace(q_lag, q_target, general);
      const int k = swept::prismSideEdge(f), next = (k + 1) & 3;
      swept::sweptPrismSide(lag[k], lag[next], target[k], target[next], height, prism);
      const auto byVolumeThenHeight = [](const SweptRegion& a, const SweptRegion& b) {
        const double scale = 1e-9 * (std::fabs(a.volume) + std::fabs(b.volume));
        if (std::fabs(a.volume - b.volume) > scale) return a.volume < b.volume;
        return a.moment.z < b.moment.z;
      };
      std::sort(general, general + 4, byVolumeThenHeight);
      std::sort(prism, prism + 4, byVolumeThenHeight);
      int positive = 0;
      for (const SweptRegion& t : general) positive += t.volume > 0.0;
      mixed += positive > 0 && positive < 4;
      // round-off scale: a region of a twisting face is the difference of
      // terms of the size of the face (~1) times its height and displacement
      const double size = height * amplitude;
      for (int t = 0; t < 4; ++t) {
        EXPECT_NEAR(prism[t].volume, general[t].volume, 1e-13 * size) << "face " << f;
        EXPECT_LT(norm(prism[t].moment - general[t].moment), 1e-13 * size * norm(offset))
            << "face " << f << " triangle " << t;
      }
    }
  }
  EXPECT_GT(mixed, 20);  // twisting faces, regions on both sides
}

// A whole slab of prisms, one cell thick between z symmetry planes, whose
// nodes move in the xy plane: computeSweptFaces with the prism forms gives
// every region of the general tensor rule to round-off.
TEST(SweptFace, SlabOfPrismsSweepsTheGeneralRegions) {
  const BlockSpec block = testing::perturbedBlock(7, 6, 1, {-1.0, 0.5, 2.0}, {1.4, 2.5, 2.1}, 0.2);
  Mesh mesh = buildBlockMesh(block, testing::allWalls());
  ASSERT_TRUE(mesh.z_prisms);
  const HostMesh host = copyToHost(mesh);
  Vec3View::HostMirror x_lag("lagremap::test::x_lag_host", mesh.n_nodes);
  const double h = 2.4 / 7;
  for (Index n = 0; n < mesh.n_nodes; ++n) {  // a swirl in the plane; walls keep theirs
    const Vec3 x = loadVec3(host.x_n, n);
    const int i = n % (block.nx + 1), j = (n / (block.nx + 1)) % (block.ny + 1);
    const bool x_wall = i == 0 || i == block.nx, y_wall = j == 0 || j == block.ny;
    storeVec3(x_lag, n,
              Vec3{x.x + (x_wall ? 0.0 : 0.3 * h * std::sin(3.0 * x.y)),
                   x.y + (y_wall ? 0.0 : 0.3 * h * std::cos(2.0 * x.x)), x.z});
  }
  Vec3View x_lag_device("lagremap::test::x_lag", mesh.n_nodes);
  Kokkos::deep_copy(x_lag_device, x_lag);
  const auto regions = [&](bool prisms) {
    mesh.z_prisms = prisms;
    const SweptFaces swept = allocateSweptFaces(mesh);
    computeSweptFaces(mesh, x_lag_device, mesh.x_n, swept);
    return std::make_pair(Kokkos::create_mirror_view_and_copy(HostSpace(), swept.dvol_r),
                          Kokkos::create_mirror_view_and_copy(HostSpace(), swept.moment_r));
  };
  const auto [dvol, moment] = regions(true);
  const auto [dvol_general, moment_general] = regions(false);
  double largest = 0.0;
  for (std::size_t r = 0; r < dvol.extent(0); ++r) {
    largest = std::max(largest, std::fabs(dvol_general(r)));
  }
  ASSERT_GT(largest, 1e-4);         // it swept
  const double size = 0.1 * h * h;  // height x displacement x edge
  for (std::size_t r = 0; r < dvol.extent(0); ++r) {
    EXPECT_NEAR(dvol(r), dvol_general(r), 1e-13 * size) << "region " << r;
    EXPECT_LT(norm(loadVec3(moment, r) - loadVec3(moment_general, r)), 1e-12 * size)
        << "region " << r;
  }
}

// The staged form (KernelForm: each face's nodes loaded by itself, one
// triangle at a time) gives the fused form's regions bit for bit, on twisted
// hexahedra (free and wall boundaries) and on a slab of prisms.
TEST(SweptFace, StagedFormSweepsTheFusedBits) {
  const auto bits = [](const Mesh& mesh, const Vec3View& x_lag, KernelForm form) {
    const SweptFaces swept = allocateSweptFaces(mesh);
    computeSweptFaces(mesh, x_lag, mesh.x_n, swept, form);
    return std::make_pair(Kokkos::create_mirror_view_and_copy(HostSpace(), swept.dvol_r),
                          Kokkos::create_mirror_view_and_copy(HostSpace(), swept.moment_r));
  };
  const auto same = [](const auto& a, const auto& b) {
    return a.span() == b.span() && std::memcmp(a.data(), b.data(), a.span() * sizeof(double)) == 0;
  };
  for (const bool free_boundary : {false, true}) {
    const SweptMeshCase sc = distortedCase(free_boundary, 31u);
    const auto staged = bits(sc.mesh, sc.x_lag, KernelForm::Staged);
    if (!kFusedKernelsBuilt) continue;
    const auto fused = bits(sc.mesh, sc.x_lag, KernelForm::Fused);
    EXPECT_TRUE(same(staged.first, fused.first)) << "free " << free_boundary;
    EXPECT_TRUE(same(staged.second, fused.second)) << "free " << free_boundary;
  }
  const BlockSpec block = testing::perturbedBlock(5, 4, 1, {-1.0, 0.5, 2.0}, {1.4, 2.5, 2.1}, 0.2);
  const Mesh mesh = buildBlockMesh(block, testing::allWalls());
  ASSERT_TRUE(mesh.z_prisms);
  // (a View of its own: on a host backend the mirror of x_n is x_n itself)
  Vec3View::HostMirror x_lag("lagremap::test::x_lag_host", mesh.n_nodes);
  Kokkos::deep_copy(x_lag, Kokkos::create_mirror_view_and_copy(HostSpace(), mesh.x_n));
  for (Index n = 0; n < mesh.n_nodes; ++n) {  // interior nodes moved in the plane
    const int i = n % (block.nx + 1), j = (n / (block.nx + 1)) % (block.ny + 1);
    if (i == 0 || i == block.nx || j == 0 || j == block.ny) continue;
    x_lag(n, 0) += 0.05 * std::sin(3.0 * x_lag(n, 1));
    x_lag(n, 1) += 0.05 * std::cos(2.0 * x_lag(n, 0));
  }
  Vec3View x_lag_device("lagremap::test::x_lag", mesh.n_nodes);
  Kokkos::deep_copy(x_lag_device, x_lag);
  const auto staged = bits(mesh, x_lag_device, KernelForm::Staged);
  double largest = 0.0;
  for (std::size_t r = 0; r < staged.first.extent(0); ++r) {
    largest = std::max(largest, std::fabs(staged.first(r)));
  }
  EXPECT_GT(largest, 1e-4);  // it swept
  if (kFusedKernelsBuilt) {
    const auto fused = bits(mesh, x_lag_device, KernelForm::Fused);
    EXPECT_TRUE(same(staged.first, fused.first));
    EXPECT_TRUE(same(staged.second, fused.second));
  }
}

// The owner's 2 regions of an interior face are stored negated, bit for bit,
// in the neighbour's slots of the same face, gained and given exchanged; the
// neighbour's face is found here from the node ids, independently of the
// kernel's index arithmetic.
TEST(SweptFace, BothSidesOfAFaceHoldTheSameBitsUpToSign) {
  const SweptMeshCase sc = distortedCase(false, 27u);
  const auto cell_nodes = Kokkos::create_mirror_view_and_copy(HostSpace(), sc.mesh.cell_nodes);
  const auto neighbors = Kokkos::create_mirror_view_and_copy(HostSpace(), sc.mesh.cell_neighbors);
  const auto dvol = Kokkos::create_mirror_view_and_copy(HostSpace(), sc.swept.dvol_r);
  const auto moment = Kokkos::create_mirror_view_and_copy(HostSpace(), sc.swept.moment_r);
  auto face_key = [&](Index c, int f) {
    std::vector<Index> nodes;
    for (int k = 0; k < 4; ++k) nodes.push_back(cell_nodes(c, hex::faceNode(f, k)));
    std::sort(nodes.begin(), nodes.end());
    return nodes;
  };
  int matched = 0;
  for (Index c = 0; c < sc.mesh.n_cells; ++c)
    for (int f = 0; f < 6; ++f) {
      const Index n = neighbors(c, f);
      if (n < 0) continue;
      int found = 0;
      for (int g = 0; g < 6; ++g) {
        if (face_key(n, g) != face_key(c, f)) continue;
        ++found;
        for (int side = 0; side < 2; ++side) {
          const Index mine = sweptRegionId(c, f, side), theirs = sweptRegionId(n, g, 1 - side);
          EXPECT_EQ(dvol(theirs), -dvol(mine));
          for (int d = 0; d < 3; ++d) EXPECT_EQ(moment(theirs, d), -moment(mine, d));
        }
        EXPECT_NE(dvol(sweptRegionId(c, f, 0)) - dvol(sweptRegionId(c, f, 1)), 0.0);
      }
      EXPECT_EQ(found, 1) << "cell " << c << " face " << f;
      matched += found;
    }
  const int interior_faces = 5 * 5 * 4 + 6 * 4 * 4 + 6 * 5 * 3;
  EXPECT_EQ(matched, 2 * interior_faces);
}

// Interior faces cancel pairwise and faces sliding in the box sides sweep
// nothing, so the regions of all cells sum to zero; with a free boundary they
// sum to the change of the total volume.
TEST(SweptFace, SweptVolumesAndMomentsSumToTheTotalChange) {
  for (const bool free_boundary : {false, true}) {
    const SweptMeshCase sc = distortedCase(free_boundary, 4242u);
    const HostMesh target = copyToHost(sc.mesh);
    const auto x_lag = Kokkos::create_mirror_view_and_copy(HostSpace(), sc.x_lag);
    const auto dvol = Kokkos::create_mirror_view_and_copy(HostSpace(), sc.swept.dvol_r);
    const auto moment = Kokkos::create_mirror_view_and_copy(HostSpace(), sc.swept.moment_r);
    double dvol_total = 0.0, volume_target = 0.0, volume_lag = 0.0;
    Vec3 moment_total{0, 0, 0}, moment_target{0, 0, 0}, moment_lag{0, 0, 0};
    for (Index t = 0; t < Index(dvol.extent(0)); ++t) {
      dvol_total += dvol(t);
      moment_total += loadVec3(moment, t);
    }
    for (Index c = 0; c < sc.mesh.n_cells; ++c) {
      Vec3 x[8];
      cellNodes(target.x_n, target.cell_nodes, c, x);
      const hex::CellShape shape_target = hex::cellShape(x);
      cellNodes(x_lag, target.cell_nodes, c, x);
      const hex::CellShape shape_lag = hex::cellShape(x);
      volume_target += shape_target.volume;
      volume_lag += shape_lag.volume;
      moment_target += shape_target.volume * shape_target.centroid;
      moment_lag += shape_lag.volume * shape_lag.centroid;
    }
    const double box_volume = volume_target;
    if (!free_boundary) {
      EXPECT_LT(std::abs(dvol_total), 1e-15 * box_volume);
      EXPECT_LT(norm(moment_total), 1e-15 * norm(moment_target));
      EXPECT_NEAR(volume_lag, box_volume, 1e-13 * box_volume);
    } else {
      EXPECT_GT(std::abs(volume_target - volume_lag), 1e-4 * box_volume);
      EXPECT_NEAR(dvol_total, volume_target - volume_lag, 1e-14 * box_volume);
      EXPECT_LT(norm(moment_total - (moment_target - moment_lag)), 1e-14 * norm(moment_target));
    }
  }
}

// A unit square face translated by d sweeps the prism of base 1 and height
// d . n: dV = d . n, centroid = face centre + d / 2; each of its 4 triangles
// sweeps a quarter, with its own centroid + d / 2. Checked in a rotated frame,
// far from the origin, moving outward (the cell gains) and inward.
TEST(SweptFace, TranslatedSquareSweepsItsPrism) {
  const double cos_a = std::cos(0.7), sin_a = std::sin(0.7);
  const Mat3 about_z{{{cos_a, -sin_a, 0.0}, {sin_a, cos_a, 0.0}, {0.0, 0.0, 1.0}}};
  const Mat3 about_x{{{1.0, 0.0, 0.0}, {0.0, cos_a, -sin_a}, {0.0, sin_a, cos_a}}};
  const Mat3 rotation = about_z * about_x;
  const Vec3 offset{12.0, -7.0, 30.0};
  // Rounding the corners far from the origin perturbs the square by eps |offset|.
  const double scale = norm(offset);
  // Counter-clockwise seen from +z: outward normal +z in the square's frame.
  const Vec3 square[4] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  const Vec3 normal = rotation * Vec3{0, 0, 1};
  for (const Vec3 d_local : {Vec3{0.3, -0.2, 0.7}, Vec3{-0.1, 0.4, -0.25}}) {
    const Vec3 d = rotation * d_local;
    Vec3 q_lag[4], q_target[4];
    for (int k = 0; k < 4; ++k) {
      q_lag[k] = offset + rotation * square[k];
      q_target[k] = q_lag[k] + d;
    }
    SweptRegion swept[4];
    swept::sweptFace(q_lag, q_target, swept);
    const Vec3 centre = 0.25 * (q_lag[0] + q_lag[1] + q_lag[2] + q_lag[3]);
    double dvol_sum = 0.0;
    Vec3 moment_sum{0, 0, 0};
    for (int k = 0; k < 4; ++k) {
      const double quarter = 0.25 * dot(d, normal);
      EXPECT_NEAR(swept[k].volume, quarter, 1e-15 * scale);
      const Vec3 centroid = (1.0 / 3.0) * (q_lag[k] + q_lag[(k + 1) & 3] + centre) + 0.5 * d;
      EXPECT_LT(norm(swept[k].moment - quarter * centroid), 1e-14 * scale);
      dvol_sum += swept[k].volume;
      moment_sum += swept[k].moment;
    }
    EXPECT_NEAR(dvol_sum, d_local.z, 1e-15 * scale);
    EXPECT_LT(norm(moment_sum - d_local.z * (centre + 0.5 * d)), 1e-14 * scale);
  }

  // The sign seen from a cell: the x+ face of the unit cube moving out by 0.1
  // sweeps +0.1, the volume the cube gains.
  const Vec3 cube[8] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
                        {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
  Vec3 grown[8];
  for (int p = 0; p < 8; ++p) grown[p] = cube[p] + Vec3{cube[p].x > 0.5 ? 0.1 : 0.0, 0, 0};
  Vec3 q_lag[4], q_target[4];
  hex::faceNodes(cube, 1, q_lag);
  hex::faceNodes(grown, 1, q_target);
  SweptRegion swept[4];
  swept::sweptFace(q_lag, q_target, swept);
  const double gained = swept[0].volume + swept[1].volume + swept[2].volume + swept[3].volume;
  EXPECT_NEAR(gained, 0.1, 1e-15);
  EXPECT_NEAR(hex::cellShape(grown).volume, hex::cellShape(cube).volume + gained, 1e-15);
}

// A triangle with one moving vertex sweeps the tetrahedron (a, b, c, a'):
// volume 1/6 (a' - a) . (e1 x e2), centroid (a + b + c + a') / 4.
TEST(SweptFace, OneMovingVertexSweepsATetrahedron) {
  std::mt19937 rng(8);
  for (int trial = 0; trial < 100; ++trial) {
    const Vec3 origin = randomVec3(rng, 50.0);
    const Vec3 a = origin + randomVec3(rng, 1.0), b = origin + randomVec3(rng, 1.0),
               c = origin + randomVec3(rng, 1.0);
    const Vec3 a_target = a + randomVec3(rng, 0.5);
    const SweptRegion swept = swept::sweptTriangle(a, b, c, a_target, b, c);
    const double volume = dot(a_target - a, cross(b - a, c - a)) / 6.0;
    EXPECT_NEAR(swept.volume, volume, 1e-15);
    const Vec3 centroid = 0.25 * (a + b + c + a_target);
    EXPECT_LT(norm(swept.moment - volume * centroid), 1e-13 * norm(origin));
  }
}

// A triangle that moves, turns and deforms within its own (oblique) plane
// sweeps nothing: d(xi) lies in the plane, J(tau) is normal to it.
TEST(SweptFace, MotionWithinItsPlaneSweepsNothing) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  for (int trial = 0; trial < 100; ++trial) {
    const Vec3 origin = randomVec3(rng, 10.0);
    Vec3 u = randomVec3(rng, 1.0), v = randomVec3(rng, 1.0);
    auto in_plane = [&](double amplitude) {
      return origin + amplitude * (unit(rng) * u + unit(rng) * v);
    };
    const Vec3 a = in_plane(1.0), b = in_plane(1.0), c = in_plane(1.0);
    const Vec3 a_target = in_plane(2.0), b_target = in_plane(2.0), c_target = in_plane(2.0);
    const SweptRegion swept = swept::sweptTriangle(a, b, c, a_target, b_target, c_target);
    EXPECT_LT(std::abs(swept.volume), 1e-14);
    EXPECT_LT(norm(swept.moment), 1e-14 * norm(origin));
  }
}

// Gauss-Legendre nodes and weights on [0, 1] (Newton on P_n).
void gaussLegendre(int n, std::vector<double>& nodes, std::vector<double>& weights) {
  nodes.resize(n);
  weights.resize(n);
  for (int i = 0; i < n; ++i) {
    double x = std::cos(std::acos(-1.0) * (i + 0.75) / (n + 0.5));
    double derivative = 1.0;
    for (int iteration = 0; iteration < 100; ++iteration) {
      double p_prev = 1.0, p = x;
      for (int order = 2; order <= n; ++order) {
        const double p_next = ((2 * order - 1) * x * p - (order - 1) * p_prev) / order;
        p_prev = p;
        p = p_next;
      }
      derivative = n * (x * p - p_prev) / (x * x - 1.0);
      const double step = p / derivative;
      x -= step;
      if (std::abs(step) < 1e-16) break;
    }
    nodes[i] = 0.5 * (1.0 - x);
    weights[i] = 1.0 / ((1.0 - x * x) * derivative * derivative);
  }
}

// Brute force on strongly non-planar regions (large, shearing, twisting
// motions): the straight-path map x = (1 - tau) X(xi) + tau X'(xi) with its
// Jacobian determinant from the three partial derivatives, integrated with an
// 8^3-point Gauss rule over the square mapped onto the triangle (xi2 = (1 - u) v).
// Also: the tensor rule without x is the closed-form volume.
TEST(SweptFace, TensorRuleMatchesHighOrderQuadratureAndClosedForm) {
  std::vector<double> nodes, weights;
  gaussLegendre(8, nodes, weights);
  double weight_sum = 0.0;
  for (double w : weights) weight_sum += w;
  ASSERT_NEAR(weight_sum, 1.0, 1e-15);
  std::mt19937 rng(1234);
  double max_volume_gap = 0.0, max_moment_gap = 0.0, max_rule_gap = 0.0;
  for (int trial = 0; trial < 200; ++trial) {
    const Vec3 origin = randomVec3(rng, 5.0);
    const Vec3 a = origin + randomVec3(rng, 1.0), b = origin + randomVec3(rng, 1.0),
               c = origin + randomVec3(rng, 1.0);
    const Vec3 a_target = a + randomVec3(rng, 1.0), b_target = b + randomVec3(rng, 1.0),
               c_target = c + randomVec3(rng, 1.0);
    double volume = 0.0;
    Vec3 moment{0, 0, 0};
    for (int i = 0; i < 8; ++i)
      for (int j = 0; j < 8; ++j)
        for (int l = 0; l < 8; ++l) {
          const double xi1 = nodes[i], xi2 = (1.0 - nodes[i]) * nodes[j], tau = nodes[l];
          const Vec3 x_lag = a + xi1 * (b - a) + xi2 * (c - a);
          const Vec3 x_target =
              a_target + xi1 * (b_target - a_target) + xi2 * (c_target - a_target);
          const Vec3 x = (1.0 - tau) * x_lag + tau * x_target;
          const Vec3 dx_dxi1 = (1.0 - tau) * (b - a) + tau * (b_target - a_target);
          const Vec3 dx_dxi2 = (1.0 - tau) * (c - a) + tau * (c_target - a_target);
          const Vec3 dx_dtau = x_target - x_lag;
          const Mat3 jacobian{{{dx_dxi1.x, dx_dxi2.x, dx_dtau.x},
                               {dx_dxi1.y, dx_dxi2.y, dx_dtau.y},
                               {dx_dxi1.z, dx_dxi2.z, dx_dtau.z}}};
          const double w = weights[i] * weights[j] * weights[l] * (1.0 - nodes[i]) * det(jacobian);
          volume += w;
          moment += w * x;
        }
    const SweptRegion swept = swept::sweptTriangle(a, b, c, a_target, b_target, c_target);
    const double closed = swept::sweptVolume(a, b, c, a_target, b_target, c_target);
    // Edges and displacements are of order 1: volumes get an absolute tolerance,
    // moments one relative to the distance from the origin.
    const double volume_scale = 1.0, moment_scale = norm(origin) + 1.0;
    max_volume_gap = std::max(max_volume_gap, std::abs(swept.volume - volume) / volume_scale);
    max_moment_gap = std::max(max_moment_gap, norm(swept.moment - moment) / moment_scale);
    max_rule_gap = std::max(max_rule_gap, std::abs(closed - swept.volume) / volume_scale);
  }
  EXPECT_LT(max_volume_gap, 1e-14);
  EXPECT_LT(max_moment_gap, 1e-14);
  EXPECT_LT(max_rule_gap, 1e-15);
  std::printf("tensor rule vs 8^3 Gauss: volume %.2e, moment %.2e; rule vs closed volume %.2e\n",
              max_volume_gap, max_moment_gap, max_rule_gap);
}

}  // namespace
}  // namespace lagremap
