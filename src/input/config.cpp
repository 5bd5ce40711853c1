#include "config.hpp"

#include <toml++/toml.h>
#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <functional>
#include <iomanip>
#include <limits>
#include <sstream>

namespace lagremap {
namespace {

std::string formatReal(double value) {
  std::ostringstream out;
  out << std::setprecision(17) << value;
  // Shortest text that reads back to the same double.
  for (int digits = 1; digits <= 17; ++digits) {
    std::ostringstream trial;
    trial << std::setprecision(digits) << value;
    if (std::strtod(trial.str().c_str(), nullptr) == value) return trial.str();
  }
  return out.str();
}

// Decimal text only: strtod alone would also take leading blanks, hex
// ("0x1p-3") and "infinity" or "nan" words.
bool isDecimal(const std::string& text) {
  return !text.empty() && text.find_first_not_of("0123456789+-.eE") == std::string::npos;
}

bool parseReal(const std::string& text, double* value) {
  if (!isDecimal(text)) return false;
  errno = 0;
  char* end = nullptr;
  *value = std::strtod(text.c_str(), &end);
  return errno == 0 && end == text.c_str() + text.size() && std::isfinite(*value);
}

bool parseInteger(const std::string& text, long* value) {
  if (!isDecimal(text)) return false;
  errno = 0;
  char* end = nullptr;
  *value = std::strtol(text.c_str(), &end, 10);
  return errno == 0 && end == text.c_str() + text.size();
}

bool parseBoolean(const std::string& text, bool* value) {
  if (text == "true" || text == "1" || text == "on" || text == "yes") return *value = true, true;
  if (text == "false" || text == "0" || text == "off" || text == "no") return *value = false, true;
  return false;
}

std::string typeName(const Param& param) {
  switch (param.type) {
    case ParamType::Real:
      return "a real number";
    case ParamType::Integer:
      return "an integer";
    case ParamType::Boolean:
      return "true or false";
    case ParamType::Text:
      return "text";
    case ParamType::Choice: {
      std::string names;
      for (const auto& c : param.choices) names += (names.empty() ? "" : "|") + c;
      return "one of " + names;
    }
  }
  return "";
}

// Lengths (unit m) beyond this magnitude overflow the geometry's products of
// lengths (volumes, their squares) in doubles.
constexpr double kLargestLength = 1e50;

// The tables of the deck at `path`, or ConfigError naming it. Only a regular
// file is read: a device would read as an empty deck (/dev/urandom) or never
// end (/dev/zero), and a pipe only once (the driver reads the deck twice).
// toml++ refuses what is not text (invalid UTF-8, control characters).
toml::table parseDeck(const std::string& path) {
  const std::string deck = "input deck '" + path + "'";
  std::error_code error;
  const auto status = std::filesystem::status(path, error);
  if (!std::filesystem::exists(status)) throw ConfigError(deck + " does not exist");
  if (!std::filesystem::is_regular_file(status)) {
    throw ConfigError(deck + " is not a regular file (a directory, device or pipe)");
  }
  try {
    return toml::parse_file(path);
  } catch (const toml::parse_error& syntax) {
    const auto line = syntax.source().begin.line;  // 0: the file as a whole
    throw ConfigError(deck + (line > 0 ? " line " + std::to_string(line) : "") + ": " +
                      std::string(syntax.description()));
  }
}

}  // namespace

std::string abbreviated(const std::string& text) {
  constexpr std::size_t kShown = 60;
  if (text.size() <= kShown) return text;
  // (back to the start of a UTF-8 character: half of one prints as garbage)
  std::size_t cut = kShown;
  while (cut > 0 && (static_cast<unsigned char>(text[cut]) & 0xC0) == 0x80) --cut;
  return text.substr(0, cut) + "...";
}

void Config::add(Param param) {
  param.default_value = param.value;
  params_[param.key] = std::move(param);
}

void Config::addReal(const std::string& key, double value, const std::string& unit,
                     const std::string& help) {
  add({key, ParamType::Real, formatReal(value), "", unit, help, {}, false});
}

void Config::addCellLength(const std::string& key, double value, const std::string& help) {
  add({key, ParamType::Real, formatReal(value), "", "m", help, {}, false, true});
}

void Config::addInteger(const std::string& key, long value, const std::string& help,
                        bool cell_count) {
  add({key, ParamType::Integer, std::to_string(value), "", "-", help, {}, cell_count});
}

void Config::addText(const std::string& key, const std::string& value, const std::string& help) {
  add({key, ParamType::Text, value, "", "-", help, {}, false});
}

void Config::addChoice(const std::string& key, const std::string& value,
                       const std::vector<std::string>& choices, const std::string& help) {
  add({key, ParamType::Choice, value, "", "-", help, choices, false});
}

void Config::addBoolean(const std::string& key, bool value, const std::string& help) {
  add({key, ParamType::Boolean, value ? "true" : "false", "", "-", help, {}, false});
}

void Config::setDefault(const std::string& key, const std::string& value) {
  set(key, value);
  params_.at(key).default_value = params_.at(key).value;
}

void Config::set(const std::string& key, const std::string& value) {
  auto it = params_.find(key);
  if (it == params_.end()) {
    throw ConfigError("unknown key '" + abbreviated(key) + "' (see --print-config for the keys)");
  }
  Param& param = it->second;
  bool ok = true;
  std::string normalized = value;
  switch (param.type) {
    case ParamType::Real: {
      double parsed;
      ok = parseReal(value, &parsed);
      if (ok) normalized = formatReal(parsed);
      if (ok && param.unit == "m" && std::abs(parsed) > kLargestLength) {
        throw ConfigError(key + " = " + normalized + " m is out of range: lengths are at most " +
                          formatReal(kLargestLength) + " m (beyond, products of lengths overflow)");
      }
      break;
    }
    case ParamType::Integer: {
      long parsed;
      ok = parseInteger(value, &parsed);
      break;
    }
    case ParamType::Boolean: {
      bool parsed;
      ok = parseBoolean(value, &parsed);
      if (ok) normalized = parsed ? "true" : "false";
      break;
    }
    case ParamType::Choice:
      ok = false;
      for (const auto& choice : param.choices) ok = ok || choice == value;
      break;
    case ParamType::Text:
      break;
  }
  if (!ok) {
    throw ConfigError("bad value '" + abbreviated(value) + "' for key '" + key + "': expected " +
                      typeName(param));
  }
  param.value = normalized;
}

void Config::setAssignment(const std::string& assignment) {
  const auto equals = assignment.find('=');
  if (equals == std::string::npos || equals == 0) {
    throw ConfigError("bad --set '" + abbreviated(assignment) + "': expected key=value");
  }
  set(assignment.substr(0, equals), assignment.substr(equals + 1));
}

void Config::peekDeck(const std::string& path, std::string* problem, std::string* mode) {
  const toml::table deck = parseDeck(path);
  if (problem) *problem = deck["problem"].value_or(std::string());
  if (mode) *mode = deck["mode"].value_or(std::string());
}

void Config::loadDeck(const std::string& path, std::string* problem, std::string* mode) {
  const toml::table deck = parseDeck(path);
  // Walk the tables; each leaf becomes a dotted key.
  std::function<void(const toml::table&, const std::string&)> walk =
      [&](const toml::table& table, const std::string& prefix) {
        for (const auto& [name, node] : table) {
          const std::string key =
              prefix.empty() ? std::string(name.str()) : prefix + "." + std::string(name.str());
          if (const auto* sub = node.as_table()) {
            walk(*sub, key);
            continue;
          }
          const auto param = params_.find(key);
          const bool number_key =
              param != params_.end() &&
              (param->second.type == ParamType::Real || param->second.type == ParamType::Integer);
          std::string text;
          if (const auto* s = node.as_string()) {
            // (a quoted number is a string in TOML: a typo or a pasted value)
            if (number_key) {
              throw ConfigError("input deck '" + path + "': key '" + key +
                                "' is a number; the deck gives the string \"" +
                                abbreviated(s->get()) + "\"");
            }
            text = s->get();
          } else if (const auto* i = node.as_integer()) {
            if (i->flags() != toml::value_flags::none) {
              throw ConfigError("input deck '" + path + "': key '" + key +
                                "': write the number in decimal, not hex, octal or binary");
            }
            text = std::to_string(i->get());
          } else if (const auto* d = node.as_floating_point()) {
            text = formatReal(d->get());
          } else if (const auto* b = node.as_boolean()) {
            text = b->get() ? "true" : "false";
          } else {
            throw ConfigError("input deck '" + path + "': key '" + abbreviated(key) +
                              "' must be a number, string or boolean");
          }
          if (key == "problem" && problem) {
            *problem = text;
          } else if (key == "mode" && mode) {
            *mode = text;
          } else {
            try {
              set(key, text);
            } catch (const ConfigError& error) {
              throw ConfigError("input deck '" + path + "': " + error.what());
            }
          }
        }
      };
  walk(deck, "");
}

void Config::scaleCellCounts(double scale) {
  for (auto& [key, param] : params_) {
    // A cell length the user set (deck, --set) is the length they asked for.
    if (param.cell_length && param.value == param.default_value) {
      param.value = formatReal(real(key) / scale);
    }
    if (!param.cell_count) continue;
    const long count = integer(key);
    if (count <= 1) continue;
    // (a mesh axis is an int; a larger count would not even round to a long)
    const double scaled = std::max(1.0, std::round(static_cast<double>(count) * scale));
    if (!(scaled <= std::numeric_limits<int>::max())) {
      throw ConfigError("--scale " + formatReal(scale) + " makes " + key + " = " +
                        formatReal(scaled) + ", more cells than a mesh axis holds (2^31 - 1)");
    }
    param.value = std::to_string(static_cast<long>(scaled));
  }
}

const Param& Config::get(const std::string& key) const {
  auto it = params_.find(key);
  if (it == params_.end()) throw ConfigError("unknown key '" + key + "'");
  return it->second;
}

double Config::real(const std::string& key) const {
  double value;
  if (!parseReal(get(key).value, &value)) throw ConfigError("key '" + key + "' is not a number");
  return value;
}

long Config::integer(const std::string& key) const {
  long value;
  if (!parseInteger(get(key).value, &value)) {
    throw ConfigError("key '" + key + "' is not an integer");
  }
  return value;
}

bool Config::boolean(const std::string& key) const {
  bool value;
  if (!parseBoolean(get(key).value, &value)) throw ConfigError("key '" + key + "' is not boolean");
  return value;
}

const std::string& Config::text(const std::string& key) const {
  return get(key).value;
}

std::string Config::printable() const {
  std::ostringstream out;
  std::size_t width = 0;
  for (const auto& entry : params_)
    width = std::max(width, entry.first.size() + 1 + entry.second.value.size());
  for (const auto& [key, param] : params_) {
    const std::string assignment = key + "=" + param.value;
    out << std::left << std::setw(static_cast<int>(width) + 2) << assignment << "# [" << param.unit
        << "] " << param.help;
    if (param.type == ParamType::Choice) out << " (" << typeName(param) << ")";
    if (param.value != param.default_value) out << " [default " << param.default_value << "]";
    out << '\n';
  }
  return out.str();
}

}  // namespace lagremap
