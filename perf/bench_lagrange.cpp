// Google Benchmark drivers of the Lagrange-Remap step (CONTRIBUTING.md
// style 11): each kernel of the Lagrangian step (docs/method.md §A4-A5) and of the
// remap (docs/method.md §A9: densities, gradients, swept faces, fluxes and
// update), the whole remap and whole steps,
// on the `sedov` blast at N^3 cells, advanced a few dozen steps first so the
// shock exists (limiters and wall mirrors take their nontrivial branches).
// Every iteration is timed with a Kokkos::Timer closed by Kokkos::fence()
// (UseManualTime); rates are per cell.
//
//   bench_lagrange [--n=N] [--kokkos-threads=T] [--benchmark_...]
//   LAGREMAP_BENCH_N=N (default 60), LAGREMAP_BENCH_WARMUP=steps (default 40)
//
// Nothing is allocated inside a timed region: the state, its warm snapshot and
// the remap kernels' work arrays are allocated once in main(), and each
// benchmark starts from that snapshot.
#include <benchmark/benchmark.h>

#include <Kokkos_Core.hpp>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "bench_support.hpp"
#include "kernels/cell_update.hpp"
#include "kernels/corner_terms.hpp"
#include "kernels/geometry.hpp"
#include "kernels/nodal_solver.hpp"
#include "kernels/remap.hpp"
#include "kernels/swept_face.hpp"
#include "src/floating_point.hpp"
#include "src/kokkos_session.hpp"
#include "src/lagrange_step.hpp"
#include "src/mesh_relaxation.hpp"
#include "src/problem.hpp"
#include "src/remap_step.hpp"
#include "src/run.hpp"

namespace {

using namespace lagremap;

// The fixed dt of the timed steps, as a fraction of the stable dt after warm-up.
constexpr double kBenchDtFraction = 0.2;

// The developed blast and everything the benchmarks share.
class Bench {
 public:
  Bench(int n, long warmup_steps) {
    // (a named argument: GCC 13 warns of a reference returned from a call
    // with a temporary one, -Wdangling-reference)
    const std::string sedov = "sedov";
    const Problem& problem = findProblem(sedov);
    Config config = declareConfig(problem);
    config.set("mesh.nx", std::to_string(n));
    config.set("mesh.ny", std::to_string(n));
    config.set("mesh.nz", std::to_string(n));
    setup_ = problem.setup(config);
    numerics_ = readNumerics(config);
    Mesh& mesh = setup_.mesh;
    // Atomics node sums allocated too: the Gather::Atomics variants need them.
    state_ = allocateState(mesh, true);
    initializeState(setup_, state_);
    own_corners_ = state_;
    x_n_warm_ = Vec3View("bench::x_n_warm", mesh.n_nodes);
    v_c_warm_ = Vec3View("bench::v_c_warm", mesh.n_cells);
    E_c_warm_ = RealView("bench::E_c_warm", mesh.n_cells);
    dvdt_c_warm_ = RealView("bench::dvdt_c_warm", mesh.n_cells);

    // The time loop of run.cpp (initial dt factor, growth limit), no outputs.
    const Kokkos::Timer wall;
    LagrangeStep lagrange(mesh, state_, numerics_, timers_);
    StepLimit limit;
    time_ = bench::warmUp(lagrange, numerics_, warmup_steps, limit);
    warmup_seconds_ = wall.seconds();
    dt_stable_ = limit.val;
    Kokkos::deep_copy(x_n_warm_, mesh.x_n);
    Kokkos::deep_copy(v_c_warm_, state_.v_c);
    Kokkos::deep_copy(E_c_warm_, state_.E_c);
    Kokkos::deep_copy(dvdt_c_warm_, state_.dvdt_c);
    m_c_warm_ = RealView("bench::m_c_warm", mesh.n_cells);
    Kokkos::deep_copy(m_c_warm_, state_.m_c);
    m_ck_warm_ = MatRealView("bench::m_ck_warm", mesh.n_cells, state_.n_materials);
    Kokkos::deep_copy(m_ck_warm_, state_.m_ck);
    e_ck_warm_ = MatRealView("bench::e_ck_warm", mesh.n_cells, state_.n_materials);
    Kokkos::deep_copy(e_ck_warm_, state_.e_ck);
    shocked_cells_ = countShockedCells(config.real("ambient.rho"));
  }

