// Named material presets (PROBLEMS.md "Materials used"), host only. Kept out of
// the device headers because it uses std::string and exceptions. Header-only so
// it needs no entry in the library's source list.
#pragma once

#include <stdexcept>
#include <string>

#include "kernels/eos.hpp"

namespace lagremap {

// Returns the parameters of "Al", "Be-hypo", "Steel-hyper", "Be-hyper" or "Gas"
// (ideal gas, gamma = 1.4; its state is set per problem). Neo-Hookean presets
// leave `mu` at 0: their shear modulus is shearModulus(mat) = E/(2(1+nu)), so an
// override of E or nu cannot leave a stale mu behind.
inline MaterialParams materialPreset(const std::string& name) {
  MaterialParams mat;
  if (name == "Gas") {
    mat.eos = EosKind::IdealGas;
    mat.gamma = 1.4;
  } else if (name == "Al") {
    mat.eos = EosKind::MieGruneisen;
    mat.rho0 = 2785.0;
    mat.a0 = 5328.0;
    mat.Gamma0 = 2.0;
    mat.s = 1.338;
    mat.strength = StrengthKind::HypoElastic;
    mat.mu = 27.6e9;
    mat.yield_stress = 3.0e8;
  } else if (name == "Be-hypo") {
    mat.eos = EosKind::MieGruneisen;
    mat.rho0 = 1845.0;
    mat.a0 = 12870.0;
    mat.Gamma0 = 2.0;
    mat.s = 1.124;
    mat.strength = StrengthKind::HypoElastic;
    mat.mu = 151.9e9;
    mat.yield_stress = 330.0e6;
  } else if (name == "Steel-hyper") {
    mat.eos = EosKind::NeoHookean;
    mat.rho0 = 8000.0;
    mat.strength = StrengthKind::NeoHookean;
    mat.young = 200.0e9;
    mat.poisson = 0.0;
  } else if (name == "Be-hyper") {
    mat.eos = EosKind::NeoHookean;
    mat.rho0 = 1845.0;
    mat.strength = StrengthKind::NeoHookean;
    mat.young = 3.1827e11;
    mat.poisson = 0.0539;
  } else {
    throw std::invalid_argument("unknown material preset '" + name +
                                "' (known: Al, Be-hypo, Steel-hyper, Be-hyper, Gas)");
  }
  return mat;
}

}  // namespace lagremap
