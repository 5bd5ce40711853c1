// What the kernels of one step leave for the host (docs/performance.md §8):
// its time-step limits, the remap's boundary crossings, the conservation
// totals, the boundaries' force and power, the mesh quality and the
// problem's probe. Each is written by a reduction that does not wait, into
// memory the host reads in place (ReportSpace); the host reads them all after
// the step's one fence, then reduces them over the ranks.
#pragma once

#include "data/types.hpp"
#include "kernels/audit_sums.hpp"
#include "kernels/sum_array.hpp"
#include "kernels/time_step.hpp"

namespace lagremap {

// Where a problem's probe leaves its reductions (Problem::probe).
struct ProbeSlots {
  ReportView<SumArray<2>> sums{"lagremap::report::probe_sums"};
  ReportView<double> scalar{"lagremap::report::probe_scalar"};  // a sum, a min or a max
};

struct StepReport {
  StepLimitView predictor{"lagremap::report::predictor"};      // the half-step state
  StepLimitView end_of_step{"lagremap::report::end_of_step"};  // the corrector's
  StepLimitView after_remap{"lagremap::report::after_remap"};  // the remapped state
  // the remap's outer-face crossings and the remapped cells' totals (RemapAudit)
  RemapAuditView remap{"lagremap::report::remap", kRemapAuditSums};
  // the conservation audit's sums: the cells' totals, the boundary's work
  CellTotalSumsView totals{"lagremap::report::totals"};
  BoundaryPowerView boundary{"lagremap::report::boundary"};
  ReportView<double> mesh_quality{"lagremap::report::mesh_quality"};
  ProbeSlots probe;
};

}  // namespace lagremap
