// Allocation of the state's Views (labels lagremap::state::<field>), once
// before the time loop.
#pragma once

#include "data/state.hpp"
#include "data/work_arena.hpp"
#include "kernels/step_start.hpp"

namespace lagremap {

// Allocates every cell, corner and node field for the mesh (labels
// lagremap::state::<field>); the per-material ones come with the material table.
// The corner arrays A_cp, M_cp, B_cp too when own_corner_arrays, else they are
// left for a RemapStep to carve out of its work memory (carveCornerArrays).
State allocateState(const Mesh& mesh, bool with_atomics_gather, bool own_corner_arrays = true);
// Moves the corner arrays into memory carved from `arena`, their values kept
// (those of allocateState, when it allocated them).
void carveCornerArrays(State& state, Index n_cells, WorkArena& arena);
// Allocates the per-material fields for n_materials; the deviators only when
// has_solids (a fluids-only run never touches them), the left Cauchy-Green
// tensors B^k only when has_neo_hookean (only Neo-Hookean materials carry
// them: 192 bytes a cell of two-material runs with a hypo-elastic solid).
// The plastic strains eps_p^k only when has_plastic_strain (some material
// hardens: hasPlasticStrain).
void allocateMaterialState(State& state, Index n_cells, int n_materials, bool has_solids,
                           bool has_neo_hookean, bool has_plastic_strain);

// The start-of-step copy of the state a step changes (copyCellStart,
// kernels/step_start.hpp), in one kernel over the cells (and the nodes x_n
// where `nodes`).
void copyStepStart(const State& state, const Vec3View& x_n, StepStart direction, unsigned solids,
                   bool nodes);

}  // namespace lagremap
