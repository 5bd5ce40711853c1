// The corner terms (kernels/corner_terms.hpp, docs/method.md §A4, §A5): the
// fused form's cells in the lanes of a vector give the bits of the same
// kernel run cell by cell (docs/method.md §7.1), and the staged form's teams
// the fused form's bits (docs/method.md §7.6).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <random>
#include <vector>

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

// A gas, or a hypo-elastic solid that does not yield.
MaterialParams cornerTestMaterial(bool solid) {
  MaterialParams material;
  if (solid) {
    material.strength = StrengthKind::HypoElastic;
    material.mu = 0.5;
    material.yield_stress = 1e9;
  }
  return material;
}

// Random cell velocities, pressures and (with `deviators`) stress deviators.
void randomCellState(const State& state, Index n_cells, unsigned seed, bool deviators) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  auto v = Kokkos::create_mirror_view_and_copy(HostSpace(), state.v_c);
  auto p = Kokkos::create_mirror_view_and_copy(HostSpace(), state.p_c);
  auto deviator = Kokkos::create_mirror_view_and_copy(HostSpace(), state.S_c);
  for (Index c = 0; c < n_cells; ++c) {
    for (int d = 0; d < 3; ++d) v(c, d) = unit(rng);
    p(c) = 1.0 + 0.5 * unit(rng);
    for (int i = 0; deviators && i < 6; ++i) deviator(c, i) = 0.3 * unit(rng);
  }
  Kokkos::deep_copy(state.v_c, v);
  Kokkos::deep_copy(state.p_c, p);
  Kokkos::deep_copy(state.S_c, deviator);
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
      const MaterialParams material = cornerTestMaterial(solid);
      auto [setup, state] =
          testing::uniformBlock(block, SideBoundaries{}, material, 1.0, 2.0, Vec3{0, 0, 0});
      const Mesh& mesh = setup.mesh;
      ASSERT_GT(computeGeometry(mesh, state, TimeStepControls{}).val, 0.0);
      randomCellState(state, mesh.n_cells, solid ? 11 : 7, solid);

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

// The staged form (a cell's faces, gradient rows, vertices and corners in
// the lanes of a team, kernels/corner_terms_staged.hpp) gives the fused
// form's B_cp bit for bit: first and second order; gas, solid and a mix of
// solid and gas cells (each cell's branch by its aT); walls, free sides and
// a traction side, so that open sides take their opposite face's jump
// reversed (x-, y-) or have none to take (z+ against a wall, y+ traction
// against a free side).
TEST(CornerTerms, StagedTeamsGiveTheFusedBits) {
  if constexpr (!kFusedKernelsBuilt) {
    GTEST_SKIP() << "the fused form, the reference, is not built on GPU builds";
  } else {
    SideBoundaries sides = testing::allWalls();
    sides[0].kind = BoundaryKind::Free;
    sides[2].kind = BoundaryKind::Free;
    sides[3].kind = BoundaryKind::Traction;
    sides[5].kind = BoundaryKind::Free;
    const BlockSpec block = testing::perturbedBlock(9, 7, 5, {0, 0, 0}, {0.9, 0.7, 0.5}, 0.25);
    for (const int cells_solid : {0, 1, 2}) {                    // none, all, every third
      const MaterialParams material = cornerTestMaterial(true);  // (aT below picks the solids)
      auto [setup, state] = testing::uniformBlock(block, sides, material, 1.0, 2.0, Vec3{0, 0, 0});
      const Mesh& mesh = setup.mesh;
      ASSERT_GT(computeGeometry(mesh, state, TimeStepControls{}).val, 0.0);
      randomCellState(state, mesh.n_cells, 17 + cells_solid, true);
      std::mt19937 rng(23 + cells_solid);
      std::uniform_real_distribution<double> unit(-1.0, 1.0);
      auto a_t = Kokkos::create_mirror_view_and_copy(HostSpace(), state.aT_c);
      for (Index c = 0; c < mesh.n_cells; ++c) {
        const bool solid = cells_solid == 1 || (cells_solid == 2 && c % 3 == 0);
        a_t(c) = solid ? 0.5 + 0.1 * unit(rng) : 0.0;
      }
      Kokkos::deep_copy(state.aT_c, a_t);
      decltype(Kokkos::create_mirror(HostSpace(), state.B_cp)) first_order;
      for (const int order : {1, 2}) {
        const CornerControls controls{order, Gather::Crs};
        computeCornerTerms(mesh, state, controls, KernelForm::Fused);
        const auto fused = Kokkos::create_mirror(HostSpace(), state.B_cp);
        Kokkos::deep_copy(fused, state.B_cp);
        Kokkos::deep_copy(state.B_cp, 0.0);
        computeCornerTerms(mesh, state, controls, KernelForm::Staged);
        const auto staged = Kokkos::create_mirror_view_and_copy(HostSpace(), state.B_cp);
        double largest = 0.0;
        for (Index corner = 0; corner < 8 * mesh.n_cells; ++corner) {
          for (int d = 0; d < 3; ++d) {
            largest = std::max(largest, std::fabs(fused(corner, d)));
            ASSERT_EQ(std::memcmp(&staged(corner, d), &fused(corner, d), sizeof(double)), 0)
                << "solid cells " << cells_solid << ", order " << order << ", corner " << corner
                << " component " << d << ": " << staged(corner, d) << " vs " << fused(corner, d);
          }
        }
        EXPECT_GT(largest, 1e-3);  // (the terms are not all zero)
        if (order == 1) {
          first_order = Kokkos::create_mirror(HostSpace(), state.B_cp);  // (a copy of its own)
          Kokkos::deep_copy(first_order, staged);
        } else {  // the limited reconstruction moves the node values
          int moved = 0;
          for (Index corner = 0; corner < 8 * mesh.n_cells; ++corner) {
            moved += staged(corner, 0) != first_order(corner, 0);
          }
          EXPECT_GT(moved, 4 * mesh.n_cells) << "solid cells " << cells_solid;
        }
      }
    }
  }
}

