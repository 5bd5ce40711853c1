// The corner terms (kernels/corner_terms.hpp, docs/method.md §A4, §A5): the
// fused form's cells in the lanes of a vector give the bits of the same
// kernel run cell by cell (docs/method.md §7.1).
#include <gtest/gtest.h>

#include <random>

#include "kernels/corner_terms.hpp"
#include "kernels/geometry.hpp"
#include "test_support.hpp"

namespace lagremap {
namespace {

// The corner kernel one cell at a time (a free function: nvcc refuses an
// extended lambda in a test body).
void cornerTermsCellByCell(const detail::CornerTerms& terms, Index n_cells) {
  Kokkos::parallel_for(
      "test::corner_terms_cell_by_cell", Kokkos::RangePolicy<ExecSpace>(0, n_cells),
      KOKKOS_LAMBDA(const Index c) { terms.ofCells<double>(c); });
}

// The corner kernel takes kCellLanes cells at once in the lanes of a vector
// where their stencils have one shape (detail::CornerTerms): its corner
// terms must be the bits of the same kernel run cell by cell. A perturbed
// block with random velocities, pressures and (a solid) deviators; 12 cells
// a row, so most chunks of 4 share a shape and those at the walls do not.
TEST(CornerTerms, CellLanesGiveTheCellByCellBits) {
  if constexpr (!kFusedKernelsBuilt) {
    GTEST_SKIP() << "cell lanes are the fused form's, which GPU builds do not have";
  } else {
    for (const bool solid : {false, true}) {
      const BlockSpec block = testing::perturbedBlock(12, 6, 5, {0, 0, 0}, {1.2, 0.6, 0.5}, 0.25);
      MaterialParams material;
      if (solid) {
        material.strength = StrengthKind::HypoElastic;
        material.mu = 0.5;
        material.yield_stress = 1e9;
      }
      auto [setup, state] =
          testing::uniformBlock(block, SideBoundaries{}, material, 1.0, 2.0, Vec3{0, 0, 0});
      const Mesh& mesh = setup.mesh;
      ASSERT_GT(computeGeometry(mesh, state, TimeStepControls{}).val, 0.0);
      std::mt19937 rng(solid ? 11 : 7);
      std::uniform_real_distribution<double> unit(-1.0, 1.0);
      auto v = Kokkos::create_mirror_view_and_copy(HostSpace(), state.v_c);
      auto p = Kokkos::create_mirror_view_and_copy(HostSpace(), state.p_c);
      auto deviator = Kokkos::create_mirror_view_and_copy(HostSpace(), state.S_c);
      for (Index c = 0; c < mesh.n_cells; ++c) {
        for (int d = 0; d < 3; ++d) v(c, d) = unit(rng);
        p(c) = 1.0 + 0.5 * unit(rng);
        for (int i = 0; solid && i < 6; ++i) deviator(c, i) = 0.3 * unit(rng);
      }
      Kokkos::deep_copy(state.v_c, v);
      Kokkos::deep_copy(state.p_c, p);
      Kokkos::deep_copy(state.S_c, deviator);

      computeCornerTerms(mesh, state, CornerControls{2, Gather::Crs});
      // (create_mirror: a copy of its own, where a host mirror view of host
      // memory would be the kernel's View itself)
      const auto lanes = Kokkos::create_mirror(HostSpace(), state.B_cp);
      Kokkos::deep_copy(lanes, state.B_cp);
      Kokkos::deep_copy(state.B_cp, 0.0);
      const detail::CornerTerms terms =
          detail::cornerTerms(mesh, state, CornerControls{2, Gather::Crs});
      int shared_shapes = 0;
      for (Index first = 0; first + hex::kCellLanes <= mesh.n_cells; first += hex::kCellLanes) {
        shared_shapes += terms.lanesShareStencilShape(first, hex::kCellLanes);
      }
      cornerTermsCellByCell(terms, mesh.n_cells);
      const auto cells = Kokkos::create_mirror_view_and_copy(HostSpace(), state.B_cp);
      if (hex::kCellLanes > 1) {
        EXPECT_GE(shared_shapes, mesh.n_cells / (3 * hex::kCellLanes));  // the middle of each row
      }
      for (Index corner = 0; corner < 8 * mesh.n_cells; ++corner) {
        for (int d = 0; d < 3; ++d) {
          ASSERT_EQ(lanes(corner, d), cells(corner, d))
              << (solid ? "solid" : "gas") << " corner " << corner << " component " << d;
        }
      }
    }
  }
}

}  // namespace
}  // namespace lagremap
