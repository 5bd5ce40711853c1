#include "kokkos_session.hpp"

#include "types.hpp"

namespace lagremap {

namespace {
// Kokkos 3.7 introduced --kokkos-num-threads; 4.0 dropped --kokkos-threads.
#if KOKKOS_VERSION >= 30700
constexpr const char* kThreadsFlag = "--kokkos-num-threads";
constexpr const char* kOtherThreadsFlag = "--kokkos-threads";
#else
constexpr const char* kThreadsFlag = "--kokkos-threads";
constexpr const char* kOtherThreadsFlag = "--kokkos-num-threads";
#endif
}  // namespace

const char* kokkosThreadsFlag() {
  return kThreadsFlag;
}

std::string withKokkosThreadsSpelling(const std::string& argument) {
  const std::string other = std::string(kOtherThreadsFlag) + "=";
  if (argument.compare(0, other.size(), other) != 0) return argument;
  return std::string(kThreadsFlag) + "=" + argument.substr(other.size());
}

KokkosSession::KokkosSession(int& argc, char* argv[]) {
  rewritten_.reserve(argc);  // no reallocation: argv keeps pointers into it
  for (int i = 1; i < argc; ++i) {
    const std::string respelt = withKokkosThreadsSpelling(argv[i]);
    if (respelt != argv[i]) {
      rewritten_.push_back(respelt);
      argv[i] = rewritten_.back().data();
    }
  }
  Kokkos::initialize(argc, argv);
}

KokkosSession::~KokkosSession() {
  Kokkos::finalize();
}

bool executionSpaceIsHost() {
  return Kokkos::SpaceAccessibility<Kokkos::HostSpace, ExecSpace::memory_space>::accessible;
}

std::string executionSpaceText() {
  const std::string count = std::to_string(ExecSpace().concurrency());
  return std::string(ExecSpace::name()) +
         (executionSpaceIsHost() ? ", " + count + " threads" : ", concurrency " + count);
}

}  // namespace lagremap
