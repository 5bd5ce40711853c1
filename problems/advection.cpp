// `advection` and `advection1d` — the standard test of a mixed-cell closure
// (docs/verification.md): an aluminium body (Mie-Gruneisen, hypo-elastic) and
// the gas round it translate together at a uniform velocity and pressure
// through the fixed mesh, remap mode only. `advection`: a disc in the x-y
// plane moving along the diagonal (mixed cells of every shape); `advection1d`:
// a slab moving along x through a row of cells. The open sides carry the gas
// pressure as a traction (what flows in is the boundary cell's own state,
// docs/method.md §5.8), z is a symmetry plane.
// Exact answer: nothing changes but the body's position. Checks: the
// pressure and the velocity stay uniform and every material keeps its
// density, to round-off (the tolerances below), and the body's centroid moves
// by v t (to a tenth of a cell). probe.csv: the centroid's x after every step.
// L1 errors: against the initial densities translated by v t, each cell's
// exact density its mixture of the body's and the gas's by the body's exact
// volume fraction.
#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

#include "../kernels/sum_array.hpp"
#include "../src/exact_sum.hpp"
#include "../src/problem.hpp"
#include "uniform_flow.hpp"

namespace lagremap {
namespace {

enum AdvectionMaterial : int { kBody = 0, kGas = 1 };

// Round-off tolerances: each step may add rounding errors of a few hundred
// units in the last place (1e-13, relative) to a density or a velocity, over
// the run's steps; a stiff material's pressure moves by K drho / rho (K = rho
// a^2 = 79 GPa for the aluminium), so its relative error is K / p0 times the
// density's; the velocity, pushed by those pressure errors, gets ten times
// the allowance. Measured (2026-12-03): densities within 7e-11 and velocities
// within 3.2e-10 after 3255 steps (advection1d, both closures).
constexpr double kRoundOffPerStep = 1e-13;
constexpr double kVelocityRoundOffPerStep = 1e-12;

void declareAdvection(Config& config, bool two_d) {
  const std::string name = two_d ? "advection" : "advection1d";
  refuseLagrangeMode(config, name,
                     "the test is of the remap's mixed cells: in lagrange mode the mesh moves "
                     "with the body and nothing is mixed");
  config.addReal("t_end", two_d ? 1.5e-3 : 2e-3, "s", "final time");
  declareHypoSolidKeys(config, "al", "Al");
  config.addReal("body.vx", 100.0, "m/s", "velocity of the body and the gas along x");
  config.addReal("body.vy", two_d ? 50.0 : 0.0, "m/s", "velocity along y");
  if (two_d) {
    config.addReal("body.x", 0.35, "m", "disc centre x");
    config.addReal("body.y", 0.35, "m", "disc centre y");
    config.addReal("body.radius", 0.2, "m", "disc radius");
  } else {
    config.addReal("body.x_min", 0.2, "m", "slab extent along x");
    config.addReal("body.x_max", 0.5, "m", "slab extent along x");
  }
  config.addReal("gas.rho", 1.0, "kg/m^3", "gas density");
  config.addReal("gas.p", 1e5, "Pa", "pressure of the gas and the body");
  config.addReal("gas.gamma", 1.4, "-", "ratio of specific heats of the gas");
  declareFlowBox(config, two_d, 1.0, two_d ? 50 : 100, two_d ? 0.02 : 0.01, 1e5);
}

void declareAdvection2D(Config& config) {
  declareAdvection(config, true);
}
void declareAdvection1D(Config& config) {
  declareAdvection(config, false);
}

struct AdvectionCase {
  bool two_d = true;
  FlowBox box;
  double vx = 0, vy = 0, x = 0, y = 0, radius = 0, x_min = 0, x_max = 0, length = 0;
  double p0 = 0, rho_gas = 0, e_gas = 0, rho_body = 0, e_body = 0;
  bool inBody(const Vec3& point) const {
    return two_d ? std::hypot(point.x - x, point.y - y) <= radius
                 : point.x >= x_min && point.x <= x_max;
  }
  // Whether the body, moved by v t, still lies inside the domain (the
  // exact solution holds there).
  bool insideAt(double t) const {
    const double dx = vx * t, dy = vy * t;
    return two_d ? x + dx - radius > 0 && x + dx + radius < length && y + dy - radius > 0 &&
                       y + dy + radius < length
                 : x_min + dx > 0 && x_max + dx < length;
  }
  // The body's volume fraction, moved by v t, of the cell centred at c: the
  // slab's overlap exactly; the disc's from 64 x 64 midpoint samples where
  // the circle crosses the cell (to 1/64 of a cut cell at worst, a small
  // part of the one-cell error of a captured interface).
  double bodyFraction(const Vec3& c, double t) const {
    const double x0 = c.x - 0.5 * box.dx, x1 = c.x + 0.5 * box.dx;
    if (!two_d) {
      const double lo = std::max(x0, x_min + vx * t), hi = std::min(x1, x_max + vx * t);
      return std::max(hi - lo, 0.0) / box.dx;
    }
    const double y0 = c.y - 0.5 * box.dy, y1 = c.y + 0.5 * box.dy;
    const double cx = x + vx * t, cy = y + vy * t;
    const double near_x = std::max({x0 - cx, 0.0, cx - x1}),
                 near_y = std::max({y0 - cy, 0.0, cy - y1});
    if (std::hypot(near_x, near_y) >= radius) return 0.0;
    const double far_x = std::max(std::abs(x0 - cx), std::abs(x1 - cx));
    const double far_y = std::max(std::abs(y0 - cy), std::abs(y1 - cy));
    if (std::hypot(far_x, far_y) <= radius) return 1.0;
    constexpr int kSamples = 64;
    int inside = 0;
    for (int i = 0; i < kSamples; ++i) {
      for (int j = 0; j < kSamples; ++j) {
        const double px = x0 + (i + 0.5) * box.dx / kSamples;
        const double py = y0 + (j + 0.5) * box.dy / kSamples;
        inside += std::hypot(px - cx, py - cy) <= radius;
      }
    }
    return double(inside) / double(kSamples * kSamples);
  }
};

AdvectionCase readAdvection(const Config& config, bool two_d) {
  const std::string name = two_d ? "advection" : "advection1d";
  AdvectionCase a;
  a.two_d = two_d;
  a.vx = config.real("body.vx");
  a.vy = config.real("body.vy");
  a.p0 = config.real("gas.p");
  a.box = readFlowBox(config, name, two_d, a.p0);
  a.length = a.box.length;
  if (two_d) {
    a.x = config.real("body.x");
    a.y = config.real("body.y");
    a.radius = config.real("body.radius");
    if (!(a.radius > 0 && a.x - a.radius > 0 && a.x + a.radius < a.length && a.y - a.radius > 0 &&
          a.y + a.radius < a.length)) {
      throw ConfigError(name + ": the disc must lie inside the domain");
    }
  } else {
    a.x_min = config.real("body.x_min");
    a.x_max = config.real("body.x_max");
    if (!(a.x_min > 0 && a.x_min < a.x_max && a.x_max < a.length)) {
      throw ConfigError(name + ": need 0 < body.x_min < body.x_max < domain.length");
    }
    if (a.vy != 0.0) throw ConfigError(name + ": body.vy must be 0 (a row of cells)");
  }
  const AmbientGas gas = readAmbientGas(config, name);
  a.rho_gas = gas.rho;
  a.e_gas = gas.e;
  const MaterialParams al = readHypoSolid(config, "al", "Al");
  a.rho_body = al.rho0;
  a.e_body = a.p0 / (al.rho0 * al.Gamma0);  // Mie-Gruneisen at rho0 and the gas pressure
  return a;
}

ProblemSetup setupAdvection(const Config& config, bool two_d) {
  const AdvectionCase a = readAdvection(config, two_d);
  const MaterialParams al = readHypoSolid(config, "al", "Al");
  MaterialParams gas;
  gas.gamma = config.real("gas.gamma");
  CellShapes shapes;
  ProblemSetup setup = setupFlowBox(config, a.box, {al, gas}, shapes);
  MaterialRegions regions;
  regions.material_at = [=](const Vec3& x) { return a.inBody(x) ? kBody : kGas; };
  regions.rho = {a.rho_body, a.rho_gas};
  regions.e = {a.e_body, a.e_gas};
  regions.velocity = [=](int, const Vec3&) { return Vec3{a.vx, a.vy, 0}; };
  fillMaterialRegions(setup, regions);
  return setup;
}

ProblemSetup setupAdvection2D(const Config& config) {
  return setupAdvection(config, true);
}
ProblemSetup setupAdvection1D(const Config& config) {
  return setupAdvection(config, false);
}

// The body's centroid x (volume-fraction weighted), after every step: its
// history is advection_body.csv, and its length the number of steps.
void sampleBodyCentroidX(const Mesh& mesh, const State& state, const ProbeSlots& slots) {
  const auto alpha = state.alpha_ck;
  const auto vol = state.vol_c;
  const auto x_c = state.x_c;
  const auto owned = mesh.cell_owned;  // sums over the ranks' owned cells
  Kokkos::parallel_reduce(             // sum alpha v, sum alpha v x
      "lagremap::diagnostics::body_centroid", Kokkos::RangePolicy<ExecSpace>(0, mesh.n_cells),
      KOKKOS_LAMBDA(const Index c, SumArray<2>& acc) {
        if (!owned(c)) return;
        acc.v[0] += alpha(c, kBody) * vol(c);
        acc.v[1] += alpha(c, kBody) * vol(c) * x_c(c, 0);
      },
      Kokkos::Sum<SumArray<2>, ReportSpace>(slots.sums));
}
double bodyCentroidX(const Mesh&, const State&, const ProbeSlots& slots) {
  return ratioOverRanks(slots);
}

ProblemResults finishAdvection(const Config& config, const FinalFields& fields, bool two_d) {
  const AdvectionCase a = readAdvection(config, two_d);
  const double speed = std::hypot(a.vx, a.vy);
  const double rho0[2] = {a.rho_body, a.rho_gas};
  // Bulk moduli K = rho a^2 at the initial states: under pressure equilibrium
  // (the relaxation closure) a stiff material's rounding error of its density
  // becomes a soft one's density change K_stiff / K_soft times larger; each
  // material's error is weighed by what it does to the pressure, K drho / rho.
  const MaterialParams al = readHypoSolid(config, "al", "Al");
  const double bulk[2] = {al.rho0 * al.a0 * al.a0, config.real("gas.gamma") * a.p0};
  // (the probe's first entry is the initial state, one more per step)
  const double steps = fields.probe.empty() ? 1.0 : double(fields.probe.size() - 1);
  const double round_off = kRoundOffPerStep * std::max(steps, 1.0);
  double pressure = 0.0, velocity = 0.0, density = 0.0;
  ExactSum body_volume, body_x, body_y;
  const Index n_cells = Index(fields.rho.extent(0));
  for (Index c = 0; c < n_cells; ++c) {
    if (!fields.counts(c)) continue;
    pressure = std::max(pressure, std::abs(fields.p(c) - a.p0) / a.p0);
    for (int k = 0; k < 2; ++k) {
      // (a trace, below alpha_trace, is no material state: its density is
      // the ratio of two tiny numbers, docs/method.md §4.6)
      const double alpha = fields.alpha(c, k);
      if (!(alpha >= config.real("remap.alpha_trace"))) continue;
      pressure = std::max(pressure, std::abs(fields.p_k(c, k) - a.p0) / a.p0);
      const double rho = fields.m_k(c, k) / (alpha * fields.vol(c));
      density = std::max(density, std::abs(rho - rho0[k]) / rho0[k] * bulk[k] / bulk[kBody]);
    }
    const double dv[3] = {fields.v(c, 0) - a.vx, fields.v(c, 1) - a.vy, fields.v(c, 2)};
    velocity = std::max(velocity, std::sqrt(dv[0] * dv[0] + dv[1] * dv[1] + dv[2] * dv[2]) / speed);
    const double body = fields.alpha(c, kBody) * fields.vol(c);
    body_volume += body;
    body_x += body * fields.x_c(c, 0);
    body_y += body * fields.x_c(c, 1);
  }
  if (fields.distributed) {
    pressure = parallel::max(pressure);
    velocity = parallel::max(velocity);
    density = parallel::max(density);
    std::vector<ExactSum> sums{body_volume, body_x, body_y};
    ExactSum::sumOverRanks(sums);
    body_volume = sums[0];
    body_x = sums[1];
    body_y = sums[2];
  }
  const double t = fields.time;
  const double x_start = two_d ? a.x : 0.5 * (a.x_min + a.x_max);
  const double shift_x = body_x.value() / body_volume.value() - x_start - a.vx * t;
  const double shift_y = two_d ? body_y.value() / body_volume.value() - a.y - a.vy * t : 0.0;
  const double cell = a.length / double(config.integer("mesh.nx"));
  // (the stiffest material's pressure moves by K drho / rho: bound it with K / p0)
  const double stiffness = bulk[kBody] / a.p0;
  std::vector<Check> checks;
  checks.push_back({"uniform_pressure", pressure, 0.0, round_off * stiffness,
                    "max |p - p0| / p0 over the cells' and their materials' pressures (round-off: "
                    "1e-13 per step times the aluminium's bulk modulus / p0)"});
  checks.push_back({"uniform_velocity", velocity, 0.0,
                    round_off * kVelocityRoundOffPerStep / kRoundOffPerStep,
                    "max |v - v0| / |v0| over the cells (round-off: 1e-12 per step)"});
  checks.push_back({"material_density", density, 0.0, round_off,
                    "max K^k |rho^k - rho^k_0| / (rho^k_0 K_Al) over the materials above "
                    "alpha_trace in every cell, K = rho a^2 (round-off: 1e-13 per step; each "
                    "material keeps its density)"});
  checks.push_back({"body_centroid", std::hypot(shift_x, shift_y) / cell, 0.0, 0.1,
                    "distance of the body's centroid (volume-fraction weighted) from its start "
                    "+ v t, in cells"});
  for (Check& check : checks) check.source = "exact: uniform translation";
  ProblemResults results = std::move(checks);
  if (a.insideAt(t)) {
    const auto exact_density = [&](Index c) {
      const double alpha = a.bodyFraction({fields.x_c(c, 0), fields.x_c(c, 1), 0.0}, t);
      return alpha * a.rho_body + (1.0 - alpha) * a.rho_gas;
    };
    results.l1_errors =
        flowL1Errors(fields, a.box, {a.vx, a.vy, 0.0}, a.p0, exact_density,
                     std::string("each cell's density the mixture of the body's and the gas's by "
                                 "the body's volume fraction, its initial shape moved by V t (") +
                         (two_d ? "64 x 64 samples in a cell the circle crosses)" : "exactly)"));
  }
  return results;
}

ProblemResults finishAdvection2D(const Config& config, const FinalFields& fields,
                                 const std::string&) {
  return finishAdvection(config, fields, true);
}
ProblemResults finishAdvection1D(const Config& config, const FinalFields& fields,
                                 const std::string&) {
  return finishAdvection(config, fields, false);
}

}  // namespace

extern const Problem kAdvectionProblem = {
    "advection",
    "aluminium disc and gas translating together through the fixed mesh (remap only): "
    "uniform p and v, each material's density kept",
    declareAdvection2D,
    setupAdvection2D,
    finishAdvection2D,
    {sampleBodyCentroidX, bodyCentroidX, "body_centroid_x"}};

extern const Problem kAdvection1DProblem = {
    "advection1d",
    "aluminium slab and gas translating together along a row of cells (remap only): uniform p "
    "and v, each material's density kept",
    declareAdvection1D,
    setupAdvection1D,
    finishAdvection1D,
    {sampleBodyCentroidX, bodyCentroidX, "body_centroid_x"}};

}  // namespace lagremap
