// Set-up of a run (docs/method.md §7.5): every key a run has, the numerics, the
// problem's mesh and initial state on this rank, and the checks of bad input
// that must come before anything is allocated.
#pragma once

#include <memory>
#include <string>

#include "decomposition.hpp"
#include "input/config.hpp"
#include "lagrange_step.hpp"
#include "mesh_relaxation.hpp"
#include "parallel.hpp"
#include "problem.hpp"
#include "remap_step.hpp"

namespace lagremap {

// Every key a run has: the common numerics keys plus the problem's.
Config declareConfig(const Problem& problem, const std::string& mode = "lagrange");
// remap.parcel_bound (face or stencil, docs/method.md §5.2) with the given
// default: declareConfig declares it unless the problem has (`bump`).

// The numerics.* keys (and t_end) as the time loop uses them; throws
// ConfigError for impossible values.
Numerics readNumerics(const Config& config);

// A mesh that cannot fit in memory is bad input, said before anything is
// allocated (the operating system would otherwise kill the run).
void checkMemoryFits(const Config& config);

// The problem's mesh, materials and initial cells; an impossible mesh is ConfigError.
ProblemSetup setUpProblem(const Problem& problem, const Config& config, const std::string& name);

// Uploads a problem's initial cells into an allocated state: m = rho v (v from
// the same geometry the kernels use), E = e + |V|^2 / 2, and the material table.
void initializeState(const ProblemSetup& setup, State& state);

// The ale.* keys but ale.every; throws ConfigError for impossible values.
RelaxationControls readRelaxationControls(const Config& config);

// The remap.* keys; the trace threshold goes to the state (the mixture rules read it).
RemapControls readRemapControls(const Config& config, State& state);

// The remap step of the mesh; a mesh it cannot remap on is ConfigError.
std::unique_ptr<RemapStep> makeRemapStep(Mesh& mesh, State& state, const RemapControls& controls,
                                         PhaseTimers& timers, const Halo* halo,
                                         const std::string& problem);

// Runs `action` on every rank; an error one rank finds (bad input, an
// unreadable file) is thrown as ConfigError by all, with the lowest rank's message.
template <class Action>
void collectively(Action action) {
  std::string error;
  try {
    action();
  } catch (const std::exception& bad) {
    error = bad.what();
  }
  error = parallel::firstMessage(error);
  if (!error.empty()) throw ConfigError(error);
}

}  // namespace lagremap
