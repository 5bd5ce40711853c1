#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include "../kernels/hex.hpp"
#include "../src/boundary_keys.hpp"
#include "../src/diagnostics.hpp"
#include "../src/materials.hpp"
#include "../src/outputs.hpp"
#include "../src/problem.hpp"

namespace lagremap {

extern const Problem kSodProblem;
extern const Problem kSedovProblem;
extern const Problem kWilkinsProblem;
extern const Problem kPileProblem;
extern const Problem kTaylorProblem;
extern const Problem kShellProblem;
extern const Problem kBeamProblem;
extern const Problem kBallProblem;
extern const Problem kRodProblem;
extern const Problem kAdvectionProblem;
extern const Problem kAdvection1DProblem;
extern const Problem kAirHeliumProblem;
extern const Problem kWaterAirProblem;
extern const Problem kBumpProblem;
extern const Problem kBump1DProblem;

const std::vector<Problem>& problemRegistry() {
  static const std::vector<Problem> problems = {
      kSodProblem,         kSedovProblem,     kWilkinsProblem,  kTaylorProblem, kPileProblem,
      kBeamProblem,        kShellProblem,     kBallProblem,     kRodProblem,    kAdvectionProblem,
      kAdvection1DProblem, kAirHeliumProblem, kWaterAirProblem, kBumpProblem,   kBump1DProblem};
  return problems;
}

const Problem& findProblem(const std::string& name) {
  std::string known;
  for (const auto& problem : problemRegistry()) {
    if (name == problem.name) return problem;
    known += (known.empty() ? "" : ", ") + std::string(problem.name);
  }
  throw ConfigError("unknown problem '" + abbreviated(name) + "' (known: " + known + ")");
}

bool Check::pass() const {
  return std::isfinite(value) && std::abs(value - reference) <= tolerance;
}

std::string differenceFromDefaultCase(const Config& config) {
  for (const auto& [key, param] : config.params()) {
    const bool resolution = param.cell_count || param.cell_length || key.rfind("mesh.", 0) == 0;
    const bool controls = key.rfind("numerics.", 0) == 0 || key.rfind("remap.", 0) == 0 ||
                          key.rfind("mixture.", 0) == 0 || key.rfind("check.", 0) == 0;
    if (resolution || controls || param.value == param.default_value) continue;
    return key + " = " + param.value + " (case: " + param.default_value + ")";
  }
  return "";
}

void markDefaultCaseOnly(const Config& config, std::vector<Check>& checks,
                         const std::vector<std::string>& names, const std::string& source) {
  const std::string difference = differenceFromDefaultCase(config);
  for (Check& check : checks) {
    if (std::find(names.begin(), names.end(), check.name) == names.end()) continue;
    check.source = source;
    if (!difference.empty()) {
      check.doesNotApply("the reference is the default case's; this run has " + difference);
    }
  }
}

void markPerfectPlasticityOnly(const Config& config, std::vector<Check>& checks,
                               const std::string& prefix, const std::vector<std::string>& names) {
  const std::string hardening = config.text(prefix + ".hardening");
  if (hardening == "perfect") return;
  for (Check& check : checks) {
    if (!names.empty() && std::find(names.begin(), names.end(), check.name) == names.end()) {
      continue;
    }
    check.doesNotApply("the reference is for a perfectly plastic solid; this run has " + prefix +
                       ".hardening = " + hardening);
  }
}

void setModeIndependentReferences(const Config& config, std::vector<Check>& checks) {
  if (!config.remapMode()) return;
  for (Check& check : checks)
    if (!check.lagrange_reference) check.lagrange_reference = check.reference;
}

void declareMeshKeys(Config& config, int nx, int ny, int nz) {
  config.addInteger("mesh.nx", nx, "cells along x", true);
  config.addInteger("mesh.ny", ny, "cells along y", true);
  config.addInteger("mesh.nz", nz, "cells along z", true);
}

void declareBoundaryKeys(Config& config, const std::array<const char*, kNumSides>& defaults) {
  for (int side = 0; side < kNumSides; ++side) {
    config.addChoice(std::string("bc.") + sideName(side), defaults[side],
                     {"free", "wall", "symmetry", "fixed", "traction"},
                     std::string("boundary condition on the ") + sideName(side) + " side");
  }
}

void declareHypoSolidKeys(Config& config, const std::string& prefix, const std::string& preset) {
  const MaterialParams m = materialPreset(preset);
  config.addReal(prefix + ".rho0", m.rho0, "kg/m^3", "reference density (Mie-Gruneisen)");
  config.addReal(prefix + ".a0", m.a0, "m/s", "bulk sound speed a0 (Mie-Gruneisen)");
  config.addReal(prefix + ".Gamma0", m.Gamma0, "-", "Gruneisen coefficient Gamma0");
  config.addReal(prefix + ".s", m.s, "-", "Hugoniot slope s (Us = a0 + s up)");
  config.addReal(prefix + ".mu", m.mu, "Pa", "shear modulus (hypo-elastic)");
  config.addReal(prefix + ".yield_stress", m.yield_stress, "Pa",
                 "von Mises yield stress Y0 (Johnson-Cook's A)");
  declareHardeningKeys(config, prefix, m);
}

void declareHardeningKeys(Config& config, const std::string& prefix, const MaterialParams& m) {
  config.addChoice(prefix + ".hardening", hardeningName(m.hardening),
                   {"perfect", "linear", "johnson_cook"},
                   "yield stress: perfect (Y0), linear (Y0 + H eps_p), johnson_cook");
  config.addReal(prefix + ".hardening_modulus", m.hardening_modulus, "Pa",
                 "H of linear hardening, Y = Y0 + H eps_p");
  config.addReal(prefix + ".jc_B", m.jc_B, "Pa", "Johnson-Cook B (strain term B eps_p^n)");
  config.addReal(prefix + ".jc_n", m.jc_n, "-", "Johnson-Cook strain exponent n");
  config.addReal(prefix + ".jc_C", m.jc_C, "-", "Johnson-Cook rate coefficient C");
  config.addReal(prefix + ".jc_rate0", m.jc_rate0, "1/s", "Johnson-Cook reference strain rate");
  config.addReal(prefix + ".jc_m", m.jc_m, "-", "Johnson-Cook thermal exponent m");
  config.addReal(prefix + ".room_temperature", m.room_temperature, "K",
                 "temperature at e = 0 (Johnson-Cook T_room)");
  config.addReal(prefix + ".melt_temperature", m.melt_temperature, "K",
                 "Johnson-Cook melting temperature T_melt");
  config.addReal(prefix + ".specific_heat", m.specific_heat, "J/(kg K)",
                 "c_v of T = T_room + e / c_v (0: no thermal softening)");
}

void readHardening(const Config& config, const std::string& prefix, MaterialParams& m) {
  const std::string kind = config.text(prefix + ".hardening");
  m.hardening = kind == "linear"         ? HardeningKind::Linear
                : kind == "johnson_cook" ? HardeningKind::JohnsonCook
                                         : HardeningKind::Perfect;
  m.hardening_modulus = config.real(prefix + ".hardening_modulus");
  m.jc_B = config.real(prefix + ".jc_B");
  m.jc_n = config.real(prefix + ".jc_n");
  m.jc_C = config.real(prefix + ".jc_C");
  m.jc_rate0 = config.real(prefix + ".jc_rate0");
  m.jc_m = config.real(prefix + ".jc_m");
  m.room_temperature = config.real(prefix + ".room_temperature");
  m.melt_temperature = config.real(prefix + ".melt_temperature");
  m.specific_heat = config.real(prefix + ".specific_heat");
  if (!(m.hardening_modulus >= 0)) throw ConfigError(prefix + ".hardening_modulus must be >= 0");
  if (!(m.jc_B >= 0 && m.jc_n > 0 && m.jc_C >= 0 && m.jc_rate0 > 0 && m.jc_m > 0)) {
    throw ConfigError(prefix + ": need jc_B >= 0, jc_n > 0, jc_C >= 0, jc_rate0 > 0, jc_m > 0");
  }
  if (!(m.specific_heat >= 0 && m.room_temperature >= 0 && m.melt_temperature >= 0)) {
    throw ConfigError(prefix + ": specific_heat, room_temperature, melt_temperature must be >= 0");
  }
  if (m.hardening == HardeningKind::JohnsonCook && m.specific_heat > 0 &&
      !(m.melt_temperature > m.room_temperature)) {
    throw ConfigError(prefix + ".melt_temperature must exceed room_temperature" +
                      " (or specific_heat = 0: no thermal softening)");
  }
}

const char* hardeningName(HardeningKind kind) {
  switch (kind) {
    case HardeningKind::Linear:
      return "linear";
    case HardeningKind::JohnsonCook:
      return "johnson_cook";
    case HardeningKind::Perfect:
      break;
  }
  return "perfect";
}

MaterialParams readHypoSolid(const Config& config, const std::string& prefix,
                             const std::string& preset) {
  MaterialParams m = materialPreset(preset);
  m.rho0 = config.real(prefix + ".rho0");
  m.a0 = config.real(prefix + ".a0");
  m.Gamma0 = config.real(prefix + ".Gamma0");
  m.s = config.real(prefix + ".s");
  m.mu = config.real(prefix + ".mu");
  m.yield_stress = config.real(prefix + ".yield_stress");
  readHardening(config, prefix, m);
  // (Gamma0 > 0, not >= 0: the problems set a solid's initial energy from its
  // pressure at rho0, e0 = p0 / (rho0 Gamma0))
  if (!(m.rho0 > 0 && m.a0 > 0 && m.Gamma0 > 0 && m.s >= 0 && m.mu >= 0 && m.yield_stress >= 0)) {
    throw ConfigError(prefix + ": rho0, a0 and Gamma0 must be > 0; s, mu and yield_stress >= 0");
  }
  return m;
}

void declareNeoHookeanKeys(Config& config, const std::string& prefix, const std::string& preset) {
  const MaterialParams m = materialPreset(preset);
  config.addReal(prefix + ".rho0", m.rho0, "kg/m^3", "reference density");
  config.addReal(prefix + ".young", m.young, "Pa", "Young's modulus E (Neo-Hookean)");
  config.addReal(prefix + ".poisson", m.poisson, "-", "Poisson's ratio nu (Neo-Hookean)");
}

MaterialParams readNeoHookean(const Config& config, const std::string& prefix,
                              const std::string& preset) {
  MaterialParams m = materialPreset(preset);
  m.rho0 = config.real(prefix + ".rho0");
  m.young = config.real(prefix + ".young");
  m.poisson = config.real(prefix + ".poisson");
  if (!(m.rho0 > 0 && m.young > 0 && m.poisson >= 0 && m.poisson < 0.5)) {
    throw ConfigError(prefix + ": need rho0 > 0, young > 0 and 0 <= poisson < 0.5");
  }
  return m;
}

namespace {
// Mean of value(c) over the cells with a face on `side`: one reduction of (sum, count).
template <class Value>
double sideMean(const Mesh& mesh, int side, const char* label, Value value) {
  const auto face_side = mesh.cell_face_side;
  const auto owned = mesh.cell_owned;
  SumArray<2> sums;
  Kokkos::parallel_reduce(
      label, Kokkos::RangePolicy<ExecSpace>(0, mesh.n_cells),
      KOKKOS_LAMBDA(const Index c, SumArray<2>& acc) {
        if (owned(c) && face_side(c, side) == side) {
          acc.v[0] += value(c);
          acc.v[1] += 1.0;
        }
      },
      Kokkos::Sum<SumArray<2>>(sums));
  parallel::sum(sums.v, 2);
  return sums.v[1] > 0 ? sums.v[0] / sums.v[1] : 0.0;
}
}  // namespace

double sideMeanStressXX(const Mesh& mesh, const State& state, int side) {
  const auto p = state.p_c;
  const auto S = state.S_c;
  return sideMean(
      mesh, side, "lagremap::diagnostics::side_stress_xx",
      KOKKOS_LAMBDA(const Index c) { return -p(c) + S(c, 0); });
}

double sideMeanCentroid(const Mesh& mesh, const State& state, int side, int axis) {
  const auto x_c = state.x_c;
  return sideMean(
      mesh, side, "lagremap::diagnostics::side_centroid",
      KOKKOS_LAMBDA(const Index c) { return x_c(c, axis); });
}

double materialLengthAlongAxis(const char* label, const Mesh& mesh, const State& state,
                               bool z_axis_too) {
  const auto x_n = mesh.x_n;
  const auto cell_nodes = mesh.cell_nodes;
  const auto alpha = state.alpha_ck;
  const auto vol = state.vol_c;
  const auto owned = mesh.cell_owned;
  double length = 0.0;
  Kokkos::parallel_reduce(
      label, Kokkos::RangePolicy<ExecSpace>(0, mesh.n_cells),
      KOKKOS_LAMBDA(const Index c, double& sum) {
        double lo[3], hi[3];
        for (int d = 1; d < 3; ++d) lo[d] = hi[d] = x_n(cell_nodes(c, 0), d);
        for (int p = 1; p < 8; ++p) {
          for (int d = 1; d < 3; ++d) {
            const double x = x_n(cell_nodes(c, p), d);
            lo[d] = x < lo[d] ? x : lo[d];
            hi[d] = x > hi[d] ? x : hi[d];
          }
        }
        const double dy = hi[1] - lo[1], dz = hi[2] - lo[2];
        const bool on_axis =
            math::fabs(lo[1]) <= 1e-9 * dy && (!z_axis_too || math::fabs(lo[2]) <= 1e-9 * dz);
        if (owned(c) && on_axis) sum += alpha(c, 0) * vol(c) / (dy * dz);
      },
      length);
  return parallel::sum(length);
}

double largestNodeX(const char* label, const Mesh& mesh) {
  const auto x_n = mesh.x_n;
  double largest = 0.0;
  Kokkos::parallel_reduce(
      label, Kokkos::RangePolicy<ExecSpace>(0, mesh.n_nodes),
      KOKKOS_LAMBDA(const Index n, double& acc) { acc = x_n(n, 0) > acc ? x_n(n, 0) : acc; },
      Kokkos::Max<double>(largest));
  return parallel::max(largest);
}

AmbientGas readAmbientGas(const Config& config, const std::string& problem) {
  AmbientGas gas;
  gas.material.gamma = config.real("gas.gamma");
  gas.rho = config.real("gas.rho");
  const double p = config.real("gas.p");
  if (!(gas.rho > 0 && p > 0 && gas.material.gamma > 1)) {
    throw ConfigError(problem + ": gas.rho, gas.p must be > 0 and gas.gamma > 1");
  }
  gas.e = p / ((gas.material.gamma - 1.0) * gas.rho);
  return gas;
}

void declareTractionKeys(Config& config, int side, const SymMat3& stress) {
  const std::string prefix = std::string("bc.") + sideName(side) + ".sigma_";
  const double values[6] = {stress.xx, stress.yy, stress.zz, stress.xy, stress.yz, stress.xz};
  const char* names[6] = {"xx", "yy", "zz", "xy", "yz", "xz"};
  for (int k = 0; k < 6; ++k) {
    config.addReal(prefix + names[k], values[k], "Pa",
                   std::string("imposed Cauchy stress (tension > 0) on ") + sideName(side));
  }
}

SideBoundaries readBoundaries(const Config& config) {
  SideBoundaries boundaries;
  for (int side = 0; side < kNumSides; ++side) {
    const std::string key = std::string("bc.") + sideName(side);
    boundaries[side].kind = parseBoundaryKind(key, config.text(key));
    if (boundaries[side].kind == BoundaryKind::Traction) {
      const std::string prefix = key + ".sigma_";
      if (!config.has(prefix + "xx")) {
        throw ConfigError("side " + std::string(sideName(side)) +
                          " has a traction condition but this problem declares no " + prefix +
                          "* keys");
      }
      SymMat3& s = boundaries[side].traction_stress;
      s = {config.real(prefix + "xx"), config.real(prefix + "yy"), config.real(prefix + "zz"),
           config.real(prefix + "xy"), config.real(prefix + "yz"), config.real(prefix + "xz")};
    }
  }
  return boundaries;
}

void hostCellShapes(const HostMesh& mesh, std::vector<double>& volume,
                    std::vector<Vec3>& centroid) {
  const Index n_cells = Index(mesh.cell_nodes.extent(0));
  volume.resize(n_cells);
  centroid.resize(n_cells);
  for (Index c = 0; c < n_cells; ++c) {
    Vec3 x[8];
    for (int p = 0; p < 8; ++p) x[p] = loadVec3(mesh.x_n, mesh.cell_nodes(c, p));
    const hex::CellShape shape = hex::cellShape(x);
    volume[c] = shape.volume;
    centroid[c] = shape.centroid;
  }
}

void refuseLagrangeMode(const Config& config, const std::string& problem, const std::string& why) {
  if (config.remapMode()) return;
  throw ConfigError(problem + ": lagrange mode is not available (" + why + "); use --mode remap");
}

void fillMaterialRegions(ProblemSetup& setup, const MaterialRegions& regions,
                         int samples_per_edge) {
  const Kokkos::Timer timer;
  const HostMesh mesh = copyToHost(setup.mesh);
  const Index n_cells = setup.mesh.n_cells;
  const int n_materials = int(setup.materials.size());
  InitialCells& cells = setup.cells;
  cells = InitialCells();
  cells.alpha_k.assign(std::size_t(n_cells) * n_materials, 0.0);
  cells.rho_k.assign(std::size_t(n_cells) * n_materials, 0.0);
  cells.e_k.assign(std::size_t(n_cells) * n_materials, 0.0);
  cells.v.assign(std::size_t(n_cells), Vec3{0, 0, 0});
  const int n = samples_per_edge;
  std::vector<double> weight_k(static_cast<std::size_t>(n_materials));
  for (Index c = 0; c < n_cells; ++c) {
    Vec3 x[8];
    for (int p = 0; p < 8; ++p) x[p] = loadVec3(mesh.x_n, mesh.cell_nodes(c, p));
    std::fill(weight_k.begin(), weight_k.end(), 0.0);
    Vec3 momentum{0, 0, 0};
    double mass = 0.0;
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j)
        for (int k = 0; k < n; ++k) {
          // Trilinear map of VTK hexahedron nodes (0..3 at zeta = 0, 4..7 at zeta = 1).
          const double a = (i + 0.5) / n, b = (j + 0.5) / n, g = (k + 0.5) / n;
          const double w[8] = {(1 - a) * (1 - b) * (1 - g),
                               a * (1 - b) * (1 - g),
                               a * b * (1 - g),
                               (1 - a) * b * (1 - g),
                               (1 - a) * (1 - b) * g,
                               a * (1 - b) * g,
                               a * b * g,
                               (1 - a) * b * g};
          Vec3 point{0, 0, 0}, dxa{0, 0, 0}, dxb{0, 0, 0}, dxg{0, 0, 0};
          for (int p = 0; p < 8; ++p) point += w[p] * x[p];
          dxa = (1 - b) * (1 - g) * (x[1] - x[0]) + b * (1 - g) * (x[2] - x[3]) +
                (1 - b) * g * (x[5] - x[4]) + b * g * (x[6] - x[7]);
          dxb = (1 - a) * (1 - g) * (x[3] - x[0]) + a * (1 - g) * (x[2] - x[1]) +
                (1 - a) * g * (x[7] - x[4]) + a * g * (x[6] - x[5]);
          dxg = (1 - a) * (1 - b) * (x[4] - x[0]) + a * (1 - b) * (x[5] - x[1]) +
                a * b * (x[6] - x[2]) + (1 - a) * b * (x[7] - x[3]);
          const double jacobian = dot(dxa, cross(dxb, dxg));
          const int material = regions.material_at(point);
          if (material < 0 || material >= n_materials) {
            throw std::logic_error("problem set-up: a point has no material");
          }
          weight_k[material] += jacobian;
          mass += jacobian * regions.rho[material];
          momentum += (jacobian * regions.rho[material]) * regions.velocity(material, point);
        }
    double total = 0.0;
    for (double weight : weight_k) total += weight;
    for (int m = 0; m < n_materials; ++m) {
      const std::size_t at = std::size_t(c) * n_materials + m;
      cells.alpha_k[at] = weight_k[m] / total;
      cells.rho_k[at] = regions.rho[m];
      cells.e_k[at] = regions.e[m];
    }
    cells.v[c] = (1.0 / mass) * momentum;
  }
  setup.sample_seconds += timer.seconds();
}

