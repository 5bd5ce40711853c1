// Exact solution of the Riemann problem for the 1D Euler equations of ideal and stiffened gases,
// following Toro, "Riemann Solvers and Numerical Methods for Fluid Dynamics" (3rd ed.), chapter 4.
//
// Each side is its own gas, a stiffened gas
//   p = (gamma - 1) rho e - gamma p_inf,   a^2 = gamma (p + p_inf) / rho,
// with its own gamma and p_inf (p_inf = 0: the ideal gas). Every wave travels through only one gas
// (left waves through the left gas, right waves through the right gas), and in the shifted
// pressure P = p + p_inf the stiffened gas's shock (Hugoniot) and isentrope relations are exactly
// those of the ideal gas in p. So Toro's f_K, shock and fan formulas hold on side K with every
// pressure replaced by p + p_inf_K, the star pressure p* being common to both sides.
//
// Plain host code, used to generate reference solutions for verification problems.
#pragma once

namespace lagremap {

// Primitive state of a gas: density, velocity, pressure.
struct GasState {
  double rho;
  double u;
  double p;
};

// The self-similar solution W(x/t) of one Riemann problem. Waves are ordered
//   left_head_speed <= left_tail_speed <= u_star <= right_tail_speed <= right_head_speed.
// A rarefaction's head is the edge that faces the undisturbed gas, its tail the edge facing the
// star region; a shock has head == tail == its speed.
struct RiemannSolution {
  GasState left;
  GasState right;
  double gamma_left;
  double gamma_right;
  // Stiffened-gas pressure shift of each gas; 0 for an ideal gas. sample() needs them in fans.
  double p_inf_left = 0.0;
  double p_inf_right = 0.0;

  double p_star;          // pressure of the star region (both sides of the contact)
  double u_star;          // velocity of the star region = contact speed
  double rho_star_left;   // density between the left wave and the contact
  double rho_star_right;  // density between the contact and the right wave

  bool left_is_shock;
  bool right_is_shock;
  double left_head_speed;
  double left_tail_speed;
  double right_head_speed;
  double right_tail_speed;

  // State at similarity coordinate xi = (x - x0) / t. At a discontinuity located exactly at xi the
  // state on its right is returned (so xi == u_star gives the right star state).
  GasState sample(double xi) const;
};

// Solves the Riemann problem with `left` for x < x0 and `right` for x > x0, each side a stiffened
// gas with its own gamma and p_inf (the defaults p_inf = 0 give the ideal-gas solver, bit for bit).
// A state with p_inf > 0 may carry a negative pressure (tension) as long as p + p_inf > 0, and so
// may p*.
// Throws std::invalid_argument for a non-positive or non-finite density, a non-finite pressure or
// velocity, p + p_inf <= 0, gamma <= 1, a negative or non-finite p_inf, or data that generate
// vacuum (the pressure positivity condition, Toro (4.40), with p + p_inf in place of p, violated).
// Throws std::runtime_error if the iteration for p* fails.
RiemannSolution solveRiemann(const GasState& left, const GasState& right, double gamma_left,
                             double gamma_right, double p_inf_left = 0.0, double p_inf_right = 0.0);

// Specific internal energy of a stiffened-gas state, e = (p + gamma p_inf) / ((gamma - 1) rho),
// the inverse of the equation of state above (p_inf = 0: the ideal gas's p / ((gamma - 1) rho)).
inline double stiffenedGasInternalEnergy(const GasState& state, double gamma, double p_inf = 0.0) {
  return (state.p + gamma * p_inf) / ((gamma - 1.0) * state.rho);
}

}  // namespace lagremap
