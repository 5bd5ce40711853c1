// GoogleTest main for tests that use Kokkos: Kokkos is initialised once (its
// --kokkos-* flags are honoured) around the whole test run.
#include <gtest/gtest.h>

#include <Kokkos_Core.hpp>
#include <cstdlib>

#include "src/floating_point.hpp"
#include "src/kokkos_session.hpp"

int main(int argc, char* argv[]) {
  // Unbound threads, as Kokkos advises for unit tests (the OpenMP runtime
  // started unbound already); this also keeps Kokkos' binding advice off the
  // output that ctest's test discovery parses.
  setenv("OMP_PROC_BIND", "false", 0);
  lagremap::flushDenormalsToZero();  // as the lagremap driver does
  lagremap::KokkosSession kokkos(argc, argv);
  ::testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
