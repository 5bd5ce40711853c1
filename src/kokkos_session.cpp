#include "kokkos_session.hpp"

#include <cstdlib>
#include <string>
#include <utility>

#include "data/types.hpp"
#include "kokkos_events.hpp"

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

namespace {
// `text` as a user typed it, cut to a readable length.
std::string shortened(const std::string& text) {
  return text.size() <= 60 ? text : text.substr(0, 60) + "...";
}

// A whole number of decimal digits (an optional leading minus), in long's range.
bool parseWhole(const std::string& text, long& value) {
  if (text.empty() || text == "-" || text.size() > 18) return false;
  if (text.find_first_not_of("0123456789", text[0] == '-' ? 1 : 0) != std::string::npos)
    return false;
  value = std::stol(text);
  return true;
}

// What is wrong with `value` of `what` (a count of threads when `threads`),
// at least `least`; empty if nothing.
std::string countError(const std::string& what, const std::string& value, long least,
                       bool threads) {
  long count = 0;
  if (!parseWhole(value, count)) return what + ": expects a whole number";
  if (count < least) return what + ": must be at least " + std::to_string(least);
  if (threads && count > kMaxHostThreads)
    return what + ": at most " + std::to_string(kMaxHostThreads) +
           " threads (Kokkos' OpenMP back-end)";
  return "";
}
}  // namespace

std::string kokkosArgumentsError(int argc, const char* const argv[]) {
  struct NumberFlag {
    const char* name;
    long least;
    bool threads;
  };
  const NumberFlag flags[] = {{"--kokkos-threads", 1, true},
                              {"--kokkos-num-threads", 1, true},
                              {"--kokkos-numa", 1, false},
                              {"--kokkos-device-id", 0, false},
                              {"--kokkos-num-devices", 1, false}};
  for (int i = 1; i < argc; ++i) {
    const std::string argument = argv[i];
    for (const NumberFlag& flag : flags) {
      const std::string name = flag.name;
      if (argument.compare(0, name.size(), name) != 0) continue;
      if (argument.size() > name.size() && argument[name.size()] != '=') continue;  // another flag
      if (argument.size() == name.size()) return name + ": expects " + name + "=N";
      const std::string error = countError(shortened(argument), argument.substr(name.size() + 1),
                                           flag.least, flag.threads);
      if (!error.empty()) return error;
    }
  }
  // Whatever the flags say: Kokkos' OpenMP back-end sizes its pool by
  // OpenMP's own count too. (OpenMP reads the first entry of a list such as
  // "4,2" for the outer level.)
  const char* omp = std::getenv("OMP_NUM_THREADS");
  if (omp != nullptr && *omp != '\0') {
    const std::string value = omp;
    return countError("OMP_NUM_THREADS=" + shortened(value), value.substr(0, value.find(',')), 1,
                      true);
  }
  return "";
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
  installKokkosEventCounter();  // (before Kokkos asks its tool settings)
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
