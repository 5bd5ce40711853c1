// Boundary conditions per side of the generated block (docs/method.md §A4).
#pragma once

#include <array>

#include "math.hpp"

namespace lagremap {

enum class BoundaryKind { Free, Wall, Fixed, Traction };

// `symmetry` is the same condition as `wall` (zero normal velocity, slip).
struct BoundaryCondition {
  BoundaryKind kind = BoundaryKind::Wall;
  SymMat3 traction_stress{0, 0, 0, 0, 0, 0};  // Cauchy stress sigma^b, tension positive
};

constexpr int kNumSides = 6;  // x-, x+, y-, y+, z-, z+ of the block
using SideBoundaries = std::array<BoundaryCondition, kNumSides>;

}  // namespace lagremap
