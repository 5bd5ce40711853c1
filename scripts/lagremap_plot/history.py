"""history.csv: the time step, coloured by the limiter that set it, and
the drift of total energy and mass over the run."""

import math
from typing import Tuple

import numpy as np
import matplotlib.pyplot as plt
from matplotlib.ticker import SymmetricalLogLocator

from .figure import LABELS, SPARE_COLOURS, fmt_num, run_title, save
from .readers import Run


# Fixed colours per time-step limiter, so the same reason has the same colour
# in every run and runs can be compared side by side.  Unknown reasons (the
# C++ side may add some) get the remaining colours of the default cycle.
DT_REASON_COLOURS = {
    "cfl": "tab:blue",
    "volume": "tab:orange",
    "growth": "tab:green",
    "end": "tab:red",
    "initial": "tab:purple",
}


def relative_drift(q: np.ndarray) -> Tuple[np.ndarray, bool]:
    """(q - q0) / |q0|, or q - q0 if q0 is 0; the flag says which.

    Relative drift is what is comparable between problems of different
    scale; a zero initial value (possible for a quantity the C++ side adds
    later) would make it undefined, so fall back to the absolute drift.
    """
    q0 = q[0]
    if q0 != 0 and math.isfinite(q0):
        return (q - q0) / abs(q0), True
    return q - q0, False


def plot_history(run: Run, out_path: str) -> str:
    """Time step per reason, and conservation drift, over the run.

    The top panel shows which limiter controls Δt when (a run stuck on
    'volume' or 'growth' points at a problem); the bottom one shows the
    drift of total energy and mass, which a Lagrangian scheme should keep at
    round-off.  Symlog keeps exact zeros (mass in pure Lagrange mode) and
    the sign of the drift visible while still spanning many decades.
    """
    name = "history.csv"
    t = run.table(name, ["t", "dt", "dt_reason", "mass", "total_energy"])
    time, dt = t["t"], t["dt"]
    reasons = np.array([str(r).strip() for r in t["dt_reason"]])

    fig, (ax_dt, ax_drift) = plt.subplots(2, 1, figsize=(9, 8), sharex=True)

    ax_dt.plot(time, dt, "-", color="0.75", lw=0.8, zorder=1)
    spare = iter(SPARE_COLOURS * 10)
    # Legend in order of first appearance, which reads as the run's story.
    for reason in dict.fromkeys(reasons):
        sel = reasons == reason
        count = int(sel.sum())
        colour = DT_REASON_COLOURS.get(reason) or next(spare)
        ax_dt.scatter(time[sel], dt[sel], s=10, color=colour, zorder=2,
                      label=f"{reason} ({count} step{'s' if count != 1 else ''})")
    if np.any(dt > 0):
        ax_dt.set_yscale("log")
    ax_dt.set_ylabel(LABELS["dt"])
    ax_dt.grid(alpha=0.3, which="major")
    ax_dt.legend(title="Δt limited by", fontsize="small", loc="best")
    ax_dt.set_title("Time step")

    all_relative = True
    for field, label, colour in (("total_energy", "total energy", "tab:red"),
                                 ("mass", "mass", "tab:blue")):
        drift, relative = relative_drift(t[field])
        all_relative &= relative
        kind = "" if relative else ", absolute"
        ax_drift.plot(time, drift, "-", lw=1.2, color=colour,
                      label=f"{label} (final {drift[-1]:+.2e}{kind})")
    # Below ~1e-16 relative drift is round-off: plot that band linearly.
    ax_drift.set_yscale("symlog", linthresh=1e-16, linscale=0.5)
    ax_drift.yaxis.set_minor_locator(
        SymmetricalLogLocator(base=10, linthresh=1e-16, subs=range(2, 10)))
    ax_drift.axhline(0.0, color="0.5", lw=0.6)
    ax_drift.set_xlabel(LABELS["t"])
    ax_drift.set_ylabel("relative drift (q − q₀)/|q₀|" if all_relative
                        else "drift q − q₀")
    ax_drift.grid(alpha=0.3, which="major")
    ax_drift.legend(fontsize="small", loc="best")
    ax_drift.set_title("Conservation drift")

    s = run.summary
    title = run_title(run, "History")
    perf = []
    if "steps" in s:
        perf.append(f"{s['steps']} steps")
    if "wall_seconds" in s:
        perf.append(f"wall {fmt_num(s['wall_seconds'])} s")
    total = (s.get("cell_steps_per_second") or {}).get("total") \
        if isinstance(s.get("cell_steps_per_second"), dict) else None
    if total is not None:
        perf.append(f"{fmt_num(total, '.3e')} cell-steps/s")
    if perf:
        title += "\n" + ", ".join(perf)
    fig.suptitle(title)
    fig.tight_layout()
    return save(fig, out_path)
