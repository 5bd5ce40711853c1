// Names of the block's sides and boundary conditions in the run-time keys.
#pragma once

#include <string>

#include "data/boundary.hpp"

namespace lagremap {

const char* sideName(int side);  // "xmin", "xmax", ...
// Parses "free" | "wall" | "symmetry" | "fixed" | "traction"; throws ConfigError otherwise.
BoundaryKind parseBoundaryKind(const std::string& key, const std::string& text);
const char* boundaryKindName(BoundaryKind kind);

}  // namespace lagremap
