#include "cli.hpp"

#include <CLI/CLI.hpp>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <iostream>
#include <sstream>

#include "kokkos_session.hpp"
#include "parallel.hpp"
#include "run.hpp"
#include "stop_signals.hpp"
#include "timers.hpp"

namespace lagremap {
namespace {

constexpr int kExitChecksFailed = 1;
constexpr int kExitBadInput = 2;
constexpr int kExitRunFailed = 3;

// Exact text of a double for Config::set (std::to_string would round to 6 decimals).
std::string exactText(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.17g", value);
  return text;
}

// Range check of a numeric option whose message names the rule in a few
// words ("must be positive, got 0"): CLI11's own spell out DBL_MAX in full.
CLI::Validator numberIn(const std::string& rule, const std::function<bool(double)>& inside) {
  return CLI::Validator(
      [=](std::string& text) -> std::string {
        char* end = nullptr;
        const double value = std::strtod(text.c_str(), &end);
        if (text.empty() || end != text.c_str() + text.size()) {
          return "'" + abbreviated(text) + "' is not a number";
        }
        return inside(value) ? "" : "must be " + rule + ", got " + abbreviated(text);
      },
      rule);
}
CLI::Validator positiveNumber() {
  return numberIn("positive", [](double v) { return v > 0.0; });
}
CLI::Validator nonNegativeNumber() {
  return numberIn("non-negative", [](double v) { return v >= 0.0; });
}
// A name or path given empty (--output "" from an unset shell variable) is a
// mistake, not a request for the default: leaving the option out is that.
CLI::Validator nonEmpty() {
  return CLI::Validator(
      [](std::string& text) -> std::string { return text.empty() ? "must not be empty" : ""; }, "");
}

// Our own message with every word of more than 200 characters (a path, say)
// cut to its first and last 60 (the file's name stays); a value the message
// quotes is already cut (abbreviated).
std::string withLongWordsCut(const std::string& message) {
  constexpr std::size_t kLongWord = 200, kKept = 60;
  std::istringstream words(message);
  std::string line, word;
  while (words >> word) {
    if (word.size() > kLongWord)
      word = word.substr(0, kKept) + "..." + word.substr(word.size() - kKept);
    line += (line.empty() ? "" : " ") + word;
  }
  return line;
}

// CLI11's message on one line a user can read: it quotes what was typed as
// it was typed, so each word is cut as our own messages cut a value, and the
// line after 200 characters (a long value with spaces in it).
std::string oneReadableLine(const CLI::ParseError& error) {
  std::istringstream words(error.what());
  std::string line, word;
  while (words >> word) line += (line.empty() ? "" : " ") + abbreviated(word);
  return line.size() <= 200 ? line : line.substr(0, 200) + "...";
}

int badInput(const std::string& message) {
  // Every rank finds the same bad input; one says so.
  if (parallel::isRoot())
    std::fprintf(stderr, "lagremap: error: %s\n", withLongWordsCut(message).c_str());
  return kExitBadInput;
}

void printReport(const RunOptions& options, const RunResult& result) {
  std::printf("lagremap: %s (%s, order %s), %ld cells, %ld steps, t = %.6g, %.3f s\n",
              options.problem.c_str(), options.mode.c_str(),
              options.config.text("numerics.order").c_str(), result.cells, result.steps,
              result.time, result.wall_seconds);
  std::printf("drift (relative, boundary work subtracted): mass %.2e  momentum %.2e  energy %.2e\n",
              result.drift_mass, result.drift_momentum, result.drift_energy);
  for (const auto& check : result.checks) {
    const char* verdict = !check.counts() ? "n/a" : check.pass() ? "pass" : "FAIL";
    std::printf("check %-22s %-13.6g reference %-12.6g tolerance %-10.3g %s", check.name.c_str(),
                check.value, check.reference, check.tolerance, verdict);
    if (!check.source.empty()) std::printf("  [%s]", check.source.c_str());
    if (!check.counts()) std::printf("  (%s)", check.not_applicable.c_str());
    std::printf("\n");
  }
  if (result.mixed_cells) std::printf("%s\n", mixedCellsLine(*result.mixed_cells).c_str());
  std::printf("FOM: %.4g cell-steps/s (%s)\n", result.cell_steps_per_second,
              executionSpaceText().c_str());
  const RankCosts& costs = result.costs;
  std::printf("set-up %.3g s, peak memory per rank %.1f MB (largest), halo %.3g MB per step\n",
              costs.setup.total(), costs.peak_bytes.max / 1e6, costs.halo_bytes_per_step / 1e6);
}

// What the command line says, before it is resolved against a problem.
struct CommandLine {
  std::string problem, mode = "lagrange", input, output, restart_file;
  double scale = 1.0, t_end = 0.0, cfl = 0.0;
  int order = 0;
  long output_every = 0, checkpoint_every = 0;
  std::vector<std::string> assignments;
  std::vector<double> output_times;
  bool quiet = false, list = false, print_config = false, profile_phases = false;
};

void addOptions(CLI::App& app, CommandLine& line) {
  app.add_option("--problem", line.problem, "problem to run (see --list)")->check(nonEmpty());
  app.add_option("--mode", line.mode,
                 "lagrange (pure Lagrangian), remap (Lagrange-Remap) or ale (relaxed mesh)")
      ->check(CLI::IsMember({"lagrange", "remap", "ale"}));
  app.add_option("--scale", line.scale, "multiply every cell count by S")->check(positiveNumber());
  app.add_option("--t-end", line.t_end, "final time [s]")->check(positiveNumber());
  app.add_option("--cfl", line.cfl, "CFL number")
      ->check(numberIn("between 1e-06 and 1", [](double v) { return v >= 1e-6 && v <= 1.0; }));
  app.add_option("--order", line.order, "1 or 2")->check(CLI::IsMember({1, 2}));
  app.add_option("--set", line.assignments, "set a problem or numerics key: --set key=value")
      ->allow_extra_args(false);
  app.add_option("--input", line.input, "TOML input deck (tables become dotted keys)")
      ->check(nonEmpty())
      ->check(CLI::ExistingFile);
  app.add_option("--output", line.output, "output directory (default out/<problem>)")
      ->check(nonEmpty());
  app.add_option("--output-times", line.output_times,
                 "snapshot times, comma separated, in any order [s]")
      ->delimiter(',');
  app.add_option("--output-every", line.output_every, "snapshot every N steps")
      ->check(nonNegativeNumber());
  app.add_option("--checkpoint-every", line.checkpoint_every,
                 "write <output>/checkpoint.h5 every N steps (and when a run fails)")
      ->check(nonNegativeNumber());
  app.add_option("--restart", line.restart_file, "continue the run saved in this checkpoint file")
      ->check(nonEmpty());
  app.add_flag("--quiet", line.quiet, "no progress line");
  app.add_flag("--profile-phases", line.profile_phases,
               "wait for the device at each phase's ends, so that summary.json's phase times are "
               "the kernels' own on a GPU (a host synchronisation per phase)");
  app.add_flag("--list", line.list, "list the built-in problems");
  app.add_flag("--print-config", line.print_config,
               "print every key of the problem with its value, unit and help");
}

// The problem and mode a deck names where the command line does not; throws
// ConfigError for a deck that names neither problem nor a known mode.
void takeProblemAndModeFromDeck(CommandLine& line, bool mode_given) {
  if (line.input.empty()) return;
  if (line.problem.empty()) {
    Config::peekDeck(line.input, &line.problem, nullptr);
    if (line.problem.empty()) {
      throw ConfigError("input deck '" + line.input +
                        "' names no problem and --problem is not given");
    }
  }
  if (!mode_given) {
    std::string deck_mode;
    Config::peekDeck(line.input, nullptr, &deck_mode);
    if (!deck_mode.empty()) line.mode = deck_mode;
    if (line.mode != "lagrange" && line.mode != "remap" && line.mode != "ale") {
      throw ConfigError("input deck '" + line.input + "': mode '" + abbreviated(line.mode) +
                        "' is not one of lagrange|remap|ale");
    }
  }
}

// Every key of the run: the problem's defaults, then the deck, then --set,
// then the options that stand for keys (--t-end, --cfl, --order, --scale).
Config resolveConfig(const Problem& problem, const CommandLine& line, const CLI::App& app) {
  Config config = declareConfig(problem, line.mode);
  if (!line.input.empty()) {
    std::string deck_problem, deck_mode;
    config.loadDeck(line.input, &deck_problem, &deck_mode);
    if (!deck_problem.empty() && deck_problem != line.problem) {
      throw ConfigError("input deck '" + line.input + "' is for problem '" +
                        abbreviated(deck_problem) + "', not '" + line.problem + "'");
    }
  }
  for (const auto& assignment : line.assignments) config.setAssignment(assignment);
  if (app.count("--t-end")) config.set("t_end", exactText(line.t_end));
  if (app.count("--cfl")) config.set("numerics.cfl", exactText(line.cfl));
  if (app.count("--order")) config.set("numerics.order", std::to_string(line.order));
  config.scaleCellCounts(line.scale);
  return config;
}

RunOptions runOptions(const Problem& problem, CommandLine& line, Config config, bool times_given) {
  RunOptions options;
  options.problem = problem.name;
  options.mode = line.mode;
  options.config = std::move(config);
  options.output_dir = line.output.empty() ? "out/" + options.problem : line.output;
  options.output_times = line.output_times;
  if (!times_given) {
    for (double t_out : problem.default_output_times) {
      if (t_out <= options.config.real("t_end")) options.output_times.push_back(t_out);
    }
  }
  options.output_every = line.output_every;
  options.quiet = line.quiet;
  options.profile_phases = line.profile_phases;
  options.checkpoint_every = line.checkpoint_every;
  options.restart_file = line.restart_file;
  return options;
}

// Runs and reports (rank 0); every rank returns the same exit code.
int runAndReport(const RunOptions& options) {
  const RunResult result = runProblem(options);
  const int code = result.stopped_by     ? kExitStopped
                   : result.failed       ? kExitRunFailed
                   : result.checksPass() ? 0
                                         : kExitChecksFailed;
  if (!parallel::isRoot()) return code;
  if (result.stopped_by) {
    std::fprintf(stderr,
                 "lagremap: %s; checkpoint and outputs written to %s (continue with --restart "
                 "%s/checkpoint.h5)\n",
                 result.failure.c_str(), options.output_dir.c_str(), options.output_dir.c_str());
    return code;
  }
  if (result.failed) {
    std::fprintf(stderr, "lagremap: run failed: %s; last good state (t = %.6g) written to %s\n",
                 result.failure.c_str(), result.time, options.output_dir.c_str());
    return code;
  }
  printReport(options, result);
  return code;
}

}  // namespace

int refuseInput(const std::string& message) {
  return badInput(message);
}

int runCommandLine(int argc, char* argv[]) {
  CLI::App app{
      "lagremap: 3D cell-centred Lagrangian (and Lagrange-Remap) multi-material dynamics.\n"
      "Kokkos options (--kokkos-threads=N or --kokkos-num-threads=N, ...) are accepted too;\n"
      "--kokkos-help lists them.\n"
      "Threads: OMP_NUM_THREADS (or --kokkos-threads). Thread binding is OpenMP's default\n"
      "unless OMP_PROC_BIND is set; OMP_PROC_BIND=spread OMP_PLACES=threads is fastest\n"
      "(scripts/run.sh sets them). Kokkos' advice about it is not printed.",
      "lagremap"};
  CommandLine line;
  addOptions(app, line);
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& help) {
    return app.exit(help);
  } catch (const CLI::ParseError& error) {
    return badInput(oneReadableLine(error));
  }
  if (line.list) {
    for (const auto& problem : problemRegistry()) {
      if (!parallel::isRoot()) break;
      std::printf("%-10s %s\n", problem.name, problem.description);
    }
    return 0;
  }
  try {
    takeProblemAndModeFromDeck(line, app.count("--mode") > 0);
    if (line.problem.empty()) return badInput("--problem is required (see --list)");
    const Problem& problem = findProblem(line.problem);
    Config config = resolveConfig(problem, line, app);
    if (line.print_config) {
      if (!parallel::isRoot()) return 0;
      std::printf("# problem %s: every settable key (--set key=value, or in a TOML deck)\n%s",
                  problem.name, config.printable().c_str());
      return 0;
    }
    return runAndReport(runOptions(problem, line, std::move(config), app.count("--output-times")));
  } catch (const ConfigError& error) {
    return badInput(error.what());
  } catch (const parallel::AgreedError& error) {
    if (parallel::isRoot())
      std::fprintf(stderr, "lagremap: error: %s\n", withLongWordsCut(error.what()).c_str());
    return kExitRunFailed;
  } catch (const std::exception& error) {  // (perhaps this rank's alone: each says so)
    std::fprintf(stderr, "lagremap: error: %s\n", withLongWordsCut(error.what()).c_str());
    return kExitRunFailed;
  }
}

}  // namespace lagremap
