// Helpers shared by the tests: run the executable as a user would, and build a
// problem's run options through the library.
#pragma once

#include <hdf5.h>
#include <sys/wait.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "src/run.hpp"

namespace lagremap::testing {

struct CommandResult {
  int exit_code = -1;
  std::string output;  // stdout and stderr, merged
  std::string error;   // stderr only
};

// Runs `lagremap ARGS` in a shell; OMP_PROC_BIND is set so Kokkos prints no
// advice on stderr and stderr holds only lagremap's own messages.
// Lines of a program's output (a last line without its newline counts).
inline int lineCount(const std::string& text) {
  int lines = 0;
  for (char ch : text) lines += ch == '\n';
  return lines + (!text.empty() && text.back() != '\n');
}

inline CommandResult runLagremap(const std::string& args) {
  static int counter = 0;
  const std::string stem =
      (std::filesystem::temp_directory_path() /
       ("lagremap_cmd_" + std::to_string(::getpid()) + "_" + std::to_string(counter++)))
          .string();
  const std::string command = "OMP_PROC_BIND=false " + std::string(LAGREMAP_EXE) + " " + args +
                              " >" + stem + ".out 2>" + stem + ".err";
  const int status = std::system(command.c_str());
  CommandResult result;
  result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  auto slurp = [](const std::string& path) {
    std::ifstream in(path);
    std::stringstream text;
    text << in.rdbuf();
    return text.str();
  };
  result.error = slurp(stem + ".err");
  result.output = slurp(stem + ".out") + result.error;
  std::filesystem::remove(stem + ".out");
  std::filesystem::remove(stem + ".err");
  return result;
}

// The whole text of a file ("" if it cannot be read).
inline std::string readFile(const std::string& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// Flips bit `bit` of the byte at `offset` of file `path`, as a disk might.
inline void flipBit(const std::string& path, std::uint64_t offset, int bit) {
  std::fstream file(path, std::ios::in | std::ios::out | std::ios::binary);
  file.seekg(std::streamoff(offset));
  char byte = 0;
  file.get(byte);
  file.seekp(std::streamoff(offset));
  file.put(char(byte ^ (1 << bit)));
}

// Where value `index` of an HDF5 dataset of doubles (`name`, a path in the
// file) lies in the file: the dataset's contiguous data, 8 bytes a value.
inline std::uint64_t valueOffset(const std::string& path, const char* name, std::uint64_t index) {
  const hid_t file = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  const hid_t dataset = H5Dopen2(file, name, H5P_DEFAULT);
  const haddr_t offset = H5Dget_offset(dataset);
  H5Dclose(dataset);
  H5Fclose(file);
  return offset == HADDR_UNDEF ? 0 : offset + 8 * index;
}

// The doubles of an HDF5 dataset (`name`, a path in the file), flattened.
inline std::vector<double> readDoubles(const std::string& path, const char* name) {
  const hid_t file = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  const hid_t dataset = H5Dopen2(file, name, H5P_DEFAULT);
  const hid_t space = H5Dget_space(dataset);
  std::vector<double> values(std::size_t(H5Sget_simple_extent_npoints(space)));
  if (H5Dread(dataset, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data()) < 0) {
    values.clear();
  }
  H5Sclose(space);
  H5Dclose(dataset);
  H5Fclose(file);
  return values;
}

// A fresh scratch directory for one test.
// Host copies of named Views: a test's snapshot of fields, compared bit for
// bit (sameBits).
using HostFields = std::map<std::string, std::vector<double>>;
template <class View>
void addHostCopy(HostFields& fields, const char* name, const View& view) {
  if (view.span() == 0) return;
  const auto host = Kokkos::create_mirror_view_and_copy(HostSpace(), view);
  fields[name].assign(host.data(), host.data() + host.span());
}
inline bool sameBits(const std::vector<double>& a, const std::vector<double>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0;
}

inline std::string scratchDir(const std::string& name) {
  const auto dir = std::filesystem::temp_directory_path() /
                   ("lagremap_test_" + std::to_string(::getpid()) + "_" + name);
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir.string();
}

// A block of nx x ny x nz cells over [lo, hi] whose interior nodes are moved
// at random by up to `perturbation` of the local cell size.
inline BlockSpec perturbedBlock(int nx, int ny, int nz, const Vec3& lo, const Vec3& hi,
                                double perturbation) {
  BlockSpec block;
  block.nx = nx;
  block.ny = ny;
  block.nz = nz;
  block.lo = lo;
  block.hi = hi;
  block.perturbation = perturbation;
  return block;
}

// Every side of the box a wall (symmetry).
inline SideBoundaries allWalls() {
  SideBoundaries sides;
  for (auto& side : sides) side.kind = BoundaryKind::Wall;
  return sides;
}

// A block of one material in a uniform state, uploaded into a fresh State.
struct UniformBlock {
  ProblemSetup setup;
  State state;
};
inline UniformBlock uniformBlock(const BlockSpec& block, const SideBoundaries& sides,
                                 const MaterialParams& material, double rho, double e,
                                 const Vec3& velocity) {
  UniformBlock uniform;
  ProblemSetup& setup = uniform.setup;
  setup.mesh = buildBlockMesh(block, sides);
  setup.materials = {material};
  const Index n_cells = setup.mesh.n_cells;
  setup.cells.rho.assign(n_cells, rho);
  setup.cells.e.assign(n_cells, e);
  setup.cells.v.assign(n_cells, velocity);
  setup.cells.mat.assign(n_cells, 0);
  uniform.state = allocateState(setup.mesh, false);
  initializeState(setup, uniform.state);
  return uniform;
}

// Run options of a built-in problem with `key=value` overrides; no files;
// the final fields of the whole block on every rank (the tests compare them).
inline RunOptions problemOptions(const std::string& problem,
                                 const std::vector<std::string>& assignments = {},
                                 double scale = 1.0, const std::string& mode = "lagrange") {
  RunOptions options;
  options.problem = problem;
  options.mode = mode;
  options.config = declareConfig(findProblem(problem), mode);
  for (const auto& assignment : assignments) options.config.setAssignment(assignment);
  options.config.scaleCellCounts(scale);
  options.quiet = true;
  options.write_files = false;
  options.gather_final_fields = true;
  return options;
}

// A coarse, short `rod` (lagrange 20 x 3 x 3, remap 17 x 5 x 5) to `t_end`.
inline RunOptions coarseRodOptions(const std::string& mode, const std::string& t_end) {
  const std::vector<std::string> mesh =
      mode == "lagrange" ? std::vector<std::string>{"mesh.nx=20", "mesh.ny=3", "mesh.nz=3"}
                         : std::vector<std::string>{"mesh.nx=17", "mesh.ny=5", "mesh.nz=5"};
  std::vector<std::string> settings = mesh;
  settings.push_back("t_end=" + t_end);
  return problemOptions("rod", settings, 1.0, mode);
}

// Mass per material, x-momentum and energies of a run's state: of a problem's
// initial cells (the set-up rebuilt, m^k = alpha^k rho^k v as initializeState
// makes it) or of a run's final fields, summed independently of the audit.
struct StateTotals {
  std::vector<double> mass_k;
  double momentum_x = 0.0, kinetic = 0.0, internal = 0.0;
  double energy() const { return kinetic + internal; }
};

inline StateTotals initialTotals(const ProblemSetup& setup) {
  std::vector<double> volume;
  std::vector<Vec3> centroid;
  hostCellShapes(copyToHost(setup.mesh), volume, centroid);
  const std::size_t n_materials = setup.materials.size();
  StateTotals totals;
  totals.mass_k.assign(n_materials, 0.0);
  for (std::size_t c = 0; c < volume.size(); ++c) {
    double mass = 0.0;
    for (std::size_t k = 0; k < n_materials; ++k) {
      const std::size_t at = c * n_materials + k;
      const double m = setup.cells.alpha_k[at] * setup.cells.rho_k[at] * volume[c];
      totals.mass_k[k] += m;
      totals.internal += m * setup.cells.e_k[at];
      mass += m;
    }
    const Vec3 v = setup.cells.v[c];
    totals.momentum_x += mass * v.x;
    totals.kinetic += 0.5 * mass * dot(v, v);
  }
  return totals;
}

inline StateTotals finalTotals(const FinalFields& fields) {
  const Index n_materials = Index(fields.m_k.extent(1));
  StateTotals totals;
  totals.mass_k.assign(std::size_t(n_materials), 0.0);
  for (Index c = 0; c < Index(fields.m_k.extent(0)); ++c) {
    double mass = 0.0;
    for (Index k = 0; k < n_materials; ++k) {
      totals.mass_k[std::size_t(k)] += fields.m_k(c, k);
      totals.internal += fields.m_k(c, k) * fields.e_k(c, k);
      mass += fields.m_k(c, k);
    }
    const Vec3 v{fields.v(c, 0), fields.v(c, 1), fields.v(c, 2)};
    totals.momentum_x += mass * v.x;
    totals.kinetic += 0.5 * mass * dot(v, v);
  }
  return totals;
}

// Largest relative difference of every field of two runs' final states.
inline double maxRelativeDifference(const FinalFields& a, const FinalFields& b) {
  double worst = 0.0;
  auto compare = [&](const auto& x, const auto& y) {
    if (x.size() != y.size()) {
      worst = INFINITY;
      return;
    }
    for (std::size_t i = 0; i < x.size(); ++i) {
      const double u = x.data()[i], v = y.data()[i];
      if (u == v) continue;
      worst = std::max(worst, std::abs(u - v) / std::max(std::abs(u), std::abs(v)));
    }
  };
  compare(a.rho, b.rho);
  compare(a.p, b.p);
  compare(a.e, b.e);
  compare(a.vol, b.vol);
  compare(a.v, b.v);
  compare(a.x_c, b.x_c);
  compare(a.S, b.S);
  compare(a.alpha, b.alpha);
  compare(a.m_k, b.m_k);
  compare(a.e_k, b.e_k);
  compare(a.p_k, b.p_k);
  compare(a.eps_k, b.eps_k);
  compare(a.mesh.x_n, b.mesh.x_n);
  return worst;
}

}  // namespace lagremap::testing
