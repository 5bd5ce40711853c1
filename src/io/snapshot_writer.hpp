// HDF5 + XDMF snapshot writer for unstructured 8-node hexahedral meshes.
//
// Each call to SnapshotSeries::write() produces, in the series directory:
//   <series>_<NNNNN>.h5   heavy data:  /mesh/coordinates   float64 [n_nodes, 3]
//                                      /mesh/connectivity  int64   [n_cells, 8] (VTK_HEXAHEDRON
//                                      order) /fields/<name>      float64 [n_cells] or [n_cells,
//                                      components] attribute "time" (float64) on the root group
//   <series>_<NNNNN>.xmf  light data describing that one snapshot
//   <series>.xmf          temporal collection of every snapshot written so far in the
//                         directory (rewritten atomically after each snapshot; open this
//                         one in ParaView to get an animated series)
// The .xmf files reference the .h5 files by relative file name, so the directory can be
// moved or copied as a whole.
//
// Plain host C++17 + the HDF5 C API (MPI-IO through src/io/hdf5_rows.hpp); no Kokkos. Device data
// must be copied to host (e.g. Kokkos::create_mirror_view_and_copy) before calling write().
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace lagremap::io {

// One cell-centred field. data holds n_cells * components doubles, component fastest.
//   components == 1 : scalar            -> XDMF AttributeType "Scalar"
//   components == 3 : vector            -> "Vector"
//   components == 6 : symmetric tensor, stored in the order xx, yy, zz, xy, yz, xz
//                                       -> "Tensor6". ParaView's XDMF3 readers
//                     (Xdmf3ReaderS/T) pass the 6 components through unchanged, which is
//                     VTK's symmetric-tensor order, so they come out right. The legacy
//                     XDMF2 "XDMFReader" instead expands Tensor6 to 9 components assuming
//                     XDMF's xx, xy, xz, yy, yz, zz order, mislabelling the off-diagonals.
//   components == 9 : full tensor, row-major xx, xy, xz, yx, ... -> "Tensor"
//   any other count >= 1                -> "Matrix" (n_cells x components)
// name must be non-empty, unique within one write() call, and contain no '/' or ':'.
// Instead of `data`, a field may give `fill`, which writes the n_cells * components
// values into `out` when the field's turn comes: the writer then packs one field at a
// time into one buffer, so a snapshot costs the memory of its largest field, not of
// all of them (a caller whose fields are laid out otherwise, e.g. with ghost cells).
struct CellField {
  std::string name;
  const double* data;
  int components;
  std::function<void(double* out)> fill = nullptr;
};

// Host view of the mesh. node_xyz: 3 * n_nodes (x, y, z per node);
// cell_nodes: 8 * n_cells zero-based node indices in VTK_HEXAHEDRON order.
// A decomposed run (method.md §7.5) passes each rank's owned nodes and cells with
// their global rows (increasing) and the global counts; cell_nodes then hold
// global node numbers. Every rank calls write() (collective MPI-IO); the file
// is the one a single rank would write.
// Either array may instead be given by a function filling it (as CellField::fill).
struct SnapshotMesh {
  std::int64_t n_nodes;
  const double* node_xyz;
  std::int64_t n_cells;
  const std::int64_t* cell_nodes;
  const std::int64_t* node_rows = nullptr;  // global row of each node (null: 0..n_nodes-1)
  const std::int64_t* cell_rows = nullptr;  // global row of each cell (null: 0..n_cells-1)
  std::int64_t n_global_nodes = -1;         // -1: n_nodes
  std::int64_t n_global_cells = -1;         // -1: n_cells
  std::function<void(double* out)> fill_node_xyz = nullptr;
  std::function<void(std::int64_t* out)> fill_cell_nodes = nullptr;
};

// A time series of snapshots sharing one directory and one base name.
//
// Errors: a file or directory that cannot be created/written, or any HDF5 failure, throws
// std::runtime_error with a one-line message naming the file. Invalid arguments (bad series
// name, null pointers, out-of-range connectivity, bad field names/component counts) throw
// std::invalid_argument. A failed write() leaves count() unchanged and removes the
// partially written .h5 file.
//
// Note: a new SnapshotSeries starts at index 0 and overwrites existing files of the same
// series in the directory, unless resume() says which are already there.
//
class SnapshotSeries {
 public:
  // Creates `directory` (and parents) if needed; throws std::runtime_error if it cannot.
  // series_name must be non-empty and contain no '/', '\\' or ':'.
  SnapshotSeries(std::string directory, std::string series_name);

  // Writes snapshot number count() (see the file layout above) and rewrites the series
  // .xmf. Returns the path of the .h5 file written (<directory>/<series>_<NNNNN>.h5).
  std::string write(double time, const SnapshotMesh& mesh, const std::vector<CellField>& fields);

  // Number of snapshots successfully written so far.
  int count() const;

  // Continues a series whose first snapshots were taken at `times` (a
  // restarted run): the next write gets the next index, and the series .xmf
  // lists the earlier files found in the directory, with the same mesh sizes
  // and fields. A run restarted into another directory finds none there: its
  // series lists its own files only, and opens there.
  void resume(const std::vector<double>& times);
  const std::vector<double> times() const;

  const std::string& directory() const { return directory_; }
  const std::string& series_name() const { return series_name_; }
  // Path of the temporal-collection file <directory>/<series>.xmf (exists after the first write).
  std::string series_xmf_path() const;

 private:
  struct FieldInfo {
    std::string name;
    int components;
  };
  struct Entry {
    double time;
    std::string h5_name;  // file name relative to directory_
    std::int64_t n_nodes;
    std::int64_t n_cells;
    std::vector<FieldInfo> fields;
    bool listed = true;  // in the series .xmf (false: an earlier file not in directory_)
  };

  std::string directory_;
  std::string series_name_;
  std::vector<Entry> entries_;
};

}  // namespace lagremap::io
