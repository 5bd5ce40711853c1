#include "snapshot_writer.hpp"

#include <hdf5.h>

#include <charconv>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <system_error>
#include <utility>

namespace lagremap::io {

namespace fs = std::filesystem;

namespace {

constexpr int kNodesPerHex = 8;

// ---------------------------------------------------------------------------------------
// HDF5 helpers
// ---------------------------------------------------------------------------------------

// Disables HDF5's automatic error-stack printing for the lifetime of the object and
// restores the previous handler afterwards (we report errors through exceptions).
class QuietHdf5Errors {
 public:
  QuietHdf5Errors() {
    H5Eget_auto2(H5E_DEFAULT, &func_, &client_data_);
    H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
  }
  ~QuietHdf5Errors() { H5Eset_auto2(H5E_DEFAULT, func_, client_data_); }
  QuietHdf5Errors(const QuietHdf5Errors&) = delete;
  QuietHdf5Errors& operator=(const QuietHdf5Errors&) = delete;

 private:
  H5E_auto2_t func_ = nullptr;
  void* client_data_ = nullptr;
};

// Description of the innermost entry of the current HDF5 error stack, newlines removed.
std::string hdf5_error_detail() {
  std::string detail;
  auto walker = [](unsigned n, const H5E_error2_t* err, void* out) -> herr_t {
    if (n == 0 && err != nullptr && err->desc != nullptr)
      *static_cast<std::string*>(out) = err->desc;
    return 0;
  };
  H5Ewalk2(H5E_DEFAULT, H5E_WALK_UPWARD, walker, &detail);
  H5Eclear2(H5E_DEFAULT);
  for (char& c : detail)
    if (c == '\n' || c == '\r') c = ' ';
  return detail;
}

[[noreturn]] void fail_hdf5(const std::string& what, const std::string& file) {
  std::string msg = "lagremap::io: HDF5 failure (" + what + ") writing '" + file + "'";
  const std::string detail = hdf5_error_detail();
  if (!detail.empty()) msg += ": " + detail;
  throw std::runtime_error(msg);
}

// Returns v, or throws if it is a negative HDF5 id / status.
template <class T>
T check(T v, const char* what, const std::string& file) {
  if (v < 0) fail_hdf5(what, file);
  return v;
}

// Owning hid_t with its matching close function.
class Handle {
 public:
  using Closer = herr_t (*)(hid_t);
  Handle(hid_t id, Closer closer) : id_(id), closer_(closer) {}
  ~Handle() {
    if (id_ >= 0) closer_(id_);
  }
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;
  hid_t get() const { return id_; }
  // Closes now and reports failure (needed for files: H5Fclose flushes).
  herr_t close() {
    const herr_t status = id_ >= 0 ? closer_(id_) : 0;
    id_ = -1;
    return status;
  }

 private:
  hid_t id_;
  Closer closer_;
};

// Writes the row slab [row_offset, row_offset + local_rows) of a dataset of global shape
// [global_rows] (cols == 0) or [global_rows, cols] from `data` (local_rows * max(cols, 1)
// values of mem_type). Serial callers pass row_offset = 0 and local_rows = global_rows;
// the hyperslab selection is exactly what a collective MPI-IO write needs.
void write_rows(hid_t loc, const std::string& name, hid_t file_type, hid_t mem_type,
                std::int64_t global_rows, std::int64_t row_offset, std::int64_t local_rows,
                int cols, const void* data, hid_t dxpl, const std::string& file) {
  const int rank = cols == 0 ? 1 : 2;
  const hsize_t gdims[2] = {static_cast<hsize_t>(global_rows), static_cast<hsize_t>(cols)};
  const hsize_t start[2] = {static_cast<hsize_t>(row_offset), 0};
  const hsize_t count[2] = {static_cast<hsize_t>(local_rows), static_cast<hsize_t>(cols)};

  Handle file_space(check(H5Screate_simple(rank, gdims, nullptr), "H5Screate_simple", file),
                    H5Sclose);
  Handle dset(check(H5Dcreate2(loc, name.c_str(), file_type, file_space.get(), H5P_DEFAULT,
                               H5P_DEFAULT, H5P_DEFAULT),
                    ("create dataset " + name).c_str(), file),
              H5Dclose);
  // Serial: nothing to write for an empty slab. In a collective write every rank must still
  // call H5Dwrite, with H5Sselect_none() on both the file and the memory space.
  if (local_rows == 0) return;
  check(H5Sselect_hyperslab(file_space.get(), H5S_SELECT_SET, start, nullptr, count, nullptr),
        "H5Sselect_hyperslab", file);
  Handle mem_space(check(H5Screate_simple(rank, count, nullptr), "H5Screate_simple", file),
                   H5Sclose);
  check(H5Dwrite(dset.get(), mem_type, mem_space.get(), file_space.get(), dxpl, data),
        ("write dataset " + name).c_str(), file);
}

void write_scalar_attribute(hid_t loc, const char* name, double value, const std::string& file) {
  Handle space(check(H5Screate(H5S_SCALAR), "H5Screate", file), H5Sclose);
  Handle attr(check(H5Acreate2(loc, name, H5T_IEEE_F64LE, space.get(), H5P_DEFAULT, H5P_DEFAULT),
                    "create attribute", file),
              H5Aclose);
  check(H5Awrite(attr.get(), H5T_NATIVE_DOUBLE, &value), "write attribute", file);
}

// Writes one complete snapshot file.
//
// How to make this parallel (collective MPI-IO), when lagremap gets MPI domains:
//  * fapl: H5Pset_fapl_mpio(fapl, comm, MPI_INFO_NULL) instead of the default driver
//    (requires the parallel HDF5 build, H5_HAVE_PARALLEL, which Debian's
//    libhdf5-openmpi-dev is); optionally H5Pset_all_coll_metadata_ops /
//    H5Pset_coll_metadata_write.
//  * dxpl: H5Pset_dxpl_mpio(dxpl, H5FD_MPIO_COLLECTIVE).
//  * Sizes: each rank owns n_local cells and n_local owned nodes; global sizes from
//    MPI_Allreduce, each rank's row offset from MPI_Exscan. Pass them to write_rows()
//    (global_rows, row_offset, local_rows) instead of (n, 0, n). Connectivity must hold
//    global node numbers (local index + owner's node offset; ghost nodes mapped to their
//    owner's global number). All ranks create every dataset/attribute (metadata calls are
//    collective); the attribute value must be identical on all ranks.
//  * Only rank 0 writes the .xmf files (they need only the global sizes).
void write_snapshot_h5(const std::string& path, double time, const SnapshotMesh& mesh,
                       const std::vector<CellField>& fields) {
  Handle fapl(check(H5Pcreate(H5P_FILE_ACCESS), "H5Pcreate(FILE_ACCESS)", path), H5Pclose);
  Handle dxpl(check(H5Pcreate(H5P_DATASET_XFER), "H5Pcreate(DATASET_XFER)", path), H5Pclose);

  const hid_t fid = H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, fapl.get());
  if (fid < 0) {
    std::string msg = "lagremap::io: cannot create HDF5 file '" + path + "'";
    const std::string detail = hdf5_error_detail();
    if (!detail.empty()) msg += ": " + detail;
    throw std::runtime_error(msg);
  }
  Handle file(fid, H5Fclose);

