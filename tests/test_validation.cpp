// Long physics runs (ctest label "long"): the default resolutions of the
// problems, whose summary checks must all pass, and Sod's convergence over a
// decade of resolution.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

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

// The 3D copper rod's default case in both modes (docs/verification.md
// §8.10: about 5 minutes each on 2 threads): final length and mushroom
// radius inside the published band (lagrange 21.60 / 6.96 mm, remap
// 21.56 / 6.97 mm; before the limiters' continuation across open sides the
// lagrange radius fell 0.2 mm short), and the plastic strain of the
// impact face above 2 (2.73, 2.48).
TEST(Validation, RodDefaultCaseIsInThePublishedBand) {
  for (const char* mode : {"lagrange", "remap"}) {
    const RunResult result = runProblem(testing::problemOptions("rod", {}, 1.0, mode));
    ASSERT_FALSE(result.failed) << mode << ": " << result.failure;
    int applicable = 0;
    for (const auto& check : result.checks) {
      std::printf("rod %s: %-22s %.6g (reference %.6g, tolerance %.3g)\n", mode, check.name.c_str(),
                  check.value, check.reference, check.tolerance);
      if (check.name == "final_length" || check.name == "mushroom_radius") {
        EXPECT_TRUE(check.applies) << mode << " " << check.name;
        ++applicable;
      }
      if (check.name == "largest_plastic_strain") {
        EXPECT_GT(check.value, 2.0) << mode;
      }
      EXPECT_TRUE(!check.applies || check.pass()) << mode << ": " << check.name;
    }
    EXPECT_EQ(applicable, 2) << mode;
  }
}

// Every paper case and the rod at twice the default resolution (--scale 2),
// in both modes (the ball in remap mode only): every applicable check passes
// and the totals are conserved (docs/verification.md §5.1 lists the runs and
// their wall times: from 1 minute for the pile to several hours for the
// rod). One ctest entry per case.
class AtTwiceTheResolution : public ::testing::TestWithParam<std::pair<const char*, const char*>> {
};

TEST_P(AtTwiceTheResolution, PassesItsChecks) {
  const auto [problem, mode] = GetParam();
  const RunResult result = runProblem(testing::problemOptions(problem, {}, 2.0, mode));
  ASSERT_FALSE(result.failed) << problem << " " << mode << ": " << result.failure;
  for (const auto& check : result.checks) {
    std::printf("%s %s --scale 2: %-22s %.6g (reference %.6g, tolerance %.3g)%s\n", problem, mode,
                check.name.c_str(), check.value, check.reference, check.tolerance,
                check.applies ? "" : " n/a");
    EXPECT_TRUE(!check.applies || check.pass()) << problem << " " << mode << ": " << check.name;
  }
  EXPECT_LT(result.drift_mass, 1e-12);
  EXPECT_LT(result.drift_momentum, 1e-11);
  EXPECT_LT(result.drift_energy, 1e-11);
}

INSTANTIATE_TEST_SUITE_P(
    Validation, AtTwiceTheResolution,
    ::testing::Values(std::pair{"wilkins", "lagrange"}, std::pair{"wilkins", "remap"},
                      std::pair{"pile", "lagrange"}, std::pair{"pile", "remap"},
                      std::pair{"taylor", "lagrange"}, std::pair{"taylor", "remap"},
                      std::pair{"beam", "lagrange"}, std::pair{"beam", "remap"},
                      std::pair{"shell", "lagrange"}, std::pair{"shell", "remap"},
                      std::pair{"ball", "remap"}, std::pair{"rod", "lagrange"},
                      std::pair{"rod", "remap"}),
    [](const auto& info) { return std::string(info.param.first) + "_" + info.param.second; });

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

// The shell stops where Howell and Ball say at any speed, and its final
// speed check reads that: at V0 = 250, 300, 417.1 and 500 m/s in lagrange
// mode (t_end 160 us, after every one of their stops, 89-140 us) and at 250
// m/s in remap mode, every check applies and passes (final inward speed 0,
// 11.3, 0 and 6.1 m/s against 21.6; remap 0); a shell too soft in shear to
// stop there (mu / 1000) still fails final_inward_speed (67 m/s against
// 27.8). Before the bound was twice the elastic ringing speed, 300 m/s
// failed with 0.035 V0 against 1% of V0.
const Check& shellCheck(const RunResult& result, const std::string& name) {
  for (const Check& check : result.checks)
    if (check.name == name) return check;
  throw std::runtime_error("no check " + name);
}

TEST(Validation, ShellStopsWhereHowellBallSayAtEverySpeed) {
  // 500 m/s on the 30 x 180 mesh: the shell closes to half its radius, and
  // the 15 x 90 one stops it 3.1 mm early (0.9 mm at 30 x 180; 1.2 and 0.25
  // mm at 417.1 m/s), outside the 2 mm of the radii checks
  for (const auto& [v0, scale] :
       {std::pair<const char*, double>{"250", 1.0}, {"300", 1.0}, {"417.1", 1.0}, {"500", 2.0}}) {
    const RunResult result = runProblem(
        testing::problemOptions("shell", {std::string("shell.v0=") + v0, "t_end=1.6e-4"}, scale));
    ASSERT_FALSE(result.failed) << result.failure;
    for (const Check& check : result.checks) {
      std::printf("shell lagrange V0 = %s: %-22s %.6g (reference %.6g, tolerance %.3g)\n", v0,
                  check.name.c_str(), check.value, check.reference, check.tolerance);
      EXPECT_TRUE(check.counts()) << v0 << " " << check.name;
      EXPECT_TRUE(check.pass()) << v0 << " " << check.name;
    }
  }
  const RunResult remapped =
      runProblem(testing::problemOptions("shell", {"shell.v0=250"}, 0.5, "remap"));
  ASSERT_FALSE(remapped.failed) << remapped.failure;
  const Check remap_speed = shellCheck(remapped, "final_inward_speed");
  std::printf("shell remap V0 = 250: final_inward_speed %.6g (tolerance %.3g)\n", remap_speed.value,
              remap_speed.tolerance);
  EXPECT_TRUE(remap_speed.counts() && remap_speed.pass());

  const RunResult soft = runProblem(
      testing::problemOptions("shell", {"shell.v0=300", "be.mu=1.519e8", "t_end=1.6e-4"}));
  ASSERT_FALSE(soft.failed) << soft.failure;
  const Check soft_speed = shellCheck(soft, "final_inward_speed");
  std::printf("shell too soft to stop: final_inward_speed %.6g (tolerance %.3g)\n",
              soft_speed.value, soft_speed.tolerance);
  EXPECT_TRUE(soft_speed.counts());
  EXPECT_FALSE(soft_speed.pass());
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
