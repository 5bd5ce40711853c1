#include "stop_signals.hpp"

#include <csignal>

namespace lagremap {

namespace {
constexpr int kStopSignals[] = {SIGTERM, SIGINT, SIGUSR1};

volatile std::sig_atomic_t requested_stop = 0;

// Async-signal-safe: records the signal and restores the default actions
// (sigaction is safe in a handler).
extern "C" void requestStop(int signal) {
  if (requested_stop != 0) {  // a second one, in another thread: at once
    std::signal(signal, SIG_DFL);
    std::raise(signal);
    return;
  }
  requested_stop = signal;
  struct sigaction action {};
  action.sa_handler = SIG_DFL;
  sigemptyset(&action.sa_mask);
  for (int stop : kStopSignals) sigaction(stop, &action, nullptr);
}
}  // namespace

void installStopSignals() {
  struct sigaction action {};
  action.sa_handler = requestStop;
  sigemptyset(&action.sa_mask);
  action.sa_flags = SA_RESTART;  // a write or a wait under way carries on
  for (int stop : kStopSignals) sigaction(stop, &action, nullptr);
}

int stopSignal() {
  return requested_stop;
}

const char* stopSignalName(int signal) {
  switch (signal) {
    case SIGTERM:
      return "SIGTERM";
    case SIGINT:
      return "SIGINT";
    case SIGUSR1:
      return "SIGUSR1";
    default:
      return "a signal";
  }
}

}  // namespace lagremap
