#include "snapshot_writer.hpp"

#include <hdf5.h>

#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <system_error>
#include <utility>

#include "../parallel.hpp"
#include "hdf5_rows.hpp"

namespace lagremap::io {

namespace fs = std::filesystem;

namespace {

constexpr int kNodesPerHex = 8;

std::int64_t globalNodes(const SnapshotMesh& mesh) {
  return mesh.n_global_nodes >= 0 ? mesh.n_global_nodes : mesh.n_nodes;
}
std::int64_t globalCells(const SnapshotMesh& mesh) {
  return mesh.n_global_cells >= 0 ? mesh.n_global_cells : mesh.n_cells;
}

// The connectivity's first node number outside [0, n_global_nodes), as an
// error message ("" if there is none).
std::string connectivityError(const std::int64_t* cell_nodes, std::int64_t n_cells,
                              std::int64_t n_global_nodes) {
  for (std::int64_t i = 0; i < n_cells * kNodesPerHex; ++i) {
    const std::int64_t v = cell_nodes[i];
    if (v < 0 || v >= n_global_nodes)
      return "cell " + std::to_string(i / kNodesPerHex) + " references node " + std::to_string(v) +
             " outside [0, " + std::to_string(n_global_nodes) + ")";
  }
  return "";
}

// `data`, or `fill`'s values in `buffer` (resized to n values).
template <class T>
const T* valuesOf(const T* data, const std::function<void(T*)>& fill, std::size_t n,
                  std::vector<T>& buffer) {
  if (!fill) return data;
  buffer.resize(n);
  fill(buffer.data());
  return buffer.data();
}

// Writes one complete snapshot file; collective over the ranks (each writes
// its own rows of every dataset, rank-count independent file contents). The
// filled arrays pass through one buffer each, one after the other.
void write_snapshot_h5(const std::string& path, double time, const SnapshotMesh& mesh,
                       const std::vector<CellField>& fields) {
  Handle fapl(fileAccess(path), H5Pclose);
  Handle dxpl(transfer(path), H5Pclose);
  OutputFile file(path, fapl.get());
  writeScalarAttribute(file.get(), "time", time, path);
  const RowSelection nodes{globalNodes(mesh), mesh.n_nodes, mesh.node_rows};
  const RowSelection cells{globalCells(mesh), mesh.n_cells, mesh.cell_rows};
  std::vector<double> buffer;
  {
    Handle mesh_group(check(H5Gcreate2(file.get(), "mesh", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
                            "create group /mesh", path),
                      H5Gclose);
    {  // (the connectivity's buffer is freed before the others are filled)
      std::vector<std::int64_t> connectivity;
      const std::int64_t* cell_nodes =
          valuesOf(mesh.cell_nodes, mesh.fill_cell_nodes, kNodesPerHex * std::size_t(mesh.n_cells),
                   connectivity);
      if (mesh.fill_cell_nodes) {  // (given arrays are checked before the file is made)
        const std::string error =
            parallel::firstMessage(connectivityError(cell_nodes, mesh.n_cells, globalNodes(mesh)));
        if (!error.empty())
          throw std::invalid_argument("lagremap::io::SnapshotSeries::write: " + error);
      }
      writeRows(mesh_group.get(), "connectivity", H5T_STD_I64LE, H5T_NATIVE_INT64, cells,
                kNodesPerHex, cell_nodes, dxpl.get(), path);
    }
    writeRows(mesh_group.get(), "coordinates", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, nodes, 3,
              valuesOf(mesh.node_xyz, mesh.fill_node_xyz, 3 * std::size_t(mesh.n_nodes), buffer),
              dxpl.get(), path);
  }
  {
    Handle field_group(
        check(H5Gcreate2(file.get(), "fields", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
              "create group /fields", path),
        H5Gclose);
    for (const CellField& f : fields) {
      writeRows(field_group.get(), f.name, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, cells,
                f.components == 1 ? 0 : f.components,
                valuesOf(f.data, f.fill, std::size_t(mesh.n_cells) * f.components, buffer),
                dxpl.get(), path);
    }
  }
  file.close();
}

// ---------------------------------------------------------------------------------------
// XDMF helpers
// ---------------------------------------------------------------------------------------

std::string xml_escape(const std::string& s) {
  std::string out;
  out.reserve(s.size());
  for (char c : s) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      case '\'':
        out += "&apos;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

// Shortest decimal text that reads back as exactly `v` (locale independent).
std::string format_double(double v) {
  char buf[64];
  const auto res = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, res.ptr);
}

const char* attribute_type(int components) {
  switch (components) {
    case 1:
      return "Scalar";
    case 3:
      return "Vector";
    case 6:
      return "Tensor6";
    case 9:
      return "Tensor";
    default:
      return "Matrix";
  }
}

std::string data_item(const std::string& dims, const char* number_type, const std::string& h5_name,
                      const std::string& dataset) {
  return "<DataItem Dimensions=\"" + dims + "\" NumberType=\"" + number_type +
         "\" Precision=\"8\" Format=\"HDF\">" + xml_escape(h5_name + ":" + dataset) + "</DataItem>";
}

// The light-data <Grid> of one snapshot; every line is prefixed with `indent`.
template <class Entry>
std::string grid_xml(const Entry& e, const std::string& indent) {
  const std::string nc = std::to_string(e.n_cells);
  const std::string nn = std::to_string(e.n_nodes);
  std::ostringstream x;
  x << indent << "<Grid Name=\"mesh\" GridType=\"Uniform\">\n";
  x << indent << "  <Time Value=\"" << format_double(e.time) << "\"/>\n";
  x << indent << "  <Topology TopologyType=\"Hexahedron\" NumberOfElements=\"" << nc
    << "\" NodesPerElement=\"" << kNodesPerHex << "\">\n";
  x << indent << "    "
    << data_item(nc + " " + std::to_string(kNodesPerHex), "Int", e.h5_name, "/mesh/connectivity")
    << "\n";
  x << indent << "  </Topology>\n";
  x << indent << "  <Geometry GeometryType=\"XYZ\">\n";
  x << indent << "    " << data_item(nn + " 3", "Float", e.h5_name, "/mesh/coordinates") << "\n";
  x << indent << "  </Geometry>\n";
  for (const auto& f : e.fields) {
    const std::string dims = f.components == 1 ? nc : nc + " " + std::to_string(f.components);
    x << indent << "  <Attribute Name=\"" << xml_escape(f.name) << "\" AttributeType=\""
      << attribute_type(f.components) << "\" Center=\"Cell\">\n";
    x << indent << "    " << data_item(dims, "Float", e.h5_name, "/fields/" + f.name) << "\n";
    x << indent << "  </Attribute>\n";
  }
  x << indent << "</Grid>\n";
  return x.str();
}

// Writes `text` to `path` via a temporary file and a rename, so that a reader (e.g. a
// ParaView session reloading the series) never sees a half-written file.
void write_text_file_atomically(const std::string& path, const std::string& text) {
  const std::string tmp = path + ".tmp";
  {
    std::ofstream out(tmp, std::ios::out | std::ios::trunc | std::ios::binary);
    if (!out) throw std::runtime_error("lagremap::io: cannot create file '" + tmp + "'");
    out << text;
    out.close();
    if (!out) {
      std::error_code ec;
      fs::remove(tmp, ec);
      throw std::runtime_error("lagremap::io: cannot write file '" + tmp + "'");
    }
  }
  std::error_code ec;
  fs::rename(tmp, path, ec);
  if (ec) {
    std::error_code ignored;
    fs::remove(tmp, ignored);
    throw std::runtime_error("lagremap::io: cannot rename '" + tmp + "' to '" + path +
                             "': " + ec.message());
  }
}

const char* kXdmfHeader =
    "<?xml version=\"1.0\" ?>\n"
    "<Xdmf Version=\"3.0\" xmlns:xi=\"http://www.w3.org/2001/XInclude\">\n"
    "  <Domain>\n";
const char* kXdmfFooter =
    "  </Domain>\n"
    "</Xdmf>\n";

std::string index_suffix(int index) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "_%05d", index);
  return buf;
}

// ---------------------------------------------------------------------------------------
// Argument validation (std::invalid_argument)
// ---------------------------------------------------------------------------------------

void validate(double time, const SnapshotMesh& mesh, const std::vector<CellField>& fields) {
  auto bad = [](const std::string& m) {
    throw std::invalid_argument("lagremap::io::SnapshotSeries::write: " + m);
  };
  if (!std::isfinite(time)) bad("time is not finite");
  if (mesh.n_nodes < 0 || mesh.n_cells < 0) bad("negative node or cell count");
  if (mesh.n_nodes > 0 && mesh.node_xyz == nullptr && !mesh.fill_node_xyz) bad("node_xyz is null");
  if (mesh.n_cells > 0 && mesh.cell_nodes == nullptr && !mesh.fill_cell_nodes)
    bad("cell_nodes is null");
  if (!mesh.fill_cell_nodes) {
    const std::string error = connectivityError(mesh.cell_nodes, mesh.n_cells, globalNodes(mesh));
    if (!error.empty()) bad(error);
  }
  for (std::size_t i = 0; i < fields.size(); ++i) {
    const CellField& f = fields[i];
    if (f.name.empty()) bad("field " + std::to_string(i) + " has an empty name");
    if (f.name.find_first_of("/:") != std::string::npos || f.name == ".")
      bad("field name '" + f.name + "' must not be '.' or contain '/' or ':'");
    if (f.components < 1) bad("field '" + f.name + "' has components < 1");
    if (mesh.n_cells > 0 && f.data == nullptr && !f.fill)
      bad("field '" + f.name + "' has null data");
    for (std::size_t j = 0; j < i; ++j)
      if (fields[j].name == f.name) bad("duplicate field name '" + f.name + "'");
  }
}

}  // namespace

// ---------------------------------------------------------------------------------------
// SnapshotSeries
// ---------------------------------------------------------------------------------------

SnapshotSeries::SnapshotSeries(std::string directory, std::string series_name)
    : directory_(std::move(directory)), series_name_(std::move(series_name)) {
  if (series_name_.empty() || series_name_.find_first_of("/\\:") != std::string::npos)
    throw std::invalid_argument("lagremap::io::SnapshotSeries: series name '" + series_name_ +
                                "' must be non-empty and contain no '/', '\\' or ':'");
  if (directory_.empty()) directory_ = ".";
  std::error_code ec;
  fs::create_directories(directory_, ec);
  if (ec || !fs::is_directory(directory_)) {
    throw std::runtime_error("lagremap::io: cannot create snapshot directory '" + directory_ + "'" +
                             (ec ? ": " + ec.message() : std::string(": not a directory")));
  }
}

int SnapshotSeries::count() const {
  return static_cast<int>(entries_.size());
}

void SnapshotSeries::resume(const std::vector<double>& times) {
  entries_.clear();
  for (std::size_t i = 0; i < times.size(); ++i) {
    // sizes and fields are those of the next write (a run's snapshots all match)
    Entry entry{times[i], series_name_ + index_suffix(int(i)) + ".h5", -1, -1, {}};
    entry.listed = fs::exists(fs::path(directory_) / entry.h5_name);
    entries_.push_back(std::move(entry));
  }
}

const std::vector<double> SnapshotSeries::times() const {
  std::vector<double> out;
  for (const Entry& e : entries_) out.push_back(e.time);
  return out;
}

std::string SnapshotSeries::series_xmf_path() const {
  return (fs::path(directory_) / (series_name_ + ".xmf")).string();
}

std::string SnapshotSeries::write(double time, const SnapshotMesh& mesh,
                                  const std::vector<CellField>& fields) {
  validate(time, mesh, fields);

  const std::string stem = series_name_ + index_suffix(count());
  Entry entry{time, stem + ".h5", globalNodes(mesh), globalCells(mesh), {}};
  entry.fields.reserve(fields.size());
  for (const CellField& f : fields) entry.fields.push_back({f.name, f.components});

  for (Entry& e : entries_) {  // resumed entries take this snapshot's sizes and fields
    if (e.n_cells >= 0) continue;
    e.n_nodes = entry.n_nodes;
    e.n_cells = entry.n_cells;
    e.fields = entry.fields;
  }
  const std::string h5_path = (fs::path(directory_) / entry.h5_name).string();
  const std::string xmf_path = (fs::path(directory_) / (stem + ".xmf")).string();
  auto remove_outputs = [&] {
    std::error_code ignored;
    fs::remove(h5_path, ignored);
    fs::remove(xmf_path, ignored);
  };

  {
    QuietHdf5Errors quiet;
    try {
      write_snapshot_h5(h5_path, time, mesh, fields);
    } catch (...) {
      remove_outputs();
      throw;
    }
  }

  // The light data is rank 0's; its failure (a full disk) is every rank's.
  std::string error;
  if (parallel::isRoot()) {
    try {
      write_text_file_atomically(xmf_path,
                                 std::string(kXdmfHeader) + grid_xml(entry, "    ") + kXdmfFooter);
      std::string series = kXdmfHeader;
      series += "    <Grid Name=\"" + xml_escape(series_name_) +
                "\" GridType=\"Collection\" CollectionType=\"Temporal\">\n";
      for (const Entry& e : entries_) {
        if (e.listed) series += grid_xml(e, "      ");
      }
      series += grid_xml(entry, "      ");
      series += "    </Grid>\n";
      series += kXdmfFooter;
      write_text_file_atomically(series_xmf_path(), series);
    } catch (const std::exception& failure) {
      error = failure.what();
    }
  }
  error = parallel::firstMessage(error);
  if (!error.empty()) {
    remove_outputs();
    throw parallel::AgreedError(error);
  }

  entries_.push_back(std::move(entry));
  return h5_path;
}

}  // namespace lagremap::io
