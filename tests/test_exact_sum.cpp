// ExactSum (src/exact_sum.hpp): the sums the problems' checks take over the
// ranks' cells are exact and do not depend on the order or the split.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "src/exact_sum.hpp"

namespace lagremap {
namespace {

double exactSum(const std::vector<double>& terms) {
  ExactSum sum;
  for (double term : terms) sum += term;
  return sum.value();
}

TEST(ExactSum, CancellationLosesNothing) {
  // floating point: 1e16 + 1 - 1e16 = 0
  EXPECT_EQ(exactSum({1e16, 1.0, -1e16}), 1.0);
  const double tiny = std::numeric_limits<double>::denorm_min();
  const double huge = std::numeric_limits<double>::max();
  EXPECT_EQ(exactSum({huge, tiny, -huge}), tiny);
  // the binary values of 0.1 + 0.2 - 0.3 sum to exactly 2^-55
  EXPECT_EQ(exactSum({0.1, 0.2, -0.3}), std::ldexp(1.0, -55));
  EXPECT_EQ(exactSum({}), 0.0);
  EXPECT_EQ(exactSum({-2.5}), -2.5);
  EXPECT_EQ(exactSum({huge, huge / 2, -huge}), huge / 2);
}

TEST(ExactSum, TheSameBitsInAnyOrderAndSplit) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  std::uniform_int_distribution<int> scale(-60, 60);
  std::vector<double> terms(20000);
  for (double& t : terms) t = std::ldexp(unit(rng), scale(rng));
  const double reference = exactSum(terms);
  // close to a careful sum (long double, sorted by magnitude)
  std::vector<double> sorted = terms;
  std::sort(sorted.begin(), sorted.end(),
            [](double a, double b) { return std::fabs(a) < std::fabs(b); });
  long double careful = 0.0L;
  for (double t : sorted) careful += t;
  EXPECT_NEAR(reference, double(careful), 1e-12 * std::fabs(double(careful)) + 1e-300);
  for (int trial = 0; trial < 5; ++trial) {
    std::shuffle(terms.begin(), terms.end(), rng);
    ASSERT_EQ(exactSum(terms), reference);
    // three "ranks" of unequal parts, combined
    ExactSum parts[3];
    for (std::size_t i = 0; i < terms.size(); ++i) parts[(i * 7 + trial) % 3] += terms[i];
    parts[2] += parts[0];
    parts[2] += parts[1];
    ASSERT_EQ(parts[2].value(), reference);
  }
}

TEST(ExactSum, ANonFiniteTermMakesItNaN) {
  EXPECT_TRUE(std::isnan(exactSum({1.0, std::numeric_limits<double>::quiet_NaN()})));
  EXPECT_TRUE(std::isnan(exactSum({1.0, std::numeric_limits<double>::infinity()})));
}

}  // namespace
}  // namespace lagremap
