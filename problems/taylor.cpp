// `taylor` — planar Taylor impact of an aluminium bar on a rigid wall
// (hypo-elastic perfectly plastic, Mie-Gruneisen), PROBLEMS.md §2, as a slab
// one cell thick in z. Lagrange mode: the bar [0,5] x [-0.5,0.5] alone, moving
// at -150 m/s onto the wall x = 0, free elsewhere. Checks: final bar length
// ~4.62 (paper, Lagrange) and the kinetic energy dissipated plastically.
#include <algorithm>
#include <cmath>
#include <fstream>
#include <iomanip>

#include "../src/problem.hpp"

namespace lagremap {
namespace {

void declareTaylor(Config& config) {
  config.addReal("t_end", 5e-3, "s", "final time");
  declareHypoSolidKeys(config, "al", "Al");
  config.addReal("bar.vx", -150.0, "m/s", "impact velocity");
  config.addReal("geometry.length", 5.0, "m", "bar length along x");
  config.addReal("geometry.height", 1.0, "m", "bar height along y");
  config.addReal("geometry.thickness", 0.025, "m", "slab thickness along z (one cell)");
  declareMeshKeys(config, 200, 40, 1);
  declareBoundaryKeys(config, {"wall", "free", "free", "free", "symmetry", "symmetry"});
  config.addReal("check.reference_length", 4.62, "m", "final length (paper, Lagrange)");
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
  ProblemSetup setup =
      setupBlock(config, {0, -height / 2, 0}, {length, height / 2, thickness}, {al}, shapes);
  const double vx = config.real("bar.vx");
  for (std::size_t c = 0; c < shapes.volume.size(); ++c) {
    setup.cells.rho.push_back(al.rho0);
    setup.cells.e.push_back(0.0);
    setup.cells.v.push_back({vx, 0, 0});
    setup.cells.mat.push_back(0);
  }
  return setup;
}

// Bar length: the largest x of any node (the wall is at x = 0).
double barLength(const Mesh& mesh, const State&) {
  const auto x_n = mesh.x_n;
  double length = 0.0;
  Kokkos::parallel_reduce(
      "lagremap::diagnostics::bar_length", Kokkos::RangePolicy<ExecSpace>(0, mesh.n_nodes),
      KOKKOS_LAMBDA(const Index n, double& acc) { acc = x_n(n, 0) > acc ? x_n(n, 0) : acc; },
      Kokkos::Max<double>(length));
  return length;
}

std::vector<Check> finishTaylor(const Config& config, const FinalFields& fields,
                                const std::string& out_dir) {
  // Outline of the deformed bar: the boundary nodes of the z = 0 layer.
  std::ofstream outline;
  if (!out_dir.empty()) outline.open(out_dir + "/taylor_mesh_z0.csv");
  outline << "x0,y0,x1,y1,x2,y2,x3,y3,density\n" << std::setprecision(8);
  const Index n_cells = Index(fields.rho.extent(0));
  double kinetic = 0.0, mass = 0.0;
  for (Index c = 0; c < n_cells; ++c) {
    const double m = fields.rho(c) * fields.vol(c);
    mass += m;
    kinetic += 0.5 * m *
               (fields.v(c, 0) * fields.v(c, 0) + fields.v(c, 1) * fields.v(c, 1) +
                fields.v(c, 2) * fields.v(c, 2));
    for (int p = 0; p < 4; ++p) {
      const Index node = fields.mesh.cell_nodes(c, p);
      outline << fields.mesh.x_n(node, 0) << ',' << fields.mesh.x_n(node, 1) << ',';
    }
    outline << fields.rho(c) << '\n';
  }
  const double vx = config.real("bar.vx");
  const double kinetic0 = 0.5 * mass * vx * vx;
  std::ofstream history;
  if (!out_dir.empty()) history.open(out_dir + "/taylor_length.csv");
  history << "t,length\n";
  for (const auto& [t, value] : fields.probe) history << t << ',' << value << '\n';
  const double final_length = fields.probe.empty() ? NAN : fields.probe.back().second;
  return {
      {"final_length", final_length, config.real("check.reference_length"),
       config.real("check.length_tolerance"), "largest node x at t_end (paper, Lagrange: 4.62)"},
      {"kinetic_fraction", kinetic / kinetic0, 0.0, config.real("check.kinetic_fraction"),
       "final kinetic energy / initial (dissipated plastically)"}};
}

}  // namespace

extern const Problem kTaylorProblem = {
    "taylor",
    "planar Taylor impact of an aluminium bar on a rigid wall (hypo-elastic, 2D slab)",
    declareTaylor,
    setupTaylor,
    finishTaylor,
    barLength,
    "bar_length"};

}  // namespace lagremap
