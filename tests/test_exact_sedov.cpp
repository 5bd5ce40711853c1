// Tests for lagremap::solveSedov, the exact Sedov-Taylor blast wave (src/exact_sedov.hpp).
//
// Kinds of checks, so that a wrong formula cannot hide behind a matching one:
//  - published values: Kamm & Timmes, "On efficient generation of numerically robust Sedov
//    solutions" (LA-UR-07-2849, 2007), Tables 1-3 (the profile at 4 decimals) and Table 4
//    (the energy integrals), and the usual E0 = 0.851072 that puts the spherical gamma = 1.4
//    shock at R = 1 at t = 1 (their Table 5);
//  - physics the solution must obey, computed here from sample() alone: the Euler equations
//    (finite differences in r and t), the strong-shock jump at R, the swept mass and the total
//    energy E0 of the profile (quadrature in r, independent of the solver's own in its
//    parameter), the behaviour at the centre;
//  - the singular parameters: gamma = 2 continuous through its special form, spherical
//    gamma = 7 and the vacuum beyond it.
#include "src/exact_sedov.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

using lagremap::sedovEnergyConstant;
using lagremap::SedovFamily;
using lagremap::SedovGeometry;
using lagremap::sedovSimilarity;
using lagremap::SedovSolution;
using lagremap::SedovState;
using lagremap::solveSedov;

constexpr double kPi = 3.14159265358979323846;
const SedovGeometry kGeometries[] = {SedovGeometry::planar, SedovGeometry::cylindrical,
                                     SedovGeometry::spherical};
// Every family and the special gamma = 2: below, at and above it, spherical 7 (singular) and 8
// (vacuum: planar and cylindrical stay standard).
const double kGammas[] = {1.1, 1.4, 5.0 / 3.0, 2.0, 3.0, 7.0, 8.0};

// Integral of fn over [lo, hi]: composite 5-point Gauss-Legendre on n equal panels.
double gaussLegendre(const std::function<double(double)>& fn, double lo, double hi, int n) {
  const double x[5] = {-0.9061798459386640, -0.5384693101056831, 0.0, 0.5384693101056831,
                       0.9061798459386640};
  const double w[5] = {0.2369268850561891, 0.4786286704993665, 0.5688888888888889,
                       0.4786286704993665, 0.2369268850561891};
  double sum = 0.0;
  const double width = (hi - lo) / n;
  for (int panel = 0; panel < n; ++panel) {
    const double mid = lo + (panel + 0.5) * width;
    for (int k = 0; k < 5; ++k) sum += 0.5 * width * w[k] * fn(mid + 0.5 * width * x[k]);
  }
  return sum;
}

// Measure of the shell at r: dV = area_j r^(j-1) dr (Kamm & Timmes: dr for the planar case).
double shellArea(SedovGeometry geometry, double r) {
  switch (geometry) {
    case SedovGeometry::planar:
      return 1.0;
    case SedovGeometry::cylindrical:
      return 2.0 * kPi * r;
    default:
      return 4.0 * kPi * r * r;
  }
}

std::string caseName(double gamma, SedovGeometry geometry) {
  return "gamma " + std::to_string(gamma) + " j " + std::to_string(int(geometry));
}

