#include "mixed_cells.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>

#include "parallel.hpp"

namespace lagremap {

namespace {

// The k-th smallest (0-based) of the positive numbers `values` held by all
// ranks together: a bisection over the ordered bit patterns of positive
// doubles, counting over the ranks (64 sums, exact; no rank gathers them).
double kthOverRanks(const std::vector<double>& values, long k) {
  auto bits = [](double x) {
    std::uint64_t u;
    std::memcpy(&u, &x, sizeof u);
    return u;
  };
  std::uint64_t lo = 0, hi = bits(HUGE_VAL);  // the answer's pattern is in (lo, hi]
  while (hi - lo > 1) {
    const std::uint64_t mid = lo + (hi - lo) / 2;
    double mid_value;
    std::memcpy(&mid_value, &mid, sizeof mid_value);
    long at_most = 0;
    for (double v : values) at_most += v <= mid_value;
    if (long(parallel::sum(double(at_most))) > k) {
      hi = mid;
    } else {
      lo = mid;
    }
  }
  double value;
  std::memcpy(&value, &hi, sizeof value);
  return value;
}

// Median of positive numbers spread over the ranks (the mean of the two
// middle ones for an even count); 0 for none.
double medianOverRanks(std::vector<double> values, bool distributed) {
  const long n = distributed ? long(parallel::sum(double(values.size()))) : long(values.size());
  if (n == 0) return 0.0;
  if (!distributed) {
    std::sort(values.begin(), values.end());
    return n % 2 ? values[std::size_t(n / 2)]
                 : 0.5 * (values[std::size_t(n / 2 - 1)] + values[std::size_t(n / 2)]);
  }
  return n % 2 ? kthOverRanks(values, n / 2)
               : 0.5 * (kthOverRanks(values, n / 2 - 1) + kthOverRanks(values, n / 2));
}

struct Range {
  double lo = HUGE_VAL, hi = -HUGE_VAL;
  void include(double x) {
    lo = std::min(lo, x);
    hi = std::max(hi, x);
  }
  void overRanks(bool distributed) {
    if (!distributed) return;
    lo = parallel::min(lo);
    hi = parallel::max(hi);
  }
  bool empty() const { return !(lo <= hi); }
  // [min(lo, 0) - margin_scale M, hi + margin_scale M], M = max(|lo|, |hi|)
  bool outside(double x, double margin_scale) const {
    const double margin = margin_scale * std::max(std::abs(lo), std::abs(hi));
    return x < std::min(lo, 0.0) - margin || x > hi + margin;
  }
};

long countOverRanks(long count, bool distributed) {
  return distributed ? long(parallel::sum(double(count))) : count;
}

}  // namespace

bool MixedCellReport::hasCondensed() const {
  for (const auto& m : materials)
    if (m.condensed) return true;
  return false;
}

double MixedCellReport::worstFraction(std::string* what) const {
  double worst = mixtureOutlierFraction();
  if (what) *what = "mixture pressure outliers among the cells not pure";
  for (const auto& m : materials) {
    if (!m.condensed) continue;
    const std::string name = "material " + std::to_string(m.material);
    if (m.stretchedFraction() > worst) {
      worst = m.stretchedFraction();
      if (what) *what = name + " stretched";
    }
    if (m.pressureOutlierFraction() > worst) {
      worst = m.pressureOutlierFraction();
      if (what) *what = name + " pressure outliers";
    }
  }
  return worst;
}

namespace {

// The final fields as measureMixedCells reads them: each material's density,
// pure and mixed cells, and its balance with the cell's other materials.
struct CellsRead {
  const FinalFields& fields;
  Index n_cells;
  int n_materials;

