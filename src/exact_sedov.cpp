// Exact Sedov-Taylor blast wave; see exact_sedov.hpp. Equation numbers refer
// to Kamm & Timmes (2007) with their omega = 0 (uniform ambient density).
#include "exact_sedov.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>

namespace lagremap {
namespace {

constexpr double kPi = 3.14159265358979323846;
// Within this distance of 0 in epsilon = 1 - e v2 (spherical gamma = 7 +- 4e-4)
// the standard and vacuum forms resolve the layer next to the shock that holds
// the profile (its width in the parameter is of order epsilon) with too few
// digits for the quadrature, and the singular closed form, which the solution
// tends to, is used instead. Its error at the band's edges: 6e-6 in p / p2,
// 1e-4 in u / u2 and rho / rho2 beyond r = 0.3 R, but up to 2% inside
// r = 0.02 R, where the solution tends to it slowly (a vacuum of radius
// 0.009 R opens just above gamma = 7).
constexpr double kSingularTolerance = 1e-5;
// The quadrature of the energy integral stops once two levels agree to this.
constexpr double kQuadratureTolerance = 1e-13;
// Newton on the profile's parameter stops at this relative step.
constexpr double kParameterTolerance = 1e-15;
constexpr int kMaxNewtonIterations = 200;

// log1p(d K) / d, and its limit K at d = 0: the log of x3 / x4 over (2 - gamma).
double logRatioOverDelta(double delta, double k) {
  return delta == 0.0 ? k : std::log1p(delta * k) / delta;
}

}  // namespace

SedovSimilarity sedovSimilarity(double gamma, SedovGeometry geometry) {
  if (!(gamma > 1.0) || !std::isfinite(gamma)) {
    std::ostringstream message;
    message << "sedovSimilarity: needs gamma > 1 (gamma=" << gamma << ")";
    throw std::invalid_argument(message.str());
  }
  SedovSimilarity s{};
  s.gamma = gamma;
  s.j = int(geometry);
  const double j = s.j, g = gamma, xg2 = j + 2.0;
  // (33)-(37), and the characteristic values of V
  s.a = xg2 * (g + 1.0) / 4.0;
  s.b = (g + 1.0) / (g - 1.0);
  s.c = xg2 * g / 2.0;
  s.e = (2.0 + j * (g - 1.0)) / 2.0;
  s.v0 = 2.0 / (xg2 * g);
  s.v2 = 4.0 / (xg2 * (g + 1.0));
  s.vv = 2.0 / xg2;
  // (42)-(47)
  const double denom2 = 2.0 * (g - 1.0) + j;
  s.alpha0 = 2.0 / xg2;
  s.alpha2 = -(g - 1.0) / denom2;
  s.beta = -s.alpha2;
  s.alpha1 = xg2 * g / (2.0 + j * (g - 1.0)) * (2.0 * j * (2.0 - g) / (g * xg2 * xg2) + s.beta);
  s.alpha3 = j / denom2;
  // alpha4 + alpha5 = (xg2 alpha1 - 2) / (2 - gamma): the numerator is
  // (2 - gamma) [2 j Q - (j^2 + 4) gamma + (j - 2)^2] / (P Q), P = 2 + j (gamma - 1),
  // Q = denom2, which leaves this after the division.
  s.alpha45 = (j - 2.0) * ((3.0 * j - 2.0) - (j - 2.0) * g) / ((2.0 + j * (g - 1.0)) * denom2);
  // 1 - e v2 = (3j - 2 + gamma (2 - j)) / ((j + 2)(gamma + 1)): its sign
  // tells the family (v2 against v* = 1 / e).
  const double one_minus_ev2 = (3.0 * j - 2.0 + g * (2.0 - j)) / (xg2 * (g + 1.0));
  if (std::abs(one_minus_ev2) < kSingularTolerance) {
    s.family = SedovFamily::singular;
  } else if (one_minus_ev2 > 0.0) {
    s.family = SedovFamily::standard;
  } else {
    s.family = SedovFamily::vacuum;
    s.lambda_vacuum = s.at(0.0).lambda;
  }
  return s;
}

SedovSimilarity::Point SedovSimilarity::at(double q) const {
  Point point{};
  if (family == SedovFamily::singular) {  // Kamm & Timmes (88)-(92)
    point.lambda = q;
    point.dlambda_dq = 1.0;
    point.profile = {q, std::pow(q, j - 2.0), std::pow(q, double(j))};
    return point;
  }
  const double xg2 = j + 2.0;
  const double epsilon = 1.0 - e * v2;  // > 0 standard, < 0 vacuum
  // The x's through w = v2 - V, each 1 at the shock plus a multiple of w:
  //   x1 = 1 - a w, x3 = 1 + e w / epsilon, x4 = 1 + b (j+2) w / 2,
  // with no cancellation where epsilon is small (near spherical gamma = 7).
  // Standard: q = tau = x2^beta, x2 = tau^(1/beta), w = (1 - x2) / (b c);
  // lambda = tau x1^-alpha0 x3^-alpha1 (tau factored out, never a log of it).
  // Vacuum: q = x4, w = -2 (1 - x4) / ((j+2) b) <= 0, x2 = 1 - b c w.
  const bool standard = family == SedovFamily::standard;
  double w, x2_power_alpha3, log_x2_term;
  if (standard) {
    const double x2 = std::pow(q, 1.0 / beta);
    w = q > 0.5 ? -std::expm1(std::log(q) / beta) / (b * c) : (1.0 - x2) / (b * c);
    x2_power_alpha3 = std::pow(q, alpha3 / beta);
    log_x2_term = 0.0;
  } else {
    w = -2.0 * (1.0 - q) / (xg2 * b);
    const double x2 = 1.0 - b * c * w;
    x2_power_alpha3 = std::pow(x2, alpha3);
    log_x2_term = beta * std::log(x2);
  }
  const double v = v2 - w;
  const double x1 = 1.0 - a * w;
  const double x3 = 1.0 + e * w / epsilon;
  const double x4 = standard ? 1.0 + b * xg2 * w / 2.0 : q;
  const double log_x1 = std::log(x1), log_x3 = std::log(x3), log_x4 = std::log(x4);
  // (38): lambda, and d log(lambda) / dV less the x2 term
  const double lambda_over_tau = std::exp(-alpha0 * log_x1 - alpha1 * log_x3 + log_x2_term);
  const double dlog_lambda_dv_rest = -alpha0 / v + alpha1 * e / (epsilon * x3);
  if (standard) {
    const double x2 = std::pow(q, 1.0 / beta);
    point.lambda = q * lambda_over_tau;
    point.dlambda_dq = lambda_over_tau * (1.0 + dlog_lambda_dv_rest * x2 / (beta * b * c));
  } else {
    point.lambda = lambda_over_tau;
    const double dlog_lambda_dv = dlog_lambda_dv_rest + beta * b * c / (1.0 - b * c * w);
    point.dlambda_dq = point.lambda * dlog_lambda_dv * (-2.0 / (xg2 * b));
  }
  // (39)-(41). x3^alpha4 x4^alpha5 = exp(alpha4 log(x3/x4) + (alpha4 + alpha5) log x4),
  // with alpha4 = (j+2) alpha1 / (2 - gamma) and x3 / x4 = 1 + (2 - gamma) K,
  // K = -(j/2) b w / (x4 epsilon): the factor (2 - gamma) cancels.
  const double k = -0.5 * j * b * w / (x4 * epsilon);
  const double singular_pair = xg2 * alpha1 * logRatioOverDelta(2.0 - gamma, k) + alpha45 * log_x4;
  point.profile.f = x1 * point.lambda;
  point.profile.g = x2_power_alpha3 * std::exp(singular_pair);
  point.profile.h = std::exp(alpha0 * j * log_x1 + singular_pair - 2.0 * alpha1 * log_x3 + log_x4);
  return point;
}

SedovProfile SedovSimilarity::profile(double lambda) const {
  if (!(lambda > 0.0)) return at(0.0).profile;
  if (lambda >= 1.0) return at(1.0).profile;
  if (family == SedovFamily::singular) return at(lambda).profile;
  if (family == SedovFamily::vacuum && lambda <= lambda_vacuum) return {0.0, 0.0, 0.0};
  // Newton on F = log lambda(q) - log lambda for q (standard: on s = log q,
  // where F is nearly s + constant; vacuum: on q itself), kept in a bracket.
  const double target = std::log(lambda);
  const bool standard = family == SedovFamily::standard;
  double lo = standard ? -1.0 : 0.0, hi = standard ? 0.0 : 1.0;
  double x;
  if (standard) {
    // lambda / tau at the centre gives the start; widen the bracket below it.
    x = target - std::log(at(0.0).dlambda_dq);
    lo = std::min(x, 0.0) - 1.0;
    while (std::log(at(std::exp(lo)).lambda) > target) lo -= 16.0;
    x = std::clamp(x, lo, hi);
  } else {
    x = 0.5;
  }
  for (int iteration = 0; iteration < kMaxNewtonIterations; ++iteration) {
    const double q = standard ? std::exp(x) : x;
    const Point point = at(q);
    const double residual = std::log(point.lambda) - target;
    const double slope = point.dlambda_dq / point.lambda * (standard ? q : 1.0);
    if (residual == 0.0) return point.profile;
    (residual < 0.0 ? lo : hi) = x;
    double next = x - residual / slope;
    if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
    if (std::abs(next - x) <= kParameterTolerance * std::max(1.0, std::abs(x))) {
      return at(standard ? std::exp(next) : next).profile;
    }
    x = next;
  }
  throw std::runtime_error("SedovSimilarity::profile: no convergence");
}

double SedovSimilarity::energyIntegral() const {
  // Tanh-sinh quadrature on q in [0, 1]: q = 1 / (1 + exp(-pi sinh t)),
  // dq/dt = pi cosh t q (1 - q); exact to the last digits for integrands
  // analytic inside with algebraic behaviour at the ends (the vacuum's x4^alpha5).
  auto integrand = [&](double q) {
    const Point p = at(q);
    return (p.profile.g * p.profile.f * p.profile.f + p.profile.h) * std::pow(p.lambda, j - 1.0) *
           p.dlambda_dq;
  };
  auto term = [&](double t) {
    const double small = std::exp(-kPi * std::sinh(std::abs(t)));
    const double q = t < 0.0 ? small / (1.0 + small) : 1.0 / (1.0 + small);
    const double weight = kPi * std::cosh(t) * small / ((1.0 + small) * (1.0 + small));
    return weight * integrand(q);
  };
  constexpr double t_max = 4.5;  // q (1 - q) < 1e-60 beyond
  double step = 0.5;
  double sum = term(0.0);
  for (double t = step; t <= t_max; t += step) sum += term(t) + term(-t);
  double integral = step * sum;
  for (int level = 1; level <= 12; ++level) {
    step *= 0.5;
    for (double t = step; t <= t_max; t += 2.0 * step) sum += term(t) + term(-t);
    const double refined = step * sum;
    const bool converged =
        level >= 3 && std::abs(refined - integral) <= kQuadratureTolerance * std::abs(refined);
    integral = refined;
    if (converged) return integral;
  }
  throw std::runtime_error("SedovSimilarity::energyIntegral: no convergence");
}

double sedovEnergyConstant(double gamma, SedovGeometry geometry) {
  const SedovSimilarity s = sedovSimilarity(gamma, geometry);
  const double xg2 = s.j + 2.0;
  const double area = s.j == 1 ? 1.0 : (s.j == 2 ? 2.0 * kPi : 4.0 * kPi);
  return area * 8.0 / (xg2 * xg2 * (gamma * gamma - 1.0)) * s.energyIntegral();
}

SedovSolution solveSedov(double energy, double rho0, double gamma, double time,
                         SedovGeometry geometry) {
  auto positive = [](double x) { return x > 0.0 && std::isfinite(x); };
  if (!positive(energy) || !positive(rho0) || !positive(time)) {
    std::ostringstream message;
    message << "solveSedov: energy, density and time must be positive (E=" << energy
            << ", rho0=" << rho0 << ", t=" << time << ")";
    throw std::invalid_argument(message.str());
  }
  SedovSolution s{};
  s.energy = energy;
  s.rho0 = rho0;
  s.gamma = gamma;
  s.time = time;
  s.geometry = geometry;
  s.similarity = sedovSimilarity(gamma, geometry);
  s.alpha = sedovEnergyConstant(gamma, geometry);
  const double xg2 = s.similarity.j + 2.0;
  s.shock_radius = std::pow(energy / (s.alpha * rho0), 1.0 / xg2) * std::pow(time, 2.0 / xg2);
  s.shock_speed = 2.0 * s.shock_radius / (xg2 * time);
  s.post_shock.rho = rho0 * (gamma + 1.0) / (gamma - 1.0);
  s.post_shock.u = 2.0 * s.shock_speed / (gamma + 1.0);
  s.post_shock.p = 2.0 * rho0 * s.shock_speed * s.shock_speed / (gamma + 1.0);
  s.vacuum_radius = s.similarity.lambda_vacuum * s.shock_radius;
  return s;
}

SedovState SedovSolution::sample(double r) const {
  if (r > shock_radius) return {rho0, 0.0, 0.0};
  const SedovProfile profile = similarity.profile(r / shock_radius);
  return {post_shock.rho * profile.g, post_shock.u * profile.f, post_shock.p * profile.h};
}

}  // namespace lagremap
