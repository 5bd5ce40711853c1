#include "howell_ball.hpp"

#include <cmath>
#include <stdexcept>

namespace lagremap {
namespace {

constexpr double kPi = 3.14159265358979323846;

double F(double x, double B) {
  return (x + B) * std::log(x + B) - (x > 0.0 ? x * std::log(x) : 0.0);
}

}  // namespace

double howellBallWork(double yield_stress, double ri, double ro, double a) {
  const double B = ro * ro - ri * ri;
  return kPi / std::sqrt(3.0) * yield_stress * (F(ri * ri, B) - F(a * a, B));
}

ShellStop howellBallStop(double rho, double yield_stress, double ri, double ro, double v0,
                         bool incompressible_profile) {
  if (!(rho > 0 && yield_stress > 0 && v0 > 0 && ri > 0 && ro > ri)) {
    throw std::invalid_argument("Howell-Ball: need rho, Y, V0 > 0 and 0 < Ri < Ro");
  }
  const double B = ro * ro - ri * ri;
  const double k0 =
      incompressible_profile
          ? kPi * rho * (ri * v0) * (ri * v0) * std::log(ro / ri)
          : kPi * rho * v0 * v0 * (ro * ro * ro * ro - ri * ri * ri * ri) / (4.0 * ri * ri);
  auto work = [&](double a) { return howellBallWork(yield_stress, ri, ro, a); };
  ShellStop stop;
  if (k0 >= work(0.0)) return stop;  // energy enough to close the cavity
  double lo = 0.0, hi = ri;          // W rises as a falls
  for (int iteration = 0; iteration < 200 && hi - lo > 1e-15 * ri; ++iteration) {
    const double mid = 0.5 * (lo + hi);
    (work(mid) > k0 ? lo : hi) = mid;
  }
  const double a_stop = 0.5 * (lo + hi);
  stop.inner_radius = a_stop;
  stop.outer_radius = std::sqrt(a_stop * a_stop + B);
  // t = integral of da / |da/dt| from a_stop to Ri; a = a_stop + s^2 takes
  // out the 1 / sqrt(a - a_stop) of the stop (midpoint rule in s).
  const int n = 4000;
  const double s_max = std::sqrt(ri - a_stop), ds = s_max / n;
  for (int i = 0; i < n; ++i) {
    const double s = (i + 0.5) * ds, a = a_stop + s * s;
    const double b = std::sqrt(a * a + B);
    const double energy = k0 - work(a);
    stop.time += 2.0 * s * a * std::sqrt(kPi * rho * std::log(b / a) / energy) * ds;
  }
  return stop;
}

double elasticRingingSpeed(double rho, double yield_stress, double longitudinal_sound_speed) {
  return yield_stress / (rho * longitudinal_sound_speed);
}

}  // namespace lagremap
