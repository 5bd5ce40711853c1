// Google Benchmark drivers of the solid constitutive kernels (docs/method.md §A7) and of
// the whole Lagrangian step on solid problems (CONTRIBUTING.md style 11):
//   BM_MieGruneisenEos     evaluateEos on the Al preset, densities 0.9-1.4 rho0
//                          and energies 0-1 MJ/kg;
//   BM_HypoElasticUpdate   jaumannUpdate + radialReturn with a velocity gradient
//                          of ~1e4 1/s and deviators of 0.5-1.5 times the yield
//                          radius, so about half the cells yield;
//   BM_NeoHookeanUpdate    pushForward of B with an incremental F (dt |L| ~ 1e-3)
//                          + neoHookeanDeviator, Steel-hyper;
//   BM_SolidFullStep       LagrangeStep::advance on `taylor` (hypo-elastic,
//                          plastic near the wall) and `beam` (Neo-Hookean) meshes
//                          scaled up, advanced a few dozen steps first.
// The pointwise kernels run over N cells of Views (inputs untouched, outputs
// written, so every iteration does the same work); every iteration is timed
// with a Kokkos::Timer closed by Kokkos::fence() (UseManualTime); rates are per
// cell (per cell-step for the full steps).
//
//   bench_constitutive [--cells=N] [--kokkos-threads=T] [--benchmark_...]
//   LAGREMAP_BENCH_CELLS=N (pointwise kernels, default 262144),
//   LAGREMAP_BENCH_SOLID_SCALE=S (cell-count scale of taylor, 0.6 S for the 3D
//   beam; default 4: taylor 800 x 160 x 1, beam 240 x 24 x 24),
//   LAGREMAP_BENCH_WARMUP=steps (default 40)
//
// Nothing is allocated inside a timed region.
#include <benchmark/benchmark.h>

#include <Kokkos_Core.hpp>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <stdexcept>
#include <string>

#include "bench_support.hpp"
#include "kernels/constitutive.hpp"
#include "kernels/eos.hpp"
#include "src/floating_point.hpp"
#include "src/kokkos_session.hpp"
#include "src/lagrange_step.hpp"
#include "src/materials.hpp"
#include "src/problem.hpp"
#include "src/run.hpp"

namespace {

using namespace lagremap;

using Mat9View = DeviceView<Real* [9]>;  // a Mat3 per cell, row-major

// The fixed dt of the timed full steps, as a fraction of the stable dt after
// warm-up (the restores between them: bench_support.hpp).
constexpr double kBenchDtFraction = 0.2;

// Reproducible uniform numbers in [0, 1) on any backend (splitmix64 of the
// cell id and a stream number).
KOKKOS_INLINE_FUNCTION double uniform01(std::uint64_t cell, std::uint64_t stream) {
  std::uint64_t z = cell * 0x9E3779B97F4A7C15ULL + stream * 0xD1B54A32D192ED03ULL + 1;
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
  z ^= z >> 31;
  return double(z >> 11) * (1.0 / 9007199254740992.0);
}

// A 3x3 matrix with entries uniform in [-1, 1).
KOKKOS_INLINE_FUNCTION Mat3 randomMat(std::uint64_t cell, std::uint64_t stream) {
  Mat3 a;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) a.m[i][j] = 2.0 * uniform01(cell, stream + 3 * i + j) - 1.0;
  return a;
}

template <class View>
KOKKOS_INLINE_FUNCTION void storeMat(const View& v, Index i, const Mat3& a) {
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) v(i, 3 * r + c) = a.m[r][c];
}
template <class View>
KOKKOS_INLINE_FUNCTION Mat3 loadMat(const View& v, Index i) {
  Mat3 a;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) a.m[r][c] = v(i, 3 * r + c);
  return a;
}

// ---------------------------------------------------------------- pointwise kernels

