// Remap phase (docs/method.md §A9-A11): the Lagrangian state is carried back onto the
// initial mesh every step of `--mode remap`, in four parts and four kernels
// (remapDensitiesAndSweptFaces launches the first and third together;
// remapAuditAndMoveNodes puts the nodes on the target, and in the staged
// form sums what crossed the outer boundary and the totals, which the fused
// form's update sums):
//   remapDensities:  per cell, the remapped quantities per unit volume on the
//                    Lagrangian cell: alpha^k, alpha^k rho^k, alpha^k rho^k e^k,
//                    rho V, rho |V|^2/2 and alpha^k S^k / alpha^k B^k;
//   remapGradients:  least-squares gradients on the Lagrangian mesh, limited
//                    (Barth-Jespersen, beta = 1; volume fractions compressive,
//                    beta = 2 by default);
//   computeSweptFaces (swept_face.hpp): volume and first moment swept by
//                    every face triangle between the two meshes, summed by
//                    face side (the region a face gains, the one it gives);
//   remapUpdate:     per cell, the upwind flux of each of its 12 face-side
//                    regions, the new integrals, the clean-up of volume
//                    fractions, the recovered state and the kinetic-energy fix.
// Fluxes are second order in the primitive variables, each reconstructed
// (limited) in the upwind cell: alpha^k (compressive limiter), the material
// density rho^k and energy e^k, and the velocity V. The conserved fluxes
// follow by the product rule,
//   F(alpha^k rho^k) = F(alpha^k) rho^k_up + alpha^k_up grad(rho^k) . (M_t - x_up dV_t),
//   F(alpha^k rho^k e^k) = F(alpha^k rho^k) e^k_up + (alpha^k rho^k)_up grad(e^k) . (...),
//   F(rho V) = F(rho) V_r,  F(rho |V|^2/2) = F(rho) |V_r|^2 / 2,
//   V_r = V_up + grad(V) . (M_t - x_up dV_t) / dV_t (the velocity at the region's centroid),
// and the tensors ride on the volume flux, F(alpha^k T^k) = F(alpha^k) T^k_up.
// So a material's density, energy and the velocity stay weighted means of
// limited values: a trace of a material swept into a cell (alpha ~ 1e-6)
// keeps a physical density instead of the ratio of two independently limited
// reconstructions, and velocity gets no new extrema at a density jump.
// Every cell computes the fluxes of its own 12 regions. The swept regions of a
// face are stored with exactly opposite signs on its two sides and the upwind
// cell is chosen identically from both (ties at dV = 0 go to the lower cell
// id), so the neighbour's flux is the exact negative of ours: every remapped
// total is conserved to round-off without atomics, deterministically.
// Its kernel launchers are `static` (internal linkage: docs/method.md §7.2).
#pragma once

#include "../data/mesh.hpp"
#include "../data/state.hpp"
#include "../data/work_arena.hpp"
#include "audit_sums.hpp"
#include "kernel_form.hpp"
#include "reconstruction.hpp"
#include "sum_array.hpp"
#include "swept_face.hpp"

namespace lagremap {

constexpr int kMaxRemapVariables = 3 * kMaxMaterials + 4 + 7 * kMaxMaterials;

// Columns of the per-cell tables of remapped quantities.
struct RemapLayout {
  int n_materials = 0;
  int n_variables = 0;
  // First of the 6 tensor columns of material k (alpha^k S^k for a
  // hypo-elastic material, alpha^k B^k for a Neo-Hookean one), -1 for a fluid.
  Kokkos::Array<int, kMaxMaterials> tensor_column;
  // The column of material k's plastic strain, (alpha rho eps_p)^k (a
  // hardening material, hasPlasticStrain), -1 for the others: after the
  // energies, before the momentum (so a column is per unit mass, as the
  // mass, energy and plastic strain are, exactly when v < kinetic()).
  Kokkos::Array<int, kMaxMaterials> plastic_column;
  int momentum_begin = 0;  // 3 n_materials + the plastic strains' columns

  KOKKOS_INLINE_FUNCTION int alpha(int k) const { return k; }
  KOKKOS_INLINE_FUNCTION int mass(int k) const { return n_materials + k; }
  KOKKOS_INLINE_FUNCTION int energy(int k) const { return 2 * n_materials + k; }
  KOKKOS_INLINE_FUNCTION int momentum(int d) const { return momentum_begin + d; }
  KOKKOS_INLINE_FUNCTION int kinetic() const { return momentum_begin + 3; }
  // Columns with a reconstructed gradient. The gradient is that of the
  // primitive variable of the column (remapDensities): alpha^k, rho^k, e^k,
  // the velocity, the tensors S^k or B^k and eps_p^k; the kinetic energy is
  // not reconstructed (it rides on the momentum's parcels).
  KOKKOS_INLINE_FUNCTION bool reconstructed(int v) const { return v != kinetic(); }

  // Material of column v: k for the columns of material k but its volume
  // fraction (rho^k, e^k and its tensor), -1 for the volume fractions and the
  // velocity, which every cell has (makeRemapLayout fills it).
  Kokkos::Array<int, kMaxRemapVariables> column_material;

