// A minimal JSON writer for summary.json (no dependency needed for output only).
#pragma once

#include <cmath>
#include <iomanip>
#include <ostream>
#include <sstream>
#include <string>
#include <vector>

namespace lagremap {

class JsonWriter {
 public:
  explicit JsonWriter(std::ostream& out) : out_(out) { out_ << std::setprecision(17); }

  JsonWriter& beginObject(const std::string& key = "") { return open(key, '{'); }
  JsonWriter& endObject() { return close('}'); }
  JsonWriter& value(const std::string& key, double number) {
    prefix(key);
    if (std::isfinite(number)) {
      out_ << number;
    } else {
      out_ << "null";  // JSON has no NaN or infinity
    }
    return *this;
  }
  JsonWriter& value(const std::string& key, long number) {
    prefix(key);
    out_ << number;
    return *this;
  }
  JsonWriter& value(const std::string& key, int number) { return value(key, long(number)); }
  JsonWriter& value(const std::string& key, bool flag) {
    prefix(key);
    out_ << (flag ? "true" : "false");
    return *this;
  }
  JsonWriter& value(const std::string& key, const std::string& text) {
    prefix(key);
    out_ << quote(text);
    return *this;
  }
  JsonWriter& value(const std::string& key, const char* text) {
    return value(key, std::string(text));
  }

  static std::string quote(const std::string& text) {
    std::ostringstream quoted;
    quoted << '"';
    for (const char ch : text) {
      switch (ch) {
        case '"':
          quoted << "\\\"";
          break;
        case '\\':
          quoted << "\\\\";
          break;
        case '\n':
          quoted << "\\n";
          break;
        case '\t':
          quoted << "\\t";
          break;
        default:
          if (static_cast<unsigned char>(ch) < 0x20) {
            quoted << "\\u" << std::hex << std::setw(4) << std::setfill('0') << int(ch) << std::dec;
          } else {
            quoted << ch;
          }
      }
    }
    quoted << '"';
    return quoted.str();
  }

 private:
  JsonWriter& open(const std::string& key, char bracket) {
    prefix(key);
    out_ << bracket;
    first_.push_back(true);
    return *this;
  }
  JsonWriter& close(char bracket) {
    first_.pop_back();
    out_ << '\n' << std::string(2 * first_.size(), ' ') << bracket;
    if (first_.empty()) out_ << '\n';
    return *this;
  }
  void prefix(const std::string& key) {
    if (!first_.empty()) {
      if (!first_.back()) out_ << ',';
      first_.back() = false;
      out_ << '\n' << std::string(2 * first_.size(), ' ');
      if (!key.empty()) out_ << quote(key) << ": ";
    }
  }
  std::ostream& out_;
  std::vector<bool> first_;
};

}  // namespace lagremap
