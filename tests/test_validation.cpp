// Long physics runs (ctest label "long"): the default resolutions of the
// problems, whose summary checks must all pass, and Sod's convergence over a
// decade of resolution.
#include <gtest/gtest.h>

#include <cmath>

#include "test_support.hpp"

namespace lagremap {
namespace {

TEST(Validation, DefaultProblemsPassTheirChecks) {
  for (const char* problem : {"sod", "sedov"}) {
    for (const char* order : {"1", "2"}) {
      const RunResult result =
          runProblem(testing::problemOptions(problem, {std::string("numerics.order=") + order}));
      ASSERT_FALSE(result.failed) << result.failure;
      for (const auto& check : result.checks) {
        std::printf("%s order %s: %-20s %.6g (reference %.6g, tolerance %.3g)\n", problem, order,
                    check.name.c_str(), check.value, check.reference, check.tolerance);
        EXPECT_TRUE(check.pass()) << problem << " order " << order << ": " << check.name;
      }
      EXPECT_LT(result.drift_energy, 1e-12);
      EXPECT_LT(result.drift_momentum, 1e-12);
    }
  }
}

// The flyer plate at 2000 cells, where the elastic precursor is resolved:
// every check of the exact two-wave solution, precursor included.
TEST(Validation, WilkinsTwoWaveStructure) {
  const RunResult result = runProblem(testing::problemOptions("wilkins", {}, 10.0));
  ASSERT_FALSE(result.failed) << result.failure;
  ASSERT_EQ(result.checks.size(), 4u);  // precursor + plastic velocity, stress, density
  for (const auto& check : result.checks) {
    std::printf("wilkins 2000 cells: %-20s %.6g (reference %.6g, tolerance %.3g)\n",
                check.name.c_str(), check.value, check.reference, check.tolerance);
    EXPECT_TRUE(check.pass()) << check.name;
  }
  EXPECT_LT(result.drift_energy, 1e-12);
}

// Planar Taylor impact at half resolution (100 x 20): final length within
// 0.05 m of the paper's 4.62 (measured 4.621; 4.605 at full resolution), the
// kinetic energy dissipated, and conservation to round-off.
TEST(Validation, TaylorImpactHalfResolution) {
  const RunResult result = runProblem(testing::problemOptions("taylor", {}, 0.5));
  ASSERT_FALSE(result.failed) << result.failure;
  for (const auto& check : result.checks) {
    std::printf("taylor 100x20: %-18s %.6g (reference %.6g, tolerance %.3g)\n", check.name.c_str(),
                check.value, check.reference, check.tolerance);
    EXPECT_TRUE(check.pass()) << check.name;
  }
  EXPECT_LT(result.drift_energy, 1e-12);
  EXPECT_LT(result.drift_momentum, 1e-12);
}

// The headline Lagrange-Remap case at half resolution (110 x 40): the bar in
// gas on the fixed mesh, length from the alpha = 0.5 contour near the paper's
// 4.63, every total conserved through 3000 remaps.
TEST(Validation, TaylorRemapHalfResolution) {
  const RunResult result = runProblem(testing::problemOptions("taylor", {}, 0.5, "remap"));
  ASSERT_FALSE(result.failed) << result.failure;
  for (const auto& check : result.checks) {
    std::printf("taylor remap 110x40: %-18s %.6g (reference %.6g, tolerance %.3g)\n",
                check.name.c_str(), check.value, check.reference, check.tolerance);
    EXPECT_TRUE(check.pass()) << check.name;
  }
  EXPECT_LT(result.drift_mass, 1e-12);
  EXPECT_LT(result.drift_energy, 1e-12);
  EXPECT_LT(result.drift_momentum, 1e-12);
}

// The Neo-Hookean plate in its first bending mode: half period within 5% of
// the Timoshenko-corrected theory, energy conserved to round-off.
TEST(Validation, BeamBendingPeriod) {
  const RunResult result = runProblem(testing::problemOptions("beam"));
  ASSERT_FALSE(result.failed) << result.failure;
  ASSERT_EQ(result.checks.size(), 1u);
  std::printf("beam: half period %.4g s (reference %.4g)\n", result.checks[0].value,
              result.checks[0].reference);
  EXPECT_TRUE(result.checks[0].pass());
  EXPECT_LT(result.drift_energy, 1e-12);
  EXPECT_LT(result.drift_momentum, 1e-12);
}

TEST(Validation, SodConvergenceOverADecade) {
  for (int order : {1, 2}) {
    double previous = 0.0;
    for (int nx : {100, 200, 400, 800, 1600}) {
      const RunResult result = runProblem(testing::problemOptions(
          "sod", {"mesh.nx=" + std::to_string(nx), "numerics.order=" + std::to_string(order)}));
      ASSERT_FALSE(result.failed);
      const double error = result.checks.front().value;
      EXPECT_TRUE(result.checks.front().pass()) << "nx " << nx << " order " << order;
      if (previous > 0.0) {
        const double rate = std::log2(previous / error);
        std::printf("sod order %d: nx %4d  L1(rho) %.4e  observed order %.2f\n", order, nx, error,
                    rate);
        EXPECT_GT(rate, order == 2 ? 0.85 : 0.5);
      }
      previous = error;
    }
  }
}

}  // namespace
}  // namespace lagremap
