#include "hdf5_rows.hpp"

#include <fcntl.h>
#include <mpi.h>
#include <unistd.h>

#include <cerrno>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <stdexcept>
#include <vector>

#include "../parallel.hpp"
#include "checksum.hpp"

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
  // The POSIX driver describes a failed read or write by its time, buffer,
  // sizes and offsets, and the system's message, which is what a user can
  // act on ("file write failed: No space left on device").
  const std::string system_message = "error message = '";
  const auto quoted = detail.find(system_message);
  if (quoted != std::string::npos) {
    const auto start = quoted + system_message.size();
    detail = detail.substr(0, detail.find(':')) + ": " +
             detail.substr(start, detail.find('\'', start) - start);
  }
  for (char& c : detail)
    if (c == '\n' || c == '\r') c = ' ';
  return detail;
}

namespace {
std::string failureMessage(const std::string& what, const std::string& file) {
  std::string message = "HDF5 failure (" + what + ") on '" + file + "'";
  const std::string detail = hdf5ErrorDetail();
  if (!detail.empty()) message += ": " + detail;
  return message;
}

// Throws on every rank if `status` is a failure on any: a transfer that
// failed on some ranks only (theirs reached a full disk) would otherwise
// leave the others waiting for them in the next collective call.
void agreeOn(herr_t status, const std::string& what, const std::string& file) {
  const std::string error = parallel::firstMessage(status < 0 ? failureMessage(what, file) : "");
  if (!error.empty()) throw parallel::AgreedError(error);
}
}  // namespace

void failHdf5(const std::string& what, const std::string& file) {
  throw std::runtime_error(failureMessage(what, file));
}

namespace {
// What HDF5 writes when it creates a file (the superblock) or closes it (the
// metadata, some hundred bytes per dataset and attribute, and the raw data
// it holds back, a sieve buffer of 64 KiB by default): a megabyte is room
// to spare for either.
constexpr off_t kRoom = off_t(1) << 20;
}  // namespace

OutputFile::OutputFile(const std::string& path, hid_t fapl) : path_(path), room_(path + ".room") {
  // Room for the create and for the close; the first half goes back at once.
  std::string error;
  if (parallel::isRoot()) {
    const int fd = ::open(room_.c_str(), O_CREAT | O_WRONLY | O_TRUNC, 0644);
    int code = fd < 0 ? errno : posix_fallocate(fd, 0, 2 * kRoom);
    if (code == 0 && ::ftruncate(fd, kRoom) != 0) code = errno;
    if (fd >= 0) ::close(fd);
    if (code != 0) {
      error = "cannot write '" + path + "': " + std::strerror(code);
      releaseRoom();
    }
  }
  error = parallel::firstMessage(error);
  if (!error.empty()) throw parallel::AgreedError(error);
  // (the create is collective: every rank fails alike, and says so once)
  id_ = H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, fapl);
  error = parallel::firstMessage(id_ < 0 ? failureMessage("create", path) : "");
  if (!error.empty()) {
    releaseRoom();
    throw parallel::AgreedError(error);
  }
}

void OutputFile::releaseRoom() {
  if (!parallel::isRoot()) return;
  std::error_code ignored;
  std::filesystem::remove(room_, ignored);
}

void OutputFile::close() {
  releaseRoom();
  const hid_t id = id_;
  id_ = -1;
  check(H5Fclose(id), "close", path_);
}

OutputFile::~OutputFile() {
  if (id_ < 0) return;
  // The room and the file's own space (it goes anyway) for what the close writes.
  releaseRoom();
  std::error_code ignored;
  std::filesystem::resize_file(path_, 0, ignored);
  H5Fclose(id_);
  H5Eclear2(H5E_DEFAULT);
  std::filesystem::remove(path_, ignored);
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
  agreeOn(H5Dwrite(dataset.get(), mem_type, memory_space.get(), file_space.get(), dxpl, data),
          "write dataset " + name, file);
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
  agreeOn(H5Dread(dataset.get(), mem_type, memory_space.get(), file_space.get(), dxpl, data),
          "read dataset " + name, file);
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

void writeWordAttribute(hid_t loc, const char* name, std::uint64_t value, const std::string& file) {
  Handle space(check(H5Screate(H5S_SCALAR), "H5Screate", file), H5Sclose);
  Handle attribute(
      check(H5Acreate2(loc, name, H5T_STD_U64LE, space.get(), H5P_DEFAULT, H5P_DEFAULT),
            "create attribute", file),
      H5Aclose);
  check(H5Awrite(attribute.get(), H5T_NATIVE_UINT64, &value), "write attribute", file);
}

std::uint64_t readWordAttribute(hid_t loc, const char* name, const std::string& file) {
  if (H5Aexists(loc, name) <= 0) {
    throw std::runtime_error("'" + file + "' has no attribute '" + std::string(name) + "'");
  }
  Handle attribute(check(H5Aopen(loc, name, H5P_DEFAULT), "open attribute", file), H5Aclose);
  std::uint64_t value = 0;
  check(H5Aread(attribute.get(), H5T_NATIVE_UINT64, &value), "read attribute", file);
  return value;
}

std::uint64_t attributesHash(hid_t loc, const char* except, const std::string& file) {
  std::vector<std::string> names;
  auto collect = [](hid_t, const char* name, const H5A_info_t*, void* out) -> herr_t {
    static_cast<std::vector<std::string>*>(out)->push_back(name);
    return 0;
  };
  check(H5Aiterate2(loc, H5_INDEX_NAME, H5_ITER_INC, nullptr, collect, &names), "list attributes",
        file);
  WordHash hash;
  for (const std::string& name : names) {
    if (name == except) continue;
    Handle attribute(check(H5Aopen(loc, name.c_str(), H5P_DEFAULT), "open attribute", file),
                     H5Aclose);
    Handle type(check(H5Aget_type(attribute.get()), "H5Aget_type", file), H5Tclose);
    // The type's description too: the same bytes read as another type are another value.
    std::size_t type_size = 0;
    check(H5Tencode(type.get(), nullptr, &type_size), "H5Tencode", file);
    std::vector<unsigned char> bytes(type_size);
    check(H5Tencode(type.get(), bytes.data(), &type_size), "H5Tencode", file);
    hash.addBytes(name.data(), name.size());
    hash.addBytes(bytes.data(), bytes.size());
    bytes.assign(H5Aget_storage_size(attribute.get()), 0);
    check(H5Aread(attribute.get(), type.get(), bytes.data()), "read attribute", file);
    hash.addBytes(bytes.data(), bytes.size());
  }
  return hash.value();
}

}  // namespace lagremap::io
