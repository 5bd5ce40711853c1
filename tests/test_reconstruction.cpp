// Kernel-level properties of the reconstruction (kernels/reconstruction.hpp,
// docs/method.md §A5, §A10): least squares is exact on linear fields, the
// limited reconstruction stays within its neighbours' bounds, and the vector
// and tensor limiter is frame-independent and keeps a one-cell plateau's jump
// at the node.
#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

#include "kernels/hex.hpp"
#include "kernels/reconstruction.hpp"
#include "random_draws.hpp"

namespace lagremap {
namespace {

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

// A one-cell-thick slab (neighbours along x and y only) or a 1D bar (x only):
// the neighbours' centroids are off the slab's plane by round-off and a tiny
// twist of the mesh. The gradient in the spanned directions stays exact and
// the missing ones get none; a regularisation of 1e-12 tr instead turned the
// 1e-9 offsets into a z-gradient hundreds of times the true one.
TEST(Reconstruction, LeastSquaresGivesNoGradientAlongDirectionsWithoutNeighbours) {
  for (int trial = 0; trial < 100; ++trial) {
    const Vec3 gradient = randomVec(5.0);
    const bool bar = trial % 2 == 1;
    const Vec3 axes[4] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}};
    LeastSquares lsq;
    Vec3 rhs{0, 0, 0};
    for (int i = 0; i < (bar ? 2 : 4); ++i) {
      Vec3 dx = uniform(0.5, 2.0) * (axes[i] + (bar ? 0.0 : 0.2) * randomVec(1.0));
      dx.z = uniform(-1e-9, 1e-9);
      if (bar) dx.y = uniform(-1e-9, 1e-9);
      lsq.addOffset(dx);
      rhs += dot(gradient, dx) * dx;
    }
    const Vec3 recovered = lsq.solver() * rhs;
    EXPECT_NEAR(recovered.x, gradient.x, 1e-6 * norm(gradient)) << trial;
    if (bar) {
      EXPECT_LT(std::fabs(recovered.y), 1e-6 * norm(gradient)) << trial;
    } else {
      EXPECT_NEAR(recovered.y, gradient.y, 1e-6 * norm(gradient)) << trial;
    }
    EXPECT_LT(std::fabs(recovered.z), 1e-6 * norm(gradient)) << trial;
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
      // The two-division form is the min over vertices of docs/method.md §A10's formula.
      EXPECT_NEAR(phi, per_vertex_min, 1e-15);
    }
  }
}

Vec3 unitVec() {
  const Vec3 v = randomVec(1.0);
  return (1.0 / norm(v)) * v;
}

// A random rotation: Gram-Schmidt on two random vectors.
Mat3 randomRotation() {
  const Vec3 a = unitVec();
  Vec3 b = randomVec(1.0);
  b -= dot(a, b) * a;
  b = (1.0 / norm(b)) * b;
  const Vec3 c = cross(a, b);
  return {{{a.x, b.x, c.x}, {a.y, b.y, c.y}, {a.z, b.z, c.z}}};
}

SymMat3 randomSym(double scale) {
  return {uniform(-scale, scale), uniform(-scale, scale), uniform(-scale, scale),
          uniform(-scale, scale), uniform(-scale, scale), uniform(-scale, scale)};
}

SymMat3 rotate(const Mat3& q, const SymMat3& t) {
  return symPart(q * fullMat(t) * transpose(q));
}

double component(const SymMat3& t, int k) {
  const double c[6] = {t.xx, t.yy, t.zz, t.xy, t.yz, t.xz};
  return c[k];
}

