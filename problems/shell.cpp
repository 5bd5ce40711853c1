// `shell` — collapse of a thick beryllium shell (hypo-elastic perfectly
// plastic, Mie-Gruneisen), docs/verification.md §8.6, inward with the incompressible
// Howell-Ball profile V = -V0 (Ri / r) e_r (or the paper's text's V0 r / Ri).
// Checks: the stopping radii (smallest inner radius reached, and the outer
// radius then) against Howell & Ball's energy balance for the run's
// parameters (src/howell_ball.hpp; 50 mm / 78.1 mm at V0 = 417.1 m/s, paper:
// 51 / 79 mm), the roundness and that the shell has stopped.
// Lagrange mode: the shell alone on a polar hex mesh of a quarter annulus
// Ri = 0.08, Ro = 0.1 (symmetry planes x = 0 and y = 0, one cell thick in z,
// free inner and outer surfaces).
// Remap mode (the paper's): the whole annulus in gas (5 kg/m^3, at rest,
// 1e5 Pa) inside and outside, on the fixed 160 x 160 mesh of [-0.11, 0.11]^2,
// walls all round; the radii are read from the beryllium volume fraction.
#include <algorithm>
#include <cmath>
#include <iomanip>

#include "../kernels/eos.hpp"
#include "../src/diagnostics.hpp"
#include "../src/exact_sum.hpp"
#include "../src/howell_ball.hpp"
#include "../src/kokkos_events.hpp"
#include "../src/materials.hpp"
#include "../src/problem.hpp"

