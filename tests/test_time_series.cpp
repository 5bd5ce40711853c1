// The half period of a history from a fitted sinusoid (src/time_series.hpp),
// the `beam`'s check: exact on a pure sinusoid with an offset, and within 1%
// when a higher mode and the jumps of a cell-based measure are added.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "../src/time_series.hpp"

using namespace lagremap;

namespace {
constexpr double kPi = 3.14159265358979323846;

TimeSeries sampled(double half_period, double higher_mode, double jitter) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> jump(-jitter, jitter);
  TimeSeries series;
  double held = 0.0;
  for (int i = 0; i <= 1500; ++i) {
    const double t = 30e-6 * i / 1500.0;
    if (i % 40 == 0) held = jump(rng);  // a measure that jumps now and then
    const double y = 3.5e-3 * std::sin(kPi * t / half_period + 0.1) + 2e-4 +
                     higher_mode * std::sin(3.3 * kPi * t / half_period + 0.5) + held;
    series.emplace_back(t, y);
  }
  return series;
}
}  // namespace

TEST(TimeSeries, FittedHalfPeriodOfAPureSinusoidIsExact) {
  const double half_period = 14.9e-6;
  const double fitted = fittedHalfPeriod(sampled(half_period, 0.0, 0.0), 7e-6, 22e-6);
  EXPECT_NEAR(fitted, half_period, 1e-6 * half_period);
}

TEST(TimeSeries, FittedHalfPeriodToleratesAHigherModeAndJumps) {
  const double half_period = 14.9e-6;
  const double fitted = fittedHalfPeriod(sampled(half_period, 4e-4, 3e-4), 7e-6, 22e-6);
  EXPECT_NEAR(fitted, half_period, 0.01 * half_period);
}

TEST(TimeSeries, TooShortASeriesHasNoPeriod) {
  EXPECT_TRUE(std::isnan(fittedHalfPeriod({{0.0, 0.0}, {1.0, 1.0}}, 0.5, 2.0)));
}
