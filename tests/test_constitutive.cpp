// Constitutive models of docs/method.md §A7: equations of state (against finite
// differences and the Hugoniot form of Mie-Grüneisen), the hypo-elastic Jaumann
// update and radial return (objectivity, exact shear solution, yield surface),
// the Neo-Hookean stress (closed forms for stretch and shear, rigid rotations)
// and the material presets of docs/verification.md §8.1. The device functions are inline, so
// the tests call them directly on the host.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

#include "data/math.hpp"
#include "kernels/constitutive.hpp"
#include "kernels/eos.hpp"
#include "src/materials.hpp"

namespace lagremap {
namespace {

// ---------------------------------------------------------------- helpers

// Rotation by angle theta about the unit axis n (Rodrigues):
// R = I + sin(theta) K + (1 - cos(theta)) K^2, K the cross-product matrix of n.
Mat3 crossMatrix(const Vec3& n) {
  return {{{0.0, -n.z, n.y}, {n.z, 0.0, -n.x}, {-n.y, n.x, 0.0}}};
}
Mat3 rotation(const Vec3& axis, double theta) {
  const Vec3 n = (1.0 / norm(axis)) * axis;
  const Mat3 K = crossMatrix(n);
  return identityMat() + std::sin(theta) * K + (1.0 - std::cos(theta)) * (K * K);
}

// Q A Q^T through full 3x3 products (independent of pushForward).
SymMat3 conjugate(const Mat3& Q, const SymMat3& A) {
  const Mat3 full = Q * fullMat(A) * transpose(Q);
  return symPart(full);
}

double relativeError(const SymMat3& value, const SymMat3& reference) {
  return norm(value - reference) / norm(reference);
}

double maxAbs(const SymMat3& a) {
  return std::max({std::fabs(a.xx), std::fabs(a.yy), std::fabs(a.zz), std::fabs(a.xy),
                   std::fabs(a.yz), std::fabs(a.xz)});
}

// tr(S^2) = S : S for a symmetric tensor.
double secondInvariant(const SymMat3& S) {
  return ddot(S, S);
}

// Isentropic sound speed from the EOS by central differences:
// a^2 = dp/drho|_e + (p/rho^2) dp/de|_rho (from de = (p/rho^2) drho at constant s).
double finiteDifferenceSoundSpeed2(const MaterialParams& mat, double rho, double e) {
  const double h_rho = 1e-5 * rho;
  const double h_e = 1e-3 * std::max(std::fabs(e), 1e3);
  const double p = evaluateEos(mat, rho, e).pressure;
  const double dp_drho =
      (evaluateEos(mat, rho + h_rho, e).pressure - evaluateEos(mat, rho - h_rho, e).pressure) /
      (2.0 * h_rho);
  const double dp_de =
      (evaluateEos(mat, rho, e + h_e).pressure - evaluateEos(mat, rho, e - h_e).pressure) /
      (2.0 * h_e);
  return dp_drho + p / (rho * rho) * dp_de;
}

// A generic deviatoric tensor (all six entries nonzero, distinct eigenvalues).
SymMat3 sampleDeviator(double scale) {
  return dev(
      SymMat3{1.0 * scale, -0.4 * scale, -0.1 * scale, 0.3 * scale, -0.2 * scale, 0.5 * scale});
}

// ---------------------------------------------------------------- math helpers

TEST(MathHelpers, Mat3ProductTransposeDeterminant) {
  const Mat3 A{{{2.0, -1.0, 0.5}, {0.3, 1.5, -0.7}, {1.1, 0.2, 3.0}}};
  const Mat3 B{{{0.4, 1.2, -2.0}, {-0.6, 0.9, 0.1}, {1.3, -0.8, 0.7}}};
  const Mat3 AB = A * B;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      double expected = 0.0;
      for (int k = 0; k < 3; ++k) expected += A.m[i][k] * B.m[k][j];
      EXPECT_DOUBLE_EQ(AB.m[i][j], expected);
      EXPECT_EQ(transpose(A).m[i][j], A.m[j][i]);
      // L = sym(L) + skew(L)
      EXPECT_NEAR(fullMat(symPart(A)).m[i][j] + skewPart(A).m[i][j], A.m[i][j], 1e-15);
    }
  // det by the rule of Sarrus, written out independently
  const auto& a = A.m;
  const double sarrus = a[0][0] * a[1][1] * a[2][2] + a[0][1] * a[1][2] * a[2][0] +
                        a[0][2] * a[1][0] * a[2][1] - a[0][2] * a[1][1] * a[2][0] -
                        a[0][0] * a[1][2] * a[2][1] - a[0][1] * a[1][0] * a[2][2];
  EXPECT_NEAR(det(A), sarrus, 1e-14 * std::fabs(sarrus));
  EXPECT_NEAR(det(AB), det(A) * det(B), 1e-13 * std::fabs(det(A) * det(B)));
  EXPECT_NEAR(det(rotation({1.0, 2.0, 3.0}, 0.7)), 1.0, 1e-15);
  EXPECT_NEAR(det(transpose(A)), det(A), 1e-14 * std::fabs(det(A)));
}

// ---------------------------------------------------------------- EOS

TEST(Eos, IdealGasAggregateInitSoundSpeedAndValidity) {
  const MaterialParams gas{EosKind::IdealGas, 5.0 / 3.0};  // the callers' spelling
  EXPECT_EQ(gas.gamma, 5.0 / 3.0);
  for (double rho : {0.125, 1.0, 7.0})
    for (double e : {1e-3, 2.5, 4e4}) {
      const ThermoState state = evaluateEos(gas, rho, e);
      EXPECT_TRUE(state.valid);
      EXPECT_NEAR(state.pressure, (2.0 / 3.0) * rho * e, 1e-14 * state.pressure);
      EXPECT_NEAR(state.sound_speed2, finiteDifferenceSoundSpeed2(gas, rho, e),
                  1e-6 * state.sound_speed2);
    }
}

TEST(Eos, MieGruneisenSoundSpeedIsTheIsentropicDerivative) {
  for (const char* name : {"Al", "Be-hypo"}) {
    const MaterialParams mat = materialPreset(name);
    // At the reference state p = 0 and a = a0 (f(1) = 0, f'(1) = 1).
    const ThermoState reference = evaluateEos(mat, mat.rho0, 0.0);
    EXPECT_EQ(reference.pressure, 0.0) << name;
    EXPECT_NEAR(reference.sound_speed2, mat.a0 * mat.a0, 1e-14 * mat.a0 * mat.a0) << name;
    // Tension (eta < 1) and compression (eta > 1), cold and hot.
    for (double eta : {0.8, 0.95, 1.0, 1.05, 1.3, 1.8})
      for (double e : {0.0, 2e5, 3e6}) {
        const double rho = eta * mat.rho0;
        const ThermoState state = evaluateEos(mat, rho, e);
        ASSERT_TRUE(state.valid) << name << " eta=" << eta;
        EXPECT_NEAR(state.sound_speed2, finiteDifferenceSoundSpeed2(mat, rho, e),
                    1e-6 * state.sound_speed2)
            << name << " eta=" << eta << " e=" << e;
      }
  }
}

// The (V, e) form of the paper: reference curve = the Hugoniot through (V0, 0, 0),
//   p_H(V) = rho0 a0^2 x / (1 - s x)^2, x = 1 - V/V0,  e_H = p_H (V0 - V)/2,
// and a Grüneisen offset with Gamma/V = Gamma0/V0 constant:
//   p = p_H + (Gamma0/V0) (e - e_H).
// (Substituting x = (eta-1)/eta gives method.md §A7's f(eta); the test only uses V.)
double mieGruneisenVolumeForm(const MaterialParams& mat, double V, double e) {
  const double V0 = 1.0 / mat.rho0;
  const double x = 1.0 - V / V0;
  const double p_H = mat.rho0 * mat.a0 * mat.a0 * x / ((1.0 - mat.s * x) * (1.0 - mat.s * x));
  const double e_H = 0.5 * p_H * (V0 - V);
  return p_H + (mat.Gamma0 / V0) * (e - e_H);
}

TEST(Eos, MieGruneisenEqualsTheHugoniotVolumeForm) {
  for (const char* name : {"Al", "Be-hypo"}) {
    const MaterialParams mat = materialPreset(name);
    const double scale = mat.rho0 * mat.a0 * mat.a0;  // pressure scale
    for (double eta : {0.7, 0.9, 1.0, 1.1, 1.5, 2.2})
      for (double e : {0.0, 1e5, 5e6}) {
        const double rho = eta * mat.rho0;
        EXPECT_NEAR(evaluateEos(mat, rho, e).pressure, mieGruneisenVolumeForm(mat, 1.0 / rho, e),
                    1e-13 * scale)
            << name << " eta=" << eta << " e=" << e;
      }
    // Rankine-Hugoniot from rest: particle velocity u, shock speed U = a0 + s u,
    // p = rho0 U u, V = V0 (1 - u/U), e = u^2/2 must lie on the EOS.
    for (double u : {50.0, 400.0, 1500.0}) {
      const double U = mat.a0 + mat.s * u;
      const double rho = mat.rho0 / (1.0 - u / U);
      EXPECT_NEAR(evaluateEos(mat, rho, 0.5 * u * u).pressure, mat.rho0 * U * u,
                  1e-12 * mat.rho0 * U * u)
          << name << " u=" << u;
    }
  }
}

TEST(Eos, MieGruneisenFlagsTheLimitingCompression) {
  const MaterialParams al = materialPreset("Al");
  // eta - s(eta-1) vanishes at eta = s/(s-1) = 3.9586 for s = 1.338.
  const ThermoState beyond = evaluateEos(al, 4.0 * al.rho0, 1e5);
  EXPECT_FALSE(beyond.valid);
  EXPECT_LT(beyond.sound_speed2, 0.0);  // the time step rejects it too
  EXPECT_FALSE(mieGruneisen(al.rho0, al.a0, al.Gamma0, al.s, 10.0 * al.rho0, 0.0).valid);
  const ThermoState before = evaluateEos(al, 3.9 * al.rho0, 1e5);
  EXPECT_TRUE(before.valid);
  EXPECT_GT(before.sound_speed2, 0.0);
}

TEST(Eos, NeoHookeanVolumetricPressure) {
  const MaterialParams steel = materialPreset("Steel-hyper");
  const double kappa = bulkModulusNeoHookean(steel);
  for (double J : {0.6, 0.9, 1.0, 1.2, 1.7}) {
    const double rho = steel.rho0 / J;
    const ThermoState state = evaluateEos(steel, rho, 1e4);
    ASSERT_TRUE(state.valid);
    const double p_hand = -0.5 * kappa * ((J - 1.0) + std::log(J) / J);
    EXPECT_NEAR(state.pressure, p_hand, 1e-14 * kappa) << "J=" << J;
    EXPECT_EQ(state.pressure, evaluateEos(steel, rho, 0.0).pressure);  // independent of e
    EXPECT_NEAR(state.sound_speed2, finiteDifferenceSoundSpeed2(steel, rho, 1e4),
                1e-6 * state.sound_speed2)
        << "J=" << J;
  }
  // Small strain: a^2 = kappa/rho0.
  EXPECT_NEAR(evaluateEos(steel, steel.rho0, 0.0).sound_speed2, kappa / steel.rho0,
              1e-14 * kappa / steel.rho0);
}

// ---------------------------------------------------------------- hypo-elastic

// Pure spin L = omega K (v = omega n x X) for a time theta/omega in N steps.
// The exact solution of dS/dt = W S - S W is R S0 R^T. The Hughes-Winget
// rotation is the Cayley transform of the spin: exactly orthogonal, with a
// phase error of theta^3 / (12 N^2) (second order in dt): about 1e-8 for
// theta = 0.5, N = 1000. The invariants are kept to round-off.
SymMat3 spinStress(const SymMat3& S0, const Vec3& axis, double omega, double theta, int steps,
                   double mu) {
  const Mat3 L = omega * crossMatrix((1.0 / norm(axis)) * axis);
  const double dt = theta / (omega * steps);
  SymMat3 S = S0;
  for (int n = 0; n < steps; ++n) S = jaumannUpdate(S, L, mu, dt);
  return S;
}

TEST(HypoElastic, RigidSpinRotatesTheDeviatorAndKeepsItsInvariants) {
  const SymMat3 S0 = sampleDeviator(2e8);
  const Vec3 axis{1.0, 2.0, 3.0};
  const double omega = 1e3, theta = 0.5;
  const SymMat3 exact = conjugate(rotation(axis, theta), S0);
  const SymMat3 S1000 = spinStress(S0, axis, omega, theta, 1000, 27.6e9);
  const SymMat3 S2000 = spinStress(S0, axis, omega, theta, 2000, 27.6e9);
  const double error1000 = relativeError(S1000, exact);
  const double error2000 = relativeError(S2000, exact);
  EXPECT_LT(error1000, 1e-7);
  EXPECT_GT(error1000, 1e-12);  // sanity: the comparison is not vacuous
  // Second order in dt: halving the step quarters the error.
  EXPECT_NEAR(error1000 / error2000, 4.0, 0.1);
  // Deviatoric to round-off; a spin does no work, so mu must not matter.
  EXPECT_LT(std::fabs(trace(S1000)), 1e-14 * norm(S1000));
  const SymMat3 S_no_mu = spinStress(S0, axis, omega, theta, 1000, 0.0);
  EXPECT_EQ(relativeError(S_no_mu, S1000), 0.0);
  // Invariants of S: unchanged to round-off after 1000 rotations.
  EXPECT_LT(std::fabs(secondInvariant(S1000) / secondInvariant(S0) - 1.0), 1e-12);
  EXPECT_LT(std::fabs(det(S1000) / det(S0) - 1.0), 1e-12);
}

TEST(MathHelpers, GeneralInverse) {
  Mat3 a = zeroMat();
  const double values[3][3] = {{2.0, -1.0, 0.5}, {0.3, 1.5, -0.7}, {1.1, 0.2, 3.0}};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) a.m[i][j] = values[i][j];
  const Mat3 product = a * inverse(a);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) EXPECT_NEAR(product.m[i][j], i == j ? 1.0 : 0.0, 1e-15);
}

