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
  tools::set_begin_parallel_for_callback(onBeginKernel);
  tools::set_begin_parallel_reduce_callback(onBeginKernel);
  tools::set_begin_parallel_scan_callback(onBeginKernel);
  tools::set_push_region_callback(onPushRegion);
  tools::set_allocate_data_callback(onAllocate);
  // each kernel form the build has (the fused one on CPU backends only), both gathers
  std::vector<std::string> forms{"staged"};
  if (kFusedKernelsBuilt) forms.push_back("fused");
  for (const std::string& form : forms) {
    for (const char* gather : {"crs", "atomics"}) {
      runProblem(testing::problemOptions(
          "sod", {"mesh.nx=20", "t_end=0.01", std::string("numerics.gather=") + gather,
                  "numerics.kernels=" + form}));
    }
  }
  tools::set_begin_parallel_for_callback(nullptr);
  tools::set_begin_parallel_reduce_callback(nullptr);
  tools::set_begin_parallel_scan_callback(nullptr);
  tools::set_push_region_callback(nullptr);
  tools::set_allocate_data_callback(nullptr);

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
                                            "lagremap::corners::velocity_limiter",
                                            "lagremap::corners::right_hand_sides",
                                            "lagremap::cell_update::corner_forces",
                                            "lagremap::cell_update::geometry"};
  if (kFusedKernelsBuilt) {
    expected_kernels.insert(expected_kernels.end(), {"lagremap::corners::reconstruct_and_impedance",
                                                     "lagremap::cell_update::update_and_geometry"});
  }
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

}  // namespace
}  // namespace lagremap
