#include "kokkos_session.hpp"

#include <cstdlib>
#include <utility>

#include "data/types.hpp"

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

// What Kokkos sees in place of a --help or -h: text no Kokkos reads.
constexpr const char* kHiddenHelp = "lagremap-hidden-help";
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
  std::vector<std::pair<const char*, char*>> hidden_help;  // (what Kokkos sees, the flag)
  for (int i = 1; i < argc; ++i) {
    const std::string argument = argv[i];
    printed_kokkos_help_ = printed_kokkos_help_ || argument == "--kokkos-help";
    const bool help = argument == "--help" || argument == "-h";
    const std::string for_kokkos = help ? kHiddenHelp : withKokkosThreadsSpelling(argument);
    if (for_kokkos == argument) continue;
    rewritten_.push_back(for_kokkos);
    if (help) hidden_help.emplace_back(rewritten_.back().data(), argv[i]);
    argv[i] = rewritten_.back().data();
  }
  // Without OMP_PROC_BIND, Kokkos' OpenMP back-end prints four lines of
  // binding advice before every command; the binding is the user's choice
  // (--help says which is fastest), so a plain run stays quiet. Other Kokkos
  // warnings are silenced with it; setting OMP_PROC_BIND brings them back.
  if (std::getenv("OMP_PROC_BIND") == nullptr) setenv("KOKKOS_DISABLE_WARNINGS", "1", 0);
  Kokkos::initialize(argc, argv);
  // (Kokkos moves the arguments it leaves up over those it removes: the
  // stand-ins are found by their address)
  for (int i = 1; i < argc; ++i) {
    for (const auto& [stand_in, flag] : hidden_help)
      if (argv[i] == stand_in) argv[i] = flag;
  }
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
