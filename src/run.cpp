#include "run.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <memory>

#include <unistd.h>

#include "checkpoint.hpp"
#include "decomposition.hpp"
#include "diagnostics.hpp"
#include "io/snapshot_writer.hpp"
#include "json.hpp"
#include "kokkos_session.hpp"
#include "lagrange_step.hpp"
#include "parallel.hpp"
#include "remap_step.hpp"

namespace lagremap {

bool RunResult::checksPass() const {
  for (const auto& check : checks)
    if (!check.pass()) return false;
  return !failed;
}

Config declareConfig(const Problem& problem, const std::string& mode) {
  Config config;
  config.setMode(mode);
  problem.declare(config);
  if (config.remapMode()) {
    config.addReal(
        "remap.beta", 2.0, "-",
        "limiter parameter of the volume fractions (1: Barth-Jespersen, 2: compressive)");
    config.addReal("remap.alpha_floor", 1e-10, "-",
                   "volume fraction below which a material is dropped from a cell (mass and "
                   "energy kept)");
    config.addReal("remap.alpha_trace", 1e-3, "-",
                   "volume fraction below which a material of a mixed cell is a trace: carried, "
                   "but left out of the cell's stress and sound speed");
  }
  config.addChoice("numerics.order", "2", {"1", "2"},
                   "1: first order; 2: limited linear reconstruction + predictor-corrector");
  config.addReal("numerics.cfl", 0.4, "-", "CFL number C_cfl of dt <= C_cfl l_c / aL_c");
  config.addReal("numerics.c_vol", 0.1, "-", "max relative volume change per step C_vol");
  config.addReal("numerics.dt_growth", 1.05, "-", "max ratio of two successive time steps");
  config.addReal("numerics.dt_initial_factor", 0.1, "-", "first dt as a fraction of the stable dt");
  config.addReal("numerics.dt_min_fraction", 1e-12, "-",
                 "the run stops when dt falls below this fraction of t_end");
  config.addInteger("numerics.max_steps", 10000000, "the run stops after this many steps");
  config.addChoice("numerics.gather", "crs", {"crs", "atomics"},
                   "node sums: node->corner CRS (deterministic) or atomic scatter");
  return config;
}

namespace {

// Host copies of the fields of the whole mesh: a decomposed run (`global`:
// the generated mesh, for its connectivity) gathers every rank's owned rows.
FinalFields copyFields(const Mesh& mesh, const Mesh* global, const State& state, double time) {
  FinalFields fields;
  fields.time = time;
  fields.nx = mesh.nx;
  fields.ny = mesh.ny;
  fields.nz = mesh.nz;
  auto cells = [&](const auto& view) {
    auto host = Kokkos::create_mirror_view_and_copy(HostSpace(), view);
    return global ? gatherGlobal(host, mesh, true) : host;
  };
  fields.mesh = copyToHost(mesh);
  if (global) {
    fields.mesh.x_n = gatherGlobal(fields.mesh.x_n, mesh, false);
    fields.mesh.cell_nodes = Kokkos::create_mirror_view_and_copy(HostSpace(), global->cell_nodes);
  }
  fields.rho = cells(state.rho_c);
  fields.p = cells(state.p_c);
  fields.e = cells(state.e_c);
  fields.vol = cells(state.vol_c);
  fields.v = cells(state.v_c);
  fields.x_c = cells(state.x_c);
  fields.S = cells(state.S_c);
  fields.alpha = cells(state.alpha_ck);
  fields.m_k = cells(state.m_ck);
  fields.e_k = cells(state.e_ck);
  fields.p_k = cells(state.p_ck);
  return fields;
}

// Writes a snapshot of this rank's owned cells and nodes, numbered globally
// (all of them on one rank); `fields` are the rank's host copies (copyFields
// without gathering). Collective over the ranks.
void writeSnapshot(io::SnapshotSeries& series, const FinalFields& fields, const Mesh& mesh) {
  const auto cell_owned = Kokkos::create_mirror_view_and_copy(HostSpace(), mesh.cell_owned);
  const auto node_owned = Kokkos::create_mirror_view_and_copy(HostSpace(), mesh.node_owned);
  std::vector<Index> cells, nodes;  // local ids of the owned rows
  std::vector<std::int64_t> cell_rows, node_rows;
  for (Index c = 0; c < mesh.n_cells; ++c) {
    if (!cell_owned(c)) continue;
    cells.push_back(c);
    cell_rows.push_back(mesh.cell_global(c));
  }
  for (Index n = 0; n < mesh.n_nodes; ++n) {
    if (!node_owned(n)) continue;
    nodes.push_back(n);
    node_rows.push_back(mesh.node_global(n));
  }
  const std::size_t n_cells = cells.size(), n_nodes = nodes.size();
  std::vector<double> xyz(3 * n_nodes), velocity(3 * n_cells), deviator(6 * n_cells);
  std::vector<std::int64_t> connectivity(8 * n_cells);
  for (std::size_t i = 0; i < n_nodes; ++i)
    for (int d = 0; d < 3; ++d) xyz[3 * i + d] = fields.mesh.x_n(nodes[i], d);
  // One scalar per owned cell.
  auto scalars = [&](auto value) {
    std::vector<double> column(n_cells);
    for (std::size_t i = 0; i < n_cells; ++i) column[i] = value(cells[i]);
    return column;
  };
  for (std::size_t i = 0; i < n_cells; ++i) {
    const Index c = cells[i];
    for (int p = 0; p < 8; ++p)
      connectivity[8 * i + p] = mesh.node_global(fields.mesh.cell_nodes(c, p));
    for (int d = 0; d < 3; ++d) velocity[3 * i + d] = fields.v(c, d);
    for (int k = 0; k < 6; ++k) deviator[6 * i + k] = fields.S(c, k);
  }
  std::vector<std::vector<double>> columns = {scalars([&](Index c) { return fields.rho(c); }),
                                              scalars([&](Index c) { return fields.p(c); }),
                                              scalars([&](Index c) { return fields.e(c); }),
                                              scalars([&](Index c) { return fields.vol(c); })};
  std::vector<io::CellField> cell_fields = {
      {"density", columns[0].data(), 1},         {"pressure", columns[1].data(), 1},
      {"internal_energy", columns[2].data(), 1}, {"volume", columns[3].data(), 1},
      {"velocity", velocity.data(), 3},          {"deviatoric_stress", deviator.data(), 6}};
  // Multi-material problems: each material's volume fraction, density
  // m^k / (alpha^k v), specific internal energy and pressure (0 where absent).
  const int n_materials = int(fields.alpha.extent(1));
  columns.reserve(columns.size() + 4 * std::size_t(n_materials));
  for (int k = 0; n_materials > 1 && k < n_materials; ++k) {
    auto present = [&](Index c) { return fields.alpha(c, k) > 0.0; };
    columns.push_back(scalars([&](Index c) { return fields.alpha(c, k); }));
    columns.push_back(scalars([&](Index c) {
      return present(c) ? fields.m_k(c, k) / (fields.alpha(c, k) * fields.vol(c)) : 0.0;
    }));
    columns.push_back(scalars([&](Index c) { return present(c) ? fields.e_k(c, k) : 0.0; }));
    columns.push_back(scalars([&](Index c) { return present(c) ? fields.p_k(c, k) : 0.0; }));
    const std::string suffix = "_" + std::to_string(k);
    const std::size_t first = columns.size() - 4;
    cell_fields.push_back({"volume_fraction" + suffix, columns[first].data(), 1});
    cell_fields.push_back({"material_density" + suffix, columns[first + 1].data(), 1});
    cell_fields.push_back({"material_internal_energy" + suffix, columns[first + 2].data(), 1});
    cell_fields.push_back({"material_pressure" + suffix, columns[first + 3].data(), 1});
  }
  const io::SnapshotMesh snapshot_mesh{
      std::int64_t(n_nodes), xyz.data(),       std::int64_t(n_cells), connectivity.data(),
      node_rows.data(),      cell_rows.data(), mesh.n_global_nodes,   mesh.n_global_cells};
  series.write(fields.time, snapshot_mesh, cell_fields);
}

// Runs `action` on every rank; an error one rank finds (bad input, an
// unreadable file) is thrown as ConfigError by all, with the lowest rank's message.
template <class Action>
void collectively(Action action) {
  std::string error;
  try {
    action();
  } catch (const std::exception& bad) {
    error = bad.what();
  }
  error = parallel::firstMessage(error);
  if (!error.empty()) throw ConfigError(error);
}

// Replaces the generated mesh and initial cells of `setup` by this rank's
// subdomain; the generated mesh goes to `global_mesh` (output connectivity).
std::unique_ptr<Halo> keepSubdomain(ProblemSetup& setup, Mesh& global_mesh,
                                    const std::string& problem) {
  Subdomain sub;
  try {
    sub = decompose(setup.mesh);
  } catch (const std::invalid_argument& error) {
    throw ConfigError(problem + ": " + error.what());
  }
  setup.cells = localInitialCells(setup.cells, sub.mesh, int(setup.materials.size()));
  global_mesh = std::move(setup.mesh);
  setup.mesh = std::move(sub.mesh);
  return std::make_unique<Halo>(std::move(sub.halo));
}

// The remap.* keys; the trace threshold goes to the state (the mixture rules read it).
RemapControls readRemapControls(const Config& config, State& state) {
  RemapControls controls;
  controls.beta_alpha = config.real("remap.beta");
  controls.alpha_floor = config.real("remap.alpha_floor");
  state.alpha_trace = config.real("remap.alpha_trace");
  if (!(state.alpha_trace >= 0.0 && state.alpha_trace < 0.5 / state.n_materials)) {
    throw ConfigError("remap.alpha_trace must be in [0, 0.5 / number of materials)");
  }
  if (!(controls.beta_alpha >= 1.0 && controls.beta_alpha <= 2.0)) {
    throw ConfigError("remap.beta must be in [1, 2]");
  }
  if (!(controls.alpha_floor >= 0.0 && controls.alpha_floor < 0.5)) {
    throw ConfigError("remap.alpha_floor must be in [0, 0.5)");
  }
  return controls;
}

// The header and the lines of steps <= last_step of an existing history.csv
// ("" if there is none): what a restart from step last_step keeps.
std::string historyUpTo(const std::string& path, long last_step) {
  std::ifstream in(path);
  std::string line, kept;
  if (!in || !std::getline(in, line)) return "";
  kept = line + '\n';
  while (std::getline(in, line)) {
    if (std::atol(line.c_str()) > last_step) break;
    kept += line + '\n';
  }
  return kept;
}

// A mesh that cannot fit in memory is bad input, said before anything is
// allocated (the operating system would otherwise kill the run). About 1.2 kB
// per cell: corner records, cell and node fields, host copies for output.
void checkMemoryFits(const Config& config) {
  if (!config.has("mesh.nx") || !config.has("mesh.ny") || !config.has("mesh.nz")) return;
  const double cells = double(config.integer("mesh.nx")) * double(config.integer("mesh.ny")) *
                       double(config.integer("mesh.nz"));
  const double needed = 1200.0 * cells;
  const double available = double(sysconf(_SC_PHYS_PAGES)) * double(sysconf(_SC_PAGE_SIZE));
  if (available > 0 && needed > 0.8 * available) {
    char text[160];
    std::snprintf(text, sizeof text,
                  "mesh of %.3g cells needs about %.1f GB, more than this machine's %.1f GB", cells,
                  needed / 1e9, available / 1e9);
    throw ConfigError(text);
  }
}

// Sharpness of material k's interface in the final state (issue: compare the
// volume-fraction limiters): mixed cells (0.01 < alpha < 0.99), the area of the
// alpha = 1/2 surface (interior faces across which alpha crosses 1/2), and
// the smeared width sum 4 alpha (1 - alpha) v / area (one cell at alpha = 1/2
// per cell of interface gives the cell size).
struct InterfaceMeasure {
  long mixed_cells = 0;
  double area = 0.0, smeared_width = 0.0;
};

InterfaceMeasure measureInterface(const Mesh& mesh, const FinalFields& fields, int k) {
  InterfaceMeasure measure;
  const auto neighbors = Kokkos::create_mirror_view_and_copy(HostSpace(), mesh.cell_neighbors);
  double smeared = 0.0;
  for (Index c = 0; c < mesh.n_cells; ++c) {
    const double alpha = fields.alpha(c, k);
    measure.mixed_cells += alpha > 0.01 && alpha < 0.99;
    smeared += 4.0 * alpha * (1.0 - alpha) * fields.vol(c);
    Vec3 x[8];
    for (int p = 0; p < 8; ++p) x[p] = loadVec3(fields.mesh.x_n, fields.mesh.cell_nodes(c, p));
    for (int f = 0; f < 6; ++f) {
      const Index nb = neighbors(c, f);
      if (nb <= c || (alpha - 0.5) * (fields.alpha(nb, k) - 0.5) >= 0.0) continue;
      Vec3 q[4], w[4];
      hex::faceNodes(x, f, q);
      measure.area += norm(hex::faceCornerVectors(q, w));
    }
  }
  measure.smeared_width = measure.area > 0.0 ? smeared / measure.area : 0.0;
  return measure;
}

const char* limitReason(const StepLimit& limit) {
  return limit.loc % kLimitCodes == kLimitVolume ? "volume" : "cfl";
}

std::string formatSeconds(double seconds) {
  char text[32];
  if (seconds < 120) {
    std::snprintf(text, sizeof text, "%.0fs", seconds);
  } else {
    std::snprintf(text, sizeof text, "%.0fm%02.0fs", std::floor(seconds / 60),
                  std::fmod(seconds, 60.0));
  }
  return text;
}

}  // namespace

Numerics readNumerics(const Config& config) {
  Numerics numerics;
  numerics.order = int(config.integer("numerics.order"));
  numerics.step.cfl = config.real("numerics.cfl");
  numerics.step.c_vol = config.real("numerics.c_vol");
  numerics.dt_growth = config.real("numerics.dt_growth");
  numerics.dt_initial_factor = config.real("numerics.dt_initial_factor");
  numerics.dt_min = config.real("numerics.dt_min_fraction") * config.real("t_end");
  numerics.max_steps = config.integer("numerics.max_steps");
  numerics.gather = config.text("numerics.gather") == "atomics" ? Gather::Atomics : Gather::Crs;
  if (!(numerics.step.cfl > 0.0 && numerics.step.cfl <= 1.0)) {
    throw ConfigError("numerics.cfl must be in (0, 1]");
  }
  if (!(numerics.step.c_vol > 0.0 && numerics.step.c_vol < 1.0)) {
    throw ConfigError("numerics.c_vol must be in (0, 1)");
  }
  if (!(numerics.dt_growth >= 1.0)) throw ConfigError("numerics.dt_growth must be >= 1");
  if (!(numerics.dt_initial_factor > 0.0 && numerics.dt_initial_factor <= 1.0)) {
    throw ConfigError("numerics.dt_initial_factor must be in (0, 1]");
  }
  if (numerics.max_steps < 1) throw ConfigError("numerics.max_steps must be >= 1");
  if (!(config.real("t_end") > 0.0)) throw ConfigError("t_end must be > 0");
  return numerics;
}

// Uploads the problem's initial cells and allocates the per-material state:
// m^k = alpha^k rho^k v (v from the same geometry kernel the run uses),
// m = sum m^k, m e = sum m^k e^k, E = e + |V|^2 / 2; undeformed solids
// (S = 0, B = I).
void initializeState(const ProblemSetup& setup, State& state) {
  const Index n_cells = setup.mesh.n_cells;
  const int n_materials = int(setup.materials.size());
  const InitialCells& cells = setup.cells;
  const bool mixed = !cells.alpha_k.empty();
  const std::size_t n_entries = std::size_t(n_cells) * std::size_t(n_materials);
  const bool sizes_ok =
      Index(cells.v.size()) == n_cells &&
      (mixed ? cells.alpha_k.size() == n_entries && cells.rho_k.size() == n_entries &&
                   cells.e_k.size() == n_entries
             : Index(cells.rho.size()) == n_cells && Index(cells.e.size()) == n_cells &&
                   Index(cells.mat.size()) == n_cells);
  if (n_materials < 1 || !sizes_ok) {
    throw std::logic_error("problem set-up gave initial data of the wrong size");
  }
  bool has_solids = false;
  for (const MaterialParams& material : setup.materials) {
    has_solids = has_solids || material.strength != StrengthKind::None;
  }
  allocateMaterialState(state, n_cells, n_materials, has_solids);

  std::vector<double> volume;
  std::vector<Vec3> centroid;
  hostCellShapes(copyToHost(setup.mesh), volume, centroid);
  auto m_host = Kokkos::create_mirror_view(state.m_c);
  auto v_host = Kokkos::create_mirror_view(state.v_c);
  auto E_host = Kokkos::create_mirror_view(state.E_c);
  auto alpha_host = Kokkos::create_mirror_view(state.alpha_ck);
  auto m_k_host = Kokkos::create_mirror_view(state.m_ck);
  auto e_k_host = Kokkos::create_mirror_view(state.e_ck);
  Kokkos::deep_copy(alpha_host, 0.0);
  Kokkos::deep_copy(m_k_host, 0.0);
  Kokkos::deep_copy(e_k_host, 0.0);
  for (Index c = 0; c < n_cells; ++c) {
    const std::string where = "initial state: cell " + std::to_string(c);
    if (!(volume[c] > 0.0)) throw ConfigError(where + " has a non-positive volume");
    double mass = 0.0, internal_energy = 0.0, alpha_sum = 0.0;
    for (int k = 0; k < n_materials; ++k) {
      const std::size_t i = std::size_t(c) * std::size_t(n_materials) + std::size_t(k);
      const double alpha = mixed ? cells.alpha_k[i] : double(cells.mat[c] == k);
      if (!(alpha >= 0.0 && alpha <= 1.0)) {
        throw ConfigError(where + " has a volume fraction outside [0, 1]");
      }
      if (alpha == 0.0) continue;
      const double rho = mixed ? cells.rho_k[i] : cells.rho[c];
      const double e = mixed ? cells.e_k[i] : cells.e[c];
      if (!(rho > 0.0)) throw ConfigError(where + " has a non-positive density");
      alpha_host(c, k) = alpha;
      m_k_host(c, k) = alpha * rho * volume[c];
      e_k_host(c, k) = e;
      alpha_sum += alpha;
      mass += m_k_host(c, k);
      internal_energy += m_k_host(c, k) * e;
    }
    if (!mixed && (cells.mat[c] < 0 || cells.mat[c] >= n_materials)) {
      throw std::logic_error("problem set-up gave an unknown material index");
    }
    if (!(std::fabs(alpha_sum - 1.0) <= 1e-12)) {
      throw ConfigError(where + " has volume fractions that do not sum to 1");
    }
    m_host(c) = mass;
    storeVec3(v_host, c, cells.v[c]);
    E_host(c) = internal_energy / mass + 0.5 * dot(cells.v[c], cells.v[c]);
  }
  Kokkos::deep_copy(state.m_c, m_host);
  Kokkos::deep_copy(state.v_c, v_host);
  Kokkos::deep_copy(state.E_c, E_host);
  Kokkos::deep_copy(state.alpha_ck, alpha_host);
  Kokkos::deep_copy(state.m_ck, m_k_host);
  Kokkos::deep_copy(state.e_ck, e_k_host);
  if (has_solids) {
    auto B_host = Kokkos::create_mirror_view(state.B_ck);
    for (Index c = 0; c < n_cells; ++c)
      for (int k = 0; k < n_materials; ++k) storeSym(B_host, c, k, identitySym());
    Kokkos::deep_copy(state.B_ck, B_host);
  }
  state.materials = MaterialView("lagremap::state::materials", setup.materials.size());
  auto materials_host = Kokkos::create_mirror_view(state.materials);
  for (std::size_t k = 0; k < setup.materials.size(); ++k) materials_host(k) = setup.materials[k];
  Kokkos::deep_copy(state.materials, materials_host);
}

RunResult runProblem(const RunOptions& options) {
  const Problem& problem = findProblem(options.problem);
  if (options.mode != "lagrange" && options.mode != "remap") {
    throw ConfigError("unknown mode '" + options.mode + "' (known: lagrange, remap)");
  }
  const Config& config = options.config;
  if (config.mode() != options.mode) {
    throw std::logic_error("run options: the keys were declared for mode '" + config.mode() +
                           "', not '" + options.mode + "'");
  }
  const Numerics numerics = readNumerics(config);
  const double t_end = config.real("t_end");
  for (double t_out : options.output_times) {
    if (!(t_out >= 0.0 && t_out <= t_end)) {
      throw ConfigError("output time " + std::to_string(t_out) + " is outside [0, t_end]");
    }
  }
  if (options.output_every < 0) throw ConfigError("--output-every must be >= 0");

  checkMemoryFits(config);
  ProblemSetup setup;
  try {
    setup = problem.setup(config);
  } catch (const std::invalid_argument& error) {  // e.g. an impossible mesh
    throw ConfigError(options.problem + ": " + error.what());
  }
  // --- decomposition (DESIGN §6): this rank's block of cells and its ghosts
  const bool decomposed = parallel::size() > 1;
  Mesh global_mesh;  // the generated mesh of a decomposed run (output connectivity)
  std::unique_ptr<Halo> halo;
  if (decomposed) halo = keepSubdomain(setup, global_mesh, options.problem);
  const Mesh* output_mesh = decomposed ? &global_mesh : nullptr;
  Mesh& mesh = setup.mesh;
  State state = allocateState(mesh, numerics.gather == Gather::Atomics);
  collectively([&] { initializeState(setup, state); });

  PhaseTimers timers;
  LagrangeStep lagrange(mesh, state, numerics, timers, halo.get());
  StepLimit limit = lagrange.computeGeometry();
  if (limit.val < 0.0) {
    throw ConfigError("initial state is invalid: " + describeInvalidCell(limit, 0, "set-up"));
  }
  lagrange.saveStartOfStep();
  std::unique_ptr<RemapStep> remap;
  if (config.remapMode()) {
    const RemapControls controls = readRemapControls(config, state);
    try {
      remap = std::make_unique<RemapStep>(mesh, state, controls, timers, halo.get());
    } catch (const std::invalid_argument& error) {
      throw ConfigError(options.problem + ": " + error.what());
    }
    lagrange.remapFollowsEveryStep();
  }

  // --- restart (DESIGN §6): the evolved state and the loop's counters of a
  // checkpoint; the derived fields follow from the same geometry kernel.
  LoopState loop;
  loop.problem = options.problem;
  loop.mode = options.mode;
  const bool restart = !options.restart_file.empty();
  if (restart) {
    collectively([&] {
      loop = readCheckpoint(options.restart_file, mesh, state, options.problem, options.mode);
    });
    if (!(loop.time < t_end)) {
      throw ConfigError("checkpoint '" + options.restart_file +
                        "' is at t = " + std::to_string(loop.time) + ", not before t_end");
    }
    limit = lagrange.computeGeometry();
    if (limit.val < 0.0) {
      throw ConfigError("checkpoint '" + options.restart_file + "' holds an invalid state: " +
                        describeInvalidCell(limit, loop.step, "restart"));
    }
    lagrange.saveStartOfStep();
  }

  // --- outputs
  const std::string& dir = options.output_dir;
  std::unique_ptr<io::SnapshotSeries> snapshots;
  std::ofstream history;
  const bool writer = options.write_files && parallel::isRoot();  // rank 0 writes the files
  std::string output_error;  // rank 0's, reported by every rank
  if (writer) {
    std::error_code error;
    std::filesystem::create_directories(dir, error);
    if (error) {
      output_error = "cannot create output directory '" + dir + "': " + error.message();
    } else {
      // A restart keeps the history of the steps it does not redo.
      const std::string kept = restart ? historyUpTo(dir + "/history.csv", loop.step) : "";
      history.open(dir + "/history.csv");
      if (!history) output_error = "cannot write '" + dir + "/history.csv'";
      if (kept.empty()) {
        history << "step,t,dt,dt_reason,mass,momentum_x,momentum_y,momentum_z,kinetic_energy,"
                   "internal_energy,total_energy\n";
      }
      history << kept << std::setprecision(15);
    }
  }
  output_error = parallel::firstMessage(output_error);
  if (!output_error.empty()) throw ConfigError(output_error);
  if (options.write_files) {
    snapshots = std::make_unique<io::SnapshotSeries>(dir, "fields");
    snapshots->resume(loop.snapshot_times);
  }
  auto writeHistory = [&](long step, double t, double dt, const char* reason, const Totals& tot) {
    if (!history.is_open()) return;
    history << step << ',' << t << ',' << dt << ',' << reason << ',' << tot.mass << ','
            << tot.momentum.x << ',' << tot.momentum.y << ',' << tot.momentum.z << ','
            << tot.kinetic << ',' << tot.internal << ',' << tot.total() << '\n';
  };
  auto snapshot = [&](double t) {
    if (!snapshots) return;
    auto scope = timers.scope(Phase::Output);
    writeSnapshot(*snapshots, copyFields(mesh, nullptr, state, t), mesh);
  };

  std::vector<std::pair<double, double>> probe = loop.probe;
  Totals initial = loop.initial;
  if (!restart) {
    if (problem.probe) probe.emplace_back(0.0, problem.probe(mesh, state));
    initial = computeTotals(mesh, state);
    writeHistory(0, 0.0, 0.0, "initial", initial);
    snapshot(0.0);
  }
  std::vector<double> pending_outputs;  // after the initial (or restart) time
  for (double t_out : options.output_times) {
    if (t_out > loop.time) pending_outputs.push_back(t_out);
  }
  std::sort(pending_outputs.begin(), pending_outputs.end());

  // --- time loop (DESIGN §3)
  RunResult result;
  result.cells = mesh.n_global_cells;
  Vec3 impulse = loop.impulse;  // boundary impulse and work, for the conservation audit
  double work = loop.work;
  double mass_in = loop.mass_in;  // what the remap brought in through a moving outer boundary
  double t = loop.time, dt_prev = loop.dt_prev;
  long step = loop.step;
  // A checkpoint of the state at t (collective; atomic replacement of the last one).
  auto checkpoint = [&] {
    if (!snapshots) return;
    auto scope = timers.scope(Phase::Output);
    const LoopState now{
        options.problem, options.mode,       t,    dt_prev, step, impulse, work, mass_in,
        initial,         snapshots->times(), probe};
    writeCheckpoint(dir + "/checkpoint.h5", mesh, state, now);
  };
  const auto wall_start = std::chrono::steady_clock::now();
  auto last_progress = wall_start;
  auto elapsed = [&] {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  };
  Totals totals = initial;
  while (t < t_end) {
    // dt = min(stable dt, growth * dt_prev, next output time, t_end) (DESIGN §3)
    double dt = limit.val;
    const char* reason = limitReason(limit);
    if (step == 0) {
      dt *= numerics.dt_initial_factor;
      reason = "initial";
    } else if (numerics.dt_growth * dt_prev < dt) {
      dt = numerics.dt_growth * dt_prev;
      reason = "growth";
    }
    if (!pending_outputs.empty() && t + dt >= pending_outputs.front()) {
      dt = pending_outputs.front() - t;
      reason = "output";
    }
    if (t + dt >= t_end) {
      dt = t_end - t;
      reason = "end";
    }
    if (step >= numerics.max_steps) {
      result.failure = "step " + std::to_string(step) +
                       ": numerics.max_steps reached at t = " + std::to_string(t);
    } else if (dt < numerics.dt_min && reason != std::string("end") &&
               reason != std::string("output")) {
      result.failure = "step " + std::to_string(step + 1) +
                       ": time step collapse, dt = " + std::to_string(dt) + " (" + reason +
                       " limited, cell " + std::to_string(limit.loc / kLimitCodes) + ")";
    }
    if (!result.failure.empty()) break;

    RemapBoundaryFlux crossed;
    try {
      limit = lagrange.advance(dt, step + 1);  // and the next step's candidates
      if (limit.val < 0.0) throw RunFailure(describeInvalidCell(limit, step + 1, "end of step"));
      if (remap) {  // back onto the initial mesh (DESIGN §5), then its time step
        crossed = remap->apply();
        limit = lagrange.computeGeometry(remap->targetGeometry());
        if (limit.val < 0.0) {
          remap->restoreStartOfStep();
          throw RunFailure(describeInvalidCell(limit, step + 1, "after the remap"));
        }
      }
    } catch (const RunFailure& failure) {
      lagrange.restoreStartOfStep();
      result.failure = failure.what();
      break;
    }
    t = (reason == std::string("end")) ? t_end : t + dt;
    dt_prev = dt;
    ++step;
    if (!pending_outputs.empty() && reason == std::string("output")) {
      t = pending_outputs.front();
      pending_outputs.erase(pending_outputs.begin());
      snapshot(t);
    } else if (options.output_every > 0 && step % options.output_every == 0 && t < t_end) {
      snapshot(t);
    }
    {
      auto scope = timers.scope(Phase::Diagnostics);
      const BoundaryPower boundary = computeBoundaryPower(mesh, state);
      impulse += dt * boundary.force + Vec3{crossed.v[1], crossed.v[2], crossed.v[3]};
      work += dt * boundary.power + crossed.v[4];
      mass_in += crossed.v[0];
      totals = computeTotals(mesh, state);
    }
    writeHistory(step, t, dt, reason, totals);
    if (problem.probe) {
      auto scope = timers.scope(Phase::Diagnostics);
      probe.emplace_back(t, problem.probe(mesh, state));
    }
    if (options.checkpoint_every > 0 && step % options.checkpoint_every == 0 && t < t_end) {
      checkpoint();
    }
    if (!options.quiet && parallel::isRoot()) {
      const auto now = std::chrono::steady_clock::now();
      if (std::chrono::duration<double>(now - last_progress).count() > 3.0) {
        last_progress = now;
        const double seconds = elapsed();
        std::fprintf(stderr, "[lagremap] %5.1f%%  step %ld  t %.6g  dt %.3g (%s)  ETA %s\n",
                     100.0 * t / t_end, step, t, dt, reason,
                     formatSeconds(seconds * (t_end - t) / (t - loop.time)).c_str());
      }
    }
  }
  result.wall_seconds = elapsed();
  result.failed = !result.failure.empty();
  if (result.failed) checkpoint();  // the last good state, to restart from
  result.steps = step;
  result.time = t;
  const long steps_run = step - loop.step;  // by this process (a restart continues a run)
  result.cell_steps_per_second =
      steps_run > 0 ? double(mesh.n_global_cells) * steps_run / result.wall_seconds : 0;

  // --- conservation audit: change of each total minus what the boundaries put in.
  // Scales: the largest energy the run held or received (a body at rest
  // driven by a traction starts with zero energy).
  const double energy_scale =
      std::max({std::abs(initial.total()), std::abs(totals.total()), std::abs(work), 1e-300});
  const double momentum_scale = std::max(std::sqrt(2.0 * initial.mass * energy_scale), 1e-300);
  result.drift_mass = std::abs(totals.mass - initial.mass - mass_in) / initial.mass;
  result.drift_momentum = norm(totals.momentum - initial.momentum - impulse) / momentum_scale;
  result.drift_energy = std::abs(totals.total() - initial.total() - work) / energy_scale;

  result.fields = copyFields(mesh, output_mesh, state, t);
  result.fields.probe = std::move(probe);
  if (problem.probe && writer) {
    std::ofstream probe_csv(dir + "/probe.csv");
    probe_csv << "t," << problem.probe_name << '\n' << std::setprecision(12);
    for (const auto& [time, value] : result.fields.probe) probe_csv << time << ',' << value << '\n';
  }
  for (Index c = 0; c < Index(result.fields.v.extent(0)); ++c) {
    result.max_transverse_velocity =
        std::max({result.max_transverse_velocity, std::abs(result.fields.v(c, 1)),
                  std::abs(result.fields.v(c, 2))});
  }
  if (!result.failed) result.checks = problem.finish(config, result.fields, writer ? dir : "");
  if (snapshots) {
    auto scope = timers.scope(Phase::Output);
    writeSnapshot(*snapshots, decomposed ? copyFields(mesh, nullptr, state, t) : result.fields,
                  mesh);
  }
  if (!writer) return result;
  // --- summary.json
  std::ofstream out(dir + "/summary.json");
  JsonWriter json(out);
  json.beginObject()
      .value("problem", options.problem)
      .value("mode", options.mode)
      .value("order", numerics.order)
      .value("gather", config.text("numerics.gather"))
      .value("threads", executionSpaceIsHost() ? long(ExecSpace().concurrency()) : 0L)
      .value("concurrency", long(ExecSpace().concurrency()))
      .value("execution_space", ExecSpace::name())
      .value("cells", mesh.n_global_cells)
      .value("nodes", mesh.n_global_nodes)
      .value("ranks", long(parallel::size()))
      .value("steps", step)
      .value("t_end", t_end)
      .value("t_final", t)
      .value("status", result.failed ? "failed" : "completed");
  if (result.failed) json.value("failure", result.failure);
  json.value("wall_seconds", result.wall_seconds);
  json.beginObject("cell_steps_per_second").value("total", result.cell_steps_per_second);
  json.beginObject("phases");
  for (int phase = 0; phase < int(Phase::Count); ++phase) {
    const double seconds = timers.seconds(Phase(phase));
    json.value(phaseName(Phase(phase)),
               seconds > 0 ? double(mesh.n_global_cells) * step / seconds : 0.0);
  }
  json.endObject().endObject();
  json.beginObject("phase_seconds");
  for (int phase = 0; phase < int(Phase::Count); ++phase) {
    json.value(phaseName(Phase(phase)), timers.seconds(Phase(phase)));
  }
  json.endObject();
  json.beginObject("drift")
      .value("mass", result.drift_mass)
      .value("momentum", result.drift_momentum)
      .value("total_energy", result.drift_energy)
      .value("note", "relative; boundary impulse and work subtracted (conservation audit)")
      .endObject();
  json.beginObject("totals")
      .value("mass", totals.mass)
      .value("kinetic_energy", totals.kinetic)
      .value("internal_energy", totals.internal)
      .value("boundary_work", work)
      .endObject();
  if (state.n_materials > 1) {
    json.beginObject("interfaces");
    for (int k = 0; k < state.n_materials; ++k) {
      const InterfaceMeasure measure =
          measureInterface(decomposed ? global_mesh : mesh, result.fields, k);
      json.beginObject("material_" + std::to_string(k))
          .value("solid", setup.materials[k].strength != StrengthKind::None)
          .value("mixed_cells", measure.mixed_cells)
          .value("area", measure.area)
          .value("mixed_cells_per_unit_area",
                 measure.area > 0.0 ? double(measure.mixed_cells) / measure.area : 0.0)
          .value("smeared_width", measure.smeared_width)
          .value("note",
                 "mixed: 0.01 < alpha < 0.99; area of the alpha = 1/2 surface [m^2]; "
                 "width = sum 4 alpha (1 - alpha) v / area [m]")
          .endObject();
    }
    json.endObject();
  }
  json.beginObject("checks");
  for (const auto& check : result.checks) {
    json.beginObject(check.name)
        .value("value", check.value)
        .value("reference", check.reference)
        .value("tolerance", check.tolerance);
    if (check.lagrange_reference) json.value("lagrange_reference", *check.lagrange_reference);
    if (check.paper) json.value("paper", *check.paper);
    json.value("pass", check.pass()).value("note", check.note).endObject();
  }
  json.endObject();
  json.beginObject("config");
  for (const auto& [key, param] : config.params()) json.value(key, param.value);
  json.endObject();
  json.endObject();
  return result;
}

}  // namespace lagremap
