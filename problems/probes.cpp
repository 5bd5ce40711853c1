// Device reductions problems sample during a run (a side's mean stress or
// centroid, a material's length along an axis, the largest node x).

#include "../kernels/sum_array.hpp"
#include "../src/problem.hpp"

namespace lagremap {

namespace {
// Mean of value(c) over the cells with a face on `side`: one reduction of (sum, count).
template <class Value>
double sideMean(const Mesh& mesh, int side, const char* label, Value value) {
  const auto face_side = mesh.cell_face_side;
  const auto owned = mesh.cell_owned;
  SumArray<2> sums;
  Kokkos::parallel_reduce(
      label, Kokkos::RangePolicy<ExecSpace>(0, mesh.n_cells),
      KOKKOS_LAMBDA(const Index c, SumArray<2>& acc) {
        if (owned(c) && face_side(c, side) == side) {
          acc.v[0] += value(c);
          acc.v[1] += 1.0;
        }
      },
      Kokkos::Sum<SumArray<2>>(sums));
  parallel::sum(sums.v, 2);
  return sums.v[1] > 0 ? sums.v[0] / sums.v[1] : 0.0;
}
}  // namespace

double sideMeanStressXX(const Mesh& mesh, const State& state, int side) {
  const auto p = state.p_c;
  const auto S = state.S_c;
  return sideMean(
      mesh, side, "lagremap::diagnostics::side_stress_xx",
      KOKKOS_LAMBDA(const Index c) { return -p(c) + S(c, 0); });
}

double sideMeanCentroid(const Mesh& mesh, const State& state, int side, int axis) {
  const auto x_c = state.x_c;
  return sideMean(
      mesh, side, "lagremap::diagnostics::side_centroid",
      KOKKOS_LAMBDA(const Index c) { return x_c(c, axis); });
}

double materialLengthAlongAxis(const char* label, const Mesh& mesh, const State& state,
                               bool z_axis_too) {
  const auto x_n = mesh.x_n;
  const auto cell_nodes = mesh.cell_nodes;
  const auto alpha = state.alpha_ck;
  const auto vol = state.vol_c;
  const auto owned = mesh.cell_owned;
  double length = 0.0;
  Kokkos::parallel_reduce(
      label, Kokkos::RangePolicy<ExecSpace>(0, mesh.n_cells),
      KOKKOS_LAMBDA(const Index c, double& sum) {
        double lo[3], hi[3];
        for (int d = 1; d < 3; ++d) lo[d] = hi[d] = x_n(cell_nodes(c, 0), d);
        for (int p = 1; p < 8; ++p) {
          for (int d = 1; d < 3; ++d) {
            const double x = x_n(cell_nodes(c, p), d);
            lo[d] = x < lo[d] ? x : lo[d];
            hi[d] = x > hi[d] ? x : hi[d];
          }
        }
        const double dy = hi[1] - lo[1], dz = hi[2] - lo[2];
        const bool on_axis =
            math::fabs(lo[1]) <= 1e-9 * dy && (!z_axis_too || math::fabs(lo[2]) <= 1e-9 * dz);
        if (owned(c) && on_axis) sum += alpha(c, 0) * vol(c) / (dy * dz);
      },
      length);
  return parallel::sum(length);
}

double largestNodeX(const char* label, const Mesh& mesh) {
  const auto x_n = mesh.x_n;
  double largest = 0.0;
  Kokkos::parallel_reduce(
      label, Kokkos::RangePolicy<ExecSpace>(0, mesh.n_nodes),
      KOKKOS_LAMBDA(const Index n, double& acc) { acc = x_n(n, 0) > acc ? x_n(n, 0) : acc; },
      Kokkos::Max<double>(largest));
  return parallel::max(largest);
}

}  // namespace lagremap