  // Puts back the warm state: positions, velocities, energies, the derived
  // cell fields, and the start-of-step copies the node and cell kernels read.
  void restore() {
    // (a RemapStep moves the corner arrays into its work memory, which goes
    // with it: a benchmark after one gets them back)
    state_.A_cp = own_corners_.A_cp;
    state_.M_cp = own_corners_.M_cp;
    state_.B_cp = own_corners_.B_cp;
    Kokkos::deep_copy(setup_.mesh.x_n, x_n_warm_);
    Kokkos::deep_copy(state_.v_c, v_c_warm_);
    Kokkos::deep_copy(state_.E_c, E_c_warm_);
    Kokkos::deep_copy(state_.dvdt_c, dvdt_c_warm_);
    Kokkos::deep_copy(state_.m_c, m_c_warm_);  // the remap changes the masses
    Kokkos::deep_copy(state_.m_ck, m_ck_warm_);
    Kokkos::deep_copy(state_.e_ck, e_ck_warm_);
    lagremap::computeGeometry(setup_.mesh, state_, numerics_.step);
    Kokkos::deep_copy(state_.x_n0, setup_.mesh.x_n);
    Kokkos::deep_copy(state_.v_c0, state_.v_c);
    Kokkos::deep_copy(state_.E_c0, state_.E_c);
    Kokkos::fence();
  }

  Mesh& mesh() { return setup_.mesh; }
  State& state() { return state_; }
  PhaseTimers& timers() { return timers_; }
  const Numerics& numerics() const { return numerics_; }
  Index cells() const { return setup_.mesh.n_cells; }
  Index nodes() const { return setup_.mesh.n_nodes; }
  double dtBench() const { return kBenchDtFraction * dt_stable_; }
  double time() const { return time_; }
  double warmupSeconds() const { return warmup_seconds_; }
  long shockedCells() const { return shocked_cells_; }

  // (Public: nvcc's extended lambdas may not live in private member functions.)
  // Cells whose density left the ambient value by more than 1%: the blast.
  long countShockedCells(double rho_ambient) const {
    const auto rho = state_.rho_c;
    long count = 0;
    Kokkos::parallel_reduce(
        "bench::shocked_cells", Kokkos::RangePolicy<ExecSpace>(0, setup_.mesh.n_cells),
        KOKKOS_LAMBDA(const Index c, long& sum) {
          sum += math::fabs(rho(c) - rho_ambient) > 0.01 * rho_ambient ? 1 : 0;
        },
        count);
    return count;
  }

 private:
  ProblemSetup setup_;
  State state_;
  State own_corners_;  // the state as allocated: its corner arrays (restore)
  PhaseTimers timers_;
  Numerics numerics_;
  Vec3View x_n_warm_, v_c_warm_;
  RealView E_c_warm_, dvdt_c_warm_, m_c_warm_;
  MatRealView m_ck_warm_, e_ck_warm_;
  double dt_stable_ = 0.0, time_ = 0.0, warmup_seconds_ = 0.0;
  long shocked_cells_ = 0;
};

std::unique_ptr<Bench> g_bench;

// The inputs of the remap's kernels, one Lagrangian step off the warm state,
// in the benchmark's own work arrays: RemapStep keeps its private, so they are
// allocated as its constructor allocates them, with the same layout.
struct RemapInputs {
  explicit RemapInputs(Bench& b)
      : layout(makeRemapLayout(b.state())),
        x_target("bench::remap::x_target", b.nodes()),
        fields(allocateRemapFields(b.cells(), layout)),
        swept(allocateSweptFaces(b.mesh())) {}

