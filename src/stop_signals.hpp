// Stopping a run cleanly on a signal (docs/running.md §4): a batch scheduler
// ending a job at its wall time sends SIGTERM (or a chosen signal such as
// SIGUSR1) before it kills it, and an interactive user presses Ctrl-C
// (SIGINT). The first of SIGTERM, SIGINT and SIGUSR1 asks the time loop to
// stop at the end of the current step, write its checkpoint and outputs and
// exit with kExitStopped; the handlers then go back to the defaults, so a
// second signal ends the process at once.
#pragma once

namespace lagremap {

// Exit code of a run stopped by a signal, its checkpoint and outputs written.
constexpr int kExitStopped = 4;

// Installs the handlers (the driver does, once; library users and tests run
// without them).
void installStopSignals();
// The signal that asked the run to stop, 0 for none (this process's).
int stopSignal();
// Its name ("SIGTERM").
const char* stopSignalName(int signal);

}  // namespace lagremap
