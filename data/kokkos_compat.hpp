// The one place that bridges Kokkos 3.x and 4.x spellings, so the kernels
// compile unchanged against the Kokkos 3.4.01 built by scripts/setup.sh and any
// newer Kokkos a user points Kokkos_ROOT at (docs/building.md §2).
#pragma once

#include <Kokkos_Core.hpp>

namespace lagremap::math {

#if KOKKOS_VERSION >= 30700
using Kokkos::cbrt;
using Kokkos::fabs;
using Kokkos::fmax;
using Kokkos::fmin;
using Kokkos::isfinite;
using Kokkos::log;
using Kokkos::pow;
using Kokkos::sqrt;
#else
using Kokkos::Experimental::cbrt;
using Kokkos::Experimental::fabs;
using Kokkos::Experimental::fmax;
using Kokkos::Experimental::fmin;
using Kokkos::Experimental::isfinite;
using Kokkos::Experimental::log;
using Kokkos::Experimental::pow;
using Kokkos::Experimental::sqrt;
#endif

}  // namespace lagremap::math

// A function kept out of line on the host, for a rarely taken branch of a
// hot kernel whose frame it would otherwise grow for every call. Device
// passes inline as they choose.
#if defined(__CUDA_ARCH__) || defined(__HIP_DEVICE_COMPILE__)
#define LAGREMAP_OUT_OF_LINE
#else
#define LAGREMAP_OUT_OF_LINE __attribute__((noinline))
#endif

// Full unrolling of the short fixed loops over a hexahedron's faces and nodes:
// the face-node table then folds into constant offsets and the per-node
// accumulators stay in registers. Only a hint; every compiler may ignore it.
// nvcc and hipcc take `unroll` in their device passes (__CUDA_ARCH__,
// __HIP_DEVICE_COMPILE__); their front ends reject GCC's spelling and pass a bare
// `unroll` on to the host compiler, which warns, so their host passes get none.
#if defined(__CUDA_ARCH__) || defined(__HIP_DEVICE_COMPILE__)
#define LAGREMAP_UNROLL _Pragma("unroll")
#elif defined(__CUDACC__) || defined(__HIPCC__)
#define LAGREMAP_UNROLL
#elif defined(__clang__)
#define LAGREMAP_UNROLL _Pragma("unroll")
#elif defined(__GNUC__)
#define LAGREMAP_UNROLL _Pragma("GCC unroll 8")
#else
#define LAGREMAP_UNROLL
#endif

// A loop kept rolled where unrolling would hold all its iterations' state at
// once (the staged form's loops over a corner's faces, kernels/hex.hpp, and
// over a cell's faces' terms, kernels/geometry_staged.hpp; the stage end's
// loops over a cell's materials, whose count only the run knows: unrolled,
// they spilled the materials' kernel past 128 registers on sm_90): device
// passes.
#if defined(__CUDA_ARCH__) || defined(__HIP_DEVICE_COMPILE__)
#define LAGREMAP_NO_UNROLL _Pragma("unroll 1")
#else
#define LAGREMAP_NO_UNROLL
#endif

// A loop over lanes (the 8 vertices of a hexahedron, structure of arrays)
// whose iterations are independent: vectorised on CPUs (OpenMP simd, which
// also lets the compiler turn a selection into a blend); device passes get
// none (one thread does the whole loop).
#if defined(__CUDA_ARCH__) || defined(__HIP_DEVICE_COMPILE__) || defined(__CUDACC__) || \
    defined(__HIPCC__) || !defined(_OPENMP)
#define LAGREMAP_LANES
#else
#define LAGREMAP_LANES _Pragma("omp simd")
#endif

// Cells computed at once in the lanes of a vector register by the geometry
// sweep (hex::cellGeometries, kCellLanes of them): 4 on CPU builds with GCC,
// whose vector extensions give a pack of 4 doubles (one AVX2 register) the
// arithmetic, comparisons and selections of a double, lane by lane; 1 in
// device passes and with other compilers.
#if defined(__GNUC__) && !defined(__clang__) && !defined(__CUDACC__) && !defined(__HIPCC__) && \
    !defined(__CUDA_ARCH__) && !defined(__HIP_DEVICE_COMPILE__) && !defined(__INTEL_LLVM_COMPILER)
#define LAGREMAP_CELL_PACKS 1
#else
#define LAGREMAP_CELL_PACKS 0
#endif

// Software prefetch of gathered records on CPU builds (GCC and Clang):
// LAGREMAP_PREFETCH(address) asks for the cache line holding `address`. For
// gathers through an index list, whose addresses the hardware prefetchers
// cannot guess (the nodal solve's corner records). Off (0, and the macro a
// no-op) in device passes, where the gathering threads hide the latency.
#if defined(__GNUC__) && !defined(__CUDACC__) && !defined(__HIPCC__) && !defined(__CUDA_ARCH__) && \
    !defined(__HIP_DEVICE_COMPILE__)
#define LAGREMAP_PREFETCHES 1
#define LAGREMAP_PREFETCH(address) __builtin_prefetch((address), 0, 3)
#else
#define LAGREMAP_PREFETCHES 0
#define LAGREMAP_PREFETCH(address) ((void)0)
#endif
