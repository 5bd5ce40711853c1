// The multi-material set-ups of docs/verification.md §8.5-8.7 in remap mode (the beryllium
// shell and plate in gas, the aluminium ball and plate in near-vacuum), each
// coarse and short: every total conserved to round-off (each material's mass
// too), volume fractions inside [0, 1] and summing to 1, a finite state, and
// the first sign of the problem's physics.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <tuple>
#include <vector>

#include "src/materials.hpp"
#include "test_support.hpp"

namespace lagremap {
namespace {

// Runs the problem in remap mode and checks what every remap run must keep.
RunResult runAndCheckRemap(const std::string& problem, const std::vector<std::string>& settings,
                           double scale) {
  const RunOptions options = testing::problemOptions(problem, settings, scale, "remap");
  const ProblemSetup setup = findProblem(problem).setup(options.config);
  const std::vector<double> masses0 = testing::initialTotals(setup).mass_k;
  RunResult result = runProblem(options);
  EXPECT_FALSE(result.failed) << problem << ": " << result.failure;
  if (result.failed) return result;
  std::printf("%-6s %5ld cells, %4ld steps: drift mass %.1e, momentum %.1e, energy %.1e\n",
              problem.c_str(), result.cells, result.steps, result.drift_mass, result.drift_momentum,
              result.drift_energy);
  EXPECT_LT(result.drift_mass, 1e-13) << problem;
  EXPECT_LT(result.drift_momentum, 1e-12) << problem;
  EXPECT_LT(result.drift_energy, 1e-12) << problem;
  const FinalFields& fields = result.fields;
  const Index n_cells = Index(fields.rho.extent(0));
  const int n_materials = int(fields.alpha.extent(1));
  std::vector<double> masses(std::size_t(n_materials), 0.0);
  double worst_sum = 0.0;
  long outside = 0, not_finite = 0;
  for (Index c = 0; c < n_cells; ++c) {
    double alpha_sum = 0.0;
    for (int k = 0; k < n_materials; ++k) {
      const double alpha = fields.alpha(c, k);
      outside += !(alpha >= 0.0 && alpha <= 1.0);
      alpha_sum += alpha;
      masses[std::size_t(k)] += fields.m_k(c, k);
      not_finite += !std::isfinite(fields.e_k(c, k)) || !std::isfinite(fields.p_k(c, k));
    }
    worst_sum = std::max(worst_sum, std::abs(alpha_sum - 1.0));
    not_finite += !std::isfinite(fields.rho(c)) || !std::isfinite(fields.p(c)) ||
                  !std::isfinite(fields.e(c)) || !std::isfinite(fields.v(c, 0)) ||
                  !std::isfinite(fields.v(c, 1)) || !std::isfinite(fields.v(c, 2));
  }
  EXPECT_EQ(outside, 0) << problem << ": volume fractions outside [0, 1]";
  EXPECT_LT(worst_sum, 1e-12) << problem << ": volume fractions do not sum to 1";
  EXPECT_EQ(not_finite, 0) << problem << ": NaN or infinite cell values";
  // Each material's mass: the remap conserves it to round-off but for the
  // traces below remap.alpha_floor (1e-10) that join their cell's main
  // material (measured: up to 2e-8 of the total mass moved, 4% of the ball's
  // near-vacuum gas).
  double total0 = 0.0;
  for (double mass : masses0) total0 += mass;
  for (int k = 0; k < n_materials; ++k) {
    EXPECT_LT(std::abs(masses[std::size_t(k)] - masses0[std::size_t(k)]), 1e-7 * total0)
        << problem << ": mass of material " << k;
  }
  for (const auto& [t, value] : fields.probe) {
    EXPECT_TRUE(std::isfinite(value)) << problem << ": probe at t = " << t;
  }
  return result;
}

const Check* findCheck(const RunResult& result, const std::string& name) {
  for (const Check& check : result.checks)
    if (check.name == name) return &check;
  return nullptr;
}

// The beryllium shell in gas (40 x 40, the first 40 us of 130): its inner
// surface, the equal-area radius of the gas inside, moves in from 80 mm as
// the collapse starts (Lagrange reference: 65.5 mm at 39 us).
TEST(RemapProblems, ShellInGasCollapsesAndConserves) {
  const RunResult result =
      runAndCheckRemap("shell", {"geometry.thickness=5.5e-3", "t_end=4e-5"}, 0.25);
  ASSERT_FALSE(result.failed);
  ASSERT_GT(result.fields.probe.size(), 2u);
  const double r0 = result.fields.probe.front().second, r1 = result.fields.probe.back().second;
  std::printf("shell: inner radius %.4f -> %.4f m\n", r0, r1);
  EXPECT_NEAR(r0, 0.08, 1e-3);
  EXPECT_LT(r1, 0.070);
  EXPECT_GT(r1, 0.060);
}

// The Neo-Hookean plate in gas (25 x 10 x 2, 4 us): its tip rises from 0 as
// the bending mode starts (tip speed 1.18 km/s), no faster than that.
TEST(RemapProblems, BeamPlateInGasStartsToBend) {
  const double t_end = 4e-6;
  const RunResult result = runAndCheckRemap("beam", {"t_end=4e-6"}, 0.25);
  ASSERT_FALSE(result.failed);
  const double y0 = result.fields.probe.front().second, y1 = result.fields.probe.back().second;
  std::printf("beam: tip displacement %.3e -> %.3e m\n", y0, y1);
  EXPECT_NEAR(y0, 0.0, 1e-12);
  EXPECT_GT(y1, 1e-3);
  EXPECT_LT(y1, 1182.0 * t_end);
}

// The plate's tip in remap mode (50 x 20 x 5) against the lagrange tip
// (100 x 10 x 10) at 6 us, near its first peak, when the end has turned by
// some 30 degrees: the remap measure, the centre of the end face from the
// cells whose interface normal points along the plate, turns with the end
// as the lagrange one does (the vertical cut through the end used before
// read about 2 mm, the end face's lower corner), and the plate, whose
// surface layers stretch along their normal (kernels/geometry.hpp
// isSolidBody), is nearly as stiff. Measured 3.59 against 4.42 mm (4.02 mm
// for the remap plate at 100 x 40 x 10): the lagrange plate keeps 0.88 of
// its kinetic energy over a half period since its free surfaces are no
// longer limited to first order (3.89 mm and 0.47 before), the remap plate
// 0.68, its surface layers being mixed cells.
TEST(RemapProblems, BeamTipFollowsTheLagrangeTip) {
  const RunResult remap = runAndCheckRemap("beam", {"t_end=6e-6"}, 0.5);
  ASSERT_FALSE(remap.failed);
  const RunResult lagrange = runProblem(testing::problemOptions("beam", {"t_end=6e-6"}));
  ASSERT_FALSE(lagrange.failed) << lagrange.failure;
  const double y_remap = remap.fields.probe.back().second;
  const double y_lagrange = lagrange.fields.probe.back().second;
  std::printf("beam tip at 6 us: remap %.3e m, lagrange %.3e m\n", y_remap, y_lagrange);
  EXPECT_NEAR(y_remap, y_lagrange, 0.2 * y_lagrange);
}

// The remap plate at twice the paper's resolution through its thickness (200
// x 80 cells in x-y; one cell in z: the plate fills the depth between its
// symmetry planes, so the 3D case of --scale 2 is this slab), to 11.9 us,
// past the largest deflection (7 us, 20 GPa of tension along the bent
// plate's lower face) and back towards the straight plate: it gives back
// its strain energy as kinetic energy (0.56 of the initial, 0.49 at the
// paper's 100 x 40) and no gas gets inside it. Before the diffusion tail of
// the gas inside the plate was a trace (remap.alpha_tail, docs/method.md
// §4.6), the relaxation inflated that tail where the plate is in tension,
// cracks opened from its lower face from 3 us on, and only 0.26 of the
// kinetic energy came back, with 9% of the plate's volume in gas.
TEST(RemapProblems, BeamPlateAtTwiceTheResolutionStaysWhole) {
  const std::vector<std::string> settings{"t_end=1.19e-5", "mesh.nx=200", "mesh.ny=80",
                                          "mesh.nz=1"};
  const RunOptions options = testing::problemOptions("beam", settings, 1.0, "remap");
  const testing::StateTotals initial =
      testing::initialTotals(findProblem("beam").setup(options.config));
  const RunResult result = runAndCheckRemap("beam", settings, 1.0);
  ASSERT_FALSE(result.failed);
  const FinalFields& fields = result.fields;
  double kinetic = 0.0, beryllium = 0.0, gas_inside = 0.0;
  for (Index c = 0; c < Index(fields.rho.extent(0)); ++c) {
    const double v2 = fields.v(c, 0) * fields.v(c, 0) + fields.v(c, 1) * fields.v(c, 1) +
                      fields.v(c, 2) * fields.v(c, 2);
    kinetic += 0.5 * fields.rho(c) * fields.vol(c) * v2;
    const double alpha = fields.alpha(c, 0);
    beryllium += alpha * fields.vol(c);
    if (alpha >= 0.5) gas_inside += (1.0 - alpha) * fields.vol(c);
  }
  std::printf("beam 200 x 80 at 11.9 us: kinetic energy %.3f of the initial, gas inside %.4f\n",
              kinetic / initial.kinetic, gas_inside / beryllium);
  EXPECT_GT(kinetic / initial.kinetic, 0.45);
  EXPECT_LT(gas_inside / beryllium, 0.06);
}

// The aluminium ball and plate in near-vacuum gas (37 x 50, 1 us): the ball
// hits the plate (at 50 ns) and slows down, and the momentum stays the ball's.
TEST(RemapProblems, BallHitsThePlateAndSlowsDown) {
  const double t_end = 1e-6;
  const RunResult result =
      runAndCheckRemap("ball", {"geometry.thickness=1e-4", "t_end=1e-6"}, 0.25);
  ASSERT_FALSE(result.failed);
  const double x0 = result.fields.probe.front().second, x1 = result.fields.probe.back().second;
  std::printf("ball: centroid %.4e -> %.4e m (free flight %.4e)\n", x0, x1, x0 + 1000.0 * t_end);
  EXPECT_GT(x1 - x0, 0.2 * 1000.0 * t_end);
  EXPECT_LT(x1 - x0, 0.9 * 1000.0 * t_end);
  const Check* momentum = findCheck(result, "momentum_x");
  ASSERT_NE(momentum, nullptr);
  EXPECT_NEAR(momentum->value, 1.0, 1e-6);
  const Check* shift = findCheck(result, "centre_of_mass_shift");
  ASSERT_NE(shift, nullptr);
  EXPECT_TRUE(shift->pass()) << shift->value << " vs " << shift->reference;
  // The near-vacuum gas (material 2) heats no more than the aluminium it
  // shares cells with: when its own pdV work counted at 1e-9 of a cell's
  // mass, compression in the Lagrangian step and work-free re-expansion in
  // the remap ratcheted it up to 1e12 J/kg (mixed_cell_budget.hpp, kMassTrace).
  const FinalFields& fields = result.fields;
  double e_gas_max = 0.0, e_aluminium_max = 0.0;
  for (Index c = 0; c < Index(fields.m_k.extent(0)); ++c) {
    if (fields.m_k(c, 2) > 0.0) e_gas_max = std::max(e_gas_max, fields.e_k(c, 2));
    for (int k = 0; k < 2; ++k) {
      if (fields.m_k(c, k) > 0.0) e_aluminium_max = std::max(e_aluminium_max, fields.e_k(c, k));
    }
  }
  std::printf("ball: largest specific internal energy: gas %.3e J/kg, aluminium %.3e J/kg\n",
              e_gas_max, e_aluminium_max);
  EXPECT_LT(e_gas_max, 10.0 * e_aluminium_max);
}

// The ball's first steps at coarse resolutions where the ball's front shares
// cells with near-vacuum gas at rest (1e-5 kg/m^3, 2.5 J/kg): without the
// acoustic bound on the corner reconstruction (corner_stencil.hpp) a gas cell
// beside aluminium at 1000 m/s took node velocities of 6e5 m/s and tangled
// (--scale 0.2, step 6) or went to negative energy (--scale 0.5, step 2).
TEST(RemapProblems, BallStartsBesideNearVacuumAtCoarseResolutions) {
  for (const double scale : {0.2, 0.5}) {
    const RunResult result =
        runAndCheckRemap("ball", {"geometry.thickness=1e-4", "t_end=1e-7"}, scale);
    EXPECT_FALSE(result.failed) << "scale " << scale << ": " << result.failure;
    EXPECT_GT(result.steps, 20) << "scale " << scale;
  }
}

// A harder vacuum (1e-12 kg/m^3 and Pa): the nodes of the gas on the slab's
// symmetry planes have impedances of 1e-20 kg/s, which the constrained solve
// lost in M + 1 - 1 (NaN velocities, a tangled cell at step 1) until it
// added I - P at M's own scale (nodal_solver.hpp, constrainedMatrix).
TEST(RemapProblems, BallRunsInAHarderVacuum) {
  const RunResult result = runAndCheckRemap(
      "ball", {"geometry.thickness=1e-4", "t_end=3e-7", "gas.rho=1e-12", "gas.p=1e-12"}, 0.2);
  EXPECT_FALSE(result.failed) << result.failure;
  EXPECT_GT(result.steps, 50);
}

// The ball in free flight (the plate moved out of its way): in near-vacuum it
// keeps its kinetic energy and gains no heat, with the ball's boundary in
// mixed cells swept through the fixed mesh every step (0.3 mm of travel,
// about 4 cells at this resolution).
TEST(RemapProblems, BallInFreeFlightKeepsItsKineticEnergy) {
  const std::vector<std::string> settings = {"geometry.thickness=1e-4", "t_end=3e-7",
                                             "plate.x_min=-1.7e-3", "plate.x_max=-1.6e-3"};
  const RunResult result = runAndCheckRemap("ball", settings, 0.25);
  ASSERT_FALSE(result.failed);
  const RunOptions options = testing::problemOptions("ball", settings, 0.25, "remap");
  const testing::StateTotals initial =
      testing::initialTotals(findProblem("ball").setup(options.config));
  const testing::StateTotals final_state = testing::finalTotals(result.fields);
  std::printf("ball in flight: kinetic %.9e -> %.9e J, internal %.6e -> %.6e J\n", initial.kinetic,
              final_state.kinetic, initial.internal, final_state.internal);
  // measured: 6e-9 of the kinetic energy turned into heat (the internal
  // energy up 1.2e-4 of itself)
  EXPECT_NEAR(final_state.kinetic / initial.kinetic, 1.0, 1e-7);
  EXPECT_LT(final_state.internal - initial.internal, 1e-7 * initial.kinetic);
}

}  // namespace
}  // namespace lagremap

