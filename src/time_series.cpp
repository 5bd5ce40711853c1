#include "time_series.hpp"

#include <cmath>

#include "data/math.hpp"

namespace lagremap {

namespace {

// Sum of squared residuals of the least-squares fit of
// y = a sin(w t) + b cos(w t) + c to the series, w = pi / half_period.
double sinusoidMisfit(const TimeSeries& series, double half_period) {
  const double w = 3.14159265358979323846 / half_period;
  SymMat3 normal{0, 0, 0, 0, 0, 0};
  Vec3 rhs{0, 0, 0};
  for (const auto& [t, y] : series) {
    const Vec3 basis{std::sin(w * t), std::cos(w * t), 1.0};
    normal += outerSelf(basis, 1.0);
    rhs += y * basis;
  }
  const Vec3 coefficients = inverse(normal) * rhs;
  double misfit = 0.0;
  for (const auto& [t, y] : series) {
    const double model = dot(coefficients, Vec3{std::sin(w * t), std::cos(w * t), 1.0});
    misfit += (y - model) * (y - model);
  }
  return misfit;
}

}  // namespace

double fittedHalfPeriod(const TimeSeries& series, double lo, double hi) {
  if (series.size() < 4) return NAN;
  constexpr int kScan = 1000;
  const double step = (hi - lo) / kScan;
  int best = 0;
  double best_misfit = INFINITY;
  for (int i = 0; i <= kScan; ++i) {
    const double misfit = sinusoidMisfit(series, lo + i * step);
    if (misfit < best_misfit) {
      best_misfit = misfit;
      best = i;
    }
  }
  double a = lo + (best - 1) * step, b = lo + (best + 1) * step;
  const double golden = 0.5 * (std::sqrt(5.0) - 1.0);
  while (b - a > 1e-6 * step) {
    const double c = b - golden * (b - a), d = a + golden * (b - a);
    if (sinusoidMisfit(series, c) < sinusoidMisfit(series, d)) {
      b = d;
    } else {
      a = c;
    }
  }
  return 0.5 * (a + b);
}

}  // namespace lagremap
