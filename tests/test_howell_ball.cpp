// Howell and Ball's stop of a collapsing rigid-plastic shell
// (src/howell_ball.hpp): their 50 / 78.1 mm for the beryllium shell at
// 417.1 m/s, the energy balance at the stop, the time to stop against a
// direct integration of the same motion, and the trend with the speed.
#include <gtest/gtest.h>

#include <cmath>

#include "src/howell_ball.hpp"

namespace lagremap {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kRho = 1845.0, kYield = 330e6, kRi = 0.08, kRo = 0.1;

TEST(HowellBall, BerylliumShellStopsAtFiftyAndSeventyEightMillimetres) {
  const ShellStop stop = howellBallStop(kRho, kYield, kRi, kRo, 417.1, true);
  EXPECT_NEAR(stop.inner_radius, 0.050, 1e-4);
  EXPECT_NEAR(stop.outer_radius, 0.0781, 1e-4);
  // incompressible: the shell's area is kept
  EXPECT_NEAR(stop.outer_radius * stop.outer_radius - stop.inner_radius * stop.inner_radius,
              kRo * kRo - kRi * kRi, 1e-15);
  // all the kinetic energy went into plastic work
  const double k0 = kPi * kRho * (kRi * 417.1) * (kRi * 417.1) * std::log(kRo / kRi);
  EXPECT_NEAR(howellBallWork(kYield, kRi, kRo, stop.inner_radius), k0, 1e-12 * k0);
}

TEST(HowellBall, StopTimeMatchesAStepByStepIntegration) {
  const double v0 = 417.1;
  const ShellStop stop = howellBallStop(kRho, kYield, kRi, kRo, v0, true);
  // da/dt = -sqrt((K0 - W(a)) / (pi rho ln(b / a))) / a, stepped until K0 - W <= 0
  const double k0 = kPi * kRho * (kRi * v0) * (kRi * v0) * std::log(kRo / kRi);
  const double B = kRo * kRo - kRi * kRi, dt = 1e-10;
  double a = kRi, t = 0.0;
  while (true) {
    auto rate = [&](double radius) {
      const double energy = k0 - howellBallWork(kYield, kRi, kRo, radius);
      if (energy <= 0.0) return 0.0;
      const double b = std::sqrt(radius * radius + B);
      return -std::sqrt(energy / (kPi * kRho * std::log(b / radius))) / radius;
    };
    const double k1 = rate(a), k2 = rate(a + 0.5 * dt * k1);
    if (k2 == 0.0) break;
    a += dt * k2;
    t += dt;
  }
  EXPECT_NEAR(a, stop.inner_radius, 2e-5);
  EXPECT_NEAR(t, stop.time, 0.01 * stop.time);
  EXPECT_GT(stop.time, 100e-6);  // the case's t_end (130 us) is just past it
  EXPECT_LT(stop.time, 130e-6);
}

TEST(HowellBall, FasterShellsGoFurtherAndAFastOneCloses) {
  double previous = kRi;
  for (double v0 : {100.0, 250.0, 417.1, 550.0}) {
    const ShellStop stop = howellBallStop(kRho, kYield, kRi, kRo, v0, true);
    EXPECT_LT(stop.inner_radius, previous) << v0;
    previous = stop.inner_radius;
  }
  EXPECT_EQ(howellBallStop(kRho, kYield, kRi, kRo, 5000.0, true).inner_radius, 0.0);
  // the paper's text's profile V0 r / Ri carries more energy: it goes further
  EXPECT_LT(howellBallStop(kRho, kYield, kRi, kRo, 250.0, false).inner_radius,
            howellBallStop(kRho, kYield, kRi, kRo, 250.0, true).inner_radius);
  EXPECT_THROW(howellBallStop(kRho, kYield, kRo, kRi, 250.0, true), std::invalid_argument);
}

}  // namespace
}  // namespace lagremap
