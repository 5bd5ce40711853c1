// The state of the mixed cells at the end of a remap run (docs/method.md
// §4.9): whether each condensed material keeps its own density and a
// pressure like its pure cells' where it shares a cell with another material.
#pragma once

#include <string>
#include <vector>

#include "data/material_params.hpp"
#include "problem.hpp"

namespace lagremap {

// A cell is pure in a material above this volume fraction, and a material is
// mixed in it between kMixedAlphaLow and 1 - kMixedAlphaLow.
constexpr double kPureAlpha = 0.999;
constexpr double kMixedAlphaLow = 0.01;
// A mixed cell's material is stretched below (1 - kStretchFraction) times the
// median density of that material's pure cells.
constexpr double kStretchFraction = 0.02;
// The mixed_cells check fails a run where a fraction is above this.
constexpr double kMixedCellFractionBound = 0.01;

// Of one condensed material (not an ideal gas), over its mixed cells:
// `stretched` below (1 - kStretchFraction) rho_pure_median, `pressure_outliers`
// with a material pressure outside [min(p_pure_lo, 0) - M, p_pure_hi + M], M =
// max |p| over the material's pure cells.
struct MaterialMixedCells {
  int material = 0;
  bool condensed = false;
  long mixed_cells = 0, pure_cells = 0;
  long stretched = 0, pressure_outliers = 0;
  double rho_pure_median = 0.0;
  double p_pure_lo = 0.0, p_pure_hi = 0.0;
  double p_mixed_lo = 0.0, p_mixed_hi = 0.0;  // material pressure over its mixed cells
  double stretchedFraction() const { return mixed_cells > 0 ? double(stretched) / mixed_cells : 0; }
  double pressureOutlierFraction() const {
    return mixed_cells > 0 ? double(pressure_outliers) / mixed_cells : 0.0;
  }
};

// All materials, and the mixture pressure of the cells that are not pure in
// any material against [min(p_lo, 0) - M/2, p_hi + M/2], p_lo, p_hi and M =
// max |p| from the pure cells' mixture pressure.
struct MixedCellReport {
  std::vector<MaterialMixedCells> materials;
  long impure_cells = 0, mixture_pressure_outliers = 0;
  double mixture_p_pure_lo = 0.0, mixture_p_pure_hi = 0.0;
  double mixtureOutlierFraction() const {
    return impure_cells > 0 ? double(mixture_pressure_outliers) / impure_cells : 0.0;
  }
  bool hasCondensed() const;
  // The largest of the fractions the check bounds, and what it is.
  double worstFraction(std::string* what = nullptr) const;
};

// Collective when the fields are distributed (owned cells counted once; the
// medians are exact over the ranks, the same number on any rank count).
MixedCellReport measureMixedCells(const FinalFields& fields,
                                  const std::vector<MaterialParams>& materials);

// The `mixed_cells` check: the worst fraction against kMixedCellFractionBound.
Check mixedCellsCheck(const MixedCellReport& report);

// One stdout line, e.g. "mixed cells: material 0: 0 of 1072 stretched, 0 p
// outliers, p -0.17 .. 0.21 GPa (pure -0.19 .. 0.23); mixture p: 0 of 1300
// outliers".
std::string mixedCellsLine(const MixedCellReport& report);

}  // namespace lagremap
