// Thin driver (STYLE §1): Kokkos takes its own flags, the library does the rest.
#include <Kokkos_Core.hpp>

#include "cli.hpp"

int main(int argc, char* argv[]) {
  Kokkos::ScopeGuard kokkos(argc, argv);
  return lagremap::runCommandLine(argc, argv);
}
