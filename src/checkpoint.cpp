#include "checkpoint.hpp"

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <map>
#include <set>
#include <sstream>
#include <stdexcept>

#include "fields.hpp"
#include "input/config.hpp"
#include "io/checksum.hpp"
#include "io/hdf5_rows.hpp"
#include "parallel.hpp"

namespace lagremap {
namespace {

using io::check;
using io::Handle;

// Format 2 carries checksums; format 1's files (written without them) are
// still read. A checksum present is verified whatever the format attribute
// says: editing that attribute does not turn verification off.
constexpr const char* kFormat = "lagremap checkpoint 2";
constexpr const char* kFormatWithoutChecksums = "lagremap checkpoint 1";
// Attribute of each dataset (io::RowsChecksum of its rows) and of the root
// (io::attributesHash of the root's other attributes: the loop's numbers).
constexpr const char* kChecksum = "checksum";

// Local ids and global rows of the owned (or of all) cells or nodes of this
// rank, and which of them it owns.
struct Rows {
  IndexView ids;
  std::vector<std::int64_t> global;
  std::vector<char> owned;
  io::RowSelection selection(long n_global) const {
    return {n_global, std::int64_t(global.size()), global.data()};
  }
  // This rank's part of the checksum of rows of `components` values: its
  // owned rows, so that each row counts once over the ranks.
  std::uint64_t checksum(const double* values, int components) const {
    io::RowsChecksum sum;
    for (std::size_t i = 0; i < global.size(); ++i) {
      if (owned[i]) sum.add(global[i], values + i * components, components);
    }
    return sum.value();
  }
};

Rows makeRows(const DeviceView<int*>& owned_flags, const Kokkos::View<long*, HostSpace>& global_ids,
              bool owned_only) {
  const auto owned = Kokkos::create_mirror_view_and_copy(HostSpace(), owned_flags);
  std::vector<Index> ids;
  Rows rows;
  for (std::size_t e = 0; e < owned.extent(0); ++e) {
    if (owned_only && !owned(e)) continue;
    ids.push_back(Index(e));
    rows.global.push_back(global_ids(e));
    rows.owned.push_back(owned(e) != 0);
  }
  Kokkos::View<Index*, HostSpace> host("lagremap::checkpoint::rows", ids.size());
  for (std::size_t i = 0; i < ids.size(); ++i) host(i) = ids[i];
  rows.ids = IndexView("lagremap::checkpoint::rows", ids.size());
  Kokkos::deep_copy(rows.ids, host);
  return rows;
}

std::string numberText(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.6g", value);
  return text;
}

// Writes the checksum of a dataset's rows, the same on every rank (collective).
void writeChecksum(hid_t loc, const std::string& name, std::uint64_t checksum,
                   const std::string& file) {
  Handle dataset(check(H5Dopen2(loc, name.c_str(), H5P_DEFAULT), "open dataset", file), H5Dclose);
  io::writeWordAttribute(dataset.get(), kChecksum, checksum, file);
}

// Which checksums a checkpoint's reader verifies: every one (format 2, where
// a missing checksum is a corruption), or those present (format 1).
enum class Checksums { kRequired, kWherePresent };

// Throws unless dataset `name` (`shown` in the message) holds `checksum`
// (or, kWherePresent, holds none).
void verifyChecksum(hid_t loc, const std::string& name, const std::string& shown,
                    std::uint64_t checksum, Checksums checksums, const std::string& file) {
  Handle dataset(check(H5Dopen2(loc, name.c_str(), H5P_DEFAULT), "open dataset", file), H5Dclose);
  const bool present = H5Aexists(dataset.get(), kChecksum) > 0;
  if (!present && checksums == Checksums::kWherePresent) return;
  if (!present || io::readWordAttribute(dataset.get(), kChecksum, file) != checksum) {
    throw std::runtime_error("checkpoint '" + file + "' is corrupted: dataset " + shown +
                             " does not match its checksum");
  }
}

// Writes this rank's owned rows of a field, and the checksum of every rank's.
void writeField(hid_t group, const FieldRef& field, const Rows& rows, long n_global, hid_t dxpl,
                const std::string& file) {
  const std::size_t n = rows.global.size() * std::size_t(field.components);
  RealView buffer("lagremap::checkpoint::buffer", n);
  field.pack(rows.ids, buffer, 0);
  Kokkos::fence();
  auto host = Kokkos::create_mirror_view_and_copy(HostSpace(), buffer);
  io::writeRows(group, field.name, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, rows.selection(n_global),
                field.components == 1 ? 0 : field.components, host.data(), dxpl, file);
  std::uint64_t checksum = rows.checksum(host.data(), field.components);
  parallel::sum(&checksum, 1);
  writeChecksum(group, field.name, checksum, file);
}

// What a field's values must be besides finite, where a state that breaks it
// would not be noticed when the run starts: a negative mass gives a negative
// density, of which an ideal gas's sound speed, gamma (gamma - 1) e, knows
// nothing. (Volumes follow from the node positions: the restart's geometry
// kernel checks them.)
struct ValueRule {
  const char* field;
  bool (*holds)(double);
  const char* rule;
};
constexpr ValueRule kValueRules[] = {
    {"m_c", [](double m) { return m > 0.0; }, "masses must be positive"},
    {"m_ck", [](double m) { return m >= 0.0; }, "material masses must not be negative"},
    {"alpha_ck", [](double a) { return a >= 0.0 && a <= 1.0; },
     "volume fractions must lie in [0, 1]"},
    {"eps_ck", [](double eps) { return eps >= 0.0; }, "plastic strains must not be negative"},
};

// Reads this rank's rows (ghosts included) of the checkpoint's fields. Each
// is checked against its checksum, summed over the ranks: every rank reaches
// the same verdict and throws alike. Each value is checked against its
// field's rule: a rank finds the breaks in its own rows only, so the first
// is kept (brokenRule) until every rank has taken part in every read.
class FieldReader {
 public:
  FieldReader(const std::string& path, hid_t dxpl, Checksums checksums)
      : path_(path), dxpl_(dxpl), checksums_(checksums) {}