namespace lagremap {
namespace {

// The paper's equal-strain closure (mixture.closure = equal_strain) through
// the solid problems in gas, coarse and short: every total conserved to
// round-off, volume fractions in [0, 1] summing to 1, finite fields
// (runAndCheckRemap), as with the default closure. The ball's near-vacuum gas
// is taken below zero energy by its share (by volume fraction) of the mixed
// cells' negative dissipation: the run stops with exit 3 and a one-line
// reason naming step and cell (docs/method.md §4.5).
TEST(RemapProblems, EqualStrainClosureConservesInEverySolidProblem) {
  const std::string closure = "mixture.closure=equal_strain";
  runAndCheckRemap("taylor", {closure, "t_end=2e-4"}, 0.25);
  runAndCheckRemap("shell", {closure, "geometry.thickness=5.5e-3", "t_end=2e-5"}, 0.25);
  runAndCheckRemap("beam", {closure, "t_end=2e-6"}, 0.25);
  const RunResult ball = runProblem(testing::problemOptions(
      "ball", {closure, "geometry.thickness=1e-4", "t_end=5e-7"}, 0.25, "remap"));
  ASSERT_TRUE(ball.failed);
  EXPECT_NE(ball.failure.find("cell"), std::string::npos) << ball.failure;
  // its near-vacuum gas, heated by its volume share of the dissipation, drives
  // the stable dt a hundredfold down (numerics.dt_drop_fraction)
  EXPECT_NE(ball.failure.find("time step collapse"), std::string::npos) << ball.failure;
  std::printf("ball, equal strain: %s\n", ball.failure.c_str());
}

}  // namespace
}  // namespace lagremap

