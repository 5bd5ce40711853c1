// Cell, corner and node fields of the Lagrangian phase (docs/method.md §A3), flat SoA
// Views allocated once before the time loop.
#pragma once

#include "material_params.hpp"
#include "mesh.hpp"

namespace lagremap {

using MaterialView = DeviceView<MaterialParams*>;

// Most materials a run holds: per-cell kernels keep one number per material
// in registers (the remap's integrals, the mixed cells' volume ratios).
constexpr int kMaxMaterials = 8;

// How a mixed cell's materials share its volume change in the Lagrangian
// phase (docs/method.md §4): Relaxation (the default: shared by
// compressibility, pressure / normal-stress relaxation, solid bodies take
// their own normal stretch, dissipation by mass) or EqualStrain (the source
// paper's: volume fractions constant, every material compressed at the cell's
// rate, reversible work plus dissipation shared by volume fraction).
enum class MixtureClosure : int { Relaxation = 0, EqualStrain = 1 };

struct State {
  // Conserved per cell: mass (constant in the Lagrangian phase), velocity,
  // specific total energy.
  RealView m_c;
  Vec3View v_c;
  RealView E_c;
  MaterialView materials;  // material table

  // Per material k (docs/method.md §A3), allocated by initializeState once the table is
  // known. A material is present in a cell when alpha > 0; a pure cell (one
  // material) is the lagrange-mode case, mixed cells come with the remap.
  int n_materials = 0;
  bool has_solids = false;  // some material has strength: S and B are carried
  // Which of them the materials evolve (set with the material table): S^k of
  // hypo-elastic materials, B^k of Neo-Hookean ones, whose S^k the closure
  // derives from B^k. Both false: not known (the halo then sends both).
  bool has_hypo_elastic = false, has_neo_hookean = false;
  // In a mixed cell, a material below this volume fraction is a trace: it is
  // carried (mass, energy) but has no say in the cell's stress (its density
  // is the ratio of two tiny remapped numbers). 0 in lagrange mode.
  double alpha_trace = 0.0;
  // ... and a fluid below this one in a cell that also holds a solid (the
  // remap's diffusion tail of a gas inside a body, docs/method.md §4.6).
  double alpha_tail = 0.0;
  MixtureClosure closure = MixtureClosure::Relaxation;
  MatRealView alpha_ck;  // volume fraction (docs/method.md §4.2: shared volume changes)
  MatRealView m_ck;      // mass
  MatRealView e_ck;      // specific internal energy
  MatRealView p_ck;      // pressure (derived at every stage)
  MatSym6View S_ck;      // deviator: evolved (hypo-elastic) or from B (Neo-Hookean)
  MatSym6View B_ck;      // left Cauchy-Green tensor (only in runs with a Neo-Hookean material)
  // Equivalent plastic strain of the hardening solids (hasPlasticStrain; 0
  // elsewhere; only in runs with one): their yield stress grows with it.
  MatRealView eps_ck;
  // Compressibility weight alpha^k / (rho^k a_k^2) (derived): a mixed cell's
  // volume change is shared among its materials in proportion to it.
  MatRealView w_ck;
  // Unit normal out of material k's interface, -grad alpha^k / |grad alpha^k|
  // on the mesh of the last remap (0 where alpha^k is uniform): a solid's
  // normal stress across it is what pressure relaxation equalises. Allocated
  // for multi-material runs with solids only.
  MatVec3View n_ck;

  // Derived at every stage from the node positions (computeGeometry); the
  // mixture rules of docs/method.md §A3 give p = sum alpha^k p^k, S = sum alpha^k S^k,
  // aL^2 = sum (m^k/m) aL_k^2, aT^2 likewise.
  RealView vol_c, rho_c, e_c, p_c, aL_c, aT_c, len_c;
  Sym6View S_c;     // mixture deviatoric Cauchy stress (0 in fluids)
  Vec3View x_c;     // true centroid
  RealView dvdt_c;  // dv/dt = sum_p A_cp . V_p of the last update (time-step control)

  // Start of step t^n: base of the predictor-corrector and the last good state.
  Vec3View x_n0, v_c0;
  RealView E_c0;
  MatRealView e_ck0, alpha_ck0, w_ck0;
  // Material pressures of the step start: a mixed cell's pressure relaxation
  // is computed from them in both stages (docs/method.md §4.3).
  MatRealView p_ck0;
  RealView vol_c0;
  MatSym6View S_ck0, B_ck0;
  MatRealView eps_ck0;
  // Material masses of the step start, kept where a remap follows (the
  // Lagrangian step does not change them; RemapStep allocates them).
  MatRealView m_ck0;

  // Corner arrays, corner id = 8 c + local node.
  Vec3View A_cp;  // corner vector sum_f s_pf n_pf = d v_c / d x_p
  Sym6View M_cp;  // sum_f s_pf Q_cfp
  Vec3View B_cp;  // M_cp V_c(p) - sigma_c(p) A_cp

  // Nodes.
  Vec3View v_n;       // nodal velocity from the nodal solver
  Vec3View x_n_next;  // node positions at the end of the stage (swapped with Mesh::x_n)
  Vec3View f_ext_n;   // external force on the node (wall reaction + traction): sum_c F_cp
  // Node sums for the atomics gather variant (allocated only when used).
  Sym6View M_n;
  Vec3View B_n;
};

}  // namespace lagremap