  void read(hid_t group, const char* group_name, const char* entity, const FieldRef& field,
            const Rows& rows, long n_global) {
    const std::size_t n = rows.global.size() * std::size_t(field.components);
    Kokkos::View<Real*, HostSpace> host("lagremap::checkpoint::buffer", n);
    io::readRows(group, field.name, H5T_NATIVE_DOUBLE, rows.selection(n_global),
                 field.components == 1 ? 0 : field.components, host.data(), dxpl_, path_);
    const std::string shown = std::string(group_name) + "/" + field.name;
    std::uint64_t checksum = rows.checksum(host.data(), field.components);
    parallel::sum(&checksum, 1);
    verifyChecksum(group, field.name, shown, checksum, checksums_, path_);
    if (broken_.empty()) findBrokenRule(shown, entity, field, rows, host.data());
    RealView buffer("lagremap::checkpoint::buffer", n);
    Kokkos::deep_copy(buffer, host);
    field.unpack(rows.ids, buffer, 0);
    Kokkos::fence();
  }

  // A table of `cols` columns every rank reads whole (see writeTable).
  std::vector<double> readTable(hid_t file, const char* name, int cols) {
    if (H5Lexists(file, name, H5P_DEFAULT) <= 0) {
      throw std::runtime_error("checkpoint '" + path_ + "' has no " + name);
    }
    Handle dataset(check(H5Dopen2(file, name, H5P_DEFAULT), "open table", path_), H5Dclose);
    Handle space(check(H5Dget_space(dataset.get()), "H5Dget_space", path_), H5Sclose);
    hsize_t dims[2] = {0, 0};
    H5Sget_simple_extent_dims(space.get(), dims, nullptr);
    std::vector<double> values(std::size_t(dims[0]) * std::size_t(cols));
    const io::RowSelection selection{std::int64_t(dims[0]), std::int64_t(dims[0]), nullptr};
    io::readRows(file, name, H5T_NATIVE_DOUBLE, selection, cols == 1 ? 0 : cols, values.data(),
                 dxpl_, path_);
    verifyChecksum(file, name, name, tableChecksum(values, cols), checksums_, path_);
    return values;
  }

