"""Per-problem curves: the sod and wilkins profiles along x, the pile's
wall stress and the beam's tip displacement against time (lagrange solid,
remap dashed where both runs are at hand)."""

import numpy as np
import matplotlib.pyplot as plt

from .figure import LABELS, check_text, run_title, save
from .pairing import curve_tables, pair_title
from .readers import Run


def plot_sod_profiles(run: Run, out_path: str) -> str:
    """Sod shock tube: numeric vs exact density, velocity, pressure, energy.

    Numeric values are markers and the exact Riemann solution a line, so
    over- and undershoots at the shock and contact, and the smearing width,
    are visible per cell.  The L1 density error from the summary goes in the
    title because it is the number the regression check judges.
    """
    name = "sod_profile.csv"
    fields = ["rho", "u", "p", "e"]
    t = run.table(name, ["x"] + fields)
    order = np.argsort(t["x"], kind="stable")
    x = t["x"][order]

    fig, axes = plt.subplots(2, 2, figsize=(11, 8), sharex=True)
    for ax, field in zip(axes.flat, fields):
        exact = t.get(f"{field}_exact")
        if exact is not None and exact.dtype.kind == "f":
            ax.plot(x, exact[order], "-", color="black", lw=1.2,
                    label="exact", zorder=1)
        ax.plot(x, t[field][order], "o", ms=3, mfc="none", mew=0.8,
                color="tab:blue", label="lagremap", zorder=2)
        ax.set_ylabel(LABELS[field])
        ax.grid(alpha=0.3)
        ax.legend(loc="best", fontsize="small")
    for ax in axes[-1]:
        ax.set_xlabel(LABELS["x"])

    title = run_title(run, "Sod shock tube")
    l1 = check_text(run.check("l1_density"), "L1 density error")
    if l1:
        title += "\n" + l1
    fig.suptitle(title)
    fig.tight_layout()
    return save(fig, out_path)


def plot_wilkins_profiles(run: Run, out_path: str) -> str:
    """Flyer plate: density, velocity and sigma_xx along x (paper Fig. 3),
    lagrange solid and remap dashed when both runs are at hand.

    Thin horizontal lines mark the exact plastic state and elastic precursor
    levels of the default impact, so the two-wave structure (precursor
    plateau ahead of the plastic shock) can be judged by eye.

    The figure shows the aluminium only.  A remap run also holds the light
    gas behind the flyer (x from -0.04 to the flyer's back face): its cells
    (alpha_al < 1/2) are left out, the density drawn is aluminium's own
    (rho_al, not the cell's mixture density, which falls to ~1 kg/m3 over
    the smeared back face), and the x axis spans the aluminium of the runs,
    the lagrange run's whole mesh, so both curves fill the same frame.
    Profiles written before the alpha_al column are drawn whole.
    """
    fields = ["rho", "u", "sigma_xx"]
    curves = curve_tables(run, "wilkins_profile.csv", ["x"] + fields)
    exact = {"rho": (2985.6, 2800.2), "u": (400.0, 35.2), "sigma_xx": (-6.637e9, -0.636e9)}
    drawn = []  # (curve, {field: values on the aluminium cells, in x order})
    gas_note = None
    for curve, t in curves:
        order = np.argsort(t["x"], kind="stable")
        keep = np.ones(len(order), dtype=bool)
        columns = {f: t[f][order] for f in ["x"] + fields}
        alpha = t.get("alpha_al")
        if alpha is not None and alpha.dtype.kind == "f":
            keep = alpha[order] >= 0.5
            if "rho_al" in t and t["rho_al"].dtype.kind == "f":
                columns["rho"] = t["rho_al"][order]
            if not keep.all() and keep.any():
                x_gas = columns["x"][~keep]
                gas_note = (f"{curve.label}: cells with alpha_al < 1/2 (the gas, "
                            f"x ≤ {x_gas.max():.4g} m) not drawn; ρ of the aluminium")
        drawn.append((curve, {f: v[keep] for f, v in columns.items()}))
    fig, axes = plt.subplots(3, 1, figsize=(9, 9.5), sharex=True)
    for ax, field in zip(axes, fields):
        plastic, precursor = exact[field]
        ax.axhline(plastic, ls="-", lw=0.6, color="0.35", label="exact plastic state")
        ax.axhline(precursor, ls="-.", lw=0.6, color="0.35", label="exact elastic precursor")
        for curve, columns in drawn:
            ax.plot(columns["x"], columns[field], lw=1.2, label=curve.label, **curve.style)
        ax.set_ylabel(LABELS[field])
        ax.grid(alpha=0.3)
    xs = [columns["x"] for _, columns in drawn if len(columns["x"])]
    if xs:
        lo = min(x.min() for x in xs)
        hi = max(x.max() for x in xs)
        pad = 0.02 * (hi - lo)
        axes[-1].set_xlim(lo - pad, hi + pad)
    axes[0].legend(loc="best", fontsize="small")
    axes[-1].set_xlabel(LABELS["x"])
    title = pair_title(run, "Wilkins flyer plate")
    if gas_note:
        title += "\n" + gas_note
    fig.suptitle(title)
    fig.tight_layout()
    return save(fig, out_path)


