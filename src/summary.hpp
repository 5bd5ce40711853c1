// summary.json of a run: what ran, its status, figure of merit per phase,
// drifts, totals, the sharpness of each material's interface, the checks and
// every key (docs/running.md, Output).
#pragma once

#include <string>

#include "run.hpp"
#include "simulation.hpp"

namespace lagremap {

void writeSummary(const std::string& path, const Simulation& simulation, const RunResult& result);

}  // namespace lagremap