std::vector<double> recordsOfAllRanks(const FinalFields& fields, std::vector<double> mine) {
  return fields.distributed ? parallel::gatherOnAll(mine) : mine;
}

double materialFrontX(const FinalFields& fields, int material, double y_line) {
  const Index n_cells = Index(fields.x_c.extent(0));
  // The row of cells whose centroids are nearest to the line (on a line
  // between two rows, the one above it): the first such cell in global order.
  double row_y = NAN, best = INFINITY;
  long best_cell = -1;
  for (Index c = 0; c < n_cells; ++c) {
    if (!fields.counts(c)) continue;
    const double dy = fields.x_c(c, 1) - y_line;
    const double distance = std::abs(dy) - (dy >= 0.0 ? 1e-12 * (1.0 + std::abs(y_line)) : 0.0);
    if (distance < best) {
      best = distance;
      best_cell = fields.globalCell(c);
      row_y = fields.x_c(c, 1);
    }
  }
  if (fields.distributed) {  // (distance, global id, y) of each rank's nearest cell
    const std::vector<double> nearest = parallel::gatherOnAll({best, double(best_cell), row_y});
    for (std::size_t r = 0; r < nearest.size(); r += 3) {
      const bool nearer = nearest[r] < best || (nearest[r] == best && nearest[r + 1] < best_cell);
      if (nearest[r + 1] >= 0 && nearer) {
        best = nearest[r];
        best_cell = long(nearest[r + 1]);
        row_y = nearest[r + 2];
      }
    }
  }
  std::vector<double> mine;  // (x, alpha) of the row's cells
  for (Index c = 0; c < n_cells; ++c) {
    if (fields.counts(c) && std::abs(fields.x_c(c, 1) - row_y) <= 1e-9 * (1.0 + std::abs(row_y))) {
      mine.insert(mine.end(), {fields.x_c(c, 0), fields.alpha(c, material)});
    }
  }
  return outwardHalfCrossing(fields, mine);
}

