// The checks' shared rules: pass or fail, and the references that hold
// for the default case only or under perfect plasticity (src/problem.hpp).
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "../src/problem.hpp"

namespace lagremap {

bool Check::pass() const {
  return std::isfinite(value) && std::abs(value - reference) <= tolerance;
}

std::string differenceFromDefaultCase(const Config& config) {
  for (const auto& [key, param] : config.params()) {
    const bool resolution = param.cell_count || param.cell_length || key.rfind("mesh.", 0) == 0;
    const bool controls = key.rfind("numerics.", 0) == 0 || key.rfind("remap.", 0) == 0 ||
                          key.rfind("mixture.", 0) == 0 || key.rfind("check.", 0) == 0;
    if (resolution || controls || param.value == param.default_value) continue;
    return key + " = " + param.value + " (case: " + param.default_value + ")";
  }
  return "";
}

void markDefaultCaseOnly(const Config& config, std::vector<Check>& checks,
                         const std::vector<std::string>& names, const std::string& source) {
  const std::string difference = differenceFromDefaultCase(config);
  for (Check& check : checks) {
    if (std::find(names.begin(), names.end(), check.name) == names.end()) continue;
    check.source = source;
    if (!difference.empty()) {
      check.doesNotApply("the reference is the default case's; this run has " + difference);
    }
  }
}

void markPerfectPlasticityOnly(const Config& config, std::vector<Check>& checks,
                               const std::string& prefix, const std::vector<std::string>& names) {
  const std::string hardening = config.text(prefix + ".hardening");
  if (hardening == "perfect") return;
  for (Check& check : checks) {
    if (!names.empty() && std::find(names.begin(), names.end(), check.name) == names.end()) {
      continue;
    }
    check.doesNotApply("the reference is for a perfectly plastic solid; this run has " + prefix +
                       ".hardening = " + hardening);
  }
}

void setModeIndependentReferences(const Config& config, std::vector<Check>& checks) {
  if (!config.remapSetup()) return;
  for (Check& check : checks)
    if (!check.lagrange_reference) check.lagrange_reference = check.reference;
}

}  // namespace lagremap