  // Whether a cell of densities q has the primitive variable of column v (a
  // material absent from it has no density, energy or tensor).
  template <class Table>
  KOKKOS_INLINE_FUNCTION bool hasPrimitive(const Table& q, Index c, int v) const {
    const int k = column_material[v];
    if (k < 0) return true;
    const bool has_volume = q(c, alpha(k)) > 0.0;
    return v > kinetic() ? has_volume : has_volume && q(c, mass(k)) > 0.0;
  }
};

// A trace below RemapControls::alpha_floor joins the cell's main material
// when its mass is at most this fraction of the main material's.
constexpr double kTraceMassJoined = 1e-15;

struct RemapControls {
  double beta_alpha = 2.0;  // limiter parameter of the volume fractions (1: Barth-Jespersen)
  // Below this volume fraction a material is dropped from the cell after the
  // sweep (its mass and energy go to the cell's main material).
  double alpha_floor = 1e-10;
  bool limit = true;  // false: unlimited reconstruction (tests: linear exactness)
  // false (--order 1): constant states in the cells, first-order upwind
  // fluxes (the gradients zeroed after remapGradients, which still gives
  // the interface normals)
  bool reconstruct = true;
  // The range that bounds a swept parcel's specific energy and plastic
  // strain (remap.parcel_bound, docs/method.md §5.2): false, the two cells
  // sharing the face; true, the upwind cell's limiter stencil (it and its
  // face neighbours).
  bool stencil_parcel_bound = true;
  // Each parcel's volume fraction kept in [0, 1] (remap.parcel_fractions,
  // docs/method.md §5.3): a lever near the upwind cell's reach extrapolates
  // its reconstruction past the vertex values the limiter bounds.
  bool bounded_parcel_fractions = false;
  bool kinetic_energy_fix = true;  // false: kinetic energy from the remapped momentum (tests)
  KernelForm kernels = defaultKernelForm();  // numerics.kernels
};

// Per-cell work arrays of the remap, written by remapDensities and
// remapGradients and read by remapUpdate.
struct RemapFields {
  MatRealView density;              // (cell, column) per unit volume on the Lagrangian cell
  MatRealView primitive;            // (cell, column) primitive variable, where the cell has it
  DeviceView<Real** [3]> gradient;  // (cell, column, xyz) of the primitive, limited
  RealView reach;                   // largest centroid-vertex distance of each Lagrangian cell
  // The staged form's per-cell work rows of remapUpdate (empty in the fused
  // form, whose thread holds them): each cell's integrals (cell, column) and
  // its materials' source ranges (cell, 4 m + rho_lo, rho_hi, e_lo, e_hi).
  MatRealView integral, source_range;
  RealView memory;  // what holds them (allocateRemapFields; empty when carved from a RemapStep's)
};

// The remap's work arrays carved out of `arena`: every entry is written in
// each apply() before it is read, so the memory may hold anything before.
inline RemapFields carveRemapFields(Index n_cells, const RemapLayout& layout, KernelForm form,
                                    WorkArena& arena) {
  const Index rows = form == KernelForm::Staged ? n_cells : 0;
  RemapFields fields;
  fields.density = arena.carve<MatRealView>(n_cells, layout.n_variables);
  fields.primitive = arena.carve<MatRealView>(n_cells, layout.n_variables);
  fields.gradient = arena.carve<DeviceView<Real** [3]>>(n_cells, layout.n_variables);
  fields.reach = arena.carve<RealView>(n_cells);
  fields.integral = arena.carve<MatRealView>(rows, layout.n_variables);
  fields.source_range = arena.carve<MatRealView>(rows, 4 * layout.n_materials);
  return fields;
}

// The same in memory of their own (label lagremap::remap::fields).
inline RemapFields allocateRemapFields(Index n_cells, const RemapLayout& layout,
                                       KernelForm form = defaultKernelForm()) {
  WorkArena size;
  carveRemapFields(n_cells, layout, form, size);
  const RealView memory("lagremap::remap::fields", size.used());
  WorkArena arena(memory);
  RemapFields fields = carveRemapFields(n_cells, layout, form, arena);
  fields.memory = memory;
  return fields;
}

// Cell c's remapped quantities per unit volume (remapDensities, the file's
// head), and the primitive variable of each column, which the gradients and the
// fluxes read (computed once per cell, not once per neighbour and per swept
// triangle): alpha^k, rho^k = (alpha rho)^k / alpha^k, e^k = (alpha rho e)^k /
// (alpha rho)^k, V = rho V / rho and T^k = (alpha T)^k / alpha^k; zero where
// the cell does not have it (RemapLayout::hasPrimitive).
namespace detail {
KOKKOS_FORCEINLINE_FUNCTION void cellDensities(const State& s, const RemapLayout& layout,
                                               const MatRealView& q, const MatRealView& w,
                                               Index c) {
  const double inv_volume = 1.0 / s.vol_c(c);
  double rho = 0.0;  // bulk density, summed as the momentum's primitive needs it
  for (int k = 0; k < layout.n_materials; ++k) {
    const double alpha = s.alpha_ck(c, k);
    const double mass = s.m_ck(c, k);
    const double mass_density = mass * inv_volume;
    const double energy_density = alpha > 0.0 ? mass * s.e_ck(c, k) * inv_volume : 0.0;
    const bool has_mass = alpha > 0.0 && mass_density > 0.0;
    q(c, layout.alpha(k)) = alpha;
    q(c, layout.mass(k)) = mass_density;
    q(c, layout.energy(k)) = energy_density;
    w(c, layout.alpha(k)) = alpha;
    w(c, layout.mass(k)) = has_mass ? mass_density / alpha : 0.0;
    w(c, layout.energy(k)) = has_mass ? energy_density / mass_density : 0.0;
    rho += mass_density;
    const int column = layout.tensor_column[k];
    if (column < 0) continue;
    const SymMat3 tensor = s.materials(k).strength == StrengthKind::NeoHookean
                               ? loadSym(s.B_ck, c, k)
                               : loadSym(s.S_ck, c, k);
    const double t[6] = {tensor.xx, tensor.yy, tensor.zz, tensor.xy, tensor.yz, tensor.xz};
    for (int i = 0; i < 6; ++i) {
      q(c, column + i) = alpha * t[i];
      // (alpha T) / alpha: the primitive the tensor integral was always divided back to
      w(c, column + i) = alpha > 0.0 ? (alpha * t[i]) / alpha : 0.0;
    }
    const int plastic = layout.plastic_column[k];
    if (plastic < 0) continue;
    const double plastic_density = alpha > 0.0 ? mass_density * s.eps_ck(c, k) : 0.0;
    q(c, plastic) = plastic_density;
    w(c, plastic) = has_mass ? plastic_density / mass_density : 0.0;
  }
  const double mass = s.m_c(c);
  const Vec3 v = loadVec3(s.v_c, c);
  const double momentum[3] = {mass * v.x * inv_volume, mass * v.y * inv_volume,
                              mass * v.z * inv_volume};
  for (int d = 0; d < 3; ++d) {
    q(c, layout.momentum(d)) = momentum[d];
    w(c, layout.momentum(d)) = momentum[d] / rho;
  }
  q(c, layout.kinetic()) = 0.5 * mass * dot(v, v) * inv_volume;
  w(c, layout.kinetic()) = 0.0;  // not reconstructed
}
}  // namespace detail

static inline void remapDensities(const State& state, const RemapLayout& layout,
                                  const RemapFields& fields) {
  const auto s = state;
  const auto q = fields.density;
  const auto w = fields.primitive;
  Kokkos::parallel_for(
      "lagremap::remap::densities", Kokkos::RangePolicy<ExecSpace>(0, Index(s.m_c.extent(0))),
      KOKKOS_LAMBDA(const Index c) { detail::cellDensities(s, layout, q, w, c); });
}

// remapDensities and computeSweptFaces in one launch, a cell at a time (they
// read nothing the other writes): the remap's first kernel.
static inline void remapDensitiesAndSweptFaces(const Mesh& mesh, const State& state,
                                               const RemapLayout& layout, const RemapFields& fields,
                                               const Vec3View& x_lag, const Vec3View& x_target,
                                               const SweptFaces& swept_faces,
                                               KernelForm form = defaultKernelForm()) {
  const auto s = state;
  const auto q = fields.density;
  const auto w = fields.primitive;
  const swept::CellSweeper sweeper(mesh, x_lag, x_target, swept_faces);
  const auto policy = Kokkos::RangePolicy<ExecSpace>(0, mesh.n_cells);
  if constexpr (kFusedKernelsBuilt) {
    if (form == KernelForm::Fused) {
      Kokkos::parallel_for(
          "lagremap::remap::densities_and_swept_faces", policy, KOKKOS_LAMBDA(const Index c) {
            detail::cellDensities(s, layout, q, w, c);
            sweeper.sweep<true>(c);
          });
      return;
    }
  }
  Kokkos::parallel_for(
      "lagremap::remap::densities_and_swept_faces", policy, KOKKOS_LAMBDA(const Index c) {
        detail::cellDensities(s, layout, q, w, c);
        sweeper.sweep<false>(c);
      });
}

namespace detail {

// The face-neighbour stencil of a cell's least-squares gradients: neighbour
// ids (-1: none; no ghost, the gradient is one-sided at the boundary) and the
// pseudo-inverse of the normal matrix; the neighbours' centroid offsets come
// from `offset(f)` (held or reloaded: see remapGradients).
struct GradientStencil {
  Index nb[6];
  SymMat3 solver;
};

// Limited gradient of column v's primitive (docs/method.md §A10: Barth-Jespersen,
// compressive beta for the volume fractions), and for a volume fraction the
// interface normal -grad alpha / |grad alpha| of the next Lagrangian steps
// (unlimited: the limiter scales the gradient, and may zero it). A
// neighbour without the material counts as "no change".
// `excursion_of(grad)`: the extremes of grad . (x_p - x_c) over the 8 vertices
// in vertex order.
template <class Normals, class Offset, class ExcursionOf>
KOKKOS_FORCEINLINE_FUNCTION void limitedColumnGradient(
    const RemapLayout& layout, const RemapFields& fields, const Normals& interface_normal, Index c,
    int v, const GradientStencil& stencil, const Offset& offset, const ExcursionOf& excursion_of,
    double beta_alpha, bool limit) {
  const double center = fields.primitive(c, v);
  Bounds bounds(center);
  Vec3 rhs{0.0, 0.0, 0.0};
  for (int f = 0; f < 6; ++f) {
    const Index nb = stencil.nb[f];
    if (nb < 0 || !layout.hasPrimitive(fields.density, nb, v)) continue;
    const double value = fields.primitive(nb, v);
    rhs += (value - center) * offset(f);
    bounds.include(value);
  }
  const Vec3 grad = stencil.solver * rhs;
  if (v < layout.n_materials && c < Index(interface_normal.extent(0))) {
    const double length = math::sqrt(dot(grad, grad));
    const Vec3 normal = length > 0.0 ? (-1.0 / length) * grad : Vec3{0.0, 0.0, 0.0};
    interface_normal(c, v, 0) = normal.x;
    interface_normal(c, v, 1) = normal.y;
    interface_normal(c, v, 2) = normal.z;
  }
  const VertexExcursion excursion = excursion_of(grad);
  const double beta = v < layout.n_materials ? beta_alpha : 1.0;
  const double limiter = limit ? cellLimiter(excursion, center, bounds, beta) : 1.0;
  fields.gradient(c, v, 0) = limiter * grad.x;
  fields.gradient(c, v, 1) = limiter * grad.y;
  fields.gradient(c, v, 2) = limiter * grad.z;
}

// Kinetic-energy limit of the velocity slopes where a gas is present
// (docs/method.md §5.6): cut into parcels that follow the linear velocity, a
// cell holds up to |grad V|^2 R^2 / 2 per unit mass more kinetic energy than
// its mean velocity carries, which the kinetic-energy fix takes from the
// internal energy, and a gas cannot go below zero (the `ball`'s near-vacuum
// wake did). So |grad V| R <= sqrt(e_gas); solids may cool below zero
// (tension).
template <class MaterialTable>
KOKKOS_FORCEINLINE_FUNCTION void limitVelocitySlopesByGasEnergy(const RemapLayout& layout,
                                                                const RemapFields& fields,
                                                                const MaterialTable& materials,
                                                                Index c, double reach2) {
  const auto& q = fields.density;
  double gas_energy = 1e300;
  for (int k = 0; k < layout.n_materials; ++k) {
    const double alpha = q(c, layout.alpha(k)), mass = q(c, layout.mass(k));
    if (!(alpha > 0.0 && mass > 0.0) || !isGasFamily(materials(k))) continue;
    const double e = q(c, layout.energy(k)) / mass;
    gas_energy = e < gas_energy ? e : gas_energy;
  }
  if (gas_energy == 1e300) return;
  double slope2 = 0.0;
  for (int d = 0; d < 3; ++d) {
    for (int i = 0; i < 3; ++i) {
      const double g = fields.gradient(c, layout.momentum(d), i);
      slope2 += g * g;
    }
  }
  const double allowed2 = gas_energy > 0.0 ? gas_energy / reach2 : 0.0;
  if (slope2 > allowed2) {
    const double scale = math::sqrt(allowed2 / slope2);
    for (int d = 0; d < 3; ++d) {
      for (int i = 0; i < 3; ++i) fields.gradient(c, layout.momentum(d), i) *= scale;
    }
  }
}

}  // namespace detail

namespace detail {

// remapGradients of one cell. kHold: the neighbours' centroid offsets and
// the vertex offsets are computed once and held for every column (the fused
// form: the vertex offsets in lanes, VertexVectors); else they are reloaded
// from the mesh for each column (the staged form: a GPU thread holds 60 fewer
// doubles). The same numbers, so the same bits, either way.
template <bool kHold, class Normals, class Materials>
KOKKOS_FORCEINLINE_FUNCTION void cellGradients(const CellNodesView& cell_nodes,
                                               const CellFacesView& neighbors, const Vec3View& x_n,
                                               const Vec3View& x_c, const Normals& interface_normal,
                                               const Materials& materials,
                                               const RemapLayout& layout, const RemapFields& fields,
                                               double beta_alpha, bool limit, Index c) {
  const Vec3 centroid = loadVec3(x_c, c);
  GradientStencil stencil;
  Vec3 held_offset[kHold ? 6 : 1];
  LeastSquares lsq;
  for (int f = 0; f < 6; ++f) {
    stencil.nb[f] = neighbors(c, f);
    const Vec3 d = stencil.nb[f] < 0 ? Vec3{0.0, 0.0, 0.0}  // (no neighbour: never read)
                                     : loadVec3(x_c, stencil.nb[f]) - centroid;
    if constexpr (kHold) held_offset[f] = d;
    if (stencil.nb[f] >= 0) lsq.addOffset(d);
  }
  stencil.solver = lsq.solver();
  const auto offset = [&](int f) {
    if constexpr (kHold) {
      return held_offset[f];
    } else {
      return loadVec3(x_c, stencil.nb[f]) - centroid;
    }
  };
  const auto vertex = [&](int p) { return loadVec3(x_n, cell_nodes(c, p)) - centroid; };
  VertexVectors held_vertex;  // (kHold: in lanes)
  double reach2 = 0.0;
  if constexpr (kHold) {
    for (int p = 0; p < kHexVertices; ++p) held_vertex.set(p, vertex(p));
    double length2[kHexVertices];
    dotEach(held_vertex, held_vertex, length2);
    for (int p = 0; p < kHexVertices; ++p) reach2 = length2[p] > reach2 ? length2[p] : reach2;
  } else {
    for (int p = 0; p < kHexVertices; ++p) {
      const Vec3 d = vertex(p);
      const double length2 = d.x * d.x + d.y * d.y + d.z * d.z;
      reach2 = length2 > reach2 ? length2 : reach2;
    }
  }
  fields.reach(c) = math::sqrt(reach2);
  const auto excursion_of = [&](const Vec3& grad) {
    VertexExcursion excursion;
    if constexpr (kHold) {
      double delta[kHexVertices];
      dotEach(grad, held_vertex, delta);
      for (int p = 0; p < kHexVertices; ++p) excursion.include(delta[p]);
    } else {
      for (int p = 0; p < kHexVertices; ++p) {
        const Vec3 d = vertex(p);
        excursion.include(grad.x * d.x + grad.y * d.y + grad.z * d.z);
      }
    }
    return excursion;
  };
  // A mixed cell's rho^k, e^k, V and tensors are swept constant
  // (remapUpdate): only its volume fractions need a gradient.
  int materials_present = 0;
  for (int k = 0; k < layout.n_materials; ++k) {
    materials_present += fields.density(c, layout.alpha(k)) > 0.0;
  }
  const int reconstructed_end = materials_present > 1 ? layout.n_materials : layout.n_variables;
  for (int v = 0; v < layout.n_variables; ++v) {
    if (!layout.reconstructed(v)) continue;
    if (v >= reconstructed_end || !layout.hasPrimitive(fields.density, c, v)) {
      for (int d = 0; d < 3; ++d) fields.gradient(c, v, d) = 0.0;
      continue;
    }
    limitedColumnGradient(layout, fields, interface_normal, c, v, stencil, offset, excursion_of,
                          beta_alpha, limit);
  }
  // (a mixed cell's velocity slopes are zero: nothing to limit)
  if (limit && materials_present <= 1) {
    limitVelocitySlopesByGasEnergy(layout, fields, materials, c, reach2);
  }
}

}  // namespace detail

// Limited least-squares gradients (docs/method.md §A10) on the Lagrangian mesh, stored
// already multiplied by their limiter: psi(x) = psi_c + grad . (x - x_c).
// Also stores each cell's reach, the largest distance from its centroid to a
// vertex: every point of the cell is within it (remapUpdate's lever limit),
// and each material's interface normal -grad alpha^k / |grad alpha^k|
// (State::n_ck, for the stress relaxation of mixed cells, geometry.hpp).
static inline void remapGradients(const Mesh& mesh, const State& state, const RemapLayout& layout,
                                  const RemapControls& controls, const RemapFields& fields) {
  const auto cell_nodes = mesh.cell_nodes;
  const auto neighbors = mesh.cell_neighbors;
  const auto x_n = mesh.x_n;
  const auto x_c = state.x_c;
  const auto interface_normal = state.n_ck;
  const auto materials = state.materials;
  const double beta_alpha = controls.beta_alpha;
  const bool limit = controls.limit;
  const auto policy = Kokkos::RangePolicy<ExecSpace>(0, mesh.n_cells);
  if constexpr (kFusedKernelsBuilt) {
    if (controls.kernels == KernelForm::Fused) {
      Kokkos::parallel_for(
          "lagremap::remap::gradients", policy, KOKKOS_LAMBDA(const Index c) {
            detail::cellGradients<true>(cell_nodes, neighbors, x_n, x_c, interface_normal,
                                        materials, layout, fields, beta_alpha, limit, c);
          });
      return;
    }
  }
  Kokkos::parallel_for(
      "lagremap::remap::gradients", policy, KOKKOS_LAMBDA(const Index c) {
        detail::cellGradients<false>(cell_nodes, neighbors, x_n, x_c, interface_normal, materials,
                                     layout, fields, beta_alpha, limit, c);
      });
}

namespace detail {

// Range of each material's density and specific energy over the cells it
// comes from (the cell and its upwind cells): the bounds of the clean-up.
// `Store` holds them (rho_lo, rho_hi, e_lo, e_hi: bound(0..3, m)): the
// thread's own arrays in the fused form (SourceBounds), a row of a View in
// the staged form (SourceBoundsRow, RemapFields::source_range).
template <class Store>
struct SourceRangeOf {
  Store bound;