TEST(HypoElastic, OneStepOfStretchAndShearFromRest) {
  const double mu = 27.6e9, dt = 1e-7;
  // Uniaxial stretch rate d: D0 = d diag(2/3, -1/3, -1/3), S = 2 mu dt D0.
  const double d = 1e3;
  Mat3 L = zeroMat();
  L.m[0][0] = d;
  const SymMat3 stretched = jaumannUpdate(SymMat3{0, 0, 0, 0, 0, 0}, L, mu, dt);
  EXPECT_NEAR(stretched.xx, (4.0 / 3.0) * mu * d * dt, 1e-15 * mu * d * dt);
  EXPECT_NEAR(stretched.yy, -(2.0 / 3.0) * mu * d * dt, 1e-15 * mu * d * dt);
  EXPECT_NEAR(stretched.zz, -(2.0 / 3.0) * mu * d * dt, 1e-15 * mu * d * dt);
  // Simple shear, convention L_ij = dV_i/dx_j: only L_xy = gdot (V_x = gdot y).
  // Then D_xy = gdot/2 and, from rest, S_xy = 2 mu D_xy dt = mu gdot dt; the
  // spin terms vanish on S = 0, so every other entry is exactly zero.
  const double gdot = 2e3;
  L = zeroMat();
  L.m[0][1] = gdot;
  const SymMat3 sheared = jaumannUpdate(SymMat3{0, 0, 0, 0, 0, 0}, L, mu, dt);
  EXPECT_NEAR(sheared.xy, mu * gdot * dt, 1e-15 * mu * gdot * dt);
  EXPECT_EQ(sheared.xx, 0.0);
  EXPECT_EQ(sheared.yy, 0.0);
  EXPECT_EQ(sheared.zz, 0.0);
  EXPECT_EQ(sheared.yz, 0.0);
  EXPECT_EQ(sheared.xz, 0.0);
}