// Inputs and outputs of the three pointwise kernels, filled once.
class PointwiseData {
 public:
  explicit PointwiseData(Index n)
      : n_(n),
        al_(materialPreset("Al")),
        steel_(materialPreset("Steel-hyper")),
        rho_("bench::rho", n),
        e_("bench::e", n),
        p_("bench::p", n),
        sound_speed2_("bench::sound_speed2", n),
        grad_v_("bench::grad_v", n),
        S0_("bench::S0", n),
        S_("bench::S", n),
        yielded_("bench::yielded", n),
        F_("bench::F", n),
        J_("bench::J", n),
        B0_("bench::B0", n),
        B_("bench::B", n) {
    fillInputs();
  }

  // Random inputs of the three kernels. (Not in the constructor: nvcc's
  // extended lambdas may not live in one.)
  void fillInputs() {
    const MaterialParams al = al_;
    const auto rho = rho_, e = e_, J = J_;
    const auto grad_v = grad_v_, F = F_;
    const auto S0 = S0_, B0 = B0_;
    const double radius = math::sqrt(2.0 / 3.0) * al.yield_stress;
    Kokkos::parallel_for(
        "bench::fill", Kokkos::RangePolicy<ExecSpace>(0, n_), KOKKOS_LAMBDA(const Index c) {
          // EOS: compression 0.9-1.4 (tension to strong shock), e up to 1 MJ/kg.
          rho(c) = al.rho0 * (0.9 + 0.5 * uniform01(c, 0));
          e(c) = 1e6 * uniform01(c, 1);
          // Hypo-elastic: |L| ~ 1e4 1/s (Taylor bar near the wall); a deviator of
          // random direction and norm 0.5-1.5 times the yield radius.
          storeMat(grad_v, c, 1e4 * randomMat(c, 10));
          const Mat3 direction = randomMat(c, 20);
          const SymMat3 deviator = dev(symPart(direction));
          const double scale = (0.5 + uniform01(c, 30)) * radius / norm(deviator);
          storeSym(S0, c, scale * deviator);
          // Neo-Hookean: an accumulated deformation of ~5% and a step increment
          // F = I + dt L with dt |L| ~ 1e-3.
          const Mat3 deformation = identityMat() + 0.05 * randomMat(c, 40);
          const Mat3 increment = identityMat() + 1e-3 * randomMat(c, 50);
          storeMat(F, c, increment);
          storeSym(B0, c, pushForward(deformation, identitySym()));
          J(c) = det(increment * deformation);
        });
    Kokkos::fence();
  }

  void eos() const {
    const MaterialParams al = al_;
    const auto rho = rho_, e = e_, p = p_, sound_speed2 = sound_speed2_;
    Kokkos::parallel_for(
        "bench::mie_gruneisen_eos", Kokkos::RangePolicy<ExecSpace>(0, n_),
        KOKKOS_LAMBDA(const Index c) {
          const ThermoState thermo = evaluateEos(al, rho(c), e(c));
          p(c) = thermo.pressure;
          sound_speed2(c) = thermo.sound_speed2;
        });
  }

  // Mirrors the hypo-elastic branch of updateCell (updateMaterials, kernels/material_update.hpp).
  void hypoElastic(double dt) const {
    const double mu = al_.mu, yield_stress = al_.yield_stress;
    const auto grad_v = grad_v_;
    const auto S0 = S0_, S = S_;
    const auto yielded = yielded_;
    Kokkos::parallel_for(
        "bench::hypo_elastic_update", Kokkos::RangePolicy<ExecSpace>(0, n_),
        KOKKOS_LAMBDA(const Index c) {
          const SymMat3 trial = jaumannUpdate(loadSym(S0, c), loadMat(grad_v, c), mu, dt);
          const ReturnMapResult result = radialReturn(trial, yield_stress);
          storeSym(S, c, result.S);
          yielded(c) = result.yielded ? 1 : 0;
        });
  }