  explicit CellsRead(const FinalFields& final_fields)
      : fields(final_fields),
        n_cells(Index(final_fields.alpha.extent(0))),
        n_materials(int(final_fields.alpha.extent(1))) {}
  double density(Index c, int k) const {
    return fields.m_k(c, k) / (fields.alpha(c, k) * fields.vol(c));
  }
  bool pure(Index c) const {
    for (int k = 0; k < n_materials; ++k)
      if (fields.alpha(c, k) > kPureAlpha) return true;
    return false;
  }
  bool mixed(Index c, int k) const {
    return fields.alpha(c, k) >= kMixedAlphaLow && fields.alpha(c, k) <= 1.0 - kMixedAlphaLow;
  }
  // Material k's normal stress across its interface less the cell's other
  // materials' (their volume fractions' mean): zero where the closure's
  // relaxation has balanced them.
  double imbalance(Index c, int k) const {
    double others = 0.0, weight = 0.0;
    for (int n = 0; n < n_materials; ++n) {
      if (n == k || !(fields.alpha(c, n) > 0.0)) continue;
      others += fields.alpha(c, n) * fields.sigma_n_k(c, n);
      weight += fields.alpha(c, n);
    }
    return weight > 0.0 ? fields.sigma_n_k(c, k) - others / weight : 0.0;
  }
};

// Material k's pure and mixed cells: their counts, the pure cells' median
// density and both pressure ranges; the pure range is added to pure_p_all.
MaterialMixedCells pureAndMixedCells(const CellsRead& cells, int k, bool condensed,
                                     Range& pure_p_all) {
  const bool distributed = cells.fields.distributed;
  MaterialMixedCells m;
  m.material = k;
  m.condensed = condensed;
  std::vector<double> pure_density;
  Range pure_p_k, mixed_p;
  for (Index c = 0; c < cells.n_cells; ++c) {
    if (!cells.fields.counts(c)) continue;
    if (cells.fields.alpha(c, k) > kPureAlpha) {
      pure_density.push_back(cells.density(c, k));
      pure_p_k.include(cells.fields.p_k(c, k));
    } else if (cells.mixed(c, k)) {
      mixed_p.include(cells.fields.p_k(c, k));
      ++m.mixed_cells;
    }
  }
  m.pure_cells = countOverRanks(long(pure_density.size()), distributed);
  m.mixed_cells = countOverRanks(m.mixed_cells, distributed);
  m.rho_pure_median = medianOverRanks(pure_density, distributed);
  pure_p_k.overRanks(distributed);
  mixed_p.overRanks(distributed);
  m.p_pure_lo = pure_p_k.empty() ? 0.0 : pure_p_k.lo;
  m.p_pure_hi = pure_p_k.empty() ? 0.0 : pure_p_k.hi;
  m.p_mixed_lo = mixed_p.empty() ? 0.0 : mixed_p.lo;
  m.p_mixed_hi = mixed_p.empty() ? 0.0 : mixed_p.hi;
  if (!pure_p_k.empty()) {
    pure_p_all.include(pure_p_k.lo);
    pure_p_all.include(pure_p_k.hi);
  }
  return m;
}

// Counts material m's mixed cells that are expanded, stretched, pressure
// outliers, or beyond its pure cells' pressures but in balance. A material
// out of balance with its cell by more than `balance_margin` is held there
// by the closure (docs/method.md §4.9).
void countStretchedAndOutliers(const CellsRead& cells, const Range& pure_p_all,
                               double balance_margin, MaterialMixedCells& m) {
  const int k = m.material;
  const double rho_expanded = (1.0 - kStretchFraction) * m.rho_pure_median;
  // Tension, not heat (docs/method.md §4.9): a stretched material is below
  // its pure cells' lowest pressure as well as below 0.
  const double p_stretched = std::min(m.p_pure_lo, 0.0);
  for (Index c = 0; c < cells.n_cells; ++c) {
    if (!cells.fields.counts(c) || !cells.mixed(c, k)) continue;
    const double p = cells.fields.p_k(c, k);
    const double out_of_balance = pure_p_all.empty() ? 0.0 : cells.imbalance(c, k);
    bool by_pressure = false, failed = false;  // beyond the pure cells; and held there
    // (without pure cells there is no density to compare a mixed cell's with)
    if (m.pure_cells > 0 && cells.density(c, k) < rho_expanded) {
      const bool in_tension = p < p_stretched;
      m.expanded += !in_tension;
      // in tension and pulling harder than the cell's other materials
      const bool stretched = in_tension && out_of_balance > balance_margin;
      m.stretched += stretched;
      by_pressure = in_tension;
      failed = stretched;
    }
    // Against every material's pure cells: a contact's pressure that only
    // the other body's pure cells reach is no outlier (docs/method.md §4.9).
    if (!pure_p_all.empty() && pure_p_all.outside(p, 1.0)) {
      const bool outlier = std::abs(out_of_balance) > balance_margin;
      m.pressure_outliers += outlier;
      by_pressure = true;
      failed = failed || outlier;
    }
    // a body's own stress, balanced across its interface (a bent plate's
    // outer fibre in tension along the plate): reported, not failed
    m.in_balance += by_pressure && !failed;
  }
  const bool distributed = cells.fields.distributed;
  m.stretched = countOverRanks(m.stretched, distributed);
  m.expanded = countOverRanks(m.expanded, distributed);
  m.pressure_outliers = countOverRanks(m.pressure_outliers, distributed);
  m.in_balance = countOverRanks(m.in_balance, distributed);
}

// The cells not pure whose mixture pressure lies beyond the pure cells',
// held there (a material out of balance) or in balance.
void countMixtureOutliers(const CellsRead& cells, double balance_margin, MixedCellReport& report) {
  const bool distributed = cells.fields.distributed;
  Range pure_mixture;
  for (Index c = 0; c < cells.n_cells; ++c) {
    if (cells.fields.counts(c) && cells.pure(c)) pure_mixture.include(cells.fields.p(c));
  }
  pure_mixture.overRanks(distributed);
  report.mixture_p_pure_lo = pure_mixture.empty() ? 0.0 : pure_mixture.lo;
  report.mixture_p_pure_hi = pure_mixture.empty() ? 0.0 : pure_mixture.hi;
  for (Index c = 0; c < cells.n_cells; ++c) {
    if (!cells.fields.counts(c) || cells.pure(c)) continue;
    ++report.impure_cells;
    if (pure_mixture.empty() || !pure_mixture.outside(cells.fields.p(c), 0.5)) continue;
    // held there: a material of the cell out of balance with the others
    bool held = false;
    for (int k = 0; k < cells.n_materials; ++k) {
      held = held ||
             (cells.fields.alpha(c, k) > 0.0 && std::abs(cells.imbalance(c, k)) > balance_margin);
    }
    report.mixture_pressure_outliers += held;
    report.mixture_in_balance += !held;
  }
  report.impure_cells = countOverRanks(report.impure_cells, distributed);
  report.mixture_pressure_outliers = countOverRanks(report.mixture_pressure_outliers, distributed);
  report.mixture_in_balance = countOverRanks(report.mixture_in_balance, distributed);
}

}  // namespace

MixedCellReport measureMixedCells(const FinalFields& fields,
                                  const std::vector<MaterialParams>& materials) {
  const CellsRead cells(fields);
  MixedCellReport report;
  Range pure_p_all;  // every material's pure cells
  for (int k = 0; k < cells.n_materials; ++k) {
    report.materials.push_back(
        pureAndMixedCells(cells, k, isCondensed(materials[std::size_t(k)]), pure_p_all));
  }
  report.p_pure_all_lo = pure_p_all.empty() ? 0.0 : pure_p_all.lo;
  report.p_pure_all_hi = pure_p_all.empty() ? 0.0 : pure_p_all.hi;
  const double balance_margin = std::max(std::abs(pure_p_all.lo), std::abs(pure_p_all.hi));
  for (MaterialMixedCells& m : report.materials) {
    countStretchedAndOutliers(cells, pure_p_all, balance_margin, m);
  }
  countMixtureOutliers(cells, balance_margin, report);
  return report;
}

Check mixedCellsCheck(const MixedCellReport& report) {
  std::string what;
  const double worst = report.worstFraction(&what);
  Check check("mixed_cells", worst, 0.0, kMixedCellFractionBound,
              "largest fraction of mixed cells out of their material's pure state (" + what +
                  "): each condensed material's stretched (density 2% below its pure cells' "
                  "median at a pressure below their lowest and below 0, held in tension out of "
                  "balance with its cell's other materials; the expanded, hot at a higher "
                  "pressure, and a body's own stress in balance are not counted) and pressure "
                  "outliers (against every material's pure cells, out of balance), and the "
                  "mixture pressure outliers of the cells not pure (docs/method.md §4.9)");
  check.source = "mixed-cell state";
  return check;
}

std::string mixedCellsLine(const MixedCellReport& report) {
  std::string line = "mixed cells:";
  char text[256];
  for (const auto& m : report.materials) {
    if (!m.condensed) continue;
    std::snprintf(text, sizeof text,
                  " material %d: %ld of %ld stretched, %ld expanded, %ld p outliers, %ld in "
                  "balance, p %.3g .. %.3g GPa (pure %.3g .. %.3g);",
                  m.material, m.stretched, m.mixed_cells, m.expanded, m.pressure_outliers,
                  m.in_balance, m.p_mixed_lo / 1e9, m.p_mixed_hi / 1e9, m.p_pure_lo / 1e9,
                  m.p_pure_hi / 1e9);
    line += text;
  }
  std::snprintf(text, sizeof text, " pure p of all materials %.3g .. %.3g GPa;",
                report.p_pure_all_lo / 1e9, report.p_pure_all_hi / 1e9);
  line += text;
  std::snprintf(text, sizeof text, " mixture p: %ld of %ld not pure outside (%ld more in balance)",
                report.mixture_pressure_outliers, report.impure_cells, report.mixture_in_balance);
  return line + text;
}

}  // namespace lagremap