// Direct definition of the projected limiter (docs/method.md §2.3), one
// vertex at a time, with the faces holding each vertex read from the hex's
// face-node table: the reference for the kernel's forms.
template <class Field, class Inner>
double directLimiter(const Field jumps[6], const Field excursions[8], bool guard, Inner inner_of) {
  double phi = 1.0;
  for (int p = 0; p < 8; ++p) {
    const double length2 = inner_of(excursions[p], excursions[p]);
    if (length2 == 0.0) continue;
    std::vector<double> along;
    double at_vertex[3];
    int n_at_vertex = 0;
    for (int f = 0; f < 6; ++f) {
      along.push_back(inner_of(jumps[f], excursions[p]));
      for (int k = 0; k < 4; ++k) {
        if (hex::faceNode(f, k) == p) at_vertex[n_at_vertex++] = along.back();
      }
    }
    EXPECT_EQ(n_at_vertex, 3);
    along.push_back(at_vertex[0] + at_vertex[1]);  // edge and corner neighbours
    along.push_back(at_vertex[1] + at_vertex[2]);
    along.push_back(at_vertex[0] + at_vertex[2]);
    along.push_back(at_vertex[0] + at_vertex[1] + at_vertex[2]);
    double toward = 0.0, away = 0.0;
    for (double a : along) {
      toward = std::max(toward, a);
      away = std::max(away, -a);
    }
    const double r = toward / away;
    const double f = guard && toward < away ? 0.5 * (1.0 + r * r) : 1.0;
    phi = std::min(phi, f * toward / length2);
  }
  return phi;
}

// Along one fixed direction (a 1D run: jumps across the x faces only, the
// transverse faces' mirror jumps zero up to round-off) the vector limiter is
// Barth-Jespersen on that component, whatever the direction (a common factor
// of per-component limiters is not: it limits the round-off as if it were
// the flow).
TEST(Reconstruction, VectorLimiterIsBarthJespersenAlongOneDirection) {
  for (int trial = 0; trial < 500; ++trial) {
    const Vec3 e = unitVec();
    const double center = uniform(-1, 1);
    Bounds bounds(center);
    Vec3 jumps[6], excursions[8];
    VertexExcursion excursion;
    double length2[8];
    for (int f = 0; f < 6; ++f) {
      const double value = f < 2 ? uniform(-2, 2) : center;
      bounds.include(value);
      jumps[f] = (value - center) * e + randomVec(1e-17);
    }
    for (int p = 0; p < 8; ++p) {
      const double delta = uniform(-3, 3);
      excursion.include(delta);
      excursions[p] = delta * e + randomVec(1e-17);
      length2[p] = dot(excursions[p], excursions[p]);
    }
    const double bj = cellLimiter(excursion, center, bounds, 1.0);
    EXPECT_NEAR((projectedLimiter<false, true>(jumps, excursions, length2)), bj, 1e-12) << trial;
  }
}

// A linear field varying along x, y and z at once (jumps +-g_k along axis k,
// vertex excursions (+-g_x +- g_y +- g_z)/2 on a unit cube) is not limited:
// the vertex may go as far as the corner neighbour, the sum of its three
// faces' jumps. Face neighbours alone would allow only 2/3 of it.
TEST(Reconstruction, LinearFieldAlongSeveralAxesIsNotLimited) {
  for (int trial = 0; trial < 100; ++trial) {
    const Vec3 g[3] = {randomVec(1.0), randomVec(1.0), randomVec(1.0)};
    Vec3 jumps[6], excursions[8];
    double length2[8];
    for (int k = 0; k < 3; ++k) {
      jumps[2 * k] = -g[k];  // the minus side
      jumps[2 * k + 1] = g[k];
    }
    for (int p = 0; p < 8; ++p) {
      // VTK unit cube: x+ for nodes 1, 2, 5, 6; y+ for 2, 3, 6, 7; z+ for 4-7
      const double sx = ((p ^ (p >> 1)) & 1) ? 0.5 : -0.5;
      const double sy = (p & 2) ? 0.5 : -0.5, sz = (p & 4) ? 0.5 : -0.5;
      excursions[p] = sx * g[0] + sy * g[1] + sz * g[2];
      length2[p] = dot(excursions[p], excursions[p]);
    }
    EXPECT_NEAR((projectedLimiter<false, true>(jumps, excursions, length2)), 1.0, 1e-14);
    EXPECT_NEAR((projectedLimiter<true, true>(jumps, excursions, length2)), 1.0, 1e-14);
  }
}