  write_scalar_attribute(file.get(), "time", time, path);

  {
    Handle mesh_group(check(H5Gcreate2(file.get(), "mesh", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
                            "create group /mesh", path),
                      H5Gclose);
    write_rows(mesh_group.get(), "coordinates", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, mesh.n_nodes, 0,
               mesh.n_nodes, 3, mesh.node_xyz, dxpl.get(), path);
    write_rows(mesh_group.get(), "connectivity", H5T_STD_I64LE, H5T_NATIVE_INT64, mesh.n_cells, 0,
               mesh.n_cells, kNodesPerHex, mesh.cell_nodes, dxpl.get(), path);
  }
  {
    Handle field_group(
        check(H5Gcreate2(file.get(), "fields", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
              "create group /fields", path),
        H5Gclose);
    for (const CellField& f : fields) {
      write_rows(field_group.get(), f.name, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, mesh.n_cells, 0,
                 mesh.n_cells, f.components == 1 ? 0 : f.components, f.data, dxpl.get(), path);
    }
  }

  if (file.close() < 0) fail_hdf5("H5Fclose", path);
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
  if (mesh.n_nodes > 0 && mesh.node_xyz == nullptr) bad("node_xyz is null");
  if (mesh.n_cells > 0 && mesh.cell_nodes == nullptr) bad("cell_nodes is null");
  const std::int64_t n_conn = mesh.n_cells * kNodesPerHex;
  for (std::int64_t i = 0; i < n_conn; ++i) {
    const std::int64_t v = mesh.cell_nodes[i];
    if (v < 0 || v >= mesh.n_nodes)
      bad("cell " + std::to_string(i / kNodesPerHex) + " references node " + std::to_string(v) +
          " outside [0, " + std::to_string(mesh.n_nodes) + ")");
  }
  for (std::size_t i = 0; i < fields.size(); ++i) {
    const CellField& f = fields[i];
    if (f.name.empty()) bad("field " + std::to_string(i) + " has an empty name");
    if (f.name.find_first_of("/:") != std::string::npos || f.name == ".")
      bad("field name '" + f.name + "' must not be '.' or contain '/' or ':'");
    if (f.components < 1) bad("field '" + f.name + "' has components < 1");
    if (mesh.n_cells > 0 && f.data == nullptr) bad("field '" + f.name + "' has null data");
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

std::string SnapshotSeries::series_xmf_path() const {
  return (fs::path(directory_) / (series_name_ + ".xmf")).string();
}

std::string SnapshotSeries::write(double time, const SnapshotMesh& mesh,
                                  const std::vector<CellField>& fields) {
  validate(time, mesh, fields);

  const std::string stem = series_name_ + index_suffix(count());
  Entry entry{time, stem + ".h5", mesh.n_nodes, mesh.n_cells, {}};
  entry.fields.reserve(fields.size());
  for (const CellField& f : fields) entry.fields.push_back({f.name, f.components});

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

  try {
    write_text_file_atomically(xmf_path,
                               std::string(kXdmfHeader) + grid_xml(entry, "    ") + kXdmfFooter);

    std::string series = kXdmfHeader;
    series += "    <Grid Name=\"" + xml_escape(series_name_) +
              "\" GridType=\"Collection\" CollectionType=\"Temporal\">\n";
    for (const Entry& e : entries_) series += grid_xml(e, "      ");
    series += grid_xml(entry, "      ");
    series += "    </Grid>\n";
    series += kXdmfFooter;
    write_text_file_atomically(series_xmf_path(), series);
  } catch (...) {
    remove_outputs();
    throw;
  }

  entries_.push_back(std::move(entry));
  return h5_path;
}

}  // namespace lagremap::io