  // Mirrors the Neo-Hookean branches of updateCell and cellThermo.
  void neoHookean() const {
    const double mu = shearModulus(steel_);
    const auto F = F_;
    const auto J = J_;
    const auto B0 = B0_, B = B_, S = S_;
    Kokkos::parallel_for(
        "bench::neo_hookean_update", Kokkos::RangePolicy<ExecSpace>(0, n_),
        KOKKOS_LAMBDA(const Index c) {
          const SymMat3 pushed = pushForward(loadMat(F, c), loadSym(B0, c));
          storeSym(B, c, pushed);
          storeSym(S, c, neoHookeanDeviator(pushed, J(c), mu));
        });
  }

  double yieldedFraction() const {
    const auto yielded = yielded_;
    long count = 0;
    Kokkos::parallel_reduce(
        "bench::yielded_cells", Kokkos::RangePolicy<ExecSpace>(0, n_),
        KOKKOS_LAMBDA(const Index c, long& sum) { sum += yielded(c); }, count);
    return double(count) / double(n_);
  }

  Index cells() const { return n_; }

 private:
  Index n_;
  MaterialParams al_, steel_;
  RealView rho_, e_, p_, sound_speed2_;
  Mat9View grad_v_;
  Sym6View S0_, S_;
  DeviceView<int*> yielded_;
  Mat9View F_;
  RealView J_;
  Sym6View B0_, B_;
};

std::unique_ptr<PointwiseData> g_pointwise;

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

void setRate(benchmark::State& state, const char* name, Index cells) {
  state.counters[name] =
      benchmark::Counter(double(cells), benchmark::Counter::kIsIterationInvariantRate);
}

void BM_MieGruneisenEos(benchmark::State& state) {
  const PointwiseData& data = *g_pointwise;
  timedLoop(state, [&] { data.eos(); });
  setRate(state, "cells_per_second", data.cells());
}

void BM_HypoElasticUpdate(benchmark::State& state) {
  const PointwiseData& data = *g_pointwise;
  const double dt = 1e-7;  // 2 mu dt |D| ~ 0.2 of the yield radius
  timedLoop(state, [&] { data.hypoElastic(dt); });
  setRate(state, "cells_per_second", data.cells());
  state.counters["yielded_fraction"] = data.yieldedFraction();
}

void BM_NeoHookeanUpdate(benchmark::State& state) {
  const PointwiseData& data = *g_pointwise;
  timedLoop(state, [&] { data.neoHookean(); });
  setRate(state, "cells_per_second", data.cells());
}

// ---------------------------------------------------------------- full step

// A solid problem advanced past its start (the wave and plastic zone exist),
// with a snapshot of that state to start every benchmark from.
class SolidBench {
 public:
  SolidBench(const std::string& name, double scale, long warmup_steps) {
    const Problem& problem = findProblem(name);
    Config config = declareConfig(problem);
    config.scaleCellCounts(scale);
    setup_ = problem.setup(config);
    numerics_ = readNumerics(config);
    Mesh& mesh = setup_.mesh;
    state_ = allocateState(mesh, false);
    initializeState(setup_, state_);
    x_n_warm_ = Vec3View("bench::x_n_warm", mesh.n_nodes);
    v_c_warm_ = Vec3View("bench::v_c_warm", mesh.n_cells);
    E_c_warm_ = RealView("bench::E_c_warm", mesh.n_cells);
    dvdt_c_warm_ = RealView("bench::dvdt_c_warm", mesh.n_cells);
    S_ck_warm_ = MatSym6View("bench::S_ck_warm", state_.S_ck.extent(0), state_.S_ck.extent(1));
    B_ck_warm_ = MatSym6View("bench::B_ck_warm", state_.B_ck.extent(0), state_.B_ck.extent(1));
    e_ck_warm_ = MatRealView("bench::e_ck_warm", state_.e_ck.extent(0), state_.e_ck.extent(1));

    // The time loop of run.cpp (initial dt factor, growth limit), no outputs.
    LagrangeStep lagrange(mesh, state_, numerics_, timers_);
    StepLimit limit;
    time_ = bench::warmUp(lagrange, numerics_, warmup_steps, limit);
    dt_stable_ = limit.val;
    Kokkos::deep_copy(x_n_warm_, mesh.x_n);
    Kokkos::deep_copy(v_c_warm_, state_.v_c);
    Kokkos::deep_copy(E_c_warm_, state_.E_c);
    Kokkos::deep_copy(dvdt_c_warm_, state_.dvdt_c);
    Kokkos::deep_copy(S_ck_warm_, state_.S_ck);
    Kokkos::deep_copy(B_ck_warm_, state_.B_ck);
    Kokkos::deep_copy(e_ck_warm_, state_.e_ck);
    yielded_cells_ = countYieldedCells();
  }