// Simple shear L_xy = gdot integrated to shear gamma = gdot t. With the
// Jaumann rate, a = S_xx = -S_yy and b = S_xy obey da/dgamma = b,
// db/dgamma = mu - a, so b = mu sin(gamma), a = mu (1 - cos(gamma)) (the
// classical Jaumann result; a wrong sign of W would flip a). Small strain:
// S_xy = mu gamma to O(gamma^3). Explicit Euler error ~ gamma^2/(2N) mu.
SymMat3 simpleShear(double mu, double gamma, int steps) {
  const double gdot = 1e3;
  Mat3 L = zeroMat();
  L.m[0][1] = gdot;
  const double dt = gamma / (gdot * steps);
  SymMat3 S{0, 0, 0, 0, 0, 0};
  for (int n = 0; n < steps; ++n) S = jaumannUpdate(S, L, mu, dt);
  return S;
}

TEST(HypoElastic, SimpleShearFollowsTheJaumannSolution) {
  const double mu = 27.6e9;
  const SymMat3 small = simpleShear(mu, 1e-3, 100);
  EXPECT_NEAR(small.xy, mu * 1e-3, 1e-6 * mu * 1e-3);
  // S_xx = mu gamma^2/2 at second order; explicit Euler gives (1 - 1/N) of it.
  EXPECT_NEAR(small.xx, 0.5 * mu * 1e-6, 0.02 * 0.5 * mu * 1e-6);
  const double gamma = 1.0;
  const SymMat3 large = simpleShear(mu, gamma, 10000);  // error ~ 5e-5 mu
  EXPECT_NEAR(large.xy, mu * std::sin(gamma), 1e-4 * mu);
  EXPECT_NEAR(large.xx, mu * (1.0 - std::cos(gamma)), 1e-4 * mu);
  EXPECT_NEAR(large.yy, -mu * (1.0 - std::cos(gamma)), 1e-4 * mu);
  EXPECT_LT(std::fabs(large.zz), 1e-14 * mu);
  EXPECT_EQ(large.yz, 0.0);
  EXPECT_EQ(large.xz, 0.0);
}

