// Kernel-level properties of the nodal solver (kernels/nodal_solver.hpp,
// docs/method.md §A4): constrained node velocities satisfy their planes and
// the tangential balance exactly.
#include <gtest/gtest.h>

#include "kernels/nodal_solver.hpp"
#include "random_draws.hpp"

namespace lagremap {
namespace {

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

// Axis-plane projectors (walls and symmetry planes normal to x, y, z, alone
// or two together) take constrainedMatrix's and project's shortcut: the same
// numbers as P M P + s (I - P) (s = tr(M) / 3) and P v multiplied out in full.
TEST(NodalSolver, AxisProjectorShortcutGivesTheFullProduct) {
  for (int trial = 0; trial < 50; ++trial) {
    const SymMat3 m = randomSpd();
    const Vec3 v = randomVec(2.0);
    for (int mask = 1; mask < 8; ++mask) {  // the constrained axes
      const double free[3] = {(mask & 1) ? 0.0 : 1.0, (mask & 2) ? 0.0 : 1.0,
                              (mask & 4) ? 0.0 : 1.0};
      const SymMat3 projector{free[0], free[1], free[2], 0.0, 0.0, 0.0};
      const double full[3][3] = {{m.xx, m.xy, m.xz}, {m.xy, m.yy, m.yz}, {m.xz, m.yz, m.zz}};
      const SymMat3 shortcut = detail::constrainedMatrix(projector, m);
      const double got[3][3] = {{shortcut.xx, shortcut.xy, shortcut.xz},
                                {shortcut.xy, shortcut.yy, shortcut.yz},
                                {shortcut.xz, shortcut.yz, shortcut.zz}};
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
          double pmp = 0.0;  // (P M P)_ij, then + I - P in the definition's order
          for (int k = 0; k < 3; ++k)
            for (int l = 0; l < 3; ++l) {
              pmp += (i == k ? free[i] : 0.0) * full[k][l] * (l == j ? free[j] : 0.0);
            }
          const double scale = (m.xx + m.yy + m.zz) * (1.0 / 3.0);
          const double expected = pmp + scale * ((i == j) - (i == j ? free[i] : 0.0));
          EXPECT_EQ(got[i][j], expected) << "mask " << mask << " entry " << i << j;
        }
      const Vec3 projected = detail::project(projector, v);
      EXPECT_EQ(projected.x, free[0] * v.x);
      EXPECT_EQ(projected.y, free[1] * v.y);
      EXPECT_EQ(projected.z, free[2] * v.z);
    }
  }
}

// An impedance is dimensional: a node of near-vacuum (M ~ 1e-16 kg/s, the
// `ball`'s wake at `--scale 2`) or of a very stiff material must give the
// velocity of the same node in other units. With I - P added unscaled,
// M + 1 - 1 lost the small M's free entries (NaN velocities, a tangled cell).
TEST(NodalSolver, ConstrainedVelocityDoesNotDependOnTheImpedanceUnits) {
  for (int trial = 0; trial < 100; ++trial) {
    const SymMat3 m = randomSpd();
    const Vec3 b = randomVec(3.0);
    const Vec3 normals[3] = {Vec3{0, 0, 1}, randomVec(1.0), Vec3{1, 0, 0}};
    for (int planes = 1; planes <= 2; ++planes) {
      const Vec3 reference = constrainedVelocity(m, b, normals, planes);
      for (const double units : {1e-18, 1e-9, 1e9, 1e18}) {
        const Vec3 v = constrainedVelocity(units * m, units * b, normals, planes);
        EXPECT_LT(norm(v - reference), 1e-10 * (norm(reference) + 1.0))
            << "units " << units << ", planes " << planes;
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
