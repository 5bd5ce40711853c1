// `wilkins` — 1D flyer-plate impact of aluminium on aluminium (hypo-elastic
// perfectly plastic, Mie-Gruneisen), docs/verification.md §8.2, as a 3D bar one cell
// thick. The flyer [-0.01, 0.005] moves at 800 m/s into aluminium at rest.
// Lagrange mode meshes the solid only: the flyer and the target up to the
// wall at x = 0.05, the flyer's back face free, at the paper's cell size
// (200 cells over the 0.09 m of the remap domain, so 133 over 0.06 m); a
// bonded aluminium block behind the flyer would instead pull it back with
// several GPa of tension.
// Remap mode: the paper's fixed mesh [-0.04, 0.05] (200 cells), walls at both
// ends, and for the same reason a light gas instead of aluminium in
// [-0.04, -0.01] (departure from the paper's "all Al", docs/method.md §6.1): the flyer's back
// face stays nearly free, and nothing enters the fixed mesh.
// Checks (aluminium cells only), against the exact two-wave solution of the
// run's own speed and material (src/exact_two_wave.hpp): the plastic state
// behind the right-going shock (at 800 m/s: u = 400 m/s, sigma_xx = -6.637
// GPa, rho = 2985.6) and the elastic precursor ahead of it (u = 35.2 m/s).
#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>
#include <utility>
#include <vector>

#include "../src/exact_sum.hpp"
#include "../src/exact_two_wave.hpp"
#include "../src/materials.hpp"
#include "../src/problem.hpp"