  KOKKOS_FORCEINLINE_FUNCTION double& rho_lo(int m) { return bound(0, m); }
  KOKKOS_FORCEINLINE_FUNCTION double& rho_hi(int m) { return bound(1, m); }
  KOKKOS_FORCEINLINE_FUNCTION double& e_lo(int m) { return bound(2, m); }
  KOKKOS_FORCEINLINE_FUNCTION double& e_hi(int m) { return bound(3, m); }

  KOKKOS_INLINE_FUNCTION void reset(int n_materials) {
    for (int m = 0; m < n_materials; ++m) {
      rho_lo(m) = e_lo(m) = 1e300;
      rho_hi(m) = e_hi(m) = -1e300;
    }
  }
  KOKKOS_FORCEINLINE_FUNCTION void include(const RemapLayout& layout, const RemapFields& fields,
                                           Index cell, int m) {
    if (!layout.hasPrimitive(fields.density, cell, layout.mass(m))) return;
    includeSource(layout, fields, cell, m);
  }
  // The same for a cell known to have material m's density (a volume and a
  // mass, RemapLayout::hasPrimitive).
  KOKKOS_FORCEINLINE_FUNCTION void includeSource(const RemapLayout& layout,
                                                 const RemapFields& fields, Index cell, int m) {
    const double rho = fields.primitive(cell, layout.mass(m));
    const double e = fields.primitive(cell, layout.energy(m));
    rho_lo(m) = rho < rho_lo(m) ? rho : rho_lo(m);
    rho_hi(m) = rho > rho_hi(m) ? rho : rho_hi(m);
    e_lo(m) = e < e_lo(m) ? e : e_lo(m);
    e_hi(m) = e > e_hi(m) ? e : e_hi(m);
  }
};

struct SourceBounds {
  double value[4][kMaxMaterials];
  KOKKOS_FORCEINLINE_FUNCTION double& operator()(int i, int m) { return value[i][m]; }
};
struct SourceBoundsRow {
  MatRealView view;
  Index row;
  KOKKOS_FORCEINLINE_FUNCTION double& operator()(int i, int m) const {
    return view(row, 4 * m + i);
  }
};

// A row of a View as an array (the staged form's per-cell work arrays).
struct RowOf {
  MatRealView view;
  Index row;
  KOKKOS_FORCEINLINE_FUNCTION double& operator[](int i) const { return view(row, i); }
};

// What a region swept across the outer boundary carries out of cell c: it
// takes the cell's own state (zero gradient, its densities `q`), booked as
// crossed (mass, momentum, total energy).
KOKKOS_FORCEINLINE_FUNCTION void bookCrossing(const RemapLayout& layout, const MatRealView& q,
                                              Index c, double dvol, double* crossed) {
  double mass = 0.0, energy = dvol * q(c, layout.kinetic());
  for (int m = 0; m < layout.n_materials; ++m) {
    mass += dvol * q(c, layout.mass(m));
    energy += dvol * q(c, layout.energy(m));
  }
  crossed[0] += mass;
  for (int d = 0; d < 3; ++d) crossed[1 + d] += dvol * q(c, layout.momentum(d));
  crossed[4] += energy;
}

// The integrals of a region swept across the outer boundary: the cell's own
// state (zero gradient), its crossing booked into `crossed` if given.
template <class Integral>
KOKKOS_FORCEINLINE_FUNCTION void fluxOuterRegion(const RemapLayout& layout,
                                                 const RemapFields& fields, Index c, double dvol,
                                                 Integral& integral, double* crossed) {
  const auto& q = fields.density;
  for (int v = 0; v < layout.n_variables; ++v) integral[v] += dvol * q(c, v);
  if (crossed) bookCrossing(layout, q, c, dvol, crossed);
}

// Lever limit (docs/method.md §5.2): the slopes are evaluated at the region's
// centroid x_up + lever / dV. A region that sweeps almost no volume but has a
// first moment (a twisting face) puts that point arbitrarily far away, where
// the reconstruction extrapolates without bound; it is kept within the
// upwind cell's reach. Both sides of the face compute the same scale.
KOKKOS_FORCEINLINE_FUNCTION Vec3 limitedLever(const Vec3& lever, double reach_up, double dvol) {
  const double lever_norm = math::sqrt(dot(lever, lever));
  const double lever_max = reach_up * (dvol < 0.0 ? -dvol : dvol);
  return lever_norm > lever_max ? (lever_max / lever_norm) * lever : lever;
}

// A parcel's specific energy (or plastic strain: `column`) stays inside the
// range of the cells it may come from (a positivity guard: within the reach
// the linear extrapolation may still pass the face, which a material at 1
// J/kg beside one at 1e6 J/kg cannot afford): the two cells sharing the face
// (`other`: the downwind cell), or with `stencil` the upwind cell and its
// face neighbours, the range its limiter keeps the reconstruction in. A
// region swept by an oblique face reaches the upwind cell's neighbours
// across its other faces, whose values the face's two cells need not span:
// clipped to the face's range, the parcel's energy alone is cut, its
// density not, and a smooth flow at uniform pressure gets a pressure error
// of the size of the slope along the face (docs/verification.md §2f).
KOKKOS_FORCEINLINE_FUNCTION double boundedSpecificFlux(const RemapLayout& layout,
                                                       const RemapFields& fields,
                                                       const CellFacesView& neighbors, bool stencil,
                                                       Index up, Index other, int m, int column,
                                                       double mass_flux, double e_up,
                                                       double energy_flux) {
  double e_lo = e_up, e_hi = e_up;
  const auto include = [&](Index source) {
    if (!(fields.density(source, layout.alpha(m)) > 0.0 &&
          fields.density(source, layout.mass(m)) > 0.0)) {
      return;
    }
    const double e_source = fields.primitive(source, column);
    e_lo = e_source < e_lo ? e_source : e_lo;
    e_hi = e_source > e_hi ? e_source : e_hi;
  };
  if (stencil) {
    for (int f = 0; f < 6; ++f) {
      const Index nb = neighbors(up, f);
      if (nb >= 0) include(nb);
    }
  } else {
    include(other);
  }
  const double bound_a = mass_flux * e_lo, bound_b = mass_flux * e_hi;
  const double lowest = bound_a < bound_b ? bound_a : bound_b;
  const double highest = bound_a < bound_b ? bound_b : bound_a;
  return energy_flux < lowest ? lowest : (energy_flux > highest ? highest : energy_flux);
}

// The parcel guards of a remap (RemapControls): the range of a parcel's
// specific energy (stencil or face) and the bound of its volume fractions.
struct ParcelGuards {
  bool stencil_range = true;
  bool bounded_fractions = false;
};

// A parcel's volume-fraction flux with its fraction alpha_flux / dvol in [0, 1].
KOKKOS_FORCEINLINE_FUNCTION double boundedFractionFlux(double alpha_flux, double dvol) {
  const double lo = dvol < 0.0 ? dvol : 0.0, hi = dvol < 0.0 ? 0.0 : dvol;
  return alpha_flux < lo ? lo : (alpha_flux > hi ? hi : alpha_flux);
}

// Upwind flux of one interior face-side region of volume dvol and lever
// M - x_up dV (docs/method.md §A9, §5.3-5.6): each material's volume second
// order, its mass and energy by the product rule on the upwind alpha^k,
// rho^k, e^k, its tensor on the volume flux; then momentum and kinetic energy
// as a rigid parcel of the mass flux at the upwind velocity at the region's
// centroid, V_r = V_up + grad V . lever / dV. From a mixed upwind cell rho^k,
// e^k and V are taken constant (their slopes would carry the cell's whole
// (alpha rho)_up into a region that may hold a sliver of the material).
template <class Integral, class Range>
KOKKOS_FORCEINLINE_FUNCTION void fluxInteriorRegion(
    const RemapLayout& layout, const RemapFields& fields, const CellFacesView& neighbors, Index c,
    Index nb, Index up, double dvol, const Vec3& lever, bool limit, ParcelGuards guards,
    Integral& integral, Range& range) {
  const auto& q = fields.density;
  const auto& w = fields.primitive;
  auto slope = [&](int v) {  // limited gradient of column v's primitive . lever
    return fields.gradient(up, v, 0) * lever.x + fields.gradient(up, v, 1) * lever.y +
           fields.gradient(up, v, 2) * lever.z;
  };
  int materials_up = 0;
  for (int m = 0; m < layout.n_materials; ++m) materials_up += q(up, layout.alpha(m)) > 0.0;
  const bool pure_up = materials_up == 1;
  double mass_flux_total = 0.0;
  for (int m = 0; m < layout.n_materials; ++m) {
    const int a = layout.alpha(m);
    double alpha_flux = dvol * q(up, a) + slope(a);
    if (limit && guards.bounded_fractions) alpha_flux = boundedFractionFlux(alpha_flux, dvol);
    integral[a] += alpha_flux;
    const double alpha_up = q(up, a);
    const double mass_up = q(up, layout.mass(m));
    if (!(alpha_up > 0.0 && mass_up > 0.0)) continue;         // nothing of m to carry
    if (up != c) range.includeSource(layout, fields, up, m);  // (it has m's density)
    const double rho_up_m = w(up, layout.mass(m));
    const double e_up = w(up, layout.energy(m));
    const double mass_flux =
        alpha_flux * rho_up_m + (pure_up ? alpha_up * slope(layout.mass(m)) : 0.0);
    integral[layout.mass(m)] += mass_flux;
    double energy_flux = mass_flux * e_up + (pure_up ? mass_up * slope(layout.energy(m)) : 0.0);
    if (limit) {
      energy_flux =
          boundedSpecificFlux(layout, fields, neighbors, guards.stencil_range, up, up == c ? nb : c,
                              m, layout.energy(m), mass_flux, e_up, energy_flux);
    }
    integral[layout.energy(m)] += energy_flux;
    mass_flux_total += mass_flux;
    const int column = layout.tensor_column[m];
    if (column < 0) continue;
    for (int i = 0; i < 6; ++i) {
      integral[column + i] +=
          alpha_flux * w(up, column + i) + (pure_up ? alpha_up * slope(column + i) : 0.0);
    }
    // a hardening solid's eps_p rides on the mass flux as e^k does
    const int plastic = layout.plastic_column[m];
    if (plastic < 0) continue;
    const double eps_up = w(up, plastic);
    double plastic_flux = mass_flux * eps_up + (pure_up ? mass_up * slope(plastic) : 0.0);
    if (limit) {
      plastic_flux =
          boundedSpecificFlux(layout, fields, neighbors, guards.stencil_range, up, up == c ? nb : c,
                              m, plastic, mass_flux, eps_up, plastic_flux);
    }
    integral[plastic] += plastic_flux;
  }
  // dm V_r and dm |V_r|^2 / 2: a new velocity is a weighted mean of limited
  // values, and the kinetic-energy fix is the same in every frame.
  const double inv_dvol = dvol != 0.0 ? 1.0 / dvol : 0.0;
  double kinetic_flux = 0.0;
  for (int d = 0; d < 3; ++d) {
    const int column = layout.momentum(d);
    const double v_region = w(up, column) + (pure_up ? slope(column) * inv_dvol : 0.0);
    integral[column] += mass_flux_total * v_region;
    kinetic_flux += mass_flux_total * 0.5 * v_region * v_region;
  }
  integral[layout.kinetic()] += kinetic_flux;
}

// The new material state of a cell of volume `volume` from its integrals
// (docs/method.md §5.7): volume fractions clipped to [0, 1]; a
// material whose volume and mass fluxes nearly cancel keeps its density in
// the range of its sources (by its volume fraction) and its specific energy
// too (the excess internal energy goes to the heaviest material); traces
// below alpha_floor join the main material; the fractions are renormalised.
// Nothing is lost: mass and energy only move between materials.
// (Integral, Range, Array: the fused form's arrays or the staged form's rows)
template <class MaterialTable, class Integral, class Range, class Array>
KOKKOS_FORCEINLINE_FUNCTION void cleanUpMaterials(const RemapLayout& layout,
                                                  const MaterialTable& materials,
                                                  const Integral& integral, double volume,
                                                  Range& range, double alpha_floor, Array& alpha,
                                                  Array& mass, Array& internal) {
  const int n_materials = layout.n_materials;
  int main_material = 0, heaviest = 0;
  for (int k = 0; k < n_materials; ++k) {
    const double fraction = integral[layout.alpha(k)] / volume;
    alpha[k] = fraction < 0.0 ? 0.0 : (fraction > 1.0 ? 1.0 : fraction);
    mass[k] = integral[layout.mass(k)];
    internal[k] = integral[layout.energy(k)];
    if (alpha[k] > alpha[main_material]) main_material = k;
    if (mass[k] > mass[heaviest]) heaviest = k;
  }
  for (int k = 0; k < n_materials; ++k) {
    if (!(alpha[k] > 0.0 && mass[k] > 0.0) || !(range.rho_hi(k) >= range.rho_lo(k))) continue;
    const double rho = mass[k] / (alpha[k] * volume);
    if (rho < range.rho_lo(k) || rho > range.rho_hi(k)) {
      alpha[k] = mass[k] / ((rho < range.rho_lo(k) ? range.rho_lo(k) : range.rho_hi(k)) * volume);
      alpha[k] = alpha[k] > 1.0 ? 1.0 : alpha[k];
    }
    // (the heaviest: the `ball`'s near-vacuum gas cannot take an aluminium
    // trace's excess, which took it to 1e6 J/kg or below zero by volume)
    if (k == heaviest) continue;
    const double e = internal[k] / mass[k];
    if (e < range.e_lo(k) || e > range.e_hi(k)) {
      const double bounded = mass[k] * (e < range.e_lo(k) ? range.e_lo(k) : range.e_hi(k));
      internal[heaviest] += internal[k] - bounded;
      internal[k] = bounded;
    }
  }
  double alpha_sum = 0.0;
  for (int k = 0; k < n_materials; ++k) {
    if (k == main_material) continue;
    // A trace (or a round-off negative mass) is not a material state; but a
    // trace whose negative energy (a solid fragment in tension) would take a
    // gas below zero stays a material until it can.
    const bool takes_gas_below_zero = internal[k] < 0.0 &&
                                      internal[main_material] + internal[k] < 0.0 &&
                                      isGasFamily(materials(main_material)) && alpha[k] > 0.0;
    // A trace joins only once its mass is nothing to the material taking it:
    // an aluminium trace at alpha_floor holds 3e-7 of a gas's mass at 1
    // kg/m^3, which raised the gas's density by as much (docs/method.md §5.7).
    const bool negligible_mass = mass[k] <= kTraceMassJoined * mass[main_material];
    if ((alpha[k] <= alpha_floor && negligible_mass && !takes_gas_below_zero) || !(mass[k] > 0.0)) {
      // A round-off negative mass goes to the heaviest material, which can
      // afford it: the main material by volume may be a near-vacuum gas
      // lighter than the deficit (the `ball` at --scale 0.5 took its gas to a
      // negative mass, 3e-18 kg less 2e-17, and stopped).
      const int sink = mass[k] > 0.0 || heaviest == k ? main_material : heaviest;
      mass[sink] += mass[k];
      internal[sink] += internal[k];
      alpha[k] = 0.0;
      mass[k] = 0.0;
      internal[k] = 0.0;
    }
    alpha_sum += alpha[k];
  }
  alpha_sum += alpha[main_material];
  for (int k = 0; k < n_materials; ++k) alpha[k] /= alpha_sum;
}

// Velocity, the kinetic-energy fix and the stored state of cell c: the
// remapped kinetic energy is kept and its difference to |m V|^2 / 2m goes to
// the internal energies by mass fraction, so the total energy is remapped
// conservatively; each tensor is alpha^k T^k over the remapped alpha^k volume.
// (internal: read before e^k is stored, so it may be the row of e^k itself)
template <class Integral, class Array>
KOKKOS_FORCEINLINE_FUNCTION void storeRemappedCell(const State& s, const RemapLayout& layout,
                                                   Index c, const Integral& integral,
                                                   const Array& alpha, const Array& mass,
                                                   Array& internal, bool kinetic_energy_fix) {
  const int n_materials = layout.n_materials;
  double cell_mass = 0.0;
  for (int k = 0; k < n_materials; ++k) cell_mass += mass[k];
  const Vec3 momentum{integral[layout.momentum(0)], integral[layout.momentum(1)],
                      integral[layout.momentum(2)]};
  const Vec3 velocity = (1.0 / cell_mass) * momentum;
  const double kinetic_remapped = integral[layout.kinetic()];
  const double kinetic_fix =
      kinetic_energy_fix ? kinetic_remapped - 0.5 * dot(momentum, velocity) : 0.0;
  double cell_internal = 0.0;
  for (int k = 0; k < n_materials; ++k) {
    internal[k] += (mass[k] / cell_mass) * kinetic_fix;
    cell_internal += internal[k];
  }
  s.m_c(c) = cell_mass;
  storeVec3(s.v_c, c, velocity);
  s.E_c(c) = (cell_internal + 0.5 * dot(momentum, velocity)) / cell_mass;
  for (int k = 0; k < n_materials; ++k) {
    s.alpha_ck(c, k) = alpha[k];
    s.m_ck(c, k) = mass[k];
    s.e_ck(c, k) = alpha[k] > 0.0 ? internal[k] / mass[k] : 0.0;
    const int column = layout.tensor_column[k];
    if (column < 0) continue;
    const double material_volume = integral[layout.alpha(k)];
    const bool present = alpha[k] > 0.0 && material_volume > 0.0;
    double t[6];
    for (int i = 0; i < 6; ++i) t[i] = present ? integral[column + i] / material_volume : 0.0;
    const bool hyper = s.materials(k).strength == StrengthKind::NeoHookean;
    const SymMat3 tensor =
        hyper && !present ? identitySym() : SymMat3{t[0], t[1], t[2], t[3], t[4], t[5]};
    storeSym(hyper ? s.B_ck : s.S_ck, c, k, tensor);
    // eps_p^k over the remapped mass, at least 0 (a trace that joins the
    // main material brings it its mass, not its strain)
    const int plastic = layout.plastic_column[k];
    if (plastic < 0) continue;
    const double eps = present && mass[k] > 0.0 ? integral[plastic] / mass[k] : 0.0;
    s.eps_ck(c, k) = eps > 0.0 ? eps : 0.0;
  }
}

}  // namespace detail

namespace detail {

// remapUpdate of cell c with its work arrays (the fused form's own, or the
// staged form's rows: RemapFields::integral and source_range, the state's
// alpha^k, m^k and e^k rows for alpha, mass and internal energy, which no
// other cell reads in the kernel). The same arithmetic, so the same bits.
// `audit`: the cell's part of the remap's audit added there (addRemapAudit's,
// as the fluxes go), or nothing.
template <class Integral, class Range, class Array>
KOKKOS_FORCEINLINE_FUNCTION void remapCell(const State& s, const CellFacesView& neighbors,
                                           const RemapLayout& layout, const RemapFields& fields,
                                           const SweptFaces& swept, bool limit, ParcelGuards guards,
                                           double alpha_floor, bool kinetic_energy_fix, Index c,
                                           Integral& integral, Range& range, Array& alpha,
                                           Array& mass, Array& internal, double* audit) {
  // integrals over the Lagrangian cell, then the fluxes of its regions
  const double volume_lag = s.vol_c(c);
  for (int v = 0; v < layout.n_variables; ++v) integral[v] = fields.density(c, v) * volume_lag;
  range.reset(layout.n_materials);
  for (int m = 0; m < layout.n_materials; ++m) range.include(layout, fields, c, m);
  double volume = volume_lag;
  for (int f = 0; f < 6; ++f) {
    const Index nb = neighbors(c, f);
    for (int side = 0; side < 2; ++side) {
      const Index r = sweptRegionId(c, f, side);
      const double dvol = swept.dvol_r(r);
      volume += dvol;
      if (nb < 0) {  // nothing crosses a wall (dV = 0 there)
        if (dvol != 0.0) fluxOuterRegion(layout, fields, c, dvol, integral, audit);
        continue;
      }
      // A region of no volume carries nothing once its lever is limited
      // (and is no source of the clean-up bounds); unlimited, its first
      // moment still carries the linear part.
      if (dvol == 0.0 && limit) continue;
      // upwind: the neighbour for the gained side, as on the other side
      const Index up = side == kGainedSide ? nb : c;
      Vec3 lever = loadVec3(swept.moment_r, r) - dvol * loadVec3(s.x_c, up);
      if (limit) lever = limitedLever(lever, fields.reach(up), dvol);
      fluxInteriorRegion(layout, fields, neighbors, c, nb, up, dvol, lever, limit, guards, integral,
                         range);
    }
  }
  cleanUpMaterials(layout, s.materials, integral, volume, range, alpha_floor, alpha, mass,
                   internal);
  storeRemappedCell(s, layout, c, integral, alpha, mass, internal, kinetic_energy_fix);
  if (audit) addCellTotals(s, c, audit + 5);
}

// The crossings of cell c's outer regions (a cell's outer faces are its
// own: its sweep wrote them), added to crossed[0 .. 4] (RemapBoundaryFlux's
// order).
KOKKOS_FORCEINLINE_FUNCTION void bookCellCrossings(const RemapLayout& layout, const MatRealView& q,
                                                   const CellFacesView& neighbors,
                                                   const RealView& dvol_r, Index c,
                                                   double* crossed) {
  for (int f = 0; f < 6; ++f) {
    if (neighbors(c, f) >= 0) continue;
    for (int side = 0; side < 2; ++side) {
      const double dvol = dvol_r(sweptRegionId(c, f, side));
      if (dvol != 0.0) bookCrossing(layout, q, c, dvol, crossed);
    }
  }
}
}  // namespace detail

// The owned cell c's part of a remap's audit (RemapAuditView): what its outer
// regions carried across, and its remapped totals.
KOKKOS_FORCEINLINE_FUNCTION void addRemapAudit(const State& s, const RemapLayout& layout,
                                               const MatRealView& q, const CellFacesView& neighbors,
                                               const RealView& dvol_r, Index c, double* sums) {
  detail::bookCellCrossings(layout, q, neighbors, dvol_r, c, sums);
  addCellTotals(s, c, sums + 5);
}

// Sum of the upwind fluxes of the cell's 12 face-side regions, the new state on
// the initial mesh, clean-up and kinetic-energy fix (docs/method.md §A9-A11).
// The fused form also sums the remap's audit into `audit_into`, without
// waiting (each crossing as its flux loop meets it, the totals of the stored
// cell); the staged form's update holds no reduction
// (remapAuditAndMoveNodes sums it).
static inline void remapUpdate(const Mesh& mesh, const State& state, const RemapLayout& layout,
                               const RemapControls& controls, const RemapFields& fields,
                               const SweptFaces& swept, const RemapAuditView& audit_into) {
  const auto neighbors = mesh.cell_neighbors;
  const auto s = state;
  const bool limit = controls.limit;
  const detail::ParcelGuards guards{controls.stencil_parcel_bound,
                                    controls.bounded_parcel_fractions};
  const double alpha_floor = controls.alpha_floor;
  const bool kinetic_energy_fix = controls.kinetic_energy_fix;
  const auto policy = Kokkos::RangePolicy<ExecSpace>(0, mesh.n_cells);
  if constexpr (kFusedKernelsBuilt) {
    if (controls.kernels == KernelForm::Fused) {  // the thread's own work arrays
      const auto owned = mesh.cell_owned;
      const auto cell = KOKKOS_LAMBDA(const Index c, double* sums) {
        double integral[kMaxRemapVariables];
        detail::SourceRangeOf<detail::SourceBounds> range;
        double alpha[kMaxMaterials], mass[kMaxMaterials], internal[kMaxMaterials];
        detail::remapCell(s, neighbors, layout, fields, swept, limit, guards, alpha_floor,
                          kinetic_energy_fix, c, integral, range, alpha, mass, internal,
                          owned(c) ? sums : nullptr);
      };
      Kokkos::parallel_reduce("lagremap::remap::fluxes_and_update", policy,
                              SumsInArray<kRemapAuditSums, decltype(cell)>(cell), audit_into);
      return;
    }
  }
  const auto integral = fields.integral, source_range = fields.source_range;
  Kokkos::parallel_for(
      "lagremap::remap::fluxes_and_update", policy, KOKKOS_LAMBDA(const Index c) {
        using detail::RowOf;
        RowOf integral_row{integral, c}, alpha{s.alpha_ck, c}, mass{s.m_ck, c}, internal{s.e_ck, c};
        detail::SourceRangeOf<detail::SourceBoundsRow> range{{source_range, c}};
        detail::remapCell(s, neighbors, layout, fields, swept, limit, guards, alpha_floor,
                          kinetic_energy_fix, c, integral_row, range, alpha, mass, internal,
                          nullptr);
      });
}

// The mesh's nodes put on the remap's target, x_n <- target
// (remapAuditAndMoveNodes: nothing after the gradients reads the Lagrangian
// positions). Empty: the nodes stay.
struct NodesOntoTarget {
  Vec3View x_n, target;
  KOKKOS_INLINE_FUNCTION Index count() const { return Index(x_n.extent(0)); }
  KOKKOS_INLINE_FUNCTION void move(Index n) const {
    for (int d = 0; d < 3; ++d) x_n(n, d) = target(n, d);
  }
};

// The remap's last kernel, after remapUpdate: the nodes moved onto the
// target; in the staged form (a thread per cell or node, the larger count)
// with the audit of each owned cell (addRemapAudit) summed into `into`
// without waiting (in the update's kernel the sums held 144 registers on
// sm_90 where it holds 124). The fused form's update summed it (remapUpdate);
// its nodes move in a kernel of their own (within the update's range they
// cost the CPU 54 instructions a cell-step more).
static inline void remapAuditAndMoveNodes(const Mesh& mesh, const State& state,
                                          const RemapLayout& layout, const RemapFields& fields,
                                          const SweptFaces& swept, const NodesOntoTarget& nodes,
                                          const RemapAuditView& into,
                                          KernelForm form = defaultKernelForm()) {
  if constexpr (kFusedKernelsBuilt) {
    if (form == KernelForm::Fused) {
      Kokkos::parallel_for(
          "lagremap::remap::move_nodes", Kokkos::RangePolicy<ExecSpace>(0, nodes.count()),
          KOKKOS_LAMBDA(const Index n) { nodes.move(n); });
      return;
    }
  }
  const auto owned = mesh.cell_owned;
  const auto neighbors = mesh.cell_neighbors;
  const auto q = fields.density;
  const auto dvol_r = swept.dvol_r;
  const auto s = state;
  const Index n_cells = mesh.n_cells;
  const Index count = n_cells > nodes.count() ? n_cells : nodes.count();
  const auto terms = KOKKOS_LAMBDA(const Index i, double* sums) {
    if (i < nodes.count()) nodes.move(i);
    if (i >= n_cells || !owned(i)) return;  // (a ghost's sums are its owner's)
    addRemapAudit(s, layout, q, neighbors, dvol_r, i, sums);
  };
  Kokkos::parallel_reduce("lagremap::remap::audit_and_move_nodes",
                          Kokkos::RangePolicy<ExecSpace>(0, count),
                          SumsInArray<kRemapAuditSums, decltype(terms)>(terms), into);
}

}  // namespace lagremap