// Kamm & Timmes, Table 4 (gamma = 1.4): their energy integrals J1 = int b g V^2 lambda^(j+1)
// and J2 = z int h lambda^(j-1), z = 8 / ((j+2)^2 (gamma+1)). Ours from the profile by
// quadrature in lambda. J1 agrees to all their 6 digits; our J2 lies above theirs by 4.4e-4
// (planar), 4.1e-5 (cylindrical), 1.8e-5 (spherical) relative, with our alpha accordingly
// (0.538743, 0.984074, 0.851072 against their 0.538548, 0.984041, 0.851060). J2's integrand
// in their variable V, dlambda/dV, is singular at the centre (V -> v0), and the difference is
// largest where the centre weighs the most (planar): we take it to be their quadrature's. Our
// J2 is the same to 1e-12 in two quadratures in two variables (here in lambda, the solver's in
// x2^beta), the profile they integrate matches Tables 1-3, the Euler equations and the swept
// mass, and 0.851072 is the spherical alpha the literature's R = 1 at t = 1 uses.
TEST(ExactSedov, EnergyIntegralsOfKammTimmesTable4) {
  struct Row {
    SedovGeometry geometry;
    double j1, j2, alpha;  // Kamm & Timmes
    double j2_relative_tolerance;
  };
  const Row rows[] = {{SedovGeometry::planar, 0.197928, 0.175834, 0.538548, 5e-4},
                      {SedovGeometry::cylindrical, 6.54053e-2, 4.95650e-2, 0.984041, 5e-5},
                      {SedovGeometry::spherical, 2.96269e-2, 2.11647e-2, 0.851060, 3e-5}};
  const double gamma = 1.4;
  for (const Row& row : rows) {
    const lagremap::SedovSimilarity s = sedovSimilarity(gamma, row.geometry);
    const int j = s.j;
    auto kinetic = [&](double lambda) {
      const auto p = s.profile(lambda);
      return p.g * p.f * p.f * std::pow(lambda, j - 1.0);
    };
    auto thermal = [&](double lambda) { return s.profile(lambda).h * std::pow(lambda, j - 1.0); };
    const double gf2 = gaussLegendre(kinetic, 0.0, 1.0, 400);
    const double h = gaussLegendre(thermal, 0.0, 1.0, 400);
    const double xg2 = j + 2.0;
    const double j1 = s.b / (s.a * s.a) * gf2;  // g f^2 = g a^2 V^2 lambda^2
    const double j2 = 8.0 / (xg2 * xg2 * (gamma + 1.0)) * h;
    EXPECT_NEAR(j1, row.j1, 1e-6 * row.j1) << j;
    EXPECT_NEAR(j2, row.j2, row.j2_relative_tolerance * row.j2) << j;
    EXPECT_GT(j2, row.j2) << j;
    // alpha from the same integrals (the area factor of exact_sedov.hpp): the solver's quadrature
    const double area = j == 1 ? 1.0 : (j == 2 ? 2.0 * kPi : 4.0 * kPi);
    const double alpha = area * 8.0 / (xg2 * xg2 * (gamma * gamma - 1.0)) * (gf2 + h);
    EXPECT_NEAR(sedovEnergyConstant(gamma, row.geometry), alpha, 1e-12 * alpha) << j;
    EXPECT_NEAR(alpha, row.alpha, 4e-4 * row.alpha) << j;
  }
  // The standard spherical case: E0 = 0.851072 puts the shock at R = 1 at t = 1 (Kamm & Timmes,
  // Table 5); in the form R = xi0 (E0 t^2 / rho0)^(1/5), xi0 = alpha^(-1/5) = 1.0328.
  const double alpha = sedovEnergyConstant(gamma, SedovGeometry::spherical);
  EXPECT_NEAR(alpha, 0.851072, 1e-6);
  EXPECT_NEAR(std::pow(alpha, -0.2), 1.0328, 1e-4);
  EXPECT_NEAR(solveSedov(0.851072, 1.0, gamma, 1.0).shock_radius, 1.0, 1e-7);
}