namespace lagremap {
namespace {

void declareWilkins(Config& config) {
  config.addReal("t_end", 2.5e-6, "s", "final time");
  declareHypoSolidKeys(config, "al", "Al");
  config.addReal("al.p0", 1e5, "Pa", "initial pressure (e0 = p0 / (rho0 Gamma0))");
  config.addReal("flyer.vx", 800.0, "m/s", "flyer velocity");
  const bool remap = config.remapSetup();
  config.addReal(
      "geometry.x_min", remap ? -0.04 : -0.01, "m",
      remap ? "left end of the fixed mesh (wall)" : "left end of the mesh (the flyer's back face)");
  config.addReal("geometry.x_max", 0.05, "m", "right end of the domain");
  config.addReal("geometry.flyer_min", -0.01, "m", "left face of the flyer");
  config.addReal("geometry.flyer_max", 0.005, "m", "right face of the flyer (impact plane)");
  config.addReal("geometry.width", 4.5e-4, "m", "extent of the bar in y and z");
  if (remap) {
    // The gas behind the flyer (docs/method.md §6.1). At the
    // aluminium's p0 the flyer's back face starts in equilibrium; at 1 kg/m^3
    // its sound speed (374 m/s) never sets the time step (the aluminium's
    // 6450 m/s does; at 1e-3 kg/m^3 and the same p it would be 11.8 km/s),
    // and 800 m/s is below its escape speed 2 c / (gamma - 1) = 1870 m/s: the
    // gas follows the flyer in a rarefaction, the back face feels
    // p0 (1 - (gamma - 1) u / (2 c))^(2 gamma / (gamma - 1)) = 2 kPa, nearly free.
    config.addReal("gas.rho", 1.0, "kg/m^3", "density of the gas behind the flyer");
    config.addReal("gas.p", 1e5, "Pa", "pressure of the gas behind the flyer");
    config.addReal("gas.gamma", 1.4, "-", "ratio of specific heats of the gas");
    declareMeshKeys(config, 200, 1, 1);
    declareBoundaryKeys(config, {"wall", "wall", "symmetry", "symmetry", "symmetry", "symmetry"});
  } else {
    declareMeshKeys(config, 133, 1, 1);
    declareBoundaryKeys(config, {"free", "wall", "symmetry", "symmetry", "symmetry", "symmetry"});
  }
  config.addReal("check.relative_tolerance", 0.01, "-",
                 "relative tolerance on the plastic state behind the shock");
}

ProblemSetup setupWilkins(const Config& config) {
  const MaterialParams al = readHypoSolid(config, "al", "Al");
  const double x_min = config.real("geometry.x_min"), x_max = config.real("geometry.x_max");
  const double flyer_min = config.real("geometry.flyer_min");
  const double flyer_max = config.real("geometry.flyer_max");
  const double width = config.real("geometry.width");
  if (!(x_min <= flyer_min && flyer_min < flyer_max && flyer_max < x_max) || !(width > 0)) {
    throw ConfigError("wilkins: need x_min <= flyer_min < flyer_max < x_max and width > 0");
  }
  const double e0 = config.real("al.p0") / (al.rho0 * al.Gamma0);
  const double v_flyer = config.real("flyer.vx");
  CellShapes shapes;
  if (config.remapSetup()) {
    const AmbientGas gas = readAmbientGas(config, "wilkins");
    if (!(x_min < flyer_min)) {
      throw ConfigError("wilkins: remap mode needs gas behind the flyer (x_min < flyer_min)");
    }
    // Aluminium is material 0 (the checks read it), the gas material 1.
    ProblemSetup setup =
        setupBlock(config, {x_min, 0, 0}, {x_max, width, width}, {al, gas.material}, shapes);
    MaterialRegions regions;
    regions.material_at = [=](const Vec3& x) { return x.x < flyer_min ? 1 : 0; };
    regions.rho = {al.rho0, gas.rho};
    regions.e = {e0, gas.e};
    regions.velocity = [=](int material, const Vec3& x) {
      return material == 0 && x.x < flyer_max ? Vec3{v_flyer, 0, 0} : Vec3{0, 0, 0};
    };
    fillMaterialRegions(setup, regions);
    return setup;
  }
  ProblemSetup setup = setupBlock(config, {x_min, 0, 0}, {x_max, width, width}, {al}, shapes);
  InitialCells& cells = setup.cells;
  for (const Vec3& centroid : shapes.centroid) {
    const bool flyer = centroid.x >= flyer_min && centroid.x < flyer_max;
    cells.rho.push_back(al.rho0);
    cells.e.push_back(e0);
    cells.v.push_back({flyer ? v_flyer : 0.0, 0.0, 0.0});
    cells.mat.push_back(0);
  }
  return setup;
}

// The exact solution of this run's impact (flyer and target of the same
// aluminium keys: symmetric), src/exact_two_wave.hpp.
ImpactSolution exactImpact(const Config& config) {
  const MaterialParams al = readHypoSolid(config, "al", "Al");
  const ElasticPlasticSolid solid{al.rho0,
                                  al.a0,
                                  al.Gamma0,
                                  al.s,
                                  shearModulus(al),
                                  al.yield_stress,
                                  config.real("al.p0") / (al.rho0 * al.Gamma0)};
  try {
    return solveImpact(solid, solid, config.real("flyer.vx"));
  } catch (const std::invalid_argument& error) {
    throw ConfigError(std::string("wilkins: no exact solution for these parameters: ") +
                      error.what());
  }
}

// The profile along x, written to wilkins_profile.csv. rho, p and sigma_xx
// are the cell's (mixture) values; alpha_al and rho_al (aluminium's own
// density, m / (alpha v); nan in a cell without aluminium) let the plots draw
// the solid alone in remap mode.
struct WilkinsProfile {
  std::vector<double> x, u, sigma, alpha_al, rho_al;
  // The checks read aluminium cells only (in remap mode the gas behind the
  // flyer moves at up to 800 m/s and must enter no average).
  bool aluminium(std::size_t c) const { return alpha_al[c] > 1.0 - 1e-6; }
};

// The mesh is one row of cells: each rank's owned cells, gathered on every
// rank and put in cell order (a decomposed run's row is cut along x).
WilkinsProfile profileAlongX(const FinalFields& fields, const std::string& out_dir) {
  constexpr int kWidth = 8;  // global id, x, rho, u, p, sigma_xx, alpha_al, rho_al
  const bool mixed = fields.alpha.extent(1) > 1;  // remap mode: aluminium is material 0
  std::vector<double> mine;
  for (Index c = 0; c < Index(fields.rho.extent(0)); ++c) {
    if (!fields.counts(c)) continue;
    const double alpha = mixed ? fields.alpha(c, 0) : 1.0;
    const double rho = !mixed        ? fields.rho(c)
                       : alpha > 0.0 ? fields.m_k(c, 0) / (alpha * fields.vol(c))
                                     : NAN;
    mine.insert(mine.end(),
                {double(fields.globalCell(c)), fields.x_c(c, 0), fields.rho(c), fields.v(c, 0),
                 fields.p(c), -fields.p(c) + fields.S(c, 0), alpha, rho});
  }
  const std::vector<double> records = recordsOfAllRanks(fields, std::move(mine));
  std::vector<std::size_t> order(records.size() / kWidth);
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return records[kWidth * a] < records[kWidth * b];
  });
  ResultFile csv(out_dir.empty() ? "" : out_dir + "/wilkins_profile.csv");
  csv << "x,rho,u,p,sigma_xx,alpha_al,rho_al\n" << std::setprecision(10);
  WilkinsProfile profile;
  for (std::size_t i : order) {
    const double* r = &records[kWidth * i];
    profile.x.push_back(r[1]);
    profile.u.push_back(r[3]);
    profile.sigma.push_back(r[5]);
    profile.alpha_al.push_back(r[6]);
    profile.rho_al.push_back(r[7]);
    csv << r[1] << ',' << r[2] << ',' << r[3] << ',' << r[4] << ',' << r[5] << ',' << r[6] << ','
        << r[7] << '\n';
  }
  csv.write();
  return profile;
}

