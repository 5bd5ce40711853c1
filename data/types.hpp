// Every View alias, the execution and memory spaces, and the scalar/index types
// used by lagremap (CONTRIBUTING.md style 2). Views use the default layout of the execution
// space's memory (LayoutRight on host, LayoutLeft on CUDA/HIP), so the same
// kernels are coalesced on GPUs and cache-friendly on CPUs.
#pragma once

#include <Kokkos_Core.hpp>

namespace lagremap {

using Real = double;
using Index = int;  // cells, nodes and corners of one rank stay below 2^31

using ExecSpace = Kokkos::DefaultExecutionSpace;
using MemSpace = ExecSpace::memory_space;
using HostSpace = Kokkos::HostSpace;

template <class DataType>
using DeviceView = Kokkos::View<DataType, MemSpace>;

// Where a step's reductions leave their results for the host (src/step_report.hpp):
// memory the device writes and the host reads after one fence, without a
// copy (pinned host memory on a GPU).
#if defined(KOKKOS_ENABLE_CUDA)
using ReportSpace = Kokkos::CudaHostPinnedSpace;
#else
using ReportSpace = HostSpace;
#endif
template <class DataType>
using ReportView = Kokkos::View<DataType, ReportSpace>;

using RealView = DeviceView<Real*>;            // one value per cell or node
using Vec3View = DeviceView<Real* [3]>;        // x, y, z per entity
using Sym6View = DeviceView<Real* [6]>;        // xx, yy, zz, xy, yz, xz per entity
using IndexView = DeviceView<Index*>;          // CRS offsets and lists
using CellNodesView = DeviceView<Index* [8]>;  // VTK_HEXAHEDRON node order
using CellFacesView = DeviceView<Index* [6]>;  // per hex face (see kernels/hex.hpp)
using MatRealView = DeviceView<Real**>;        // (cell, material)
using MatSym6View = DeviceView<Real** [6]>;    // (cell, material, Sym6 component)
using MatVec3View = DeviceView<Real** [3]>;    // (cell, material, x y z)

constexpr int kNodesPerCell = 8;
constexpr int kFacesPerCell = 6;
constexpr int kNodesPerFace = 4;

}  // namespace lagremap
