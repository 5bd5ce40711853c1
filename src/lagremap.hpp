// The library's public API in one header, installed as <lagremap/lagremap.hpp>
// (tests/install_consumer is a user's program against it):
//   - the process: parallel::Session (MPI), KokkosSession, flushDenormalsToZero;
//   - a problem by name: problemRegistry, findProblem, declareConfig (every key
//     with its default), Config::set / setAssignment / loadDeck, ConfigError;
//   - a run: RunOptions, runProblem, RunResult with its Checks and final fields;
//   - or the whole command line of the lagremap executable: runCommandLine.
// The layers below (<lagremap/data/...>, <lagremap/kernels/...>) and the other
// driver headers are installed too, for users who build their own time loop.
#pragma once

#include "cli.hpp"
#include "floating_point.hpp"
#include "input/config.hpp"
#include "kokkos_session.hpp"
#include "parallel.hpp"
#include "problem.hpp"
#include "run.hpp"
#include "setup.hpp"
