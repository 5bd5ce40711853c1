#!/usr/bin/python3
"""Reference star states for ExactRiemann.StiffenedGasIndependentReferences.

Usage: stiffened_riemann_reference.py   (needs mpmath; prints one line per problem)

Solves the Riemann problem of two stiffened gases, p = (gamma - 1) rho e - gamma p_inf, with
40 significant digits and without the shifted-pressure formulas of src/exact_riemann.cpp, so that
the two can only agree if both are right:
  - across a shock the specific volume v* follows from the Hugoniot energy equation
      e(p*, v*) - e(p_K, v_K) + (p* + p_K) / 2 (v* - v_K) = 0,  e(p, v) = (p + gamma p_inf) v / (gamma - 1),
    solved numerically; the velocity jump is sqrt((p* - p_K)(v_K - v*)) and the mass flux
    sqrt((p* - p_K) / (v_K - v*)) gives the shock speed;
  - across a rarefaction the velocity jump is the quadrature of dp / (rho a) along the isentrope
    (p + p_inf) / rho^gamma = const, a^2 = gamma (p + p_inf) / rho;
  - p* is found by bisection on u_L - du_L(p*) = u_R + du_R(p*).
Not run by ctest: its output is pasted into tests/test_exact_riemann.cpp.
"""

import mpmath as mp

mp.mp.dps = 40


def gas(rho, u, p, gamma, p_inf):
    return {k: mp.mpf(v) for k, v in dict(rho=rho, u=u, p=p, gamma=gamma, p_inf=p_inf).items()}


def internal_energy(p, v, g):
    return (p + g["gamma"] * g["p_inf"]) * v / (g["gamma"] - 1)


def volume_behind_shock(p_star, g):
    v0 = 1 / g["rho"]
    hugoniot = lambda v: (internal_energy(p_star, v, g) - internal_energy(g["p"], v0, g)
                          + (p_star + g["p"]) / 2 * (v - v0))
    # Between the infinite-strength limit and the undisturbed volume.
    v_min = v0 * (g["gamma"] - 1) / (g["gamma"] + 1)
    return mp.findroot(hugoniot, (v_min, v0), solver="anderson")


def density_on_isentrope(p, g):
    return g["rho"] * ((p + g["p_inf"]) / (g["p"] + g["p_inf"])) ** (1 / g["gamma"])


def velocity_drop(p_star, g):
    """Velocity change across the wave into gas g that brings it to p_star (Toro's f_K)."""
    if p_star > g["p"]:
        return mp.sqrt((p_star - g["p"]) * (1 / g["rho"] - volume_behind_shock(p_star, g)))

    def slowness(p):
        rho = density_on_isentrope(p, g)
        return 1 / (rho * mp.sqrt(g["gamma"] * (p + g["p_inf"]) / rho))

    return -mp.quad(slowness, [p_star, g["p"]])


def solve(left, right):
    residual = lambda p: velocity_drop(p, left) + velocity_drop(p, right) + right["u"] - left["u"]
    scale = 1 + max(left["p_inf"], right["p_inf"], abs(left["p"]), abs(right["p"]))
    low = -min(left["p_inf"], right["p_inf"]) + mp.mpf(10) ** -30 * scale
    high = max(left["p"], right["p"], mp.mpf(1))
    while residual(high) < 0:
        high *= 2
    assert residual(low) < 0, "data generate vacuum"
    for _ in range(200):
        middle = (low + high) / 2
        if residual(middle) < 0:
            low = middle
        else:
            high = middle
    p_star = (low + high) / 2
    star = dict(p_star=p_star, u_star=(left["u"] + right["u"]) / 2
                + (velocity_drop(p_star, right) - velocity_drop(p_star, left)) / 2)
    for name, g, direction in (("left", left, -1), ("right", right, +1)):
        if p_star > g["p"]:
            v = volume_behind_shock(p_star, g)
            mass_flux = mp.sqrt((p_star - g["p"]) / (1 / g["rho"] - v))
            star["rho_star_" + name] = 1 / v
            star[name + "_shock_speed"] = g["u"] + direction * mass_flux / g["rho"]
        else:
            star["rho_star_" + name] = density_on_isentrope(p_star, g)
            star[name + "_shock_speed"] = None  # a rarefaction
    return star


# The problems of tests/test_exact_riemann.cpp (SI units for the liquids).
PROBLEMS = {
    "water_air_shock_tube": (gas(1000, 0, 1e9, 4.4, 6e8), gas(50, 0, 1e5, 1.4, 0)),
    "air_helium_sod": (gas(1, 0, 1, 1.4, 0), gas(0.125, 0, 0.1, mp.mpf(5) / 3, 0)),
    "water_water_collision": (gas(1000, 100, 1e5, 4.4, 6e8), gas(1000, -100, 1e5, 4.4, 6e8)),
    "water_water_expansion": (gas(1000, -50, 1e5, 4.4, 6e8), gas(1000, 50, 1e5, 4.4, 6e8)),
    "two_liquids": (gas(1000, 20, 2e8, 4.4, 6e8), gas(1200, -10, 1e6, 2.8, 8.5e8)),
    "water_under_tension_air": (gas(1000, 0, -1e8, 4.4, 6e8), gas(1.2, 0, 1e5, 1.4, 0)),
}

if __name__ == "__main__":
    for problem, (left, right) in PROBLEMS.items():
        star = solve(left, right)
        print(problem, ", ".join(f"{key} = {mp.nstr(value, 17) if value is not None else '-'}"
                                 for key, value in star.items()), flush=True)
