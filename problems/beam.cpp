// `beam` — a Neo-Hookean beryllium plate set vibrating in its first free-free
// bending mode, PROBLEMS.md §4: [-0.03,0.03] x [-0.005,0.005]^2, 100 x 10 x 10,
// symmetry on the z faces, free elsewhere, V = (0, Vy(x), 0) with the mode
// shape (the minus sign between the brackets: the paper's '+' would start the
// far end at ~65 km/s). Output: the tip's vertical displacement history.
// Check: the half period, from the first zero crossing of the tip
// displacement, against pi / w (w = 2.3597e5, period 26.6 us, from
// Euler-Bernoulli theory) corrected to first order for shear and rotary
// inertia (Timoshenko), which lengthen the period of this thick plate by ~10%.
#include <algorithm>
#include <cmath>
#include <fstream>
#include <iomanip>

#include "../src/problem.hpp"

namespace lagremap {
namespace {

void declareBeam(Config& config) {
  // Its free surfaces would sweep the plate out of the fixed mesh.
  refuseRemapMode(config, "beam", "the plate in gas on a 100 x 40 x 10 box");
  config.addReal("t_end", 3e-5, "s", "final time");
  declareNeoHookeanKeys(config, "be", "Be-hyper");
  config.addReal("geometry.length", 0.06, "m", "plate length L along x");
  config.addReal("geometry.height", 0.01, "m", "plate height along y");
  config.addReal("geometry.depth", 0.01, "m", "plate depth along z");
  config.addReal("mode.A", 4.3369e-5, "m", "mode amplitude A");
  config.addReal("mode.w", 2.3597e5, "1/s", "angular frequency w");
  config.addReal("mode.Omega", 78.834, "1/m", "wave number Omega (Omega L = 4.730)");
  config.addReal("mode.g1", 56.6368, "-", "mode coefficient g1");
  config.addReal("mode.g2", 57.6455, "-", "mode coefficient g2");
  declareMeshKeys(config, 100, 10, 10);
  declareBoundaryKeys(config, {"free", "free", "free", "free", "symmetry", "symmetry"});
  config.addReal("check.period_tolerance", 0.05, "-",
                 "relative tolerance on the half period (vs Timoshenko-corrected theory)");
}

ProblemSetup setupBeam(const Config& config) {
  const MaterialParams be = readNeoHookean(config, "be", "Be-hyper");
  const double length = config.real("geometry.length"), height = config.real("geometry.height");
  const double depth = config.real("geometry.depth");
  if (!(length > 0 && height > 0 && depth > 0)) throw ConfigError("beam: sizes must be positive");
  CellShapes shapes;
  ProblemSetup setup = setupBlock(config, {-length / 2, -height / 2, -depth / 2},
                                  {length / 2, height / 2, depth / 2}, {be}, shapes);
  const double a = config.real("mode.A"), w = config.real("mode.w");
  const double omega = config.real("mode.Omega");
  const double g1 = config.real("mode.g1"), g2 = config.real("mode.g2");
  for (const Vec3& x : shapes.centroid) {
    const double k = omega * (x.x + length / 2);
    const double vy =
        a * w * (g2 * (std::cosh(k) + std::cos(k)) - g1 * (std::sinh(k) + std::sin(k)));
    setup.cells.rho.push_back(be.rho0);
    setup.cells.e.push_back(0.0);
    setup.cells.v.push_back({0.0, vy, 0.0});
    setup.cells.mat.push_back(0);
  }
  return setup;
}

// Tip displacement: mean y of the centroids of the cells on the x-max face
// (zero initially by symmetry of the cross-section).
double tipDisplacement(const Mesh& mesh, const State& state) {
  return sideMeanCentroid(mesh, state, 1, 1);
}

std::vector<Check> finishBeam(const Config& config, const FinalFields& fields,
                              const std::string& out_dir) {
  std::ofstream csv;
  if (!out_dir.empty()) csv.open(out_dir + "/beam_tip.csv");
  csv << "t,tip_displacement_y\n" << std::setprecision(10);
  for (const auto& [t, y] : fields.probe) csv << t << ',' << y << '\n';
  // The tip starts moving up: the half period is its first downward crossing.
  double half_period = NAN;
  for (std::size_t i = 1; i < fields.probe.size(); ++i) {
    const auto& [t0, y0] = fields.probe[i - 1];
    const auto& [t1, y1] = fields.probe[i];
    if (y0 > 0.0 && y1 <= 0.0) {
      half_period = t0 + (t1 - t0) * y0 / (y0 - y1);  // linear interpolation of the crossing
      break;
    }
  }
  // Euler-Bernoulli's w ignores shear deformation and rotary inertia, which
  // matter for this thick plate (L/h = 6): the first-order Timoshenko
  // correction w_T / w = 1 - (beta L)^2 (r/L)^2 (1 + E/(k G)) / 2, with
  // r^2 = h^2/12, beta L = Omega L, k = 5/6 and E/G = 2 (1 + nu), is -9%.
  const double length = config.real("geometry.length"), height = config.real("geometry.height");
  const double beta_l = config.real("mode.Omega") * length;
  const double slender = height * height / (12.0 * length * length);
  const double ratio = 1.0 - 0.5 * beta_l * beta_l * slender *
                                 (1.0 + 2.0 * (1.0 + config.real("be.poisson")) / (5.0 / 6.0));
  const double exact = 3.14159265358979323846 / (config.real("mode.w") * ratio);
  return {{"half_period", half_period, exact, config.real("check.period_tolerance") * exact,
           "first zero crossing of the tip displacement vs pi / w with the first-order "
           "Timoshenko correction (Euler-Bernoulli: 13.3 us)"}};
}

}  // namespace

extern const Problem kBeamProblem = {
    "beam",
    "3D Neo-Hookean beryllium plate vibrating in its first bending mode",
    declareBeam,
    setupBeam,
    finishBeam,
    tipDisplacement,
    "tip_displacement_y"};

}  // namespace lagremap
