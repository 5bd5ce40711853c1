// Thin driver (CONTRIBUTING.md style 1): Kokkos takes its own flags, the library does the rest.
#include <string>

#include "cli.hpp"
#include "floating_point.hpp"
#include "kokkos_session.hpp"
#include "parallel.hpp"
#include "stop_signals.hpp"

int main(int argc, char* argv[]) {
  lagremap::flushDenormalsToZero();  // before Kokkos starts its threads, which inherit it
  lagremap::parallel::Session mpi(argc, argv);  // one rank per socket or GPU (method.md §7.5)
  const std::string bad_kokkos_flag = lagremap::kokkosArgumentsError(argc, argv);
  if (!bad_kokkos_flag.empty()) return lagremap::refuseInput(bad_kokkos_flag);
  lagremap::KokkosSession kokkos(argc, argv);
  if (kokkos.printedKokkosHelp()) return 0;
  lagremap::installStopSignals();
  return lagremap::runCommandLine(argc, argv);
}
