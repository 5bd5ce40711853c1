// Helpers shared by the tests: run the executable as a user would, and build a
// problem's run options through the library.
#pragma once

#include <sys/wait.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
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

// A fresh scratch directory for one test.
inline std::string scratchDir(const std::string& name) {
  const auto dir = std::filesystem::temp_directory_path() /
                   ("lagremap_test_" + std::to_string(::getpid()) + "_" + name);
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir.string();
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

// Run options of a built-in problem with `key=value` overrides; no files.
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
  return options;
}

}  // namespace lagremap::testing
