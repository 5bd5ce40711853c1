// Tests for lagremap::io::SnapshotSeries (HDF5 + XDMF snapshot writer).
//
// Set LAGREMAP_TEST_KEEP_OUTPUT=1 to keep the written series (the directory is printed),
// e.g. to open it with `pvpython scripts/check_xdmf.py <dir>/block.xmf`.
#include "src/io/snapshot_writer.hpp"

#include <gtest/gtest.h>
#include <hdf5.h>

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace {

namespace fs = std::filesystem;
using lagremap::io::CellField;
using lagremap::io::SnapshotMesh;
using lagremap::io::SnapshotSeries;

// Structured block of nx*ny*nz unit hexes, VTK_HEXAHEDRON node order.
struct Block {
  std::int64_t nx, ny, nz;
  std::vector<double> xyz;
  std::vector<std::int64_t> conn;

  Block(std::int64_t nx_, std::int64_t ny_, std::int64_t nz_) : nx(nx_), ny(ny_), nz(nz_) {
    auto node = [&](std::int64_t i, std::int64_t j, std::int64_t k) {
      return i + (nx + 1) * (j + (ny + 1) * k);
    };
    for (std::int64_t k = 0; k <= nz; ++k)
      for (std::int64_t j = 0; j <= ny; ++j)
        for (std::int64_t i = 0; i <= nx; ++i) {
          xyz.push_back(0.5 * static_cast<double>(i));
          xyz.push_back(0.25 * static_cast<double>(j));
          xyz.push_back(0.125 * static_cast<double>(k) + 1.0);
        }
    for (std::int64_t k = 0; k < nz; ++k)
      for (std::int64_t j = 0; j < ny; ++j)
        for (std::int64_t i = 0; i < nx; ++i) {
          const std::int64_t c[8] = {node(i, j, k),
                                     node(i + 1, j, k),
                                     node(i + 1, j + 1, k),
                                     node(i, j + 1, k),
                                     node(i, j, k + 1),
                                     node(i + 1, j, k + 1),
                                     node(i + 1, j + 1, k + 1),
                                     node(i, j + 1, k + 1)};
          conn.insert(conn.end(), c, c + 8);
        }
  }
  std::int64_t n_nodes() const { return static_cast<std::int64_t>(xyz.size() / 3); }
  std::int64_t n_cells() const { return static_cast<std::int64_t>(conn.size() / 8); }
  SnapshotMesh mesh() const { return {n_nodes(), xyz.data(), n_cells(), conn.data()}; }
};

class TempDir {
 public:
  TempDir() {
    std::string templ = (fs::temp_directory_path() / "lagremap_snapshot_XXXXXX").string();
    if (mkdtemp(templ.data()) == nullptr) throw std::runtime_error("mkdtemp failed");
    path_ = templ;
  }
  ~TempDir() {
    const char* keep = std::getenv("LAGREMAP_TEST_KEEP_OUTPUT");
    if (keep != nullptr && *keep != '\0' && std::string(keep) != "0") {
      std::printf("[ keeping  ] %s\n", path_.c_str());
      return;
    }
    std::error_code ec;
    fs::remove_all(path_, ec);
  }
  const fs::path& path() const { return path_; }

 private:
  fs::path path_;
};

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

std::size_t occurrences(const std::string& hay, const std::string& needle) {
  std::size_t n = 0;
  for (auto pos = hay.find(needle); pos != std::string::npos; pos = hay.find(needle, pos + 1)) ++n;
  return n;
}

// Reads a whole dataset; returns its dimensions in *dims.
template <class T>
std::vector<T> read_dataset(hid_t file, const char* path, hid_t mem_type,
                            std::vector<hsize_t>* dims) {
  const hid_t dset = H5Dopen2(file, path, H5P_DEFAULT);
  EXPECT_GE(dset, 0) << path;
  if (dset < 0) return {};
  const hid_t space = H5Dget_space(dset);
  const int rank = H5Sget_simple_extent_ndims(space);
  dims->assign(static_cast<std::size_t>(rank), 0);
  H5Sget_simple_extent_dims(space, dims->data(), nullptr);
  hsize_t n = 1;
  for (hsize_t d : *dims) n *= d;
  std::vector<T> out(n);
  EXPECT_GE(H5Dread(dset, mem_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, out.data()), 0) << path;
  H5Sclose(space);
  H5Dclose(dset);
  return out;
}

double read_time_attribute(hid_t file) {
  double t = -1.0;
  const hid_t attr = H5Aopen(file, "time", H5P_DEFAULT);
  EXPECT_GE(attr, 0);
  if (attr < 0) return t;
  EXPECT_GE(H5Aread(attr, H5T_NATIVE_DOUBLE, &t), 0);
  H5Aclose(attr);
  return t;
}

TEST(SnapshotWriter, WritesTwoSnapshotsAndReadsBackExactly) {
  TempDir tmp;
  const fs::path dir = tmp.path() / "out" / "nested";  // created by the constructor
  const Block block(2, 2, 2);
  ASSERT_EQ(block.n_nodes(), 27);
  ASSERT_EQ(block.n_cells(), 8);

  SnapshotSeries series(dir.string(), "block");
  EXPECT_TRUE(fs::is_directory(dir));
  EXPECT_EQ(series.count(), 0);

  const double times[2] = {0.0, 0.1};
  std::vector<std::vector<double>> density(2), velocity(2);
  for (int s = 0; s < 2; ++s) {
    for (int c = 0; c < 8; ++c) {
      density[s].push_back(1.0 + c + 0.1 * s + 1e-13);  // not exactly representable sums
      for (int d = 0; d < 3; ++d) velocity[s].push_back((s + 1) * (10.0 * c + d) / 3.0);
    }
    const std::vector<CellField> fields = {{"density", density[s].data(), 1},
                                           {"velocity", velocity[s].data(), 3}};
    const std::string h5 = series.write(times[s], block.mesh(), fields);
    const std::string expected_name = s == 0 ? "block_00000.h5" : "block_00001.h5";
    EXPECT_EQ(fs::path(h5).filename().string(), expected_name);
    EXPECT_EQ(fs::path(h5).parent_path(), dir);
    EXPECT_EQ(series.count(), s + 1);
  }

  for (int s = 0; s < 2; ++s) {
    const std::string stem = s == 0 ? "block_00000" : "block_00001";
    const fs::path h5 = dir / (stem + ".h5");
    ASSERT_TRUE(fs::exists(h5));
    const hid_t file = H5Fopen(h5.string().c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
    ASSERT_GE(file, 0);

    EXPECT_EQ(read_time_attribute(file), times[s]);

    std::vector<hsize_t> dims;
    const auto xyz = read_dataset<double>(file, "/mesh/coordinates", H5T_NATIVE_DOUBLE, &dims);
    EXPECT_EQ(dims, (std::vector<hsize_t>{27, 3}));
    EXPECT_EQ(xyz, block.xyz);

    const auto conn =
        read_dataset<std::int64_t>(file, "/mesh/connectivity", H5T_NATIVE_INT64, &dims);
    EXPECT_EQ(dims, (std::vector<hsize_t>{8, 8}));
    EXPECT_EQ(conn, block.conn);

    const auto rho = read_dataset<double>(file, "/fields/density", H5T_NATIVE_DOUBLE, &dims);
    EXPECT_EQ(dims, (std::vector<hsize_t>{8}));
    EXPECT_EQ(rho, density[s]);

    const auto vel = read_dataset<double>(file, "/fields/velocity", H5T_NATIVE_DOUBLE, &dims);
    EXPECT_EQ(dims, (std::vector<hsize_t>{8, 3}));
    EXPECT_EQ(vel, velocity[s]);
    H5Fclose(file);

    // Per-snapshot XDMF.
    const fs::path xmf = dir / (stem + ".xmf");
    ASSERT_TRUE(fs::exists(xmf));
    const std::string x = slurp(xmf);
    EXPECT_NE(x.find("TopologyType=\"Hexahedron\""), std::string::npos);
    EXPECT_NE(x.find("NumberOfElements=\"8\""), std::string::npos);
    EXPECT_NE(x.find("GeometryType=\"XYZ\""), std::string::npos);
    EXPECT_NE(x.find("Dimensions=\"8 8\" NumberType=\"Int\" Precision=\"8\" Format=\"HDF\">" +
                     stem + ".h5:/mesh/connectivity<"),
              std::string::npos);
    EXPECT_NE(x.find("Dimensions=\"27 3\" NumberType=\"Float\" Precision=\"8\" Format=\"HDF\">" +
                     stem + ".h5:/mesh/coordinates<"),
              std::string::npos);
    EXPECT_NE(x.find("<Attribute Name=\"density\" AttributeType=\"Scalar\" Center=\"Cell\">"),
              std::string::npos);
    EXPECT_NE(x.find("Dimensions=\"8\" NumberType=\"Float\" Precision=\"8\" Format=\"HDF\">" +
                     stem + ".h5:/fields/density<"),
              std::string::npos);
    EXPECT_NE(x.find("<Attribute Name=\"velocity\" AttributeType=\"Vector\" Center=\"Cell\">"),
              std::string::npos);
    EXPECT_NE(x.find("Dimensions=\"8 3\" NumberType=\"Float\" Precision=\"8\" Format=\"HDF\">" +
                     stem + ".h5:/fields/velocity<"),
              std::string::npos);
    EXPECT_EQ(occurrences(x, ".h5:"), 4u);  // relative file name only, no directory
    EXPECT_EQ(x.find(dir.string()), std::string::npos);
  }

  // Temporal collection of both snapshots.
  const fs::path series_xmf = dir / "block.xmf";
  ASSERT_TRUE(fs::exists(series_xmf));
  EXPECT_EQ(series.series_xmf_path(), series_xmf.string());
  const std::string sx = slurp(series_xmf);
  EXPECT_NE(sx.find("GridType=\"Collection\" CollectionType=\"Temporal\""), std::string::npos);
  EXPECT_EQ(occurrences(sx, "<Time Value="), 2u);
  EXPECT_NE(sx.find("<Time Value=\"0\"/>"), std::string::npos);
  EXPECT_NE(sx.find("<Time Value=\"0.1\"/>"), std::string::npos);
  EXPECT_EQ(occurrences(sx, "block_00000.h5:"), 4u);
  EXPECT_EQ(occurrences(sx, "block_00001.h5:"), 4u);
  EXPECT_LT(sx.find("block_00000.h5"), sx.find("block_00001.h5"));
  EXPECT_FALSE(fs::exists(dir / "block.xmf.tmp"));
}

TEST(SnapshotWriter, TensorAttributeTypes) {
  TempDir tmp;
  const Block block(1, 1, 2);
  std::vector<double> t6(2 * 6), t9(2 * 9), m2(2 * 2);
  for (std::size_t i = 0; i < t6.size(); ++i) t6[i] = static_cast<double>(i);
  for (std::size_t i = 0; i < t9.size(); ++i) t9[i] = -static_cast<double>(i);
  for (std::size_t i = 0; i < m2.size(); ++i) m2[i] = 0.5 * static_cast<double>(i);
  SnapshotSeries series(tmp.path().string(), "t");
  const std::string h5 =
      series.write(2.5, block.mesh(),
                   {{"stress", t6.data(), 6}, {"grad_v", t9.data(), 9}, {"pair", m2.data(), 2}});

  const std::string x = slurp(tmp.path() / "t_00000.xmf");
  EXPECT_NE(x.find("<Attribute Name=\"stress\" AttributeType=\"Tensor6\" Center=\"Cell\">"),
            std::string::npos);
  EXPECT_NE(x.find("Dimensions=\"2 6\""), std::string::npos);
  EXPECT_NE(x.find("<Attribute Name=\"grad_v\" AttributeType=\"Tensor\" Center=\"Cell\">"),
            std::string::npos);
  EXPECT_NE(x.find("Dimensions=\"2 9\""), std::string::npos);
  EXPECT_NE(x.find("<Attribute Name=\"pair\" AttributeType=\"Matrix\" Center=\"Cell\">"),
            std::string::npos);
  EXPECT_NE(slurp(tmp.path() / "t.xmf").find("<Time Value=\"2.5\"/>"), std::string::npos);

  const hid_t file = H5Fopen(h5.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  ASSERT_GE(file, 0);
  std::vector<hsize_t> dims;
  EXPECT_EQ(read_dataset<double>(file, "/fields/stress", H5T_NATIVE_DOUBLE, &dims), t6);
  EXPECT_EQ(dims, (std::vector<hsize_t>{2, 6}));
  EXPECT_EQ(read_dataset<double>(file, "/fields/grad_v", H5T_NATIVE_DOUBLE, &dims), t9);
  EXPECT_EQ(dims, (std::vector<hsize_t>{2, 9}));
  H5Fclose(file);
}

TEST(SnapshotWriter, UnwritableDirectoryThrows) {
  TempDir tmp;
  // A path below a regular file can never be created, not even by root.
  const fs::path blocker = tmp.path() / "not_a_dir";
  std::ofstream(blocker) << "x";
  const std::string bad_dir = (blocker / "snapshots").string();
  try {
    SnapshotSeries series(bad_dir, "s");
    FAIL() << "constructor did not throw";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(bad_dir), std::string::npos) << e.what();
  }

  // Directory disappears (replaced by a file) after construction: write() must throw,
  // name the .h5 file, and leave the series unchanged.
  const fs::path dir = tmp.path() / "gone";
  SnapshotSeries series(dir.string(), "s");
  fs::remove(dir);
  std::ofstream(dir) << "x";
  const Block block(1, 1, 1);
  std::vector<double> rho(1, 1.0);
  try {
    series.write(0.0, block.mesh(), {{"rho", rho.data(), 1}});
    FAIL() << "write did not throw";
  } catch (const std::runtime_error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find((dir / "s_00000.h5").string()), std::string::npos) << what;
    EXPECT_EQ(what.find('\n'), std::string::npos) << what;
  }
  EXPECT_EQ(series.count(), 0);
}

// Fields and mesh arrays given by functions (packed one at a time into the
// writer's buffer) give the file that the same values given as arrays give;
// a filled connectivity is checked like a given one.
TEST(SnapshotWriter, FilledArraysWriteTheGivenArraysFile) {
  TempDir tmp;
  const Block block(3, 2, 2);
  std::vector<double> density, stress;
  for (std::int64_t c = 0; c < block.n_cells(); ++c) {
    density.push_back(1.0 / (3.0 + double(c)));
    for (int k = 0; k < 6; ++k) stress.push_back(double(c) - k / 7.0);
  }
  SnapshotSeries given(tmp.path().string(), "given"), filled(tmp.path().string(), "filled");
  given.write(0.25, block.mesh(), {{"density", density.data(), 1}, {"stress", stress.data(), 6}});
  const auto copy = [](const std::vector<double>& from) {
    return [&from](double* out) { std::copy(from.begin(), from.end(), out); };
  };
  SnapshotMesh mesh{block.n_nodes(), nullptr, block.n_cells(), nullptr};
  mesh.fill_node_xyz = copy(block.xyz);
  mesh.fill_cell_nodes = [&](std::int64_t* out) {
    std::copy(block.conn.begin(), block.conn.end(), out);
  };
  filled.write(0.25, mesh,
               {{"density", nullptr, 1, copy(density)}, {"stress", nullptr, 6, copy(stress)}});
  const auto read = [&](const char* name, const char* dataset) {
    const hid_t file = H5Fopen((tmp.path() / name).string().c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
    std::vector<hsize_t> dims;
    auto values = read_dataset<double>(file, dataset, H5T_NATIVE_DOUBLE, &dims);
    H5Fclose(file);
    return std::make_pair(values, dims);
  };
  for (const char* dataset :
       {"/mesh/coordinates", "/mesh/connectivity", "/fields/density", "/fields/stress"}) {
    const auto expected = read("given_00000.h5", dataset);
    EXPECT_FALSE(expected.first.empty()) << dataset;
    EXPECT_EQ(read("filled_00000.h5", dataset), expected) << dataset;
  }
  std::string xmf = slurp(tmp.path() / "filled_00000.xmf");
  for (std::size_t at; (at = xmf.find("filled_")) != std::string::npos;)
    xmf.replace(at, 7, "given_");
  EXPECT_EQ(xmf, slurp(tmp.path() / "given_00000.xmf"));

  mesh.fill_cell_nodes = [&](std::int64_t* out) {
    std::copy(block.conn.begin(), block.conn.end(), out);
    out[5] = block.n_nodes();  // one past the last node
  };
  EXPECT_THROW(filled.write(0.5, mesh, {{"density", nullptr, 1, copy(density)}}),
               std::invalid_argument);
  EXPECT_EQ(filled.count(), 1);
  EXPECT_FALSE(fs::exists(tmp.path() / "filled_00001.h5"));
}

TEST(SnapshotWriter, RejectsInvalidArguments) {
  TempDir tmp;
  EXPECT_THROW(SnapshotSeries(tmp.path().string(), ""), std::invalid_argument);
  EXPECT_THROW(SnapshotSeries(tmp.path().string(), "a/b"), std::invalid_argument);

  SnapshotSeries series(tmp.path().string(), "s");
  const Block block(1, 1, 1);
  std::vector<double> rho(1, 1.0);
  EXPECT_THROW(series.write(0.0, block.mesh(), {{"a/b", rho.data(), 1}}), std::invalid_argument);
  EXPECT_THROW(series.write(0.0, block.mesh(), {{"rho", rho.data(), 1}, {"rho", rho.data(), 1}}),
               std::invalid_argument);
  EXPECT_THROW(series.write(0.0, block.mesh(), {{"rho", rho.data(), 0}}), std::invalid_argument);
  Block broken = block;
  broken.conn[3] = 8;  // only nodes 0..7 exist
  EXPECT_THROW(series.write(0.0, broken.mesh(), {}), std::invalid_argument);
  EXPECT_EQ(series.count(), 0);
  EXPECT_FALSE(fs::exists(tmp.path() / "s_00000.h5"));
}

}  // namespace
