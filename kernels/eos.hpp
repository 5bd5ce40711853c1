// Equations of state (docs/method.md §A7) of the material record in
// data/material_params.hpp.
#pragma once

#include "../data/material_params.hpp"
#include "../data/math.hpp"

namespace lagremap {

struct ThermoState {
  double pressure;
  double sound_speed2;  // a^2; negative means no real sound speed (invalid state)
  // false when the EOS is outside its domain (Mie-Grüneisen eta - s(eta-1) <= 0,
  // Neo-Hookean J <= 0): pressure is then meaningless and sound_speed2 = -1, so
  // callers that only look at a^2 (the time step) also reject the state.
  bool valid = true;
};

KOKKOS_INLINE_FUNCTION ThermoState invalidThermoState() {
  return {0.0, -1.0, false};
}

// Ideal gas: p = (gamma - 1) rho e, a^2 = gamma p / rho.
KOKKOS_INLINE_FUNCTION ThermoState idealGas(double gamma, double rho, double e) {
  const double p = (gamma - 1.0) * rho * e;
  return {p, gamma * p / rho};
}

// Stiffened gas: p = (gamma - 1) rho e - gamma p_inf, a^2 = gamma (p + p_inf) / rho
// (the ideal gas shifted by p_inf: a liquid's stiffness at low cost). Valid
// where p + p_inf > 0, i.e. e > p_inf / rho.
KOKKOS_INLINE_FUNCTION ThermoState stiffenedGas(double gamma, double p_inf, double rho, double e) {
  const double p = (gamma - 1.0) * rho * e - gamma * p_inf;
  return {p, gamma * (p + p_inf) / rho};
}

// Mie-Grüneisen with a linear U_s-u_p Hugoniot as reference curve, written in
// eta = rho/rho0 (docs/method.md §A7, with the paper's typo in f corrected):
//   p   = rho0 a0^2 f(eta) + rho0 Gamma0 e,
//   f   = (eta-1) [eta - Gamma0 (eta-1)/2] / (eta - s(eta-1))^2,
//   a^2 = a0^2 f'(eta) + (Gamma0/rho0) p / eta^2,
//   f'  = [eta + (s - Gamma0)(eta-1)] / (eta - s(eta-1))^3.
// a^2 is dp/drho|_e + (p/rho^2) dp/de|_rho, the isentropic derivative. The
// denominator eta - s(eta-1) vanishes at eta = s/(s-1) (the Hugoniot's limiting
// compression); beyond it the model has no meaning, hence the guard.
KOKKOS_INLINE_FUNCTION ThermoState mieGruneisen(double rho0, double a0, double Gamma0, double s,
                                                double rho, double e) {
  const double eta = rho / rho0;
  const double compression = eta - 1.0;
  const double denominator = eta - s * compression;
  if (!(denominator > 0.0)) return invalidThermoState();
  const double inv_denominator = 1.0 / denominator;
  const double inv_denominator2 = inv_denominator * inv_denominator;
  const double f = compression * (eta - 0.5 * Gamma0 * compression) * inv_denominator2;
  const double df = (eta + (s - Gamma0) * compression) * inv_denominator2 * inv_denominator;
  const double a0_2 = a0 * a0;
  const double p = rho0 * a0_2 * f + rho0 * Gamma0 * e;
  return {p, a0_2 * df + (Gamma0 / rho0) * p / (eta * eta)};
}

// Shear modulus of the strength model: mu itself for hypo-elasticity,
// E/(2(1+nu)) for Neo-Hookean (docs/method.md §A7), zero for a fluid.
KOKKOS_INLINE_FUNCTION double shearModulus(const MaterialParams& mat) {
  switch (mat.strength) {
    case StrengthKind::HypoElastic:
      return mat.mu;
    case StrengthKind::NeoHookean:
      return mat.young / (2.0 * (1.0 + mat.poisson));
    case StrengthKind::None:
    default:
      return 0.0;
  }
}

// kappa = lambda + 2/3 mu with lambda = E nu/((1+nu)(1-2nu)) (docs/method.md §A7).
KOKKOS_INLINE_FUNCTION double bulkModulusNeoHookean(const MaterialParams& mat) {
  const double E = mat.young;
  const double nu = mat.poisson;
  const double lambda = E * nu / ((1.0 + nu) * (1.0 - 2.0 * nu));
  const double mu = E / (2.0 * (1.0 + nu));
  return lambda + (2.0 / 3.0) * mu;
}

// Neo-Hookean volumetric pressure p = -kappa/2 [(J-1) + ln(J)/J], J = rho0/rho
// (docs/method.md §A7); constitutive.hpp's neoHookeanStress uses the same function.
KOKKOS_INLINE_FUNCTION double neoHookeanPressure(double J, double kappa) {
  return -0.5 * kappa * ((J - 1.0) + math::log(J) / J);
}

// p(rho) of the Neo-Hookean solid; it does not depend on e (purely elastic).
// a^2 = dp/drho = (dp/dJ)(-J/rho) = kappa/(2 rho) [J + (1 - ln J)/J], which is
// kappa/rho at J = 1 and positive for every J > 0: the bulk sound speed (the
// longitudinal one adds 4/3 mu/rho, see constitutive.hpp).
KOKKOS_INLINE_FUNCTION ThermoState neoHookeanVolumetric(double rho0, double kappa, double rho) {
  const double J = rho0 / rho;
  if (!(J > 0.0)) return invalidThermoState();
  const double p = neoHookeanPressure(J, kappa);
  return {p, 0.5 * kappa / rho * (J + (1.0 - math::log(J)) / J)};
}

KOKKOS_INLINE_FUNCTION ThermoState evaluateEos(const MaterialParams& mat, double rho, double e) {
  switch (mat.eos) {
    case EosKind::MieGruneisen:
      return mieGruneisen(mat.rho0, mat.a0, mat.Gamma0, mat.s, rho, e);
    case EosKind::NeoHookean:
      return neoHookeanVolumetric(mat.rho0, bulkModulusNeoHookean(mat), rho);
    case EosKind::StiffenedGas:
      return stiffenedGas(mat.gamma, mat.p_inf, rho, e);
    case EosKind::IdealGas:
    default:
      return idealGas(mat.gamma, rho, e);
  }
}

}  // namespace lagremap
