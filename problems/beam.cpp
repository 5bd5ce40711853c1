// `beam` — a Neo-Hookean beryllium plate set vibrating in its first free-free
// bending mode, docs/verification.md §8.5: [-0.03,0.03] x [-0.005,0.005]^2, symmetry on
// the z faces, V = (0, Vy(x), 0) with the mode shape (the minus sign between
// the brackets: the paper's '+' would start the far end at ~65 km/s).
// Lagrange mode: the plate alone, 100 x 10 x 10, free elsewhere.
// Remap mode: the plate in gas (5 kg/m^3, at rest, 1e5 Pa) on the fixed
// 100 x 40 x 10 mesh of [-0.035,0.035] x [-0.015,0.015] x [-0.005,0.005],
// walls on the x and y faces.
// Output: the tip's vertical displacement history.
// Check: the half period of the sinusoid fitted to the tip displacement
// record (fittedHalfPeriod), against pi / w (w = 2.3597e5, period 26.6 us, from
// Euler-Bernoulli theory) corrected to first order for shear and rotary
// inertia (Timoshenko), which lengthen the period of this thick plate by ~10%.
#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>

#include "../src/diagnostics.hpp"
#include "../src/kokkos_events.hpp"
#include "../src/problem.hpp"
#include "../src/time_series.hpp"

