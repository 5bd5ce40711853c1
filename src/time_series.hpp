// Analysis of a scalar history (a problem's probe): (t, value) samples.
#pragma once

#include <utility>
#include <vector>

namespace lagremap {

using TimeSeries = std::vector<std::pair<double, double>>;

// The half period pi / w of the sinusoid y = a sin(w t) + b cos(w t) + c that
// best fits the series (least squares), searched in [lo, hi]: a scan in 1000
// steps, then golden-section search in the best step's neighbourhood. NaN
// for fewer than four samples.
double fittedHalfPeriod(const TimeSeries& series, double lo, double hi);

}  // namespace lagremap
