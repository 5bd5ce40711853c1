// Run-time parameters: every settable key of a problem with its default, unit
// and help text, in the form `--set key=value` and the TOML deck accept.
#pragma once

#include <map>
#include <stdexcept>
#include <string>
#include <vector>

namespace lagremap {

// Bad user input (option, key, value, deck). The driver prints the message on
// one line and exits with code 2.
struct ConfigError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// `text` for an error message: its first 60 characters and "..." when
// longer, so that the message stays a line a user can read whatever was typed
// (a 100 kB value, a pasted file).
std::string abbreviated(const std::string& text);

enum class ParamType { Real, Integer, Text, Choice, Boolean };

struct Param {
  std::string key;
  ParamType type = ParamType::Real;
  std::string value;          // current value, as text
  std::string default_value;  // problem default
  std::string unit;           // SI unit, "-" for dimensionless
  std::string help;
  std::vector<std::string> choices;  // for ParamType::Choice
  bool cell_count = false;           // scaled by --scale
  bool cell_length = false;          // one cell's size (a slab's thickness): divided by --scale
};

class Config {
 public:
  void addReal(const std::string& key, double value, const std::string& unit,
               const std::string& help);
  // A length of one cell, e.g. the thickness of a one-cell slab: --scale divides
  // its default as it multiplies the cell counts, so the slab stays about one
  // cell thick and its thickness does not set the time step of a coarser run;
  // a value the user sets is kept as it is.
  void addCellLength(const std::string& key, double value, const std::string& help);
  void addInteger(const std::string& key, long value, const std::string& help,
                  bool cell_count = false);
  void addText(const std::string& key, const std::string& value, const std::string& help);
  void addChoice(const std::string& key, const std::string& value,
                 const std::vector<std::string>& choices, const std::string& help);
  void addBoolean(const std::string& key, bool value, const std::string& help);
  // Changes the default (and current value) of an existing key; for problems
  // that share common keys but want other defaults.
  void setDefault(const std::string& key, const std::string& value);

  // Sets a value from text; throws ConfigError for an unknown key or a value
  // that does not parse as the key's type.
  void set(const std::string& key, const std::string& value);
  // "key=value"
  void setAssignment(const std::string& assignment);
  // Reads a TOML deck: nested tables become dotted keys. The special keys
  // `problem` and `mode` are returned through the out parameters if present.
  // A file that is not a deck throws ConfigError naming it: not a regular
  // file (a device or a pipe), or not TOML (binary, not UTF-8, a syntax
  // error: with its line).
  void loadDeck(const std::string& path, std::string* problem, std::string* mode);
  // Reads only the top-level `problem` and `mode` of a deck (empty if absent);
  // throws as loadDeck does for a file that is not a deck.
  static void peekDeck(const std::string& path, std::string* problem, std::string* mode);
  // Multiplies every cell-count key with a value > 1 by `scale` and divides
  // every cell length left at its default by it (--scale); a count that
  // would not fit a mesh axis (2^31 cells) throws ConfigError.
  void scaleCellCounts(double scale);

  bool has(const std::string& key) const { return params_.count(key) != 0; }
  double real(const std::string& key) const;
  long integer(const std::string& key) const;
  bool boolean(const std::string& key) const;
  const std::string& text(const std::string& key) const;

  // The run mode the keys were declared for ("lagrange", "remap" or "ale")
  // and the problem set-up it starts from, lagrange's or remap's: problems
  // choose their domain and defaults by the set-up. ALE mode starts from the
  // lagrange set-up, or from remap's where the problem has no other
  // (useRemapSetup, refuseLagrangeMode).
  void setMode(const std::string& mode) {
    mode_ = mode;
    remap_setup_ = mode == "remap";
  }
  void useRemapSetup() { remap_setup_ = true; }
  const std::string& mode() const { return mode_; }
  bool remapSetup() const { return remap_setup_; }
  // Whether the run remaps (remap and ALE modes).
  bool remaps() const { return mode_ == "remap" || mode_ == "ale"; }
  bool aleMode() const { return mode_ == "ale"; }

  // All keys in order, for --print-config and summary.json.
  const std::map<std::string, Param>& params() const { return params_; }
  std::string printable() const;

 private:
  const Param& get(const std::string& key) const;
  void add(Param param);
  std::map<std::string, Param> params_;
  std::string mode_ = "lagrange";
  bool remap_setup_ = false;
};

}  // namespace lagremap
