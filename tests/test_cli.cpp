// The command line as a user meets it: malformed input gives exit code 2 and
// one line naming the problem; a run that fails mid-way gives exit code 3, a
// one-line reason and the last good state on disk.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>
#include <utility>

#include "test_support.hpp"

namespace lagremap {
namespace {

using testing::lineCount;
using testing::runLagremap;

struct BadInput {
  const char* args;
  const char* expected;  // a word the message must contain
};

TEST(CommandLine, MalformedInputGivesExitCodeTwoAndOneLine) {
  const std::string dir = testing::scratchDir("cli_bad");
  const std::string deck = dir + "/broken.toml";
  std::ofstream(deck) << "[mesh]\nnx = [1, \n";
  const std::string wrong_key_deck = dir + "/wrong_key.toml";
  std::ofstream(wrong_key_deck) << "problem = \"sod\"\n[mesh]\nnq = 3\n";
  // Not text: a NUL byte, and a Latin-1 e-acute (not UTF-8), on the second line.
  const std::string nul_deck = dir + "/nul.toml";
  std::ofstream(nul_deck) << "problem = \"sod\"\n# a" << '\0' << "comment\n";
  const std::string latin1_deck = dir + "/latin1.toml";
  std::ofstream(latin1_deck) << "problem = \"sod\"\n# caf\xe9\n";
  // A number written as a string, and in hex: the deck reader took both as
  // numbers.
  const std::string string_deck = dir + "/string_number.toml";
  std::ofstream(string_deck) << "problem = \"sod\"\n[left]\nrho = \"2.0\"\n";
  const std::string hex_deck = dir + "/hex_number.toml";
  std::ofstream(hex_deck) << "problem = \"sod\"\n[mesh]\nnx = 0x40\n";
  const std::string out = " --output " + dir + "/out";
  const std::vector<BadInput> table = {
      {"", "--problem is required"},
      {"--problem nope", "unknown problem 'nope'"},
      {"--problem ball", "ball: lagrange mode is not available (the ball and the plate"},
      {"--problem ball --mode lagrange --print-config", "use --mode remap"},
      {"--problem sod --mode remap --set remap.beta=3", "remap.beta must be in [1, 2]"},
      {"--problem sod --mode ale --set ale.weight=2", "ale.weight must be in [0, 1]"},
      {"--problem sod --mode ale --set ale.every=0", "ale.every must be at least 1"},
      {"--problem sod --mode ale --set ale.max_move=0", "ale.max_move must be in (0, 1]"},
      {"--problem sod --mode ale --set ale.rule=laplace", "ale.rule"},
      {"--problem sod --set ale.weight=1", "unknown key 'ale.weight'"},
      {"--problem sod --scale -1", "--scale"},
      {"--problem sod --scale abc", "--scale: 'abc' is not a number"},
      {"--problem sod --scale 0", "--scale: must be positive, got 0"},
      {"--problem sod --cfl 2", "--cfl: must be between 1e-06 and 1, got 2"},
      {"--problem sod --output-every -1", "--output-every: must be non-negative, got -1"},
      {"--problem sod --set nokey=1", "unknown key 'nokey'"},
      {"--problem sod --set mesh.nx=abc", "mesh.nx"},
      {"--problem sod --set mesh.nx=0", "mesh"},
      {"--problem sod --set numerics.cfl=2", "numerics.cfl"},
      {"--problem sod --set numerics.dt_drop_fraction=1.5", "numerics.dt_drop_fraction"},
      {"--problem sod --set numerics.dt_min_fraction=-1", "numerics.dt_min_fraction"},
      // A floor above the first step: the run would stop at once (time step
      // collapse), whether the floor is too high or t_end beyond what it resolves.
      {"--problem sod --set numerics.dt_min_fraction=0.5", "numerics.dt_min_fraction x t_end"},
      {"--problem sod --t-end 1e300", "t_end can be at most"},
      {"--problem wilkins --set al.Gamma0=-1", "Gamma0 must be > 0"},
      {"--problem sod --set check.l1_density_bound=-1", "check.l1_density_bound must be >= 0"},
      {"--problem sod --set =3", "key=value"},
      {"--problem sod --set bc.xmin=sticky", "bc.xmin"},
      {"--problem sod --set left.rho=-1", "densities"},
      {"--problem sod --order 3", "--order"},
      {"--problem sod --mode euler", "--mode"},
      {"--problem sod --t-end -1", "--t-end"},
      {"--problem sod --input /nonexistent/deck.toml", "--input"},
      {"--problem sod --input /dev/zero", "not a regular file"},
      {"--problem sod --input /dev/urandom", "not a regular file"},
      {"--problem sod --scale 1e300", "mesh.nx = 2e+302"},
      {"--problem sod --bogus-flag", "bogus"},
      {"--problem", "--problem"},
      {"--problem sod --output-times 0.5", "output time"},
      {"--problem sod --output-times 1e-9,0.25", "0.25 s is outside [0, t_end = 0.2 s]"},
      {"--problem sod --set gas.gamma=1", "gamma"},
      {"--problem sod --set geometry.x_interface=3", "x_interface"},
      {"--problem sod --set mesh.nx=100000000", "GB"},
      {"--output /proc/no/such/dir --problem sod", "output directory"},
      // (an unset shell variable: not the default out/sod)
      {"--output '' --problem sod", "--output: must not be empty"},
      {"--restart '' --problem sod", "--restart: must not be empty"},
      // Kokkos' own flags, checked before Kokkos reads them (it aborted with
      // two dozen lines; beyond 512 threads its OpenMP back-end crashed)
      {"--problem sod --kokkos-threads=-3", "--kokkos-threads=-3: must be at least 1"},
      {"--problem sod --kokkos-threads=abc", "--kokkos-threads=abc: expects a whole number"},
      {"--problem sod --kokkos-threads", "expects --kokkos-threads=N"},
      {"--problem sod --kokkos-num-threads=-1", "--kokkos-num-threads=-1: must be at least 1"},
      {"--problem sod --kokkos-device-id=-5", "--kokkos-device-id=-5: must be at least 0"},
      {"--problem sod --kokkos-num-devices=-1", "--kokkos-num-devices=-1: must be at least 1"},
      {"--problem sod --scale 0.25 --kokkos-threads=5000", "at most 512 threads"},
      // (it said "t_end can be at most 0 s": the geometry's products overflowed)
      {"--problem rod --set rod.length=1e300", "rod.length = 1e+300 m is out of range"},
      // Decimal numbers only (strtod took hex, leading blanks, "infinity")
      {"--problem sod --set left.rho=0x1p1", "bad value '0x1p1' for key 'left.rho'"},
      {"--problem sod --set 'left.rho= 2'", "bad value ' 2' for key 'left.rho'"},
      {"--problem sod --set mesh.nx=' 40'", "bad value ' 40' for key 'mesh.nx'"},
  };
  for (const BadInput& bad : table) {
    const std::string args = bad.args;
    const bool runs =
        args.rfind("--problem sod", 0) == 0 || args.rfind("--problem wilkins", 0) == 0;
    const auto result = runLagremap(args + (runs ? out : ""));
    EXPECT_EQ(result.exit_code, 2) << bad.args << "\n" << result.output;
    EXPECT_EQ(lineCount(result.error), 1) << bad.args << "\n" << result.error;
    EXPECT_LT(result.error.size(), 300u) << bad.args << ": a line a user can read\n"
                                         << result.error;
    EXPECT_NE(result.error.find("lagremap: error:"), std::string::npos) << result.error;
    EXPECT_NE(result.error.find(bad.expected), std::string::npos)
        << bad.args << ": '" << result.error << "' does not mention '" << bad.expected << "'";
  }
  for (const std::string& file :
       {deck, wrong_key_deck, nul_deck, latin1_deck, string_deck, hex_deck}) {
    const auto result = runLagremap("--input " + file + out);
    EXPECT_EQ(result.exit_code, 2) << result.output;
    EXPECT_EQ(lineCount(result.error), 1) << result.error;
    EXPECT_NE(result.error.find(file), std::string::npos) << result.error;
  }
  for (const std::string& file : {nul_deck, latin1_deck}) {
    const auto result = runLagremap("--input " + file + out);
    EXPECT_NE(result.error.find("line 2:"), std::string::npos) << result.error;
  }
  EXPECT_NE(runLagremap("--input " + string_deck + out)
                .error.find("key 'left.rho' is a number; the deck gives the string \"2.0\""),
            std::string::npos);
  EXPECT_NE(runLagremap("--input " + hex_deck + out)
                .error.find("key 'mesh.nx': write the number in decimal"),
            std::string::npos);
  std::filesystem::remove_all(dir);
}

// A path of 5,000 characters in an error is cut to its first and last 60 (the line
// was 5,070 characters), and --restart given a directory says so (it said
// "does not exist").
TEST(CommandLine, ALongPathIsCutAndADirectoryIsNoCheckpoint) {
  const std::string dir = testing::scratchDir("cli_paths");
  const std::string long_path = dir + "/" + std::string(5000, 'a');
  auto result = runLagremap("--problem sod --restart " + long_path + " --output " + dir + "/out");
  EXPECT_EQ(result.exit_code, 2) << result.output;
  EXPECT_EQ(lineCount(result.error), 1) << result.error;
  EXPECT_LT(result.error.size(), 300u) << result.error.size();
  EXPECT_NE(result.error.find("cannot be read: File name too long"), std::string::npos)
      << result.error;
  result = runLagremap("--problem sod --restart " + dir + " --output " + dir + "/out");
  EXPECT_EQ(result.exit_code, 2) << result.output;
  EXPECT_NE(result.error.find("is a directory, not a checkpoint file"), std::string::npos)
      << result.error;
  std::filesystem::remove_all(dir);
}

// SIGTERM (a batch scheduler's notice) stops the run at the end of the step
// under way: exit code 4, one line, the checkpoint and the outputs written,
// summary.json "stopped"; the checkpoint restarts.
TEST(CommandLine, ASignalStopsTheRunWithItsCheckpoint) {
  const std::string dir = testing::scratchDir("cli_signal");
  const std::string out = dir + "/out";
  const std::string command =
      "(OMP_PROC_BIND=false OMP_NUM_THREADS=1 " + std::string(LAGREMAP_EXE) +
      " --problem sedov --quiet --output " + out + " >" + dir + "/stdout 2>" + dir +
      "/stderr & pid=$!; sleep 2; kill -TERM $pid; wait $pid; echo $? >" + dir + "/rc)";
  ASSERT_EQ(std::system(command.c_str()), 0);
  EXPECT_EQ(testing::readFile(dir + "/rc"), "4\n");
  const std::string error = testing::readFile(dir + "/stderr");
  EXPECT_EQ(lineCount(error), 1) << error;
  EXPECT_NE(error.find("stopped by SIGTERM"), std::string::npos) << error;
  EXPECT_NE(testing::readFile(out + "/summary.json").find("\"status\": \"stopped\""),
            std::string::npos);
  ASSERT_TRUE(std::filesystem::exists(out + "/checkpoint.h5"));
  const auto restarted =
      runLagremap("--problem sedov --quiet --output " + out +
                  " --set numerics.max_steps=1 --restart " + out + "/checkpoint.h5");
  EXPECT_NE(restarted.error.find("numerics.max_steps reached"), std::string::npos)
      << restarted.output;
  std::filesystem::remove_all(dir);
}

// OMP_NUM_THREADS beyond what Kokkos' OpenMP back-end holds is bad input
// too, even beside a thread-count flag (the back-end sizes its pool by it:
// both crashed with a segmentation fault); at 512 it runs.
TEST(CommandLine, TooManyOpenMPThreadsIsBadInput) {
  const std::string dir = testing::scratchDir("cli_omp");
  const char* saved = std::getenv("OMP_NUM_THREADS");
  const std::string kept = saved ? saved : "";
  setenv("OMP_NUM_THREADS", "100000", 1);
  auto result = runLagremap("--problem sod --scale 0.25 --quiet --output " + dir + "/out");
  EXPECT_EQ(result.exit_code, 2) << result.output;
  EXPECT_EQ(lineCount(result.error), 1) << result.error;
  EXPECT_NE(result.error.find("OMP_NUM_THREADS=100000: at most 512 threads"), std::string::npos)
      << result.error;
  result =
      runLagremap("--problem sod --scale 0.25 --quiet --kokkos-threads=1 --output " + dir + "/out");
  EXPECT_EQ(result.exit_code, 2) << result.output;
  setenv("OMP_NUM_THREADS", "512", 1);
  result =
      runLagremap("--problem sod --scale 0.25 --quiet --kokkos-threads=2 --output " + dir + "/out");
  EXPECT_EQ(result.exit_code, 0) << result.output;
  if (saved) {
    setenv("OMP_NUM_THREADS", kept.c_str(), 1);
  } else {
    unsetenv("OMP_NUM_THREADS");
  }
  std::filesystem::remove_all(dir);
}

// A result file that cannot be written is a failure, never a silent exit 0:
// with a directory standing where summary.json or the problem's CSV goes, the run
// exits 3 with one line naming the file.
TEST(CommandLine, AResultFileThatCannotBeWrittenFailsTheRun) {
  const std::string dir = testing::scratchDir("cli_unwritable");
  for (const char* file : {"summary.json", "sod_profile.csv"}) {
    const std::string out = dir + "/" + file + "_blocked";
    std::filesystem::create_directories(out + "/" + file);
    const auto result = runLagremap("--problem sod --scale 0.25 --quiet --output " + out);
    EXPECT_EQ(result.exit_code, 3) << file << "\n" << result.output;
    EXPECT_EQ(lineCount(result.error), 1) << result.error;
    EXPECT_NE(result.error.find("cannot write " + out + "/" + file), std::string::npos)
        << result.error;
  }
  std::filesystem::remove_all(dir);
}

// A value of 100 kB (a pasted file, a runaway script) is cut in the error
// line to its first 60 characters and "...", whatever option, key or deck
// carried it; the rest of the line still says what was wrong with it.
TEST(CommandLine, ALongValueIsCutInTheErrorLine) {
  const std::string dir = testing::scratchDir("cli_long");
  const std::string value(100000, '7');
  const std::string spaced = "1" + std::string(100000, ' ') + "2";
  const std::string deck = dir + "/long.toml";
  std::ofstream(deck) << "problem = \"sod\"\n[left]\np = \"" << value << "\"\n";
  const std::vector<std::pair<std::string, const char*>> cases = {
      {"--problem sod --set left.p=x" + value, "for key 'left.p'"},
      {"--problem sod --set x" + value + "=1", "unknown key"},
      {"--problem sod --set bc.xmin=x" + value, "for key 'bc.xmin'"},
      {"--problem x" + value, "unknown problem"},
      {"--problem sod --mode x" + value, "--mode"},
      {"--problem sod --scale x" + value, "is not a number"},
      {"--problem sod --cfl 7" + value, "--cfl: must be between"},
      {"--problem sod --order x" + value, "--order"},
      {"--problem sod --output-times 0.1,x" + value, "--output-times"},
      {"--problem sod --x" + value, "not expected"},
      {"--problem sod --mode '" + spaced + "'", "--mode"},
      {"--input " + deck, "key 'left.p'"},
  };
  for (const auto& [args, expected] : cases) {
    const auto result = runLagremap(args + " --output " + dir + "/out");
    const std::string shown = args.substr(0, 40);
    EXPECT_EQ(result.exit_code, 2) << shown << "\n" << result.output.substr(0, 400);
    EXPECT_EQ(lineCount(result.error), 1) << shown;
    EXPECT_LT(result.error.size(), 300u) << shown << "\n" << result.error.substr(0, 400);
    EXPECT_NE(result.error.find(expected), std::string::npos) << shown << "\n" << result.error;
  }
  const auto cut = runLagremap("--problem sod --set left.p=x" + value);
  EXPECT_NE(cut.error.find("'x" + value.substr(0, 59) + "...'"), std::string::npos) << cut.error;
  std::filesystem::remove_all(dir);
}

// A first run prints only lagremap's own lines: no Kokkos advice about
// OMP_PROC_BIND when it is not set (runLagremap sets it, so this shell does not).
TEST(CommandLine, PlainRunWithoutBindingVariablesIsQuiet) {
  const std::string dir = testing::scratchDir("cli_quiet");
  const std::string command = "env -u OMP_PROC_BIND -u OMP_PLACES " + std::string(LAGREMAP_EXE) +
                              " --problem sod --scale 0.25 --quiet --output " + dir + "/out > " +
                              dir + "/stdout 2> " + dir + "/stderr";
  ASSERT_EQ(std::system(command.c_str()), 0);
  std::ifstream err(dir + "/stderr"), out(dir + "/stdout");
  const std::string error((std::istreambuf_iterator<char>(err)), std::istreambuf_iterator<char>());
  const std::string output((std::istreambuf_iterator<char>(out)), std::istreambuf_iterator<char>());
  EXPECT_EQ(error, "");
  EXPECT_EQ(output.find("Kokkos"), std::string::npos) << output;
  EXPECT_EQ(output.rfind("lagremap: sod", 0), 0u) << output;
  std::filesystem::remove_all(dir);
}

// --scale multiplies cell counts and divides a one-cell slab's thickness left
// at its default (the slab stays one cell thick, so it does not set the time
// step of a coarser run); a thickness the user sets is kept.
TEST(CommandLine, ScaleKeepsASlabOneCellThick) {
  Config config;
  config.addInteger("mesh.nx", 200, "cells", true);
  config.addCellLength("geometry.thickness", 0.025, "one cell");
  config.scaleCellCounts(0.5);
  EXPECT_EQ(config.integer("mesh.nx"), 100);
  EXPECT_DOUBLE_EQ(config.real("geometry.thickness"), 0.05);
  Config set_by_user;
  set_by_user.addCellLength("geometry.thickness", 0.025, "one cell");
  set_by_user.set("geometry.thickness", "0.01");
  set_by_user.scaleCellCounts(0.5);
  EXPECT_DOUBLE_EQ(set_by_user.real("geometry.thickness"), 0.01);
  // A half-resolution taylor run's slab is one of its cells thick (0.05 m).
  const auto half = runLagremap("--problem taylor --scale 0.5 --print-config");
  EXPECT_NE(half.output.find("geometry.thickness=0.05 "), std::string::npos) << half.output;
}

TEST(CommandLine, ListHelpAndPrintConfig) {
  const auto list = runLagremap("--list");
  EXPECT_EQ(list.exit_code, 0);
  EXPECT_NE(list.output.find("sod"), std::string::npos);
  EXPECT_NE(list.output.find("sedov"), std::string::npos);
  // --help (and -h) is lagremap's usage from its first line, without Kokkos'
  // own help, which --kokkos-help prints alone.
  for (const char* flag : {"--help", "-h", "--problem sod --help"}) {
    const auto help = runLagremap(flag);
    EXPECT_EQ(help.exit_code, 0) << flag;
    EXPECT_EQ(help.output.rfind("lagremap: 3D cell-centred", 0), 0u) << flag << "\n" << help.output;
    EXPECT_NE(help.output.find("--print-config"), std::string::npos) << flag;
    EXPECT_EQ(help.output.find("Kokkos command line arguments"), std::string::npos) << flag;
  }
  const auto kokkos_help = runLagremap("--kokkos-help");
  EXPECT_EQ(kokkos_help.exit_code, 0) << kokkos_help.output;
  EXPECT_NE(kokkos_help.output.find("--kokkos-help"), std::string::npos) << kokkos_help.output;
  EXPECT_EQ(kokkos_help.output.find("--print-config"), std::string::npos) << kokkos_help.output;
  const auto config = runLagremap(
      "--problem sod --scale 2 --set left.p=3 --t-end 2.5e-7 --cfl 0.25 --print-config");
  EXPECT_EQ(config.exit_code, 0);
  for (const char* line : {"mesh.nx=400", "left.p=3", "bc.xmin=wall", "gas.gamma=1.4",
                           "t_end=2.5e-07", "numerics.cfl=0.25", "[Pa]"}) {
    EXPECT_NE(config.output.find(line), std::string::npos) << line << "\n" << config.output;
  }
}

TEST(CommandLine, DeckAndCommandLineCombine) {
  const std::string dir = testing::scratchDir("cli_deck");
  const std::string deck = dir + "/sod.toml";
  std::ofstream(deck) << "problem = \"sod\"\nt_end = 0.1\n[mesh]\nnx = 50\n[numerics]\norder = 1\n";
  const auto result = runLagremap("--input " + deck + " --set mesh.nx=60 --print-config");
  EXPECT_EQ(result.exit_code, 0) << result.output;
  EXPECT_NE(result.output.find("t_end=0.1"), std::string::npos);
  EXPECT_NE(result.output.find("mesh.nx=60"), std::string::npos);  // the command line wins
  EXPECT_NE(result.output.find("numerics.order=1"), std::string::npos);
  std::filesystem::remove_all(dir);
}

TEST(CommandLine, SodRunWritesSummaryWithPassingChecks) {
  const std::string dir = testing::scratchDir("cli_sod");
  const auto result = runLagremap("--problem sod --quiet --output " + dir);
  ASSERT_EQ(result.exit_code, 0) << result.output;
  EXPECT_NE(result.output.find("FOM:"), std::string::npos);
  std::ifstream summary(dir + "/summary.json");
  std::stringstream text;
  text << summary.rdbuf();
  const std::string json = text.str();
  for (const char* field :
       {"\"problem\": \"sod\"", "\"checks\"", "\"l1_density\"", "\"cell_steps_per_second\"",
        "\"drift\"", "\"status\": \"completed\""}) {
    EXPECT_NE(json.find(field), std::string::npos) << field;
  }
  EXPECT_EQ(json.find("\"pass\": false"), std::string::npos) << json;
  // l1_errors, the norms against the exact solution (scripts/convergence.py
  // reads them): its density is the l1_density check's value, to the bit
  const std::size_t errors = json.find("\"l1_errors\": {");
  ASSERT_NE(errors, std::string::npos) << json;
  const std::string block = json.substr(errors, json.find('}', errors) - errors);
  auto numberAfter = [](const std::string& text, const std::string& field, std::size_t from) {
    const std::size_t at = text.find("\"" + field + "\": ", from);
    return at == std::string::npos ? NAN : std::stod(text.substr(at + field.size() + 4));
  };
  const double check = numberAfter(json, "value", json.find("\"l1_density\": {"));
  EXPECT_GT(check, 0.0);
  EXPECT_EQ(numberAfter(block, "density", 0), check) << block;
  EXPECT_GT(numberAfter(block, "velocity", 0), 0.0) << block;
  EXPECT_GT(numberAfter(block, "pressure", 0), 0.0) << block;
  EXPECT_NE(block.find("\"note\": \"integral over the bar"), std::string::npos) << block;
  // the mesh quality, final and lowest, and per step in history.csv (a bar
  // of boxes: right angles, 1)
  const double quality = numberAfter(json, "min_scaled_jacobian", json.find("\"mesh_quality\""));
  EXPECT_GT(quality, 0.999) << json;
  EXPECT_LE(quality, 1.0);
  std::ifstream history(dir + "/history.csv");
  std::string header, line, last;
  std::getline(history, header);
  while (std::getline(history, line)) last = line;
  EXPECT_EQ(header.substr(header.rfind(',') + 1), "min_scaled_jacobian");
  EXPECT_EQ(std::stod(last.substr(last.rfind(',') + 1)), quality);
  for (const char* file :
       {"history.csv", "sod_profile.csv", "fields.xmf", "fields_00000.h5", "fields_00001.h5"}) {
    EXPECT_TRUE(std::filesystem::exists(dir + "/" + file)) << file;
  }
  std::filesystem::remove_all(dir);
}

// A short multi-material remap run (the bar in gas on a coarse box) reports
// its interfaces in summary.json and per-material fields in its snapshots.
TEST(CommandLine, RemapRunReportsItsInterfaces) {
  const std::string dir = testing::scratchDir("cli_remap");
  const auto result = runLagremap(
      "--problem taylor --mode remap --set mesh.nx=22 --set mesh.ny=8 --t-end 2e-4 --quiet "
      "--output " +
      dir);
  // a 2e-4 s run is not the paper's case: its end-state checks do not apply
  // (exit 0, each said "n/a" with its reason), rather than a failure
  ASSERT_EQ(result.exit_code, 0) << result.output;
  EXPECT_NE(result.output.find("n/a"), std::string::npos) << result.output;
  std::ifstream summary(dir + "/summary.json");
  std::stringstream text;
  text << summary.rdbuf();
  const std::string json = text.str();
  for (const char* field :
       {"\"mode\": \"remap\"", "\"interfaces\"", "\"material_0\"", "\"mixed_cells_per_unit_area\"",
        "\"smeared_width\"", "\"solid\": true", "\"solid\": false"}) {
    EXPECT_NE(json.find(field), std::string::npos) << field;
  }
  // The alpha = 1/2 surface is the bar's outline off the wall (5 + 5 + 1 m) in
  // a 0.025 m thick slab.
  const std::size_t at = json.find("\"area\": ");
  ASSERT_NE(at, std::string::npos);
  EXPECT_NEAR(std::stod(json.substr(at + 8)), 11.0 * 0.025, 0.2 * 11.0 * 0.025);
  // The final length sits next to the paper's Lagrange (4.62) and remap
  // (4.63) lengths; the kinetic energy's reference (0) is that of both modes.
  for (const auto& [field, number] :
       {std::pair<const char*, double>{"\"lagrange_reference\": ", 4.62}, {"\"paper\": ", 4.63}}) {
    const std::size_t where = json.find(field, json.find("\"final_length\""));
    ASSERT_NE(where, std::string::npos) << field;
    EXPECT_DOUBLE_EQ(std::stod(json.substr(where + std::strlen(field))), number) << field;
  }
  const std::size_t kinetic = json.find("\"kinetic_fraction\"");
  ASSERT_NE(kinetic, std::string::npos);
  EXPECT_NE(json.find("\"lagrange_reference\": 0", kinetic), std::string::npos);
  std::filesystem::remove_all(dir);
}

// Checks follow the run's parameters: references computed for another
// speed (not the default case's numbers) pass, a paper-only reference is
// marked as not applying with its reason, and exit code 1 still means an
// applicable check failed.
TEST(CommandLine, ChecksFollowTheParameters) {
  const std::string dir = testing::scratchDir("cli_params");
  auto checkOf = [](const std::string& json, const std::string& name) {
    const std::size_t at = json.find("\"" + name + "\"");
    return at == std::string::npos ? std::string() : json.substr(at, json.find('}', at) - at);
  };
  auto numberAfter = [](const std::string& text, const std::string& field) {
    const std::size_t at = text.find("\"" + field + "\": ");
    return at == std::string::npos ? NAN : std::stod(text.substr(at + field.size() + 4));
  };
  // wilkins at 1200 m/s: the exact two-wave state of that speed
  auto wilkins =
      runLagremap("--problem wilkins --set flyer.vx=1200 --quiet --output " + dir + "/w");
  EXPECT_EQ(wilkins.exit_code, 0) << wilkins.output;
  const std::string w_json = testing::readFile(dir + "/w/summary.json");
  const std::string sigma = checkOf(w_json, "plastic_sigma_xx");
  EXPECT_NEAR(numberAfter(sigma, "reference"), -1.0345e10, 0.001e10) << sigma;
  EXPECT_NE(sigma.find("\"source\": \"exact two-wave solution\""), std::string::npos) << sigma;
  EXPECT_NEAR(numberAfter(checkOf(w_json, "plastic_velocity"), "reference"), 600.0, 1e-6);
  // shell at 250 m/s (coarse polar mesh): Howell and Ball's radii for that speed
  auto shell =
      runLagremap("--problem shell --scale 0.5 --set shell.v0=250 --quiet --output " + dir + "/s");
  EXPECT_EQ(shell.exit_code, 0) << shell.output;
  const std::string s_json = testing::readFile(dir + "/s/summary.json");
  EXPECT_NEAR(numberAfter(checkOf(s_json, "stopping_inner_radius"), "reference"), 0.06843, 1e-4);
  EXPECT_NEAR(numberAfter(checkOf(s_json, "stopping_outer_radius"), "reference"), 0.09101, 1e-4);
  EXPECT_NE(checkOf(s_json, "final_inward_speed").find("\"applies\": true"), std::string::npos);
  // taylor with another bar speed: the paper's length does not apply, and says why
  auto taylor =
      runLagremap("--problem taylor --scale 0.25 --set bar.vx=-100 --t-end 2e-4 --quiet --output " +
                  dir + "/t");
  EXPECT_EQ(taylor.exit_code, 0) << taylor.output;
  const std::string length = checkOf(testing::readFile(dir + "/t/summary.json"), "final_length");
  EXPECT_NE(length.find("\"applies\": false"), std::string::npos) << length;
  EXPECT_NE(length.find("this run has bar.vx = "), std::string::npos) << length;
  // sod, sedov and pile follow their states, energy and load (and pass)
  auto sod = runLagremap("--problem sod --set left.p=2 --set left.rho=1.5 --quiet --output " + dir +
                         "/sod");
  EXPECT_EQ(sod.exit_code, 0) << sod.output;
  auto sedov = runLagremap("--problem sedov --scale 0.5 --set blast.energy=1.2 --quiet --output " +
                           dir + "/sedov");
  EXPECT_EQ(sedov.exit_code, 0) << sedov.output;
  const std::string radius =
      checkOf(testing::readFile(dir + "/sedov/summary.json"), "shock_radius");
  EXPECT_GT(numberAfter(radius, "reference"), 1.05) << radius;  // the default E gives 1
  auto pile =
      runLagremap("--problem pile --set bc.xmax.sigma_xx=-2e7 --quiet --output " + dir + "/pile");
  EXPECT_EQ(pile.exit_code, 0) << pile.output;
  const std::string plateau =
      checkOf(testing::readFile(dir + "/pile/summary.json"), "wall_stress_plateau");
  EXPECT_NEAR(numberAfter(plateau, "reference"), -4e7, 1.0) << plateau;
  // an applicable check that fails is still exit code 1
  auto failing =
      runLagremap("--problem sod --set check.l1_density_bound=1e-9 --quiet --output " + dir + "/f");
  EXPECT_EQ(failing.exit_code, 1) << failing.output;
  std::filesystem::remove_all(dir);
}

// Snapshots at the requested times (hit exactly) plus the initial and final
// states, listed in the series file ParaView opens.
TEST(CommandLine, SnapshotsAtRequestedTimes) {
  const std::string dir = testing::scratchDir("cli_snapshots");
  const auto result = runLagremap("--problem sod --quiet --output-times 0.05,0.1 --output " + dir);
  ASSERT_EQ(result.exit_code, 0) << result.output;
  for (const char* file :
       {"fields_00000.h5", "fields_00001.h5", "fields_00002.h5", "fields_00003.h5", "fields.xmf"}) {
    EXPECT_TRUE(std::filesystem::exists(dir + "/" + file)) << file;
  }
  EXPECT_FALSE(std::filesystem::exists(dir + "/fields_00004.h5"));
  std::ifstream series(dir + "/fields.xmf");
  std::stringstream text;
  text << series.rdbuf();
  for (const char* time : {"\"0\"", "\"0.05\"", "\"0.1\"", "\"0.2\""}) {
    EXPECT_NE(text.str().find(std::string("Value=") + time), std::string::npos) << time;
  }
  std::filesystem::remove_all(dir);
}

// Snapshot times in any order, a time given twice, or closer to another (or
// to the start) than the run's smallest step (numerics.dt_min_fraction x
// t_end): one snapshot each, in time order. Given twice, a time once asked
// for a zero step and stopped the run (sod: "time step collapse, dt = 0";
// taylor in remap mode: a NaN energy).
TEST(CommandLine, RepeatedAndUnsortedOutputTimesAreOneSnapshotEach) {
  const std::string dir = testing::scratchDir("cli_repeated_times");
  const auto sod = runLagremap(
      "--problem sod --scale 0.25 --quiet --output-times "
      "0.1,0.05,0.1,1e-20,0.1000000000000001 --output " +
      dir + "/sod");
  ASSERT_EQ(sod.exit_code, 0) << sod.output;
  const std::string series = testing::readFile(dir + "/sod/fields.xmf");
  std::string times;
  for (std::size_t at = series.find("Value=\""); at != std::string::npos;
       at = series.find("Value=\"", at + 1)) {
    times += series.substr(at + 7, series.find('"', at + 7) - at - 7) + " ";
  }
  EXPECT_EQ(times, "0 0.05 0.1 0.2 ") << series;
  EXPECT_FALSE(std::filesystem::exists(dir + "/sod/fields_00004.h5"));
  const auto taylor = runLagremap(
      "--problem taylor --mode remap --scale 0.25 --t-end 0.0005 --output-times 0.0001,0.0001 "
      "--quiet --output " +
      dir + "/taylor");
  EXPECT_EQ(taylor.exit_code, 0) << taylor.output;
  std::filesystem::remove_all(dir);
}

// A problem's own snapshot times when the command line gives none: `ball`
// writes verification.md §8.7's every 0.5 us (those up to the run's t_end).
TEST(CommandLine, ProblemsOwnSnapshotTimes) {
  const std::string dir = testing::scratchDir("cli_default_snapshots");
  const auto result = runLagremap(
      "--problem ball --mode remap --scale 0.25 --set geometry.thickness=1e-4 --t-end 1.2e-6 "
      "--quiet --output " +
      dir);
  ASSERT_TRUE(result.exit_code == 0 || result.exit_code == 1) << result.output;
  for (const char* file : {"fields_00000.h5", "fields_00001.h5", "fields_00002.h5",
                           "fields_00003.h5", "ball_centroid.csv", "ball_axis.csv"}) {
    EXPECT_TRUE(std::filesystem::exists(dir + "/" + file)) << file;
  }
  EXPECT_FALSE(std::filesystem::exists(dir + "/fields_00004.h5"));
  std::ifstream series(dir + "/fields.xmf");
  std::stringstream text;
  text << series.rdbuf();
  for (const char* time : {"\"5e-07\"", "\"1e-06\"", "\"1.2e-06\""}) {
    EXPECT_NE(text.str().find(std::string("Value=") + time), std::string::npos) << time;
  }
  std::filesystem::remove_all(dir);
}

// Mid-run failures stop with exit code 3, one line naming step and reason, and
// the last good state written (summary with status "failed" and a snapshot).
TEST(CommandLine, FailureMidRunGivesExitCodeThreeAndWritesLastGoodState) {
  const std::string dir = testing::scratchDir("cli_fail");
  struct Failure {
    std::string args, reason;
  };
  const std::vector<Failure> failures = {
      {"--problem sod --set numerics.max_steps=5", "max_steps"},
      // A dt floor between sedov's first two steps: the first, the whole
      // stable dt (dt_initial_factor 1, 0.0106 s), passes; the second,
      // limited by the volume change (0.00193 s), collapses below 0.005 s.
      {"--problem sedov --scale 0.3 --set numerics.dt_initial_factor=1 "
       "--set numerics.dt_min_fraction=0.005",
       "step 2: time step collapse, dt = 0.00193"},
      // Sedov's stable dt falls to 0.75 of its largest in the first steps
      // (the blast leaves its cell): a 0.9 drop limit stops it, with the
      // fraction named.
      {"--problem sedov --scale 0.3 --set numerics.dt_drop_fraction=0.9",
       "time step collapse at t = "},
      // Ten times the stable step tangles the mesh (or drives energies negative).
      {"--problem sedov --scale 0.3 --set numerics.cfl=1 --set numerics.dt_initial_factor=1 "
       "--set numerics.dt_growth=10 --set numerics.c_vol=0.99 --set numerics.order=1",
       "cell"},
  };
  int index = 0;
  for (const Failure& failure : failures) {
    const std::string out = dir + "/f" + std::to_string(index++);
    const auto result = runLagremap(failure.args + " --quiet --output " + out);
    EXPECT_EQ(result.exit_code, 3) << failure.args << "\n" << result.output;
    EXPECT_EQ(lineCount(result.error), 1) << result.error;
    EXPECT_NE(result.error.find(failure.reason), std::string::npos) << result.error;
    EXPECT_NE(result.error.find("step"), std::string::npos) << result.error;
    std::ifstream summary(out + "/summary.json");
    std::stringstream text;
    text << summary.rdbuf();
    EXPECT_NE(text.str().find("\"status\": \"failed\""), std::string::npos) << out;
    EXPECT_TRUE(std::filesystem::exists(out + "/fields_00001.h5")) << out;
    EXPECT_TRUE(std::filesystem::exists(out + "/checkpoint.h5")) << out;  // to restart from
  }
  std::filesystem::remove_all(dir);
}

// The largest stable dt of a run (numerics.dt_drop_fraction) travels in its
// checkpoint: sedov's stable dt peaks and, two steps later, falls below 0.78
// of its peak (the stop before step 44), so a run restarted at step 42 stops
// where the uninterrupted one does (without the record, measured: step 61).
TEST(CommandLine, RestartKeepsTheLargestStableTimeStep) {
  const std::string dir = testing::scratchDir("cli_restart_drop");
  const std::string run = "--problem sedov --set numerics.dt_drop_fraction=0.78 --quiet";
  const auto whole = runLagremap(run + " --output " + dir + "/whole");
  ASSERT_EQ(whole.exit_code, 3) << whole.output;
  ASSERT_NE(whole.error.find("step 44: time step collapse"), std::string::npos) << whole.error;
  const std::string stopped = run + " --output " + dir + "/stopped";
  ASSERT_EQ(runLagremap(stopped + " --set numerics.max_steps=42").exit_code, 3);
  const auto resumed = runLagremap(stopped + " --restart " + dir + "/stopped/checkpoint.h5");
  EXPECT_EQ(resumed.exit_code, 3) << resumed.output;
  EXPECT_NE(resumed.error.find("step 44: time step collapse"), std::string::npos) << resumed.error;
  std::filesystem::remove_all(dir);
}

TEST(CommandLine, RestartFinishesAStoppedRunAndRefusesABadCheckpoint) {
  const std::string dir = testing::scratchDir("cli_restart");
  const std::string run = "--problem sod --scale 0.5 --quiet --output " + dir + "/run";
  EXPECT_EQ(runLagremap(run + " --set numerics.max_steps=40").exit_code, 3);
  const std::string checkpoint = dir + "/run/checkpoint.h5";
  ASSERT_TRUE(std::filesystem::exists(checkpoint));
  const auto resumed = runLagremap(run + " --restart " + checkpoint);
  EXPECT_EQ(resumed.exit_code, 0) << resumed.output;
  // history.csv: the 40 steps before the stop once, then the rest.
  std::ifstream history(dir + "/run/history.csv");
  std::string line;
  long lines = 0, step_40 = 0;
  while (std::getline(history, line)) {
    ++lines;
    step_40 += line.rfind("40,", 0) == 0;
  }
  EXPECT_EQ(step_40, 1);
  EXPECT_GT(lines, 42);

  std::filesystem::copy_file(checkpoint, dir + "/truncated.h5");
  std::filesystem::resize_file(dir + "/truncated.h5", std::filesystem::file_size(checkpoint) / 3);
  for (const std::string& bad : {dir + "/truncated.h5", dir + "/none.h5"}) {
    const auto result = runLagremap(run + " --restart " + bad);
    EXPECT_EQ(result.exit_code, 2) << result.output;
    EXPECT_EQ(lineCount(result.error), 1) << result.error;
    EXPECT_NE(result.error.find(bad), std::string::npos) << result.error;
  }
  // the time-step floor's check of a fresh run (it exited 3 after the restart)
  const auto floor =
      runLagremap(run + " --set numerics.dt_min_fraction=0.5 --restart " + checkpoint);
  EXPECT_EQ(floor.exit_code, 2) << floor.output;
  EXPECT_NE(floor.error.find("numerics.dt_min_fraction x t_end"), std::string::npos) << floor.error;
  const auto other =
      runLagremap("--problem sedov --quiet --output " + dir + "/x --restart " + checkpoint);
  EXPECT_EQ(other.exit_code, 2);
  EXPECT_NE(other.error.find("not sedov"), std::string::npos) << other.error;
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace lagremap
