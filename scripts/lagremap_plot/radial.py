"""radial.csv: one field against radius, a point per cell, with the exact
solution and the shock radii of the run's check."""

import numpy as np
import matplotlib.pyplot as plt
from matplotlib.lines import Line2D

from .figure import LABELS, field_word, fmt_num, run_title, save
from .readers import Run


def plot_radial(run: Run, out_path: str, field: str) -> str:
    """Scatter of one field against radius, one point per cell.

    Every cell is drawn (not a binned average) because the spread at a given
    radius is exactly what shows mesh imprinting and loss of symmetry.  The
    shock radius lines show at a glance whether the blast wave is where the
    similarity solution says and where the check measured it.
    """
    name = "radial.csv"
    t = run.table(name, ["r", field])
    r, v = t["r"], t[field]
    n = len(r)
    # Dense data needs faint points or the profile becomes a solid blob;
    # sparse data needs opaque ones to be visible at all.
    alpha = float(np.clip(10000.0 / max(n, 1), 0.1, 0.8))
    size = 4.0 if n < 5000 else 2.0 if n < 100000 else 1.0

    fig, ax = plt.subplots(figsize=(8, 5.5))
    ax.scatter(r, v, s=size, alpha=alpha, color="tab:blue", linewidths=0,
               rasterized=True)
    # Proxy handle: the real points are too faint to read in a legend.
    handles = [Line2D([], [], ls="", marker="o", ms=4, color="tab:blue",
                      label=f"cells ({n})")]
    # The exact solution at the same centroids (sedov's radial.csv carries it):
    # the curve the cells should lie on.
    exact = t.get(f"{field}_exact")
    if exact is not None and exact.dtype.kind == "f" and np.isfinite(exact).any():
        order = np.argsort(r)
        handles += ax.plot(r[order], exact[order], color="black", lw=1.0,
                           label="exact solution")

    shock = run.check("shock_radius")
    if shock:
        ref, val = shock.get("reference"), shock.get("value")
        if isinstance(ref, (int, float)):
            handles.append(ax.axvline(ref, color="black", ls="--", lw=1.2,
                                      label=f"reference shock radius "
                                            f"{fmt_num(ref, '.4g')} m"))
        if isinstance(val, (int, float)):
            handles.append(ax.axvline(val, color="tab:red", ls="-", lw=1.2,
                                      label=f"measured shock radius "
                                            f"{fmt_num(val, '.4g')} m"))

    ax.set_xlabel(LABELS["r"])
    ax.set_ylabel(LABELS[field])
    ax.set_xlim(left=0.0)
    ax.grid(alpha=0.3)
    ax.legend(handles=handles, loc="best", fontsize="small")
    ax.set_title(run_title(run, f"Radial {field_word(field)}"))
    fig.tight_layout()
    return save(fig, out_path)
