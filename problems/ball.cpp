// `ball` — an aluminium ball hits an aluminium plate at 1000 m/s
// (Mie-Gruneisen, hypo-elastic perfectly plastic), docs/verification.md §8.7, in remap
// mode only: the ball (R = 0.5 mm, centred at (-4, 0) mm) and the plate
// x in [-3.45, -2.45] mm, y in [-2, 2] mm (the paper gives no extent: a 50
// micron gap) in near-vacuum gas (1e-5 kg/m^3, at rest, 1e-5 Pa) on the fixed
// 150 x 200 mesh of [-5, -1.5] x [-2.5, 2.5] mm, one cell thick in z, walls
// all round. The ball and the plate are separate materials with the same
// parameters, so the ball can be followed through the impact.
// Output: snapshots at 0, 0.5, ... 2.5 us (paper Fig. 14), the ball's centroid
// against time, the ball and crater positions on the axis at t_end.
// Checks (no reference numbers from the paper, which shows pictures): the total
// x-momentum is the ball's initial one while nothing pushes on the walls, the
// centre of mass of everything moves by that momentum over the total mass,
// and the ball's centroid advances by less than in free flight.
#include <algorithm>
#include <cmath>
#include <iomanip>

#include "../src/diagnostics.hpp"
#include "../src/exact_sum.hpp"
#include "../src/problem.hpp"