// Kamm & Timmes, Tables 1-3: lambda, f, g, h at gamma = 1.4 (rows of their parameter V), to
// their 4 decimals. Their lambda is rounded too: at our lambda the profile moves by its slope
// times 5e-5, up to 1.5e-4 in g next to the spherical shock; 2e-4 covers both roundings.
TEST(ExactSedov, ProfilesOfKammTimmesTables1To3) {
  struct Row {
    double lambda, f, g, h;
  };
  const std::vector<Row> planar = {
      {0.9797, 0.9699, 0.8620, 0.9159}, {0.9420, 0.9157, 0.6662, 0.7917},
      {0.8565, 0.8017, 0.3981, 0.6119}, {0.7419, 0.6677, 0.2201, 0.4905},
      {0.5925, 0.5173, 0.1075, 0.4230}, {0.4161, 0.3580, 0.0415, 0.3964},
      {0.2320, 0.1989, 0.0095, 0.3905}, {0.1040, 0.0891, 0.0013, 0.3900}};
  const std::vector<Row> cylindrical = {
      {0.9998, 0.9996, 0.9972, 0.9984}, {0.9644, 0.9374, 0.6281, 0.7829},
      {0.9096, 0.8514, 0.3450, 0.5982}, {0.8094, 0.7226, 0.1415, 0.4545},
      {0.6894, 0.5990, 0.0545, 0.3969}, {0.5180, 0.4448, 0.0123, 0.3760},
      {0.3000, 0.2572, 0.0008, 0.3730}, {0.1000, 0.0857, 0.0000, 0.3729}};
  const std::vector<Row> spherical = {
      {0.9913, 0.9814, 0.8388, 0.9116}, {0.9622, 0.9238, 0.4984, 0.7082},
      {0.9080, 0.8335, 0.2275, 0.5238}, {0.8359, 0.7398, 0.0968, 0.4273},
      {0.7493, 0.6497, 0.0379, 0.3857}, {0.5794, 0.4971, 0.0052, 0.3672},
      {0.3600, 0.3086, 0.0001, 0.3655}, {0.1040, 0.0891, 0.0000, 0.3655}};
  const std::vector<Row>* tables[] = {&planar, &cylindrical, &spherical};
  for (int t = 0; t < 3; ++t) {
    const lagremap::SedovSimilarity s = sedovSimilarity(1.4, kGeometries[t]);
    for (const Row& row : *tables[t]) {
      const auto p = s.profile(row.lambda);
      EXPECT_NEAR(p.f, row.f, 2e-4) << "j " << t + 1 << " lambda " << row.lambda;
      EXPECT_NEAR(p.g, row.g, 2e-4) << "j " << t + 1 << " lambda " << row.lambda;
      EXPECT_NEAR(p.h, row.h, 2e-4) << "j " << t + 1 << " lambda " << row.lambda;
    }
  }
}

// Behind the shock the strong-shock (cold gas) Rankine-Hugoniot state: rho2 = rho0 (g+1)/(g-1),
// u2 = 2 D / (g+1), p2 = 2 rho0 D^2 / (g+1), D = dR/dt = 2 R / ((j+2) t); ahead, the gas at rest.
TEST(ExactSedov, ShockFrontIsTheStrongShockJump) {
  const double energy = 2.5, rho0 = 0.7, t = 0.3;
  for (SedovGeometry geometry : kGeometries) {
    for (double gamma : kGammas) {
      const SedovSolution s = solveSedov(energy, rho0, gamma, t, geometry);
      const double xg2 = int(geometry) + 2.0;
      const double radius = std::pow(energy / (s.alpha * rho0), 1.0 / xg2) * std::pow(t, 2 / xg2);
      ASSERT_NEAR(s.shock_radius, radius, 1e-14 * radius) << caseName(gamma, geometry);
      const double speed = 2.0 * radius / (xg2 * t);
      // D from R(t) by a central difference
      const double dt = 1e-5 * t;
      const double speed_fd = (solveSedov(energy, rho0, gamma, t + dt, geometry).shock_radius -
                               solveSedov(energy, rho0, gamma, t - dt, geometry).shock_radius) /
                              (2.0 * dt);
      EXPECT_NEAR(s.shock_speed, speed_fd, 1e-8 * speed) << caseName(gamma, geometry);
      const SedovState behind = s.sample(s.shock_radius);
      EXPECT_NEAR(behind.rho, rho0 * (gamma + 1) / (gamma - 1), 1e-12 * behind.rho)
          << caseName(gamma, geometry);
      EXPECT_NEAR(behind.u, 2.0 * speed / (gamma + 1), 1e-12 * behind.u)
          << caseName(gamma, geometry);
      EXPECT_NEAR(behind.p, 2.0 * rho0 * speed * speed / (gamma + 1), 1e-12 * behind.p)
          << caseName(gamma, geometry);
      // mass and momentum fluxes through the moving shock
      EXPECT_NEAR(rho0 * speed, behind.rho * (speed - behind.u), 1e-12 * rho0 * speed);
      EXPECT_NEAR(behind.p, rho0 * speed * behind.u, 1e-12 * behind.p);
      const SedovState ahead = s.sample(s.shock_radius * (1.0 + 1e-12));
      EXPECT_EQ(ahead.rho, rho0);
      EXPECT_EQ(ahead.u, 0.0);
      EXPECT_EQ(ahead.p, 0.0);
    }
  }
}