  // Puts back the warm state (the solid's S and B included) and its geometry.
  void restore() {
    Kokkos::deep_copy(setup_.mesh.x_n, x_n_warm_);
    Kokkos::deep_copy(state_.v_c, v_c_warm_);
    Kokkos::deep_copy(state_.E_c, E_c_warm_);
    Kokkos::deep_copy(state_.dvdt_c, dvdt_c_warm_);
    Kokkos::deep_copy(state_.S_ck, S_ck_warm_);
    Kokkos::deep_copy(state_.B_ck, B_ck_warm_);
    Kokkos::deep_copy(state_.e_ck, e_ck_warm_);
    lagremap::computeGeometry(setup_.mesh, state_, numerics_.step);
    Kokkos::fence();
  }

  Mesh& mesh() { return setup_.mesh; }
  State& state() { return state_; }
  PhaseTimers& timers() { return timers_; }
  const Numerics& numerics() const { return numerics_; }
  Index cells() const { return setup_.mesh.n_cells; }
  double dtBench() const { return kBenchDtFraction * dt_stable_; }
  double time() const { return time_; }
  long yieldedCells() const { return yielded_cells_; }
  std::string meshText() const {
    return std::to_string(setup_.mesh.nx) + "x" + std::to_string(setup_.mesh.ny) + "x" +
           std::to_string(setup_.mesh.nz);
  }

  // (Public: nvcc's extended lambdas may not live in private member functions.)
  // Cells whose hypo-elastic material is on the yield surface (||S^k|| = sqrt(2/3) Y0 to 1e-9).
  long countYieldedCells() const {
    const auto s = state_;
    long count = 0;
    Kokkos::parallel_reduce(
        "bench::yielded_cells", Kokkos::RangePolicy<ExecSpace>(0, setup_.mesh.n_cells),
        KOKKOS_LAMBDA(const Index c, long& sum) {
          bool yielded = false;
          for (int k = 0; k < s.n_materials; ++k) {
            const MaterialParams& mat = s.materials(k);
            if (mat.strength != StrengthKind::HypoElastic || !(s.alpha_ck(c, k) > 0.0)) continue;
            const double radius = math::sqrt(2.0 / 3.0) * mat.yield_stress;
            yielded = yielded || norm(loadSym(s.S_ck, c, k)) > (1.0 - 1e-9) * radius;
          }
          sum += yielded ? 1 : 0;
        },
        count);
    return count;
  }

 private:
  ProblemSetup setup_;
  State state_;
  PhaseTimers timers_;
  Numerics numerics_;
  Vec3View x_n_warm_, v_c_warm_;
  RealView E_c_warm_, dvdt_c_warm_;
  MatSym6View S_ck_warm_, B_ck_warm_;
  MatRealView e_ck_warm_;
  double dt_stable_ = 0.0, time_ = 0.0;
  long yielded_cells_ = 0;
};

std::unique_ptr<SolidBench> g_taylor, g_beam;

// One whole step as the driver takes it (advance(dt) at a fixed dt).
void BM_SolidFullStep(benchmark::State& state, SolidBench* bench, int order) {
  bench::timedFullSteps(state, *bench, order);
  setRate(state, "cell_steps_per_second", bench->cells());
}

