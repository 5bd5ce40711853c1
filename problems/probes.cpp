// Device reductions problems sample during a run (a side's mean stress or
// centroid, a material's length along an axis, the largest node x), each
// left in the step report's probe slots without waiting (Probe).

#include "../kernels/sum_array.hpp"
#include "../src/kokkos_events.hpp"
#include "../src/problem.hpp"

namespace lagremap {

double Probe::measure(const Mesh& mesh, const State& state) const {
  const ProbeSlots slots;
  sample(mesh, state, slots);
  fenceFor("lagremap::probe: a measurement");
  return value(mesh, state, slots);
}

namespace {
// Sum and count of value(c) over the cells with a face on `side`: one reduction.
template <class Value>
void sampleSideMean(const Mesh& mesh, int side, const char* label, Value value,
                    const ProbeSlots& slots) {
  const auto face_side = mesh.cell_face_side;
  const auto owned = mesh.cell_owned;
  Kokkos::parallel_reduce(
      label, Kokkos::RangePolicy<ExecSpace>(0, mesh.n_cells),
      KOKKOS_LAMBDA(const Index c, SumArray<2>& acc) {
        if (owned(c) && face_side(c, side) == side) {
          acc.v[0] += value(c);
          acc.v[1] += 1.0;
        }
      },
      Kokkos::Sum<SumArray<2>, ReportSpace>(slots.sums));
}
}  // namespace

void sampleSideMeanStressXX(const Mesh& mesh, const State& state, int side,
                            const ProbeSlots& slots) {
  const auto p = state.p_c;
  const auto S = state.S_c;
  sampleSideMean(
      mesh, side, "lagremap::diagnostics::side_stress_xx",
      KOKKOS_LAMBDA(const Index c) { return -p(c) + S(c, 0); }, slots);
}

void sampleSideMeanCentroid(const Mesh& mesh, const State& state, int side, int axis,
                            const ProbeSlots& slots) {
  const auto x_c = state.x_c;
  sampleSideMean(
      mesh, side, "lagremap::diagnostics::side_centroid",
      KOKKOS_LAMBDA(const Index c) { return x_c(c, axis); }, slots);
}

void sampleMaterialLengthAlongAxis(const char* label, const Mesh& mesh, const State& state,
                                   bool z_axis_too, const ProbeSlots& slots) {
  const auto x_n = mesh.x_n;
  const auto cell_nodes = mesh.cell_nodes;
  const auto alpha = state.alpha_ck;
  const auto vol = state.vol_c;
  const auto owned = mesh.cell_owned;
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
      Kokkos::Sum<double, ReportSpace>(slots.scalar));
}

void sampleLargestNodeX(const char* label, const Mesh& mesh, const ProbeSlots& slots) {
  const auto x_n = mesh.x_n;
  Kokkos::parallel_reduce(
      label, Kokkos::RangePolicy<ExecSpace>(0, mesh.n_nodes),
      KOKKOS_LAMBDA(const Index n, double& acc) { acc = x_n(n, 0) > acc ? x_n(n, 0) : acc; },
      Kokkos::Max<double, ReportSpace>(slots.scalar));
}

double sumOverRanks(const ProbeSlots& slots) {
  return parallel::sum(slots.scalar());
}

double largestOverRanks(const ProbeSlots& slots) {
  return parallel::max(slots.scalar());
}

double meanOverRanks(const ProbeSlots& slots) {
  SumArray<2> sums = slots.sums();
  parallel::sum(sums.v, 2);
  return sums.v[1] > 0 ? sums.v[0] / sums.v[1] : 0.0;
}

double ratioOverRanks(const ProbeSlots& slots) {
  SumArray<2> sums = slots.sums();
  parallel::sum(sums.v, 2);
  return sums.v[1] / sums.v[0];
}

}  // namespace lagremap