// The profile itself holds the blast's energy and the gas the shock swept, integrated in r
// from sample() (not the solver's quadrature in its parameter): E0 = int (rho u^2/2 + p/(g-1))
// dV and int rho dV = rho0 V(R). The quadrature is good to 1e-9 here.
TEST(ExactSedov, ProfileHoldsTheEnergyAndTheSweptMass) {
  const double energy = 2.5, rho0 = 0.7, t = 0.3;
  for (SedovGeometry geometry : kGeometries) {
    for (double gamma : kGammas) {
      const SedovSolution s = solveSedov(energy, rho0, gamma, t, geometry);
      auto energy_density = [&](double r) {
        const SedovState q = s.sample(r);
        return (0.5 * q.rho * q.u * q.u + q.p / (gamma - 1.0)) * shellArea(geometry, r);
      };
      auto density = [&](double r) { return s.sample(r).rho * shellArea(geometry, r); };
      const double radius = s.shock_radius;
      const double total = gaussLegendre(energy_density, 0.0, radius, 800);
      EXPECT_NEAR(total, energy, 1e-6 * energy) << caseName(gamma, geometry);
      const int j = int(geometry);
      const double swept = rho0 * shellArea(geometry, radius) * radius / j;
      EXPECT_NEAR(gaussLegendre(density, 0.0, radius, 800), swept, 1e-6 * swept)
          << caseName(gamma, geometry);
    }
  }
}

// The solution satisfies the Euler equations of radial flow between the centre and the shock,
// in the form  D ln(rho)/Dt + du/dr + (j-1) u/r = 0,  Du/Dt + (dp/dr)/rho = 0,
// D ln(p rho^-gamma)/Dt = 0  (D/Dt = d/dt + u d/dr), each made dimensionless by t (and the
// momentum equation by the shock speed). Central differences of step 1e-5 r, 1e-5 t: their error
// is about 1e-9 here; a wrong exponent of the profile gives residuals of order 1.
TEST(ExactSedov, SatisfiesTheEulerEquations) {
  const double energy = 1.3, rho0 = 1.1, t = 0.8;
  for (SedovGeometry geometry : kGeometries) {
    for (double gamma : kGammas) {
      const double dt = 1e-5 * t;
      const SedovSolution now = solveSedov(energy, rho0, gamma, t, geometry);
      const SedovSolution before = solveSedov(energy, rho0, gamma, t - dt, geometry);
      const SedovSolution after = solveSedov(energy, rho0, gamma, t + dt, geometry);
      const int j = int(geometry);
      for (double lambda : {0.15, 0.4, 0.7, 0.9, 0.98}) {
        const double r = lambda * now.shock_radius;
        if (r <= 1.01 * now.vacuum_radius) continue;
        const double dr = 1e-5 * r;
        const SedovState q = now.sample(r);
        const SedovState left = now.sample(r - dr), right = now.sample(r + dr);
        const SedovState early = before.sample(r), late = after.sample(r);
        auto entropy = [&](const SedovState& x) { return std::log(x.p) - gamma * std::log(x.rho); };
        const double dlnrho_dt = (std::log(late.rho) - std::log(early.rho)) / (2 * dt);
        const double dlnrho_dr = (std::log(right.rho) - std::log(left.rho)) / (2 * dr);
        const double du_dt = (late.u - early.u) / (2 * dt), du_dr = (right.u - left.u) / (2 * dr);
        const double dp_dr = (right.p - left.p) / (2 * dr);
        const double ds_dt = (entropy(late) - entropy(early)) / (2 * dt);
        const double ds_dr = (entropy(right) - entropy(left)) / (2 * dr);
        const double mass = t * (dlnrho_dt + q.u * dlnrho_dr + du_dr + (j - 1) * q.u / r);
        const double momentum = t / now.shock_speed * (du_dt + q.u * du_dr + dp_dr / q.rho);
        const double energy_residual = t * (ds_dt + q.u * ds_dr);
        const std::string where = caseName(gamma, geometry) + " lambda " + std::to_string(lambda);
        // Where the gas is nearly empty (rho / rho2 ~ 1e-12 at lambda = 0.4 for gamma = 1.1,
        // spherical) dp/dr / rho is a difference of nearly equal pressures over a tiny density:
        // its rounding, 1e-15 p / (dr rho) (a few ulps of the profile), is allowed for.
        const double rounding = 1e-15 * q.p / (dr * q.rho) * t / now.shock_speed;
        EXPECT_LT(std::abs(mass), 1e-6) << where;
        EXPECT_LT(std::abs(momentum), 1e-6 + rounding) << where;
        EXPECT_LT(std::abs(energy_residual), 1e-6) << where;
      }
    }
  }
}