struct PlasticState {
  double u = NAN, rho = NAN, sigma = NAN;
};

// Mean over the middle half of [interface, shock]: the impact plane moves at
// the interface velocity from flyer_max; the right-going shock is the
// right-most cell with u above half of it.
PlasticState plasticState(const WilkinsProfile& profile, double impact, double u_interface,
                          double t) {
  const double interface = impact + u_interface * t;
  double shock = interface;
  for (std::size_t c = 0; c < profile.x.size(); ++c) {
    if (profile.aluminium(c) && profile.u[c] > 0.5 * u_interface) {
      shock = std::max(shock, profile.x[c]);
    }
  }
  double sum_u = 0, sum_rho = 0, sum_sigma = 0;
  int count = 0;
  const double lo = interface + 0.25 * (shock - interface), hi = shock - 0.25 * (shock - interface);
  for (std::size_t c = 0; c < profile.x.size(); ++c) {
    if (!profile.aluminium(c) || profile.x[c] < lo || profile.x[c] > hi) continue;
    sum_u += profile.u[c];
    sum_rho += profile.rho_al[c];
    sum_sigma += profile.sigma[c];
    ++count;
  }
  const double n = std::max(count, 1);
  return {sum_u / n, sum_rho / n, sum_sigma / n};
}

// The elastic precursor's level: the median u over the middle half of the
// plateau between the exact solution's plastic and elastic fronts (its
// cells, to tell whether the plateau is resolved).
std::vector<double> precursorPlateau(const WilkinsProfile& profile, const TwoWaveSolution& target,
                                     double impact, double t) {
  const double x_plastic = impact + target.plastic_speed * t;
  const double x_elastic = impact + target.precursor_speed * t;
  std::vector<double> plateau;
  for (std::size_t c = 0; c < profile.x.size() && target.plastic_wave; ++c) {
    const double where = (profile.x[c] - x_plastic) / (x_elastic - x_plastic);
    if (profile.aluminium(c) && where > 0.25 && where < 0.75) plateau.push_back(profile.u[c]);
  }
  std::sort(plateau.begin(), plateau.end());
  return plateau;
}

