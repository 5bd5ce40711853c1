// Exact self-similar solution of the Sedov-Taylor point blast in an ideal gas
// (any gamma > 1) at rest with uniform density rho0 and zero pressure, the
// energy E0 released at the origin at t = 0, in planar, cylindrical or
// spherical geometry (docs/verification.md §8.8).
//
// Formulation: Sedov's closed-form parametric solution ("Similarity and
// Dimensional Methods in Mechanics", 1959, chapter IV) as organised by Kamm &
// Timmes, "On efficient generation of numerically robust Sedov solutions"
// (Los Alamos report LA-UR-07-2849, 2007), for a uniform ambient density
// (their omega = 0). With j = 1, 2, 3 the geometry, the shock radius is
//   R(t) = (E0 / (alpha rho0))^(1/(j+2)) t^(2/(j+2)),
// its speed D = 2 R / ((j + 2) t), and the state behind it the strong-shock
// jump (rho2, u2, p2) = (rho0 (g+1)/(g-1), 2 D/(g+1), 2 rho0 D^2/(g+1)).
// Inside, rho = rho2 g(lambda), u = u2 f(lambda), p = p2 h(lambda) at
// lambda = r / R, each of lambda, f, g, h a product of powers of four linear
// functions of one parameter V (Kamm & Timmes' x1..x4). alpha(gamma, j) is
// the energy integral of that profile,
//   alpha = A_j 8 / ((j+2)^2 (g^2 - 1)) int_0^1 (g f^2 + h) lambda^(j-1) dlambda,
// with A_j = 1, 2 pi, 4 pi (energy per unit area of the half space x > 0,
// per unit length of the line, of the whole sphere: Kamm & Timmes'
// convention); it is computed here by quadrature, never tabulated.
//
// The singular parameter values of Kamm & Timmes are handled as follows.
// - gamma = 2 (their omega3 = j (2 - gamma) = omega): two exponents of the
//   general form diverge while their factors meet. Written as
//   exp(alpha4 log(x3/x4) + (alpha4 + alpha5) log x4), with log(x3/x4) and
//   alpha4 + alpha5 rearranged so that the factor (2 - gamma) cancels by
//   hand, the general form is accurate for every gamma, and at gamma = 2 it
//   is their special form (the exponential factor) without a switch.
// - spherical gamma = 7 (v2 = v*): the profile is Kamm & Timmes' closed form
//   f = lambda, g = lambda^(j-2), h = lambda^j; within 1e-5 of it in
//   1 - v2 / v* (|gamma - 7| < 4e-4) the general forms lose their digits and
//   that closed form is used (there 1e-4 from the solution beyond r = 0.3 R,
//   up to 2% inside r = 0.02 R).
// - spherical gamma > 7 (v2 > v*): the "vacuum" family, a hole of vacuum
//   inside vacuum_radius.
// Near the centre the parameter V tends to its limit v0 faster than any
// double resolves (V - v0 ~ lambda^9.5 for gamma = 1.4, spherical), so the
// standard family is parametrised by tau = x2^beta (lambda ~ tau), never by
// V: rho and u keep their full relative precision down to r -> 0.
//
// Plain host code, used to generate reference solutions for verification problems.
#pragma once

namespace lagremap {

enum class SedovGeometry { planar = 1, cylindrical = 2, spherical = 3 };

// Which family of Kamm & Timmes' solutions the parameters select.
enum class SedovFamily {
  standard,  // v2 < v*: every planar and cylindrical gamma, spherical gamma < 7
  singular,  // v2 = v*: spherical gamma = 7
  vacuum,    // v2 > v*: spherical gamma > 7, vacuum inside vacuum_radius
};

// Radial state of the gas: density, radial velocity, pressure.
struct SedovState {
  double rho;
  double u;
  double p;
};

// The dimensionless profile at lambda = r / R: u / u2, rho / rho2, p / p2.
struct SedovProfile {
  double f;
  double g;
  double h;
};

// The similarity solution of one gamma and geometry (independent of E0,
// rho0 and t): the constants of Kamm & Timmes' parametric form.
struct SedovSimilarity {
  double gamma;
  int j;  // 1 planar, 2 cylindrical, 3 spherical
  SedovFamily family;
  // x1 = a V, x2 = b (c V - 1), x3 = (1 - e V) / (1 - e v2), x4 = b (1 - (j+2) V / 2)
  double a, b, c, e;
  double alpha0, alpha1, alpha2, alpha3;  // exponents (Kamm & Timmes' alpha_0..alpha_3)
  double alpha45;                         // alpha4 + alpha5, with (2 - gamma) cancelled
  double v0, v2, vv;                      // V at the centre, behind the shock, at a vacuum edge
  double beta;                            // -alpha2: lambda ~ x2^beta at the centre
  double lambda_vacuum = 0.0;             // vacuum family: lambda at the vacuum's edge

  // lambda, dlambda/dq and the profile at the family's parameter q in [0, 1]
  // (q = 1 at the shock; standard: q = x2^beta, vacuum: q = x4, singular: q = lambda).
  struct Point {
    double lambda, dlambda_dq;
    SedovProfile profile;
  };
  Point at(double q) const;
  // The profile at lambda in [0, 1] (vacuum family: zero inside lambda_vacuum).
  SedovProfile profile(double lambda) const;
  // int_0^1 (g f^2 + h) lambda^(j-1) dlambda, by tanh-sinh quadrature in q.
  double energyIntegral() const;
};

// Throws std::invalid_argument for gamma <= 1 or a non-finite gamma.
SedovSimilarity sedovSimilarity(double gamma, SedovGeometry geometry);

// The energy constant alpha(gamma, j) of E0 = alpha rho0 R^(j+2) / t^2
// (0.851060 for gamma = 1.4 in spherical geometry: Kamm & Timmes, Table 4).
double sedovEnergyConstant(double gamma, SedovGeometry geometry);

struct SedovSolution {
  double energy, rho0, gamma, time;
  SedovGeometry geometry;
  SedovSimilarity similarity;
  double alpha;           // energy constant
  double shock_radius;    // R(t)
  double shock_speed;     // dR/dt
  SedovState post_shock;  // the strong-shock jump state just behind the shock
  double vacuum_radius;   // vacuum family: the edge of the central vacuum; else 0

  // The state at distance r >= 0 from the origin (the ambient gas at rest,
  // at zero pressure, beyond the shock; at r == R the post-shock state).
  SedovState sample(double r) const;
};

// Throws std::invalid_argument for a non-positive or non-finite energy,
// density or time, or gamma <= 1.
SedovSolution solveSedov(double energy, double rho0, double gamma, double time,
                         SedovGeometry geometry = SedovGeometry::spherical);

}  // namespace lagremap