namespace lagremap {

// A body and its gas translating together (the standard test of a mixed-cell
// closure, docs/verification.md): pressure and velocity stay uniform and each
// material keeps its density to round-off, in 1D and 2D, with both closures.
// (Mutation-checked: with an aluminium trace joining the gas by its mass,
// advection1d's densities were off by 4e-5.)
TEST(RemapProblems, AdvectionKeepsTheUniformStateWithBothClosures) {
  for (const char* closure : {"relaxation", "equal_strain"}) {
    for (const auto& [problem, scale, t_end] :
         {std::tuple<const char*, double, const char*>{"advection1d", 1.0, "t_end=1e-3"},
          {"advection", 0.5, "t_end=1e-3"}}) {
      const RunResult result =
          runAndCheckRemap(problem, {std::string("mixture.closure=") + closure, t_end}, scale);
      ASSERT_FALSE(result.failed) << problem << " " << closure;
      for (const Check& check : result.checks) {
        std::printf("%s %s: %s %.3g (tolerance %.3g)\n", problem, closure, check.name.c_str(),
                    check.value, check.tolerance);
        EXPECT_TRUE(check.pass()) << problem << " " << closure << ": " << check.name << " "
                                  << check.value << " > " << check.tolerance;
      }
    }
  }
}

// The taylor bar's rear end in gas (55 x 20, to t_end): its mixed cells'
// aluminium keeps its density and a pressure like its pure cells'. Before the
// relaxation read the step-start pressures in both stages (docs/method.md
// §4.3), 10 of 234 were stretched to -7.4 GPa here (mixed_cells 0.068).
TEST(RemapProblems, TaylorMixedCellsAreNotStretched) {
  const RunResult result = runAndCheckRemap("taylor", {}, 0.25);
  ASSERT_FALSE(result.failed);
  const Check* check = findCheck(result, "mixed_cells");
  ASSERT_NE(check, nullptr);
  ASSERT_TRUE(result.mixed_cells.has_value());
  const MaterialMixedCells& al = result.mixed_cells->materials[0];
  std::printf("taylor: %ld of %ld mixed Al cells stretched, %ld p outliers, p %.3g .. %.3g Pa\n",
              al.stretched, al.mixed_cells, al.pressure_outliers, al.p_mixed_lo, al.p_mixed_hi);
  EXPECT_GT(al.mixed_cells, 100);
  EXPECT_TRUE(check->pass()) << check->value;
}

// The ball's first microsecond (37 x 50): no aluminium of a mixed cell is
// in GPa tension (aluminium spalls near -1 GPa; before the fix above, -7.2
// GPa). The check itself is not asserted: at this size and time 4 of the
// ball's 140 mixed cells and 2 of the plate's 254 lie below their pure cells'
// lowest pressure (to -0.44 GPa), above the 1% that the paper's resolution
// meets at t_end (docs/method.md §4.9).
TEST(RemapProblems, BallMixedCellsAreNotInTension) {
  const RunResult result =
      runAndCheckRemap("ball", {"geometry.thickness=1e-4", "t_end=1e-6"}, 0.25);
  ASSERT_FALSE(result.failed);
  ASSERT_TRUE(result.mixed_cells.has_value());
  for (const MaterialMixedCells& m : result.mixed_cells->materials) {
    if (!m.condensed) continue;
    std::printf(
        "ball: material %d: %ld of %ld mixed cells stretched, %ld expanded, p %.3g .. %.3g Pa\n",
        m.material, m.stretched, m.mixed_cells, m.expanded, m.p_mixed_lo, m.p_mixed_hi);
    EXPECT_GT(m.p_mixed_lo, -1e9) << "material " << m.material;
  }
}

}  // namespace lagremap

