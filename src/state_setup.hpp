// Allocation of the state's Views (labels lagremap::state::<field>), once
// before the time loop.
#pragma once

#include "data/state.hpp"

namespace lagremap {

// Allocates every cell, corner and node field for the mesh (labels
// lagremap::state::<field>); the per-material ones come with the material table.
State allocateState(const Mesh& mesh, bool with_atomics_gather);
// Allocates the per-material fields for n_materials; the tensors only when
// has_solids (a fluids-only run never touches them).
void allocateMaterialState(State& state, Index n_cells, int n_materials, bool has_solids);

}  // namespace lagremap
