#include "hdf5_rows.hpp"

#include <mpi.h>

#include <stdexcept>
#include <vector>

#include "../parallel.hpp"

namespace lagremap::io {

QuietHdf5Errors::QuietHdf5Errors() {
  H5Eget_auto2(H5E_DEFAULT, &func_, &client_data_);
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
}

QuietHdf5Errors::~QuietHdf5Errors() {
  H5Eset_auto2(H5E_DEFAULT, func_, client_data_);
}

std::string hdf5ErrorDetail() {
  std::string detail;
  auto walker = [](unsigned n, const H5E_error2_t* err, void* out) -> herr_t {
    if (n == 0 && err != nullptr && err->desc != nullptr) {
      *static_cast<std::string*>(out) = err->desc;
    }
    return 0;
  };
  H5Ewalk2(H5E_DEFAULT, H5E_WALK_UPWARD, walker, &detail);
  H5Eclear2(H5E_DEFAULT);
  for (char& c : detail)
    if (c == '\n' || c == '\r') c = ' ';
  return detail;
}

void failHdf5(const std::string& what, const std::string& file) {
  std::string message = "HDF5 failure (" + what + ") on '" + file + "'";
  const std::string detail = hdf5ErrorDetail();
  if (!detail.empty()) message += ": " + detail;
  throw std::runtime_error(message);
}

namespace {
constexpr const char* kCollectiveBufferBytes = "4194304";
}  // namespace

hid_t fileAccess(const std::string& file) {
  const hid_t fapl = check(H5Pcreate(H5P_FILE_ACCESS), "H5Pcreate(FILE_ACCESS)", file);
#ifdef H5_HAVE_PARALLEL
  if (parallel::size() > 1) {
    // Collective writes gather the ranks' rows on aggregator ranks in buffers
    // of cb_buffer_size bytes; Open MPI's OMPIO takes 32 MiB by default, which
    // was a quarter of rank 0's peak at sedov 64^3 on 8 ranks (docs/performance.md
    // §6.1). 4 MiB costs more write rounds on a large file, not more memory.
    MPI_Info info;
    MPI_Info_create(&info);
    MPI_Info_set(info, "cb_buffer_size", kCollectiveBufferBytes);
    check(H5Pset_fapl_mpio(fapl, MPI_COMM_WORLD, info), "H5Pset_fapl_mpio", file);
    MPI_Info_free(&info);
    check(H5Pset_all_coll_metadata_ops(fapl, true), "H5Pset_all_coll_metadata_ops", file);
    check(H5Pset_coll_metadata_write(fapl, true), "H5Pset_coll_metadata_write", file);
  }
#else
  if (parallel::size() > 1) {
    throw std::runtime_error("HDF5 without MPI-IO: cannot write '" + file + "' from several ranks");
  }
#endif
  return fapl;
}

hid_t transfer(const std::string& file) {
  const hid_t dxpl = check(H5Pcreate(H5P_DATASET_XFER), "H5Pcreate(DATASET_XFER)", file);
#ifdef H5_HAVE_PARALLEL
  if (parallel::size() > 1) {
    check(H5Pset_dxpl_mpio(dxpl, H5FD_MPIO_COLLECTIVE), "H5Pset_dxpl_mpio", file);
  }
#endif
  return dxpl;
}

namespace {

// Selects the rank's rows in the file space: one hyperslab per run of
// consecutive rows (a block partition's rows come in runs of its x extent).
void selectRows(hid_t file_space, const RowSelection& selection, int cols,
                const std::string& file) {
  const hsize_t width = hsize_t(cols == 0 ? 1 : cols);
  if (selection.local_rows == 0) {
    check(H5Sselect_none(file_space), "H5Sselect_none", file);
    return;
  }
  if (selection.rows == nullptr) {
    const hsize_t start[2] = {0, 0}, count[2] = {hsize_t(selection.local_rows), width};
    check(H5Sselect_hyperslab(file_space, H5S_SELECT_SET, start, nullptr, count, nullptr),
          "H5Sselect_hyperslab", file);
    return;
  }
  H5S_seloper_t op = H5S_SELECT_SET;
  std::int64_t i = 0;
  while (i < selection.local_rows) {
    std::int64_t j = i + 1;
    while (j < selection.local_rows && selection.rows[j] == selection.rows[j - 1] + 1) ++j;
    const hsize_t start[2] = {hsize_t(selection.rows[i]), 0}, count[2] = {hsize_t(j - i), width};
    check(H5Sselect_hyperslab(file_space, op, start, nullptr, count, nullptr),
          "H5Sselect_hyperslab", file);
    op = H5S_SELECT_OR;
    i = j;
  }
}

}  // namespace

void writeRows(hid_t loc, const std::string& name, hid_t file_type, hid_t mem_type,
               const RowSelection& selection, int cols, const void* data, hid_t dxpl,
               const std::string& file) {
  const int rank = cols == 0 ? 1 : 2;
  const hsize_t global_dims[2] = {hsize_t(selection.global_rows), hsize_t(cols)};
  const hsize_t local_dims[2] = {hsize_t(selection.local_rows), hsize_t(cols)};
  Handle file_space(check(H5Screate_simple(rank, global_dims, nullptr), "H5Screate_simple", file),
                    H5Sclose);
  Handle dataset(check(H5Dcreate2(loc, name.c_str(), file_type, file_space.get(), H5P_DEFAULT,
                                  H5P_DEFAULT, H5P_DEFAULT),
                       ("create dataset " + name).c_str(), file),
                 H5Dclose);
  // One rank with nothing to write skips the call; in a collective write every
  // rank takes part, an empty one with empty selections.
  if (selection.global_rows == 0 || (selection.local_rows == 0 && parallel::size() == 1)) return;
  selectRows(file_space.get(), selection, cols, file);
  Handle memory_space(check(H5Screate_simple(rank, local_dims, nullptr), "H5Screate_simple", file),
                      H5Sclose);
  if (selection.local_rows == 0) check(H5Sselect_none(memory_space.get()), "H5Sselect_none", file);
  check(H5Dwrite(dataset.get(), mem_type, memory_space.get(), file_space.get(), dxpl, data),
        ("write dataset " + name).c_str(), file);
}

void readRows(hid_t loc, const std::string& name, hid_t mem_type, const RowSelection& selection,
              int cols, void* data, hid_t dxpl, const std::string& file) {
  const int rank = cols == 0 ? 1 : 2;
  if (H5Lexists(loc, name.c_str(), H5P_DEFAULT) <= 0) {
    throw std::runtime_error("'" + file + "' has no dataset '" + name + "'");
  }
  Handle dataset(check(H5Dopen2(loc, name.c_str(), H5P_DEFAULT), ("open " + name).c_str(), file),
                 H5Dclose);
  Handle file_space(check(H5Dget_space(dataset.get()), "H5Dget_space", file), H5Sclose);
  hsize_t dims[2] = {0, 0};
  const int file_rank = H5Sget_simple_extent_ndims(file_space.get());
  if (file_rank != rank)
    throw std::runtime_error("'" + file + "': dataset '" + name + "' has the wrong rank");
  H5Sget_simple_extent_dims(file_space.get(), dims, nullptr);
  if (dims[0] != hsize_t(selection.global_rows) || (rank == 2 && dims[1] != hsize_t(cols))) {
    throw std::runtime_error("'" + file + "': dataset '" + name + "' has the wrong shape");
  }
  if (selection.global_rows == 0) return;  // an empty table: nothing to read
  const hsize_t local_dims[2] = {hsize_t(selection.local_rows), hsize_t(cols)};
  selectRows(file_space.get(), selection, cols, file);
  Handle memory_space(check(H5Screate_simple(rank, local_dims, nullptr), "H5Screate_simple", file),
                      H5Sclose);
  if (selection.local_rows == 0) check(H5Sselect_none(memory_space.get()), "H5Sselect_none", file);
  check(H5Dread(dataset.get(), mem_type, memory_space.get(), file_space.get(), dxpl, data),
        ("read dataset " + name).c_str(), file);
}

void writeScalarAttribute(hid_t loc, const char* name, double value, const std::string& file) {
  Handle space(check(H5Screate(H5S_SCALAR), "H5Screate", file), H5Sclose);
  Handle attribute(
      check(H5Acreate2(loc, name, H5T_IEEE_F64LE, space.get(), H5P_DEFAULT, H5P_DEFAULT),
            "create attribute", file),
      H5Aclose);
  check(H5Awrite(attribute.get(), H5T_NATIVE_DOUBLE, &value), "write attribute", file);
}

double readScalarAttribute(hid_t loc, const char* name, const std::string& file) {
  if (H5Aexists(loc, name) <= 0) {
    throw std::runtime_error("'" + file + "' has no attribute '" + std::string(name) + "'");
  }
  Handle attribute(check(H5Aopen(loc, name, H5P_DEFAULT), "open attribute", file), H5Aclose);
  double value = 0.0;
  check(H5Aread(attribute.get(), H5T_NATIVE_DOUBLE, &value), "read attribute", file);
  return value;
}

void writeTextAttribute(hid_t loc, const char* name, const std::string& value,
                        const std::string& file) {
  Handle type(check(H5Tcopy(H5T_C_S1), "H5Tcopy", file), H5Tclose);
  check(H5Tset_size(type.get(), value.empty() ? 1 : value.size()), "H5Tset_size", file);
  Handle space(check(H5Screate(H5S_SCALAR), "H5Screate", file), H5Sclose);
  Handle attribute(check(H5Acreate2(loc, name, type.get(), space.get(), H5P_DEFAULT, H5P_DEFAULT),
                         "create attribute", file),
                   H5Aclose);
  const std::string padded = value.empty() ? std::string(1, '\0') : value;
  check(H5Awrite(attribute.get(), type.get(), padded.data()), "write attribute", file);
}

std::string readTextAttribute(hid_t loc, const char* name, const std::string& file) {
  if (H5Aexists(loc, name) <= 0) {
    throw std::runtime_error("'" + file + "' has no attribute '" + std::string(name) + "'");
  }
  Handle attribute(check(H5Aopen(loc, name, H5P_DEFAULT), "open attribute", file), H5Aclose);
  Handle type(check(H5Aget_type(attribute.get()), "H5Aget_type", file), H5Tclose);
  if (H5Tget_class(type.get()) != H5T_STRING || H5Tis_variable_str(type.get()) > 0) {
    throw std::runtime_error("'" + file + "': attribute '" + std::string(name) + "' is not text");
  }
  std::string value(H5Tget_size(type.get()), '\0');
  check(H5Aread(attribute.get(), type.get(), value.data()), "read attribute", file);
  return value.substr(0, value.find('\0'));
}

}  // namespace lagremap::io