def plot_pile_wall_stress(run: Run, out_path: str) -> str:
    """Pile driving: wall sigma_xx against time with the exact square wave,
    lagrange solid and remap dashed when both runs are at hand.

    The exact linear-elastic answer is 0 / twice the imposed stress / 0 on
    [0, L/c] / [L/c, 3L/c] / [3L/c, 4L/c]; overshoot at the fronts and the
    arrival time are what to look at.
    """
    curves = curve_tables(run, "pile_wall_stress.csv", ["t", "sigma_xx", "exact"])
    fig, ax = plt.subplots(figsize=(9, 4.8))
    own = next(t for curve, t in curves if curve.run is run)
    ax.plot(own["t"], own["exact"], "-", color="black", lw=0.8,
            label="exact (linear elastic)")
    for curve, t in curves:
        ax.plot(t["t"], t["sigma_xx"], lw=1.2, label=curve.label, **curve.style)
    ax.set_xlabel(LABELS["t"])
    ax.set_ylabel("wall stress σ_xx [Pa]")
    ax.grid(alpha=0.3)
    ax.legend(loc="best", fontsize="small")
    ax.set_title(pair_title(run, "Pile driving: stress on the wall"))
    fig.tight_layout()
    return save(fig, out_path)


def plot_beam_tip(run: Run, out_path: str) -> str:
    """Oscillating plate: vertical tip displacement against time (paper
    Fig. 12), the lagrange run a curve and the remap run points, with the
    theoretical half period marked."""
    curves = curve_tables(run, "beam_tip.csv", ["t", "tip_displacement_y"])
    fig, ax = plt.subplots(figsize=(9, 4.8))
    ax.axhline(0.0, color="0.5", lw=0.6)
    for curve, t in curves:
        if curve.run.mode == "remap":
            # Points, as the paper: about 40 of them over the run.
            every = max(1, len(t["t"]) // 40)
            ax.plot(t["t"][::every], t["tip_displacement_y"][::every], "o", ms=4,
                    mfc="none", color=curve.style["color"], label=f"{curve.label} (points)")
        else:
            ax.plot(t["t"], t["tip_displacement_y"], lw=1.2, label=curve.label, **curve.style)
    check = run.check("half_period")
    if check and isinstance(check.get("reference"), (int, float)):
        ax.axvline(check["reference"], ls="-.", color="black", lw=0.8,
                   label=f"half period (Timoshenko) {1e6 * check['reference']:.2f} µs")
    ax.set_xlabel(LABELS["t"])
    ax.set_ylabel("tip displacement y [m]")
    ax.grid(alpha=0.3)
    ax.legend(loc="best", fontsize="small")
    ax.set_title(pair_title(run, "Oscillating plate: tip displacement"))
    fig.tight_layout()
    return save(fig, out_path)