// The limiter of a rotated field is the limiter of the field: a vector, and
// a symmetric tensor in the pulled-back form the kernel uses, which equals
// the direct definition.
TEST(Reconstruction, ProjectedLimiterIsFrameIndependent) {
  int limited = 0;
  for (int trial = 0; trial < 300; ++trial) {
    const Mat3 q = randomRotation();
    const bool guard = trial % 2 == 1;
    const auto limit = [&](const auto jumps[6], const auto directions[8], const double len2[8]) {
      return guard ? projectedLimiter<true, true>(jumps, directions, len2)
                   : projectedLimiter<false, true>(jumps, directions, len2);
    };
    // vector: jumps and vertex excursions
    Vec3 jumps[6], excursions[8], jumps_q[6], excursions_q[8];
    double length2[8];
    for (int j = 0; j < 6; ++j) {
      jumps[j] = randomVec(1.0);
      jumps_q[j] = q * jumps[j];
    }
    for (int p = 0; p < 8; ++p) {
      excursions[p] = randomVec(0.8);
      excursions_q[p] = q * excursions[p];
      length2[p] = dot(excursions[p], excursions[p]);
    }
    const double phi = limit(jumps, excursions, length2);
    const auto vec_inner = [](const Vec3& a, const Vec3& b) { return dot(a, b); };
    EXPECT_NEAR(phi, directLimiter(jumps, excursions, guard, vec_inner), 1e-12);
    EXPECT_NEAR(limit(jumps_q, excursions_q, length2), phi, 1e-12);
    limited += phi > 0.0 && phi < 1.0;

    // tensor: least-squares gradient rows G_k (component k), offsets d_p
    Vec3 gradients[6], gradients_q[6], offsets[8];
    SymMat3 tjumps[6], tjumps_q[6], texcursions[8], texcursions_q[8];
    for (Vec3& g : gradients) g = randomVec(1.0);
    for (Vec3& d : offsets) d = randomVec(0.5);
    // rotating the field maps the components linearly: G'_k = sum_m R_km G_m
    for (int k = 0; k < 6; ++k) gradients_q[k] = Vec3{0, 0, 0};
    for (int m = 0; m < 6; ++m) {
      SymMat3 basis{0, 0, 0, 0, 0, 0};
      double* entries[6] = {&basis.xx, &basis.yy, &basis.zz, &basis.xy, &basis.yz, &basis.xz};
      *entries[m] = 1.0;
      const SymMat3 image = rotate(q, basis);
      for (int k = 0; k < 6; ++k) gradients_q[k] += component(image, k) * gradients[m];
    }
    for (int j = 0; j < 6; ++j) {
      tjumps[j] = randomSym(1.0);
      tjumps_q[j] = rotate(q, tjumps[j]);
    }
    for (int p = 0; p < 8; ++p) {
      const Vec3& d = offsets[p];
      texcursions[p] = {dot(gradients[0], d), dot(gradients[1], d), dot(gradients[2], d),
                        dot(gradients[3], d), dot(gradients[4], d), dot(gradients[5], d)};
      texcursions_q[p] = rotate(q, texcursions[p]);
    }
    const auto pulled_phi = [&](const Vec3 grads[6], const SymMat3 tj[6]) {
      Vec3 pulled[6];
      pullBack(grads, tj, pulled);
      double len2[8];  // as computeCornerTerms: the Frobenius square of G d_p
      for (int p = 0; p < 8; ++p) {
        const Vec3& d = offsets[p];
        const SymMat3 excursion{dot(grads[0], d), dot(grads[1], d), dot(grads[2], d),
                                dot(grads[3], d), dot(grads[4], d), dot(grads[5], d)};
        len2[p] = ddot(excursion, excursion);
      }
      return limit(pulled, offsets, len2);
    };
    const double phi_t = pulled_phi(gradients, tjumps);
    const auto sym_inner = [](const SymMat3& a, const SymMat3& b) { return ddot(a, b); };
    EXPECT_NEAR(phi_t, directLimiter(tjumps, texcursions, guard, sym_inner), 1e-12);
    EXPECT_NEAR(directLimiter(tjumps_q, texcursions_q, guard, sym_inner), phi_t, 1e-12);
    EXPECT_NEAR(pulled_phi(gradients_q, tjumps_q), phi_t, 1e-12);
    limited += phi_t > 0.0 && phi_t < 1.0;
  }
  EXPECT_GT(limited, 60);  // not vacuous: many cases bind between 0 and 1
}