TEST(HypoElastic, RadialReturnLandsOnTheYieldSurface) {
  const double Y0 = 3e8;
  const double radius = std::sqrt(2.0 / 3.0) * Y0;
  for (double factor : {1.0000001, 1.5, 10.0, 1e4}) {
    const SymMat3 trial = sampleDeviator(1.0);
    const SymMat3 scaled = (factor * radius / norm(trial)) * trial;
    const ReturnMapResult result = radialReturn(scaled, Y0);
    EXPECT_TRUE(result.yielded) << factor;
    EXPECT_NEAR(norm(result.S), radius, 1e-14 * radius) << factor;
    // Radial: the direction of the trial deviator is kept.
    EXPECT_LT(norm(result.S - (1.0 / factor) * scaled), 1e-14 * radius) << factor;
  }
  for (double factor : {0.0, 0.3, 0.999999}) {
    const SymMat3 inside = (factor * radius / norm(sampleDeviator(1.0))) * sampleDeviator(1.0);
    const ReturnMapResult result = radialReturn(inside, Y0);
    EXPECT_FALSE(result.yielded) << factor;
    EXPECT_EQ(result.S.xx, inside.xx);
    EXPECT_EQ(result.S.yy, inside.yy);
    EXPECT_EQ(result.S.zz, inside.zz);
    EXPECT_EQ(result.S.xy, inside.xy);
    EXPECT_EQ(result.S.yz, inside.yz);
    EXPECT_EQ(result.S.xz, inside.xz);
  }
}

