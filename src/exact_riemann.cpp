// Exact Riemann solver for the 1D Euler equations of ideal gases; see exact_riemann.hpp.
// Equation numbers refer to Toro, "Riemann Solvers and Numerical Methods for Fluid Dynamics",
// 3rd edition, chapter 4.
#include "exact_riemann.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>

namespace lagremap {
namespace {

// Newton stops once successive iterates of p* agree to this relative amount.
constexpr double kPressureRelativeTolerance = 1e-14;
// Newton from a PVRS/TRRS/TSRS guess needs a handful of iterations; the cap leaves ample room for
// the geometric-bisection fallback (each halving of the bracket's width in decades costs one).
constexpr int kMaxPressureIterations = 200;
// Pressure ratio below which the primitive-variable guess is trusted (Toro's Q_user, Sec. 9.5.1).
constexpr double kPvrsMaxPressureRatio = 2.0;

// Quantities of one undisturbed state that recur in the wave relations of that side.
struct SideConstants {
  double rho;
  double u;
  double p;
  double gamma;
  double sound_speed;
  double shock_a;  // A_K = 2 / ((gamma + 1) rho_K), Toro (4.8)
  double shock_b;  // B_K = (gamma - 1) / (gamma + 1) p_K, Toro (4.8)
};

SideConstants makeSideConstants(const GasState& state, double gamma) {
  SideConstants side{};
  side.rho = state.rho;
  side.u = state.u;
  side.p = state.p;
  side.gamma = gamma;
  side.sound_speed = std::sqrt(gamma * state.p / state.rho);
  side.shock_a = 2.0 / ((gamma + 1.0) * state.rho);
  side.shock_b = (gamma - 1.0) / (gamma + 1.0) * state.p;
  return side;
}

void validateInput(const GasState& state, double gamma, const char* side_name) {
  auto fail = [&](const std::string& what) {
    std::ostringstream message;
    message << "solveRiemann: " << side_name << " state " << what << " (rho=" << state.rho
            << ", u=" << state.u << ", p=" << state.p << ", gamma=" << gamma << ")";
    throw std::invalid_argument(message.str());
  };
  // Written as !(x > 0) so that NaN is rejected as well.
  if (!(state.rho > 0.0) || !std::isfinite(state.rho)) fail("has non-positive density");
  if (!(state.p > 0.0) || !std::isfinite(state.p)) fail("has non-positive pressure");
  if (!std::isfinite(state.u)) fail("has non-finite velocity");
  if (!(gamma > 1.0) || !std::isfinite(gamma)) fail("needs an ideal-gas gamma > 1");
}

struct ValueAndSlope {
  double value;
  double slope;
};

// f_K(p) relates the velocity change across the K-wave to the star pressure p: a shock for
// p > p_K (Toro (4.6) left, (4.7) right), a rarefaction otherwise. The slope is Toro (4.37).
// f_K is monotone increasing and concave in p; both branches meet with equal value and slope
// 1 / (rho_K a_K) at p = p_K.
ValueAndSlope pressureFunction(double p, const SideConstants& side) {
  if (p > side.p) {
    const double root = std::sqrt(side.shock_a / (p + side.shock_b));
    return {(p - side.p) * root, root * (1.0 - 0.5 * (p - side.p) / (p + side.shock_b))};
  }
  const double gamma = side.gamma;
  const double ratio = p / side.p;
  return {2.0 * side.sound_speed / (gamma - 1.0) *
              (std::pow(ratio, (gamma - 1.0) / (2.0 * gamma)) - 1.0),
          std::pow(ratio, -(gamma + 1.0) / (2.0 * gamma)) / (side.rho * side.sound_speed)};
}

// Starting value for Newton, Toro Sec. 4.3.2 and the adaptive selection of Sec. 9.5.1:
// the linearised primitive-variable solution (PVRS, (4.47)) when the data are nearly uniform,
// otherwise the two-rarefaction (TRRS, (4.46)) or two-shock (TSRS, (4.48)) approximation.
double initialPressureGuess(const SideConstants& left, const SideConstants& right,
                            double velocity_jump) {
  const double p_min = std::min(left.p, right.p);
  const double p_max = std::max(left.p, right.p);
  const double p_pvrs = 0.5 * (left.p + right.p) - 0.125 * velocity_jump * (left.rho + right.rho) *
                                                       (left.sound_speed + right.sound_speed);
  // The guess only needs to be positive; the caller clamps it into a bracket of p*.
  const double p_floor = 1e-6 * p_min;

  if (p_max / p_min < kPvrsMaxPressureRatio && p_pvrs >= p_min && p_pvrs <= p_max) return p_pvrs;

  if (p_pvrs < p_min) {
    // Two rarefactions: sum of the rarefaction branches of f_L, f_R. With one gamma the exponent
    // z = (gamma - 1) / (2 gamma) is shared and p^z solves a linear equation, Toro (4.46). With two
    // gammas we use the mean exponent, which is exact for equal gammas and only a guess otherwise.
    const double z_left = (left.gamma - 1.0) / (2.0 * left.gamma);
    const double z_right = (right.gamma - 1.0) / (2.0 * right.gamma);
    const double z = 0.5 * (z_left + z_right);
    const double weight_left = 2.0 * left.sound_speed / (left.gamma - 1.0);
    const double weight_right = 2.0 * right.sound_speed / (right.gamma - 1.0);
    // Positive whenever the positivity condition (4.40) holds.
    const double numerator = weight_left + weight_right - velocity_jump;
    const double denominator =
        weight_left * std::pow(left.p, -z) + weight_right * std::pow(right.p, -z);
    return std::max(p_floor, std::pow(numerator / denominator, 1.0 / z));
  }

  // Two shocks: linearise the shock branches about the PVRS pressure, Toro (4.48).
  const double p_linearisation = std::max(p_floor, p_pvrs);
  const double g_left = std::sqrt(left.shock_a / (p_linearisation + left.shock_b));
  const double g_right = std::sqrt(right.shock_a / (p_linearisation + right.shock_b));
  const double p_tsrs = (g_left * left.p + g_right * right.p - velocity_jump) / (g_left + g_right);
  return std::max(p_floor, p_tsrs);
}

// f(p) = f_L(p) + f_R(p) + (u_R - u_L), whose root is p*, Toro (4.5), with its slope.
ValueAndSlope starPressureResidual(double p, const SideConstants& left, const SideConstants& right,
                                   double velocity_jump) {
  const ValueAndSlope f_left = pressureFunction(p, left);
  const ValueAndSlope f_right = pressureFunction(p, right);
  return {f_left.value + f_right.value + velocity_jump, f_left.slope + f_right.slope};
}

[[noreturn]] void throwNotConverged(const char* phase, double p, const SideConstants& left,
                                    const SideConstants& right) {
  std::ostringstream message;
  message << "solveRiemann: " << phase << " for p* did not converge in " << kMaxPressureIterations
          << " iterations (last iterate " << p << ", left rho=" << left.rho << " u=" << left.u
          << " p=" << left.p << " gamma=" << left.gamma << ", right rho=" << right.rho
          << " u=" << right.u << " p=" << right.p << " gamma=" << right.gamma << ")";
  throw std::runtime_error(message.str());
}

// Root of f by Newton's method (4.44) from the guess of Sec. 4.3.2, safeguarded by a bracket.
// Plain Newton is not enough near vacuum: there f ~ p^z with z = (gamma-1)/(2 gamma) small, so
// from above a step jumps past p = 0 and from below (f concave, so no overshoot) it only gains a
// factor ~1/(1-z) per step; with gamma = 1.05 and p* ~ 1e-70 that exceeded 200 steps. So p* is
// first bracketed (analytically when both waves are rarefactions, by climbing otherwise), and a
// Newton step that leaves the bracket or fails to halve the previous step is replaced by a
// geometric bisection, which copes with brackets spanning many decades.
double solveStarPressure(const SideConstants& left, const SideConstants& right,
                         double velocity_jump) {
  auto residualAt = [&](double p) { return starPressureResidual(p, left, right, velocity_jump); };

  const double p_guess = initialPressureGuess(left, right, velocity_jump);
  const double p_min = std::min(left.p, right.p);
  const ValueAndSlope at_p_min = residualAt(p_min);
  if (at_p_min.value == 0.0) return p_min;

  double p_below = 0.0;
  double p_above = 0.0;
  if (at_p_min.value > 0.0) {
    // p* < p_min: two rarefactions, and with c_K = 2 a_K / (gamma_K - 1) f(p*) = 0 reads
    //   c_L (p/p_L)^z_L + c_R (p/p_R)^z_R = c_L + c_R - (u_R - u_L) =: D,
    // with D > 0 by (4.40). Both terms lie in (0, D), the larger one is >= D/2, so
    //   min_K p_K (D / (2 c_K))^(1/z_K) <= p* <= min_K p_K (D / c_K)^(1/z_K).
    const double available = 2.0 * left.sound_speed / (left.gamma - 1.0) +
                             2.0 * right.sound_speed / (right.gamma - 1.0) - velocity_jump;
    p_below = p_min;
    p_above = p_min;
    for (const SideConstants* side : {&left, &right}) {
      const double z = (side->gamma - 1.0) / (2.0 * side->gamma);
      const double c = 2.0 * side->sound_speed / (side->gamma - 1.0);
      p_below = std::min(p_below, side->p * std::pow(0.5 * available / c, 1.0 / z));
      p_above = std::min(p_above, side->p * std::pow(available / c, 1.0 / z));
    }
  } else {
    // p* > p_min: climb from the guess. Below the root a Newton step undershoots (f concave), so
    // twice the Newton iterate at least doubles p and soon passes the root.
    p_below = p_min;
    double p = std::max(p_guess, 2.0 * p_min);
    for (int iteration = 0;; ++iteration) {
      if (iteration == kMaxPressureIterations)
        throwNotConverged("upper bracket search", p, left, right);
      const ValueAndSlope at_p = residualAt(p);
      if (!std::isfinite(at_p.value)) throwNotConverged("upper bracket search", p, left, right);
      if (at_p.value >= 0.0) {
        p_above = p;
        break;
      }
      p_below = p;
      p = 2.0 * (p - at_p.value / at_p.slope);
    }
  }

  double p = p_guess;
  if (!(p >= p_below && p <= p_above)) p = std::sqrt(p_below) * std::sqrt(p_above);
  double previous_step = p_above - p_below;
  for (int iteration = 0; iteration < kMaxPressureIterations; ++iteration) {
    const ValueAndSlope at_p = residualAt(p);
    if (!std::isfinite(at_p.value)) break;
    if (at_p.value == 0.0) return p;
    (at_p.value < 0.0 ? p_below : p_above) = p;

    double p_next = p - at_p.value / at_p.slope;
    // Relative change of successive iterates, Toro (4.45). Tested before the safeguard: once
    // converged the correction can round to zero, which would look like leaving the bracket.
    if (std::abs(p_next - p) <= kPressureRelativeTolerance * p) return p_next;
    const bool leaves_bracket = !(p_next > p_below && p_next < p_above);
    if (leaves_bracket || std::abs(p_next - p) > 0.5 * previous_step) {
      p_next = std::sqrt(p_below) * std::sqrt(p_above);
    }
    previous_step = std::abs(p_next - p);
    // A bisection step this small means the bracket has collapsed onto p*.
    if (previous_step <= kPressureRelativeTolerance * p) return p_next;
    p = p_next;
  }
  throwNotConverged("Newton iteration", p, left, right);
}

// Density behind a shock with post-shock pressure p_star, Toro (4.50) / (4.57).
double densityBehindShock(const SideConstants& side, double p_star) {
  const double pressure_ratio = p_star / side.p;
  const double gamma_ratio = (side.gamma - 1.0) / (side.gamma + 1.0);
  return side.rho * (pressure_ratio + gamma_ratio) / (gamma_ratio * pressure_ratio + 1.0);
}

// Shock speed, Toro (4.52) / (4.59); direction is -1 for the left wave and +1 for the right.
double shockSpeed(const SideConstants& side, double p_star, double direction) {
  const double gamma = side.gamma;
  return side.u + direction * side.sound_speed *
                      std::sqrt((gamma + 1.0) / (2.0 * gamma) * p_star / side.p +
                                (gamma - 1.0) / (2.0 * gamma));
}

// State inside a rarefaction fan at similarity coordinate xi, Toro (4.56) for the left fan
// (direction -1) and (4.63) for the right fan (direction +1). The fan is the set of
// characteristics u + direction * a = xi with the Riemann invariant of the undisturbed side
// u - direction * 2a / (gamma - 1) and the entropy p / rho^gamma carried over from that side.
GasState sampleFan(const GasState& outer, double gamma, double direction, double xi) {
  const double sound_speed = std::sqrt(gamma * outer.p / outer.rho);
  const double base = 2.0 / (gamma + 1.0) -
                      direction * (gamma - 1.0) / ((gamma + 1.0) * sound_speed) * (outer.u - xi);
  GasState state{};
  state.rho = outer.rho * std::pow(base, 2.0 / (gamma - 1.0));
  state.u = 2.0 / (gamma + 1.0) * (-direction * sound_speed + 0.5 * (gamma - 1.0) * outer.u + xi);
  state.p = outer.p * std::pow(base, 2.0 * gamma / (gamma - 1.0));
  return state;
}

}  // namespace

RiemannSolution solveRiemann(const GasState& left, const GasState& right, double gamma_left,
                             double gamma_right) {
  validateInput(left, gamma_left, "left");
  validateInput(right, gamma_right, "right");

  const SideConstants left_side = makeSideConstants(left, gamma_left);
  const SideConstants right_side = makeSideConstants(right, gamma_right);
  const double velocity_jump = right.u - left.u;

  // Pressure positivity condition, Toro (4.40): two rarefactions can at most expand each gas to
  // zero pressure; a larger separation speed leaves vacuum between them, which this solver (and
  // the hydro code it verifies) does not represent.
  const double critical_velocity_jump = 2.0 * left_side.sound_speed / (gamma_left - 1.0) +
                                        2.0 * right_side.sound_speed / (gamma_right - 1.0);
  if (!(velocity_jump < critical_velocity_jump)) {
    std::ostringstream message;
    message << "solveRiemann: initial data generate vacuum (u_R - u_L = " << velocity_jump
            << " >= 2 a_L / (gamma_L - 1) + 2 a_R / (gamma_R - 1) = " << critical_velocity_jump
            << ", Toro (4.40))";
    throw std::invalid_argument(message.str());
  }

  RiemannSolution solution{};
  solution.left = left;
  solution.right = right;
  solution.gamma_left = gamma_left;
  solution.gamma_right = gamma_right;

  const double p_star = solveStarPressure(left_side, right_side, velocity_jump);
  solution.p_star = p_star;
  // Toro (4.9): the mean of the star velocities computed from either side.
  solution.u_star = 0.5 * (left.u + right.u) + 0.5 * (pressureFunction(p_star, right_side).value -
                                                      pressureFunction(p_star, left_side).value);

  solution.left_is_shock = p_star > left.p;
  if (solution.left_is_shock) {
    solution.rho_star_left = densityBehindShock(left_side, p_star);
    solution.left_head_speed = shockSpeed(left_side, p_star, -1.0);
    solution.left_tail_speed = solution.left_head_speed;
  } else {
    // Isentropic expansion, Toro (4.53) and (4.54)-(4.55).
    const double pressure_ratio = p_star / left.p;
    solution.rho_star_left = left.rho * std::pow(pressure_ratio, 1.0 / gamma_left);
    const double sound_speed_star =
        left_side.sound_speed * std::pow(pressure_ratio, (gamma_left - 1.0) / (2.0 * gamma_left));
    solution.left_head_speed = left.u - left_side.sound_speed;
    solution.left_tail_speed = solution.u_star - sound_speed_star;
  }

  solution.right_is_shock = p_star > right.p;
  if (solution.right_is_shock) {
    solution.rho_star_right = densityBehindShock(right_side, p_star);
    solution.right_head_speed = shockSpeed(right_side, p_star, +1.0);
    solution.right_tail_speed = solution.right_head_speed;
  } else {
    // Isentropic expansion, Toro (4.60) and (4.61)-(4.62).
    const double pressure_ratio = p_star / right.p;
    solution.rho_star_right = right.rho * std::pow(pressure_ratio, 1.0 / gamma_right);
    const double sound_speed_star =
        right_side.sound_speed *
        std::pow(pressure_ratio, (gamma_right - 1.0) / (2.0 * gamma_right));
    solution.right_head_speed = right.u + right_side.sound_speed;
    solution.right_tail_speed = solution.u_star + sound_speed_star;
  }
  return solution;
}

// Sampling, Toro Sec. 4.5 (Fig. 4.14 flow chart): first locate xi relative to the contact, then
// relative to the wave on that side.
GasState RiemannSolution::sample(double xi) const {
  if (xi < u_star) {
    if (xi < left_head_speed) return left;
    if (xi >= left_tail_speed) return GasState{rho_star_left, u_star, p_star};
    return sampleFan(left, gamma_left, -1.0, xi);  // only reachable for a rarefaction
  }
  if (xi >= right_head_speed) return right;
  if (xi < right_tail_speed) return GasState{rho_star_right, u_star, p_star};
  return sampleFan(right, gamma_right, +1.0, xi);
}

}  // namespace lagremap