double outwardHalfCrossing(const FinalFields& fields, const std::vector<double>& mine) {
  const std::vector<double> records = recordsOfAllRanks(fields, mine);
  std::vector<std::pair<double, double>> row;  // (coordinate, alpha)
  for (std::size_t i = 0; i + 1 < records.size(); i += 2) {
    row.emplace_back(records[i], records[i + 1]);
  }
  std::sort(row.begin(), row.end());
  for (std::size_t i = row.size(); i-- > 1;) {
    const auto [x1, a1] = row[i];
    const auto [x0, a0] = row[i - 1];
    if (a0 >= 0.5 && a1 < 0.5) return x0 + (a0 - 0.5) / (a0 - a1) * (x1 - x0);
  }
  return NAN;
}

namespace {

// The cell centres of a uniform slab: cell (i, j)'s is first + i dx + j dy,
// read from global cells 0, 1 and nx (from their owners on distributed fields).
struct SlabCentres {
  Vec3 first;
  double dx = 0.0, dy = 0.0;
};

SlabCentres slabCentres(const FinalFields& fields) {
  const long nx = fields.nx;
  std::vector<double> mine;  // (global id, x, y) of cells 0, 1 and nx
  for (Index c = 0; c < Index(fields.x_c.extent(0)); ++c) {
    const long cell = fields.globalCell(c);
    if (fields.counts(c) && (cell == 0 || cell == 1 || cell == nx)) {
      mine.insert(mine.end(), {double(cell), fields.x_c(c, 0), fields.x_c(c, 1)});
    }
  }
  double x[3] = {NAN, NAN, NAN}, y[3] = {NAN, NAN, NAN};
  const std::vector<double> records = recordsOfAllRanks(fields, mine);
  for (std::size_t r = 0; r < records.size(); r += 3) {
    const long cell = long(records[r]);
    const int which = cell == 0 ? 0 : cell == 1 ? 1 : 2;
    x[which] = records[r + 1];
    y[which] = records[r + 2];
  }
  return {{x[0], y[0], 0.0}, x[1] - x[0], y[2] - y[0]};
}

// The bilinear stencil of the point (x, y) among the centres: cells (i, j)
// to (i + 1, j + 1) with weights from a and b; constant beyond the outer centres.
struct SlabStencil {
  int i, j;
  double a, b;
};

SlabStencil stencilAt(const SlabCentres& centres, int nx, int ny, double x, double y) {
  const double fi = std::clamp((x - centres.first.x) / centres.dx, 0.0, double(nx - 1));
  const double fj = std::clamp((y - centres.first.y) / centres.dy, 0.0, double(ny - 1));
  const int i = std::min(int(fi), nx - 2), j = std::min(int(fj), ny - 2);
  return {i, j, fi - i, fj - j};
}

}  // namespace