// Towards the centre the gas is hot and rarefied: rho ~ r^(j/(gamma-1)) -> 0, p -> a finite
// constant (0.3655 p2 spherical at gamma = 1.4: Kamm & Timmes, Table 3), u -> 2 r / ((j+2) gamma t)
// (V -> v0), each to full relative precision however small r (the parametrisation by x2^beta).
TEST(ExactSedov, CentreIsRarefiedAtFinitePressure) {
  const double energy = 0.851072, rho0 = 1.0, t = 1.0;
  for (SedovGeometry geometry : kGeometries) {
    for (double gamma : {1.1, 1.4, 5.0 / 3.0, 2.0, 3.0}) {
      const SedovSolution s = solveSedov(energy, rho0, gamma, t, geometry);
      const int j = int(geometry);
      for (double r : {1e-3, 1e-6, 1e-12}) {
        if (std::pow(r, j / (gamma - 1.0)) < 1e-250) continue;  // rho below the doubles
        const SedovState q = s.sample(r), half = s.sample(0.5 * r);
        const std::string where = caseName(gamma, geometry) + " r " + std::to_string(r);
        EXPECT_NEAR(q.rho / half.rho, std::pow(2.0, j / (gamma - 1.0)),
                    1e-3 * std::pow(2.0, j / (gamma - 1.0)))
            << where;
        EXPECT_NEAR(q.u * t / r, 2.0 / ((j + 2.0) * gamma), 1e-3) << where;
        EXPECT_NEAR(q.p, s.sample(0.0).p, 1e-6 * q.p) << where;
      }
      const SedovState centre = s.sample(0.0);
      EXPECT_EQ(centre.rho, 0.0);
      EXPECT_EQ(centre.u, 0.0);
      EXPECT_GT(centre.p, 0.1 * s.post_shock.p);
    }
  }
  const SedovSolution standard = solveSedov(energy, rho0, 1.4, t);
  EXPECT_NEAR(standard.sample(1e-4).p / standard.post_shock.p, 0.3655, 1e-4);
}

// gamma = 2 (Kamm & Timmes' omega3 singularity): one formula for every gamma, so the profile and
// alpha are continuous through it, to within the distance times their slope (about 1).
TEST(ExactSedov, ContinuousThroughGammaTwo) {
  for (SedovGeometry geometry : kGeometries) {
    const lagremap::SedovSimilarity at_two = sedovSimilarity(2.0, geometry);
    for (double delta : {-1e-9, 1e-9, -1e-6, 1e-6}) {
      const lagremap::SedovSimilarity near = sedovSimilarity(2.0 + delta, geometry);
      for (double lambda : {0.1, 0.5, 0.9, 0.999}) {
        const auto a = at_two.profile(lambda), b = near.profile(lambda);
        EXPECT_NEAR(a.f, b.f, 2 * std::abs(delta) + 1e-13) << int(geometry) << " " << delta;
        EXPECT_NEAR(a.g, b.g, 2 * std::abs(delta) + 1e-13) << int(geometry) << " " << delta;
        EXPECT_NEAR(a.h, b.h, 2 * std::abs(delta) + 1e-13) << int(geometry) << " " << delta;
      }
      EXPECT_NEAR(sedovEnergyConstant(2.0, geometry), sedovEnergyConstant(2.0 + delta, geometry),
                  2 * std::abs(delta) + 1e-13);
    }
  }
}

