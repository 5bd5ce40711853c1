// GoogleTest main for tests that use Kokkos: Kokkos is initialised once (its
// --kokkos-* flags are honoured) around the whole test run.
#include <gtest/gtest.h>

#include <Kokkos_Core.hpp>

int main(int argc, char* argv[]) {
  Kokkos::ScopeGuard kokkos(argc, argv);
  ::testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