  // Untimed: the warm state, whose positions become the remap target (as
  // BM_Remap's RemapStep keeps them), one Lagrangian step off it, then the
  // kernels of RemapStep::apply() that precede the update. Densities,
  // gradients and swept faces write nothing they or the earlier ones read, so
  // each can be timed over and over on these inputs; the update overwrites
  // the state the densities come from.
  void prepare(Bench& b) {
    b.restore();
    Kokkos::deep_copy(x_target, b.mesh().x_n);
    LagrangeStep lagrange(b.mesh(), b.state(), b.numerics(), b.timers());
    lagrange.advance(b.dtBench(), 1);
    remapDensities(b.state(), layout, fields);
    remapGradients(b.mesh(), b.state(), layout, controls, fields);
    computeSweptFaces(b.mesh(), b.mesh().x_n, x_target, swept);
    Kokkos::fence();
  }

  RemapControls controls;  // BM_Remap's: the defaults
  RemapLayout layout;
  Vec3View x_target;
  RemapFields fields;
  SweptFaces swept;
};

std::unique_ptr<RemapInputs> g_remap;

// Per-cell rate of one kernel (kIsIterationInvariantRate: cells x iterations / manual time).
void setCellRate(benchmark::State& state, const char* name) {
  state.counters[name] =
      benchmark::Counter(double(g_bench->cells()), benchmark::Counter::kIsIterationInvariantRate);
}

// Runs `body` once per iteration, timed by a Kokkos::Timer opened and closed
// by a fence (on an asynchronous backend, set-up kernels launched before the
// loop would otherwise run inside the first timed iteration).
template <class Body>
void timedLoop(benchmark::State& state, Body&& body) {
  for (auto _ : state) {
    Kokkos::fence();
    Kokkos::Timer timer;
    body();
    Kokkos::fence();
    state.SetIterationTime(timer.seconds());
  }
}

void BM_Geometry(benchmark::State& state) {
  Bench& b = *g_bench;
  b.restore();
  const StepLimitView limit("bench::limit");
  timedLoop(state,
            [&] { lagremap::computeGeometry(b.mesh(), b.state(), b.numerics().step, limit); });
  setCellRate(state, "cells_per_second");
}

void BM_CornerTerms(benchmark::State& state, int order, Gather gather) {
  Bench& b = *g_bench;
  b.restore();
  const CornerControls controls{order, gather};
  timedLoop(state, [&] { computeCornerTerms(b.mesh(), b.state(), controls); });
  setCellRate(state, "cells_per_second");
}

// Corner terms + nodal solve, the pair whose split differs between the gathers
// (Atomics: the node sums are scattered by the corner kernel).
void BM_NodalSolve(benchmark::State& state, Gather gather) {
  Bench& b = *g_bench;
  b.restore();
  const CornerControls controls{2, gather};
  const double dt_stage = 0.5 * b.dtBench();
  timedLoop(state, [&] {
    computeCornerTerms(b.mesh(), b.state(), controls);
    nodalSolve(b.mesh(), b.state(), controls, dt_stage);
  });
  setCellRate(state, "cells_per_second");
}

// The node kernel alone (node sums gathered via CRS, or read from M_n/B_n).
void BM_NodalSolveOnly(benchmark::State& state, Gather gather) {
  Bench& b = *g_bench;
  b.restore();
  const CornerControls controls{2, gather};
  const double dt_stage = 0.5 * b.dtBench();
  computeCornerTerms(b.mesh(), b.state(), controls);
  timedLoop(state, [&] { nodalSolve(b.mesh(), b.state(), controls, dt_stage); });
  setCellRate(state, "cells_per_second");
}

void BM_CellUpdate(benchmark::State& state) {
  Bench& b = *g_bench;
  b.restore();
  const CornerControls controls{2, Gather::Crs};
  const double dt_stage = 0.5 * b.dtBench();
  computeCornerTerms(b.mesh(), b.state(), controls);
  nodalSolve(b.mesh(), b.state(), controls, dt_stage);
  timedLoop(state, [&] { updateCells(b.mesh(), b.state(), dt_stage); });
  setCellRate(state, "cells_per_second");
}

void BM_UpdateAndGeometry(benchmark::State& state) {
  Bench& b = *g_bench;
  b.restore();
  const CornerControls controls{2, Gather::Crs};
  const double dt_stage = 0.5 * b.dtBench();
  computeCornerTerms(b.mesh(), b.state(), controls);
  nodalSolve(b.mesh(), b.state(), controls, dt_stage);
  const StepLimitView limit("bench::limit");
  timedLoop(state, [&] {
    updateCellsAndGeometry(b.mesh(), b.state(), dt_stage, b.numerics().step, limit);
  });
  setCellRate(state, "cells_per_second");
}

// One whole step as the driver takes it: advance(dt), whose last sweep also
// gives the next step's geometry and dt candidates.
void BM_FullStep(benchmark::State& state, int order) {
  bench::timedFullSteps(state, *g_bench, order);
  setCellRate(state, "cell_steps_per_second");
}

// The remap alone (docs/method.md §A9: densities, gradients, swept regions, fluxes and
// update) after an untimed Lagrangian step has moved the mesh off its target.
void BM_Remap(benchmark::State& state) {
  Bench& b = *g_bench;
  b.restore();
  RemapStep remap(b.mesh(), b.state(), RemapControls(), b.timers());
  LagrangeStep lagrange(b.mesh(), b.state(), b.numerics(), b.timers());
  const double dt = b.dtBench();
  long step = 0;
  for (auto _ : state) {
    lagrange.advance(dt, ++step);  // untimed: the Lagrangian mesh to remap from
    Kokkos::fence();
    Kokkos::Timer timer;
    const RemapBoundaryFlux crossed = remap.apply();
    Kokkos::fence();
    state.SetIterationTime(timer.seconds());
    benchmark::DoNotOptimize(crossed.v[0]);
    lagrange.computeGeometry();
  }
  setCellRate(state, "cells_per_second");
}

// The kernels of RemapStep::apply() one at a time, on the inputs of BM_Remap's
// first iteration (RemapInputs::prepare). Their sum is BM_Remap's time less
// its copies (masses and fractions saved, the mesh put back), give or take the
// later iterations of BM_Remap remapping a blast a few steps further on.
void BM_RemapDensities(benchmark::State& state) {
  Bench& b = *g_bench;
  RemapInputs& r = *g_remap;
  r.prepare(b);
  timedLoop(state, [&] { remapDensities(b.state(), r.layout, r.fields); });
  setCellRate(state, "cells_per_second");
}

void BM_RemapGradients(benchmark::State& state) {
  Bench& b = *g_bench;
  RemapInputs& r = *g_remap;
  r.prepare(b);
  timedLoop(state, [&] { remapGradients(b.mesh(), b.state(), r.layout, r.controls, r.fields); });
  setCellRate(state, "cells_per_second");
}

void BM_SweptFaces(benchmark::State& state) {
  Bench& b = *g_bench;
  RemapInputs& r = *g_remap;
  r.prepare(b);
  timedLoop(state, [&] { computeSweptFaces(b.mesh(), b.mesh().x_n, r.x_target, r.swept); });
  setCellRate(state, "cells_per_second");
}

// Upwind fluxes, clean-up and kinetic-energy fix (one fused kernel). It
// overwrites the masses, velocities and energies, so the inputs are prepared
// again before every iteration: each one remaps the same Lagrangian state,
// whatever the kernel comes to read.
void BM_RemapFluxes(benchmark::State& state) {
  Bench& b = *g_bench;
  RemapInputs& r = *g_remap;
  const RemapAuditView audit("bench::remap_audit", kRemapAuditSums);
  for (auto _ : state) {
    r.prepare(b);  // untimed
    Kokkos::fence();
    Kokkos::Timer timer;
    remapUpdate(b.mesh(), b.state(), r.layout, r.controls, r.fields, r.swept, audit);
    Kokkos::fence();
    state.SetIterationTime(timer.seconds());
  }
  setCellRate(state, "cells_per_second");
}

// ALE mode's relaxation alone (docs/method.md §8): Winslow targets of the
// warmed-up Lagrangian mesh, the move limit and the quality guard's passes.
void BM_MeshRelaxation(benchmark::State& state) {
  Bench& b = *g_bench;
  b.restore();
  MeshRelaxation relaxation(b.mesh(), RelaxationControls(), 1, b.timers());
  for (auto _ : state) {
    Kokkos::Timer timer;
    const Vec3View& target = relaxation.target();
    Kokkos::fence();
    state.SetIterationTime(timer.seconds());
    benchmark::DoNotOptimize(target.data());
  }
  setCellRate(state, "cells_per_second");
}

// A whole Lagrange-Remap step as the driver takes it: the Lagrangian step, the
// remap and the geometry launched, then one fence for the step's report;
// `ale`: an ALE step, the remap onto the relaxed mesh (docs/method.md §8).
// Its counters: the Kokkos events of a step (src/kokkos_events.hpp).
void BM_LagrangeRemapStep(benchmark::State& state, bool ale) {
  Bench& b = *g_bench;
  b.restore();
  RemapStep remap(b.mesh(), b.state(), RemapControls(), b.timers());
  LagrangeStep lagrange(b.mesh(), b.state(), b.numerics(), b.timers());
  MeshRelaxation relaxation(b.mesh(), RelaxationControls(), 1, b.timers());
  if (ale) {
    lagrange.remapFollowsNextStep(true);  // as the driver does, every step
  } else {
    lagrange.remapFollowsEveryStep();
  }
  const double dt = b.dtBench();
  StepReport report;
  StepEvents events;
  for (auto _ : state) {
    const KokkosEventCounts before = kokkosEventCounts();
    Kokkos::Timer timer;
    lagrange.launch(dt, report);
    if (ale) {
      remap.launch(relaxation.target(), report.remap);
    } else {
      remap.launch(report.remap);
    }
    lagrange.computeGeometry(report.after_remap);
    fenceFor("bench: the step's report");
    state.SetIterationTime(timer.seconds());
    events.add(kokkosEventCounts() - before);
    if (report.predictor().val < 0.0 || report.after_remap().val < dt) {
      state.SkipWithError("the fixed benchmark dt exceeds the stable dt");
      break;
    }
  }
  setCellRate(state, "cell_steps_per_second");
  bench::setEventCounters(state, events);
}

void registerBenchmarks() {
  auto manual = [](benchmark::internal::Benchmark* bench) {
    bench->UseManualTime()->Unit(benchmark::kMillisecond);
  };
  manual(benchmark::RegisterBenchmark("BM_Geometry", BM_Geometry));
  manual(benchmark::RegisterBenchmark("BM_CornerTerms/order2", BM_CornerTerms, 2, Gather::Crs));
  manual(benchmark::RegisterBenchmark("BM_CornerTerms/order2_atomics", BM_CornerTerms, 2,
                                      Gather::Atomics));
  manual(benchmark::RegisterBenchmark("BM_NodalSolve/crs", BM_NodalSolve, Gather::Crs));
  manual(benchmark::RegisterBenchmark("BM_NodalSolve/atomics", BM_NodalSolve, Gather::Atomics));
  manual(benchmark::RegisterBenchmark("BM_NodalSolveOnly/crs", BM_NodalSolveOnly, Gather::Crs));
  manual(benchmark::RegisterBenchmark("BM_NodalSolveOnly/atomics", BM_NodalSolveOnly,
                                      Gather::Atomics));
  manual(benchmark::RegisterBenchmark("BM_CellUpdate", BM_CellUpdate));
  manual(benchmark::RegisterBenchmark("BM_UpdateAndGeometry", BM_UpdateAndGeometry));
  manual(benchmark::RegisterBenchmark("BM_FullStep/order1", BM_FullStep, 1));
  manual(benchmark::RegisterBenchmark("BM_FullStep/order2", BM_FullStep, 2));
  manual(benchmark::RegisterBenchmark("BM_Remap", BM_Remap));
  manual(benchmark::RegisterBenchmark("BM_RemapDensities", BM_RemapDensities));
  manual(benchmark::RegisterBenchmark("BM_RemapGradients", BM_RemapGradients));
  manual(benchmark::RegisterBenchmark("BM_SweptFaces", BM_SweptFaces));
  manual(benchmark::RegisterBenchmark("BM_RemapFluxes", BM_RemapFluxes));
  manual(benchmark::RegisterBenchmark("BM_LagrangeRemapStep/order2", BM_LagrangeRemapStep, false));
  manual(benchmark::RegisterBenchmark("BM_MeshRelaxation", BM_MeshRelaxation));
  manual(benchmark::RegisterBenchmark("BM_AleStep/order2", BM_LagrangeRemapStep, true));
}

}  // namespace

