// The exact elastic-plastic impact solution (src/exact_two_wave.hpp): the
// published 800 m/s aluminium states, its own Rankine-Hugoniot jump
// conditions at several speeds, the elastic limit, a purely elastic impact
// and an impact of two different solids.
#include <gtest/gtest.h>

#include <cmath>

#include "src/exact_two_wave.hpp"

namespace lagremap {
namespace {

// The aluminium of docs/verification.md §8.1 with p0 = 1e5 Pa (e0 = p0 / (rho0 Gamma0)).
ElasticPlasticSolid aluminium() {
  return {2785.0, 5328.0, 2.0, 1.338, 27.6e9, 3.0e8, 1e5 / (2785.0 * 2.0)};
}
ElasticPlasticSolid beryllium() {  // Be-hypo
  return {1845.0, 12870.0, 2.0, 1.124, 151.9e9, 330.0e6, 0.0};
}

// Residuals of mass, momentum and energy across the jump a -> b at speed U,
// each relative to the size of its terms.
void expectJump(const UniaxialState& a, const UniaxialState& b, double U) {
  const double mass_a = a.rho * (U - a.u), mass_b = b.rho * (U - b.u);
  EXPECT_NEAR(mass_a, mass_b, 1e-12 * std::fabs(mass_a));
  const double dP = -b.sigma_xx + a.sigma_xx, impulse = mass_a * (b.u - a.u);
  EXPECT_NEAR(dP, impulse, 1e-10 * std::fabs(dP));
  const double de = b.e - a.e;
  const double work = 0.5 * (-a.sigma_xx - b.sigma_xx) * (1.0 / a.rho - 1.0 / b.rho);
  EXPECT_NEAR(de, work, 1e-10 * std::fabs(work) + 1e-12 * std::fabs(b.e));
}

TEST(ExactTwoWave, PublishedAluminiumStatesAt800MetresPerSecond) {
  const ImpactSolution impact = solveImpact(aluminium(), aluminium(), 800.0);
  EXPECT_EQ(impact.u_interface, 400.0);  // symmetric
  const TwoWaveSolution& w = impact.target;
  ASSERT_TRUE(w.plastic_wave);
  EXPECT_NEAR(w.precursor_speed, 6490.0, 5.0);
  EXPECT_NEAR(w.precursor.sigma_xx, -0.636e9, 0.002e9);
  EXPECT_NEAR(w.precursor.u, 35.2, 0.05);
  EXPECT_NEAR(w.plastic_speed, 5909.0, 2.0);
  EXPECT_NEAR(w.plastic.sigma_xx, -6.637e9, 0.005e9);
  EXPECT_NEAR(w.plastic.p, 6.437e9, 0.005e9);
  EXPECT_NEAR(w.plastic.rho, 2985.6, 0.2);
  EXPECT_NEAR(w.plastic.u, 400.0, 1e-9);
}

TEST(ExactTwoWave, JumpsSatisfyRankineHugoniotAtEverySpeed) {
  for (double v : {100.0, 400.0, 800.0, 1200.0, 2400.0}) {
    SCOPED_TRACE(v);
    const TwoWaveSolution w = solveImpact(aluminium(), aluminium(), v).target;
    expectJump(w.initial, w.precursor, w.precursor_speed);
    if (w.plastic_wave) {
      expectJump(w.precursor, w.plastic, w.plastic_speed);
      EXPECT_LT(w.plastic_speed, w.precursor_speed);
      // at yield behind the plastic shock: S_xx = -2Y/3
      EXPECT_NEAR(w.plastic.sigma_xx + w.plastic.p, -2.0e8, 1e-3);
    }
    EXPECT_NEAR(w.plastic.u, 0.5 * v, 1e-9 * v);
  }
}

TEST(ExactTwoWave, ElasticLimitAndAnElasticImpact) {
  const ElasticPlasticSolid al = aluminium();
  const TwoWaveSolution strong = solveTwoWave(al, 400.0);
  // the precursor sits at the elastic limit: (4/3) mu ln(rho/rho0) = 2Y/3
  EXPECT_NEAR(strong.precursor.rho, al.rho0 * std::exp(al.yield_stress / (2.0 * al.mu)), 1e-9);
  EXPECT_NEAR(strong.precursor.sigma_xx + strong.precursor.p, -2.0e8, 1e-3);
  const TwoWaveSolution weak = solveTwoWave(al, 20.0);  // below the limit's 35 m/s
  EXPECT_FALSE(weak.plastic_wave);
  EXPECT_EQ(weak.precursor.rho, weak.plastic.rho);
  EXPECT_GT(weak.precursor.sigma_xx + weak.precursor.p, -2.0e8);
  expectJump(weak.initial, weak.plastic, weak.plastic_speed);
  // a weak elastic shock travels at the longitudinal sound speed
  const double c_l = std::sqrt(al.a0 * al.a0 + 4.0 / 3.0 * al.mu / al.rho0);
  EXPECT_NEAR(weak.plastic_speed, c_l, 0.01 * c_l);
}

TEST(ExactTwoWave, DifferentSolidsMatchStressAtTheInterface) {
  const ImpactSolution impact = solveImpact(aluminium(), beryllium(), 800.0);
  // beryllium is stiffer: the interface moves slower than half the flyer
  EXPECT_GT(impact.u_interface, 0.0);
  EXPECT_LT(impact.u_interface, 400.0);
  EXPECT_NEAR(impact.target.plastic.sigma_xx, impact.flyer.plastic.sigma_xx,
              1e-9 * std::fabs(impact.sigma_interface));
  EXPECT_NEAR(impact.target.plastic.u + impact.flyer.plastic.u, 800.0, 1e-9);
}

TEST(ExactTwoWave, RefusesImpossibleInput) {
  EXPECT_THROW(solveTwoWave(aluminium(), -1.0), std::invalid_argument);
  ElasticPlasticSolid bad = aluminium();
  bad.mu = 0.0;
  EXPECT_THROW(solveTwoWave(bad, 100.0), std::invalid_argument);
  EXPECT_THROW(solveTwoWave(aluminium(), NAN), std::invalid_argument);
  EXPECT_THROW(solveImpact(aluminium(), aluminium(), 0.0), std::invalid_argument);
}

}  // namespace
}  // namespace lagremap