// ---------------------------------------------------------------- Neo-Hookean

struct NeoHookeanModuli {
  double mu, kappa;
};
NeoHookeanModuli moduli(const char* name) {
  const MaterialParams mat = materialPreset(name);
  return {shearModulus(mat), bulkModulusNeoHookean(mat)};
}

TEST(NeoHookean, UniaxialStretchMatchesTheClosedForm) {
  const auto [mu, kappa] = moduli("Be-hyper");
  for (double lambda : {0.7, 0.9, 1.0, 1.1, 1.5}) {
    // F = diag(lambda, 1, 1): B = diag(lambda^2, 1, 1), J = lambda, det B = lambda^2,
    // Bbar = lambda^{-2/3} B, dev(Bbar) = lambda^{-2/3} (lambda^2 - 1) diag(2/3, -1/3, -1/3).
    const Mat3 F{{{lambda, 0, 0}, {0, 1, 0}, {0, 0, 1}}};
    const SymMat3 B = pushForward(F, identitySym());
    const double J = lambda;
    const double p = -0.5 * kappa * ((J - 1.0) + std::log(J) / J);
    const double shear = mu / J * std::pow(lambda, -2.0 / 3.0) * (lambda * lambda - 1.0);
    const SymMat3 sigma = neoHookeanStress(B, J, mu, kappa);
    const double tol = 1e-13 * (kappa + mu);
    EXPECT_NEAR(sigma.xx, -p + (2.0 / 3.0) * shear, tol) << lambda;
    EXPECT_NEAR(sigma.yy, -p - (1.0 / 3.0) * shear, tol) << lambda;
    EXPECT_NEAR(sigma.zz, -p - (1.0 / 3.0) * shear, tol) << lambda;
    EXPECT_EQ(sigma.xy, 0.0);
    EXPECT_EQ(sigma.yz, 0.0);
    EXPECT_EQ(sigma.xz, 0.0);
    if (lambda > 1.0) {
      EXPECT_GT(sigma.xx, 0.0) << "tension positive (docs/method.md §A1)";
    } else if (lambda < 1.0) {
      EXPECT_LT(sigma.xx, 0.0);
    }
  }
}