std::vector<AlphaCrossing> alphaCrossingsAlongRay(const FinalFields& fields, int material,
                                                  const Vec3& origin, const Vec3& direction) {
  const int nx = fields.nx, ny = fields.ny;
  if (fields.nz != 1 || nx < 2 || ny < 2) {
    throw std::logic_error(
        "alphaCrossingsAlongRay: needs a slab one cell thick, 2 x 2 cells or more");
  }
  const SlabCentres centres = slabCentres(fields);
  const double dx = centres.dx, dy = centres.dy;
  const double length = std::hypot(direction.x, direction.y);
  const double ux = direction.x / length, uy = direction.y / length;
  const double step = 0.125 * std::min(dx, dy);
  // the block's extent; outside the outer centroids the values are constant
  const double lo_x = centres.first.x - 0.5 * dx, hi_x = centres.first.x + (nx - 0.5) * dx;
  const double lo_y = centres.first.y - 0.5 * dy, hi_y = centres.first.y + (ny - 0.5) * dy;
  // The samples: the origin, then every `step` until the ray leaves the block.
  std::vector<std::pair<double, SlabStencil>> samples{
      {0.0, stencilAt(centres, nx, ny, origin.x, origin.y)}};
  for (double s = step;; s += step) {
    const double x = origin.x + s * ux, y = origin.y + s * uy;
    if (x < lo_x || x > hi_x || y < lo_y || y > hi_y) break;  // out of the block
    samples.emplace_back(s, stencilAt(centres, nx, ny, x, y));
  }
  // The volume fractions of the samples' cells: the whole block's, or the
  // cells the samples read, from their owners.
  std::unordered_map<long, double> alpha_near;
  if (fields.distributed) {
    std::vector<long> wanted;
    for (const auto& [s, at] : samples)
      for (int jj : {at.j, at.j + 1})
        for (int ii : {at.i, at.i + 1}) wanted.push_back(ii + long(nx) * jj);
    std::sort(wanted.begin(), wanted.end());
    std::vector<double> mine;  // (global id, alpha)
    for (Index c = 0; c < Index(fields.alpha.extent(0)); ++c) {
      const long cell = fields.globalCell(c);
      if (fields.counts(c) && std::binary_search(wanted.begin(), wanted.end(), cell)) {
        mine.insert(mine.end(), {double(cell), fields.alpha(c, material)});
      }
    }
    const std::vector<double> records = parallel::gatherOnAll(mine);
    for (std::size_t r = 0; r < records.size(); r += 2)
      alpha_near[long(records[r])] = records[r + 1];
  }
  const auto value = [&](int ii, int jj) {
    const long cell = ii + long(nx) * jj;
    return fields.distributed ? alpha_near.at(cell) : fields.alpha(cell, material);
  };
  const auto alphaAt = [&](const SlabStencil& at) {
    const double a = at.a, b = at.b;
    return (1 - a) * (1 - b) * value(at.i, at.j) + a * (1 - b) * value(at.i + 1, at.j) +
           (1 - a) * b * value(at.i, at.j + 1) + a * b * value(at.i + 1, at.j + 1);
  };
  std::vector<AlphaCrossing> crossings;
  double s0 = 0.0, a0 = alphaAt(samples.front().second);
  for (std::size_t n = 1; n < samples.size(); ++n) {
    const double s1 = samples[n].first, a1 = alphaAt(samples[n].second);
    if ((a0 - 0.5) * (a1 - 0.5) < 0.0 || (a1 == 0.5 && a0 != 0.5)) {
      crossings.push_back({s0 + (0.5 - a0) / (a1 - a0) * (s1 - s0), a1 > a0});
    }
    s0 = s1;
    a0 = a1;
  }
  return crossings;
}

