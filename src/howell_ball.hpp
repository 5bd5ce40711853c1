// Where a collapsing cylindrical shell stops (the `shell` problem, docs/verification.md
// §8.6; Howell and Ball): an incompressible rigid-plastic shell in plane strain,
// von Mises yield stress Y, inner radius a and outer radius b with
// b^2 - a^2 = B fixed. Its radial velocity is C / r (C = a da/dt), its
// kinetic energy per unit length pi rho C^2 ln(b / a), and its plastic work
// from the initial inner radius Ri down to a
//   W(a) = (pi / sqrt 3) Y [F(Ri^2) - F(a^2)],  F(x) = (x + B) ln(x + B) - x ln x
// (dissipation density Y (2 / sqrt 3) |C| / r^2). It stops where W equals
// the initial kinetic energy K0: pi rho (Ri V0)^2 ln(Ro / Ri) for the
// incompressible profile V0 Ri / r, pi rho V0^2 (Ro^4 - Ri^4) / (4 Ri^2) for
// the paper's text's V0 r / Ri (which this balance takes to turn
// incompressible at once). The time to stop follows from the same balance,
// (a da/dt)^2 = (K0 - W(a)) / (pi rho ln(b / a)).
//
// Plain host code, an independent reference for the problem's checks.
#pragma once

namespace lagremap {

struct ShellStop {
  double inner_radius = 0.0, outer_radius = 0.0;  // when the shell stops (0: it closes)
  double time = 0.0;                              // from the start
};

// Throws std::invalid_argument unless rho, Y, V0 > 0 and 0 < Ri < Ro.
ShellStop howellBallStop(double rho, double yield_stress, double ri, double ro, double v0,
                         bool incompressible_profile);

// The plastic work W(a) of the collapse from Ri to a (per unit length).
double howellBallWork(double yield_stress, double ri, double ro, double a);

// The speed at which a real (elastic-plastic) shell rings after the
// rigid-plastic stop: it stops with its hoop stress at yield and unloads
// elastically, and an elastic wave that changes the stress by Y carries the
// particle velocity Y / (rho c_L), c_L = sqrt(a0^2 + 4 mu / (3 rho)) the
// longitudinal sound speed. The stopped shell's inner surface moves with
// velocities of this order, not of V0 (beryllium: 10.8 m/s, whatever V0).
double elasticRingingSpeed(double rho, double yield_stress, double longitudinal_sound_speed);

}  // namespace lagremap
