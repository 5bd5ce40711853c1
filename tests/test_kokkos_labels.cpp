// Every kernel launch of a step is labelled lagremap::<phase>::<kernel>, every
// View lagremap::<area>::<name>, and each phase is one profiling region
// (CONTRIBUTING.md style 7), checked through Kokkos Tools callbacks installed in-process.
#include <gtest/gtest.h>

#include <cstdint>
#include <mutex>
#include <regex>
#include <set>
#include <string>
#include <vector>

#include "kernels/kernel_form.hpp"
#include "src/kokkos_events.hpp"
#include "test_support.hpp"

namespace lagremap {
namespace {

std::set<std::string> g_kernels, g_regions, g_allocations;
std::mutex g_mutex;

void onBeginKernel(const char* name, uint32_t, uint64_t* id) {
  std::lock_guard<std::mutex> lock(g_mutex);
  g_kernels.insert(name);
  *id = 0;
}
void onPushRegion(const char* name) {
  std::lock_guard<std::mutex> lock(g_mutex);
  g_regions.insert(name);
}
void onAllocate(Kokkos::Tools::SpaceHandle, const char* name, const void*, uint64_t) {
  std::lock_guard<std::mutex> lock(g_mutex);
  g_allocations.insert(name);
}

TEST(KokkosTools, EveryLaunchAndViewIsLabelledAndEachPhaseIsARegion) {
  namespace tools = Kokkos::Tools::Experimental;
  // each kernel form the build has (the fused one on CPU backends only), both gathers
  std::vector<std::string> forms{"staged"};
  if (kFusedKernelsBuilt) forms.push_back("fused");
  const auto runEach = [&] {
    for (const std::string& form : forms) {
      for (const char* gather : {"crs", "atomics"}) {
        runProblem(testing::problemOptions(
            "sod", {"mesh.nx=20", "t_end=0.01", std::string("numerics.gather=") + gather,
                    "numerics.kernels=" + form}));
      }
    }
  };
  // (once before watching: Kokkos' OpenMP back-end grows its per-thread
  // reduction buffers, unlabelled, on first need)
  runEach();
  const tools::EventSet counter = tools::get_callbacks();  // (the program's event counter)
  tools::set_begin_parallel_for_callback(onBeginKernel);
  tools::set_begin_parallel_reduce_callback(onBeginKernel);
  tools::set_begin_parallel_scan_callback(onBeginKernel);
  tools::set_push_region_callback(onPushRegion);
  tools::set_allocate_data_callback(onAllocate);
  runEach();
  tools::set_callbacks(counter);

  const std::regex ours("lagremap::[a-z_]+::[A-Za-z_0-9]+");
  // Kokkos's own helper kernels (View fills, initialisation) may name the View
  // they work on in brackets: "Kokkos::View::initialization [label]" (3.x),
  // "Kokkos::View::initialization [label] via memset" (4.x).
  const std::regex kokkos_internal(R"(Kokkos::[^\[]*(\[([^\]]*)\])?[^\[\]]*)");
  int labelled = 0;
  for (const std::string& kernel : g_kernels) {
    std::smatch match;
    if (std::regex_match(kernel, match, kokkos_internal)) {
      const std::string view = match[2];
      if (!view.empty()) {
        EXPECT_TRUE(std::regex_match(view, ours)) << "kernel on an unlabelled View: " << kernel;
      }
      continue;
    }
    EXPECT_TRUE(std::regex_match(kernel, ours)) << "unlabelled kernel: " << kernel;
    ++labelled;
  }
  std::vector<std::string> expected_kernels{"lagremap::geometry::cells",
                                            "lagremap::nodal_solve::crs_gather",
                                            "lagremap::nodal_solve::atomics_sum",
                                            "lagremap::diagnostics::cell_totals",
                                            "lagremap::corners::reconstruct_and_impedance",
                                            "lagremap::cell_update::corner_forces",
                                            "lagremap::cell_update::geometry"};
  if (kFusedKernelsBuilt) expected_kernels.push_back("lagremap::cell_update::update_and_geometry");
  for (const std::string& expected : expected_kernels) {
    EXPECT_EQ(g_kernels.count(expected), 1u) << expected;
  }
  EXPECT_GE(labelled, 6);
  // Kokkos' own allocations (a GPU backend's scratch and reduction buffers) are
  // named Kokkos::...; every other one is ours.
  const std::regex kokkos_allocation("Kokkos::.*");
  for (const std::string& view : g_allocations) {
    if (std::regex_match(view, kokkos_allocation)) continue;
    EXPECT_TRUE(std::regex_match(view, ours)) << "unlabelled View: '" << view << "'";
  }
  for (const char* phase : {"lagremap::geometry", "lagremap::corners", "lagremap::nodal_solve",
                            "lagremap::cell_update", "lagremap::diagnostics"}) {
    EXPECT_EQ(g_regions.count(phase), 1u) << phase;
  }
}

// One kernel launch (a free function: nvcc takes no device lambda in a test body).
void fillWithIndex(const RealView& a) {
  Kokkos::parallel_for(
      "lagremap::test::fill", Kokkos::RangePolicy<ExecSpace>(0, a.extent(0)),
      KOKKOS_LAMBDA(const Index i) { a(i) = i; });
}

// The program's event counter (src/kokkos_events.hpp): each launch and deep
// copy is counted, and a fence is a host synchronisation only when the
// device has work outstanding (a second fence costs nothing).
TEST(KokkosEvents, CountLaunchesCopiesAndOnlyTheWaitsWithWorkOutstanding) {
  ASSERT_TRUE(kokkosEventsCounted());
  const RealView a("lagremap::test::a", 100), b("lagremap::test::b", 100);
  fenceFor("test: nothing outstanding before");
  const KokkosEventCounts start = kokkosEventCounts();
  fillWithIndex(a);
  fenceFor("test: the fill");
  fenceFor("test: nothing new");
  const KokkosEventCounts after_fill = kokkosEventCounts() - start;
  EXPECT_EQ(after_fill.launches, 1);
  EXPECT_EQ(after_fill.host_syncs, 1);
  EXPECT_EQ(after_fill.deep_copies, 0);
  Kokkos::deep_copy(b, a);
  const KokkosEventCounts after_copy = kokkosEventCounts() - start;
  EXPECT_EQ(after_copy.deep_copies, 1);
  EXPECT_EQ(after_copy.copied_bytes, long(100 * sizeof(double)));
  EXPECT_EQ(after_copy.host_syncs, 2);  // (a deep copy fences)
}

// A step of taylor in remap mode (two materials, a solid, the remap) and of
// sedov (one gas, general hexahedra) in each kernel form the build has:
// no whole-View copy, one host synchronisation (the step's report) and at
// most the launches each takes today; with --profile-phases the timers wait
// at each phase's ends.
TEST(KokkosEvents, AStepCopiesNoViewAndWaitsOnce) {
  struct Case {
    const char* problem;
    const char* mode;
    double scale;
    long fused_launches, staged_launches;
  };
  const Case cases[] = {{"taylor", "remap", 0.25, 12, 16}, {"sedov", "lagrange", 0.34, 8, 10}};
  std::vector<std::string> forms{"staged"};
  if (kFusedKernelsBuilt) forms.push_back("fused");
  for (const Case& c : cases) {
    for (const std::string& form : forms) {
      const std::string what = std::string(c.problem) + " " + c.mode + " " + form;
      const RunResult result = runProblem(testing::problemOptions(
          c.problem, {"numerics.max_steps=6", "numerics.kernels=" + form}, c.scale, c.mode));
      ASSERT_TRUE(result.events_counted) << what;
      ASSERT_EQ(result.step_events.steps, 6) << what;
      const KokkosEventCounts& most = result.step_events.most;
      EXPECT_EQ(most.deep_copies, 0) << what;
      EXPECT_EQ(most.host_syncs, 1) << what;
      EXPECT_LE(most.launches, form == "fused" ? c.fused_launches : c.staged_launches) << what;
      EXPECT_GE(most.launches, 8) << what;  // (the counter sees the step's kernels)
    }
  }
  RunOptions profiled = testing::problemOptions("sedov", {"numerics.max_steps=6"}, 0.34);
  profiled.profile_phases = true;
  EXPECT_GE(runProblem(profiled).step_events.most.host_syncs, 5);
}

}  // namespace
}  // namespace lagremap
