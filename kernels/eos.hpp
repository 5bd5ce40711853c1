// Equations of state (DESIGN §4). A material is a small POD record selected by
// an enum, so kernels switch on it without virtual calls on the device.
#pragma once

#include "math.hpp"

namespace lagremap {

enum class EosKind : int { IdealGas = 0 };

struct MaterialParams {
  EosKind eos = EosKind::IdealGas;
  double gamma = 1.4;  // ideal gas
};

struct ThermoState {
  double pressure;
  double sound_speed2;  // a^2; negative means no real sound speed (invalid state)
};

// Ideal gas: p = (gamma - 1) rho e, a^2 = gamma p / rho.
KOKKOS_INLINE_FUNCTION ThermoState idealGas(double gamma, double rho, double e) {
  const double p = (gamma - 1.0) * rho * e;
  return {p, gamma * p / rho};
}

KOKKOS_INLINE_FUNCTION ThermoState evaluateEos(const MaterialParams& mat, double rho, double e) {
  switch (mat.eos) {
    case EosKind::IdealGas:
    default:
      return idealGas(mat.gamma, rho, e);
  }
}

}  // namespace lagremap