// A uniform pressure at rest has no jump across any face (a wall's mirror of
// V = 0 and of sigma = -p I included) and none to continue across a free
// side: every gradient is zero and B_cp = p A_cp exactly, for a gas and for
// a solid at an isotropic stress, at second order, in each kernel form the
// build has (on a GPU build the staged teams on the device).
TEST(CornerTerms, AUniformPressureAtRestGivesPressureTimesCornerVector) {
  SideBoundaries sides = testing::allWalls();
  sides[0].kind = BoundaryKind::Free;
  sides[3].kind = BoundaryKind::Traction;
  const BlockSpec block = testing::perturbedBlock(7, 6, 5, {0, 0, 0}, {0.7, 0.6, 0.5}, 0.25);
  std::vector<KernelForm> forms{KernelForm::Staged};
  if (kFusedKernelsBuilt) forms.push_back(KernelForm::Fused);
  for (const bool solid : {false, true}) {
    const MaterialParams material = cornerTestMaterial(solid);
    auto [setup, state] = testing::uniformBlock(block, sides, material, 1.0, 2.0, Vec3{0, 0, 0});
    const Mesh& mesh = setup.mesh;
    ASSERT_GT(computeGeometry(mesh, state, TimeStepControls{}).val, 0.0);
    Kokkos::deep_copy(state.p_c, 3.0);
    const auto area = Kokkos::create_mirror_view_and_copy(HostSpace(), state.A_cp);
    for (const KernelForm form : forms) {
      Kokkos::deep_copy(state.B_cp, -1.0);
      computeCornerTerms(mesh, state, CornerControls{2, Gather::Crs}, form);
      const auto b = Kokkos::create_mirror_view_and_copy(HostSpace(), state.B_cp);
      for (Index corner = 0; corner < 8 * mesh.n_cells; ++corner) {
        for (int d = 0; d < 3; ++d) {
          ASSERT_EQ(b(corner, d), 3.0 * area(corner, d))
              << (solid ? "solid" : "gas") << (form == KernelForm::Fused ? ", fused" : ", staged")
              << ", corner " << corner << " component " << d;
        }
      }
    }
  }
}

}  // namespace
}  // namespace lagremap
