// The command line (CONTRIBUTING.md style 9): long options with help text, no positional
// arguments. Returns the process exit code:
//   0 success, 1 a problem check failed, 2 bad input, 3 the run failed mid-way,
//   4 stopped by a signal (stop_signals.hpp).
#pragma once

#include <string>

namespace lagremap {

int runCommandLine(int argc, char* argv[]);

// Bad input found before the command line is read (the Kokkos flags): one
// line "lagremap: error: MESSAGE" from the first rank; returns exit code 2.
int refuseInput(const std::string& message);

}  // namespace lagremap
