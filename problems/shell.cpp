// `shell` — collapse of a thick beryllium shell (hypo-elastic perfectly
// plastic, Mie-Gruneisen), PROBLEMS.md §5. Lagrange mode: the shell alone on a
// polar hex mesh of a quarter annulus Ri = 0.08, Ro = 0.1 (symmetry planes
// x = 0 and y = 0, one cell thick in z, free inner and outer surfaces), moving
// inward with the incompressible Howell-Ball profile V = -V0 (Ri / r) e_r.
// Checks: the stopping radii (smallest inner and outer radius reached) against
// Howell & Ball's 50 mm / 78.1 mm.
#include <algorithm>
#include <cmath>
#include <fstream>
#include <iomanip>

#include "../src/problem.hpp"

namespace lagremap {
namespace {

constexpr double kPi = 3.14159265358979323846;

void declareShell(Config& config) {
  // Its free surfaces would sweep the shell out of the fixed mesh.
  refuseRemapMode(config, "shell", "the shell in gas on a 160 x 160 box");
  config.addReal("t_end", 130e-6, "s", "final time");
  declareHypoSolidKeys(config, "be", "Be-hypo");
  config.addReal("shell.inner_radius", 0.08, "m", "inner radius Ri");
  config.addReal("shell.outer_radius", 0.1, "m", "outer radius Ro");
  config.addReal("shell.v0", 417.1, "m/s", "inward speed at the inner radius");
  config.addChoice("shell.profile", "howell_ball", {"howell_ball", "paper_text"},
                   "radial speed V0 Ri/r (incompressible) or V0 r/Ri (the paper's text)");
  config.addReal("geometry.thickness", 1.25e-3, "m", "slab thickness along z (one cell)");
  // mesh.nx: radial cells, mesh.ny: cells over the quarter circle
  declareMeshKeys(config, 15, 90, 1);
  declareBoundaryKeys(config, {"free", "free", "symmetry", "symmetry", "symmetry", "symmetry"});
  config.addReal("check.inner_radius", 0.050, "m", "stopping inner radius (Howell & Ball)");
  config.addReal("check.outer_radius", 0.0781, "m", "stopping outer radius (Howell & Ball)");
  config.addReal("check.radius_tolerance", 0.002, "m", "tolerance on the stopping radii");
}

ProblemSetup setupShell(const Config& config) {
  const MaterialParams be = readHypoSolid(config, "be", "Be-hypo");
  const double ri = config.real("shell.inner_radius"), ro = config.real("shell.outer_radius");
  const double thickness = config.real("geometry.thickness");
  if (!(ri > 0 && ro > ri && thickness > 0)) {
    throw ConfigError("shell: need 0 < inner_radius < outer_radius and thickness > 0");
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
  ProblemSetup setup;
  setup.mesh = buildBlockMesh(block, readBoundaries(config));
  setup.materials = {be};
  std::vector<double> volume;
  std::vector<Vec3> centroid;
  hostCellShapes(copyToHost(setup.mesh), volume, centroid);
  const double v0 = config.real("shell.v0");
  const bool howell_ball = config.text("shell.profile") == "howell_ball";
  for (const Vec3& x : centroid) {
    const double r = std::hypot(x.x, x.y);
    const double speed = howell_ball ? v0 * ri / r : v0 * r / ri;
    setup.cells.rho.push_back(be.rho0);
    setup.cells.e.push_back(1e-6 / (be.rho0 * be.Gamma0));  // p0 = 1e-6 Pa
    setup.cells.v.push_back({-speed * x.x / r, -speed * x.y / r, 0.0});
    setup.cells.mat.push_back(0);
  }
  return setup;
}

// Inner radius: the smallest node radius (the inner surface).
double innerRadius(const Mesh& mesh, const State&) {
  const auto x_n = mesh.x_n;
  double radius = 0.0;
  Kokkos::parallel_reduce(
      "lagremap::diagnostics::inner_radius", Kokkos::RangePolicy<ExecSpace>(0, mesh.n_nodes),
      KOKKOS_LAMBDA(const Index n, double& acc) {
        const double r = math::sqrt(x_n(n, 0) * x_n(n, 0) + x_n(n, 1) * x_n(n, 1));
        acc = r < acc ? r : acc;
      },
      Kokkos::Min<double>(radius));
  return parallel::min(radius);
}

std::vector<Check> finishShell(const Config& config, const FinalFields& fields,
                               const std::string& out_dir) {
  // The stopping inner radius: the smallest one of the probe's history.
  double inner_min = INFINITY, stop_time = NAN;
  for (const auto& [t, r] : fields.probe) {
    if (r < inner_min) {
      inner_min = r;
      stop_time = t;
    }
  }
  // The shell is incompressible to first order: the outer radius follows from
  // the inner one by conservation of the shell's area, r_o^2 - r_i^2 = const.
  const double ri0 = config.real("shell.inner_radius"), ro0 = config.real("shell.outer_radius");
  const double outer_at_stop = std::sqrt(inner_min * inner_min + ro0 * ro0 - ri0 * ri0);
  std::ofstream csv;
  if (!out_dir.empty()) csv.open(out_dir + "/shell_radii.csv");
  csv << "t,inner_radius,outer_radius_incompressible\n" << std::setprecision(10);
  for (const auto& [t, r] : fields.probe) {
    csv << t << ',' << r << ',' << std::sqrt(r * r + ro0 * ro0 - ri0 * ri0) << '\n';
  }
  std::ofstream cells;
  if (!out_dir.empty()) cells.open(out_dir + "/shell_mesh_z0.csv");
  cells << "x0,y0,x1,y1,x2,y2,x3,y3,density\n" << std::setprecision(8);
  const Index n_cells = Index(fields.rho.extent(0));
  for (Index c = 0; c < n_cells; ++c) {
    for (int p = 0; p < 4; ++p) {
      const Index node = fields.mesh.cell_nodes(c, p);
      cells << fields.mesh.x_n(node, 0) << ',' << fields.mesh.x_n(node, 1) << ',';
    }
    cells << fields.rho(c) << '\n';
  }
  // Circularity of the inner surface: spread of the inner-surface node radii
  // (nodes of the first radial column; the shell must stay a circle).
  double inner_lo = INFINITY, inner_hi = 0.0;
  const int nx = fields.nx;
  for (Index c = 0; c < n_cells; ++c) {
    if (c % nx != 0) continue;  // cells touching the inner surface (i = 0)
    for (int p : {0, 3}) {      // VTK nodes 0 and 3 lie on the r = Ri side
      const Index node = fields.mesh.cell_nodes(c, p);
      const double r = std::hypot(fields.mesh.x_n(node, 0), fields.mesh.x_n(node, 1));
      inner_lo = std::min(inner_lo, r);
      inner_hi = std::max(inner_hi, r);
    }
  }
  const double tol = config.real("check.radius_tolerance");
  // The collapse must end inside the run (then the shell rebounds
  // elastically): the smallest radius is reached before t_end, not at it.
  const double stop_fraction = stop_time / config.real("t_end");
  return {{"stopping_inner_radius", inner_min, config.real("check.inner_radius"), tol,
           "smallest inner radius over the run (Howell & Ball 50 mm; paper 51 mm)"},
          {"stopping_outer_radius", outer_at_stop, config.real("check.outer_radius"), tol,
           "outer radius when the inner one stops, from the shell's area (H&B 78.1 mm)"},
          {"inner_circularity", (inner_hi - inner_lo) / inner_lo, 0.0, 0.01,
           "(max - min) / min of the inner-surface radius at t_end: the shell stays round"},
          {"stop_time_fraction", stop_fraction, 0.9, 0.095,
           "time of the smallest inner radius / t_end: the shell stops (and rebounds) "
           "within the run, in [0.805, 0.995]"}};
}

}  // namespace

extern const Problem kShellProblem = {
    "shell",
    "collapse of a thick beryllium shell (hypo-elastic, polar mesh of the quarter annulus)",
    declareShell,
    setupShell,
    finishShell,
    innerRadius,
    "inner_radius"};

}  // namespace lagremap
