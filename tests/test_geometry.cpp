// Geometry of docs/method.md §A2: corner vectors are the exact derivative of the cell
// volume (GCL) on distorted hexes with non-planar faces, they sum to zero, and
// volume and centroid are exact on known shapes.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "kernels/corner_terms.hpp"
#include "kernels/geometry.hpp"
#include "test_support.hpp"

namespace lagremap {
namespace {

// A cell's nodes held in an array, as the staged functions read them
// (a functor: a host lambda cannot be called from their device code).
struct NodesOfArray {
  const Vec3* x;
  KOKKOS_INLINE_FUNCTION Vec3 operator()(int n) const { return x[n]; }
};

// ... as points of the sweep, and the corner-face vector of node k of face f
// from a sweep of face f alone.
struct PointsOfArray {
  const Vec3* x;
  KOKKOS_INLINE_FUNCTION hex::detail::Point<double> operator()(int n) const {
    return {x[n].x, x[n].y, x[n].z};
  }
};
struct FaceVectorsOfArray {
  const Vec3* x;
  KOKKOS_INLINE_FUNCTION hex::detail::Point<double> operator()(int f, int k) const {
    const PointsOfArray point{x};
    hex::detail::FaceSweep<double> face;
    hex::detail::sweepFace(point, point(0), f, face);
    return hex::detail::cornerFaceVector(face, k);
  }
};

// Unit cube in VTK order.
void unitCube(Vec3 x[8]) {
  const Vec3 cube[8] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
                        {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
  for (int p = 0; p < 8; ++p) x[p] = cube[p];
}

// Randomly distorted hex: every node moves by up to `amplitude`, so faces are
// non-planar; then a large offset checks round-off far from the origin.
void distortedHex(std::mt19937& rng, double amplitude, const Vec3& offset, Vec3 x[8]) {
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  unitCube(x);
  for (int p = 0; p < 8; ++p) {
    x[p] = offset + x[p] + amplitude * Vec3{unit(rng), unit(rng), unit(rng)};
  }
}

double volumeOf(const Vec3 x[8]) {
  return hex::cellShape(x).volume;
}

TEST(Geometry, CornerVectorsAreTheVolumeGradient) {
  std::mt19937 rng(2026);
  for (int trial = 0; trial < 50; ++trial) {
    Vec3 x[8];
    distortedHex(rng, 0.25, Vec3{trial * 0.1, -3.0, 7.0}, x);
    Vec3 corner[8];
    hex::cornerVectors(x, corner);
    // The volume is quadratic in any single node coordinate, so the central
    // difference is exact up to round-off.
    const double h = 1e-3;
    for (int p = 0; p < 8; ++p) {
      double* coords[3] = {&x[p].x, &x[p].y, &x[p].z};
      const double expected[3] = {corner[p].x, corner[p].y, corner[p].z};
      for (int d = 0; d < 3; ++d) {
        const double saved = *coords[d];
        *coords[d] = saved + h;
        const double v_plus = volumeOf(x);
        *coords[d] = saved - h;
        const double v_minus = volumeOf(x);
        *coords[d] = saved;
        EXPECT_NEAR((v_plus - v_minus) / (2 * h), expected[d], 1e-11)
            << "trial " << trial << " node " << p << " direction " << d;
      }
    }
  }
}

TEST(Geometry, CornerVectorsOfAClosedCellSumToZero) {
  std::mt19937 rng(7);
  for (int trial = 0; trial < 100; ++trial) {
    Vec3 x[8];
    distortedHex(rng, 0.3, Vec3{100.0, 0.0, -50.0}, x);
    Vec3 corner[8];
    hex::cornerVectors(x, corner);
    Vec3 sum{0, 0, 0};
    for (int p = 0; p < 8; ++p) sum += corner[p];
    EXPECT_LT(norm(sum), 1e-14);
    // Euler's theorem for the degree-3 volume: v = 1/3 sum_p (x_p - x_0) . A_p.
    double euler = 0.0;
    for (int p = 0; p < 8; ++p) euler += dot(x[p] - x[0], corner[p]) / 3.0;
    EXPECT_NEAR(euler, volumeOf(x), 1e-13);
  }
}

// The fused single-sweep geometry of the kernels agrees with the separate
// reference formulas (tetrahedra with cross products; corner sums per face).
TEST(Geometry, FusedCellGeometryMatchesTheReferenceFormulas) {
  std::mt19937 rng(99);
  for (int trial = 0; trial < 50; ++trial) {
    Vec3 x[8];
    distortedHex(rng, 0.3, Vec3{-20.0, 4.0, 1.0}, x);
    hex::CellGeometry geo;
    hex::cellGeometry(x, geo);
    const hex::CellShape shape = hex::cellShape(x);
    Vec3 corner[8];
    hex::cornerVectors(x, corner);
    EXPECT_NEAR(geo.shape.volume, shape.volume, 1e-14);
    EXPECT_LT(norm(geo.shape.centroid - shape.centroid), 1e-13);
    EXPECT_NEAR(geo.shape.max_face_area, shape.max_face_area, 1e-14);
    // the fused sweep works relative to node 0, the reference in absolute coordinates
    for (int p = 0; p < 8; ++p) EXPECT_LT(norm(geo.corner[p] - corner[p]), 1e-14);
    // impedance sums over each corner's 3 corner faces, from the per-face vectors
    SymMat3 normal_moment[8];
    double corner_face_area[8] = {};
    for (int p = 0; p < 8; ++p) normal_moment[p] = identitySym(0.0);
    for (int f = 0; f < 6; ++f) {
      Vec3 q[4], w[4];
      hex::faceNodes(x, f, q);
      const Vec3 face_area = hex::faceCornerVectors(q, w);
      // the one-cross-product area vector is the 4 triangles' sum
      EXPECT_LT(norm(hex::faceArea(q) - face_area), 1e-14 * norm(face_area));
      for (int k = 0; k < 4; ++k) {
        const int p = hex::faceNode(f, k);
        normal_moment[p] += outerSelf(w[k], 1.0 / norm(w[k]));
        corner_face_area[p] += norm(w[k]);
      }
    }
    for (int p = 0; p < 8; ++p) {
      EXPECT_NEAR(geo.corner_face_area[p], corner_face_area[p], 1e-14);
      const SymMat3 d = geo.normal_moment[p] - normal_moment[p];
      EXPECT_LT(std::sqrt(ddot(d, d)), 1e-14);
    }
    // The sweep without corner sums (the end of a step the remap follows)
    // gives the same volume, centroid and face area, bit for bit.
    hex::CellGeometry shape_only;
    hex::cellGeometry<false>(x, shape_only);
    EXPECT_EQ(shape_only.shape.volume, geo.shape.volume);
    EXPECT_EQ(shape_only.shape.centroid.x, geo.shape.centroid.x);
    EXPECT_EQ(shape_only.shape.centroid.y, geo.shape.centroid.y);
    EXPECT_EQ(shape_only.shape.centroid.z, geo.shape.centroid.z);
    EXPECT_EQ(shape_only.shape.max_face_area, geo.shape.max_face_area);
  }
}

// The sweep of hex::kCellLanes cells at once (the lanes of a vector on CPU
// builds) gives every cell the bits of its own sweep, a cell with a
// degenerate face (its bottom collapsed to a point: corner faces of no area,
// which add nothing) among them.
TEST(Geometry, CellsInLanesGiveTheSameBitsAsOneByOne) {
  std::mt19937 rng(3);
  for (int trial = 0; trial < 20; ++trial) {
    Vec3 x[hex::kCellLanes][8];
    for (int i = 0; i < hex::kCellLanes; ++i) {
      distortedHex(rng, 0.3, Vec3{10.0 * i, -3.0, 7.0}, x[i]);
    }
    if (trial % 2) {
      for (int p = 1; p < 4; ++p) x[0][p] = x[0][0];
    }
    hex::CellGeometry lanes[hex::kCellLanes], shapes[hex::kCellLanes];
    hex::cellGeometries(x, lanes);
    hex::cellGeometries<false>(x, shapes);
    for (int i = 0; i < hex::kCellLanes; ++i) {
      hex::CellGeometry one;
      hex::cellGeometry(x[i], one);
      for (const auto* g : {&lanes[i], &shapes[i]}) {
        EXPECT_EQ(g->shape.volume, one.shape.volume) << "cell " << i;
        EXPECT_EQ(g->shape.centroid.x, one.shape.centroid.x);
        EXPECT_EQ(g->shape.centroid.y, one.shape.centroid.y);
        EXPECT_EQ(g->shape.centroid.z, one.shape.centroid.z);
        EXPECT_EQ(g->shape.max_face_area, one.shape.max_face_area);
      }
      for (int p = 0; p < 8; ++p) {
        EXPECT_EQ(lanes[i].corner[p].x, one.corner[p].x) << "cell " << i << " corner " << p;
        EXPECT_EQ(lanes[i].corner[p].y, one.corner[p].y);
        EXPECT_EQ(lanes[i].corner[p].z, one.corner[p].z);
        EXPECT_EQ(lanes[i].corner_face_area[p], one.corner_face_area[p]);
        const SymMat3& m = lanes[i].normal_moment[p];
        const SymMat3& m_one = one.normal_moment[p];
        EXPECT_EQ(m.xx, m_one.xx);
        EXPECT_EQ(m.yy, m_one.yy);
        EXPECT_EQ(m.zz, m_one.zz);
        EXPECT_EQ(m.xy, m_one.xy);
        EXPECT_EQ(m.yz, m_one.yz);
        EXPECT_EQ(m.xz, m_one.xz);
      }
    }
    if (trial % 2) {  // the collapsed face's corners: finite sums, no NaN of a 0 / 0 normal
      EXPECT_GT(lanes[0].shape.volume, 0.0);
      for (int p = 0; p < 4; ++p) {
        EXPECT_TRUE(std::isfinite(lanes[0].corner_face_area[p]));
        EXPECT_TRUE(std::isfinite(ddot(lanes[0].normal_moment[p], lanes[0].normal_moment[p])));
      }
    }
  }
}

// A right prism along z (a one-cell slab's cell, Mesh::z_prisms): the
// closed forms of hex::prismGeometry give the general sweep's volume,
// centroid, face area, corner vectors and impedance sums to round-off, on
// distorted (non-convex too) quads far from the origin, thin and thick.
// The staged form's pieces (kernels/geometry_staged.hpp, KernelForm): the
// shape alone with the node positions read one at a time, and each corner
// from the corner-face vectors of its 3 faces; the same bits as the fused
// sweep, a degenerate face included.
TEST(Geometry, StagedFormGivesTheSweepsBitsCornerByCorner) {
  std::mt19937 rng(11);
  for (int trial = 0; trial < 40; ++trial) {
    Vec3 x[8];
    distortedHex(rng, trial % 3 ? 0.3 : 0.45, Vec3{-20.0 + trial, 4.0, 9.0}, x);
    if (trial % 4 == 1) {
      for (int p = 5; p < 8; ++p) x[p] = x[4];  // the top face collapsed to a point
    }
    hex::CellGeometry fused;
    hex::cellGeometry(x, fused);
    const NodesOfArray node{x};
    const hex::CellShape shape = hex::sweptShape(node);
    EXPECT_EQ(shape.volume, fused.shape.volume) << "trial " << trial;
    EXPECT_EQ(shape.centroid.x, fused.shape.centroid.x);
    EXPECT_EQ(shape.centroid.y, fused.shape.centroid.y);
    EXPECT_EQ(shape.centroid.z, fused.shape.centroid.z);
    EXPECT_EQ(shape.max_face_area, fused.shape.max_face_area);
    for (int p = 0; p < 8; ++p) {
      const hex::CornerSums corner = hex::cornerOfFaces(FaceVectorsOfArray{x}, p);
      EXPECT_EQ(corner.vector.x, fused.corner[p].x) << "trial " << trial << " corner " << p;
      EXPECT_EQ(corner.vector.y, fused.corner[p].y);
      EXPECT_EQ(corner.vector.z, fused.corner[p].z);
      EXPECT_EQ(corner.area, fused.corner_face_area[p]);
      const SymMat3& m = corner.normal_moment;
      const SymMat3& m_fused = fused.normal_moment[p];
      EXPECT_EQ(m.xx, m_fused.xx);
      EXPECT_EQ(m.yy, m_fused.yy);
      EXPECT_EQ(m.zz, m_fused.zz);
      EXPECT_EQ(m.xy, m_fused.xy);
      EXPECT_EQ(m.yz, m_fused.yz);
      EXPECT_EQ(m.xz, m_fused.xz);
    }
  }
  // each node's 3 faces, in increasing order, hold it
  for (int p = 0; p < 8; ++p) {
    for (int i = 0; i < 3; ++i) {
      const int f = hex::faceOfNode(p, i);
      EXPECT_EQ(f / 2, i);
      int holds = 0;
      for (int k = 0; k < 4; ++k) holds += hex::faceNode(f, k) == p;
      EXPECT_EQ(holds, 1) << "node " << p << " face " << f;
    }
  }
}

// The staged form's geometry (kernels/geometry_staged.hpp: a cell's faces and
// corners in the lanes of a team, its closure in one) on a perturbed block of
// a gas and a hypo-elastic solid, pure cells of each and mixed cells with
// random fractions, energies, velocities and deviators: on every build (a
// GPU's the device kernel) its volumes, centroids and corner vectors are the
// host's sweep of each cell (hex::cellGeometry) to round-off and every cell
// is valid; where the fused form is built, every field it writes and the
// time-step limit are the fused form's bit for bit.
TEST(Geometry, StagedTeamsGiveTheHostSweepAndTheFusedBits) {
  const BlockSpec block = testing::perturbedBlock(9, 6, 5, {0, 0, 0}, {0.9, 0.6, 0.5}, 0.3);
  auto uniform =
      testing::uniformBlock(block, SideBoundaries{}, MaterialParams{}, 1.0, 2.0, Vec3{0, 0, 0});
  ProblemSetup& setup = uniform.setup;
  State& state = uniform.state;
  MaterialParams solid;
  solid.strength = StrengthKind::HypoElastic;
  solid.mu = 0.5;
  solid.yield_stress = 1e9;
  setup.materials = {MaterialParams{}, solid};
  for (Index c = 0; c < setup.mesh.n_cells; ++c) setup.cells.mat[c] = c % 2;
  state = allocateState(setup.mesh, false);
  initializeState(setup, state);
  ASSERT_EQ(state.n_materials, 2);
  const Mesh& mesh = setup.mesh;
  ASSERT_GT(computeGeometry(mesh, state, TimeStepControls{}).val, 0.0);

  std::mt19937 rng(31);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const auto v = Kokkos::create_mirror_view_and_copy(HostSpace(), state.v_c);
  const auto energy = Kokkos::create_mirror_view_and_copy(HostSpace(), state.E_c);
  const auto alpha = Kokkos::create_mirror_view_and_copy(HostSpace(), state.alpha_ck);
  const auto mass = Kokkos::create_mirror_view_and_copy(HostSpace(), state.m_ck);
  const auto cell_mass = Kokkos::create_mirror_view_and_copy(HostSpace(), state.m_c);
  const auto e_k = Kokkos::create_mirror_view_and_copy(HostSpace(), state.e_ck);
  const auto deviator = Kokkos::create_mirror_view_and_copy(HostSpace(), state.S_ck);
  const auto volume = Kokkos::create_mirror_view_and_copy(HostSpace(), state.vol_c);
  int mixed = 0;
  for (Index c = 0; c < mesh.n_cells; ++c) {
    for (int d = 0; d < 3; ++d) v(c, d) = unit(rng) - 0.5;
    energy(c) = 2.0 + unit(rng) + 0.5 * (v(c, 0) * v(c, 0) + v(c, 1) * v(c, 1) + v(c, 2) * v(c, 2));
    for (int i = 0; i < 6; ++i) deviator(c, 1, i) = 0.1 * (unit(rng) - 0.5);
    if (c % 3 != 0) continue;                                                 // a mixed cell
    const double solid_fraction = c % 9 == 0 ? 2e-4 : 0.2 + 0.6 * unit(rng);  // (some a trace)
    alpha(c, 0) = 1.0 - solid_fraction;
    alpha(c, 1) = solid_fraction;
    mass(c, 0) = alpha(c, 0) * volume(c) * (0.8 + 0.4 * unit(rng));
    mass(c, 1) = alpha(c, 1) * volume(c) * (2.0 + unit(rng));
    cell_mass(c) = mass(c, 0) + mass(c, 1);
    e_k(c, 0) = 1.0 + unit(rng);
    e_k(c, 1) = 0.5 + unit(rng);
    ++mixed;
  }
  EXPECT_GT(mixed, 50);
  Kokkos::deep_copy(state.v_c, v);
  Kokkos::deep_copy(state.E_c, energy);
  Kokkos::deep_copy(state.alpha_ck, alpha);
  Kokkos::deep_copy(state.m_ck, mass);
  Kokkos::deep_copy(state.m_c, cell_mass);
  Kokkos::deep_copy(state.e_ck, e_k);
  Kokkos::deep_copy(state.S_ck, deviator);

  const auto written = [&state] {
    testing::HostFields fields;
    testing::addHostCopy(fields, "vol_c", state.vol_c);
    testing::addHostCopy(fields, "x_c", state.x_c);
    testing::addHostCopy(fields, "len_c", state.len_c);
    testing::addHostCopy(fields, "rho_c", state.rho_c);
    testing::addHostCopy(fields, "e_c", state.e_c);
    testing::addHostCopy(fields, "p_c", state.p_c);
    testing::addHostCopy(fields, "aL_c", state.aL_c);
    testing::addHostCopy(fields, "aT_c", state.aT_c);
    testing::addHostCopy(fields, "S_c", state.S_c);
    testing::addHostCopy(fields, "A_cp", state.A_cp);
    testing::addHostCopy(fields, "M_cp", state.M_cp);
    testing::addHostCopy(fields, "p_ck", state.p_ck);
    testing::addHostCopy(fields, "w_ck", state.w_ck);
    testing::addHostCopy(fields, "S_ck", state.S_ck);
    return fields;
  };
  const TimeStepControls controls{};
  StepLimit fused_limit{};
  testing::HostFields fused;
  if constexpr (kFusedKernelsBuilt) {  // (GPU builds have no fused form)
    fused_limit = computeGeometry(mesh, state, controls, KernelForm::Fused);
    fused = written();
  }
  const double nan = std::nan("");  // (the staged form must write each cell field)
  for (const auto& field :
       {state.vol_c, state.len_c, state.rho_c, state.e_c, state.p_c, state.aL_c, state.aT_c}) {
    Kokkos::deep_copy(field, nan);
  }
  Kokkos::deep_copy(state.x_c, nan);
  Kokkos::deep_copy(state.S_c, nan);
  Kokkos::deep_copy(state.A_cp, nan);
  Kokkos::deep_copy(state.M_cp, nan);
  const StepLimit staged_limit = computeGeometry(mesh, state, controls, KernelForm::Staged);
  EXPECT_GT(staged_limit.val, 0.0);  // (every cell valid)
  const testing::HostFields staged = written();

  const auto cell_nodes = Kokkos::create_mirror_view_and_copy(HostSpace(), mesh.cell_nodes);
  const auto x_n = Kokkos::create_mirror_view_and_copy(HostSpace(), mesh.x_n);
  const std::vector<double>& vol = staged.at("vol_c");
  const std::vector<double>& centroid = staged.at("x_c");
  const std::vector<double>& corner = staged.at("A_cp");
  for (Index c = 0; c < mesh.n_cells; ++c) {
    Vec3 x[8];
    for (int p = 0; p < 8; ++p) x[p] = loadVec3(x_n, cell_nodes(c, p));
    hex::CellGeometry sweep;
    hex::cellGeometry(x, sweep);
    ASSERT_NEAR(vol[c], sweep.shape.volume, 1e-15) << "cell " << c;
    const double sweep_centroid[3] = {sweep.shape.centroid.x, sweep.shape.centroid.y,
                                      sweep.shape.centroid.z};
    for (int d = 0; d < 3; ++d) {
      ASSERT_NEAR(centroid[3 * c + d], sweep_centroid[d], 1e-14) << "cell " << c;
    }
    for (int p = 0; p < 8; ++p) {
      const double sweep_corner[3] = {sweep.corner[p].x, sweep.corner[p].y, sweep.corner[p].z};
      for (int d = 0; d < 3; ++d) {
        ASSERT_NEAR(corner[3 * (8 * c + p) + d], sweep_corner[d], 1e-15)
            << "cell " << c << " corner " << p;
      }
    }
  }

  if constexpr (kFusedKernelsBuilt) {
    EXPECT_EQ(staged_limit.val, fused_limit.val);
    EXPECT_EQ(staged_limit.loc, fused_limit.loc);
    for (const auto& [name, values] : fused) {
      EXPECT_TRUE(testing::sameBits(staged.at(name), values)) << name;
    }
  }
}

TEST(Geometry, PrismGeometryIsTheGeneralSweepOfAPrism) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  for (int trial = 0; trial < 200; ++trial) {
    const Vec3 offset{-30.0 + unit(rng), 12.0 + unit(rng), 5.0 + unit(rng)};
    const double height = trial % 2 ? 0.02 : 1.3 + unit(rng);  // a thin slab and a thick one
    const double amplitude = trial % 4 < 2 ? 0.2 : 0.45;       // 0.45: some quads not convex
    Vec3 x[8];
    unitCube(x);
    for (int p = 0; p < 4; ++p) {
      x[p] = offset + Vec3{x[p].x + amplitude * unit(rng), x[p].y + amplitude * unit(rng), 0.0};
      x[p + 4] = Vec3{x[p].x, x[p].y, offset.z + height};
    }
    hex::CellGeometry general, prism, prism_shape;
    hex::cellGeometry(x, general);
    hex::prismGeometry(x, prism);
    hex::prismGeometry<false>(x, prism_shape);
    ASSERT_GT(general.shape.volume, 0.0);
    const double area = general.shape.max_face_area;
    EXPECT_NEAR(prism.shape.volume, general.shape.volume, 1e-13 * general.shape.volume);
    EXPECT_LT(norm(prism.shape.centroid - general.shape.centroid), 1e-13 * norm(offset));
    EXPECT_NEAR(prism.shape.max_face_area, area, 1e-13 * area);
    for (int p = 0; p < 8; ++p) {
      EXPECT_LT(norm(prism.corner[p] - general.corner[p]), 1e-13 * area) << "corner " << p;
      EXPECT_NEAR(prism.corner_face_area[p], general.corner_face_area[p], 1e-13 * area);
      const SymMat3 d = prism.normal_moment[p] - general.normal_moment[p];
      EXPECT_LT(std::sqrt(ddot(d, d)), 1e-13 * area) << "corner " << p;
    }
    // the shape alone is the same bits as with the corner sums
    EXPECT_EQ(prism_shape.shape.volume, prism.shape.volume);
    EXPECT_EQ(prism_shape.shape.centroid.x, prism.shape.centroid.x);
    EXPECT_EQ(prism_shape.shape.centroid.y, prism.shape.centroid.y);
    EXPECT_EQ(prism_shape.shape.centroid.z, prism.shape.centroid.z);
    EXPECT_EQ(prism_shape.shape.max_face_area, prism.shape.max_face_area);
  }
  // the unit cube exactly
  Vec3 cube[8];
  unitCube(cube);
  hex::CellGeometry unit_prism;
  hex::prismGeometry(cube, unit_prism);
  EXPECT_EQ(unit_prism.shape.volume, 1.0);
  EXPECT_EQ(unit_prism.shape.max_face_area, 1.0);
  EXPECT_EQ(unit_prism.corner[6].x, 0.25);
  EXPECT_EQ(unit_prism.corner[6].z, 0.25);
  EXPECT_EQ(unit_prism.corner_face_area[0], 0.75);
}

TEST(Geometry, AffineImagesOfTheCubeAreExact) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  for (int trial = 0; trial < 50; ++trial) {
    // x = A xi + b with a well-conditioned random A (positive determinant).
    Mat3 a = zeroMat();
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) a.m[i][j] = (i == j ? 1.5 : 0.0) + 0.3 * unit(rng);
    const Vec3 b{5 * unit(rng), 5 * unit(rng), 5 * unit(rng)};
    const double det = a.m[0][0] * (a.m[1][1] * a.m[2][2] - a.m[1][2] * a.m[2][1]) -
                       a.m[0][1] * (a.m[1][0] * a.m[2][2] - a.m[1][2] * a.m[2][0]) +
                       a.m[0][2] * (a.m[1][0] * a.m[2][1] - a.m[1][1] * a.m[2][0]);
    ASSERT_GT(det, 0.0);
    Vec3 x[8];
    unitCube(x);
    for (int p = 0; p < 8; ++p) x[p] = a * x[p] + b;
    const hex::CellShape shape = hex::cellShape(x);
    EXPECT_NEAR(shape.volume, det, 1e-13 * det);
    const Vec3 centre = a * Vec3{0.5, 0.5, 0.5} + b;
    EXPECT_LT(norm(shape.centroid - centre), 1e-13);
  }
}

