#include "summary.hpp"

#include <sstream>

#include "json.hpp"
#include "kernels/hex.hpp"
#include "kokkos_events.hpp"
#include "kokkos_session.hpp"
#include "outputs.hpp"
#include "parallel.hpp"

namespace lagremap {
namespace {

// What a step asked of the device (src/kokkos_events.hpp): on average and
// at most in one step.
void writeStepEvents(JsonWriter& json, const StepEvents& events) {
  const double per_step = events.steps > 0 ? 1.0 / double(events.steps) : 0.0;
  const auto counts = [&](const char* name, const KokkosEventCounts& counts, double scale) {
    json.beginObject(name)
        .value("launches", double(counts.launches) * scale)
        .value("deep_copies", double(counts.deep_copies) * scale)
        .value("copied_bytes", double(counts.copied_bytes) * scale)
        .value("host_syncs", double(counts.host_syncs) * scale)
        .endObject();
  };
  json.beginObject("device_events").value("counted", kokkosEventsCounted());
  counts("per_step", events.total, per_step);
  counts("most_in_a_step", events.most, 1.0);
  json.value("note",
             "Kokkos kernel launches, deep copies and host synchronisations (a fence or copy "
             "with device work outstanding) of the time loop's steps, outputs aside; counted "
             "false: another Kokkos tool took the callbacks")
      .endObject();
}

void writeRunAndSpeed(JsonWriter& json, const Simulation& simulation, const RunResult& result) {
  const Config& config = simulation.options().config;
  const Mesh& mesh = simulation.mesh();
  json.value("problem", simulation.options().problem)
      .value("mode", simulation.options().mode)
      .value("setup", config.remapSetup() ? "remap" : "lagrange")
      .value("order", simulation.numerics().order)
      .value("gather", config.text("numerics.gather"))
      .value("kernels", simulation.numerics().kernels == KernelForm::Staged ? "staged" : "fused")
      .value("threads", executionSpaceIsHost() ? long(ExecSpace().concurrency()) : 0L)
      .value("concurrency", long(ExecSpace().concurrency()))
      .value("execution_space", ExecSpace::name())
      .value("cells", mesh.n_global_cells)
      .value("nodes", mesh.n_global_nodes)
      .value("ranks", long(parallel::size()))
      .value("steps", result.steps)
      .value("t_end", simulation.tEnd())
      .value("t_final", result.time)
      .value("status", result.stopped_by ? "stopped"
                       : result.failed   ? "failed"
                                         : "completed");
  if (result.failed) json.value("failure", result.failure);
  json.value("wall_seconds", result.wall_seconds);
  writeStepEvents(json, simulation.stepEvents());
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
  spread("peak_own_bytes", costs.peak_own_bytes);
  spread("setup_peak_bytes", costs.setup_peak_bytes);
  spread("owned_cells", costs.owned_cells);
  spread("peak_bytes_per_owned_cell", costs.peak_bytes_per_owned_cell);
  json.value("note",
             "per rank: peak resident set of the process (getrusage), of the whole run and at the "
             "end of set-up; peak_own_bytes: the whole run's less the pages of shared libraries "
             "and shared memory resident at its end, which the ranks of a machine share; min, "
             "mean and max over the ranks")
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
  json.beginObject("mesh_quality")
      .value("min_scaled_jacobian", simulation.meshQuality())
      .value("lowest_min_scaled_jacobian", simulation.loopState().lowest_mesh_quality)
      .value("note",
             "smallest corner scaled Jacobian of the cells (1: right angles, <= 0: a flat or "
             "inverted corner): of the final mesh, and the lowest of any step")
      .endObject();
}

void writeInterfaces(JsonWriter& json, const Simulation& simulation, const RunResult& result) {
  const int n_materials = int(result.interfaces.size());
  if (n_materials <= 1) return;
  json.beginObject("interfaces");
  for (int k = 0; k < n_materials; ++k) {
    const InterfaceMeasure& measure = result.interfaces[std::size_t(k)];
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

// Remap runs: each material's mixed cells (src/mixed_cells.hpp).
void writeMixedCells(JsonWriter& json, const RunResult& result) {
  if (!result.mixed_cells) return;
  const MixedCellReport& report = *result.mixed_cells;
  json.beginObject("mixed_cells");
  for (const MaterialMixedCells& m : report.materials) {
    json.beginObject("material_" + std::to_string(m.material))
        .value("condensed", m.condensed)
        .value("mixed_cells", m.mixed_cells)
        .value("pure_cells", m.pure_cells)
        .value("stretched", m.stretched)
        .value("expanded", m.expanded)
        .value("pressure_outliers", m.pressure_outliers)
        .value("in_balance", m.in_balance)
        .value("material_pressure_min", m.p_mixed_lo)
        .value("material_pressure_max", m.p_mixed_hi)
        .value("pure_pressure_min", m.p_pure_lo)
        .value("pure_pressure_max", m.p_pure_hi)
        .value("pure_density_median", m.rho_pure_median)
        .endObject();
  }
  json.value("pure_pressure_min_all_materials", report.p_pure_all_lo)
      .value("pure_pressure_max_all_materials", report.p_pure_all_hi)
      .value("impure_cells", report.impure_cells)
      .value("mixture_pressure_outliers", report.mixture_pressure_outliers)
      .value("mixture_in_balance", report.mixture_in_balance)
      .value("note",
             "mixed: 0.01 <= alpha <= 0.99, pure: alpha > 0.999; stretched (fails the check): "
             "material density below 0.98 of its pure cells' median, material pressure below "
             "both its pure cells' lowest and 0, and a normal stress across its interface above "
             "its cell's other materials' by more than M; expanded (reported, not failed): that "
             "density at a higher pressure; pressure outlier (fails): material pressure outside "
             "[min(lo, 0) - M, hi + M], lo .. hi the pressures of every material's pure cells "
             "(pure_pressure_min_all_materials .. max), M = max(|lo|, |hi|), and its normal "
             "stress across its interface more than M from its cell's other materials'; "
             "in_balance (reported, not failed): in tension or outside that range by its pressure "
             "but in balance across its interface (a body's own stress); mixture: cells pure "
             "in no material with p outside the pure cells' mixture range widened by M/2 and a "
             "material out of balance by more than M (mixture_in_balance: outside but in "
             "balance) "
             "(docs/method.md 4.9)")
      .endObject();
}

// Problems with an exact solution: the L1 norms of the final state's errors
// (src/problem.hpp L1Errors), which scripts/convergence.py reads.
void writeL1Errors(JsonWriter& json, const RunResult& result) {
  if (!result.l1_errors) return;
  const L1Errors& errors = *result.l1_errors;
  json.beginObject("l1_errors")
      .value("density", errors.density)
      .value("velocity", errors.velocity)
      .value("pressure", errors.pressure)
      .value("note", errors.note)
      .endObject();
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
  std::ostringstream out;
  JsonWriter json(out);
  json.beginObject();
  writeRunAndSpeed(json, simulation, result);
  writeConservation(json, simulation, result);
  writeCosts(json, result.costs);
  writeInterfaces(json, simulation, result);
  writeMixedCells(json, result);
  writeL1Errors(json, result);
  writeChecksAndKeys(json, simulation.options().config, result);
  json.endObject();
  writeTextFile(path, out.str());
}

}  // namespace lagremap
