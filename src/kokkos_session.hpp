// Kokkos for the life of the process (a ScopeGuard that also accepts both
// spellings of the thread-count flag): Kokkos 3.x reads --kokkos-threads=N,
// 4.x --kokkos-num-threads=N, and a lagremap user or script may write either
// with any Kokkos. --help and -h are the program's own: Kokkos, which would
// print its 40 lines of help for --help before the program's usage, prints
// them for --kokkos-help only. Used by the driver, the test mains and the
// benchmarks.
#pragma once

#include <string>
#include <vector>

namespace lagremap {

class KokkosSession {
 public:
  // Rewrites the flag in argv to the spelling of the Kokkos built against,
  // then initialises Kokkos, which removes its flags from argc/argv; --help
  // and -h are left in argv for the program, unseen by Kokkos.
  KokkosSession(int& argc, char* argv[]);
  ~KokkosSession();
  KokkosSession(const KokkosSession&) = delete;
  KokkosSession& operator=(const KokkosSession&) = delete;

  // Whether the command line held --kokkos-help: Kokkos has printed its help
  // (and removed the flag), and the program has nothing more to do.
  bool printedKokkosHelp() const { return printed_kokkos_help_; }

 private:
  std::vector<std::string> rewritten_;  // argv entries that point here must outlive Kokkos
  bool printed_kokkos_help_ = false;
};

// The thread-count flag as this Kokkos spells it ("--kokkos-threads" or
// "--kokkos-num-threads"), and `argument` rewritten to it (unchanged if it is
// not a thread-count flag).
const char* kokkosThreadsFlag();
std::string withKokkosThreadsSpelling(const std::string& argument);

// Kokkos 3.x's OpenMP back-end keeps the data of at most this many threads
// (OpenMPExec::MAX_THREAD_COUNT) and crashes beyond it.
constexpr long kMaxHostThreads = 512;

// What is wrong with the first Kokkos flag of argv that takes a number
// (--kokkos-threads, --kokkos-num-threads, --kokkos-numa, --kokkos-device-id,
// --kokkos-num-devices: a count of at least 1, an index of at least 0, at
// most kMaxHostThreads threads), or with OMP_NUM_THREADS (whatever the
// flags: the back-end sizes its pool by it too); empty if nothing. The driver asks before Kokkos
// reads them: Kokkos 3.4 aborts on a bad value with two dozen lines of dump.
std::string kokkosArgumentsError(int argc, const char* const argv[]);

// Whether the execution space runs on the host (OpenMP, Serial, Threads).
bool executionSpaceIsHost();
// The execution space for reports: "OpenMP, 2 threads" on the host,
// "Cuda, concurrency 270336" on a GPU (where threads are not the user's choice).
std::string executionSpaceText();

}  // namespace lagremap
