#include "checkpoint.hpp"

#include <filesystem>
#include <stdexcept>

#include "fields.hpp"
#include "io/hdf5_rows.hpp"
#include "parallel.hpp"

namespace lagremap {
namespace {

using io::check;
using io::Handle;

constexpr const char* kFormat = "lagremap checkpoint 1";

// Local ids and global rows of the owned (or of all) cells or nodes of this rank.
struct Rows {
  IndexView ids;
  std::vector<std::int64_t> global;
  io::RowSelection selection(long n_global) const {
    return {n_global, std::int64_t(global.size()), global.data()};
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
  }
  Kokkos::View<Index*, HostSpace> host("lagremap::checkpoint::rows", ids.size());
  for (std::size_t i = 0; i < ids.size(); ++i) host(i) = ids[i];
  rows.ids = IndexView("lagremap::checkpoint::rows", ids.size());
  Kokkos::deep_copy(rows.ids, host);
  return rows;
}

void writeField(hid_t group, const FieldRef& field, const Rows& rows, long n_global, hid_t dxpl,
                const std::string& file) {
  const std::size_t n = rows.global.size() * std::size_t(field.components);
  RealView buffer("lagremap::checkpoint::buffer", n);
  field.pack(rows.ids, buffer, 0);
  Kokkos::fence();
  auto host = Kokkos::create_mirror_view_and_copy(HostSpace(), buffer);
  io::writeRows(group, field.name, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, rows.selection(n_global),
                field.components == 1 ? 0 : field.components, host.data(), dxpl, file);
}

void readField(hid_t group, const FieldRef& field, const Rows& rows, long n_global, hid_t dxpl,
               const std::string& file) {
  const std::size_t n = rows.global.size() * std::size_t(field.components);
  Kokkos::View<Real*, HostSpace> host("lagremap::checkpoint::buffer", n);
  io::readRows(group, field.name, H5T_NATIVE_DOUBLE, rows.selection(n_global),
               field.components == 1 ? 0 : field.components, host.data(), dxpl, file);
  RealView buffer("lagremap::checkpoint::buffer", n);
  Kokkos::deep_copy(buffer, host);
  field.unpack(rows.ids, buffer, 0);
  Kokkos::fence();
}

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

// A small table every rank holds the same copy of (the probe's history):
// written from rank 0, read by all.
void writeTable(hid_t file, const char* name, const std::vector<double>& values, int cols,
                hid_t dxpl, const std::string& path) {
  const std::int64_t rows = std::int64_t(values.size()) / cols;
  const io::RowSelection selection{rows, parallel::isRoot() ? rows : 0, nullptr};
  io::writeRows(file, name, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, selection, cols == 1 ? 0 : cols,
                values.data(), dxpl, path);
}

std::vector<double> readTable(hid_t file, const char* name, int cols, hid_t dxpl,
                              const std::string& path) {
  if (H5Lexists(file, name, H5P_DEFAULT) <= 0) {
    throw std::runtime_error("checkpoint '" + path + "' has no " + name);
  }
  Handle dataset(check(H5Dopen2(file, name, H5P_DEFAULT), "open table", path), H5Dclose);
  Handle space(check(H5Dget_space(dataset.get()), "H5Dget_space", path), H5Sclose);
  hsize_t dims[2] = {0, 0};
  H5Sget_simple_extent_dims(space.get(), dims, nullptr);
  std::vector<double> values(std::size_t(dims[0]) * std::size_t(cols));
  const io::RowSelection selection{std::int64_t(dims[0]), std::int64_t(dims[0]), nullptr};
  io::readRows(file, name, H5T_NATIVE_DOUBLE, selection, cols == 1 ? 0 : cols, values.data(), dxpl,
               path);
  return values;
}

Handle group(hid_t file, const char* name, bool create, const std::string& path) {
  const hid_t id = create ? H5Gcreate2(file, name, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT)
                          : H5Gopen2(file, name, H5P_DEFAULT);
  return Handle(
      check(id, (std::string(create ? "create" : "open") + " group " + name).c_str(), path),
      H5Gclose);
}

}  // namespace

void writeCheckpoint(const std::string& path, const Mesh& mesh, const State& state,
                     const LoopState& loop_in) {
  const std::string temp = path + ".tmp";
  const Rows cells = makeRows(mesh.cell_owned, mesh.cell_global, true);
  const Rows nodes = makeRows(mesh.node_owned, mesh.node_global, true);
  {
    io::QuietHdf5Errors quiet;
    Handle fapl(io::fileAccess(temp), H5Pclose);
    Handle dxpl(io::transfer(temp), H5Pclose);
    Handle file(check(H5Fcreate(temp.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, fapl.get()),
                      "create checkpoint", temp),
                H5Fclose);
    LoopState loop = loop_in;
    double step = double(loop.step);
    io::writeTextAttribute(file.get(), "format", kFormat, temp);
    io::writeTextAttribute(file.get(), "problem", loop.problem, temp);
    io::writeTextAttribute(file.get(), "mode", loop.mode, temp);
    io::writeScalarAttribute(file.get(), "cells", double(mesh.n_global_cells), temp);
    io::writeScalarAttribute(file.get(), "nodes", double(mesh.n_global_nodes), temp);
    io::writeScalarAttribute(file.get(), "materials", double(state.n_materials), temp);
    visitNumbers(loop, step, [&](const char* name, double& value) {
      io::writeScalarAttribute(file.get(), name, value, temp);
    });
    io::writeScalarAttribute(file.get(), "dt_stable_max", loop.dt_stable_max, temp);
    {
      Handle cell_group = group(file.get(), "cells", true, temp);
      for (const FieldRef& field : evolvedCellFields(state)) {
        writeField(cell_group.get(), field, cells, mesh.n_global_cells, dxpl.get(), temp);
      }
    }
    {
      Handle node_group = group(file.get(), "nodes", true, temp);
      writeField(node_group.get(), fieldRef("x_n", mesh.x_n), nodes, mesh.n_global_nodes,
                 dxpl.get(), temp);
    }
    std::vector<double> probe;
    for (const auto& [t, value] : loop.probe) probe.insert(probe.end(), {t, value});
    writeTable(file.get(), "probe", probe, 2, dxpl.get(), temp);
    writeTable(file.get(), "snapshot_times", loop.snapshot_times, 1, dxpl.get(), temp);
    if (file.close() < 0) io::failHdf5("close checkpoint", temp);
  }
  parallel::barrier();  // every rank's part is on disk before the old file goes
  std::string error;
  if (parallel::isRoot()) {
    std::error_code code;
    std::filesystem::rename(temp, path, code);
    if (code) error = "cannot rename '" + temp + "' to '" + path + "': " + code.message();
  }
  error = parallel::firstMessage(error);
  if (!error.empty()) throw std::runtime_error(error);
}

LoopState readCheckpoint(const std::string& path, Mesh& mesh, State& state,
                         const std::string& problem, const std::string& mode) {
  if (!std::filesystem::is_regular_file(path)) {
    throw std::runtime_error("checkpoint '" + path + "' does not exist");
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
  if (io::readTextAttribute(file.get(), "format", path) != kFormat) {
    throw std::runtime_error("'" + path + "' is not a lagremap checkpoint");
  }
  LoopState loop;
  loop.problem = io::readTextAttribute(file.get(), "problem", path);
  loop.mode = io::readTextAttribute(file.get(), "mode", path);
  if (loop.problem != problem || loop.mode != mode) {
    throw std::runtime_error("checkpoint '" + path + "' is of " + loop.problem + " (" + loop.mode +
                             "), not " + problem + " (" + mode + ")");
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
  // (checkpoints before 2026-12-02 have none: the restart's own stable dt
  // starts the record)
  loop.dt_stable_max = H5Aexists(file.get(), "dt_stable_max") > 0
                           ? io::readScalarAttribute(file.get(), "dt_stable_max", path)
                           : 0.0;
  loop.step = long(step);
  if (!(loop.time >= 0.0) || loop.step < 0 || !(loop.dt_prev >= 0.0)) {
    throw std::runtime_error("checkpoint '" + path + "' has an impossible time or step");
  }
  // This rank's cells and nodes, ghosts included: no exchange needed after.
  const Rows cells = makeRows(mesh.cell_owned, mesh.cell_global, false);
  const Rows nodes = makeRows(mesh.node_owned, mesh.node_global, false);
  {
    Handle cell_group = group(file.get(), "cells", false, path);
    for (const FieldRef& field : evolvedCellFields(state)) {
      readField(cell_group.get(), field, cells, mesh.n_global_cells, dxpl.get(), path);
    }
  }
  {
    Handle node_group = group(file.get(), "nodes", false, path);
    readField(node_group.get(), fieldRef("x_n", mesh.x_n), nodes, mesh.n_global_nodes, dxpl.get(),
              path);
  }
  const std::vector<double> probe = readTable(file.get(), "probe", 2, dxpl.get(), path);
  for (std::size_t i = 0; i + 1 < probe.size(); i += 2)
    loop.probe.emplace_back(probe[i], probe[i + 1]);
  loop.snapshot_times = readTable(file.get(), "snapshot_times", 1, dxpl.get(), path);
  return loop;
}

}  // namespace lagremap
