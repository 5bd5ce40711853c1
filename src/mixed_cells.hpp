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
// A mixed cell's material is expanded below (1 - kStretchFraction) times the
// median density of that material's pure cells.
constexpr double kStretchFraction = 0.02;
// The mixed_cells check fails a run where a fraction is above this.
constexpr double kMixedCellFractionBound = 0.01;

// Of one condensed material (not an ideal gas), over its mixed cells
// (docs/method.md §4.9): `stretched` below (1 - kStretchFraction)
// rho_pure_median at a pressure below both p_pure_lo and 0, and held in
// tension by the closure: its normal stress across the interface
// (FinalFields::sigma_n_k) above its cell's other materials' by more than M
// (failed); `expanded` below that density otherwise (hot, thermally
// expanded: reported, not failed); `pressure_outliers` with a material
// pressure outside [min(lo, 0) - M, hi + M], lo .. hi the pressures of every
// material's pure cells (MixedCellReport::p_pure_all_lo .. p_pure_all_hi),
// M = max(|lo|, |hi|), and a normal stress more than M from the other
// materials' (failed); `in_balance` beyond the pure cells by its pressure
// but in balance across its interface, a body's own stress (a bent plate's
// outer fibre: reported, not failed).
struct MaterialMixedCells {
  int material = 0;
  bool condensed = false;
  long mixed_cells = 0, pure_cells = 0;
  long stretched = 0, expanded = 0, pressure_outliers = 0, in_balance = 0;
  double rho_pure_median = 0.0;
  double p_pure_lo = 0.0, p_pure_hi = 0.0;    // material pressure over its pure cells
  double p_mixed_lo = 0.0, p_mixed_hi = 0.0;  // material pressure over its mixed cells
  double stretchedFraction() const { return mixed_cells > 0 ? double(stretched) / mixed_cells : 0; }
  double expandedFraction() const { return mixed_cells > 0 ? double(expanded) / mixed_cells : 0; }
  double pressureOutlierFraction() const {
    return mixed_cells > 0 ? double(pressure_outliers) / mixed_cells : 0.0;
  }
};

// All materials; the range of the material pressures of every material's pure
// cells (the pressure outliers' reference); and the mixture pressure of the
// cells that are not pure in any material against [min(p_lo, 0) - M/2, p_hi +
// M/2], p_lo, p_hi and M = max |p| from the pure cells' mixture pressure: an
// outlier with a material out of balance with the others (as above), in
// balance otherwise (reported).
struct MixedCellReport {
  std::vector<MaterialMixedCells> materials;
  double p_pure_all_lo = 0.0, p_pure_all_hi = 0.0;
  long impure_cells = 0, mixture_pressure_outliers = 0, mixture_in_balance = 0;
  double mixture_p_pure_lo = 0.0, mixture_p_pure_hi = 0.0;
  double mixtureOutlierFraction() const {
    return impure_cells > 0 ? double(mixture_pressure_outliers) / impure_cells : 0.0;
  }
  bool hasCondensed() const;
  // The largest of the fractions the check bounds (not `expanded`), and what it is.
  double worstFraction(std::string* what = nullptr) const;
};

// Collective when the fields are distributed (owned cells counted once; the
// medians are exact over the ranks, the same number on any rank count).
MixedCellReport measureMixedCells(const FinalFields& fields,
                                  const std::vector<MaterialParams>& materials);

// The `mixed_cells` check: the worst fraction against kMixedCellFractionBound.
Check mixedCellsCheck(const MixedCellReport& report);

// One stdout line, e.g. "mixed cells: material 0: 0 of 1072 stretched, 3
// expanded, 0 p outliers, p -0.17 .. 0.21 GPa (pure -0.19 .. 0.23); pure p of
// all materials -0.19 .. 0.23 GPa; mixture p: 0 of 1300 not pure outside".
std::string mixedCellsLine(const MixedCellReport& report);

}  // namespace lagremap