// The exact state of this run at (x, t), lab frame: the target's and the
// flyer's two-wave solutions (the flyer's waves run into it at v - U, its
// material at v - u) and, in remap mode, the gas behind the flyer, a centred
// rarefaction behind its back face moving at the flyer's speed (the piston
// problem: u + 2c / (gamma - 1) uniform, u = 2 (xi + c0) / (gamma + 1) in the
// fan, xi = (x - flyer_min) / t). It holds until a wave comes back from a
// boundary: the flyer's precursor reaches its back face at (flyer_max -
// flyer_min) / U_e (2.33 us for the default case, before t_end), the
// target's the wall at x_max, the gas's head the wall at x_min; `returned`
// marks where a returning wave can have reached, bounded by the fastest
// speeds (U_e in the solid, with a 10% margin; c0 in the gas, whose
// characteristics move at u - c >= -c0 and u + c <= v + c0).
struct WilkinsExact {
  ImpactSolution impact;
  double v = 0, impact_x = 0, flyer_min = 0, x_min = 0, x_max = 0;
  bool gas = false;  // remap mode: gas in [x_min, flyer_min]
  double gamma = 0, gas_rho = 0, gas_p = 0, gas_c = 0;

  UniaxialState at(double x, double t) const {
    const TwoWaveSolution& target = impact.target;
    const TwoWaveSolution& flyer = impact.flyer;
    if (x >= impact_x + impact.u_interface * t) {
      if (x > impact_x + target.precursor_speed * t) return target.initial;
      return x > impact_x + target.plastic_speed * t ? target.precursor : target.plastic;
    }
    if (!gas || x >= flyer_min + v * t) {
      const double front = impact_x + (v - flyer.precursor_speed) * t;
      UniaxialState state = x < front                                      ? flyer.initial
                            : x < impact_x + (v - flyer.plastic_speed) * t ? flyer.precursor
                                                                           : flyer.plastic;
      state.u = v - state.u;
      return state;
    }
    // the gas: at rest ahead of the fan's head, the piston's state behind its tail
    const double escape = 2.0 * gas_c / (gamma - 1.0);
    const double u_tail = std::min(v, escape);
    const double xi = t > 0.0 ? (x - flyer_min) / t : -1e300;
    const double u = std::clamp(2.0 * (xi + gas_c) / (gamma + 1.0), 0.0, u_tail);
    const double c = std::max(gas_c - 0.5 * (gamma - 1.0) * u, 0.0);
    UniaxialState state;
    state.u = u;
    state.rho = gas_rho * std::pow(c / gas_c, 2.0 / (gamma - 1.0));
    state.p = gas_p * std::pow(c / gas_c, 2.0 * gamma / (gamma - 1.0));
    state.sigma_xx = -state.p;
    return state;
  }

  // Whether a wave returning from a boundary can have reached x by time t.
  bool returned(double x, double t) const {
    const double margin = 1.1;
    const double back = (impact_x - flyer_min) / impact.flyer.precursor_speed;
    if (t > back) {
      const double x_back = flyer_min + v * back, dt = t - back;
      const double lo = x_back - (gas ? gas_c * dt : 0.0);
      if (x >= lo && x <= x_back + (v + margin * impact.flyer.precursor_speed) * dt) return true;
    }
    const double wall = (x_max - impact_x) / impact.target.precursor_speed;
    if (t > wall && x >= x_max - margin * impact.target.precursor_speed * (t - wall)) return true;
    const double gas_wall = gas ? (flyer_min - x_min) / gas_c : 1e300;
    return t > gas_wall && x <= x_min + (v + gas_c) * (t - gas_wall);
  }
};

WilkinsExact wilkinsExact(const Config& config) {
  WilkinsExact exact;
  exact.impact = exactImpact(config);
  exact.v = config.real("flyer.vx");
  exact.impact_x = config.real("geometry.flyer_max");
  exact.flyer_min = config.real("geometry.flyer_min");
  exact.x_min = config.real("geometry.x_min");
  exact.x_max = config.real("geometry.x_max");
  exact.gas = config.remapSetup();
  if (exact.gas) {
    exact.gamma = config.real("gas.gamma");
    exact.gas_rho = config.real("gas.rho");
    exact.gas_p = config.real("gas.p");
    exact.gas_c = std::sqrt(exact.gamma * exact.gas_p / exact.gas_rho);
  }
  return exact;
}

