// Runs the Sod tube through the installed library's API and exits 0 when its
// checks pass: what a user embedding lagremap would write.
#include <cstdio>

#include <lagremap/src/kokkos_session.hpp>
#include <lagremap/src/parallel.hpp>
#include <lagremap/src/run.hpp>

int main(int argc, char* argv[]) {
  lagremap::parallel::Session mpi(argc, argv);
  lagremap::KokkosSession kokkos(argc, argv);
  lagremap::RunOptions options;
  options.problem = "sod";
  options.config = lagremap::declareConfig(lagremap::findProblem("sod"));
  options.write_files = false;
  options.quiet = true;
  const lagremap::RunResult result = lagremap::runProblem(options);
  std::printf("consumer: sod, %ld steps, checks %s\n", result.steps,
              result.checksPass() ? "pass" : "FAIL");
  return result.checksPass() ? 0 : 1;
}