  // The first value this rank read that breaks its field's rule, as an
  // error message ("" if none).
  const std::string& brokenRule() const { return broken_; }

  static std::uint64_t tableChecksum(const std::vector<double>& values, int cols) {
    io::RowsChecksum sum;
    for (std::size_t row = 0; row * cols < values.size(); ++row) {
      sum.add(std::int64_t(row), values.data() + row * cols, cols);
    }
    return sum.value();
  }

 private:
  void findBrokenRule(const std::string& shown, const char* entity, const FieldRef& field,
                      const Rows& rows, const double* values) {
    const ValueRule* rule = nullptr;
    for (const ValueRule& candidate : kValueRules) {
      if (field.name == candidate.field) rule = &candidate;
    }
    const int components = field.components;
    for (std::size_t i = 0; i < rows.global.size() * components; ++i) {
      const bool finite = std::isfinite(values[i]);
      if (finite && (rule == nullptr || rule->holds(values[i]))) continue;
      const std::string component =
          components > 1 ? "[" + std::to_string(i % components) + "]" : "";
      broken_ = "checkpoint '" + path_ + "': " + shown + component + " is " +
                numberText(values[i]) + " at " + entity + " " +
                std::to_string(rows.global[i / components]) + " (" +
                (finite ? rule->rule : "values must be finite") + ")";
      return;
    }
  }