// L1 errors against the exact solution over the cells no returning wave can
// have reached (ExactSum over the owned cells and the ranks).
L1Errors wilkinsL1Errors(const Config& config, const FinalFields& fields) {
  const WilkinsExact exact = wilkinsExact(config);
  const double width = config.real("geometry.width");
  const double t = fields.time;
  std::vector<ExactSum> l1(4);  // rho, u, p, the length left out
  for (Index c = 0; c < Index(fields.rho.extent(0)); ++c) {
    if (!fields.counts(c)) continue;
    const double x = fields.x_c(c, 0), length = fields.vol(c) / (width * width);
    if (exact.returned(x, t)) {
      l1[3] += length;
      continue;
    }
    const UniaxialState ref = exact.at(x, t);
    l1[0] += length * std::abs(fields.rho(c) - ref.rho);
    l1[1] += length * std::abs(fields.v(c, 0) - ref.u);
    l1[2] += length * std::abs(fields.p(c) - ref.p);
  }
  if (fields.distributed) ExactSum::sumOverRanks(l1);
  std::ostringstream note;
  note << std::setprecision(3) << kBarL1ErrorsNote
       << " (the flyer's and the target's two-wave solutions"
       << (exact.gas ? ", the gas's rarefaction behind the flyer" : "")
       << "), over the cells no wave returning from the flyer's back face or a wall can have "
          "reached: "
       << l1[3].value() * 1e3 << " mm of the bar left out";
  return {l1[0].value(), l1[1].value(), l1[2].value(), note.str()};
}

ProblemResults finishWilkins(const Config& config, const FinalFields& fields,
                             const std::string& out_dir) {
  const WilkinsProfile profile = profileAlongX(fields, out_dir);
  const ImpactSolution exact = exactImpact(config);
  const TwoWaveSolution& target = exact.target;
  const double impact = config.real("geometry.flyer_max"), t = fields.time;
  const PlasticState plastic = plasticState(profile, impact, exact.u_interface, t);
  const std::vector<double> plateau = precursorPlateau(profile, target, impact, t);
  const double tol = config.real("check.relative_tolerance");
  const double u_p = exact.u_interface;
  const double sigma_p = target.plastic.sigma_xx, rho_p = target.plastic.rho;
  std::vector<Check> checks;
  // The plateau is (cL - U_plastic) t wide: 3 cells at the paper's 200, so its
  // level is measured only once it spans at least 8 cells (--scale 3 and up).
  if (plateau.size() >= 8) {
    checks.push_back({"precursor_velocity", plateau[plateau.size() / 2], target.precursor.u,
                      0.05 * target.precursor.u, "median u on the elastic precursor plateau"});
  }
  const std::string wave =
      target.plastic_wave ? "the plastic shock" : "the elastic wave (no yield)";
  checks.push_back({"plastic_velocity", plastic.u, u_p, tol * std::abs(u_p),
                    "mean u behind " + wave + " (interface velocity)"});
  checks.push_back({"plastic_sigma_xx", plastic.sigma, sigma_p, tol * std::abs(sigma_p),
                    "mean sigma_xx behind " + wave});
  checks.push_back(
      {"plastic_density", plastic.rho, rho_p, tol * rho_p, "mean density behind " + wave});
  for (Check& check : checks) check.source = "exact two-wave solution";
  markPerfectPlasticityOnly(config, checks, "al");
  setModeIndependentReferences(config, checks);
  ProblemResults results = std::move(checks);
  // (the exact solution is perfect plasticity's)
  if (config.text("al.hardening") == "perfect") results.l1_errors = wilkinsL1Errors(config, fields);
  return results;
}

}  // namespace

extern const Problem kWilkinsProblem = {
    "wilkins", "1D aluminium flyer-plate impact (Mie-Gruneisen, hypo-elastic plastic)",
    declareWilkins, setupWilkins, finishWilkins};

}  // namespace lagremap