namespace lagremap {
namespace {

// measureMixedCells on made-up end-of-run fields (docs/method.md §4.9): cells
// of unit volume, each given its materials' volume fraction, density and
// pressure, and optionally their normal stresses across the interface (-p
// when not given: no deviator); the mixture pressure is the fractions' mean
// of the materials'.
struct MadeUpCell {
  std::vector<double> alpha, rho, p;
  std::vector<double> sigma_n = {};
};

FinalFields madeUpFields(const std::vector<MadeUpCell>& cells) {
  const Index n_cells = Index(cells.size());
  const Index n_materials = Index(cells.front().alpha.size());
  FinalFields fields;
  fields.vol = RealView::HostMirror("vol", n_cells);
  fields.rho = RealView::HostMirror("rho", n_cells);
  fields.p = RealView::HostMirror("p", n_cells);
  fields.alpha = MatRealView::HostMirror("alpha", n_cells, n_materials);
  fields.m_k = MatRealView::HostMirror("m_k", n_cells, n_materials);
  fields.p_k = MatRealView::HostMirror("p_k", n_cells, n_materials);
  fields.sigma_n_k = MatRealView::HostMirror("sigma_n_k", n_cells, n_materials);
  for (Index c = 0; c < n_cells; ++c) {
    const MadeUpCell& cell = cells[std::size_t(c)];
    fields.vol(c) = 1.0;
    for (Index k = 0; k < n_materials; ++k) {
      const std::size_t i = std::size_t(k);
      fields.alpha(c, k) = cell.alpha[i];
      fields.m_k(c, k) = cell.alpha[i] * cell.rho[i];
      fields.p_k(c, k) = cell.p[i];
      fields.sigma_n_k(c, k) = cell.sigma_n.empty() ? -cell.p[i] : cell.sigma_n[i];
      fields.rho(c) += fields.m_k(c, k);
      fields.p(c) += cell.alpha[i] * cell.p[i];
    }
  }
  return fields;
}

constexpr double kRhoAl = 2785.0;

// n pure cells of `material` (of n_materials) at pressures evenly from p_lo to
// p_hi, compressed by them (bulk modulus 76 GPa: aluminium's).
void addPureCells(std::vector<MadeUpCell>& cells, int material, int n_materials, int n, double rho0,
                  double p_lo, double p_hi) {
  for (int i = 0; i < n; ++i) {
    MadeUpCell cell{std::vector<double>(std::size_t(n_materials), 0.0),
                    std::vector<double>(std::size_t(n_materials), 1.0),
                    std::vector<double>(std::size_t(n_materials), 0.0)};
    const double p = p_lo + (p_hi - p_lo) * i / (n - 1);
    cell.alpha[std::size_t(material)] = 1.0;
    cell.rho[std::size_t(material)] = rho0 * (1.0 + p / 76e9);
    cell.p[std::size_t(material)] = p;
    cells.push_back(cell);
  }
}

// Aluminium (material 0) and a gas (material 1): 40 pure aluminium cells
// between -0.1 and 0.1 GPa, 20 pure gas cells at 1e5 Pa.
std::vector<MadeUpCell> aluminiumAndGas() {
  std::vector<MadeUpCell> cells;
  addPureCells(cells, 0, 2, 40, kRhoAl, -0.1e9, 0.1e9);
  addPureCells(cells, 1, 2, 20, 1.0, 1e5, 1e5);
  return cells;
}

const std::vector<MaterialParams> kAluminiumAndGas = {materialPreset("Al"), materialPreset("Gas")};

// The taylor's old state (docs/method.md §4.9: 0.90 rho0 at -7.4 GPa, held
// there by the relaxation) is tension: stretched, and the check fails.
TEST(MixedCells, TaylorsOldTensionIsStretchedAndFailsTheCheck) {
  std::vector<MadeUpCell> cells = aluminiumAndGas();
  cells.push_back({{0.41, 0.59}, {0.90 * kRhoAl, 1.0}, {-7.4e9, 6e4}});
  const MixedCellReport report = measureMixedCells(madeUpFields(cells), kAluminiumAndGas);
  const MaterialMixedCells& al = report.materials[0];
  EXPECT_EQ(al.mixed_cells, 1);
  EXPECT_EQ(al.pure_cells, 40);
  EXPECT_EQ(al.stretched, 1);
  EXPECT_EQ(al.expanded, 0);
  EXPECT_EQ(al.pressure_outliers, 1);
  EXPECT_FALSE(mixedCellsCheck(report).pass());
}

// A bent plate's outer fibre (docs/method.md §4.9): a film of solid (3% of
// its cell) in tension along its interface, at a pressure below every pure
// cell's (-3 GPa against -0.1 .. 0.1) and 5% below their density, yet its
// normal stress across the interface is the gas's: the closure balanced it. Reported in balance,
// not failed; the same cell pulling 3 GPa harder than the gas across its interface is stretched and
// an outlier, and fails.
TEST(MixedCells, ABentPlatesOuterFibreInBalanceIsReportedNotFailed) {
  std::vector<MadeUpCell> cells = aluminiumAndGas();
  cells.push_back({{0.03, 0.97}, {0.95 * kRhoAl, 1.0}, {-3e9, 1e5}, {-1e5, -1e5}});
  FinalFields fields = madeUpFields(cells);
  MixedCellReport report = measureMixedCells(fields, kAluminiumAndGas);
  const MaterialMixedCells* al = &report.materials[0];
  EXPECT_EQ(al->stretched, 0);
  EXPECT_EQ(al->pressure_outliers, 0);
  EXPECT_EQ(al->in_balance, 1);
  EXPECT_TRUE(mixedCellsCheck(report).pass());
  EXPECT_NE(mixedCellsLine(report).find("0 of 1 stretched, 0 expanded, 0 p outliers, 1 in balance"),
            std::string::npos)
      << mixedCellsLine(report);

  fields.sigma_n_k(Index(cells.size()) - 1, 0) = 3e9;
  report = measureMixedCells(fields, kAluminiumAndGas);
  al = &report.materials[0];
  EXPECT_EQ(al->stretched, 1);
  EXPECT_EQ(al->pressure_outliers, 1);
  EXPECT_EQ(al->in_balance, 0);
  EXPECT_FALSE(mixedCellsCheck(report).pass());
}

// Hot aluminium expanded thermally at about zero pressure (the ball's lips:
// 0.95 rho0), or in a tension its pure cells hold too, or below 0.98 rho0
// where every pure cell is compressed but at a pressure above 0: expanded,
// reported and not failed. (The check counted all three as stretched before
// it asked for tension.)
TEST(MixedCells, HotExpandedAluminiumIsReportedNotFailed) {
  std::vector<MadeUpCell> cells = aluminiumAndGas();
  cells.push_back({{0.5, 0.5}, {0.95 * kRhoAl, 1.0}, {2e5, 1e5}});
  cells.push_back({{0.3, 0.7}, {0.95 * kRhoAl, 1.0}, {-0.05e9, 1e5}});
  MixedCellReport report = measureMixedCells(madeUpFields(cells), kAluminiumAndGas);
  EXPECT_EQ(report.materials[0].mixed_cells, 2);
  EXPECT_EQ(report.materials[0].stretched, 0);
  EXPECT_EQ(report.materials[0].expanded, 2);
  EXPECT_EQ(report.materials[0].pressure_outliers, 0);
  EXPECT_EQ(mixedCellsCheck(report).value, 0.0);
  EXPECT_TRUE(mixedCellsCheck(report).pass());
  EXPECT_NE(mixedCellsLine(report).find("0 of 2 stretched, 2 expanded"), std::string::npos)
      << mixedCellsLine(report);

  std::vector<MadeUpCell> compressed;
  addPureCells(compressed, 0, 2, 40, kRhoAl, 0.5e9, 1e9);
  addPureCells(compressed, 1, 2, 20, 1.0, 1e5, 1e5);
  compressed.push_back({{0.5, 0.5}, {0.95 * kRhoAl, 1.0}, {0.1e9, 1e5}});
  report = measureMixedCells(madeUpFields(compressed), kAluminiumAndGas);
  EXPECT_EQ(report.materials[0].stretched, 0);
  EXPECT_EQ(report.materials[0].expanded, 1);
  EXPECT_TRUE(mixedCellsCheck(report).pass());
}

// The ball's contact (docs/method.md §4.9): ball and plate (two aluminium
// materials) meet in mixed cells at 0.32 GPa, which the plate's pure cells
// reach and the ball's few pure cells never do. Judged against every
// material's pure cells it is no outlier; a pressure beyond them all still is.
TEST(MixedCells, AContactPressureThatOnlyTheOtherBodysPureCellsReachIsNoOutlier) {
  std::vector<MadeUpCell> cells;
  addPureCells(cells, 0, 3, 12, kRhoAl, 0.0, 0.02e9);
  addPureCells(cells, 1, 3, 40, kRhoAl, -0.05e9, 0.35e9);
  addPureCells(cells, 2, 3, 20, 1e-5, 1e-5, 1e-5);
  const double rho_contact = kRhoAl * (1.0 + 0.32e9 / 76e9);
  for (double alpha_ball : {0.3, 0.5, 0.7})
    cells.push_back({{alpha_ball, 1.0 - alpha_ball, 0.0},
                     {rho_contact, rho_contact, 1e-5},
                     {0.32e9, 0.32e9, 0}});
  const std::vector<MaterialParams> materials = {materialPreset("Al"), materialPreset("Al"),
                                                 materialPreset("Gas")};
  FinalFields fields = madeUpFields(cells);
  MixedCellReport report = measureMixedCells(fields, materials);
  EXPECT_EQ(report.p_pure_all_lo, -0.05e9);
  EXPECT_EQ(report.p_pure_all_hi, 0.35e9);
  for (int k : {0, 1}) {
    EXPECT_EQ(report.materials[std::size_t(k)].mixed_cells, 3) << "material " << k;
    EXPECT_EQ(report.materials[std::size_t(k)].pressure_outliers, 0) << "material " << k;
    EXPECT_EQ(report.materials[std::size_t(k)].stretched, 0) << "material " << k;
  }
  EXPECT_TRUE(mixedCellsCheck(report).pass());

  fields.p_k(Index(cells.size()) - 1, 0) = 1e9;  // beyond 0.35 + 0.35 GPa
  fields.sigma_n_k(Index(cells.size()) - 1, 0) = -1e9;
  report = measureMixedCells(fields, materials);
  EXPECT_EQ(report.materials[0].pressure_outliers, 1);
  EXPECT_FALSE(mixedCellsCheck(report).pass());
}

}  // namespace
}  // namespace lagremap

