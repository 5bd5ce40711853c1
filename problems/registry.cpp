#include <string>
#include <vector>

#include "../src/problem.hpp"

namespace lagremap {

extern const Problem kSodProblem;
extern const Problem kSedovProblem;
extern const Problem kWilkinsProblem;
extern const Problem kPileProblem;
extern const Problem kTaylorProblem;
extern const Problem kShellProblem;
extern const Problem kBeamProblem;
extern const Problem kBallProblem;
extern const Problem kRodProblem;
extern const Problem kAdvectionProblem;
extern const Problem kAdvection1DProblem;
extern const Problem kAirHeliumProblem;
extern const Problem kWaterAirProblem;
extern const Problem kBumpProblem;
extern const Problem kBump1DProblem;

const std::vector<Problem>& problemRegistry() {
  static const std::vector<Problem> problems = {
      kSodProblem,         kSedovProblem,     kWilkinsProblem,  kTaylorProblem, kPileProblem,
      kBeamProblem,        kShellProblem,     kBallProblem,     kRodProblem,    kAdvectionProblem,
      kAdvection1DProblem, kAirHeliumProblem, kWaterAirProblem, kBumpProblem,   kBump1DProblem};
  return problems;
}

const Problem& findProblem(const std::string& name) {
  std::string known;
  for (const auto& problem : problemRegistry()) {
    if (name == problem.name) return problem;
    known += (known.empty() ? "" : ", ") + std::string(problem.name);
  }
  throw ConfigError("unknown problem '" + abbreviated(name) + "' (known: " + known + ")");
}

}  // namespace lagremap
