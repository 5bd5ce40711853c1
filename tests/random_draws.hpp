// Reproducible random numbers and vectors for the kernels' property tests
// (each ctest case runs in its own process: its draws start from the seed).
#pragma once

#include <random>

#include "data/math.hpp"

namespace lagremap {

inline std::mt19937& testRng() {
  static std::mt19937 rng(4242);
  return rng;
}
inline double uniform(double lo, double hi) {
  return std::uniform_real_distribution<double>(lo, hi)(testRng());
}
inline Vec3 randomVec(double scale) {
  return {uniform(-scale, scale), uniform(-scale, scale), uniform(-scale, scale)};
}

}  // namespace lagremap