namespace lagremap {

// Two-material shock tubes (docs/verification.md §2d): air against helium
// (ideal gases, different gamma) and water (stiffened gas) against air, with
// both closures: the contact's pressure and velocity within 1% of the exact
// p* and u*, the L1 density error within the built-in bound, no negative
// ideal-gas pressure.
TEST(RemapProblems, TwoFluidShockTubesMeetTheExactContactState) {
  for (const char* closure : {"relaxation", "equal_strain"}) {
    for (const char* problem : {"air_helium", "water_air"}) {
      const RunResult result =
          runAndCheckRemap(problem, {std::string("mixture.closure=") + closure}, 1.0);
      ASSERT_FALSE(result.failed) << problem << " " << closure;
      for (const Check& check : result.checks) {
        std::printf("%s %s: %s %.6g (reference %.6g, tolerance %.3g)\n", problem, closure,
                    check.name.c_str(), check.value, check.reference, check.tolerance);
        EXPECT_TRUE(!check.counts() || check.pass())
            << problem << " " << closure << ": " << check.name << " " << check.value;
      }
    }
  }
}

}  // namespace lagremap

namespace lagremap {

// The remap's order on a smooth field (docs/verification.md §2f): a density
// bump carried by a uniform gas flow along a bar (bump1d) and along the
// slab's diagonal (bump), at 25, 50 and 100 cells a side. The observed
// order of the L1 density error is at least 1.8 at order 2 (measured 2.0,
// 2.2 and 2.3, 2.4) and about 1 at --order 1 (0.81, 0.92 and 0.77, 0.87:
// bounds 0.65 to 1.3, which the second-order remap fails), and each run
// passes its checks (the built-in bounds of its mesh and order). With the
// parcels' energy bounded by the face's two cells, the diagonal bump's
// order falls to 0.93 between 25 and 50 cells (0.73 from 50 to 100).
// (Mass, momentum and energy are audited with what crosses the open sides:
// the background's inflow and outflow; 1e-12, as 100 x 100 cells reach
// 1.3e-13.)
TEST(RemapProblems, SmoothBumpConvergesAtTheRemapsOrder) {
  const auto errorsAt = [](const char* problem, const std::vector<std::string>& settings,
                           bool checks_pass, const std::vector<double>& scales) {
    std::vector<double> errors;
    for (double scale : scales) {
      const RunResult result =
          runProblem(testing::problemOptions(problem, settings, scale, "remap"));
      EXPECT_FALSE(result.failed) << problem << ": " << result.failure;
      EXPECT_LT(result.drift_mass, 1e-12) << problem;
      EXPECT_LT(result.drift_momentum, 1e-12) << problem;
      EXPECT_LT(result.drift_energy, 1e-12) << problem;
      if (result.failed || !result.l1_errors) return std::vector<double>{};
      const Check* check = findCheck(result, "l1_density");
      EXPECT_NE(check, nullptr) << problem;
      if (checks_pass) {
        for (const Check& c : result.checks) {
          EXPECT_TRUE(c.counts() && c.pass())
              << problem << " " << c.name << " " << c.value << " > " << c.tolerance;
        }
      }
      if (check) {
        EXPECT_EQ(check->value, result.l1_errors->density);
      }
      errors.push_back(result.l1_errors->density);
    }
    return errors;
  };
  for (const char* problem : {"bump1d", "bump"}) {
    for (const int order : {2, 1}) {
      const std::vector<double> errors =
          errorsAt(problem, {"numerics.order=" + std::to_string(order)}, true, {0.5, 1.0, 2.0});
      ASSERT_EQ(errors.size(), 3u) << problem;
      for (std::size_t i = 0; i + 1 < errors.size(); ++i) {
        const double observed = std::log2(errors[i] / errors[i + 1]);
        std::printf("%s order %d: L1 %.4e -> %.4e, observed order %.2f\n", problem, order,
                    errors[i], errors[i + 1], observed);
        if (order == 2) {
          EXPECT_GE(observed, 1.8) << problem;
        } else {
          EXPECT_GT(observed, 0.65) << problem;
          EXPECT_LT(observed, 1.3) << problem;
        }
      }
    }
  }
  const std::vector<double> face = errorsAt("bump", {"remap.parcel_bound=face"}, false, {0.5, 1.0});
  ASSERT_EQ(face.size(), 2u);
  std::printf("bump, face bound: L1 %.4e -> %.4e, observed order %.2f\n", face[0], face[1],
              std::log2(face[0] / face[1]));
  EXPECT_LT(std::log2(face[0] / face[1]), 1.3);
}

}  // namespace lagremap
