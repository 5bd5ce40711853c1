// Strain-hardening plasticity of docs/method.md §A7 (kernels/constitutive.hpp):
// the radial return with an equivalent plastic strain eps_p, against the
// analytic hardening curves of proportional paths (uniaxial strain, pure
// shear), the Johnson-Cook rate and temperature factors at steady flow,
// simple shear with spin, objectivity, and the perfect model's old bits.
// The device functions are inline, so the tests call them on the host.
#include <gtest/gtest.h>

#include <cmath>

#include "data/math.hpp"
#include "kernels/constitutive.hpp"
#include "src/materials.hpp"

namespace lagremap {
namespace {

constexpr double kMu = 46.0e9;  // copper's shear modulus (E = 117 GPa, nu = 0.27)
constexpr double kY0 = 0.4e9;

MaterialParams hardeningSolid(HardeningKind kind) {
  MaterialParams m = materialPreset("Al");
  m.mu = kMu;
  m.yield_stress = kY0;
  m.hardening = kind;
  return m;
}

// von Mises equivalent stress q = sqrt(3/2) |S|.
double equivalentStress(const SymMat3& S) {
  return std::sqrt(1.5) * norm(S);
}

struct Path {
  SymMat3 S{0, 0, 0, 0, 0, 0};
  double eps_p = 0.0;
};

// n steps of length dt of a constant velocity gradient: the Jaumann update
// and the return, as a cell's stage does them (temperature t_star).
Path load(const MaterialParams& m, const Mat3& grad_v, double dt, int n, double t_star = 0.0) {
  Path path;
  for (int i = 0; i < n; ++i) {
    const SymMat3 trial = jaumannUpdate(path.S, grad_v, m.mu, dt);
    const PlasticUpdate update = plasticReturn(trial, m, path.eps_p, dt, t_star);
    path.S = update.S;
    path.eps_p = update.eps_p;
  }
  return path;
}

// The equivalent plastic strain of a proportional path of total equivalent
// strain eps_eq under linear hardening: eps_eq = q / 3 mu + eps_p with
// q = Y0 + H eps_p once it yields.
double linearHardeningStrain(double eps_eq, double H) {
  const double elastic_limit = kY0 / (3.0 * kMu);
  return eps_eq > elastic_limit ? (eps_eq - elastic_limit) / (1.0 + H / (3.0 * kMu)) : 0.0;
}

Mat3 uniaxialStrainRate(double rate) {
  return {{{rate, 0.0, 0.0}, {0.0, 0.0, 0.0}, {0.0, 0.0, 0.0}}};
}

TEST(Hardening, UniaxialStrainFollowsTheLinearHardeningCurve) {
  for (double H : {0.0, 0.1e9, 2.0e9}) {
    MaterialParams m = hardeningSolid(HardeningKind::Linear);
    m.hardening_modulus = H;
    const double rate = 1e4, dt = 1e-8;  // equivalent strain 2/3 rate dt a step
    for (int n : {10, 100, 1000}) {
      const Path path = load(m, uniaxialStrainRate(rate), dt, n);
      const double eps_eq = 2.0 / 3.0 * rate * dt * n;
      const double eps_p = linearHardeningStrain(eps_eq, H);
      EXPECT_NEAR(path.eps_p, eps_p, 1e-12 + 1e-9 * eps_p) << "H " << H << " n " << n;
      const double q = eps_p > 0.0 ? kY0 + H * eps_p : 3.0 * kMu * eps_eq;
      EXPECT_NEAR(equivalentStress(path.S), q, 1e-9 * q) << "H " << H << " n " << n;
    }
  }
}

TEST(Hardening, PureShearFollowsTheLinearHardeningCurve) {
  MaterialParams m = hardeningSolid(HardeningKind::Linear);
  m.hardening_modulus = 0.5e9;
  const double gamma_rate = 1e4, dt = 1e-8;
  // symmetric: no spin, so the path stays proportional
  const Mat3 grad_v{{{0.0, 0.5 * gamma_rate, 0.0}, {0.5 * gamma_rate, 0.0, 0.0}, {0, 0, 0}}};
  const int n = 2000;
  const Path path = load(m, grad_v, dt, n);
  const double eps_eq = gamma_rate * dt * n / std::sqrt(3.0);
  const double eps_p = linearHardeningStrain(eps_eq, m.hardening_modulus);
  EXPECT_NEAR(path.eps_p, eps_p, 1e-9 * eps_p);
  // the shear stress of the surface: tau = q / sqrt(3)
  EXPECT_NEAR(path.S.xy, (kY0 + m.hardening_modulus * eps_p) / std::sqrt(3.0), 1e-9 * kY0);
}

TEST(Hardening, SimpleShearWithSpinStaysOnTheHardeningCurve) {
  // L = gamma_rate e_x (x) e_y: the Jaumann spin turns S, so eps_p runs a
  // little behind the proportional curve (by O(gamma^2)), and the return
  // still lands on the surface Y0 + H eps_p at every step.
  MaterialParams m = hardeningSolid(HardeningKind::Linear);
  m.hardening_modulus = 0.5e9;
  const double gamma_rate = 1e4, dt = 1e-8;
  const Mat3 grad_v{{{0.0, gamma_rate, 0.0}, {0.0, 0.0, 0.0}, {0.0, 0.0, 0.0}}};
  const int n = 3000;  // gamma = 0.3
  const Path path = load(m, grad_v, dt, n);
  const double gamma = gamma_rate * dt * n;
  const double eps_p = linearHardeningStrain(gamma / std::sqrt(3.0), m.hardening_modulus);
  EXPECT_NEAR(path.eps_p, eps_p, 0.02 * eps_p);
  EXPECT_NEAR(equivalentStress(path.S), kY0 + m.hardening_modulus * path.eps_p, 1e-9 * kY0);
  EXPECT_GT(path.S.xy, 0.0);
}

TEST(Hardening, JohnsonCookWithLinearStrainTermIsLinearHardening) {
  MaterialParams linear = hardeningSolid(HardeningKind::Linear);
  linear.hardening_modulus = 0.3e9;
  MaterialParams jc = hardeningSolid(HardeningKind::JohnsonCook);
  jc.jc_B = 0.3e9;
  jc.jc_n = 1.0;
  jc.jc_C = 0.0;
  const Path a = load(linear, uniaxialStrainRate(1e4), 1e-8, 1500);
  const Path b = load(jc, uniaxialStrainRate(1e4), 1e-8, 1500);
  EXPECT_NEAR(b.eps_p, a.eps_p, 1e-10 * a.eps_p);
  EXPECT_LT(norm(b.S - a.S), 1e-10 * norm(a.S));
}

TEST(Hardening, JohnsonCookLandsOnItsSurfaceForFractionalExponents) {
  // n < 1: an infinite slope at eps_p = 0, where Newton alone would fail
  MaterialParams jc = hardeningSolid(HardeningKind::JohnsonCook);
  jc.jc_B = 0.29e9;
  jc.jc_n = 0.31;
  jc.jc_C = 0.025;
  jc.jc_rate0 = 1.0;
  const double dt = 1e-8;
  Path path;
  for (int i = 0; i < 800; ++i) {
    const SymMat3 trial = jaumannUpdate(path.S, uniaxialStrainRate(1e4), jc.mu, dt);
    const PlasticUpdate update = plasticReturn(trial, jc, path.eps_p, dt, 0.0);
    if (update.yielded) {
      const double d_eps = update.eps_p - path.eps_p;
      const double yield = yieldPoint(jc, path.eps_p, d_eps, dt, 0.0).stress;
      ASSERT_NEAR(equivalentStress(update.S), yield, 1e-10 * yield) << "step " << i;
      ASSERT_GT(d_eps, 0.0);
    }
    path.S = update.S;
    path.eps_p = update.eps_p;
  }
  EXPECT_GT(path.eps_p, 0.01);
}

TEST(Hardening, JohnsonCookRateFactorAtSteadyFlow) {
  // B = 0: no strain hardening, so the stress settles where the plastic rate
  // is the whole equivalent strain rate, q = A (1 + C ln(rate_eq / rate0))
  MaterialParams jc = hardeningSolid(HardeningKind::JohnsonCook);
  jc.jc_C = 0.03;
  jc.jc_rate0 = 1.0;
  for (double rate : {1e2, 1e4}) {
    const double dt = 0.05 * kY0 / (kMu * rate);  // yield within 20 steps
    const Path path = load(jc, uniaxialStrainRate(rate), dt, 400);
    const double rate_eq = 2.0 / 3.0 * rate;
    const double expected = kY0 * (1.0 + jc.jc_C * std::log(rate_eq / jc.jc_rate0));
    EXPECT_NEAR(equivalentStress(path.S), expected, 1e-9 * expected) << rate;
  }
  // below the reference rate the factor is 1
  jc.jc_rate0 = 1e6;
  const Path slow = load(jc, uniaxialStrainRate(1e4), 1e-8, 400);
  EXPECT_NEAR(equivalentStress(slow.S), kY0, 1e-9 * kY0);
}

TEST(Hardening, JohnsonCookThermalFactorFromTheInternalEnergy) {
  MaterialParams jc = hardeningSolid(HardeningKind::JohnsonCook);
  jc.jc_m = 1.09;
  jc.room_temperature = 300.0;
  jc.melt_temperature = 1356.0;
  jc.specific_heat = 383.0;
  // T = T_room + e / c_v
  const double e = 383.0 * 0.5 * (1356.0 - 300.0);
  EXPECT_NEAR(homologousTemperature(jc, e), 0.5, 1e-15);
  EXPECT_EQ(homologousTemperature(jc, -1e5), 0.0);  // below the reference state
  EXPECT_EQ(homologousTemperature(jc, 1e12), 1.0);  // molten
  const double t_star = homologousTemperature(jc, e);
  const Path path = load(jc, uniaxialStrainRate(1e4), 1e-8, 600, t_star);
  const double expected = kY0 * (1.0 - std::pow(0.5, jc.jc_m));
  EXPECT_NEAR(equivalentStress(path.S), expected, 1e-9 * expected);
  // no specific heat: no softening
  jc.specific_heat = 0.0;
  EXPECT_EQ(homologousTemperature(jc, e), 0.0);
  // molten: no shear strength, the whole trial strain is plastic
  MaterialParams molten = hardeningSolid(HardeningKind::JohnsonCook);
  const SymMat3 trial = jaumannUpdate({0, 0, 0, 0, 0, 0}, uniaxialStrainRate(1e4), kMu, 1e-6);
  const PlasticUpdate update = plasticReturn(trial, molten, 0.0, 1e-6, 1.0);
  EXPECT_LT(norm(update.S), 1e-12 * norm(trial));
  EXPECT_NEAR(update.eps_p, equivalentStress(trial) / (3.0 * kMu), 1e-12);
}

TEST(Hardening, ObjectiveUnderARigidRotationOfThePath) {
  // the same loading seen in a frame turned by Q: S' = Q S Q^T, eps_p equal
  MaterialParams jc = hardeningSolid(HardeningKind::JohnsonCook);
  jc.jc_B = 0.29e9;
  jc.jc_n = 0.31;
  jc.jc_C = 0.025;
  const Mat3 grad_v{{{2e3, 5e3, -1e3}, {0.0, -4e3, 3e3}, {1e3, 0.0, 2e3}}};
  const double angle = 0.7;
  const Vec3 axis{1.0 / std::sqrt(3.0), 1.0 / std::sqrt(3.0), 1.0 / std::sqrt(3.0)};
  Mat3 K{{{0.0, -axis.z, axis.y}, {axis.z, 0.0, -axis.x}, {-axis.y, axis.x, 0.0}}};
  const Mat3 Q = identityMat() + std::sin(angle) * K + (1.0 - std::cos(angle)) * (K * K);
  const Mat3 grad_rotated = Q * grad_v * transpose(Q);
  const Path a = load(jc, grad_v, 1e-8, 500);
  const Path b = load(jc, grad_rotated, 1e-8, 500);
  EXPECT_GT(a.eps_p, 0.0);
  EXPECT_NEAR(b.eps_p, a.eps_p, 1e-11 * a.eps_p);
  const SymMat3 a_rotated = symPart(Q * fullMat(a.S) * transpose(Q));
  EXPECT_LT(norm(b.S - a_rotated), 1e-10 * norm(a.S));
}

TEST(Hardening, PerfectPlasticityKeepsTheRadialReturnBits) {
  MaterialParams perfect = hardeningSolid(HardeningKind::Perfect);
  const SymMat3 trial{3e8, -1e8, -2e8, 2.5e8, -0.7e8, 1.1e8};
  for (double scale : {0.3, 1.0, 1.7, 40.0}) {
    const SymMat3 S_trial = scale * trial;
    const ReturnMapResult old = radialReturn(S_trial, kY0);
    const PlasticUpdate update = plasticReturn(S_trial, perfect, 0.25, 1e-8, 0.0);
    EXPECT_EQ(update.yielded, old.yielded);
    EXPECT_EQ(update.S.xx, old.S.xx);
    EXPECT_EQ(update.S.yy, old.S.yy);
    EXPECT_EQ(update.S.zz, old.S.zz);
    EXPECT_EQ(update.S.xy, old.S.xy);
    EXPECT_EQ(update.S.yz, old.S.yz);
    EXPECT_EQ(update.S.xz, old.S.xz);
    // and counts the strain it took off: (q_trial - Y0) / 3 mu
    const double q = equivalentStress(S_trial);
    EXPECT_NEAR(update.eps_p, 0.25 + (old.yielded ? (q - kY0) / (3.0 * kMu) : 0.0), 1e-15);
  }
}

}  // namespace
}  // namespace lagremap
