// Exact elastic-plastic plane waves (exact_two_wave.hpp). Every jump is found
// by bisection on the density behind it: the velocity jump of a
// Rankine-Hugoniot jump, sqrt((P_b - P_a)(1/rho_a - 1/rho_b)), grows with it.
#include "exact_two_wave.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace lagremap {
namespace {

// Pressure of the Mie-Gruneisen EOS with a linear U_s-u_p Hugoniot
// (docs/method.md §A7), written here again so that the reference shares no code with the
// kernels: p = rho0 a0^2 f(eta) + rho0 Gamma0 e,
// f = (eta - 1)(eta - Gamma0 (eta - 1)/2) / (eta - s (eta - 1))^2.
double pressure(const ElasticPlasticSolid& m, double rho, double e) {
  const double eta = rho / m.rho0, x = eta - 1.0;
  const double denominator = eta - m.s * x;
  return m.rho0 * m.a0 * m.a0 * x * (eta - 0.5 * m.Gamma0 * x) / (denominator * denominator) +
         m.rho0 * m.Gamma0 * e;
}

// Densest state the EOS takes (eta - s (eta - 1) > 0), a little short of it.
double limitingDensity(const ElasticPlasticSolid& m) {
  return m.s > 1.0 ? m.rho0 * m.s / (m.s - 1.0) * (1.0 - 1e-9) : 1e3 * m.rho0;
}

// Deviator S_xx in uniaxial strain at density rho: elastic, or at yield.
double deviatorXX(const ElasticPlasticSolid& m, double rho) {
  const double elastic = -4.0 / 3.0 * m.mu * std::log(rho / m.rho0);
  const double yield = 2.0 / 3.0 * m.yield_stress;
  return elastic < -yield ? -yield : elastic;
}

UniaxialState stateAt(const ElasticPlasticSolid& m, double rho, double u, double e) {
  const double p = pressure(m, rho, e);
  return {rho, u, e, p, -p + deviatorXX(m, rho)};
}

// The state behind a jump from `a` to density rho_b (energy from the
// Hugoniot, linear in e_b for this EOS), at the velocity the jump gives.
UniaxialState jumpTo(const ElasticPlasticSolid& m, const UniaxialState& a, double rho_b) {
  const double dv = 1.0 / a.rho - 1.0 / rho_b;  // specific volume compressed away
  const double P_a = -a.sigma_xx;
  const double P_cold = pressure(m, rho_b, 0.0) - deviatorXX(m, rho_b);
  const double G = m.rho0 * m.Gamma0;  // dP/de at fixed density
  const double e_b = (a.e + 0.5 * (P_a + P_cold) * dv) / (1.0 - 0.5 * G * dv);
  UniaxialState b = stateAt(m, rho_b, a.u, e_b);
  const double dP = -b.sigma_xx - P_a;
  b.u = a.u + std::sqrt(dP > 0.0 ? dP * dv : 0.0);
  return b;
}

// Wave speed of the jump a -> b (lab frame), from mass conservation.
double jumpSpeed(const UniaxialState& a, const UniaxialState& b) {
  return (b.rho * b.u - a.rho * a.u) / (b.rho - a.rho);
}

// The jump from `a` that reaches particle velocity u (bisection on density).
UniaxialState jumpToVelocity(const ElasticPlasticSolid& m, const UniaxialState& a, double u,
                             double rho_hi) {
  double lo = a.rho, hi = rho_hi;
  if (jumpTo(m, a, hi).u < u) {
    throw std::invalid_argument("two-wave solution: a particle velocity of " + std::to_string(u) +
                                " m/s compresses beyond the EOS's limit");
  }
  for (int iteration = 0; iteration < 200 && hi - lo > 1e-15 * hi; ++iteration) {
    const double mid = 0.5 * (lo + hi);
    (jumpTo(m, a, mid).u < u ? lo : hi) = mid;
  }
  return jumpTo(m, a, 0.5 * (lo + hi));
}

void checkSolid(const ElasticPlasticSolid& m) {
  if (!(m.rho0 > 0 && m.a0 > 0 && m.Gamma0 >= 0 && m.s >= 0 && m.mu > 0 && m.yield_stress > 0)) {
    throw std::invalid_argument("two-wave solution: non-positive material constant");
  }
}

}  // namespace

TwoWaveSolution solveTwoWave(const ElasticPlasticSolid& solid, double u_piston) {
  checkSolid(solid);
  if (!(u_piston > 0.0) || !std::isfinite(u_piston)) {
    throw std::invalid_argument("two-wave solution: the piston speed must be positive");
  }
  TwoWaveSolution w;
  w.initial = stateAt(solid, solid.rho0, 0.0, solid.e0);
  // Elastic limit: (4/3) mu ln(rho / rho0) = 2Y/3.
  const double rho_limit = solid.rho0 * std::exp(solid.yield_stress / (2.0 * solid.mu));
  const UniaxialState limit = jumpTo(solid, w.initial, rho_limit);
  w.plastic_wave = u_piston > limit.u;
  if (!w.plastic_wave) {
    w.precursor = w.plastic = jumpToVelocity(solid, w.initial, u_piston, rho_limit);
    w.precursor_speed = w.plastic_speed = jumpSpeed(w.initial, w.precursor);
    return w;
  }
  w.precursor = limit;
  w.precursor_speed = jumpSpeed(w.initial, limit);
  w.plastic = jumpToVelocity(solid, limit, u_piston, limitingDensity(solid));
  w.plastic_speed = jumpSpeed(limit, w.plastic);
  if (!(w.plastic_speed < w.precursor_speed)) {
    // A strong shock overtakes its precursor: one plastic shock from rest.
    w.plastic_wave = false;
    w.precursor = w.plastic = jumpToVelocity(solid, w.initial, u_piston, limitingDensity(solid));
    w.precursor_speed = w.plastic_speed = jumpSpeed(w.initial, w.plastic);
  }
  return w;
}

ImpactSolution solveImpact(const ElasticPlasticSolid& flyer, const ElasticPlasticSolid& target,
                           double v) {
  checkSolid(flyer);
  checkSolid(target);
  if (!(v > 0.0) || !std::isfinite(v)) {
    throw std::invalid_argument("two-wave solution: the flyer speed must be positive");
  }
  const bool same = flyer.rho0 == target.rho0 && flyer.a0 == target.a0 &&
                    flyer.Gamma0 == target.Gamma0 && flyer.s == target.s && flyer.mu == target.mu &&
                    flyer.yield_stress == target.yield_stress && flyer.e0 == target.e0;
  double u = 0.5 * v;
  if (!same) {
    // the interface's stress: the target's rises with u, the flyer's falls
    double lo = 0.0, hi = v;
    for (int iteration = 0; iteration < 200 && hi - lo > 1e-14 * v; ++iteration) {
      u = 0.5 * (lo + hi);
      const double sigma_target = solveTwoWave(target, u).plastic.sigma_xx;
      const double sigma_flyer = solveTwoWave(flyer, v - u).plastic.sigma_xx;
      (sigma_target > sigma_flyer ? lo : hi) = u;  // (sigma < 0 in compression)
    }
    u = 0.5 * (lo + hi);
  }
  ImpactSolution impact;
  impact.u_interface = u;
  impact.target = solveTwoWave(target, u);
  impact.flyer = solveTwoWave(flyer, v - u);
  impact.sigma_interface = impact.target.plastic.sigma_xx;
  return impact;
}

}  // namespace lagremap