void writeCellOutlines(const std::string& path, const FinalFields& fields) {
  std::ostringstream rows;  // keyed by global cell id
  rows << std::setprecision(8);
  for (Index c = 0; c < Index(fields.rho.extent(0)); ++c) {
    if (!fields.counts(c)) continue;
    rows << fields.globalCell(c) << ' ';
    for (int p = 0; p < 4; ++p) {
      const Index node = fields.mesh.cell_nodes(c, p);
      rows << fields.mesh.x_n(node, 0) << ',' << fields.mesh.x_n(node, 1) << ',';
    }
    rows << fields.rho(c) << '\n';
  }
  ResultFile csv(path);
  csv << "x0,y0,x1,y1,x2,y2,x3,y3,density\n";
  writeRowsInCellOrder(rows.str(), fields.distributed, csv);
  csv.write();
}

void ResultFile::write() const {
  if (!path_.empty()) writeTextFile(path_, str());
}

void writeRowsInCellOrder(const std::string& keyed_lines, bool distributed, std::ostream& out) {
  std::vector<parallel::KeyedLine> lines;
  std::istringstream in(keyed_lines);
  for (std::string line; std::getline(in, line);) {
    const std::size_t space = line.find(' ');
    lines.push_back({std::stol(line.substr(0, space)), line.substr(space + 1)});
  }
  std::sort(lines.begin(), lines.end(), [](const auto& a, const auto& b) { return a.key < b.key; });
  if (distributed) {
    parallel::writeMergedOnRoot(lines, &out);
  } else {
    for (const auto& line : lines) out << line.text << '\n';
  }
}

ProblemSetup setupBlock(const Config& config, const Vec3& lo, const Vec3& hi,
                        std::vector<MaterialParams> materials, CellShapes& shapes,
                        std::function<Vec3(const Vec3&)> mapping) {
  BlockSpec block;
  block.nx = int(config.integer("mesh.nx"));
  block.ny = int(config.integer("mesh.ny"));
  block.nz = int(config.integer("mesh.nz"));
  block.lo = lo;
  block.hi = hi;
  block.mapping = std::move(mapping);
  block.part = thisRanksPart(block.nx, block.ny, block.nz);
  ProblemSetup setup;
  setup.mesh = buildBlockMesh(block, readBoundaries(config));
  setup.materials = std::move(materials);
  hostCellShapes(copyToHost(setup.mesh), shapes.volume, shapes.centroid);
  return setup;
}

}  // namespace lagremap
