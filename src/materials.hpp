// Named material presets (docs/verification.md §8.1), host only. Kept out of
// the device headers because it uses std::string and exceptions. Header-only so
// it needs no entry in the library's source list.
#pragma once

#include <stdexcept>
#include <string>

#include "kernels/eos.hpp"

namespace lagremap {

// Returns the parameters of "Al", "Be-hypo", "Cu", "Steel-hyper", "Be-hyper" or
// "Gas" (ideal gas, gamma = 1.4; its state is set per problem). Neo-Hookean presets
// leave `mu` at 0: their shear modulus is shearModulus(mat) = E/(2(1+nu)), so an
// override of E or nu cannot leave a stale mu behind.
namespace detail {
// Mie-Gruneisen EOS with Wilkins hypo-elastic perfect plasticity.
inline MaterialParams hypoElasticMieGruneisen(double rho0, double a0, double Gamma0, double s,
                                              double mu, double yield_stress) {
  MaterialParams mat;
  mat.eos = EosKind::MieGruneisen;
  mat.rho0 = rho0;
  mat.a0 = a0;
  mat.Gamma0 = Gamma0;
  mat.s = s;
  mat.strength = StrengthKind::HypoElastic;
  mat.mu = mu;
  mat.yield_stress = yield_stress;
  return mat;
}
// Neo-Hookean hyper-elastic solid (volumetric and deviatoric parts).
inline MaterialParams neoHookean(double rho0, double young, double poisson) {
  MaterialParams mat;
  mat.eos = EosKind::NeoHookean;
  mat.rho0 = rho0;
  mat.strength = StrengthKind::NeoHookean;
  mat.young = young;
  mat.poisson = poisson;
  return mat;
}
}  // namespace detail

inline MaterialParams materialPreset(const std::string& name) {
  if (name == "Gas") return MaterialParams{EosKind::IdealGas, 1.4};
  if (name == "Al")
    return detail::hypoElasticMieGruneisen(2785.0, 5328.0, 2.0, 1.338, 27.6e9, 3.0e8);
  if (name == "Be-hypo") {
    return detail::hypoElasticMieGruneisen(1845.0, 12870.0, 2.0, 1.124, 151.9e9, 330.0e6);
  }
  if (name == "Cu") {
    // The copper Taylor-rod benchmark's solid (docs/verification.md §8.10):
    // rho 8930, mu = E / (2 (1 + nu)) of E = 117 GPa, nu = 0.35, Y0 = 0.4 GPa
    // with linear hardening H = 0.1 GPa; copper's Mie-Gruneisen Hugoniot
    // (a0 = 3940 m/s, s = 1.49, Gamma0 = 2.0).
    MaterialParams cu =
        detail::hypoElasticMieGruneisen(8930.0, 3940.0, 2.0, 1.49, 117.0e9 / (2.0 * 1.35), 0.4e9);
    cu.hardening = HardeningKind::Linear;
    cu.hardening_modulus = 0.1e9;
    return cu;
  }
  if (name == "Steel-hyper") return detail::neoHookean(8000.0, 200.0e9, 0.0);
  if (name == "Be-hyper") return detail::neoHookean(1845.0, 3.1827e11, 0.0539);
  throw std::invalid_argument("unknown material preset '" + name +
                              "' (known: Al, Be-hypo, Cu, Steel-hyper, Be-hyper, Gas)");
}

}  // namespace lagremap