namespace lagremap {
namespace {

void declareBeam(Config& config) {
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
  if (config.remapSetup()) {
    // The plate fills the domain's depth: its z faces are the domain's symmetry planes.
    config.addReal("domain.length", 0.07, "m", "fixed mesh extent along x (remap)");
    config.addReal("domain.height", 0.03, "m", "fixed mesh extent along y (remap)");
    config.addReal("gas.rho", 5.0, "kg/m^3", "density of the surrounding gas");
    config.addReal("gas.p", 1e5, "Pa", "pressure of the surrounding gas");
    config.addReal("gas.gamma", 1.4, "-", "ratio of specific heats of the gas");
    declareMeshKeys(config, 100, 40, 10);
    declareBoundaryKeys(config, {"wall", "wall", "wall", "wall", "symmetry", "symmetry"});
  } else {
    declareMeshKeys(config, 100, 10, 10);
    declareBoundaryKeys(config, {"free", "free", "free", "free", "symmetry", "symmetry"});
  }
  config.addReal("check.period_tolerance", 0.05, "-",
                 "relative tolerance on the half period (vs Timoshenko-corrected theory)");
}

ProblemSetup setupBeam(const Config& config) {
  const MaterialParams be = readNeoHookean(config, "be", "Be-hyper");
  const double length = config.real("geometry.length"), height = config.real("geometry.height");
  const double depth = config.real("geometry.depth");
  if (!(length > 0 && height > 0 && depth > 0)) throw ConfigError("beam: sizes must be positive");
  const double a = config.real("mode.A"), w = config.real("mode.w");
  const double omega = config.real("mode.Omega");
  const double g1 = config.real("mode.g1"), g2 = config.real("mode.g2");
  const auto modeVelocity = [=](const Vec3& x) {
    const double k = omega * (x.x + length / 2);
    return Vec3{
        0.0, a * w * (g2 * (std::cosh(k) + std::cos(k)) - g1 * (std::sinh(k) + std::sin(k))), 0.0};
  };
  CellShapes shapes;
  if (config.remapSetup()) {
    const AmbientGas gas = readAmbientGas(config, "beam");
    const double domain_length = config.real("domain.length");
    const double domain_height = config.real("domain.height");
    if (!(domain_length > length && domain_height > height)) {
      throw ConfigError("beam: the remap domain must contain the plate");
    }
    ProblemSetup setup =
        setupBlock(config, {-domain_length / 2, -domain_height / 2, -depth / 2},
                   {domain_length / 2, domain_height / 2, depth / 2}, {be, gas.material}, shapes);
    MaterialRegions regions;
    regions.material_at = [=](const Vec3& x) {
      return std::abs(x.x) <= 0.5 * length && std::abs(x.y) <= 0.5 * height ? 0 : 1;
    };
    regions.rho = {be.rho0, gas.rho};
    regions.e = {0.0, gas.e};
    regions.velocity = [=](int material, const Vec3& x) {
      return material == 0 ? modeVelocity(x) : Vec3{0, 0, 0};
    };
    fillMaterialRegions(setup, regions);
    return setup;
  }
  ProblemSetup setup = setupBlock(config, {-length / 2, -height / 2, -depth / 2},
                                  {length / 2, height / 2, depth / 2}, {be}, shapes);
  for (const Vec3& x : shapes.centroid) {
    setup.cells.rho.push_back(be.rho0);
    setup.cells.e.push_back(0.0);
    setup.cells.v.push_back(modeVelocity(x));
    setup.cells.mat.push_back(0);
  }
  return setup;
}

// Tip displacement (zero initially by symmetry of the cross-section).
// Lagrange: mean y of the centroids of the cells on the x-max face (the
// centre of the end face, half a cell inside; it turns with the end).
// Remap: the centre of the end face too: the mean y of the mixed cells of
// the half x > 0 whose beryllium interface normal (State::n_ck, from the
// last remap) points along the plate rather than across it,
// |n_x| > |n_y|, weighted by alpha (1 - alpha) v (the interface's share of
// the cell). Before the first remap (no normals; the tip is at y = 0 by
// symmetry) the beryllium-mass-weighted mean y of the cells reaching into
// the plate's last 3% of length. That vertical cut was the measure until
// the end had turned by 30 degrees (7 us) and it held the lower corner of
// the end face, not its centre: half the lagrange amplitude.
void sampleTipDisplacement(const Mesh& mesh, const State& state, const ProbeSlots& slots) {
  if (state.n_materials == 1) return sampleSideMeanCentroid(mesh, state, 1, 1, slots);
  const auto alpha_k = state.alpha_ck;
  const auto normal_k = state.n_ck;
  const auto volume = state.vol_c;
  const auto x_c = state.x_c;
  const auto owned = mesh.cell_owned;  // sums over the ranks' owned cells
  Kokkos::parallel_reduce(             // sum w, sum w y over the end face's cells
      "lagremap::diagnostics::beam_end_face", Kokkos::RangePolicy<ExecSpace>(0, mesh.n_cells),
      KOKKOS_LAMBDA(const Index c, SumArray<2>& acc) {
        const double alpha = alpha_k(c, 0);
        if (!owned(c) || !(x_c(c, 0) > 0.0) || !(alpha > 0.01 && alpha < 0.99)) return;
        const double n_x = normal_k(c, 0, 0), n_y = normal_k(c, 0, 1);
        if (!(math::fabs(n_x) > math::fabs(n_y))) return;
        const double weight = alpha * (1.0 - alpha) * volume(c);
        acc.v[0] += weight;
        acc.v[1] += weight * x_c(c, 1);
      },
      Kokkos::Sum<SumArray<2>, ReportSpace>(slots.sums));
}

// Before the first remap: the tip region's mean y, two dependent passes
// (each waited for: the set-up's measurement, or a step without an end face).
double tipRegionMeanY(const Mesh& mesh, const State& state) {
  const auto x_n = mesh.x_n;
  const auto cell_nodes = mesh.cell_nodes;
  const auto m_k = state.m_ck;
  const auto x_c = state.x_c;
  const auto owned = mesh.cell_owned;
  SumArray<2> half;  // sum m_be, sum m_be x over x > 0
  Kokkos::parallel_reduce(
      "lagremap::diagnostics::beam_half_moment", Kokkos::RangePolicy<ExecSpace>(0, mesh.n_cells),
      KOKKOS_LAMBDA(const Index c, SumArray<2>& acc) {
        if (owned(c) && x_c(c, 0) > 0.0) {
          acc.v[0] += m_k(c, 0);
          acc.v[1] += m_k(c, 0) * x_c(c, 0);
        }
      },
      Kokkos::Sum<SumArray<2>>(half));
  fenceFor("lagremap::diagnostics: the beam's half moment");  // (Kokkos 3 reports none)
  parallel::sum(half.v, 2);
  const double x_tip = 2.0 * half.v[1] / half.v[0];
  const double x_region = 0.97 * x_tip;
  SumArray<2> tip;  // sum m_be, sum m_be y over the tip region
  Kokkos::parallel_reduce(
      "lagremap::diagnostics::beam_tip_moment", Kokkos::RangePolicy<ExecSpace>(0, mesh.n_cells),
      KOKKOS_LAMBDA(const Index c, SumArray<2>& acc) {
        // VTK nodes 0 and 1 are the ends of the cell's first x-edge.
        const double half_width = 0.5 * (x_n(cell_nodes(c, 1), 0) - x_n(cell_nodes(c, 0), 0));
        if (owned(c) && x_c(c, 0) + half_width > x_region) {
          acc.v[0] += m_k(c, 0);
          acc.v[1] += m_k(c, 0) * x_c(c, 1);
        }
      },
      Kokkos::Sum<SumArray<2>>(tip));
  fenceFor("lagremap::diagnostics: the beam's tip moment");
  parallel::sum(tip.v, 2);
  return tip.v[1] / tip.v[0];
}

double tipDisplacement(const Mesh& mesh, const State& state, const ProbeSlots& slots) {
  if (state.n_materials == 1) return meanOverRanks(slots);
  SumArray<2> end_face = slots.sums();
  parallel::sum(end_face.v, 2);
  if (end_face.v[0] > 0.0) return end_face.v[1] / end_face.v[0];
  return tipRegionMeanY(mesh, state);
}

ProblemResults finishBeam(const Config& config, const FinalFields& fields,
                          const std::string& out_dir) {
  ResultFile csv(out_dir.empty() ? "" : out_dir + "/beam_tip.csv");
  csv << "t,tip_displacement_y\n" << std::setprecision(10);
  for (const auto& [t, y] : fields.probe) csv << t << ',' << y << '\n';
  csv.write();
  // The tip starts moving up: its first downward crossing comes once it has
  // been up (above half its largest excursion: the remap's end-face measure
  // starts a few microns below zero as the corner cells fill and empty, and
  // crossed zero in the first step).
  double amplitude = 0.0;
  for (const auto& sample : fields.probe) amplitude = std::max(amplitude, std::abs(sample.second));
  double first_crossing = NAN;
  bool has_been_up = false;
  for (std::size_t i = 1; i < fields.probe.size(); ++i) {
    const auto& [t0, y0] = fields.probe[i - 1];
    const auto& [t1, y1] = fields.probe[i];
    has_been_up = has_been_up || y0 > 0.5 * amplitude;
    if (has_been_up && y0 > 0.0 && y1 <= 0.0) {
      first_crossing = t0 + (t1 - t0) * y0 / (y0 - y1);  // linear interpolation of the crossing
      break;
    }
  }
  // Euler-Bernoulli's w ignores shear deformation and rotary inertia, which
  // matter for this thick plate (L/h = 6): the first-order Timoshenko
  // correction w_T / w = 1 - (beta L)^2 (r/L)^2 (1 + E/(k G)) / 2, with
  // r^2 = h^2/12, beta L = Omega L, k = 5/6 and E/G = 2 (1 + nu), is -9%.
  // The plate's own first free-free mode (beta L = 4.7300, the first root of
  // cos(bL) cosh(bL) = 1): w_EB = beta^2 sqrt(E h^2 / (12 rho)), from the
  // run's geometry and material (the mode.* keys only shape the initial
  // velocity).
  const double length = config.real("geometry.length"), height = config.real("geometry.height");
  constexpr double kFirstFreeFreeRoot = 4.730040744862704;
  const double beta = kFirstFreeFreeRoot / length;
  const double w_plate =
      beta * beta * height * std::sqrt(config.real("be.young") / (12.0 * config.real("be.rho0")));
  const double beta_l = kFirstFreeFreeRoot;
  const double slender = height * height / (12.0 * length * length);
  const double ratio = 1.0 - 0.5 * beta_l * beta_l * slender *
                                 (1.0 + 2.0 * (1.0 + config.real("be.poisson")) / (5.0 / 6.0));
  const double exact = 3.14159265358979323846 / (w_plate * ratio);
  // (The paper gives no number, only Fig. 12's curves.)
  // The period from the whole record, not one zero crossing: the first
  // crossing carries the higher modes the initial velocity (Euler-Bernoulli's
  // mode shape) excites in this thick plate, and the remap's end-face measure
  // jumps by up to 0.3 mm as cells enter and leave it (0.4 us at the
  // crossing's speed).
  const double half_period = fittedHalfPeriod(fields.probe, 0.5 * exact, 1.5 * exact);
  std::ostringstream note;
  note << std::setprecision(4)
       << "half period of the sinusoid a sin(wt) + b cos(wt) + c fitted (least squares) to the "
          "whole tip record vs pi / w with the first-order Timoshenko correction "
          "(Euler-Bernoulli: 13.3 us); the tip's first downward zero crossing: "
       << first_crossing * 1e6 << " us";
  std::vector<Check> checks{{"half_period", half_period, exact,
                             config.real("check.period_tolerance") * exact, note.str()}};
  checks[0].source = "Timoshenko";
  if (fields.time < 1.5 * exact) {  // the fit needs more than one half period of record
    checks[0].doesNotApply("the run ends before 1.5 half periods of the plate's first mode");
  }
  setModeIndependentReferences(config, checks);
  return checks;
}

}  // namespace

extern const Problem kBeamProblem = {
    "beam",      "3D Neo-Hookean beryllium plate vibrating in its first bending mode",
    declareBeam, setupBeam,
    finishBeam,  {sampleTipDisplacement, tipDisplacement, "tip_displacement_y"}};

}  // namespace lagremap