TEST(Geometry, FrustumVolumeAndCentroidAreExact) {
  // Square frustum: side a at z = 0, side b at z = h; planar trapezoid faces.
  const double a = 2.0, b = 0.8, h = 1.5;
  const Vec3 x[8] = {{-a / 2, -a / 2, 0}, {a / 2, -a / 2, 0},  {a / 2, a / 2, 0},
                     {-a / 2, a / 2, 0},  {-b / 2, -b / 2, h}, {b / 2, -b / 2, h},
                     {b / 2, b / 2, h},   {-b / 2, b / 2, h}};
  const hex::CellShape shape = hex::cellShape(x);
  EXPECT_NEAR(shape.volume, h / 3 * (a * a + a * b + b * b), 1e-14);
  const double z_centroid = h * (a * a + 2 * a * b + 3 * b * b) / (4 * (a * a + a * b + b * b));
  EXPECT_NEAR(shape.centroid.z, z_centroid, 1e-14);
  EXPECT_NEAR(shape.centroid.x, 0.0, 1e-15);
  EXPECT_NEAR(shape.max_face_area, a * a, 1e-14);
}

// The device kernels on a whole perturbed mesh: cell volumes add up to the
// box, and at every interior node the corner vectors of its cells cancel
// (moving an interior node does not change the total volume).
TEST(Geometry, MeshKernelsConserveVolumeAndCancelAtInteriorNodes) {
  const BlockSpec block = testing::perturbedBlock(7, 5, 4, {-1.0, 0.0, 2.0}, {2.0, 1.0, 3.5}, 0.3);
  auto [setup, state] =
      testing::uniformBlock(block, SideBoundaries{}, MaterialParams{}, 1.0, 1.0, Vec3{0, 0, 0});
  const Index n_cells = setup.mesh.n_cells;
  const StepLimit limit = computeGeometry(setup.mesh, state, TimeStepControls{});
  EXPECT_GT(limit.val, 0.0);
  computeCornerTerms(setup.mesh, state, CornerControls{2, Gather::Crs});

  auto vol = Kokkos::create_mirror_view_and_copy(HostSpace(), state.vol_c);
  double total = 0.0;
  for (Index c = 0; c < n_cells; ++c) total += vol(c);
  EXPECT_NEAR(total, 3.0 * 1.0 * 1.5, 1e-13);

  auto corner_vec = Kokkos::create_mirror_view_and_copy(HostSpace(), state.A_cp);
  auto offsets = Kokkos::create_mirror_view_and_copy(HostSpace(), setup.mesh.node_corner_offsets);
  auto corners = Kokkos::create_mirror_view_and_copy(HostSpace(), setup.mesh.node_corners);
  int interior = 0;
  for (Index n = 0; n < setup.mesh.n_nodes; ++n) {
    if (offsets(n + 1) - offsets(n) != 8) continue;  // interior nodes have 8 corners
    Vec3 sum{0, 0, 0};
    for (Index i = offsets(n); i < offsets(n + 1); ++i) sum += loadVec3(corner_vec, corners(i));
    EXPECT_LT(norm(sum), 1e-15) << "node " << n;
    ++interior;
  }
  EXPECT_EQ(interior, 6 * 4 * 3);
}

}  // namespace
}  // namespace lagremap
