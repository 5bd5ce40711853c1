// Exact solution of the Riemann problem for the 1D Euler equations of ideal gases, following
// Toro, "Riemann Solvers and Numerical Methods for Fluid Dynamics" (3rd ed.), chapter 4. The two
// initial states may carry different ratios of specific heats: every wave travels through only
// one gas (left waves through the left gas, right waves through the right gas), so the method
// carries over unchanged with gamma_left in f_L and gamma_right in f_R.
//
// Plain host code, used to generate reference solutions for verification problems.
#pragma once

namespace lagremap {

// Primitive state of an ideal gas: density, velocity, pressure.
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

// Solves the Riemann problem with `left` for x < x0 and `right` for x > x0.
// Throws std::invalid_argument for a non-positive or non-finite density or pressure, a
// non-finite velocity, gamma <= 1, or data that generate vacuum (pressure positivity condition,
// Toro (4.40), violated). Throws std::runtime_error if the Newton iteration for p* fails.
RiemannSolution solveRiemann(const GasState& left, const GasState& right, double gamma_left,
                             double gamma_right);

}  // namespace lagremap
