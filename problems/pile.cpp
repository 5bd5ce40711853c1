// `pile` — pile driving of a hyper-elastic steel bar, docs/verification.md §8.4: a real
// 3D mesh 100 x 3 x 3 of [0,10] x [-0.5,0.5]^2, rigid wall at x = 0, imposed
// sigma_xx = -5e7 Pa at x = 10, free lateral faces. Linear elastic limit
// (nu = 0, c = sqrt(E/rho0) = 5000 m/s, L/c = 2 ms): the wall stress is 0 until
// 2 ms, -1e8 (the doubled reflection) until 6 ms, then 0 again; no lateral motion.
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "../src/problem.hpp"

namespace lagremap {
namespace {

void declarePile(Config& config) {
  config.addReal("t_end", 8e-3, "s", "final time");
  declareNeoHookeanKeys(config, "steel", "Steel-hyper");
  config.addReal("geometry.length", 10.0, "m", "bar length along x");
  config.addReal("geometry.width", 1.0, "m", "bar width in y and z");
  declareMeshKeys(config, 100, 3, 3);
  declareBoundaryKeys(config, {"wall", "traction", "free", "free", "free", "free"});
  declareTractionKeys(config, 1, SymMat3{-5e7, 0, 0, 0, 0, 0});
  config.addReal("check.plateau_tolerance", 0.05, "-",
                 "relative tolerance on the wall-stress plateau and the quiet phases");
  config.addReal("check.arrival_tolerance", 1e-4, "s", "tolerance on the arrival time 2 ms");
}

ProblemSetup setupPile(const Config& config) {
  const MaterialParams steel = readNeoHookean(config, "steel", "Steel-hyper");
  const double length = config.real("geometry.length"), width = config.real("geometry.width");
  if (!(length > 0 && width > 0)) throw ConfigError("pile: length and width must be positive");
  CellShapes shapes;
  ProblemSetup setup = setupBlock(config, {0, -width / 2, -width / 2},
                                  {length, width / 2, width / 2}, {steel}, shapes);
  for (std::size_t c = 0; c < shapes.volume.size(); ++c) {
    setup.cells.rho.push_back(steel.rho0);
    setup.cells.e.push_back(0.0);
    setup.cells.v.push_back({0, 0, 0});
    setup.cells.mat.push_back(0);
  }
  return setup;
}

// Mean sigma_xx = -p + S_xx of the cells touching the wall (x-min side).
void sampleWallStress(const Mesh& mesh, const State& state, const ProbeSlots& slots) {
  sampleSideMeanStressXX(mesh, state, 0, slots);
}
double wallStress(const Mesh&, const State&, const ProbeSlots& slots) {
  return meanOverRanks(slots);
}

double meanOver(const std::vector<std::pair<double, double>>& probe, double t0, double t1) {
  double sum = 0.0;
  int n = 0;
  for (const auto& [t, value] : probe)
    if (t >= t0 && t <= t1) sum += value, ++n;
  return n > 0 ? sum / n : NAN;
}

ProblemResults finishPile(const Config& config, const FinalFields& fields,
                          const std::string& out_dir) {
  const double c = std::sqrt(config.real("steel.young") / config.real("steel.rho0"));
  const double transit = config.real("geometry.length") / c;  // L/c = 2 ms
  const double load = config.real("bc.xmax.sigma_xx");
  const double plateau = 2.0 * load;  // reflection at the rigid wall doubles it
  const double tol = config.real("check.plateau_tolerance") * std::abs(plateau);
  double arrival = NAN;
  for (const auto& [t, value] : fields.probe) {
    if (value < 0.5 * plateau) {
      arrival = t;
      break;
    }
  }
  double lateral = 0.0, axial = 0.0;  // over the (owned) cells, then the ranks
  const Index n_cells = Index(fields.rho.extent(0));
  for (Index cell = 0; cell < n_cells; ++cell) {
    if (!fields.counts(cell)) continue;
    lateral = std::max({lateral, std::abs(fields.v(cell, 1)), std::abs(fields.v(cell, 2))});
    axial = std::max(axial, std::abs(fields.v(cell, 0)));
  }
  if (fields.distributed) {
    lateral = parallel::max(lateral);
    axial = parallel::max(axial);
  }
  ResultFile csv(out_dir.empty() ? "" : out_dir + "/pile_wall_stress.csv");
  csv << "t,sigma_xx,exact\n";
  for (const auto& [t, value] : fields.probe) {
    const double exact = (t > transit && t < 3 * transit) ? plateau : 0.0;
    csv << t << ',' << value << ',' << exact << '\n';
  }
  csv.write();
  std::vector<Check> checks = {
      {"wall_stress_before", meanOver(fields.probe, 0.25 * transit, 0.75 * transit), 0.0, tol,
       "mean wall sigma_xx on [L/4c, 3L/4c] (exact 0)"},
      {"wall_stress_plateau", meanOver(fields.probe, 1.25 * transit, 2.75 * transit), plateau, tol,
       "mean wall sigma_xx on [1.25 L/c, 2.75 L/c] (exact 2 x imposed)"},
      {"arrival_time", arrival, transit, config.real("check.arrival_tolerance"),
       "first time the wall stress passes half the plateau (exact L/c)"},
      {"lateral_velocity", lateral / std::max(axial, 1e-300), 0.0, 1e-3,
       "max |v_y|, |v_z| / max |v_x| (nu = 0: no lateral motion)"}};
  if (fields.time > 3.25 * transit) {
    checks.push_back({"wall_stress_after", meanOver(fields.probe, 3.25 * transit, 3.75 * transit),
                      0.0, tol, "mean wall sigma_xx on [3.25 L/c, 3.75 L/c] (exact 0)"});
  }
  for (Check& check : checks) {
    check.source = check.name == "lateral_velocity" ? "1D symmetry" : "elastic wave of the load";
  }
  // A window of the wall's record the run does not reach: not measured.
  const double window_end[] = {0.75 * transit, 2.75 * transit,
                               transit + config.real("check.arrival_tolerance")};
  for (int i = 0; i < 3; ++i) {
    if (fields.time < window_end[i]) {
      char reason[96];
      std::snprintf(reason, sizeof reason, "the run ends (t = %.4g s) before its window (%.4g s)",
                    fields.time, window_end[i]);
      checks[i].doesNotApply(reason);
    }
  }
  setModeIndependentReferences(config, checks);
  return checks;
}

}  // namespace

extern const Problem kPileProblem = {
    "pile",      "3D hyper-elastic steel bar driven by an end traction (wall stress square wave)",
    declarePile, setupPile,
    finishPile,  {sampleWallStress, wallStress, "wall_sigma_xx"}};

}  // namespace lagremap