namespace lagremap {
namespace {

constexpr double kPi = 3.14159265358979323846;
// The paper's stopping radii, from its remap run (docs/verification.md §8.6).
constexpr double kPaperInnerRadius = 0.051, kPaperOuterRadius = 0.079;

void declareShell(Config& config) {
  const bool remap = config.remapSetup();
  config.addReal("t_end", 130e-6, "s", "final time");
  declareHypoSolidKeys(config, "be", "Be-hypo");
  config.addReal("shell.inner_radius", 0.08, "m", "inner radius Ri");
  config.addReal("shell.outer_radius", 0.1, "m", "outer radius Ro");
  config.addReal("shell.v0", 417.1, "m/s", "inward speed at the inner radius");
  config.addChoice("shell.profile", "howell_ball", {"howell_ball", "paper_text"},
                   "radial speed V0 Ri/r (incompressible) or V0 r/Ri (the paper's text)");
  config.addReal("shell.p0", 1e-6, "Pa", "initial pressure of the shell");
  if (remap) {
    config.addReal("domain.half_width", 0.11, "m", "fixed mesh [-w, w]^2 (remap)");
    config.addReal("gas.rho", 5.0, "kg/m^3", "density of the gas inside and outside the shell");
    config.addReal("gas.p", 1e5, "Pa", "pressure of the gas");
    config.addReal("gas.gamma", 1.4, "-", "ratio of specific heats of the gas");
    // One cell thick: the in-plane cell size 0.22 / 160, so that z does not set dt.
    config.addCellLength("geometry.thickness", 1.375e-3, "slab thickness along z (one cell)");
    declareMeshKeys(config, 160, 160, 1);
    declareBoundaryKeys(config, {"wall", "wall", "wall", "wall", "symmetry", "symmetry"});
  } else {
    config.addCellLength("geometry.thickness", 1.25e-3, "slab thickness along z (one cell)");
    // mesh.nx: radial cells, mesh.ny: cells over the quarter circle
    declareMeshKeys(config, 15, 90, 1);
    declareBoundaryKeys(config, {"free", "free", "symmetry", "symmetry", "symmetry", "symmetry"});
  }
  config.addReal("check.inner_radius", 0.0, "m",
                 "stopping inner radius; 0: Howell & Ball for the run's parameters");
  config.addReal("check.outer_radius", 0.0, "m",
                 "stopping outer radius; 0: Howell & Ball for the run's parameters");
  config.addReal("check.radius_tolerance", 0.002, "m", "tolerance on the stopping radii");
}

// Initial velocity of the shell at x (docs/verification.md §8.6): inward, V0 Ri / r or V0 r / Ri.
Vec3 shellVelocity(const Vec3& x, double ri, double v0, bool howell_ball) {
  const double r = std::hypot(x.x, x.y);
  const double speed = howell_ball ? v0 * ri / r : v0 * r / ri;
  return {-speed * x.x / r, -speed * x.y / r, 0.0};
}

ProblemSetup setupShell(const Config& config) {
  const MaterialParams be = readHypoSolid(config, "be", "Be-hypo");
  const double ri = config.real("shell.inner_radius"), ro = config.real("shell.outer_radius");
  const double thickness = config.real("geometry.thickness");
  const double p0 = config.real("shell.p0");
  if (!(ri > 0 && ro > ri && thickness > 0)) {
    throw ConfigError("shell: need 0 < inner_radius < outer_radius and thickness > 0");
  }
  if (!(p0 >= 0)) throw ConfigError("shell: shell.p0 must be >= 0");
  const double v0 = config.real("shell.v0");
  const bool howell_ball = config.text("shell.profile") == "howell_ball";
  const double e0 = p0 / (be.rho0 * be.Gamma0);  // Mie-Gruneisen at rho = rho0
  if (config.remapSetup()) {
    const AmbientGas gas = readAmbientGas(config, "shell");
    const double half_width = config.real("domain.half_width");
    if (!(half_width > ro)) throw ConfigError("shell: the remap domain must contain the shell");
    CellShapes shapes;
    ProblemSetup setup =
        setupBlock(config, {-half_width, -half_width, 0}, {half_width, half_width, thickness},
                   {be, gas.material}, shapes);
    MaterialRegions regions;
    regions.material_at = [=](const Vec3& x) {
      const double r = std::hypot(x.x, x.y);
      return r >= ri && r <= ro ? 0 : 1;
    };
    regions.rho = {be.rho0, gas.rho};
    regions.e = {e0, gas.e};
    regions.velocity = [=](int material, const Vec3& x) {
      return material == 0 ? shellVelocity(x, ri, v0, howell_ball) : Vec3{0, 0, 0};
    };
    fillMaterialRegions(setup, regions);
    return setup;
  }
  BlockSpec block;
  block.nx = int(config.integer("mesh.nx"));
  block.ny = int(config.integer("mesh.ny"));
  block.nz = int(config.integer("mesh.nz"));
  block.lo = {ri, 0.0, 0.0};
  block.hi = {ro, 0.5 * kPi, thickness};
  // Block (r, theta, z) -> polar (x, y, z): the y-min side is the plane y = 0,
  // the y-max side the plane x = 0.
  block.mapping = [](const Vec3& p) { return Vec3{p.x * std::cos(p.y), p.x * std::sin(p.y), p.z}; };
  block.part = thisRanksPart(block.nx, block.ny, block.nz);
  ProblemSetup setup;
  setup.mesh = buildBlockMesh(block, readBoundaries(config));
  setup.materials = {be};
  std::vector<double> volume;
  std::vector<Vec3> centroid;
  hostCellShapes(copyToHost(setup.mesh), volume, centroid);
  for (const Vec3& x : centroid) {
    setup.cells.rho.push_back(be.rho0);
    setup.cells.e.push_back(e0);
    setup.cells.v.push_back(shellVelocity(x, ri, v0, howell_ball));
    setup.cells.mat.push_back(0);
  }
  return setup;
}

// Inner radius of the shell after every step.
// A slab cell's area in its plane, v / dz (VTK nodes 0 and 4 are the bottom
// and top of the cell's first z-edge).
KOKKOS_INLINE_FUNCTION double cellArea(const Vec3View& x_n, const CellNodesView& cell_nodes,
                                       const RealView& vol, Index c) {
  return vol(c) / (x_n(cell_nodes(c, 4), 2) - x_n(cell_nodes(c, 0), 2));
}

// Lagrange: the smallest node radius (the inner surface).
// Remap: the radius of the circle whose area is that of the gas inside the
// shell, sqrt(sum alpha_gas a_c / pi) over the cells inside the shell's
// mean radius (a_c = v_c / dz_c the cell's area in the slab's plane; the mean
// radius sqrt(<r^2>) weighted by beryllium area lies in its pure band). For a
// round interface smeared symmetrically this is the radius of the
// alpha = 1/2 contour, measured over every direction at once.
void sampleInnerRadius(const Mesh& mesh, const State& state, const ProbeSlots& slots) {
  const auto x_n = mesh.x_n;
  if (state.n_materials == 1) {
    Kokkos::parallel_reduce(
        "lagremap::diagnostics::inner_radius", Kokkos::RangePolicy<ExecSpace>(0, mesh.n_nodes),
        KOKKOS_LAMBDA(const Index n, double& acc) {
          const double r = math::sqrt(x_n(n, 0) * x_n(n, 0) + x_n(n, 1) * x_n(n, 1));
          acc = r < acc ? r : acc;
        },
        Kokkos::Min<double, ReportSpace>(slots.scalar));
    return;
  }
  const auto cell_nodes = mesh.cell_nodes;
  const auto owned = mesh.cell_owned;  // sums over the ranks' owned cells
  const auto alpha = state.alpha_ck;
  const auto vol = state.vol_c;
  const auto x_c = state.x_c;
  Kokkos::parallel_reduce(  // sum alpha_be a_c, sum alpha_be a_c r_c^2
      "lagremap::diagnostics::shell_mean_radius", Kokkos::RangePolicy<ExecSpace>(0, mesh.n_cells),
      KOKKOS_LAMBDA(const Index c, SumArray<2>& acc) {
        if (!owned(c)) return;
        const double a = alpha(c, 0) * cellArea(x_n, cell_nodes, vol, c);
        acc.v[0] += a;
        acc.v[1] += a * (x_c(c, 0) * x_c(c, 0) + x_c(c, 1) * x_c(c, 1));
      },
      Kokkos::Sum<SumArray<2>, ReportSpace>(slots.sums));
}

double innerRadius(const Mesh& mesh, const State& state, const ProbeSlots& slots) {
  if (state.n_materials == 1) return parallel::min(slots.scalar());
  SumArray<2> be_moments = slots.sums();
  parallel::sum(be_moments.v, 2);
  const double mean_r2 = be_moments.v[1] / be_moments.v[0];
  // the second pass needs the first's mean radius over every rank: waited for
  const auto x_n = mesh.x_n;
  const auto cell_nodes = mesh.cell_nodes;
  const auto owned = mesh.cell_owned;
  const auto alpha = state.alpha_ck;
  const auto vol = state.vol_c;
  const auto x_c = state.x_c;
  double gas_inside = 0.0;
  Kokkos::parallel_reduce(
      "lagremap::diagnostics::shell_inner_gas", Kokkos::RangePolicy<ExecSpace>(0, mesh.n_cells),
      KOKKOS_LAMBDA(const Index c, double& acc) {
        const double r2 = x_c(c, 0) * x_c(c, 0) + x_c(c, 1) * x_c(c, 1);
        if (owned(c) && r2 < mean_r2) acc += alpha(c, 1) * cellArea(x_n, cell_nodes, vol, c);
      },
      gas_inside);
  fenceFor("lagremap::diagnostics: the shell's inner gas");  // (Kokkos 3 reports none)
  return std::sqrt(parallel::sum(gas_inside) / kPi);
}

// Beryllium area in the slab's plane, sum alpha_be v / dz (remap fields; an
// exact sum over the owned cells and the ranks).
double beAreaOf(const FinalFields& fields) {
  ExactSum area;
  for (Index c = 0; c < Index(fields.vol.extent(0)); ++c) {
    if (!fields.counts(c)) continue;
    const double dz = fields.mesh.x_n(fields.mesh.cell_nodes(c, 4), 2) -
                      fields.mesh.x_n(fields.mesh.cell_nodes(c, 0), 2);
    area += fields.alpha(c, 0) * fields.vol(c) / dz;
  }
  if (fields.distributed) area.sumOverRanks();
  return area.value();
}

// The stopping inner radius: the smallest one of the probe's history.
double smallestInnerRadius(const FinalFields& fields) {
  double inner_min = INFINITY;
  for (const auto& [t, r] : fields.probe) inner_min = r < inner_min ? r : inner_min;
  return inner_min;
}

// The collapse must end inside the run: the inner surface's mean inward
// speed over the last 2% of it, against V0 (zero once it rebounds
// elastically, as in lagrange mode). The time of the smallest radius would
// not do: a remapped shell settles without a visible rebound, its inner
// radius still creeping down by micrometres (1e-3 m/s) at t_end.
double finalInwardSpeed(const FinalFields& fields, double t_end) {
  double window_t = NAN, window_r = NAN, last_t = NAN, last_r = NAN;
  for (const auto& [t, r] : fields.probe) {
    if (std::isnan(window_t) && t >= 0.98 * t_end) {
      window_t = t;
      window_r = r;
    }
    last_t = t;
    last_r = r;
  }
  return last_t > window_t ? std::max(0.0, (window_r - last_r) / (last_t - window_t)) : NAN;
}

// shell_radii.csv: the inner radius after every step and the outer radius
// from it (shell area of the initial radii; remap: also of the beryllium area).
void writeRadii(const std::string& out_dir, const FinalFields& fields, bool remap, double ri0,
                double ro0, double shell_area) {
  ResultFile csv(out_dir.empty() ? "" : out_dir + "/shell_radii.csv");
  csv << "t,inner_radius,outer_radius_incompressible" << (remap ? ",outer_radius_be_area\n" : "\n")
      << std::setprecision(10);
  for (const auto& [t, r] : fields.probe) {
    csv << t << ',' << r << ',' << std::sqrt(r * r + ro0 * ro0 - ri0 * ri0);
    if (remap) csv << ',' << std::sqrt(r * r + shell_area);
    csv << '\n';
  }
  csv.write();
}

// Smallest and largest inner radius at t_end (NaN where a ray finds none).
struct RadiusRange {
  double lo = INFINITY, hi = 0.0;
};

// Remap: where the beryllium volume fraction first rises through 1/2 along
// 32 rays from the centre (also written with the outer crossings).
RadiusRange contourInnerRadii(const Config& config, const FinalFields& fields,
                              const std::string& out_dir) {
  RadiusRange range;
  ResultFile contour(out_dir.empty() ? "" : out_dir + "/shell_contour.csv");
  contour << "theta,inner_radius,outer_radius\n" << std::setprecision(10);
  const double z_mid = 0.5 * config.real("geometry.thickness");
  constexpr int kRays = 32;
  for (int ray = 0; ray < kRays; ++ray) {
    const double theta = 2.0 * kPi * (ray + 0.5) / kRays;
    const auto crossings =
        alphaCrossingsAlongRay(fields, 0, {0, 0, z_mid}, {std::cos(theta), std::sin(theta), 0});
    double inner = NAN, outer = NAN;
    for (const AlphaCrossing& crossing : crossings) {
      if (std::isnan(inner) && crossing.rising) inner = crossing.distance;
      if (!std::isnan(inner) && !crossing.rising) {
        outer = crossing.distance;
        break;
      }
    }
    contour << theta << ',' << inner << ',' << outer << '\n';
    range.lo = std::isnan(inner) ? NAN : std::min(range.lo, inner);
    range.hi = std::isnan(inner) ? NAN : std::max(range.hi, inner);
  }
  contour.write();
  return range;
}

// Lagrange: the inner-surface nodes (first radial column of the polar mesh).
RadiusRange surfaceInnerRadii(const FinalFields& fields) {
  RadiusRange range;
  const Index n_cells = Index(fields.rho.extent(0));
  const int nx = fields.nx;
  for (Index c = 0; c < n_cells; ++c) {
    // cells touching the inner surface (i = 0)
    if (!fields.counts(c) || fields.globalCell(c) % nx != 0) continue;
    for (int p : {0, 3}) {  // VTK nodes 0 and 3 lie on the r = Ri side
      const Index node = fields.mesh.cell_nodes(c, p);
      const double r = std::hypot(fields.mesh.x_n(node, 0), fields.mesh.x_n(node, 1));
      range.lo = std::min(range.lo, r);
      range.hi = std::max(range.hi, r);
    }
  }
  if (fields.distributed) range = {parallel::min(range.lo), parallel::max(range.hi)};
  return range;
}

// Howell and Ball's stop for the run's shell, speed and profile.
ShellStop expectedStop(const Config& config) {
  const MaterialParams be = readHypoSolid(config, "be", "Be-hypo");
  try {
    return howellBallStop(be.rho0, be.yield_stress, config.real("shell.inner_radius"),
                          config.real("shell.outer_radius"), config.real("shell.v0"),
                          config.text("shell.profile") == "howell_ball");
  } catch (const std::invalid_argument& error) {
    throw ConfigError(std::string("shell: ") + error.what());
  }
}

// What the inner surface of a stopped shell may still do: ring elastically
// (elasticRingingSpeed), with twice the wave's particle velocity at a free
// surface. Not a fraction of V0: at 300 m/s the stopped beryllium rings at
// 10.5 m/s, 0.035 V0, and a fixed 1% of V0 failed a correct run.
double stoppedShellSpeedBound(const Config& config) {
  const MaterialParams be = readHypoSolid(config, "be", "Be-hypo");
  const double longitudinal = std::sqrt(be.a0 * be.a0 + (4.0 / 3.0) * shearModulus(be) / be.rho0);
  return 2.0 * elasticRingingSpeed(be.rho0, be.yield_stress, longitudinal);
}

// The checks: stopping radii, roundness at t_end and the final inward speed,
// against Howell and Ball's energy balance for the run's parameters (or the
// radii the user gives). The radii are reached only once the run lasts past
// the stop; the final speed is measured over the last 2% of the run, which
// must lie after the stop (with 5% of its time to spare) to mean "stopped".
std::vector<Check> shellChecks(const Config& config, double inner_min, double outer_at_stop,
                               const RadiusRange& inner, double inward_speed) {
  const bool remap = config.remapSetup();
  const double tol = config.real("check.radius_tolerance");
  const ShellStop stop = expectedStop(config);
  const double user_inner = config.real("check.inner_radius");
  const double user_outer = config.real("check.outer_radius");
  std::vector<Check> checks{
      {"stopping_inner_radius", inner_min, user_inner > 0.0 ? user_inner : stop.inner_radius, tol,
       remap ? "smallest equal-area radius of the gas inside the shell over the run (paper 51 mm "
               "at its V0)"
             : "smallest inner radius over the run"},
      {"stopping_outer_radius", outer_at_stop, user_outer > 0.0 ? user_outer : stop.outer_radius,
       tol,
       remap ? "outer radius when the inner one stops, from the beryllium area at t_end (paper "
               "79 mm at its V0)"
             : "outer radius when the inner one stops, from the shell's area"},
      {"inner_circularity", (inner.hi - inner.lo) / inner.lo, 0.0, remap ? 0.05 : 0.01,
       remap ? "(max - min) / min of the alpha = 1/2 inner radius along 32 rays at t_end"
             : "(max - min) / min of the inner-surface radius at t_end: the shell stays "
               "round"},
      {"final_inward_speed", inward_speed, 0.0, stoppedShellSpeedBound(config),
       "mean inward speed [m/s] of the inner surface over the last 2% of the run (0 when "
       "rebounding) within twice the elastic ringing speed Y / (rho c_L): the shell has "
       "stopped by t_end"}};
  checks[0].source = user_inner > 0.0 ? "check.inner_radius (user)" : "Howell-Ball";
  checks[1].source = user_outer > 0.0 ? "check.outer_radius (user)" : "Howell-Ball";
  checks[2].source = "round";
  checks[3].source = "at rest after the Howell-Ball stop";
  const double t_end = config.real("t_end");
  char stop_text[96];
  std::snprintf(stop_text, sizeof stop_text, "Howell-Ball stop at %.4g us", stop.time * 1e6);
  if (t_end < stop.time) {
    for (int i : {0, 1}) {
      checks[i].doesNotApply("t_end = " + config.text("t_end") + " s ends before the " + stop_text);
    }
  }
  if (0.98 * t_end < 1.05 * stop.time) {
    checks[3].doesNotApply("the last 2% of the run (from " + config.text("t_end") +
                           " s x 0.98) is not after the " + stop_text + " with 5% to spare");
  }
  if (remap && !differenceFromDefaultCase(config).size()) {  // the paper's remap run
    checks[0].paper = kPaperInnerRadius;
    checks[1].paper = kPaperOuterRadius;
  }
  // (Howell and Ball's energy balance is perfectly plastic: a user's radii
  // are the user's)
  std::vector<std::string> howell_ball = {"final_inward_speed"};
  if (!(user_inner > 0.0)) howell_ball.push_back("stopping_inner_radius");
  if (!(user_outer > 0.0)) howell_ball.push_back("stopping_outer_radius");
  markPerfectPlasticityOnly(config, checks, "be", howell_ball);
  setModeIndependentReferences(config, checks);
  return checks;
}

ProblemResults finishShell(const Config& config, const FinalFields& fields,
                           const std::string& out_dir) {
  const bool remap = config.remapSetup();
  const double inner_min = smallestInnerRadius(fields);
  const double inward_speed = finalInwardSpeed(fields, config.real("t_end"));
  // Lagrange: the shell is incompressible to first order, so the outer radius
  // follows from the inner one by conservation of the shell's area,
  // r_o^2 - r_i^2 = const. Remap: the same with the beryllium area measured
  // at t_end from the volume fractions (the probe holds one number per step;
  // the area changes by the elastic compression only, ~1e-3, i.e. ~0.02 mm
  // on the outer radius).
  const double ri0 = config.real("shell.inner_radius"), ro0 = config.real("shell.outer_radius");
  const double shell_area = remap ? beAreaOf(fields) / kPi : ro0 * ro0 - ri0 * ri0;
  const double outer_at_stop = std::sqrt(inner_min * inner_min + shell_area);
  writeRadii(out_dir, fields, remap, ri0, ro0, shell_area);
  writeCellOutlines(out_dir.empty() ? "" : out_dir + "/shell_mesh_z0.csv", fields);
  // Roundness of the inner surface at t_end: (max - min) / min of its radius.
  const RadiusRange inner =
      remap ? contourInnerRadii(config, fields, out_dir) : surfaceInnerRadii(fields);
  return shellChecks(config, inner_min, outer_at_stop, inner, inward_speed);
}

}  // namespace

extern const Problem kShellProblem = {
    "shell",
    "collapse of a thick beryllium shell (hypo-elastic; polar mesh, or in gas in remap mode)",
    declareShell,
    setupShell,
    finishShell,
    {sampleInnerRadius, innerRadius, "inner_radius"}};

}  // namespace lagremap
