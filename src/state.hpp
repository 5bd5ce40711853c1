// Cell, corner and node fields of the Lagrangian phase (DESIGN §3), flat SoA
// Views allocated once before the time loop.
#pragma once

#include "../kernels/eos.hpp"
#include "mesh.hpp"

namespace lagremap {

using MaterialView = DeviceView<MaterialParams*>;

struct State {
  // Conserved per cell: mass (constant in the Lagrangian phase), velocity,
  // specific total energy.
  RealView m_c;
  Vec3View v_c;
  RealView E_c;
  DeviceView<int*> mat_c;  // material of the cell
  Sym6View S_c;            // deviatoric Cauchy stress (solids; 0 in fluids)
  Sym6View B_c;            // left Cauchy-Green tensor (Neo-Hookean solids; I elsewhere)
  MaterialView materials;  // material table

  // Derived at every stage from the node positions (computeGeometry).
  RealView vol_c, rho_c, e_c, p_c, aL_c, aT_c, len_c;
  Vec3View x_c;     // true centroid
  RealView dvdt_c;  // dv/dt = sum_p A_cp . V_p of the last update (time-step control)

  // Start of step t^n: base of the predictor-corrector and the last good state.
  Vec3View x_n0, v_c0;
  RealView E_c0;
  Sym6View S_c0, B_c0;

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

// Allocates every field for the mesh (labels lagremap::state::<field>).
State allocateState(const Mesh& mesh, bool with_atomics_gather);

}  // namespace lagremap