int main(int argc, char* argv[]) {
  lagremap::flushDenormalsToZero();  // as the lagremap driver does
  lagremap::KokkosSession kokkos(argc, argv);
  int n = 60;
  if (const char* env = std::getenv("LAGREMAP_BENCH_N")) n = std::atoi(env);
  if (const int flag = bench::takeFlag(argc, argv, "--n=")) n = flag;
  long warmup_steps = 40;
  if (const char* env = std::getenv("LAGREMAP_BENCH_WARMUP")) warmup_steps = std::atol(env);
  if (n < 2 || warmup_steps < 0) {
    std::fprintf(stderr, "bench_lagrange: N must be >= 2 and the warm-up >= 0 steps\n");
    return 2;
  }

  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 2;

  try {
    g_bench = std::make_unique<Bench>(n, warmup_steps);
    g_remap = std::make_unique<RemapInputs>(*g_bench);
  } catch (const std::exception& error) {
    std::fprintf(stderr, "bench_lagrange: set-up failed: %s\n", error.what());
    return 1;
  }
  const Bench& b = *g_bench;
  std::fprintf(stderr,
               "bench_lagrange: sedov %d^3 (%d cells, %d nodes), %s, warm-up %ld steps "
               "(t = %.3g, %.1f s), %ld shocked cells, bench dt = %.3g\n",
               n, b.cells(), b.nodes(), executionSpaceText().c_str(), warmup_steps, b.time(),
               b.warmupSeconds(), b.shockedCells(), b.dtBench());
  benchmark::AddCustomContext("problem", "sedov");
  benchmark::AddCustomContext("n", std::to_string(n));
  benchmark::AddCustomContext("cells", std::to_string(b.cells()));
  benchmark::AddCustomContext("nodes", std::to_string(b.nodes()));
  benchmark::AddCustomContext("execution_space", ExecSpace::name());
  benchmark::AddCustomContext("kokkos_threads", std::to_string(ExecSpace().concurrency()));
  benchmark::AddCustomContext("warmup_steps", std::to_string(warmup_steps));
  benchmark::AddCustomContext("warmup_time", std::to_string(b.time()));
  benchmark::AddCustomContext("shocked_cells", std::to_string(b.shockedCells()));
  benchmark::AddCustomContext("bench_dt", std::to_string(b.dtBench()));

  registerBenchmarks();
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  g_remap.reset();  // the Views go before Kokkos::finalize
  g_bench.reset();
  return 0;
}