  std::string path_;
  hid_t dxpl_;
  Checksums checksums_;
  std::string broken_;
};

// The loop's numbers as root attributes, in one table both directions use.
template <class Visit>
void visitNumbers(LoopState& loop, double& step, Visit visit) {
  visit("time", loop.time);
  visit("dt_prev", loop.dt_prev);
  visit("step", step);
  visit("impulse_x", loop.impulse.x);
  visit("impulse_y", loop.impulse.y);
  visit("impulse_z", loop.impulse.z);
  visit("boundary_work", loop.work);
  visit("mass_in", loop.mass_in);
  visit("initial_mass", loop.initial.mass);
  visit("initial_momentum_x", loop.initial.momentum.x);
  visit("initial_momentum_y", loop.initial.momentum.y);
  visit("initial_momentum_z", loop.initial.momentum.z);
  visit("initial_kinetic_energy", loop.initial.kinetic);
  visit("initial_internal_energy", loop.initial.internal);
}

// Why the loop cannot continue from these numbers ("" if it can). A last dt
// of 0 after a step would pass the start and stop the run many steps later
// (the growth limit multiplies it).
std::string impossibleNumbers(LoopState loop, double step) {
  std::string error;
  auto is = [](const char* name, double value) {
    return std::string(name) + " = " + numberText(value);
  };
  visitNumbers(loop, step, [&](const char* name, double& value) {
    if (error.empty() && !std::isfinite(value)) error = is(name, value);
  });
  if (!error.empty()) return error;
  if (!(std::isfinite(loop.dt_stable_max) && loop.dt_stable_max >= 0.0)) {
    return is("dt_stable_max", loop.dt_stable_max);
  }
  if (!(loop.lowest_mesh_quality >= -1.0 && loop.lowest_mesh_quality <= 1.0)) {
    return is("lowest_mesh_quality", loop.lowest_mesh_quality);
  }
  if (!(step >= 0.0 && step == std::floor(step))) return is("step", step);
  if (!(loop.time >= 0.0)) return is("time", loop.time);
  if (!(loop.initial.mass > 0.0)) return is("initial_mass", loop.initial.mass);
  if (!(loop.dt_prev >= 0.0) || (step > 0.0 && loop.dt_prev == 0.0)) {
    return is("dt_prev", loop.dt_prev) + " at step " + numberText(step);
  }
  return "";
}

// A root attribute a checkpoint of an older format may lack (`fallback` then).
double optionalScalar(hid_t file, const char* name, double fallback, const std::string& path) {
  return H5Aexists(file, name) > 0 ? io::readScalarAttribute(file, name, path) : fallback;
}

// A small table every rank holds the same copy of (the probe's history):
// written from rank 0, read by all; every rank computes its checksum.
void writeTable(hid_t file, const char* name, const std::vector<double>& values, int cols,
                hid_t dxpl, const std::string& path) {
  const std::int64_t rows = std::int64_t(values.size()) / cols;
  const io::RowSelection selection{rows, parallel::isRoot() ? rows : 0, nullptr};
  io::writeRows(file, name, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, selection, cols == 1 ? 0 : cols,
                values.data(), dxpl, path);
  writeChecksum(file, name, FieldReader::tableChecksum(values, cols), path);
}

Handle group(hid_t file, const char* name, bool create, const std::string& path) {
  const hid_t id = create ? H5Gcreate2(file, name, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT)
                          : H5Gopen2(file, name, H5P_DEFAULT);
  return Handle(
      check(id, (std::string(create ? "create" : "open") + " group " + name).c_str(), path),
      H5Gclose);
}

// The "key=value" lines of `text`, by key.
std::map<std::string, std::string> keyValues(const std::string& text) {
  std::map<std::string, std::string> values;
  std::istringstream lines(text);
  for (std::string line; std::getline(lines, line);) {
    const auto equals = line.find('=');
    if (equals != std::string::npos) values[line.substr(0, equals)] = line.substr(equals + 1);
  }
  return values;
}

// "was written with key=a; this run has key=b" for the first key (in order)
// whose value differs between the checkpoint's keys and the run's, "" if none.
std::string firstChangedKey(const std::string& written, const std::string& run) {
  const auto before = keyValues(written);
  const auto now = keyValues(run);
  std::set<std::string> keys;
  for (const auto& entry : before) keys.insert(entry.first);
  for (const auto& entry : now) keys.insert(entry.first);
  const auto shown = [](const std::map<std::string, std::string>& values, const std::string& key) {
    const auto it = values.find(key);
    return it == values.end() ? "no " + key : key + "=" + abbreviated(it->second);
  };
  for (const std::string& key : keys) {
    if (before.count(key) && now.count(key) && before.at(key) == now.at(key)) continue;
    return "was written with " + shown(before, key) + "; this run has " + shown(now, key) +
           " (a restart may change only t_end, numerics.* and check.*)";
  }
  return "";
}

// Writes the whole checkpoint file (collective); throws on an I/O failure,
// every handle closed and the file removed.
void writeFile(const std::string& path, const Mesh& mesh, const State& state,
               const LoopState& loop_in) {
  const Rows cells = makeRows(mesh.cell_owned, mesh.cell_global, true);
  const Rows nodes = makeRows(mesh.node_owned, mesh.node_global, true);
  io::QuietHdf5Errors quiet;
  Handle fapl(io::fileAccess(path), H5Pclose);
  Handle dxpl(io::transfer(path), H5Pclose);
  io::OutputFile file(path, fapl.get());
  LoopState loop = loop_in;
  double step = double(loop.step);
  io::writeTextAttribute(file.get(), "format", kFormat, path);
  io::writeTextAttribute(file.get(), "problem", loop.problem, path);
  io::writeTextAttribute(file.get(), "mode", loop.mode, path);
  io::writeTextAttribute(file.get(), "keys", loop.keys, path);
  io::writeScalarAttribute(file.get(), "cells", double(mesh.n_global_cells), path);
  io::writeScalarAttribute(file.get(), "nodes", double(mesh.n_global_nodes), path);
  io::writeScalarAttribute(file.get(), "materials", double(state.n_materials), path);
  visitNumbers(loop, step, [&](const char* name, double& value) {
    io::writeScalarAttribute(file.get(), name, value, path);
  });
  io::writeScalarAttribute(file.get(), "dt_stable_max", loop.dt_stable_max, path);
  io::writeScalarAttribute(file.get(), "lowest_mesh_quality", loop.lowest_mesh_quality, path);
  io::writeWordAttribute(file.get(), kChecksum, io::attributesHash(file.get(), kChecksum, path),
                         path);
  {
    Handle cell_group = group(file.get(), "cells", true, path);
    for (const FieldRef& field : evolvedCellFields(state)) {
      writeField(cell_group.get(), field, cells, mesh.n_global_cells, dxpl.get(), path);
    }
  }
  {
    Handle node_group = group(file.get(), "nodes", true, path);
    writeField(node_group.get(), fieldRef("x_n", mesh.x_n), nodes, mesh.n_global_nodes, dxpl.get(),
               path);
  }
  std::vector<double> probe;
  for (const auto& [t, value] : loop.probe) probe.insert(probe.end(), {t, value});
  writeTable(file.get(), "probe", probe, 2, dxpl.get(), path);
  writeTable(file.get(), "snapshot_times", loop.snapshot_times, 1, dxpl.get(), path);
  file.close();
}

}  // namespace

void writeCheckpoint(const std::string& path, const Mesh& mesh, const State& state,
                     const LoopState& loop) {
  const std::string temp = path + ".tmp";
  std::string error;
  try {
    writeFile(temp, mesh, state, loop);
  } catch (const std::exception& failure) {
    error = failure.what();
  }
  // Every rank's part is on disk, or some rank failed, before the old file
  // goes. A failed file goes instead: on a full disk, its space comes back.
  error = parallel::firstMessage(error);
  if (parallel::isRoot()) {
    std::error_code code;
    if (error.empty()) {
      std::filesystem::rename(temp, path, code);
      if (code) error = "cannot rename '" + temp + "' to '" + path + "': " + code.message();
    } else {
      std::filesystem::remove(temp, code);
    }
  }
  error = parallel::firstMessage(error);
  if (!error.empty()) throw parallel::AgreedError(error);
}

LoopState readCheckpoint(const std::string& path, Mesh& mesh, State& state,
                         const std::string& problem, const std::string& mode,
                         const std::string& keys) {
  std::error_code error;
  const auto status = std::filesystem::status(path, error);
  if (std::filesystem::is_directory(status)) {
    throw std::runtime_error("checkpoint '" + path + "' is a directory, not a checkpoint file");
  }
  if (!std::filesystem::is_regular_file(status)) {
    // (a name too long, a directory above it that cannot be read: the reason)
    const bool missing = !error || error == std::errc::no_such_file_or_directory;
    throw std::runtime_error("checkpoint '" + path + "' " +
                             (missing ? "does not exist" : "cannot be read: " + error.message()));
  }
  io::QuietHdf5Errors quiet;
  Handle fapl(io::fileAccess(path), H5Pclose);
  Handle dxpl(io::transfer(path), H5Pclose);
  const hid_t id = H5Fopen(path.c_str(), H5F_ACC_RDONLY, fapl.get());
  if (id < 0) {
    throw std::runtime_error(
        "checkpoint '" + path +
        "' is not a readable HDF5 file (truncated or corrupted?): " + io::hdf5ErrorDetail());
  }
  Handle file(id, H5Fclose);
  const std::string format = io::readTextAttribute(file.get(), "format", path);
  if (format != kFormat && format != kFormatWithoutChecksums) {
    throw std::runtime_error("'" + path + "' is not a lagremap checkpoint");
  }
  const Checksums checksums = format == kFormat ? Checksums::kRequired : Checksums::kWherePresent;
  const bool root_checksum =
      checksums == Checksums::kRequired || H5Aexists(file.get(), kChecksum) > 0;
  if (root_checksum && io::readWordAttribute(file.get(), kChecksum, path) !=
                           io::attributesHash(file.get(), kChecksum, path)) {
    throw std::runtime_error("checkpoint '" + path +
                             "' is corrupted: its attributes (the loop's numbers) do not match "
                             "their checksum");
  }
  LoopState loop;
  loop.problem = io::readTextAttribute(file.get(), "problem", path);
  loop.mode = io::readTextAttribute(file.get(), "mode", path);
  if (loop.problem != problem || loop.mode != mode) {
    throw std::runtime_error("checkpoint '" + path + "' is of " + loop.problem + " (" + loop.mode +
                             "), not " + problem + " (" + mode + ")");
  }
  if (H5Aexists(file.get(), "keys") > 0) {
    loop.keys = io::readTextAttribute(file.get(), "keys", path);
    const std::string changed = firstChangedKey(loop.keys, keys);
    if (!keys.empty() && !changed.empty()) {
      throw std::runtime_error("checkpoint '" + path + "' " + changed);
    }
  }
  const double cells_in_file = io::readScalarAttribute(file.get(), "cells", path);
  const double nodes_in_file = io::readScalarAttribute(file.get(), "nodes", path);
  const double materials_in_file = io::readScalarAttribute(file.get(), "materials", path);
  if (cells_in_file != double(mesh.n_global_cells) ||
      nodes_in_file != double(mesh.n_global_nodes) ||
      materials_in_file != double(state.n_materials)) {
    throw std::runtime_error(
        "checkpoint '" + path + "' holds " + std::to_string(long(cells_in_file)) + " cells and " +
        std::to_string(long(materials_in_file)) + " materials; this run has " +
        std::to_string(mesh.n_global_cells) + " and " + std::to_string(state.n_materials) +
        " (same mesh keys and --scale needed)");
  }
  double step = 0.0;
  visitNumbers(loop, step, [&](const char* name, double& value) {
    value = io::readScalarAttribute(file.get(), name, path);
  });
  // (older checkpoints have neither: the restart's own stable dt and mesh
  // start the records)
  loop.dt_stable_max = optionalScalar(file.get(), "dt_stable_max", 0.0, path);
  loop.lowest_mesh_quality = optionalScalar(file.get(), "lowest_mesh_quality", 1.0, path);
  const std::string impossible = impossibleNumbers(loop, step);
  if (!impossible.empty()) {
    throw std::runtime_error("checkpoint '" + path + "' holds an impossible " + impossible);
  }
  loop.step = long(step);
  // This rank's cells and nodes, ghosts included: no exchange needed after.
  const Rows cells = makeRows(mesh.cell_owned, mesh.cell_global, false);
  const Rows nodes = makeRows(mesh.node_owned, mesh.node_global, false);
  FieldReader reader(path, dxpl.get(), checksums);
  {
    Handle cell_group = group(file.get(), "cells", false, path);
    for (const FieldRef& field : evolvedCellFields(state)) {
      reader.read(cell_group.get(), "cells", "cell", field, cells, mesh.n_global_cells);
    }
  }
  {
    Handle node_group = group(file.get(), "nodes", false, path);
    reader.read(node_group.get(), "nodes", "node", fieldRef("x_n", mesh.x_n), nodes,
                mesh.n_global_nodes);
  }
  const std::vector<double> probe = reader.readTable(file.get(), "probe", 2);
  for (std::size_t i = 0; i + 1 < probe.size(); i += 2)
    loop.probe.emplace_back(probe[i], probe[i + 1]);
  loop.snapshot_times = reader.readTable(file.get(), "snapshot_times", 1);
  if (!reader.brokenRule().empty()) throw std::runtime_error(reader.brokenRule());
  return loop;
}

}  // namespace lagremap
