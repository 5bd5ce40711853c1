// What a run costs each rank (issue: memory that shrinks with the rank count,
// set-up time per phase, halo traffic): measured on every rank, then gathered
// over the ranks for summary.json (docs/performance.md, Parallel runs).
#pragma once

#include "parallel.hpp"

namespace lagremap {

// Peak resident memory of this process so far [bytes]: the high-water mark of
// its resident set (getrusage), what the machine had to give it, MPI's and
// Kokkos's own buffers included.
long peakResidentBytes();
// Resident pages of this process that others may map too [bytes]: mapped
// files (the code and data of its shared libraries) and shared memory (MPI's
// segments between the ranks of a machine); 0 where /proc does not say.
// Every rank of a node counts them in its resident set, the node holds them
// once; peakResidentBytes() less this, taken at the end of a run, is the
// rank's own peak (docs/performance.md §6.1).
long sharedResidentBytes();

// Wall time of the set-up phases on one rank [s].
struct SetupSeconds {
  double generate = 0.0;          // the problem's mesh and initial cells (Problem::setup) but:
  double sample_materials = 0.0;  // the mixed-cell sampling (fillMaterialRegions)
  double decompose = 0.0;         // this rank's part and its halo
  double initialize = 0.0;        // state, geometry, remap tables, a checkpoint's state
  double total() const { return generate + sample_materials + decompose + initialize; }
};

// A run's costs over the ranks (collected collectively at its end).
struct RankCosts {
  parallel::Spread peak_bytes;        // whole run
  parallel::Spread peak_own_bytes;    // whole run, less the shared pages at its end
  parallel::Spread setup_peak_bytes;  // at the end of set-up
  parallel::Spread owned_cells;       // cells each rank updates
  parallel::Spread peak_bytes_per_owned_cell;
  SetupSeconds setup;  // the slowest rank's, phase by phase
  // Halo traffic per step (steps of this process), all ranks together: what
  // the ranks send (each message is received once).
  double halo_bytes_per_step = 0.0, halo_messages_per_step = 0.0;
  double halo_cell_bytes_per_step = 0.0, halo_node_bytes_per_step = 0.0;
  double halo_bytes_per_step_max_rank = 0.0;  // the busiest rank's
  double reductions_per_step = 0.0;           // collective reductions (dt, totals, probes)
};

}  // namespace lagremap
