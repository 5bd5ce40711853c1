#include "outputs.hpp"

#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <iomanip>
#include <stdexcept>

#include "decomposition.hpp"
#include "kernels/geometry.hpp"
#include "parallel.hpp"

namespace lagremap {

void writeTextFile(const std::string& path, const std::string& text) {
  errno = 0;
  std::FILE* file = std::fopen(path.c_str(), "w");
  if (file == nullptr)
    throw std::runtime_error("cannot write " + path + ": " + std::strerror(errno));
  const bool written = std::fwrite(text.data(), 1, text.size(), file) == text.size();
  const int write_errno = errno;
  const bool flushed = std::fflush(file) == 0;
  const int flush_errno = errno;
  const bool closed = std::fclose(file) == 0;
  if (!(written && flushed && closed)) {
    const int error = !written ? write_errno : !flushed ? flush_errno : errno;
    std::remove(path.c_str());  // no cut file left to be taken for a whole one
    throw std::runtime_error("cannot write " + path + ": " + std::strerror(error ? error : EIO));
  }
}

MatRealView interfaceNormalStresses(const State& state) {
  const State s = state;
  MatRealView sigma("lagremap::final::interface_normal_stress", s.alpha_ck.extent(0),
                    s.alpha_ck.extent(1));
  Kokkos::parallel_for(
      "lagremap::final::interface_normal_stress",
      Kokkos::RangePolicy<ExecSpace>(0, s.alpha_ck.extent(0)), KOKKOS_LAMBDA(const Index c) {
        for (int k = 0; k < s.n_materials; ++k) {
          sigma(c, k) = s.alpha_ck(c, k) > 0.0
                            ? interfaceNormalStress(s, s.alpha_ck, s.p_ck, s.S_ck, c, k)
                            : 0.0;
        }
      });
  return sigma;
}

FinalFields copyFields(const Mesh& mesh, bool global, const State& state, double time) {
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
    // (global node ids below 2^31: the gathered fields are for meshes one rank can hold)
    CellNodesView::HostMirror global_nodes("lagremap::mesh::cell_nodes", mesh.n_cells);
    for (Index c = 0; c < mesh.n_cells; ++c)
      for (int p = 0; p < 8; ++p) {
        global_nodes(c, p) = Index(mesh.node_global(fields.mesh.cell_nodes(c, p)));
      }
    fields.mesh.cell_nodes = gatherGlobal(global_nodes, mesh, true);
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
  if (state.eps_ck.extent(0) > 0) fields.eps_k = cells(state.eps_ck);
  if (state.n_materials > 1) fields.sigma_n_k = cells(interfaceNormalStresses(state));
  return fields;
}

namespace {

// Writes a snapshot of this rank's owned cells and nodes, numbered globally
// (all of them on one rank); `fields` are the rank's host copies (copyFields
// without gathering). Each field is packed into the writer's one buffer when
// its turn comes (io::CellField::fill), so the snapshot costs this rank one
// field of its owned cells, not all of them. Collective over the ranks.
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
  // A field of `components` values per owned cell, value(c, d) of local cell c.
  auto ownedCellField = [&](std::string name, int components, auto value) {
    return io::CellField{std::move(name), nullptr, components,
                         [&cells, components, value](double* out) {
                           for (std::size_t i = 0; i < cells.size(); ++i)
                             for (int d = 0; d < components; ++d)
                               out[components * i + d] = value(cells[i], d);
                         }};
  };
  std::vector<io::CellField> cell_fields = {
      ownedCellField("density", 1, [&](Index c, int) { return fields.rho(c); }),
      ownedCellField("pressure", 1, [&](Index c, int) { return fields.p(c); }),
      ownedCellField("internal_energy", 1, [&](Index c, int) { return fields.e(c); }),
      ownedCellField("volume", 1, [&](Index c, int) { return fields.vol(c); }),
      ownedCellField("velocity", 3, [&](Index c, int d) { return fields.v(c, d); }),
      ownedCellField("deviatoric_stress", 6, [&](Index c, int k) { return fields.S(c, k); })};
  if (fields.eps_k.extent(0) > 0) {
    cell_fields.push_back(ownedCellField(
        "plastic_strain", 1, [&fields](Index c, int) { return fields.plasticStrain(c); }));
  }
  // Multi-material problems: each material's volume fraction, density
  // m^k / (alpha^k v), specific internal energy and pressure (0 where absent).
  const int n_materials = int(fields.alpha.extent(1));
  for (int k = 0; n_materials > 1 && k < n_materials; ++k) {
    auto present = [&fields, k](Index c) { return fields.alpha(c, k) > 0.0; };
    const std::string suffix = "_" + std::to_string(k);
    cell_fields.push_back(ownedCellField(
        "volume_fraction" + suffix, 1, [&fields, k](Index c, int) { return fields.alpha(c, k); }));
    cell_fields.push_back(
        ownedCellField("material_density" + suffix, 1, [&fields, k, present](Index c, int) {
          return present(c) ? fields.m_k(c, k) / (fields.alpha(c, k) * fields.vol(c)) : 0.0;
        }));
    cell_fields.push_back(ownedCellField(
        "material_internal_energy" + suffix, 1,
        [&fields, k, present](Index c, int) { return present(c) ? fields.e_k(c, k) : 0.0; }));
    cell_fields.push_back(ownedCellField(
        "material_pressure" + suffix, 1,
        [&fields, k, present](Index c, int) { return present(c) ? fields.p_k(c, k) : 0.0; }));
  }
  io::SnapshotMesh snapshot_mesh{std::int64_t(nodes.size()), nullptr,
                                 std::int64_t(cells.size()), nullptr,
                                 node_rows.data(),           cell_rows.data(),
                                 mesh.n_global_nodes,        mesh.n_global_cells};
  snapshot_mesh.fill_node_xyz = [&](double* out) {
    for (std::size_t i = 0; i < nodes.size(); ++i)
      for (int d = 0; d < 3; ++d) out[3 * i + d] = fields.mesh.x_n(nodes[i], d);
  };
  snapshot_mesh.fill_cell_nodes = [&](std::int64_t* out) {
    for (std::size_t i = 0; i < cells.size(); ++i)
      for (int p = 0; p < 8; ++p)
        out[8 * i + p] = mesh.node_global(fields.mesh.cell_nodes(cells[i], p));
  };
  series.write(fields.time, snapshot_mesh, cell_fields);
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

HistoryFile::HistoryFile(const RunOptions& options, const Simulation& simulation) {
  if (!options.write_files) return;
  const std::string& dir = options.output_dir;
  std::string error;  // rank 0's, reported by every rank
  if (parallel::isRoot()) {
    std::error_code code;
    std::filesystem::create_directories(dir, code);
    if (code) {
      error = "cannot create output directory '" + dir + "': " + code.message();
    } else {
      path_ = dir + "/history.csv";
      const std::string kept = simulation.restarted() ? historyUpTo(path_, simulation.step()) : "";
      file_.open(path_);
      if (!file_) {
        error = "cannot write '" + path_ + "'";
      } else {
        if (kept.empty()) {
          file_ << "step,t,dt,dt_reason,mass,momentum_x,momentum_y,momentum_z,kinetic_energy,"
                   "internal_energy,total_energy,min_scaled_jacobian\n";
        }
        file_ << kept << std::setprecision(15);
        flush();
        error = error_;
      }
    }
  }
  error = parallel::firstMessage(error);
  if (!error.empty()) throw ConfigError(error);
}

void HistoryFile::start(const Simulation& simulation) {
  if (!simulation.restarted()) {
    writeLine(0, 0.0, 0.0, "initial", simulation.totals(), simulation.meshQuality());
  }
}

void HistoryFile::afterStep(const Simulation& simulation, const TimeStepChoice& choice) {
  writeLine(simulation.step(), simulation.time(), choice.dt, choice.reason, simulation.totals(),
            simulation.meshQuality());
}

void HistoryFile::writeLine(long step, double t, double dt, const char* reason,
                            const Totals& totals, double mesh_quality) {
  if (!file_.is_open()) return;
  file_ << step << ',' << t << ',' << dt << ',' << reason << ',' << totals.mass << ','
        << totals.momentum.x << ',' << totals.momentum.y << ',' << totals.momentum.z << ','
        << totals.kinetic << ',' << totals.internal << ',' << totals.total() << ',' << mesh_quality
        << '\n';
  flush();
}

void HistoryFile::flush() {
  file_.flush();
  if (file_) {
    written_ = file_.tellp();
    return;
  }
  const int code = errno;  // (of the write that failed)
  error_ = "cannot write '" + path_ + "': " + std::strerror(code);
  file_.close();
  std::error_code ignored;
  std::filesystem::resize_file(path_, std::uintmax_t(written_), ignored);
}

void HistoryFile::finish(const Simulation&) {
  const std::string error = parallel::firstMessage(error_);
  if (!error.empty()) throw parallel::AgreedError(error);
}

SnapshotOutput::SnapshotOutput(const RunOptions& options, const Simulation& simulation)
    : series_(options.output_dir, "fields"), every_(options.output_every) {
  series_.resume(simulation.loopState().snapshot_times);
}

void SnapshotOutput::start(const Simulation& simulation) {
  if (!simulation.restarted()) write(simulation);
}

void SnapshotOutput::afterStep(const Simulation& simulation, const TimeStepChoice& choice) {
  const bool periodic =
      every_ > 0 && simulation.step() % every_ == 0 && simulation.time() < simulation.tEnd();
  if (choice.lands_on_output() || periodic) write(simulation);
}

void SnapshotOutput::finish(const Simulation& simulation) {
  write(simulation);
}

void SnapshotOutput::write(const Simulation& simulation) {
  auto scope = simulation.timers().scope(Phase::Output);
  const Mesh& mesh = simulation.mesh();
  writeSnapshot(series_, copyFields(mesh, false, simulation.state(), simulation.time()), mesh);
}

CheckpointOutput::CheckpointOutput(const RunOptions& options, const SnapshotOutput& snapshots)
    : path_(options.output_dir + "/checkpoint.h5"),
      every_(options.checkpoint_every),
      snapshots_(snapshots) {}

void CheckpointOutput::afterStep(const Simulation& simulation, const TimeStepChoice&) {
  if (every_ > 0 && simulation.step() % every_ == 0 && simulation.time() < simulation.tEnd()) {
    write(simulation);
  }
}

void CheckpointOutput::finish(const Simulation& simulation) {
  if (simulation.failed()) write(simulation);
}

void CheckpointOutput::write(const Simulation& simulation) {
  auto scope = simulation.timers().scope(Phase::Output);
  LoopState now = simulation.loopState();
  now.snapshot_times = snapshots_.times();
  writeCheckpoint(path_, simulation.mesh(), simulation.state(), now);
}

void ProgressLine::start(const Simulation&) {
  start_ = last_ = std::chrono::steady_clock::now();
}

void ProgressLine::afterStep(const Simulation& simulation, const TimeStepChoice& choice) {
  if (!parallel::isRoot()) return;
  const auto now = std::chrono::steady_clock::now();
  if (std::chrono::duration<double>(now - last_).count() <= 3.0) return;
  last_ = now;
  const double seconds = std::chrono::duration<double>(now - start_).count();
  const double t = simulation.time(), t_end = simulation.tEnd();
  const double done = t - simulation.startState().time;
  std::fprintf(stderr, "[lagremap] %5.1f%%  step %ld  t %.6g  dt %.3g (%s)  ETA %s\n",
               100.0 * t / t_end, simulation.step(), t, choice.dt, choice.reason,
               formatSeconds(seconds * (t_end - t) / done).c_str());
}

}  // namespace lagremap
