// Kernel-level properties of the reconstruction and the nodal solver
// (DESIGN §3): least squares is exact on linear fields, the limited
// reconstruction stays within its neighbours' bounds, and constrained node
// velocities satisfy their planes and the tangential balance exactly.
#include <gtest/gtest.h>

#include <random>

#include "kernels/nodal_solver.hpp"
#include "kernels/reconstruction.hpp"

namespace lagremap {
namespace {

std::mt19937 g_rng(4242);
double uniform(double lo, double hi) {
  return std::uniform_real_distribution<double>(lo, hi)(g_rng);
}
Vec3 randomVec(double scale) {
  return {uniform(-scale, scale), uniform(-scale, scale), uniform(-scale, scale)};
}

TEST(Reconstruction, LeastSquaresIsExactForLinearFields) {
  for (int trial = 0; trial < 100; ++trial) {
    const Vec3 gradient = randomVec(5.0);
    LeastSquares lsq;
    Vec3 rhs{0, 0, 0};
    // Face neighbours of a distorted hex: near +-e_x, +-e_y, +-e_z; a boundary
    // cell misses some of the minus sides (3 to 6 neighbours).
    const Vec3 axes[6] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {-1, 0, 0}, {0, -1, 0}, {0, 0, -1}};
    const int n_neighbours = 3 + trial % 4;
    for (int i = 0; i < n_neighbours; ++i) {
      const Vec3 dx = uniform(0.5, 2.0) * (axes[i] + randomVec(0.3));
      lsq.addOffset(dx);
      rhs += dot(gradient, dx) * dx;  // psi_nb - psi_c of a linear field
    }
    const Vec3 recovered = lsq.solver() * rhs;
    EXPECT_LT(norm(recovered - gradient), 1e-10 * norm(gradient)) << trial;
  }
}

TEST(Reconstruction, LimitedVertexValuesStayWithinNeighbourBounds) {
  for (int trial = 0; trial < 1000; ++trial) {
    const double center = uniform(-1, 1);
    Bounds bounds(center);
    for (int i = 0; i < 6; ++i) bounds.include(uniform(-2, 2));
    double deltas[8];
    VertexExcursion excursion;
    for (double& delta : deltas) {
      delta = uniform(-3, 3);
      excursion.include(delta);
    }
    for (double beta : {1.0, 2.0}) {
      const double phi = cellLimiter(excursion, center, bounds, beta);
      EXPECT_GE(phi, 0.0);
      EXPECT_LE(phi, beta);
      double per_vertex_min = beta;
      for (double delta : deltas) {
        const double value = center + phi * delta;
        EXPECT_LE(value, bounds.hi + 1e-14);
        EXPECT_GE(value, bounds.lo - 1e-14);
        per_vertex_min = std::min(per_vertex_min, vertexLimiter(delta, center, bounds, beta));
      }
      // The two-division form is the min over vertices of DESIGN §5's formula.
      EXPECT_NEAR(phi, per_vertex_min, 1e-15);
    }
  }
}

SymMat3 randomSpd() {
  Mat3 a = zeroMat();
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) a.m[i][j] = uniform(-1, 1) + (i == j ? 2.0 : 0.0);
  // a a^T is SPD
  SymMat3 m{0, 0, 0, 0, 0, 0};
  for (int k = 0; k < 3; ++k) m += outerSelf(Vec3{a.m[0][k], a.m[1][k], a.m[2][k]}, 1.0);
  return m;
}

// Solves like the node kernel does for a node with the given constraint planes.
Vec3 constrainedVelocity(const SymMat3& m, const Vec3& b, const Vec3* normals, int n_planes) {
  SymMat3 projector = identitySym();
  Vec3 basis[3];
  for (int i = 0; i < n_planes; ++i) {
    Vec3 n = normals[i];
    for (int j = 0; j < i; ++j) n -= dot(n, basis[j]) * basis[j];
    basis[i] = (1.0 / norm(n)) * n;
    projector += outerSelf(basis[i], -1.0);
  }
  if (n_planes >= 3) projector = identitySym(0.0);
  return projector * (inverse(detail::constrainedMatrix(projector, m)) * (projector * b));
}

TEST(NodalSolver, ConstrainedVelocitiesSatisfyPlanesAndTangentialBalance) {
  for (int trial = 0; trial < 200; ++trial) {
    const SymMat3 m = randomSpd();
    const Vec3 b = randomVec(3.0);
    const Vec3 normals[3] = {randomVec(1.0), randomVec(1.0), randomVec(1.0)};
    // No constraint: M V = B.
    const Vec3 free = constrainedVelocity(m, b, normals, 0);
    EXPECT_LT(norm(m * free - b), 1e-12 * norm(b));
    for (int planes = 1; planes <= 3; ++planes) {
      const Vec3 v = constrainedVelocity(m, b, normals, planes);
      for (int i = 0; i < planes; ++i) EXPECT_NEAR(dot(v, normals[i]), 0.0, 1e-12);
      // The residual M V - B is the wall reaction: it lies in the span of the
      // normals (Lagrange multipliers), so it is orthogonal to every allowed direction.
      const Vec3 residual = m * v - b;
      if (planes == 1) {
        const Vec3 t1 = cross(normals[0], randomVec(1.0));
        const Vec3 t2 = cross(normals[0], t1);
        EXPECT_NEAR(dot(residual, t1), 0.0, 1e-11 * norm(t1));
        EXPECT_NEAR(dot(residual, t2), 0.0, 1e-11 * norm(t2));
      } else if (planes == 2) {
        const Vec3 t = cross(normals[0], normals[1]);
        EXPECT_NEAR(dot(residual, t), 0.0, 1e-11 * norm(t));
      } else {
        EXPECT_EQ(norm(v), 0.0);  // three planes (or fixed): the node is held
      }
    }
  }
}

// The constrained solution minimises the nodal energy 1/2 V.M V - B.V on the
// allowed plane: any other allowed velocity has higher energy.
TEST(NodalSolver, ConstrainedVelocityMinimisesTheNodalEnergy) {
  for (int trial = 0; trial < 100; ++trial) {
    const SymMat3 m = randomSpd();
    const Vec3 b = randomVec(3.0);
    const Vec3 n = randomVec(1.0);
    const Vec3 v = constrainedVelocity(m, b, &n, 1);
    auto energy = [&](const Vec3& u) { return 0.5 * dot(u, m * u) - dot(b, u); };
    for (int k = 0; k < 10; ++k) {
      Vec3 tangent = cross(n, randomVec(1.0));
      EXPECT_GT(energy(v + 1e-3 * tangent), energy(v));
    }
  }
}

}  // namespace
}  // namespace lagremap