namespace lagremap {
namespace {

// Material indices; enumerators, not variables, so that device code may use them.
enum BallMaterial : int { kBall = 0, kPlate = 1, kGas = 2 };

void declareBall(Config& config) {
  refuseLagrangeMode(config, "ball",
                     "the ball and the plate are two separate bodies that come into contact, "
                     "which one Lagrangian mesh cannot hold, and the paper has no "
                     "Lagrangian reference");
  config.addReal("t_end", 2.5e-6, "s", "final time");
  declareHypoSolidKeys(config, "al", "Al");
  config.addReal("al.p0", 1e5, "Pa", "initial pressure of the ball and the plate");
  config.addReal("ball.radius", 5e-4, "m", "ball radius R");
  config.addReal("ball.x", -4e-3, "m", "ball centre x");
  config.addReal("ball.y", 0.0, "m", "ball centre y");
  config.addReal("ball.vx", 1000.0, "m/s", "ball velocity along x");
  config.addReal("plate.x_min", -3.45e-3, "m", "plate extent (not given by the paper)");
  config.addReal("plate.x_max", -2.45e-3, "m", "plate extent (not given by the paper)");
  config.addReal("plate.y_min", -2e-3, "m", "plate extent (not given by the paper)");
  config.addReal("plate.y_max", 2e-3, "m", "plate extent (not given by the paper)");
  config.addReal("domain.x_min", -5e-3, "m", "fixed mesh extent");
  config.addReal("domain.x_max", -1.5e-3, "m", "fixed mesh extent");
  config.addReal("domain.y_min", -2.5e-3, "m", "fixed mesh extent");
  config.addReal("domain.y_max", 2.5e-3, "m", "fixed mesh extent");
  config.addReal("gas.rho", 1e-5, "kg/m^3", "density of the surrounding gas");
  config.addReal("gas.p", 1e-5, "Pa", "pressure of the surrounding gas");
  config.addReal("gas.gamma", 1.4, "-", "ratio of specific heats of the gas");
  // One cell thick: about the in-plane cell size (23.3 x 25 microns), so that z does not set dt.
  config.addCellLength("geometry.thickness", 2.5e-5, "slab thickness along z (one cell)");
  declareMeshKeys(config, 150, 200, 1);
  declareBoundaryKeys(config, {"wall", "wall", "wall", "wall", "symmetry", "symmetry"});
  config.addReal("check.momentum_tolerance", 1e-4, "-",
                 "relative tolerance on the total x-momentum (what the gas gives the walls)");
  config.addReal("check.centre_of_mass_tolerance", 0.02, "-",
                 "relative tolerance on the centre of mass shift (momentum / mass x t)");
}

struct BallGeometry {
  double radius, x, y, vx;
  double plate_lo_x, plate_hi_x, plate_lo_y, plate_hi_y;
  double domain_lo_x, domain_hi_x, domain_lo_y, domain_hi_y;
};

BallGeometry readBallGeometry(const Config& config) {
  BallGeometry g{
      config.real("ball.radius"),  config.real("ball.x"),       config.real("ball.y"),
      config.real("ball.vx"),      config.real("plate.x_min"),  config.real("plate.x_max"),
      config.real("plate.y_min"),  config.real("plate.y_max"),  config.real("domain.x_min"),
      config.real("domain.x_max"), config.real("domain.y_min"), config.real("domain.y_max")};
  const bool inside = g.domain_lo_x < g.x - g.radius && g.x + g.radius < g.domain_hi_x &&
                      g.domain_lo_y < g.y - g.radius && g.y + g.radius < g.domain_hi_y &&
                      g.domain_lo_x <= g.plate_lo_x && g.plate_hi_x <= g.domain_hi_x &&
                      g.domain_lo_y <= g.plate_lo_y && g.plate_hi_y <= g.domain_hi_y;
  if (!(g.radius > 0 && g.plate_lo_x < g.plate_hi_x && g.plate_lo_y < g.plate_hi_y && inside)) {
    throw ConfigError(
        "ball: need radius > 0, a non-empty plate, and the ball and the plate "
        "inside the domain");
  }
  const double dx = std::max(g.plate_lo_x - g.x, std::max(0.0, g.x - g.plate_hi_x));
  const double dy = std::max(g.plate_lo_y - g.y, std::max(0.0, g.y - g.plate_hi_y));
  if (std::hypot(dx, dy) <= g.radius) {
    throw ConfigError("ball: the ball must not overlap the plate");
  }
  return g;
}

ProblemSetup setupBall(const Config& config) {
  const MaterialParams al = readHypoSolid(config, "al", "Al");
  const BallGeometry g = readBallGeometry(config);
  const double thickness = config.real("geometry.thickness");
  const double p0 = config.real("al.p0");
  const AmbientGas gas = readAmbientGas(config, "ball");
  if (!(thickness > 0 && p0 >= 0)) throw ConfigError("ball: need thickness > 0 and al.p0 >= 0");
  CellShapes shapes;
  ProblemSetup setup =
      setupBlock(config, {g.domain_lo_x, g.domain_lo_y, 0},
                 {g.domain_hi_x, g.domain_hi_y, thickness}, {al, al, gas.material}, shapes);
  MaterialRegions regions;
  regions.material_at = [=](const Vec3& x) {
    if (std::hypot(x.x - g.x, x.y - g.y) <= g.radius) return kBall;
    if (x.x >= g.plate_lo_x && x.x <= g.plate_hi_x && x.y >= g.plate_lo_y && x.y <= g.plate_hi_y) {
      return kPlate;
    }
    return kGas;
  };
  const double e_al = p0 / (al.rho0 * al.Gamma0);  // Mie-Gruneisen at rho = rho0
  regions.rho = {al.rho0, al.rho0, gas.rho};
  regions.e = {e_al, e_al, gas.e};
  regions.velocity = [=](int material, const Vec3&) {
    return material == kBall ? Vec3{g.vx, 0, 0} : Vec3{0, 0, 0};
  };
  fillMaterialRegions(setup, regions);
  return setup;
}

// The ball's centroid x: its mass-weighted mean of the cell centroids.
void sampleBallCentroidX(const Mesh& mesh, const State& state, const ProbeSlots& slots) {
  const auto m_k = state.m_ck;
  const auto x_c = state.x_c;
  const auto owned = mesh.cell_owned;  // sums over the ranks' owned cells
  Kokkos::parallel_reduce(             // sum m_ball, sum m_ball x
      "lagremap::diagnostics::ball_centroid", Kokkos::RangePolicy<ExecSpace>(0, mesh.n_cells),
      KOKKOS_LAMBDA(const Index c, SumArray<2>& acc) {
        if (!owned(c)) return;
        acc.v[0] += m_k(c, kBall);
        acc.v[1] += m_k(c, kBall) * x_c(c, 0);
      },
      Kokkos::Sum<SumArray<2>, ReportSpace>(slots.sums));
}
double ballCentroidX(const Mesh&, const State&, const ProbeSlots& slots) {
  return ratioOverRanks(slots);
}

// Mass, x-momentum and first moment in x of cells (mass m_c = rho_c v_c), and
// the ball's mass and x-momentum: exact sums over the owned cells and the
// ranks (ExactSum: the same bits on any rank count).
struct MassMoments {
  double mass = 0.0, momentum_x = 0.0, moment_x = 0.0, ball_mass = 0.0, ball_momentum_x = 0.0;
};

// Adds each cell's terms (mass, momentum, moment, ball mass, ball momentum)
// and returns the totals, summed over the ranks when `distributed`.
class MomentSums {
 public:
  void add(double mass, double v_x, double x, double ball_mass) {
    sums_[0] += mass;
    sums_[1] += mass * v_x;
    sums_[2] += mass * x;
    sums_[3] += ball_mass;
    sums_[4] += ball_mass * v_x;
  }
  MassMoments totals(bool distributed) {
    if (distributed) ExactSum::sumOverRanks(sums_);
    return {sums_[0].value(), sums_[1].value(), sums_[2].value(), sums_[3].value(),
            sums_[4].value()};
  }

