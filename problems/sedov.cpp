// `sedov` — point blast in an octant of space on a Cartesian mesh, symmetry
// planes through the origin (not a case of the paper; this is the classic
// verification problem of Lagrangian hydro codes). The blast energy E (of the
// whole sphere) goes into the corner cell's octant share E/8. Checks: the
// shock radius against the self-similar R(t) = (E t^2 / (alpha rho0))^(1/5)
// and the octant symmetry of the density field.
#include <algorithm>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "../src/exact_sum.hpp"
#include "../src/problem.hpp"

namespace lagremap {
namespace {

// Self-similar constant of the spherical blast for gamma = 1.4 (Sedov; with
// E = 0.851072 the shock reaches R = 1 at t = 1 in a unit-density gas).
constexpr double kSedovAlphaGamma14 = 0.851072;

void declareSedov(Config& config) {
  config.addReal("t_end", 1.0, "s", "final time");
  config.addReal("gas.gamma", 1.4, "-", "ratio of specific heats");
  config.addReal("ambient.rho", 1.0, "kg/m^3", "density of the gas at rest");
  config.addReal("ambient.p", 1e-6, "Pa", "pressure of the gas at rest");
  config.addReal("blast.energy", 0.851072, "J",
                 "blast energy of the full sphere (octant gets 1/8)");
  config.addReal("geometry.size", 1.2, "m", "edge of the cubic octant domain");
  declareMeshKeys(config, 30, 30, 30);
  declareBoundaryKeys(config, {"symmetry", "wall", "symmetry", "wall", "symmetry", "wall"});
  config.addReal("check.radius_tolerance", 0.03, "-", "relative tolerance on the shock radius");
}

ProblemSetup setupSedov(const Config& config) {
  const double size = config.real("geometry.size");
  const double gamma = config.real("gas.gamma");
  const double rho0 = config.real("ambient.rho"), p0 = config.real("ambient.p");
  const double energy = config.real("blast.energy");
  if (!(size > 0) || !(gamma > 1) || !(rho0 > 0) || !(p0 > 0) || !(energy > 0)) {
    throw ConfigError(
        "sedov: size, gamma - 1, ambient rho and p and blast energy must be positive");
  }
  MaterialParams gas;
  gas.gamma = gamma;
  CellShapes shapes;
  ProblemSetup setup = setupBlock(config, {0.0, 0.0, 0.0}, {size, size, size}, {gas}, shapes);
  const auto& volume = shapes.volume;
  InitialCells& cells = setup.cells;
  const double e0 = p0 / ((gamma - 1.0) * rho0);
  for (std::size_t c = 0; c < volume.size(); ++c) {
    cells.rho.push_back(rho0);
    cells.e.push_back(e0);
    cells.v.push_back({0.0, 0.0, 0.0});
    cells.mat.push_back(0);
  }
  // Global cell 0 touches the origin: it takes the octant's share of the
  // blast (held first by the parts that hold it, as local ids follow global ones).
  if (setup.mesh.n_cells > 0 && setup.mesh.cell_global(0) == 0) {
    cells.e[0] += (energy / 8.0) / (rho0 * volume[0]);
  }
  return setup;
}

// Mass and volume of the cells in each of n_bins spherical shells of the
// octant, while radial.csv gets every cell's radius, density, pressure, speed.
// The bins are exact sums (ExactSum): the same bits on any rank count, where
// each rank bins its owned cells (radial.csv then lists them rank by rank).
struct RadialBins {
  std::vector<double> mass, volume;
};

RadialBins radialProfile(const FinalFields& fields, double size, int n_bins,
                         const std::string& out_dir) {
  const Index n_cells = Index(fields.rho.extent(0));
  std::ostringstream rows;
  rows << std::setprecision(8);
  std::vector<ExactSum> sums(2 * std::size_t(n_bins));  // mass, then volume
  for (Index c = 0; c < n_cells; ++c) {
    if (!fields.counts(c)) continue;
    const double r =
        std::sqrt(fields.x_c(c, 0) * fields.x_c(c, 0) + fields.x_c(c, 1) * fields.x_c(c, 1) +
                  fields.x_c(c, 2) * fields.x_c(c, 2));
    const double speed =
        std::sqrt(fields.v(c, 0) * fields.v(c, 0) + fields.v(c, 1) * fields.v(c, 1) +
                  fields.v(c, 2) * fields.v(c, 2));
    rows << r << ',' << fields.rho(c) << ',' << fields.p(c) << ',' << speed << '\n';
    const int bin = int(r / size * n_bins);
    if (bin < n_bins) {
      sums[std::size_t(bin)] += fields.rho(c) * fields.vol(c);
      sums[std::size_t(n_bins + bin)] += fields.vol(c);
    }
  }
  std::ofstream radial;
  if (!out_dir.empty()) radial.open(out_dir + "/radial.csv");
  radial << "r,rho,p,speed\n";
  if (fields.distributed) {
    ExactSum::sumOverRanks(sums);
    parallel::writeOnRoot(rows.str(), out_dir.empty() ? nullptr : &radial);
  } else {
    radial << rows.str();
  }
  RadialBins bins{std::vector<double>(n_bins), std::vector<double>(n_bins)};
  for (int b = 0; b < n_bins; ++b) {
    bins.mass[b] = sums[std::size_t(b)].value();
    bins.volume[b] = sums[std::size_t(n_bins + b)].value();
  }
  return bins;
}

// Shock radius: the radius of the peak of the shell-averaged density.
double shockRadius(const FinalFields& fields, double size, const std::string& out_dir) {
  const int n_bins = std::max(fields.nx, 10);
  const RadialBins bins = radialProfile(fields, size, n_bins, out_dir);
  const std::vector<double>& bin_mass = bins.mass;
  const std::vector<double>& bin_volume = bins.volume;
  int peak = 0;
  for (int b = 0; b < n_bins; ++b) {
    if (bin_volume[b] > 0 &&
        bin_mass[b] / bin_volume[b] > bin_mass[peak] / std::max(bin_volume[peak], 1e-300))
      peak = b;
  }
  // Sub-bin position of the peak: vertex of the parabola through the peak bin
  // and its two neighbours.
  double offset = 0.0;
  if (peak > 0 && peak + 1 < n_bins && bin_volume[peak - 1] > 0 && bin_volume[peak + 1] > 0) {
    const double left = bin_mass[peak - 1] / bin_volume[peak - 1];
    const double centre = bin_mass[peak] / bin_volume[peak];
    const double right = bin_mass[peak + 1] / bin_volume[peak + 1];
    const double curvature = left - 2.0 * centre + right;
    if (curvature < 0.0) offset = 0.5 * (left - right) / curvature;
  }
  return (peak + 0.5 + offset) * size / n_bins;
}

// Octant symmetry: the field is invariant under exchanges of x, y, z (on a
// cubic mesh): the largest density difference under them, and the largest
// density. Each cell is compared with its images under the three exchanges;
// on ranks that hold their owned cells only, a cell's density goes to the
// owners of its images (each exchange is its own inverse), which compare it
// with theirs: the same pairs, and a maximum, so the same bits.
struct OctantSymmetry {
  double asymmetry = 0.0, rho_max = 0.0;
};

OctantSymmetry octantSymmetry(const FinalFields& fields) {
  OctantSymmetry s;
  const int nx = fields.nx, ny = fields.ny;
  auto id = [&](int i, int j, int k) { return i + long(nx) * (j + long(ny) * k); };
  auto images = [&](long g, long image[3], int ijk[3][3]) {
    const int i = int(g % nx), j = int((g / nx) % ny), k = int(g / (long(nx) * ny));
    const int index[3][3] = {{j, i, k}, {k, j, i}, {i, k, j}};
    for (int e = 0; e < 3; ++e) {
      for (int d = 0; d < 3; ++d) ijk[e][d] = index[e][d];
      image[e] = id(index[e][0], index[e][1], index[e][2]);
    }
  };
  const Index n_cells = Index(fields.rho.extent(0));
  if (!fields.distributed) {
    for (Index c = 0; c < n_cells; ++c) {
      long image[3];
      int ijk[3][3];
      images(c, image, ijk);
      const double rho = fields.rho(c);
      s.rho_max = std::max(s.rho_max, rho);
      for (long g : image) s.asymmetry = std::max(s.asymmetry, std::abs(rho - fields.rho(g)));
    }
    return s;
  }
  const BlockPart part = *thisRanksPart(fields.nx, fields.ny, fields.nz);
  std::vector<parallel::KeyedValue> items;
  std::vector<int> owners;
  for (Index c = 0; c < n_cells; ++c) {
    if (!fields.counts(c)) continue;
    long image[3];
    int ijk[3][3];
    images(fields.globalCell(c), image, ijk);
    s.rho_max = std::max(s.rho_max, fields.rho(c));
    for (int e = 0; e < 3; ++e) {
      items.push_back({image[e], fields.rho(c)});
      owners.push_back(part.cellOwner(ijk[e][0], ijk[e][1], ijk[e][2]));
    }
  }
  for (const parallel::KeyedValue& item : parallel::deliver(items, owners)) {
    const long g = item.key;
    const Index local =
        Index(part.localCell(int(g % nx), int((g / nx) % ny), int(g / (long(nx) * ny))));
    s.asymmetry = std::max(s.asymmetry, std::abs(fields.rho(local) - item.value));
  }
  s.asymmetry = parallel::max(s.asymmetry);
  s.rho_max = parallel::max(s.rho_max);
  return s;
}

// slice_z.csv: the cell layer at z = 0 with the corners of each cell's bottom
// face (VTK nodes 0-3), so the map shows the Lagrangian cells as they are.
// (With distributed fields rank 0 gathers the layer's rows: writeRowsInCellOrder.)
void writeSliceZ(const std::string& out_dir, const FinalFields& fields) {
  const long layer = long(fields.nx) * fields.ny;
  std::ostringstream rows;
  rows << std::setprecision(8);
  for (Index c = 0; c < Index(fields.rho.extent(0)); ++c) {
    const long g = fields.globalCell(c);
    if (g >= layer || !fields.counts(c)) continue;
    rows << g << ' ' << fields.x_c(c, 0) << ',' << fields.x_c(c, 1) << ',' << fields.rho(c) << ','
         << fields.p(c) << ','
         << std::sqrt(fields.v(c, 0) * fields.v(c, 0) + fields.v(c, 1) * fields.v(c, 1));
    for (int p = 0; p < 4; ++p) {
      const Index node = fields.mesh.cell_nodes(c, p);
      rows << ',' << fields.mesh.x_n(node, 0) << ',' << fields.mesh.x_n(node, 1);
    }
    rows << '\n';
  }
  std::ofstream slice;
  if (!out_dir.empty()) slice.open(out_dir + "/slice_z.csv");
  slice << "x,y,rho,p,speed,x0,y0,x1,y1,x2,y2,x3,y3\n";
  writeRowsInCellOrder(rows.str(), fields.distributed, slice);
}

ProblemResults finishSedov(const Config& config, const FinalFields& fields,
                           const std::string& out_dir) {
  const double measured_radius = shockRadius(fields, config.real("geometry.size"), out_dir);
  const bool cubic = fields.nx == fields.ny && fields.ny == fields.nz;
  const OctantSymmetry symmetry = cubic ? octantSymmetry(fields) : OctantSymmetry{};
  writeSliceZ(out_dir, fields);
  std::vector<Check> checks;
  const double gamma = config.real("gas.gamma");
  if (std::abs(gamma - 1.4) < 1e-12) {
    const double reference = std::pow(config.real("blast.energy") * fields.time * fields.time /
                                          (kSedovAlphaGamma14 * config.real("ambient.rho")),
                                      0.2);
    checks.push_back({"shock_radius", measured_radius, reference,
                      config.real("check.radius_tolerance") * reference,
                      "peak of the shell-averaged density vs the self-similar radius"});
    checks.back().source = "Sedov self-similar";
  } else {
    checks.push_back(
        {"shock_radius", measured_radius, NAN, 0.0, "peak of the shell-averaged density"});
    checks.back().doesNotApply("the self-similar constant is tabulated for gamma = 1.4 only");
  }
  if (cubic) {
    checks.push_back({"octant_symmetry", symmetry.asymmetry / std::max(symmetry.rho_max, 1e-300),
                      0.0, 1e-8, "max |rho(i,j,k) - rho(permuted)| / max rho"});
    checks.back().source = "octant symmetry";
  }
  setModeIndependentReferences(config, checks);
  return checks;
}

}  // namespace

extern const Problem kSedovProblem = {
    "sedov", "3D point blast in an octant (symmetry planes), self-similar shock radius",
    declareSedov, setupSedov, finishSedov};

}  // namespace lagremap
