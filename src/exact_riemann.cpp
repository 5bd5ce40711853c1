// Exact Riemann solver for the 1D Euler equations of ideal and stiffened gases; see
// exact_riemann.hpp. Equation numbers refer to Toro, "Riemann Solvers and Numerical Methods for
// Fluid Dynamics", 3rd edition, chapter 4; there p is to be read as p + p_inf_K on side K.
//
// The star pressure is sought on the lifted axis q = p + p_inf_min, p_inf_min the smaller of the
// two p_inf. On it q > 0 is exactly the set of pressures at which both gases have p + p_inf > 0,
// q -> 0 is the vacuum of the softer gas, and the ideal-gas root finder (positive iterates,
// geometric bisection, the vacuum bracket) carries over. Side K's shifted pressure p + p_inf_K is
// q + q_offset_K with q_offset_K = p_inf_K - p_inf_min >= 0, zero for the softer gas, so that gas
// keeps the full resolution near its vacuum. With p_inf = 0 on both sides q = p, every offset is 0
// and each floating-point operation is the one of the ideal-gas solver.
#include "exact_riemann.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>

namespace lagremap {
namespace {

// Newton stops once successive iterates of q* agree to this relative amount.
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
  double p_inf;
  double gamma;
  double q;            // p_K + p_inf_min: the undisturbed pressure on the lifted axis
  double q_offset;     // p_inf_K - p_inf_min >= 0: p + p_inf_K = q + q_offset
  double shifted_p;    // P_K = p_K + p_inf_K, as q + q_offset
  double sound_speed;  // a_K = sqrt(gamma P_K / rho_K)
  double shock_a;      // A_K = 2 / ((gamma + 1) rho_K), Toro (4.8)
  double shock_b;      // B_K = (gamma - 1) / (gamma + 1) P_K, Toro (4.8)
};

SideConstants makeSideConstants(const GasState& state, double gamma, double p_inf,
                                double p_inf_min) {
  SideConstants side{};
  side.rho = state.rho;
  side.u = state.u;
  side.p = state.p;
  side.p_inf = p_inf;
  side.gamma = gamma;
  side.q = state.p + p_inf_min;
  side.q_offset = p_inf - p_inf_min;
  // Through q, not p + p_inf: then q = q_K gives exactly P = P_K, where the shock and rarefaction
  // branches of f_K meet.
  side.shifted_p = side.q + side.q_offset;
  side.sound_speed = std::sqrt(gamma * side.shifted_p / state.rho);
  side.shock_a = 2.0 / ((gamma + 1.0) * state.rho);
  side.shock_b = (gamma - 1.0) / (gamma + 1.0) * side.shifted_p;
  return side;
}

void validateInput(const GasState& state, double gamma, double p_inf, const char* side_name) {
  auto fail = [&](const std::string& what) {
    std::ostringstream message;
    message << "solveRiemann: " << side_name << " state " << what << " (rho=" << state.rho
            << ", u=" << state.u << ", p=" << state.p << ", gamma=" << gamma << ", p_inf=" << p_inf
            << ")";
    throw std::invalid_argument(message.str());
  };
  // Written as !(x > 0) so that NaN is rejected as well.
  if (!(state.rho > 0.0) || !std::isfinite(state.rho)) fail("has non-positive density");
  if (!(p_inf >= 0.0) || !std::isfinite(p_inf)) fail("needs a stiffened-gas p_inf >= 0");
  if (!std::isfinite(state.p)) fail("has non-finite pressure");
  // The equation of state holds, and the sound speed is real, only where p + p_inf > 0.
  if (!(state.p + p_inf > 0.0)) fail("has non-positive pressure p + p_inf");
  if (!std::isfinite(state.u)) fail("has non-finite velocity");
  if (!(gamma > 1.0) || !std::isfinite(gamma)) fail("needs gamma > 1");
}

struct ValueAndSlope {
  double value;
  double slope;
};

// f_K(q) relates the velocity change across the K-wave to the star pressure q (on the lifted
// axis): a shock for q > q_K (Toro (4.6) left, (4.7) right), a rarefaction otherwise. The slope is
// Toro (4.37). f_K is monotone increasing and concave in q; both branches meet with equal value
// and slope 1 / (rho_K a_K) at q = q_K.
ValueAndSlope pressureFunction(double q, const SideConstants& side) {
  if (q > side.q) {
    const double denominator = q + side.q_offset + side.shock_b;
    const double root = std::sqrt(side.shock_a / denominator);
    return {(q - side.q) * root, root * (1.0 - 0.5 * (q - side.q) / denominator)};
  }
  const double gamma = side.gamma;
  const double ratio = (q + side.q_offset) / side.shifted_p;
  return {2.0 * side.sound_speed / (gamma - 1.0) *
              (std::pow(ratio, (gamma - 1.0) / (2.0 * gamma)) - 1.0),
          std::pow(ratio, -(gamma + 1.0) / (2.0 * gamma)) / (side.rho * side.sound_speed)};
}

// Starting value for Newton, Toro Sec. 4.3.2 and the adaptive selection of Sec. 9.5.1:
// the linearised primitive-variable solution (PVRS, (4.47)) when the data are nearly uniform,
// otherwise the two-rarefaction (TRRS, (4.46)) or two-shock (TSRS, (4.48)) approximation.
// All are written on the lifted axis. With different p_inf the TRRS formula, which takes P = q on
// both sides, is only approximate, and a stiffer gas under tension (q_K <= 0) skips to the TSRS;
// the bracketing in solveStarPressure tolerates any positive guess.
double initialPressureGuess(const SideConstants& left, const SideConstants& right,
                            double velocity_jump) {
  const double q_min = std::min(left.q, right.q);
  const double q_max = std::max(left.q, right.q);
  const double q_pvrs = 0.5 * (left.q + right.q) - 0.125 * velocity_jump * (left.rho + right.rho) *
                                                       (left.sound_speed + right.sound_speed);
  // The guess only needs to be positive; the caller clamps it into a bracket of q*. q_max > 0
  // always: the softer gas has q_K = p_K + p_inf_K.
  const double q_floor = 1e-6 * (q_min > 0.0 ? q_min : q_max);

  if (q_min > 0.0) {
    if (q_max / q_min < kPvrsMaxPressureRatio && q_pvrs >= q_min && q_pvrs <= q_max) return q_pvrs;

    if (q_pvrs < q_min) {
      // Two rarefactions: sum of the rarefaction branches of f_L, f_R. With one gamma the exponent
      // z = (gamma - 1) / (2 gamma) is shared and q^z solves a linear equation, Toro (4.46). With
      // two gammas we use the mean exponent, which is exact for equal gammas and only a guess
      // otherwise.
      const double z_left = (left.gamma - 1.0) / (2.0 * left.gamma);
      const double z_right = (right.gamma - 1.0) / (2.0 * right.gamma);
      const double z = 0.5 * (z_left + z_right);
      const double weight_left = 2.0 * left.sound_speed / (left.gamma - 1.0);
      const double weight_right = 2.0 * right.sound_speed / (right.gamma - 1.0);
      // Positive whenever the positivity condition (4.40) holds.
      const double numerator = weight_left + weight_right - velocity_jump;
      const double denominator =
          weight_left * std::pow(left.q, -z) + weight_right * std::pow(right.q, -z);
      return std::max(q_floor, std::pow(numerator / denominator, 1.0 / z));
    }
  }

  // Two shocks: linearise the shock branches about the PVRS pressure, Toro (4.48).
  const double q_linearisation = std::max(q_floor, q_pvrs);
  const double g_left = std::sqrt(left.shock_a / (q_linearisation + left.q_offset + left.shock_b));
  const double g_right =
      std::sqrt(right.shock_a / (q_linearisation + right.q_offset + right.shock_b));
  const double q_tsrs = (g_left * left.q + g_right * right.q - velocity_jump) / (g_left + g_right);
  return std::max(q_floor, q_tsrs);
}

// f(q) = f_L(q) + f_R(q) + (u_R - u_L), whose root is q*, Toro (4.5), with its slope.
ValueAndSlope starPressureResidual(double q, const SideConstants& left, const SideConstants& right,
                                   double velocity_jump) {
  const ValueAndSlope f_left = pressureFunction(q, left);
  const ValueAndSlope f_right = pressureFunction(q, right);
  return {f_left.value + f_right.value + velocity_jump, f_left.slope + f_right.slope};
}

[[noreturn]] void throwNotConverged(const char* phase, double q, const SideConstants& left,
                                    const SideConstants& right) {
  std::ostringstream message;
  message << "solveRiemann: " << phase << " for p* did not converge in " << kMaxPressureIterations
          << " iterations (last iterate p + min(p_inf) = " << q << ", left rho=" << left.rho
          << " u=" << left.u << " p=" << left.p << " gamma=" << left.gamma
          << " p_inf=" << left.p_inf << ", right rho=" << right.rho << " u=" << right.u
          << " p=" << right.p << " gamma=" << right.gamma << " p_inf=" << right.p_inf << ")";
  throw std::runtime_error(message.str());
}

// f(q_below) < 0 < f(q_above) once both are set; q_below = 0 marks a lower
// end still unknown.
struct PressureBracket {
  double q_below = 0.0;
  double q_above = 0.0;
};

// q* < q_min: two rarefactions. With c_K = 2 a_K / (gamma_K - 1), z_K = (gamma_K - 1) /
// (2 gamma_K), P_K = p_K + p_inf_K and g_K(q) = c_K ((q + q_offset_K) / P_K)^z_K, f(q*) = 0
// reads
//   g_L(q*) + g_R(q*) = c_L + c_R - (u_R - u_L) =: D.
// Each g_K rises from m_K = g_K(0) = c_K (q_offset_K / P_K)^z_K (0 for the softer gas), and
// D > m_L + m_R by the positivity condition. So g_K(q*) <= D - m_other, and the larger term is
// >= D/2; with the inverse h_K(y) = P_K (y / c_K)^(1/z_K) - q_offset_K of g_K,
//   min_K h_K(D/2) <= q* <= min_K h_K(D - m_other).
// For ideal gases (offsets 0) both ends are positive. A stiffer gas with m_K >= D/2 makes the
// lower end useless; then descendToLowerEnd finds one.
PressureBracket twoRarefactionBracket(const SideConstants& left, const SideConstants& right,
                                      double velocity_jump, double q_min) {
  const double available = 2.0 * left.sound_speed / (left.gamma - 1.0) +
                           2.0 * right.sound_speed / (right.gamma - 1.0) - velocity_jump;
  PressureBracket bracket{q_min, q_min};
  for (const SideConstants* side : {&left, &right}) {
    const SideConstants* other = side == &left ? &right : &left;
    const double z = (side->gamma - 1.0) / (2.0 * side->gamma);
    const double c = 2.0 * side->sound_speed / (side->gamma - 1.0);
    const double z_other = (other->gamma - 1.0) / (2.0 * other->gamma);
    const double c_other = 2.0 * other->sound_speed / (other->gamma - 1.0);
    const double m_other = c_other * std::pow(other->q_offset / other->shifted_p, z_other);
    bracket.q_below = std::min(
        bracket.q_below, side->shifted_p * std::pow(0.5 * available / c, 1.0 / z) - side->q_offset);
    bracket.q_above =
        std::min(bracket.q_above,
                 side->shifted_p * std::pow((available - m_other) / c, 1.0 / z) - side->q_offset);
  }
  // The bounds are exact only in exact arithmetic; rounding (P_K (...) - q_offset_K cancels when
  // q* << q_offset_K) must not leave the root outside, so each end is checked.
  if (!(bracket.q_above > 0.0) ||
      starPressureResidual(bracket.q_above, left, right, velocity_jump).value < 0.0) {
    bracket.q_above = q_min;
  }
  if (bracket.q_below > 0.0 &&
      starPressureResidual(bracket.q_below, left, right, velocity_jump).value > 0.0) {
    bracket.q_below = 0.0;
  }
  return bracket;
}

// q* > q_min: climb from the guess. Below the root a Newton step undershoots (f concave), so
// twice the Newton iterate at least doubles q and soon passes the root.
PressureBracket climbToUpperEnd(const SideConstants& left, const SideConstants& right,
                                double velocity_jump, double q_min, double q_guess) {
  PressureBracket bracket{std::max(q_min, 0.0), 0.0};
  double q = std::max(q_guess, 2.0 * q_min);
  for (int iteration = 0;; ++iteration) {
    if (iteration == kMaxPressureIterations)
      throwNotConverged("upper bracket search", q, left, right);
    const ValueAndSlope at_q = starPressureResidual(q, left, right, velocity_jump);
    if (!std::isfinite(at_q.value)) throwNotConverged("upper bracket search", q, left, right);
    if (at_q.value >= 0.0) {
      bracket.q_above = q;
      return bracket;
    }
    bracket.q_below = q;
    q = 2.0 * (q - at_q.value / at_q.slope);
  }
}

// No positive lower end yet, though f(0+) < 0 by the positivity condition: descend from
// q_above by factors 2^-1, 2^-2, 2^-4, ..., which reach 1e-300 within ten steps. Returns the
// root where a step lands on it exactly.
std::optional<double> descendToLowerEnd(const SideConstants& left, const SideConstants& right,
                                        double velocity_jump, PressureBracket& bracket) {
  double factor = 0.5;
  double q = bracket.q_above;
  for (int iteration = 0;; ++iteration) {
    if (iteration == kMaxPressureIterations)
      throwNotConverged("lower bracket search", q, left, right);
    q *= factor;
    factor *= factor;
    if (!(q > 0.0)) throwNotConverged("lower bracket search", q, left, right);
    const ValueAndSlope at_q = starPressureResidual(q, left, right, velocity_jump);
    if (!std::isfinite(at_q.value)) throwNotConverged("lower bracket search", q, left, right);
    if (at_q.value == 0.0) return q;
    if (at_q.value < 0.0) {
      bracket.q_below = q;
      return std::nullopt;
    }
    bracket.q_above = q;
  }
}

// Newton's method (4.44) from q_guess inside the bracket; a step that leaves the bracket or
// fails to halve the previous step is replaced by a geometric bisection.
double safeguardedNewton(const SideConstants& left, const SideConstants& right,
                         double velocity_jump, double q_guess, PressureBracket bracket) {
  double& q_below = bracket.q_below;
  double& q_above = bracket.q_above;
  double q = q_guess;
  if (!(q >= q_below && q <= q_above)) q = std::sqrt(q_below) * std::sqrt(q_above);
  double previous_step = q_above - q_below;
  for (int iteration = 0; iteration < kMaxPressureIterations; ++iteration) {
    const ValueAndSlope at_q = starPressureResidual(q, left, right, velocity_jump);
    if (!std::isfinite(at_q.value)) break;
    if (at_q.value == 0.0) return q;
    (at_q.value < 0.0 ? q_below : q_above) = q;

    double q_next = q - at_q.value / at_q.slope;
    // Relative change of successive iterates, Toro (4.45). Tested before the safeguard: once
    // converged the correction can round to zero, which would look like leaving the bracket.
    if (std::abs(q_next - q) <= kPressureRelativeTolerance * q) return q_next;
    const bool leaves_bracket = !(q_next > q_below && q_next < q_above);
    if (leaves_bracket || std::abs(q_next - q) > 0.5 * previous_step) {
      q_next = std::sqrt(q_below) * std::sqrt(q_above);
    }
    previous_step = std::abs(q_next - q);
    // A bisection step this small means the bracket has collapsed onto q*.
    if (previous_step <= kPressureRelativeTolerance * q) return q_next;
    q = q_next;
  }
  throwNotConverged("Newton iteration", q, left, right);
}

// Root q* of f by Newton's method (4.44) from the guess of Sec. 4.3.2, safeguarded by a bracket.
// Plain Newton is not enough near vacuum: there f ~ q^z with z = (gamma-1)/(2 gamma) small, so
// from above a step jumps past q = 0 and from below (f concave, so no overshoot) it only gains a
// factor ~1/(1-z) per step; with gamma = 1.05 and p* ~ 1e-70 that exceeded 200 steps. So q* is
// first bracketed (analytically when both waves are rarefactions, by climbing otherwise), and a
// Newton step that leaves the bracket or fails to halve the previous step is replaced by a
// geometric bisection, which copes with brackets spanning many decades.
double solveStarPressure(const SideConstants& left, const SideConstants& right,
                         double velocity_jump) {
  const double q_guess = initialPressureGuess(left, right, velocity_jump);
  const double q_min = std::min(left.q, right.q);
  // A liquid under enough tension sits at q_K <= 0, below the vacuum of the softer gas; its wave
  // is a shock whatever q* > 0, so q* > q_min as when f(q_min) < 0.
  bool two_rarefactions = false;
  if (q_min > 0.0) {
    const ValueAndSlope at_q_min = starPressureResidual(q_min, left, right, velocity_jump);
    if (at_q_min.value == 0.0) return q_min;
    two_rarefactions = at_q_min.value > 0.0;
  }
  PressureBracket bracket = two_rarefactions
                                ? twoRarefactionBracket(left, right, velocity_jump, q_min)
                                : climbToUpperEnd(left, right, velocity_jump, q_min, q_guess);
  if (!(bracket.q_below > 0.0)) {
    const std::optional<double> root = descendToLowerEnd(left, right, velocity_jump, bracket);
    if (root) return *root;
  }
  return safeguardedNewton(left, right, velocity_jump, q_guess, bracket);
}

// Density behind a shock with post-shock lifted pressure q_star, Toro (4.50) / (4.57).
double densityBehindShock(const SideConstants& side, double q_star) {
  const double pressure_ratio = (q_star + side.q_offset) / side.shifted_p;
  const double gamma_ratio = (side.gamma - 1.0) / (side.gamma + 1.0);
  return side.rho * (pressure_ratio + gamma_ratio) / (gamma_ratio * pressure_ratio + 1.0);
}

// Shock speed, Toro (4.52) / (4.59); direction is -1 for the left wave and +1 for the right.
double shockSpeed(const SideConstants& side, double q_star, double direction) {
  const double gamma = side.gamma;
  const double pressure_ratio = (q_star + side.q_offset) / side.shifted_p;
  return side.u + direction * side.sound_speed *
                      std::sqrt((gamma + 1.0) / (2.0 * gamma) * pressure_ratio +
                                (gamma - 1.0) / (2.0 * gamma));
}

// State inside a rarefaction fan at similarity coordinate xi, Toro (4.56) for the left fan
// (direction -1) and (4.63) for the right fan (direction +1). The fan is the set of
// characteristics u + direction * a = xi with the Riemann invariant of the undisturbed side
// u - direction * 2a / (gamma - 1) and the entropy (p + p_inf) / rho^gamma carried over from that
// side.
GasState sampleFan(const GasState& outer, double gamma, double p_inf, double direction, double xi) {
  const double shifted_p = outer.p + p_inf;
  const double sound_speed = std::sqrt(gamma * shifted_p / outer.rho);
  const double base = 2.0 / (gamma + 1.0) -
                      direction * (gamma - 1.0) / ((gamma + 1.0) * sound_speed) * (outer.u - xi);
  GasState state{};
  state.rho = outer.rho * std::pow(base, 2.0 / (gamma - 1.0));
  state.u = 2.0 / (gamma + 1.0) * (-direction * sound_speed + 0.5 * (gamma - 1.0) * outer.u + xi);
  state.p = shifted_p * std::pow(base, 2.0 * gamma / (gamma - 1.0)) - p_inf;
  return state;
}

}  // namespace

