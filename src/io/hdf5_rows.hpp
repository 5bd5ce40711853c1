// Small HDF5 toolkit shared by the snapshot writer and the checkpoint: owning
// handles, errors as exceptions, files opened for every rank (MPI-IO when the
// run has several), and datasets of global rows written or read by each rank
// for its own, not necessarily contiguous, rows (method.md §7.5).
#pragma once

#include <hdf5.h>

#include <cstdint>
#include <string>

namespace lagremap::io {

// Disables HDF5's automatic error-stack printing while alive (errors become exceptions).
class QuietHdf5Errors {
 public:
  QuietHdf5Errors();
  ~QuietHdf5Errors();
  QuietHdf5Errors(const QuietHdf5Errors&) = delete;
  QuietHdf5Errors& operator=(const QuietHdf5Errors&) = delete;

 private:
  H5E_auto2_t func_ = nullptr;
  void* client_data_ = nullptr;
};

// Description of the innermost entry of the current HDF5 error stack, one line.
std::string hdf5ErrorDetail();
[[noreturn]] void failHdf5(const std::string& what, const std::string& file);

template <class T>
T check(T value, const char* what, const std::string& file) {
  if (value < 0) failHdf5(what, file);
  return value;
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
  // Closes now and reports failure (files: H5Fclose flushes).
  herr_t close() {
    const herr_t status = id_ >= 0 ? closer_(id_) : 0;
    id_ = -1;
    return status;
  }

 private:
  hid_t id_;
  Closer closer_;
};

// A new file every rank writes (collective create and close) that is closed
// cleanly whatever fails, a full disk above all. HDF5 1.10 writes metadata
// when it closes a file, and a close that fails (its flush, once failed,
// cannot be retried) leaves the file open in the library, whose clean-up at
// exit then fails again: an error dump, "infinite loop closing library" or
// a crash. So the file comes with a reserve of disk space, `<path>.room`,
// given back just before the close. On a failure, the destructor gives it
// back with the file's own space, closes the file and removes it.
class OutputFile {
 public:
  // Reserves the room and creates (truncates) `path`; throws naming it if
  // either cannot be done.
  OutputFile(const std::string& path, hid_t fapl);
  ~OutputFile();
  OutputFile(const OutputFile&) = delete;
  OutputFile& operator=(const OutputFile&) = delete;
  hid_t get() const { return id_; }
  // Closes the complete file; throws on a failure.
  void close();

 private:
  void releaseRoom();
  std::string path_, room_;
  hid_t id_ = -1;
};

// File access for every rank: MPI-IO on MPI_COMM_WORLD when the run has
// several ranks (collective open and metadata), the default driver otherwise.
hid_t fileAccess(const std::string& file);
// Dataset transfer: collective MPI-IO when the run has several ranks.
hid_t transfer(const std::string& file);

// A rank's rows of a dataset of `global_rows` rows: `rows` (increasing global
// row numbers, local_rows of them), or rows 0..local_rows-1 when null.
struct RowSelection {
  std::int64_t global_rows = 0;
  std::int64_t local_rows = 0;
  const std::int64_t* rows = nullptr;
};

// Creates dataset `name` of shape [global_rows] (cols == 0) or [global_rows, cols]
// and writes this rank's rows from `data` (local_rows * max(cols, 1) values).
// Collective: every rank calls it, with or without rows.
void writeRows(hid_t loc, const std::string& name, hid_t file_type, hid_t mem_type,
               const RowSelection& selection, int cols, const void* data, hid_t dxpl,
               const std::string& file);
// Reads this rank's rows of dataset `name` into `data`; throws if the dataset
// is missing or its shape is not [global_rows] / [global_rows, cols].
void readRows(hid_t loc, const std::string& name, hid_t mem_type, const RowSelection& selection,
              int cols, void* data, hid_t dxpl, const std::string& file);

void writeScalarAttribute(hid_t loc, const char* name, double value, const std::string& file);
double readScalarAttribute(hid_t loc, const char* name, const std::string& file);
void writeTextAttribute(hid_t loc, const char* name, const std::string& value,
                        const std::string& file);
std::string readTextAttribute(hid_t loc, const char* name, const std::string& file);
void writeWordAttribute(hid_t loc, const char* name, std::uint64_t value, const std::string& file);
std::uint64_t readWordAttribute(hid_t loc, const char* name, const std::string& file);

// Hash of every attribute of `loc` but `except`, each one's name and stored
// bytes, in the order of their names: whatever attributes a writer adds are
// covered without a list to keep. Collective where reading metadata is.
std::uint64_t attributesHash(hid_t loc, const char* except, const std::string& file);

}  // namespace lagremap::io