void registerBenchmarks() {
  auto manual = [](benchmark::internal::Benchmark* bench) {
    bench->UseManualTime()->Unit(benchmark::kMillisecond);
  };
  manual(benchmark::RegisterBenchmark("BM_MieGruneisenEos", BM_MieGruneisenEos));
  manual(benchmark::RegisterBenchmark("BM_HypoElasticUpdate", BM_HypoElasticUpdate));
  manual(benchmark::RegisterBenchmark("BM_NeoHookeanUpdate", BM_NeoHookeanUpdate));
  manual(benchmark::RegisterBenchmark("BM_SolidFullStep/taylor_order2", BM_SolidFullStep,
                                      g_taylor.get(), 2));
  manual(benchmark::RegisterBenchmark("BM_SolidFullStep/taylor_order1", BM_SolidFullStep,
                                      g_taylor.get(), 1));
  manual(benchmark::RegisterBenchmark("BM_SolidFullStep/beam_order2", BM_SolidFullStep,
                                      g_beam.get(), 2));
}

}  // namespace

int main(int argc, char* argv[]) {
  lagremap::flushDenormalsToZero();  // as the lagremap driver does
  lagremap::KokkosSession kokkos(argc, argv);
  long cells = 262144;
  if (const char* env = std::getenv("LAGREMAP_BENCH_CELLS")) cells = std::atol(env);
  if (const long flag = bench::takeFlag(argc, argv, "--cells=")) cells = flag;
  double scale = 4.0;
  if (const char* env = std::getenv("LAGREMAP_BENCH_SOLID_SCALE")) scale = std::atof(env);
  long warmup_steps = 40;
  if (const char* env = std::getenv("LAGREMAP_BENCH_WARMUP")) warmup_steps = std::atol(env);
  if (cells < 1 || cells >= (1L << 31) || !(scale > 0.0) || warmup_steps < 0) {
    std::fprintf(stderr,
                 "bench_constitutive: need 1 <= cells < 2^31, a positive scale and a warm-up "
                 ">= 0 steps\n");
    return 2;
  }

  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 2;

  try {
    g_pointwise = std::make_unique<PointwiseData>(Index(cells));
    g_taylor = std::make_unique<SolidBench>("taylor", scale, warmup_steps);
    // The beam is a real 3D mesh (100 x 10 x 10 cells by default): 0.6 of the
    // scale gives it about as many cells as the taylor slab.
    g_beam = std::make_unique<SolidBench>("beam", 0.6 * scale, warmup_steps);
  } catch (const std::exception& error) {
    std::fprintf(stderr, "bench_constitutive: set-up failed: %s\n", error.what());
    return 1;
  }
  const SolidBench& taylor = *g_taylor;
  const SolidBench& beam = *g_beam;
  std::fprintf(stderr,
               "bench_constitutive: %ld cells per pointwise kernel; taylor %s (%d cells, %ld "
               "yielded after %ld warm-up steps, t = %.3g), beam %s (%d cells); %s\n",
               cells, taylor.meshText().c_str(), taylor.cells(), taylor.yieldedCells(),
               warmup_steps, taylor.time(), beam.meshText().c_str(), beam.cells(),
               executionSpaceText().c_str());
  const std::string summary = "constitutive kernels over " + std::to_string(cells) +
                              " cells; full steps on taylor " + taylor.meshText() + " (" +
                              std::to_string(taylor.yieldedCells()) + " cells yielded) and beam " +
                              beam.meshText() + " after " + std::to_string(warmup_steps) +
                              " warm-up steps, " + ExecSpace::name();
  benchmark::AddCustomContext("summary", summary);
  benchmark::AddCustomContext("cells", std::to_string(cells));
  benchmark::AddCustomContext("taylor_mesh", taylor.meshText());
  benchmark::AddCustomContext("taylor_yielded_cells", std::to_string(taylor.yieldedCells()));
  benchmark::AddCustomContext("beam_mesh", beam.meshText());
  benchmark::AddCustomContext("execution_space", ExecSpace::name());
  benchmark::AddCustomContext("kokkos_threads", std::to_string(ExecSpace().concurrency()));
  benchmark::AddCustomContext("warmup_steps", std::to_string(warmup_steps));

  registerBenchmarks();
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  g_taylor.reset();  // the Views go before Kokkos::finalize
  g_beam.reset();
  g_pointwise.reset();
  return 0;
}
