#include "summary.hpp"

#include <fstream>

#include "../kernels/hex.hpp"
#include "json.hpp"
#include "kokkos_session.hpp"
#include "parallel.hpp"

namespace lagremap {
namespace {

// Sharpness of material k's interface in the final state : mixed cells (0.01 < alpha < 0.99), the
// area of the alpha = 1/2 surface (interior faces across which alpha crosses 1/2), and the smeared
// width sum 4 alpha (1 - alpha) v / area (one cell at alpha = 1/2 per cell of interface gives the
// cell size).
struct InterfaceMeasure {
  long mixed_cells = 0;
  double area = 0.0, smeared_width = 0.0;
};

// The face neighbour of cell c of the fields' block across face f (VTK
// order: x-, x+, y-, y+, z-, z+), -1 on the boundary.
Index blockNeighbor(const FinalFields& fields, Index c, int f) {
  const int n[3] = {fields.nx, fields.ny, fields.nz};
  const Index stride[3] = {1, Index(fields.nx), Index(fields.nx) * fields.ny};
  const int axis = f / 2;
  const int index = int((c / stride[axis]) % n[axis]);
  if (f % 2 == 0) return index > 0 ? c - stride[axis] : -1;
  return index < n[axis] - 1 ? c + stride[axis] : -1;
}

InterfaceMeasure measureInterface(const FinalFields& fields, int k) {
  InterfaceMeasure measure;
  double smeared = 0.0;
  for (Index c = 0; c < Index(fields.alpha.extent(0)); ++c) {
    const double alpha = fields.alpha(c, k);
    measure.mixed_cells += alpha > 0.01 && alpha < 0.99;
    smeared += 4.0 * alpha * (1.0 - alpha) * fields.vol(c);
    Vec3 x[8];
    for (int p = 0; p < 8; ++p) x[p] = loadVec3(fields.mesh.x_n, fields.mesh.cell_nodes(c, p));
    for (int f = 0; f < 6; ++f) {
      const Index nb = blockNeighbor(fields, c, f);
      if (nb <= c || (alpha - 0.5) * (fields.alpha(nb, k) - 0.5) >= 0.0) continue;
      Vec3 q[4], w[4];
      hex::faceNodes(x, f, q);
      measure.area += norm(hex::faceCornerVectors(q, w));
    }
  }
  measure.smeared_width = measure.area > 0.0 ? smeared / measure.area : 0.0;
  return measure;
}

void writeRunAndSpeed(JsonWriter& json, const Simulation& simulation, const RunResult& result) {
  const Config& config = simulation.options().config;
  const Mesh& mesh = simulation.mesh();
  json.value("problem", simulation.options().problem)
      .value("mode", simulation.options().mode)
      .value("order", simulation.numerics().order)
      .value("gather", config.text("numerics.gather"))
      .value("threads", executionSpaceIsHost() ? long(ExecSpace().concurrency()) : 0L)
      .value("concurrency", long(ExecSpace().concurrency()))
      .value("execution_space", ExecSpace::name())
      .value("cells", mesh.n_global_cells)
      .value("nodes", mesh.n_global_nodes)
      .value("ranks", long(parallel::size()))
      .value("steps", result.steps)
      .value("t_end", simulation.tEnd())
      .value("t_final", result.time)
      .value("status", result.failed ? "failed" : "completed");
  if (result.failed) json.value("failure", result.failure);
  json.value("wall_seconds", result.wall_seconds);
  const PhaseTimers& timers = simulation.timers();
  json.beginObject("cell_steps_per_second").value("total", result.cell_steps_per_second);
  json.beginObject("phases");
  for (int phase = 0; phase < int(Phase::Count); ++phase) {
    const double seconds = timers.seconds(Phase(phase));
    json.value(phaseName(Phase(phase)),
               seconds > 0 ? double(mesh.n_global_cells) * result.steps / seconds : 0.0);
  }
  json.endObject().endObject();
  json.beginObject("phase_seconds");
  for (int phase = 0; phase < int(Phase::Count); ++phase) {
    json.value(phaseName(Phase(phase)), timers.seconds(Phase(phase)));
  }
  json.endObject();
}

// Set-up time per phase (the slowest rank's), peak memory per rank and the
// halo's traffic (docs/performance.md, Parallel runs).
void writeCosts(JsonWriter& json, const RankCosts& costs) {
  json.beginObject("setup_seconds")
      .value("generate", costs.setup.generate)
      .value("sample_materials", costs.setup.sample_materials)
      .value("decompose", costs.setup.decompose)
      .value("initialize", costs.setup.initialize)
      .value("total", costs.setup.total())
      .value("note",
             "wall time of each set-up phase, the slowest rank's (total: their sum); generate: "
             "the problem's mesh and initial cells but the mixed-cell sampling")
      .endObject();
  const auto spread = [&](const std::string& name, const parallel::Spread& value) {
    json.beginObject(name)
        .value("min", value.min)
        .value("mean", value.mean)
        .value("max", value.max)
        .endObject();
  };
  json.beginObject("memory");
  spread("peak_bytes", costs.peak_bytes);
  spread("setup_peak_bytes", costs.setup_peak_bytes);
  spread("owned_cells", costs.owned_cells);
  spread("peak_bytes_per_owned_cell", costs.peak_bytes_per_owned_cell);
  json.value("note",
             "per rank: peak resident set of the process (getrusage), of the whole run and at the "
             "end of set-up; min, mean and max over the ranks")
      .endObject();
  json.beginObject("halo")
      .value("bytes_per_step", costs.halo_bytes_per_step)
      .value("messages_per_step", costs.halo_messages_per_step)
      .value("cell_bytes_per_step", costs.halo_cell_bytes_per_step)
      .value("node_bytes_per_step", costs.halo_node_bytes_per_step)
      .value("bytes_per_step_max_rank", costs.halo_bytes_per_step_max_rank)
      .value("reductions_per_step", costs.reductions_per_step)
      .value("note",
             "sent by all ranks together per step of this run (the busiest rank's apart); "
             "reductions: collective reductions over the ranks per step")
      .endObject();
}

void writeConservation(JsonWriter& json, const Simulation& simulation, const RunResult& result) {
  json.beginObject("drift")
      .value("mass", result.drift_mass)
      .value("momentum", result.drift_momentum)
      .value("total_energy", result.drift_energy)
      .value("note", "relative; boundary impulse and work subtracted (conservation audit)")
      .endObject();
  json.beginObject("totals")
      .value("mass", simulation.totals().mass)
      .value("kinetic_energy", simulation.totals().kinetic)
      .value("internal_energy", simulation.totals().internal)
      .value("boundary_work", simulation.loopState().work)
      .endObject();
}

void writeInterfaces(JsonWriter& json, const Simulation& simulation, const RunResult& result) {
  const int n_materials = simulation.state().n_materials;
  // (measured on the whole block's fields: not where a problem's checks read owned cells)
  if (n_materials <= 1 || result.fields.distributed) return;
  json.beginObject("interfaces");
  for (int k = 0; k < n_materials; ++k) {
    const InterfaceMeasure measure = measureInterface(result.fields, k);
    json.beginObject("material_" + std::to_string(k))
        .value("solid", simulation.materials()[k].strength != StrengthKind::None)
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

void writeChecksAndKeys(JsonWriter& json, const Config& config, const RunResult& result) {
  json.beginObject("checks");
  for (const auto& check : result.checks) {
    json.beginObject(check.name)
        .value("value", check.value)
        .value("reference", check.reference)
        .value("tolerance", check.tolerance);
    if (check.lagrange_reference) json.value("lagrange_reference", *check.lagrange_reference);
    if (check.paper) json.value("paper", *check.paper);
    if (!check.source.empty()) json.value("source", check.source);
    json.value("applies", check.applies);
    if (!check.applies) json.value("not_applicable", check.not_applicable);
    json.value("pass", check.pass()).value("note", check.note).endObject();
  }
  json.endObject();
  json.beginObject("config");
  for (const auto& [key, param] : config.params()) json.value(key, param.value);
  json.endObject();
}

}  // namespace

void writeSummary(const std::string& path, const Simulation& simulation, const RunResult& result) {
  std::ofstream out(path);
  JsonWriter json(out);
  json.beginObject();
  writeRunAndSpeed(json, simulation, result);
  writeConservation(json, simulation, result);
  writeCosts(json, result.costs);
  writeInterfaces(json, simulation, result);
  writeChecksAndKeys(json, simulation.options().config, result);
  json.endObject();
}

}  // namespace lagremap
