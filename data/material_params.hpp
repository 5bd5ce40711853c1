// The per-material parameter record (DESIGN §4). A material is a small POD
// record selected by enums, so kernels switch on it without virtual calls on
// the device and a table of them lives in a View.
#pragma once

namespace lagremap {

// NeoHookean is the volumetric half of the hyper-elastic model (DESIGN §4): its
// pressure depends on J = rho0/rho only, so it is an EOS like the others and
// every caller of evaluateEos (time step, nodal solver impedance) gets a real
// bulk sound speed for a Neo-Hookean solid without knowing about strength.
enum class EosKind : int { IdealGas = 0, MieGruneisen = 1, NeoHookean = 2 };

// Deviatoric response (DESIGN §4): None for fluids, HypoElastic = Wilkins
// Jaumann rate + radial return, NeoHookean = hyper-elastic from B.
enum class StrengthKind : int { None = 0, HypoElastic = 1, NeoHookean = 2 };

// `eos` and `gamma` stay first so `MaterialParams{EosKind::IdealGas, gamma}`
// keeps working; every other field defaults to "absent".
struct MaterialParams {
  EosKind eos = EosKind::IdealGas;
  double gamma = 1.4;  // ideal gas
  // Mie-Grüneisen; rho0 is also the reference density of the Neo-Hookean J.
  double rho0 = 0.0;
  double a0 = 0.0;      // bulk sound speed at rho0 (Hugoniot intercept)
  double Gamma0 = 0.0;  // Grüneisen coefficient at rho0, Gamma rho = Gamma0 rho0
  double s = 0.0;       // Hugoniot slope, U_s = a0 + s u_p
  // Strength.
  StrengthKind strength = StrengthKind::None;
  double mu = 0.0;            // shear modulus, hypo-elastic (use shearModulus())
  double yield_stress = 0.0;  // Y0, von Mises, perfect plasticity
  double young = 0.0;         // E, Neo-Hookean
  double poisson = 0.0;       // nu, Neo-Hookean
};

}  // namespace lagremap
