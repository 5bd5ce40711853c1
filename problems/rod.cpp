// `rod` — the Taylor anvil test of a round rod in 3D (docs/verification.md
// §8.10): a copper rod of radius R and length L at speed V against a rigid
// frictionless wall x = 0, its axis along x; a quarter of it (y, z >= 0)
// between the symmetry planes y = 0 and z = 0. The solid hardens linearly
// (Y = Y0 + H eps_p, docs/method.md §A7).
// Lagrange mode: the rod alone on a body-fitted mesh: each cross-section is
// a quarter disc mapped from the block's (y, z) unit square (a Coons patch
// of its two radii and two halves of its arc), so no cell is degenerate on
// the axis; free outside, the wall at x = 0.
// Remap mode: the rod in air on the fixed box [0, Lb] x [0, W]^2, its mixed
// cells sampled as for the other problems; walls on the far sides.
// Checks: final length, mushroom (impact-face) radius and the largest
// plastic strain, against published code-to-code results for the default
// case (n/a for another).
#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>

#include "../src/problem.hpp"

namespace lagremap {
namespace {

// The benchmark's published band (docs/verification.md §8.10): final length
// and mushroom radius at 80 us [m].
constexpr double kPublishedLength = 21.5e-3, kPublishedLengthTolerance = 0.25e-3;
constexpr double kPublishedRadius = 7.12e-3, kPublishedRadiusTolerance = 0.2e-3;

void declareRod(Config& config) {
  const bool remap = config.remapSetup();
  config.addReal("t_end", 80e-6, "s", "final time");
  declareHypoSolidKeys(config, "metal", "Cu");
  config.addReal("rod.length", 32.4e-3, "m", "rod length L along x");
  config.addReal("rod.radius", 3.2e-3, "m", "rod radius R");
  config.addReal("rod.speed", 227.0, "m/s", "impact speed V (towards the wall x = 0)");
  if (remap) {
    config.addReal("domain.length", 34.0e-3, "m", "fixed mesh extent along x (remap)");
    config.addReal("domain.width", 9.6e-3, "m", "fixed mesh extent along y and z (remap)");
    config.addReal("gas.rho", 1.2, "kg/m^3", "density of the surrounding air");
    config.addReal("gas.p", 1e5, "Pa", "pressure of the surrounding air");
    config.addReal("gas.gamma", 1.4, "-", "ratio of specific heats of the air");
    // 0.32 mm cells, R / 10 (verification.md §8.10: at R / 8 the mushroom is
    // 0.1 mm short of the published band)
    declareMeshKeys(config, 106, 30, 30);
    declareBoundaryKeys(config, {"wall", "wall", "symmetry", "wall", "symmetry", "wall"});
  } else {
    // ny = nz = 10 cells across the radius (the quarter disc's two radii),
    // nx = 121 along the rod (cells 0.27 mm long, 0.32 mm wide: the foot's
    // axial resolution sets the mushroom, verification.md §8.10)
    declareMeshKeys(config, 121, 10, 10);
    declareBoundaryKeys(config, {"wall", "free", "symmetry", "free", "symmetry", "free"});
  }
  config.addReal("check.reference_length", kPublishedLength, "m",
                 "final length (published code-to-code band, default case)");
  config.addReal("check.length_tolerance", kPublishedLengthTolerance, "m",
                 "tolerance on the final length");
  config.addReal("check.reference_radius", kPublishedRadius, "m",
                 "mushroom radius (published code-to-code band, default case)");
  config.addReal("check.radius_tolerance", kPublishedRadiusTolerance, "m",
                 "tolerance on the mushroom radius");
}

struct RodGeometry {
  double length, radius, speed;
};

RodGeometry readRod(const Config& config) {
  const RodGeometry rod{config.real("rod.length"), config.real("rod.radius"),
                        config.real("rod.speed")};
  if (!(rod.length > 0 && rod.radius > 0 && rod.speed >= 0)) {
    throw ConfigError("rod: rod.length and rod.radius must be > 0, rod.speed >= 0");
  }
  return rod;
}

// The quarter disc of radius R over the unit square (u, v): a Coons patch of
// its four sides, v = 0 the radius along y (z = 0), u = 0 the radius along z
// (y = 0), u = 1 and v = 1 the halves of the arc that meet at 45 degrees,
// pulled in along the diagonal near that point. (The arc is smooth there,
// so the patch's Jacobian is singular at it: the corner cell's area would
// fall as 1/n, 0.15 of the largest cell's at n = 8 cells a radius, 0.04 at
// 32. The pull, 1.5 R u v (1-u)(1-v) / ((1-u) + (1-v)), zero on all four
// sides, moves the diagonal's last node in by about 0.75 R / n: the smallest
// cell then stays 0.56-0.68 of the largest at n = 4-32, its angle on the arc
// 174-178 degrees, as every single block's corner there must have.)
Vec3 quarterDisc(double u, double v, double R) {
  const double quarter = 0.25 * std::acos(-1.0);  // pi / 4
  auto arc = [R](double angle) { return Vec3{0.0, R * std::cos(angle), R * std::sin(angle)}; };
  const Vec3 bottom{0.0, u * R, 0.0}, left{0.0, 0.0, v * R};
  const Vec3 right = arc(v * quarter), top = arc(2.0 * quarter - u * quarter);
  const Vec3 p10{0.0, R, 0.0}, p01{0.0, 0.0, R}, p11 = arc(quarter);
  const Vec3 coons = (1.0 - v) * bottom + v * top + (1.0 - u) * left + u * right -
                     ((u * (1.0 - v)) * p10 + ((1.0 - u) * v) * p01 + (u * v) * p11);
  const double to_corner = (1.0 - u) + (1.0 - v);
  const double pull = to_corner > 0.0 ? 1.5 * u * v * (1.0 - u) * (1.0 - v) / to_corner : 0.0;
  return coons - pull * p11;
}

ProblemSetup setupRod(const Config& config) {
  const MaterialParams metal = readHypoSolid(config, "metal", "Cu");
  const RodGeometry rod = readRod(config);
  const Vec3 velocity{-rod.speed, 0.0, 0.0};
  CellShapes shapes;
  if (config.remapSetup()) {
    const AmbientGas gas = readAmbientGas(config, "rod");
    const double domain_length = config.real("domain.length");
    const double width = config.real("domain.width");
    if (!(domain_length > rod.length && width > rod.radius)) {
      throw ConfigError("rod: the remap domain must contain the rod");
    }
    ProblemSetup setup =
        setupBlock(config, {0, 0, 0}, {domain_length, width, width}, {metal, gas.material}, shapes);
    MaterialRegions regions;
    regions.material_at = [=](const Vec3& x) {
      return x.x < rod.length && x.y * x.y + x.z * x.z < rod.radius * rod.radius ? 0 : 1;
    };
    regions.rho = {metal.rho0, gas.rho};
    regions.e = {0.0, gas.e};
    regions.velocity = [=](int material, const Vec3&) {
      return material == 0 ? velocity : Vec3{0, 0, 0};
    };
    fillMaterialRegions(setup, regions);
    return setup;
  }
  // the block [0, L] x [0, 1]^2, its cross-sections mapped onto the quarter disc
  ProblemSetup setup = setupBlock(config, {0, 0, 0}, {rod.length, 1.0, 1.0}, {metal}, shapes,
                                  [R = rod.radius](const Vec3& p) {
                                    const Vec3 section = quarterDisc(p.y, p.z, R);
                                    return Vec3{p.x, section.y, section.z};
                                  });
  for (std::size_t c = 0; c < shapes.volume.size(); ++c) {
    setup.cells.rho.push_back(metal.rho0);
    setup.cells.e.push_back(0.0);
    setup.cells.v.push_back(velocity);
    setup.cells.mat.push_back(0);
  }
  return setup;
}

// The rod's length. Lagrange: the largest x of any node (the wall is at
// x = 0). Remap: the copper volume of the row of cells along the axis (the
// cells with a corner on it) over the row's cross-section, sum alpha v /
// (dy dz): a smooth measure (the check reads the alpha = 1/2 front).
void sampleRodLength(const Mesh& mesh, const State& state, const ProbeSlots& slots) {
  if (state.n_materials > 1) {
    sampleMaterialLengthAlongAxis("lagremap::diagnostics::rod_length_alpha", mesh, state, true,
                                  slots);
  } else {
    sampleLargestNodeX("lagremap::diagnostics::rod_length", mesh, slots);
  }
}
double rodLength(const Mesh&, const State& state, const ProbeSlots& slots) {
  return state.n_materials > 1 ? sumOverRanks(slots) : largestOverRanks(slots);
}

// Lagrange: the largest distance from the axis of a node on the wall (the
// impact face, x = 0 to round-off: the wall holds it there).
double impactFaceRadius(const FinalFields& fields, double length0) {
  double radius = 0.0;
  for (Index n = 0; n < Index(fields.mesh.x_n.extent(0)); ++n) {
    if (!(std::abs(fields.mesh.x_n(n, 0)) <= 1e-9 * length0)) continue;
    radius = std::max(radius, std::hypot(fields.mesh.x_n(n, 1), fields.mesh.x_n(n, 2)));
  }
  return fields.distributed ? parallel::max(radius) : radius;
}

// Remap: where copper's volume fraction falls through 1/2 along a row of
// cells (those whose centroid has the smallest value of the two other
// coordinates), outwards along `axis` (0: x, the rod's length; 1: y, the
// mushroom's radius on the wall), interpolated linearly between centroids.
double alphaFront(const FinalFields& fields, int axis) {
  const int other[2] = {axis == 0 ? 1 : 0, 2};
  double lowest[2] = {INFINITY, INFINITY};
  for (Index c = 0; c < Index(fields.x_c.extent(0)); ++c) {
    if (!fields.counts(c)) continue;
    for (int i = 0; i < 2; ++i) lowest[i] = std::min(lowest[i], fields.x_c(c, other[i]));
  }
  if (fields.distributed) {
    for (double& value : lowest) value = parallel::min(value);
  }
  std::vector<double> mine;  // (coordinate along the row, alpha)
  for (Index c = 0; c < Index(fields.x_c.extent(0)); ++c) {
    bool in_row = fields.counts(c);
    for (int i = 0; i < 2 && in_row; ++i) {
      in_row = std::abs(fields.x_c(c, other[i]) - lowest[i]) <= 1e-9 * (1.0 + std::abs(lowest[i]));
    }
    if (in_row) mine.insert(mine.end(), {fields.x_c(c, axis), fields.alpha(c, 0)});
  }
  return outwardHalfCrossing(fields, mine);
}

// The largest plastic strain of copper over the cells (remap: those where
// copper fills at least half the cell).
double largestPlasticStrain(const FinalFields& fields) {
  double largest = 0.0;
  for (Index c = 0; c < Index(fields.eps_k.extent(0)); ++c) {
    if (fields.counts(c) && fields.alpha(c, 0) >= 0.5) {
      largest = std::max(largest, fields.eps_k(c, 0));
    }
  }
  return fields.distributed ? parallel::max(largest) : largest;
}

// The cells of the symmetry plane z = 0 (those with a face on it): their
// in-plane corners (VTK nodes 0-3), copper's volume fraction and the
// plastic strain, for the plots of the profile and of eps_p.
void writeSymmetryPlane(const std::string& path, const FinalFields& fields, double scale) {
  std::ostringstream rows;
  rows << std::setprecision(8);
  for (Index c = 0; c < Index(fields.x_c.extent(0)); ++c) {
    if (!fields.counts(c)) continue;
    bool on_plane = true;
    for (int p = 0; p < 4 && on_plane; ++p) {
      on_plane = std::abs(fields.mesh.x_n(fields.mesh.cell_nodes(c, p), 2)) <= 1e-9 * scale;
    }
    if (!on_plane) continue;
    rows << fields.globalCell(c) << ' ';
    for (int p = 0; p < 4; ++p) {
      const Index node = fields.mesh.cell_nodes(c, p);
      rows << fields.mesh.x_n(node, 0) << ',' << fields.mesh.x_n(node, 1) << ',';
    }
    rows << fields.alpha(c, 0) << ',' << fields.plasticStrain(c) << '\n';
  }
  ResultFile csv(path);
  csv << "x0,y0,x1,y1,x2,y2,x3,y3,alpha_cu,plastic_strain\n";
  writeRowsInCellOrder(rows.str(), fields.distributed, csv);
  csv.write();
}

ProblemResults finishRod(const Config& config, const FinalFields& fields,
                         const std::string& out_dir) {
  const RodGeometry rod = readRod(config);
  const bool remap = config.remapSetup();
  writeSymmetryPlane(out_dir.empty() ? "" : out_dir + "/rod_plane_z0.csv", fields, rod.length);
  ResultFile history(out_dir.empty() ? "" : out_dir + "/rod_length.csv");
  history << "t,length\n";
  for (const auto& [t, value] : fields.probe) history << t << ',' << value << '\n';
  history.write();
  const double length = remap                  ? alphaFront(fields, 0)
                        : fields.probe.empty() ? NAN
                                               : fields.probe.back().second;
  const double radius = remap ? alphaFront(fields, 1) : impactFaceRadius(fields, rod.length);
  std::vector<Check> checks = {
      {"final_length", length, config.real("check.reference_length"),
       config.real("check.length_tolerance"),
       remap ? "alpha = 1/2 front of copper on the axis at t_end [m]"
             : "largest node x at t_end [m]"},
      {"mushroom_radius", radius, config.real("check.reference_radius"),
       config.real("check.radius_tolerance"),
       remap ? "alpha = 1/2 front of copper along y on the wall at t_end [m]"
             : "largest distance of an impact-face node from the axis at t_end [m]"},
      {"largest_plastic_strain", largestPlasticStrain(fields), 0.0, 0.0,
       "largest equivalent plastic strain of copper at t_end"}};
  checks[2].source = "no published value";
  checks[2].doesNotApply("no published value found for this case (docs/verification.md §8.10)");
  // The published band is the default case's; a reference the user sets with
  // check.reference_* is theirs.
  const char* reference_keys[2] = {"check.reference_length", "check.reference_radius"};
  for (int i = 0; i < 2; ++i) {
    const Param& reference = config.params().at(reference_keys[i]);
    if (reference.value == reference.default_value) {
      markDefaultCaseOnly(config, checks, {checks[i].name},
                          "published code-to-code band, default case only");
    } else {
      checks[i].source = std::string(reference_keys[i]) + " (user)";
    }
  }
  setModeIndependentReferences(config, checks);
  return checks;
}

}  // namespace

extern const Problem kRodProblem = {
    "rod",
    "3D Taylor anvil test of a round copper rod on a rigid wall (quarter rod, linear hardening; "
    "body-fitted, or in air in remap mode)",
    declareRod,
    setupRod,
    finishRod,
    {sampleRodLength, rodLength, "rod_length"}};

}  // namespace lagremap