TEST(NeoHookean, SimpleShear) {
  const auto [mu, kappa] = moduli("Steel-hyper");
  for (double g : {0.01, 0.5, 2.0}) {
    // F = I + g e_x (x) e_y: J = 1, p = 0, B = [[1+g^2, g, 0], [g, 1, 0], [0, 0, 1]].
    const Mat3 F{{{1, g, 0}, {0, 1, 0}, {0, 0, 1}}};
    const SymMat3 B = pushForward(F, identitySym());
    const PressureDeviator split = neoHookeanPressureDeviator(B, 1.0, mu, kappa);
    EXPECT_EQ(split.pressure, 0.0);
    const SymMat3 sigma = neoHookeanStress(B, 1.0, mu, kappa);
    const double tol = 1e-14 * mu * (1.0 + g * g);
    EXPECT_NEAR(sigma.xy, mu * g, tol) << g;
    EXPECT_NEAR(sigma.xx - sigma.yy, mu * g * g, tol) << g;
    EXPECT_NEAR(sigma.yy, -mu * g * g / 3.0, tol) << g;
    EXPECT_NEAR(sigma.zz, sigma.yy, tol) << g;
    EXPECT_EQ(sigma.yz, 0.0);
    EXPECT_EQ(sigma.xz, 0.0);
  }
}

