#include "run.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iomanip>
#include <memory>
#include <sstream>

#include "exact_sum.hpp"
#include "kernels/hex.hpp"
#include "outputs.hpp"
#include "parallel.hpp"
#include "simulation.hpp"
#include "summary.hpp"

namespace lagremap {

bool RunResult::checksPass() const {
  for (const auto& check : checks)
    if (check.counts() && !check.pass()) return false;
  return !failed;
}

namespace {

void checkRunOptions(const RunOptions& options) {
  if (options.mode != "lagrange" && options.mode != "remap" && options.mode != "ale") {
    throw ConfigError("unknown mode '" + options.mode + "' (known: lagrange, remap, ale)");
  }
  const Config& config = options.config;
  if (config.mode() != options.mode) {
    throw std::logic_error("run options: the keys were declared for mode '" + config.mode() +
                           "', not '" + options.mode + "'");
  }
  // A snapshot time past t_end is a time the run never reaches: a mistake to
  // say, not to drop (a problem's own times are those up to t_end already).
  const double t_end = config.real("t_end");
  for (double t_out : options.output_times) {
    if (!(t_out >= 0.0 && t_out <= t_end)) {
      char text[120];
      std::snprintf(text, sizeof text, "output time %.6g s is outside [0, t_end = %.6g s]", t_out,
                    t_end);
      throw ConfigError(text);
    }
  }
  if (options.output_every < 0) throw ConfigError("--output-every must be >= 0");
  // The check.* keys are tolerances, bounds and reference sizes: a negative
  // one would fail its check whatever the run did.
  for (const auto& [key, param] : config.params()) {
    if (key.rfind("check.", 0) == 0 && param.type == ParamType::Real && !(config.real(key) >= 0.0))
      throw ConfigError(key + " must be >= 0, got " + param.value);
  }
}

}  // namespace

RankCosts costsOverRanks(const Simulation& simulation, long steps_run) {
  RankCosts costs;
  const Mesh& mesh = simulation.mesh();
  const double owned_cells = double(parallel::size() > 1 ? mesh.n_owned_cells : mesh.n_cells);
  const double peak = double(peakResidentBytes());
  costs.peak_bytes = parallel::spread(peak);
  costs.peak_own_bytes = parallel::spread(std::max(0.0, peak - double(sharedResidentBytes())));
  costs.setup_peak_bytes = parallel::spread(double(simulation.setupPeakBytes()));
  costs.owned_cells = parallel::spread(owned_cells);
  costs.peak_bytes_per_owned_cell = parallel::spread(owned_cells > 0 ? peak / owned_cells : 0.0);
  const SetupSeconds& setup = simulation.setupSeconds();
  costs.setup = {parallel::max(setup.generate), parallel::max(setup.sample_materials),
                 parallel::max(setup.decompose), parallel::max(setup.initialize)};
  Halo::Traffic cells, nodes;
  if (simulation.halo()) {
    cells = simulation.halo()->cellTraffic();
    nodes = simulation.halo()->nodeTraffic();
  }
  const double per_step = steps_run > 0 ? 1.0 / double(steps_run) : 0.0;
  const double rank_bytes = cells.bytes + nodes.bytes;
  costs.halo_bytes_per_step = parallel::sum(rank_bytes) * per_step;
  costs.halo_messages_per_step = parallel::sum(double(cells.messages + nodes.messages)) * per_step;
  costs.halo_cell_bytes_per_step = parallel::sum(cells.bytes) * per_step;
  costs.halo_node_bytes_per_step = parallel::sum(nodes.bytes) * per_step;
  costs.halo_bytes_per_step_max_rank = parallel::max(rank_bytes) * per_step;
  costs.reductions_per_step = double(simulation.loopReductions()) * per_step;
  return costs;
}

namespace {

// The final (or last good) fields for the problem's checks: on a decomposed
// run this rank's, or the whole block's on every rank when the caller asks.
FinalFields finalFields(const Simulation& simulation) {
  const bool decomposed = parallel::size() > 1;
  const bool gather = decomposed && simulation.options().gather_final_fields;
  const Mesh& mesh = simulation.mesh();
  FinalFields fields = copyFields(mesh, gather, simulation.state(), simulation.time());
  if (decomposed && !gather) {
    fields.distributed = true;
    fields.owned = Kokkos::create_mirror_view_and_copy(HostSpace(), mesh.cell_owned);
    fields.cell_global = mesh.cell_global;
  }
  fields.probe = simulation.loopState().probe;
  return fields;
}

// The neighbour of cell c of `fields` across face f (VTK order: x-, x+, y-,
// y+, z-, z+), -1 on the boundary: by the block's formula for the whole
// block's fields, from the rank's mesh for its own.
Index fieldsNeighbor(const FinalFields& fields, const CellFacesView::HostMirror& neighbors, Index c,
                     int f) {
  if (fields.distributed) return neighbors(c, f);
  const int n[3] = {fields.nx, fields.ny, fields.nz};
  const Index stride[3] = {1, Index(fields.nx), Index(fields.nx) * fields.ny};
  const int axis = f / 2;
  const int index = int((c / stride[axis]) % n[axis]);
  if (f % 2 == 0) return index > 0 ? c - stride[axis] : -1;
  return index < n[axis] - 1 ? c + stride[axis] : -1;
}

// Collective when the fields are distributed: each interior face is counted
// by the owner of its cell of lower global id (a neighbour may be a ghost,
// whose alpha the last exchange gave it).
InterfaceMeasure measureInterface(const Mesh& mesh, const FinalFields& fields, int k) {
  CellFacesView::HostMirror neighbors;
  if (fields.distributed) {
    neighbors = CellFacesView::HostMirror("lagremap::mesh::cell_neighbors", mesh.n_cells);
    Kokkos::deep_copy(neighbors, mesh.cell_neighbors);
  }
  double mixed = 0.0;
  ExactSum smeared, area;
  for (Index c = 0; c < Index(fields.alpha.extent(0)); ++c) {
    if (!fields.counts(c)) continue;
    const double alpha = fields.alpha(c, k);
    mixed += alpha > 0.01 && alpha < 0.99;
    smeared += 4.0 * alpha * (1.0 - alpha) * fields.vol(c);
    Vec3 x[8];
    for (int p = 0; p < 8; ++p) x[p] = loadVec3(fields.mesh.x_n, fields.mesh.cell_nodes(c, p));
    for (int f = 0; f < 6; ++f) {
      const Index nb = fieldsNeighbor(fields, neighbors, c, f);
      if (nb < 0 || fields.globalCell(nb) <= fields.globalCell(c) ||
          (alpha - 0.5) * (fields.alpha(nb, k) - 0.5) >= 0.0)
        continue;
      Vec3 q[4], w[4];
      hex::faceNodes(x, f, q);
      area += norm(hex::faceCornerVectors(q, w));
    }
  }
  if (fields.distributed) {
    std::vector<ExactSum> sums{smeared, area};
    ExactSum::sumOverRanks(sums);
    smeared = sums[0];
    area = sums[1];
    mixed = parallel::sum(mixed);
  }
  InterfaceMeasure measure;
  measure.mixed_cells = long(mixed);
  measure.area = area.value();
  measure.smeared_width = measure.area > 0.0 ? smeared.value() / measure.area : 0.0;
  return measure;
}

// What the loop did: counters, speed, drifts and the final (or last good) fields.
RunResult resultOf(const Simulation& simulation) {
  RunResult result;
  result.cells = simulation.mesh().n_global_cells;
  result.wall_seconds = simulation.wallSeconds();
  result.failed = simulation.failed();
  result.failure = simulation.failure();
  result.stopped_by = simulation.stoppedBy();
  result.steps = simulation.step();
  result.step_events = simulation.stepEvents();
  result.events_counted = kokkosEventsCounted();
  result.time = simulation.time();
  const long steps_run = simulation.step() - simulation.startState().step;  // a restart continues
  result.cell_steps_per_second =
      steps_run > 0 ? double(result.cells) * steps_run / result.wall_seconds : 0;
  result.drift_mass = simulation.driftMass();
  result.drift_momentum = simulation.driftMomentum();
  result.drift_energy = simulation.driftEnergy();
  result.fields = finalFields(simulation);
  // (after the final fields' gather, which the peak memory then includes)
  result.costs = costsOverRanks(simulation, steps_run);
  const FinalFields& fields = result.fields;
  for (Index c = 0; c < Index(fields.v.extent(0)); ++c) {
    if (!fields.counts(c)) continue;
    result.max_transverse_velocity = std::max(
        {result.max_transverse_velocity, std::abs(fields.v(c, 1)), std::abs(fields.v(c, 2))});
  }
  if (fields.distributed)
    result.max_transverse_velocity = parallel::max(result.max_transverse_velocity);
  const int n_materials = simulation.state().n_materials;
  for (int k = 0; n_materials > 1 && k < n_materials; ++k) {
    result.interfaces.push_back(measureInterface(simulation.mesh(), fields, k));
  }
  if (n_materials > 1 && simulation.options().config.remaps()) {
    result.mixed_cells = measureMixedCells(fields, simulation.materials());
  }
  return result;
}

void writeProbe(const std::string& path, const Problem& problem, const FinalFields& fields) {
  std::ostringstream probe_csv;
  probe_csv << "t," << problem.probe.name << '\n' << std::setprecision(12);
  for (const auto& [time, value] : fields.probe) probe_csv << time << ',' << value << '\n';
  writeTextFile(path, probe_csv.str());
}

}  // namespace

RunResult runProblem(const RunOptions& options) {
  const Problem& problem = findProblem(options.problem);
  checkRunOptions(options);
  Simulation simulation(options, problem);
  HistoryFile history(options, simulation);
  simulation.observe(history);
  std::unique_ptr<SnapshotOutput> snapshots;
  std::unique_ptr<CheckpointOutput> checkpoints;
  if (options.write_files) {
    snapshots = std::make_unique<SnapshotOutput>(options, simulation);
    checkpoints = std::make_unique<CheckpointOutput>(options, *snapshots);
    simulation.observe(*snapshots);
    simulation.observe(*checkpoints);
  }
  ProgressLine progress;
  if (!options.quiet) simulation.observe(progress);

  simulation.run();

  RunResult result = resultOf(simulation);
  const bool writer = options.write_files && parallel::isRoot();  // rank 0 writes the files
  const std::string& dir = options.output_dir;
  if (problem.probe && writer) writeProbe(dir + "/probe.csv", problem, result.fields);
  if (!result.failed) {
    ProblemResults finished = problem.finish(options.config, result.fields, writer ? dir : "");
    result.checks = std::move(finished.checks);
    result.l1_errors = std::move(finished.l1_errors);
    if (result.mixed_cells && result.mixed_cells->hasCondensed()) {
      result.checks.push_back(mixedCellsCheck(*result.mixed_cells));
      if (problem.mixed_cells_not_applicable)
        result.checks.back().doesNotApply(problem.mixed_cells_not_applicable);
    }
  }
  if (writer) writeSummary(dir + "/summary.json", simulation, result);
  return result;
}

}  // namespace lagremap
