// Runs the Sod tube through the installed library's API and exits 0 when its
// checks pass: what a user embedding lagremap would write, with the one
// umbrella header.
#include <cstdio>

#include <lagremap/lagremap.hpp>

int main(int argc, char* argv[]) {
  lagremap::flushDenormalsToZero();
  lagremap::parallel::Session mpi(argc, argv);
  lagremap::KokkosSession kokkos(argc, argv);
  lagremap::RunOptions options;
  options.problem = "sod";
  options.config = lagremap::declareConfig(lagremap::findProblem("sod"));
  options.write_files = false;
  options.quiet = true;
  const lagremap::RunResult result = lagremap::runProblem(options);
  std::printf("consumer: sod, %ld cells, %ld steps, checks %s\n", result.cells, result.steps,
              result.checksPass() ? "pass" : "FAIL");
  for (const lagremap::Check& check : result.checks)
    std::printf("  %s = %g (reference %g, tolerance %g)%s\n", check.name.c_str(), check.value,
                check.reference, check.tolerance, check.pass() ? "" : "  FAIL");
  return result.checksPass() ? 0 : 1;
}