TEST(NeoHookean, RigidRotationIsStressFreeAndStressIsObjective) {
  const auto [mu, kappa] = moduli("Be-hyper");
  const Mat3 R = rotation({-1.0, 0.5, 2.0}, 2.3);
  const SymMat3 sigma_R = neoHookeanStress(pushForward(R, identitySym()), 1.0, mu, kappa);
  EXPECT_LT(maxAbs(sigma_R), 1e-12 * mu);
  // Superposed rotation of a deformed state: B -> R B R^T gives sigma -> R sigma R^T.
  const Mat3 F{{{1.2, 0.3, -0.1}, {0.05, 0.9, 0.2}, {-0.2, 0.1, 1.1}}};
  const SymMat3 B = pushForward(F, identitySym());
  const double J = det(F);
  const SymMat3 sigma = neoHookeanStress(B, J, mu, kappa);
  const SymMat3 sigma_rotated = neoHookeanStress(pushForward(R, B), J, mu, kappa);
  EXPECT_LT(norm(sigma_rotated - conjugate(R, sigma)), 1e-13 * (mu + kappa));
  // Pure volume change B = c I carries no deviator, whatever J is passed.
  EXPECT_LT(maxAbs(neoHookeanDeviator(identitySym(1.3), 1.14, mu)), 1e-14 * mu);
  // The split and the EOS kind agree on the pressure.
  const MaterialParams be = materialPreset("Be-hyper");
  const PressureDeviator split = neoHookeanPressureDeviator(B, J, mu, kappa);
  EXPECT_EQ(split.pressure, evaluateEos(be, be.rho0 / J, 0.0).pressure);
  EXPECT_LT(norm(split.S + identitySym(-split.pressure) - sigma), 1e-15 * (mu + kappa));
}

TEST(NeoHookean, PushForwardComposesDeformations) {
  const Mat3 F_prev{{{1.1, 0.2, 0.0}, {-0.1, 0.95, 0.3}, {0.05, 0.0, 1.02}}};
  const Mat3 F{{{0.98, -0.04, 0.01}, {0.03, 1.01, -0.02}, {0.0, 0.05, 0.99}}};
  const SymMat3 B_prev = pushForward(F_prev, identitySym());
  const Mat3 F_total = F * F_prev;
  const SymMat3 expected = symPart(F_total * transpose(F_total));
  const SymMat3 B = pushForward(F, B_prev);
  EXPECT_LT(relativeError(B, expected), 1e-14);
  EXPECT_NEAR(det(B), det(F_total) * det(F_total), 1e-14);
}

// ---------------------------------------------------------------- sound speeds

TEST(ElasticWaves, TransverseAndLongitudinalSpeeds) {
  // Small strain, at rho0: aL^2 = (lambda + 2 mu)/rho0 = E (1-nu)/((1+nu)(1-2nu) rho0),
  // which is E/rho0 for nu = 0 (steel: aL = 5000 m/s).
  for (const char* name : {"Steel-hyper", "Be-hyper"}) {
    const MaterialParams mat = materialPreset(name);
    const double E = mat.young, nu = mat.poisson, mu = shearModulus(mat);
    const double a2 = evaluateEos(mat, mat.rho0, 0.0).sound_speed2;
    const double aL2 = longitudinalSoundSpeed2(a2, mu, mat.rho0);
    const double p_wave = E * (1.0 - nu) / ((1.0 + nu) * (1.0 - 2.0 * nu));
    EXPECT_NEAR(aL2, p_wave / mat.rho0, 1e-14 * aL2) << name;
    EXPECT_NEAR(transverseSoundSpeed2(mu, mat.rho0), E / (2.0 * (1.0 + nu) * mat.rho0), 1e-14 * aL2)
        << name;
  }
  EXPECT_NEAR(
      std::sqrt(longitudinalSoundSpeed2(
          evaluateEos(materialPreset("Steel-hyper"), 8000.0, 0.0).sound_speed2, 1e11, 8000.0)),
      5000.0, 1e-10);
  const MaterialParams al = materialPreset("Al");
  EXPECT_DOUBLE_EQ(longitudinalSoundSpeed2(al.a0 * al.a0, al.mu, al.rho0),
                   al.a0 * al.a0 + 4.0 / 3.0 * 27.6e9 / 2785.0);
}