// A one-cell plateau (an elastic precursor state h between the unshocked 0
// ahead and a plastic P behind, on a unit cube with its 1D least-squares
// slope): Barth-Jespersen lets the vertex value ahead fall to the unshocked
// value, so the node sees no jump; the plateau guard keeps about half of it.
// A linear profile is not limited by either.
TEST(Reconstruction, PlateauGuardKeepsHalfTheSmallJumpAtTheNode) {
  for (double h : {0.01, 0.1, 0.2}) {  // h < plastic / 4: Barth-Jespersen binds
    const double plastic = 1.0;
    Vec3 jumps[6] = {{-h, 0, 0}, {plastic - h, 0, 0}, {0, 0, 0}, {0, 0, 0}, {0, 0, 0}, {0, 0, 0}};
    const double slope = 0.5 * (jumps[0].x - jumps[1].x);  // central, along +x
    Vec3 excursions[8];
    double length2[8];
    for (int p = 0; p < 8; ++p) {
      const double x = (p & 1) ? 0.5 : -0.5;
      excursions[p] = {slope * x, 0, 0};
      length2[p] = dot(excursions[p], excursions[p]);
    }
    const double ahead_excursion = slope * 0.5;
    const double bj = projectedLimiter<false, true>(jumps, excursions, length2);
    const double guarded = projectedLimiter<true, true>(jumps, excursions, length2);
    EXPECT_NEAR(h + bj * ahead_excursion, 0.0, 1e-15) << h;
    const double r = h / (plastic - h);
    EXPECT_NEAR(h + guarded * ahead_excursion, 0.5 * (1.0 - r * r) * h, 1e-15) << h;
    EXPECT_GT(h + guarded * ahead_excursion, 0.45 * h);

    // a linear profile: jumps -+g, excursions +-g/2
    Vec3 linear[6] = {{h, 0, 0}, {-h, 0, 0}, {0, 0, 0}, {0, 0, 0}, {0, 0, 0}, {0, 0, 0}};
    for (int p = 0; p < 8; ++p) {
      excursions[p] = {((p & 1) ? 0.5 : -0.5) * h, 0, 0};
      length2[p] = dot(excursions[p], excursions[p]);
    }
    EXPECT_EQ((projectedLimiter<true, true>(linear, excursions, length2)), 1.0);
    EXPECT_EQ((projectedLimiter<false, true>(linear, excursions, length2)), 1.0);
  }
}

// The wall ghost of a stress: the reflected tensor R T R, R = I - 2 n (x) n.
TEST(Reconstruction, MirrorJumpIsTheReflectedTensor) {
  for (int trial = 0; trial < 100; ++trial) {
    const SymMat3 t = randomSym(3.0);
    const Vec3 n = unitVec();
    const Mat3 reflection = identityMat() - 2.0 * Mat3{{{n.x * n.x, n.x * n.y, n.x * n.z},
                                                        {n.y * n.x, n.y * n.y, n.y * n.z},
                                                        {n.z * n.x, n.z * n.y, n.z * n.z}}};
    const SymMat3 expected = rotate(reflection, t) - t;
    EXPECT_LT(norm(mirrorJump(t, n) - expected), 1e-13 * norm(t)) << trial;
    // the normal traction changes sign only in its tangential part
    const Vec3 traction_jump = mirrorJump(t, n) * n;
    EXPECT_NEAR(dot(traction_jump, n), 0.0, 1e-13 * norm(t));
  }
}

}  // namespace
}  // namespace lagremap
