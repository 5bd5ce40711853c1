// Deviatoric (strength) models of docs/method.md §A7, as pointwise device functions: the
// Wilkins hypo-elastic update with radial return, and the Neo-Hookean
// hyper-elastic stress from the left Cauchy-Green tensor B. Stress is the Cauchy
// stress, tension positive, sigma = -p I + S (docs/method.md §A1). The velocity gradient
// is L_ij = dV_i/dx_j (row i = velocity component, column j = derivative).
#pragma once

#include "../data/math.hpp"
#include "eos.hpp"

namespace lagremap {

namespace detail {
// (A F^T)_ij = row i of A . row j of F.
KOKKOS_INLINE_FUNCTION double rowDot(const Mat3& A, int i, const Mat3& F, int j) {
  return A.m[i][0] * F.m[j][0] + A.m[i][1] * F.m[j][1] + A.m[i][2] * F.m[j][2];
}
}  // namespace detail

// F B F^T, symmetric by construction (only the six independent entries are
// formed). With F the deformation gradient over a step this advances the left
// Cauchy-Green tensor, B_{n+1} = F B_n F^T, the exact integral of docs/method.md §A7's
// dB/dt = L B + B L^T for that F; it keeps B positive definite whenever F is
// invertible, which a forward-Euler step of the ODE does not guarantee.
KOKKOS_FORCEINLINE_FUNCTION SymMat3 pushForward(const Mat3& F, const SymMat3& B) {
  const Mat3 FB = F * fullMat(B);
  return {detail::rowDot(FB, 0, F, 0), detail::rowDot(FB, 1, F, 1), detail::rowDot(FB, 2, F, 2),
          detail::rowDot(FB, 0, F, 1), detail::rowDot(FB, 1, F, 2), detail::rowDot(FB, 0, F, 2)};
}

// Hypo-elastic Wilkins model, docs/method.md §A7: dS/dt = 2 mu D0 + W S - S W with
// D = sym(L), D0 = dev(D), W = skew(L). The W terms make the rate objective (a
// rigid spin only rotates S). Over a step the spin part is integrated by the
// Hughes-Winget rotation Q = (I - dt/2 W)^-1 (I + dt/2 W), the Cayley
// transform of W: Q is orthogonal to round-off, so S -> Q S Q^T keeps every
// invariant of S exactly (an explicit Euler step would inflate them at first
// order in dt), and Q = I + dt W + O(dt^2) agrees with the Jaumann rate. Then
// the elastic increment 2 mu dt D0. The result is re-deviatorised because the
// rotation keeps the trace only to round-off and a trace in S would
// double-count the pressure of the EOS. (Forced inline: GCC's inlining
// budget for src/lagrange_step.cpp left the rotation out of line in the fused
// cell update, +235 instructions a cell-step of taylor.)
KOKKOS_FORCEINLINE_FUNCTION Mat3 hughesWingetRotation(const Mat3& grad_v, double dt) {
  const Mat3 half_spin = (0.5 * dt) * skewPart(grad_v);
  return inverse(identityMat() - half_spin) * (identityMat() + half_spin);
}

KOKKOS_FORCEINLINE_FUNCTION SymMat3 jaumannUpdate(const SymMat3& S, const Mat3& grad_v, double mu,
                                                  double dt) {
  // (the strain increment first: L is then held as its 3 spin entries)
  const SymMat3 strain_increment = (2.0 * mu * dt) * dev(symPart(grad_v));
  const SymMat3 rotated = pushForward(hughesWingetRotation(grad_v, dt), S);  // Q S Q^T
  return dev(rotated + strain_increment);
}

struct ReturnMapResult {
  SymMat3 S;
  bool yielded;  // the trial state lay outside the yield surface
};

// Radial return to the von Mises surface ||S|| = sqrt(S:S) = sqrt(2/3) Y0
// (perfect plasticity, docs/method.md §A7). For J2 plasticity with a constant shear
// modulus the closest-point projection is this radial scaling of the deviator;
// the plastic work then reaches e through rho de/dt = sigma : grad V. States on
// or inside the surface are returned unchanged (bit for bit).
KOKKOS_INLINE_FUNCTION ReturnMapResult radialReturn(const SymMat3& S_trial, double yield_stress) {
  const double radius = math::sqrt(2.0 / 3.0) * yield_stress;
  const double trial_norm = norm(S_trial);
  if (trial_norm > radius) return {(radius / trial_norm) * S_trial, true};
  return {S_trial, false};
}

// Strain-hardening plasticity (docs/method.md §A7). The equivalent plastic
// strain eps_p grows by the plastic multiplier of the radial return,
//   q_trial - 3 mu d_eps = Y(eps_p0 + d_eps, d_eps / dt, T*),   q = sqrt(3/2) |S|,
// and the deviator is scaled back to the surface, S = (q_trial - 3 mu d_eps) /
// q_trial S_trial: exact for linear hardening, the root of a monotone
// function (safeguarded Newton) for Johnson-Cook.

// The homologous temperature T* = (T - T_room) / (T_melt - T_room) in [0, 1]
// of a material at specific internal energy e (above its reference state):
// T = T_room + e / c_v, every joule of plastic work heating it (the energy
// equation carries it, so the Taylor-Quinney share is 1). 0 without a
// specific heat or a melting point above the room temperature.
KOKKOS_INLINE_FUNCTION double homologousTemperature(const MaterialParams& m, double e) {
  const double melt_span = m.melt_temperature - m.room_temperature;
  if (!(m.specific_heat > 0.0 && melt_span > 0.0)) return 0.0;
  const double t_star = e / (m.specific_heat * melt_span);
  return t_star < 0.0 ? 0.0 : (t_star > 1.0 ? 1.0 : t_star);
}

// The yield stress of material m and its derivative along the plastic
// increment d_eps of a stage of length dt: Y(eps_p0 + d_eps, d_eps / dt, T*).
struct YieldPoint {
  double stress, slope;  // Y and dY / d(d_eps)
};
KOKKOS_INLINE_FUNCTION YieldPoint yieldPoint(const MaterialParams& m, double eps_p0, double d_eps,
                                             double dt, double t_star) {
  const double eps = eps_p0 + d_eps;
  if (m.hardening == HardeningKind::Linear) {
    return {m.yield_stress + m.hardening_modulus * eps, m.hardening_modulus};
  }
  if (m.hardening == HardeningKind::Perfect) return {m.yield_stress, 0.0};
  // Johnson-Cook: strain, rate and thermal factors
  const double power = eps > 0.0 ? math::pow(eps, m.jc_n) : 0.0;
  const double strain_factor = m.yield_stress + m.jc_B * power;
  const double strain_slope = eps > 0.0 ? m.jc_B * m.jc_n * power / eps : 0.0;
  const double rate_ratio = d_eps / (dt * m.jc_rate0);
  const bool rate_hardens = rate_ratio > 1.0;
  const double rate_factor = rate_hardens ? 1.0 + m.jc_C * math::log(rate_ratio) : 1.0;
  const double rate_slope = rate_hardens ? m.jc_C / d_eps : 0.0;
  const double thermal_factor = t_star > 0.0 ? 1.0 - math::pow(t_star, m.jc_m) : 1.0;
  return {strain_factor * rate_factor * thermal_factor,
          (strain_slope * rate_factor + strain_factor * rate_slope) * thermal_factor};
}

struct PlasticUpdate {
  SymMat3 S;
  double eps_p;
  bool yielded;
};

// The plastic increment of a trial state of equivalent stress q_trial above
// the yield stress (the root of q_trial - 3 mu d - Y(d) on [0, q_trial / 3
// mu], which the function crosses once: it falls with d). Linear hardening in
// closed form; Johnson-Cook by Newton's method kept inside the bracket (a
// step that leaves it bisects: eps^n with n < 1 has an infinite slope at 0,
// the rate factor a kink at rate0), to a residual of 1e-12 q_trial.
KOKKOS_INLINE_FUNCTION double plasticIncrement(const MaterialParams& m, double q_trial,
                                               double eps_p0, double dt, double t_star) {
  const double three_mu = 3.0 * m.mu;
  if (m.hardening != HardeningKind::JohnsonCook) {
    const YieldPoint start = yieldPoint(m, eps_p0, 0.0, dt, t_star);
    return (q_trial - start.stress) / (three_mu + start.slope);
  }
  double lo = 0.0, hi = q_trial / three_mu;
  double d = (q_trial - yieldPoint(m, eps_p0, 0.0, dt, t_star).stress) / three_mu;  // perfect
  for (int iteration = 0; iteration < 100; ++iteration) {
    const YieldPoint y = yieldPoint(m, eps_p0, d, dt, t_star);
    const double residual = q_trial - three_mu * d - y.stress;
    if (math::fabs(residual) <= 1e-12 * q_trial || hi - lo <= 1e-15 * hi) break;
    if (residual > 0.0) {
      lo = d;
    } else {
      hi = d;
    }
    const double newton = d + residual / (three_mu + y.slope);
    d = newton > lo && newton < hi ? newton : 0.5 * (lo + hi);
  }
  return d;
}

// One stage's return of a trial deviator to the yield surface of material m
// from the step-start plastic strain eps_p0, at homologous temperature
// t_star. Perfect plasticity keeps radialReturn's arithmetic (the same bits
// as before plastic strain was tracked) and adds its increment
// (q_trial - Y0) / (3 mu).
KOKKOS_INLINE_FUNCTION PlasticUpdate plasticReturn(const SymMat3& S_trial, const MaterialParams& m,
                                                   double eps_p0, double dt, double t_star) {
  const double q_trial = math::sqrt(1.5) * norm(S_trial);
  if (m.hardening == HardeningKind::Perfect) {
    const ReturnMapResult perfect = radialReturn(S_trial, m.yield_stress);
    const double d_eps = perfect.yielded ? (q_trial - m.yield_stress) / (3.0 * m.mu) : 0.0;
    return {perfect.S, eps_p0 + d_eps, perfect.yielded};
  }
  const double yield_now = yieldPoint(m, eps_p0, 0.0, dt, t_star).stress;
  if (!(q_trial > yield_now)) return {S_trial, eps_p0, false};
  const double d_eps = plasticIncrement(m, q_trial, eps_p0, dt, t_star);
  return {((q_trial - 3.0 * m.mu * d_eps) / q_trial) * S_trial, eps_p0 + d_eps, true};
}

// Neo-Hookean deviator S = (mu/J) dev(Bbar), Bbar = det(B)^{-1/3} B (docs/method.md §A7).
// The isochoric scaling uses det(B) rather than J^2 = (rho0/rho)^2: B and the
// density are advanced by different discretisations, and normalising B by its
// own determinant keeps a pure volume change (B = c I) stress-free in shear
// whatever the drift between them. J (the density ratio) only scales.
KOKKOS_INLINE_FUNCTION SymMat3 neoHookeanDeviator(const SymMat3& B, double J, double mu) {
  return (mu / (J * math::cbrt(det(B)))) * dev(B);
}

struct PressureDeviator {
  double pressure;
  SymMat3 S;
};

// Both halves of the Neo-Hookean Cauchy stress (docs/method.md §A7), for kernels that
// store p and S separately, as for the hypo-elastic solids. The pressure is the
// same function the EosKind::NeoHookean branch of evaluateEos uses.
KOKKOS_INLINE_FUNCTION PressureDeviator neoHookeanPressureDeviator(const SymMat3& B, double J,
                                                                   double mu, double kappa) {
  return {neoHookeanPressure(J, kappa), neoHookeanDeviator(B, J, mu)};
}

// Cauchy stress sigma = -p I + S, p = -kappa/2 [(J-1) + ln(J)/J],
// S = (mu/J) dev(det(B)^{-1/3} B), J = rho0/rho (docs/method.md §A7).
KOKKOS_INLINE_FUNCTION SymMat3 neoHookeanStress(const SymMat3& B, double J, double mu,
                                                double kappa) {
  const PressureDeviator split = neoHookeanPressureDeviator(B, J, mu, kappa);
  return split.S + identitySym(-split.pressure);
}

// Elastic wave speeds of a solid with shear modulus mu: transverse aT^2 =
// mu/rho, longitudinal aL^2 = a^2 + 4/3 aT^2 with a^2 the bulk (EOS) sound
// speed. The longitudinal one is the fastest signal, so the time step and the
// nodal-solver impedance of a solid should use it rather than the bulk a.
KOKKOS_INLINE_FUNCTION double transverseSoundSpeed2(double mu, double rho) {
  return mu / rho;
}
KOKKOS_INLINE_FUNCTION double longitudinalSoundSpeed2(double bulk_sound_speed2, double mu,
                                                      double rho) {
  return bulk_sound_speed2 + (4.0 / 3.0) * transverseSoundSpeed2(mu, rho);
}

}  // namespace lagremap