// ---------------------------------------------------------------- presets

TEST(MaterialPresets, NumbersOfProblemsMd) {
  const MaterialParams al = materialPreset("Al");
  EXPECT_EQ(al.eos, EosKind::MieGruneisen);
  EXPECT_EQ(al.strength, StrengthKind::HypoElastic);
  EXPECT_DOUBLE_EQ(al.rho0, 2785.0);
  EXPECT_DOUBLE_EQ(al.a0, 5328.0);
  EXPECT_DOUBLE_EQ(al.Gamma0, 2.0);
  EXPECT_DOUBLE_EQ(al.s, 1.338);
  EXPECT_DOUBLE_EQ(al.mu, 27.6e9);
  EXPECT_DOUBLE_EQ(al.yield_stress, 3e8);
  EXPECT_DOUBLE_EQ(shearModulus(al), 27.6e9);

  const MaterialParams be = materialPreset("Be-hypo");
  EXPECT_EQ(be.eos, EosKind::MieGruneisen);
  EXPECT_EQ(be.strength, StrengthKind::HypoElastic);
  EXPECT_DOUBLE_EQ(be.rho0, 1845.0);
  EXPECT_DOUBLE_EQ(be.a0, 12870.0);
  EXPECT_DOUBLE_EQ(be.Gamma0, 2.0);
  EXPECT_DOUBLE_EQ(be.s, 1.124);
  EXPECT_DOUBLE_EQ(be.mu, 151.9e9);
  EXPECT_DOUBLE_EQ(be.yield_stress, 330e6);

  const MaterialParams steel = materialPreset("Steel-hyper");
  EXPECT_EQ(steel.eos, EosKind::NeoHookean);
  EXPECT_EQ(steel.strength, StrengthKind::NeoHookean);
  EXPECT_DOUBLE_EQ(steel.young, 200e9);
  EXPECT_DOUBLE_EQ(steel.poisson, 0.0);
  EXPECT_DOUBLE_EQ(steel.rho0, 8000.0);
  EXPECT_DOUBLE_EQ(shearModulus(steel), 100e9);
  EXPECT_DOUBLE_EQ(bulkModulusNeoHookean(steel), 200e9 / 3.0);

  const MaterialParams be_hyper = materialPreset("Be-hyper");
  EXPECT_EQ(be_hyper.eos, EosKind::NeoHookean);
  EXPECT_EQ(be_hyper.strength, StrengthKind::NeoHookean);
  EXPECT_DOUBLE_EQ(be_hyper.young, 3.1827e11);
  EXPECT_DOUBLE_EQ(be_hyper.poisson, 0.0539);
  EXPECT_DOUBLE_EQ(be_hyper.rho0, 1845.0);
  // kappa = lambda + 2/3 mu = E / (3 (1 - 2 nu)), an independent identity.
  EXPECT_NEAR(bulkModulusNeoHookean(be_hyper), 3.1827e11 / (3.0 * (1.0 - 2.0 * 0.0539)),
              1e-14 * 3.1827e11);

  const MaterialParams gas = materialPreset("Gas");
  EXPECT_EQ(gas.eos, EosKind::IdealGas);
  EXPECT_EQ(gas.strength, StrengthKind::None);
  EXPECT_DOUBLE_EQ(gas.gamma, 1.4);
  EXPECT_EQ(shearModulus(gas), 0.0);
}

TEST(MaterialPresets, UnknownNameThrows) {
  EXPECT_THROW(materialPreset("Copper"), std::invalid_argument);
  EXPECT_THROW(materialPreset(""), std::invalid_argument);
}

}  // namespace
}  // namespace lagremap
