// `taylor` — planar Taylor impact of an aluminium bar on a rigid wall
// (hypo-elastic perfectly plastic, Mie-Gruneisen), docs/verification.md §8.3, as a slab
// one cell thick in z. Lagrange mode: the bar [0,5] x [-0.5,0.5] alone, moving
// at -150 m/s onto the wall x = 0, free elsewhere. Checks: final bar length
// ~4.62 (paper, Lagrange) and the kinetic energy dissipated plastically.
// Remap mode: the bar in gas (5 kg/m^3, at rest, 1e5 Pa) on the fixed mesh of
// [0,5.5] x [-1,1] (220 x 80), walls all round; the length is read from the
// alpha = 0.5 contour of aluminium on the bar's axis (paper: 4.63).
#include <algorithm>
#include <cmath>
#include <iomanip>

#include "../src/exact_sum.hpp"
#include "../src/problem.hpp"

namespace lagremap {
namespace {

// The paper's final bar lengths (docs/verification.md §8.3), Lagrange and remap.
constexpr double kPaperLengthLagrange = 4.62, kPaperLengthRemap = 4.63;

void declareTaylor(Config& config) {
  config.addReal("t_end", 5e-3, "s", "final time");
  declareHypoSolidKeys(config, "al", "Al");
  config.addReal("bar.vx", -150.0, "m/s", "impact velocity");
  config.addReal("geometry.length", 5.0, "m", "bar length along x");
  config.addReal("geometry.height", 1.0, "m", "bar height along y");
  config.addCellLength("geometry.thickness", 0.025, "slab thickness along z (one cell)");
  if (config.remapSetup()) {
    config.addReal("domain.length", 5.5, "m", "fixed mesh extent along x (remap)");
    config.addReal("domain.height", 2.0, "m", "fixed mesh extent along y (remap)");
    config.addReal("gas.rho", 5.0, "kg/m^3", "density of the surrounding gas");
    config.addReal("gas.p", 1e5, "Pa", "pressure of the surrounding gas");
    config.addReal("gas.gamma", 1.4, "-", "ratio of specific heats of the gas");
    declareMeshKeys(config, 220, 80, 1);
    declareBoundaryKeys(config, {"wall", "wall", "wall", "wall", "symmetry", "symmetry"});
  } else {
    declareMeshKeys(config, 200, 40, 1);
    declareBoundaryKeys(config, {"wall", "free", "free", "free", "symmetry", "symmetry"});
  }
  config.addReal(
      "check.reference_length", config.remapSetup() ? kPaperLengthRemap : kPaperLengthLagrange, "m",
      config.remapSetup() ? "final length (paper, remap)" : "final length (paper, Lagrange)");
  config.addReal("check.length_tolerance", 0.05, "m", "tolerance on the final length");
  config.addReal("check.kinetic_fraction", 0.05, "-",
                 "largest final kinetic energy as a fraction of the initial one");
}

ProblemSetup setupTaylor(const Config& config) {
  const MaterialParams al = readHypoSolid(config, "al", "Al");
  const double length = config.real("geometry.length"), height = config.real("geometry.height");
  const double thickness = config.real("geometry.thickness");
  if (!(length > 0 && height > 0 && thickness > 0)) {
    throw ConfigError("taylor: length, height and thickness must be positive");
  }
  CellShapes shapes;
  const double vx = config.real("bar.vx");
  if (config.remapSetup()) {
    const AmbientGas gas = readAmbientGas(config, "taylor");
    const double domain_length = config.real("domain.length");
    const double domain_height = config.real("domain.height");
    if (!(domain_length > length && domain_height > height)) {
      throw ConfigError("taylor: the remap domain must contain the bar");
    }
    ProblemSetup setup =
        setupBlock(config, {0, -domain_height / 2, 0},
                   {domain_length, domain_height / 2, thickness}, {al, gas.material}, shapes);
    MaterialRegions regions;
    regions.material_at = [=](const Vec3& x) {
      return x.x < length && std::abs(x.y) < 0.5 * height ? 0 : 1;
    };
    regions.rho = {al.rho0, gas.rho};
    regions.e = {0.0, gas.e};
    regions.velocity = [=](int material, const Vec3&) {
      return material == 0 ? Vec3{vx, 0, 0} : Vec3{0, 0, 0};
    };
    fillMaterialRegions(setup, regions);
    return setup;
  }
  ProblemSetup setup =
      setupBlock(config, {0, -height / 2, 0}, {length, height / 2, thickness}, {al}, shapes);
  for (std::size_t c = 0; c < shapes.volume.size(); ++c) {
    setup.cells.rho.push_back(al.rho0);
    setup.cells.e.push_back(0.0);
    setup.cells.v.push_back({vx, 0, 0});
    setup.cells.mat.push_back(0);
  }
  return setup;
}

// Bar length. Lagrange: the largest x of any node (the wall is at x = 0).
// Remap (two materials): the aluminium volume along the row of cells just
// above the axis divided by the row's cross-section, sum alpha v / (dy dz),
// a smooth measure of the length (the check reads the alpha = 0.5 contour).
void sampleBarLength(const Mesh& mesh, const State& state, const ProbeSlots& slots) {
  if (state.n_materials > 1) {
    sampleMaterialLengthAlongAxis("lagremap::diagnostics::bar_length_alpha", mesh, state, false,
                                  slots);
  } else {
    sampleLargestNodeX("lagremap::diagnostics::bar_length", mesh, slots);
  }
}
double barLength(const Mesh&, const State& state, const ProbeSlots& slots) {
  return state.n_materials > 1 ? sumOverRanks(slots) : largestOverRanks(slots);
}

ProblemResults finishTaylor(const Config& config, const FinalFields& fields,
                            const std::string& out_dir) {
  // The deformed bar's cells, and its kinetic energy (an exact sum over the
  // owned cells and the ranks: the same bits on any rank count).
  writeCellOutlines(out_dir.empty() ? "" : out_dir + "/taylor_mesh_z0.csv", fields);
  ExactSum kinetic_sum;
  for (Index c = 0; c < Index(fields.rho.extent(0)); ++c) {
    if (!fields.counts(c)) continue;
    const double m = fields.rho(c) * fields.vol(c);
    kinetic_sum += 0.5 * m *
                   (fields.v(c, 0) * fields.v(c, 0) + fields.v(c, 1) * fields.v(c, 1) +
                    fields.v(c, 2) * fields.v(c, 2));
  }
  if (fields.distributed) kinetic_sum.sumOverRanks();
  const double kinetic = kinetic_sum.value();
  const double vx = config.real("bar.vx");
  const double bar_mass = readHypoSolid(config, "al", "Al").rho0 * config.real("geometry.length") *
                          config.real("geometry.height") * config.real("geometry.thickness");
  const double kinetic0 = 0.5 * bar_mass * vx * vx;
  ResultFile history(out_dir.empty() ? "" : out_dir + "/taylor_length.csv");
  history << "t,length\n";
  for (const auto& [t, value] : fields.probe) history << t << ',' << value << '\n';
  history.write();
  const bool remap = config.remapSetup();
  const double final_length = remap                  ? materialFrontX(fields, 0, 0.0)
                              : fields.probe.empty() ? NAN
                                                     : fields.probe.back().second;
  std::vector<Check> checks = {
      {"final_length", final_length, config.real("check.reference_length"),
       config.real("check.length_tolerance"),
       remap ? "alpha = 0.5 contour of aluminium on the axis at t_end (paper, remap: 4.63)"
             : "largest node x at t_end (paper, Lagrange: 4.62)"},
      {"kinetic_fraction", kinetic / kinetic0, 0.0, config.real("check.kinetic_fraction"),
       "final kinetic energy / initial (dissipated plastically)"}};
  checks[0].paper = remap ? kPaperLengthRemap : kPaperLengthLagrange;
  // The remap length is compared with the paper's Lagrange one (its Fig. 6).
  if (remap) checks[0].lagrange_reference = kPaperLengthLagrange;
  setModeIndependentReferences(config, checks);
  // The paper's length is that of its case at its t_end (a reference the
  // user sets with check.reference_length is theirs); the bar has come to
  // rest only at the end of the case.
  const Param& reference = config.params().at("check.reference_length");
  if (reference.value == reference.default_value) {
    markDefaultCaseOnly(config, checks, {"final_length"}, "paper, default parameters only");
  } else {
    checks[0].source = "check.reference_length (user)";
  }
  checks[1].source = "at rest by the case's t_end";
  const Param& t_end = config.params().at("t_end");
  if (t_end.value != t_end.default_value) {
    checks[1].doesNotApply("an end-state check; t_end = " + t_end.value + " is not the case's " +
                           t_end.default_value);
  }
  return checks;
}

}  // namespace

extern const Problem kTaylorProblem = {
    "taylor",
    "planar Taylor impact of an aluminium bar on a rigid wall (hypo-elastic, 2D slab)",
    declareTaylor,
    setupTaylor,
    finishTaylor,
    {sampleBarLength, barLength, "bar_length"}};

}  // namespace lagremap