 private:
  std::vector<ExactSum> sums_ = std::vector<ExactSum>(5);
};

// The initial state, rebuilt as the run built it (the sampled volume
// fractions, initializeState's m = rho v): each rank rebuilds its part of
// the block and sums its owned cells. Collective on a decomposed run.
MassMoments initialMoments(const Config& config) {
  const ProblemSetup setup = setupBall(config);
  std::vector<double> volume;
  std::vector<Vec3> centroid;
  hostCellShapes(copyToHost(setup.mesh), volume, centroid);
  const auto owned = Kokkos::create_mirror_view_and_copy(HostSpace(), setup.mesh.cell_owned);
  const int n_materials = int(setup.materials.size());
  MomentSums sums;
  for (std::size_t c = 0; c < volume.size(); ++c) {
    if (!owned(c)) continue;
    double mass = 0.0, ball_mass = 0.0;
    for (int k = 0; k < n_materials; ++k) {
      const std::size_t at = c * n_materials + k;
      const double m_k = setup.cells.alpha_k[at] * setup.cells.rho_k[at] * volume[c];
      mass += m_k;
      if (k == kBall) ball_mass = m_k;
    }
    sums.add(mass, setup.cells.v[c].x, centroid[c].x, ball_mass);
  }
  return sums.totals(parallel::size() > 1);
}

// The same totals at t_end.
MassMoments finalMoments(const FinalFields& fields) {
  MomentSums sums;
  for (Index c = 0; c < Index(fields.rho.extent(0)); ++c) {
    if (!fields.counts(c)) continue;
    sums.add(fields.rho(c) * fields.vol(c), fields.v(c, 0), fields.x_c(c, 0), fields.m_k(c, kBall));
  }
  return sums.totals(fields.distributed);
}

// On the axis y = ball.y at t_end: the ball's front (its last fall through
// alpha = 1/2 along +x), the crater's bottom (the plate's first rise) and
// the plate's rear face (its last fall).
struct AxisPositions {
  double ball_front, crater_bottom, plate_rear;
};

AxisPositions axisPositions(const Config& config, const FinalFields& fields,
                            const BallGeometry& g) {
  const Vec3 origin{g.domain_lo_x, g.y, 0.5 * config.real("geometry.thickness")};
  const auto ball_crossings = alphaCrossingsAlongRay(fields, kBall, origin, {1, 0, 0});
  const auto plate_crossings = alphaCrossingsAlongRay(fields, kPlate, origin, {1, 0, 0});
  auto position = [&](const std::vector<AlphaCrossing>& crossings, bool first, bool rising) {
    double at = NAN;
    for (const AlphaCrossing& crossing : crossings) {
      if (crossing.rising != rising) continue;
      at = origin.x + crossing.distance;
      if (first) break;
    }
    return at;
  };
  return {position(ball_crossings, false, false), position(plate_crossings, true, true),
          position(plate_crossings, false, false)};
}

// ball_centroid.csv (the probe's history) and ball_axis.csv (the ball and
// crater at t_end) in out_dir.
void writeBallCsvs(const std::string& out_dir, const FinalFields& fields, const BallGeometry& g,
                   double centroid_shift, double ball_velocity, const AxisPositions& axis) {
  ResultFile history(out_dir + "/ball_centroid.csv");
  history << "t,ball_centroid_x\n" << std::setprecision(10);
  for (const auto& [t, x] : fields.probe) history << t << ',' << x << '\n';
  history.write();
  ResultFile csv(out_dir + "/ball_axis.csv");
  csv << std::setprecision(10) << "quantity,value,note\n"
      << "t," << fields.time << ",s\n"
      << "ball_centroid_shift," << centroid_shift << ",m (free flight: ball.vx t)\n"
      << "ball_velocity_x," << ball_velocity << ",m/s (ball's mass-weighted mean)\n"
      << "ball_front_x," << axis.ball_front << ",m (alpha_ball = 1/2 on the axis)\n"
      << "crater_bottom_x," << axis.crater_bottom
      << ",m (alpha_plate = 1/2 on the axis; plate face at plate.x_min)\n"
      << "crater_depth," << axis.crater_bottom - g.plate_lo_x << ",m\n"
      << "plate_rear_x," << axis.plate_rear << ",m (alpha_plate = 1/2 on the axis)\n"
      << "plate_rear_bulge," << axis.plate_rear - g.plate_hi_x << ",m\n";
  csv.write();
}

ProblemResults finishBall(const Config& config, const FinalFields& fields,
                          const std::string& out_dir) {
  const BallGeometry g = readBallGeometry(config);
  const double t_end = fields.time;
  const MassMoments initial = initialMoments(config);
  const MassMoments final_state = finalMoments(fields);
  const AxisPositions axis = axisPositions(config, fields, g);
  const double ball_centroid = fields.probe.empty() ? NAN : fields.probe.back().second;
  const double ball_centroid0 = fields.probe.empty() ? NAN : fields.probe.front().second;
  const double centroid_shift = ball_centroid - ball_centroid0;
  if (!out_dir.empty()) {
    writeBallCsvs(out_dir, fields, g, centroid_shift,
                  final_state.ball_momentum_x / final_state.ball_mass, axis);
  }
  // With nothing pushing on the walls (the gas is at 1e-5 Pa), the total
  // momentum stays the ball's, and the centre of mass of everything moves by
  // P t / M: the remapped mass goes where the momentum says.
  const double momentum_ratio = final_state.momentum_x / initial.momentum_x;
  const double shift = (final_state.moment_x - initial.moment_x) / final_state.mass;
  const double expected_shift = initial.momentum_x * t_end / initial.mass;
  const double free_flight = g.vx * t_end;
  std::vector<Check> checks = {
      {"momentum_x", momentum_ratio, 1.0, config.real("check.momentum_tolerance"),
       "total x-momentum at t_end / initial (the ball's): kept but for what the gas gives the "
       "walls (the run's momentum drift audits that impulse too)"},
      {"centre_of_mass_shift", shift, expected_shift,
       config.real("check.centre_of_mass_tolerance") * std::abs(expected_shift),
       "shift of the centre of mass of everything [m] vs momentum / mass x t (no paper "
       "reference)"},
      {"ball_advance_fraction", centroid_shift / free_flight, 0.5, 0.5,
       "ball centroid shift / free flight ball.vx t: in [0, 1], the plate slows the ball"}};
  // (all three follow the run's parameters: conservation and a bound)
  checks[0].source = "momentum conservation";
  checks[1].source = "momentum / mass x t";
  checks[2].source = "bound [0, 1]";
  return checks;
}

}  // namespace

extern const Problem kBallProblem = {"ball",
                                     "aluminium ball impact on an aluminium plate at 1000 m/s "
                                     "(hypo-elastic, in near-vacuum gas; remap mode only)",
                                     declareBall,
                                     setupBall,
                                     finishBall,
                                     {sampleBallCentroidX, ballCentroidX, "ball_centroid_x"},
                                     {0.0, 0.5e-6, 1.0e-6, 1.5e-6, 2.0e-6, 2.5e-6}};

}  // namespace lagremap