// Spherical gamma = 7 (v2 = v*): Kamm & Timmes' singular closed form, alpha = b 2^j pi /
// (j ((gamma-1) j + 2)^2) = 32 pi / 3600 (their eq. for the singular case); just below, the
// standard family, just above, a central vacuum that opens from r = 0.
TEST(ExactSedov, SingularAndVacuumFamilies) {
  const lagremap::SedovSimilarity singular = sedovSimilarity(7.0, SedovGeometry::spherical);
  EXPECT_EQ(singular.family, SedovFamily::singular);
  EXPECT_NEAR(sedovEnergyConstant(7.0, SedovGeometry::spherical), 32.0 * kPi / 3600.0, 1e-14);
  const auto p = singular.profile(0.6);
  EXPECT_DOUBLE_EQ(p.f, 0.6);
  EXPECT_DOUBLE_EQ(p.g, 0.6);
  EXPECT_DOUBLE_EQ(p.h, 0.6 * 0.6 * 0.6);
  EXPECT_EQ(sedovSimilarity(6.99, SedovGeometry::spherical).family, SedovFamily::standard);
  EXPECT_EQ(sedovSimilarity(7.0 + 1e-3, SedovGeometry::spherical).family, SedovFamily::vacuum);
  EXPECT_EQ(sedovSimilarity(8.0, SedovGeometry::cylindrical).family, SedovFamily::standard);
  // the closed form is the limit of its neighbours (away from the centre, where they tend to
  // it slowly: 1.5e-4 at r = 0.3 R for |gamma - 7| = 1e-3)
  for (double delta : {-1e-3, 1e-3}) {
    const lagremap::SedovSimilarity near = sedovSimilarity(7.0 + delta, SedovGeometry::spherical);
    for (double lambda : {0.3, 0.6, 0.95}) {
      EXPECT_NEAR(near.profile(lambda).f, lambda, 3e-4) << delta;
      EXPECT_NEAR(near.profile(lambda).g, lambda, 3e-4) << delta;
      EXPECT_NEAR(near.profile(lambda).h, lambda * lambda * lambda, 3e-5) << delta;
    }
  }
  const SedovSolution vacuum = solveSedov(1.0, 1.0, 8.0, 1.0);
  EXPECT_EQ(vacuum.similarity.family, SedovFamily::vacuum);
  EXPECT_GT(vacuum.vacuum_radius, 0.1 * vacuum.shock_radius);
  EXPECT_LT(vacuum.vacuum_radius, vacuum.shock_radius);
  const SedovState hole = vacuum.sample(0.99 * vacuum.vacuum_radius);
  EXPECT_EQ(hole.rho, 0.0);
  EXPECT_EQ(hole.p, 0.0);
  const SedovState edge = vacuum.sample(1.001 * vacuum.vacuum_radius);
  EXPECT_LT(edge.rho, 0.1 * vacuum.post_shock.rho);
  EXPECT_GT(edge.u, 0.0);
}

TEST(ExactSedov, RejectsImpossibleParameters) {
  EXPECT_THROW(solveSedov(0.0, 1.0, 1.4, 1.0), std::invalid_argument);
  EXPECT_THROW(solveSedov(1.0, -1.0, 1.4, 1.0), std::invalid_argument);
  EXPECT_THROW(solveSedov(1.0, 1.0, 1.0, 1.0), std::invalid_argument);
  EXPECT_THROW(solveSedov(1.0, 1.0, 1.4, 0.0), std::invalid_argument);
  EXPECT_THROW(solveSedov(1.0, 1.0, NAN, 1.0), std::invalid_argument);
}

}  // namespace