RiemannSolution solveRiemann(const GasState& left, const GasState& right, double gamma_left,
                             double gamma_right, double p_inf_left, double p_inf_right) {
  validateInput(left, gamma_left, p_inf_left, "left");
  validateInput(right, gamma_right, p_inf_right, "right");

  const double p_inf_min = std::min(p_inf_left, p_inf_right);
  const SideConstants left_side = makeSideConstants(left, gamma_left, p_inf_left, p_inf_min);
  const SideConstants right_side = makeSideConstants(right, gamma_right, p_inf_right, p_inf_min);
  const double velocity_jump = right.u - left.u;

  // Pressure positivity condition, Toro (4.40): f(0+) < 0, i.e. the two waves can at most expand
  // the softer gas to its vacuum p + p_inf_min = 0 (q = 0); a larger separation speed leaves
  // vacuum (or a cavity in a liquid) between them, which this solver (and the hydro code it
  // verifies) does not represent. For ideal gases -f_K(0) = 2 a_K / (gamma_K - 1), Toro's bound;
  // a stiffer gas, which still has p + p_inf_K = q_offset_K > 0 there, contributes less.
  const double critical_velocity_jump =
      -(pressureFunction(0.0, left_side).value + pressureFunction(0.0, right_side).value);
  if (!(velocity_jump < critical_velocity_jump)) {
    std::ostringstream message;
    message << "solveRiemann: initial data generate vacuum (u_R - u_L = " << velocity_jump
            << " >= -f_L(p_vac) - f_R(p_vac) = " << critical_velocity_jump
            << " at p_vac = -min(p_inf_L, p_inf_R); for ideal gases 2 a_L / (gamma_L - 1) + "
               "2 a_R / (gamma_R - 1), Toro (4.40))";
    throw std::invalid_argument(message.str());
  }

  RiemannSolution solution{};
  solution.left = left;
  solution.right = right;
  solution.gamma_left = gamma_left;
  solution.gamma_right = gamma_right;
  solution.p_inf_left = p_inf_left;
  solution.p_inf_right = p_inf_right;

  const double q_star = solveStarPressure(left_side, right_side, velocity_jump);
  solution.p_star = q_star - p_inf_min;
  // Toro (4.9): the mean of the star velocities computed from either side.
  solution.u_star = 0.5 * (left.u + right.u) + 0.5 * (pressureFunction(q_star, right_side).value -
                                                      pressureFunction(q_star, left_side).value);

  solution.left_is_shock = q_star > left_side.q;
  if (solution.left_is_shock) {
    solution.rho_star_left = densityBehindShock(left_side, q_star);
    solution.left_head_speed = shockSpeed(left_side, q_star, -1.0);
    solution.left_tail_speed = solution.left_head_speed;
  } else {
    // Isentropic expansion, Toro (4.53) and (4.54)-(4.55).
    const double pressure_ratio = (q_star + left_side.q_offset) / left_side.shifted_p;
    solution.rho_star_left = left.rho * std::pow(pressure_ratio, 1.0 / gamma_left);
    const double sound_speed_star =
        left_side.sound_speed * std::pow(pressure_ratio, (gamma_left - 1.0) / (2.0 * gamma_left));
    solution.left_head_speed = left.u - left_side.sound_speed;
    solution.left_tail_speed = solution.u_star - sound_speed_star;
  }

  solution.right_is_shock = q_star > right_side.q;
  if (solution.right_is_shock) {
    solution.rho_star_right = densityBehindShock(right_side, q_star);
    solution.right_head_speed = shockSpeed(right_side, q_star, +1.0);
    solution.right_tail_speed = solution.right_head_speed;
  } else {
    // Isentropic expansion, Toro (4.60) and (4.61)-(4.62).
    const double pressure_ratio = (q_star + right_side.q_offset) / right_side.shifted_p;
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
    return sampleFan(left, gamma_left, p_inf_left, -1.0, xi);  // only reachable for a rarefaction
  }
  if (xi >= right_head_speed) return right;
  if (xi < right_tail_speed) return GasState{rho_star_right, u_star, p_star};
  return sampleFan(right, gamma_right, p_inf_right, +1.0, xi);
}

}  // namespace lagremap
