// The per-material parameter record (docs/method.md §A7). A material is a small POD
// record selected by enums, so kernels switch on it without virtual calls on
// the device and a table of them lives in a View.
#pragma once

#include <Kokkos_Core.hpp>

namespace lagremap {

// NeoHookean is the volumetric half of the hyper-elastic model (docs/method.md §A7): its
// pressure depends on J = rho0/rho only, so it is an EOS like the others and
// every caller of evaluateEos (time step, nodal solver impedance) gets a real
// bulk sound speed for a Neo-Hookean solid without knowing about strength.
// StiffenedGas: p = (gamma - 1) rho e - gamma p_inf (a liquid such as water;
// p_inf = 0 is the ideal gas).
enum class EosKind : int { IdealGas = 0, MieGruneisen = 1, NeoHookean = 2, StiffenedGas = 3 };

// Deviatoric response (docs/method.md §A7): None for fluids, HypoElastic = Wilkins
// Jaumann rate + radial return, NeoHookean = hyper-elastic from B.
enum class StrengthKind : int { None = 0, HypoElastic = 1, NeoHookean = 2 };

// The yield stress of a hypo-elastic solid (docs/method.md §A7): Perfect, Y = Y0;
// Linear isotropic hardening, Y = Y0 + H eps_p; JohnsonCook,
// Y = (Y0 + B eps_p^n)(1 + C ln(max(rate / rate0, 1)))(1 - T*^m).
enum class HardeningKind : int { Perfect = 0, Linear = 1, JohnsonCook = 2 };

// `eos` and `gamma` stay first so `MaterialParams{EosKind::IdealGas, gamma}`
// keeps working; every other field defaults to "absent".
struct MaterialParams {
  EosKind eos = EosKind::IdealGas;
  double gamma = 1.4;  // ideal and stiffened gas
  double p_inf = 0.0;  // stiffened gas: the pressure shift p_inf
  // Mie-Grüneisen; rho0 is also the reference density of the Neo-Hookean J.
  double rho0 = 0.0;
  double a0 = 0.0;      // bulk sound speed at rho0 (Hugoniot intercept)
  double Gamma0 = 0.0;  // Grüneisen coefficient at rho0, Gamma rho = Gamma0 rho0
  double s = 0.0;       // Hugoniot slope, U_s = a0 + s u_p
  // Strength.
  StrengthKind strength = StrengthKind::None;
  double mu = 0.0;            // shear modulus, hypo-elastic (use shearModulus())
  double yield_stress = 0.0;  // Y0 (Johnson-Cook's A), von Mises
  double young = 0.0;         // E, Neo-Hookean
  double poisson = 0.0;       // nu, Neo-Hookean
  // Hypo-elastic hardening (last: the fields above keep their places, which
  // the per-cell kernels read).
  HardeningKind hardening = HardeningKind::Perfect;
  double hardening_modulus = 0.0;  // H, linear hardening
  // Johnson-Cook: B, n, C, the reference rate rate0 [1/s] and the thermal
  // exponent m; the temperature is T = T_room + e / c_v (specific_heat c_v; 0:
  // no thermal softening), T* = (T - T_room) / (T_melt - T_room) in [0, 1].
  double jc_B = 0.0, jc_n = 1.0, jc_C = 0.0, jc_rate0 = 1.0, jc_m = 1.0;
  double room_temperature = 293.0, melt_temperature = 0.0, specific_heat = 0.0;
  // To 192 bytes (3 x 64): the kernels index the table by material, and x86
  // forms k x 192 with two cheap instructions (k x 176 took cellThermo 3 more
  // a call).
  double padding_[2] = {0.0, 0.0};
};

// A solid whose yield stress reads its equivalent plastic strain, which the
// state then carries (State::eps_ck): a hardening hypo-elastic one. (A
// perfectly plastic solid's would be a diagnostic only; linear hardening with
// H = 0 is perfect plasticity that carries it.)
KOKKOS_INLINE_FUNCTION bool hasPlasticStrain(const MaterialParams& material) {
  return material.strength == StrengthKind::HypoElastic &&
         material.hardening != HardeningKind::Perfect;
}

// A fluid of the gas family (ideal or stiffened): its internal energy is
// positive in every valid state, so the remap and the mixed-cell energy split
// keep it so (docs/method.md §4.5, §5.6-5.7).
KOKKOS_INLINE_FUNCTION bool isGasFamily(const MaterialParams& material) {
  return material.eos == EosKind::IdealGas || material.eos == EosKind::StiffenedGas;
}

// A condensed material: a solid, or a liquid (a stiffened gas with p_inf >
// 0). Its density in a mixed cell should stay near its pure cells' (the
// mixed_cells check).
KOKKOS_INLINE_FUNCTION bool isCondensed(const MaterialParams& material) {
  return !(isGasFamily(material) && !(material.p_inf > 0.0));
}

}  // namespace lagremap
