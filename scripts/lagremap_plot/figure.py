"""What every figure shares: the resolution, axis labels with SI units,
spare colours, number formatting, the title line naming the run, the text
of a check, and save."""

from typing import Optional

import matplotlib.pyplot as plt

from .readers import Run


DPI = 120


# Axis labels with SI units, shared by every plot that shows the quantity so
# the same field is labelled the same way in every figure.
LABELS = {
    "x": "x [m]",
    "y": "y [m]",
    "r": "r [m]",
    "t": "t [s]",
    "dt": "Δt [s]",
    "rho": "density ρ [kg/m³]",
    "u": "velocity u [m/s]",
    "p": "pressure p [Pa]",
    "e": "specific internal energy e [J/kg]",
    "speed": "speed |u| [m/s]",
    "sigma_xx": "stress σ_xx [Pa]",
}


# Colours for what has no fixed colour (a time-step reason the C++ side
# added, an unknown shell radius column), taken in turn.
SPARE_COLOURS = ["tab:brown", "tab:pink", "tab:olive", "tab:cyan", "tab:gray"]


def fmt_num(value, spec: str = ".3g", missing: str = "?") -> str:
    """Format a number from JSON, tolerating absent or non-numeric values."""
    if isinstance(value, (int, float)) and not isinstance(value, bool):
        return format(value, spec)
    return missing


def run_title(run: Run, what: str) -> str:
    """Common first title line, so every figure says which run it shows."""
    s = run.summary
    parts = [str(s.get("problem", "?"))]
    if "mode" in s:
        parts.append(str(s["mode"]))
    if "order" in s:
        parts.append(f"order {s['order']}")
    if "cells" in s:
        parts.append(f"{s['cells']} cells")
    if "t_end" in s:
        parts.append(f"t = {fmt_num(s['t_end'])} s")
    return f"{what}: " + ", ".join(parts)


def check_text(check: Optional[dict], label: str) -> Optional[str]:
    """Describe a summary check as 'label = v (tolerance t, PASS)'."""
    if check is None or "value" not in check:
        return None
    text = f"{label} = {fmt_num(check['value'], '.3e')}"
    extras = []
    if "tolerance" in check:
        extras.append(f"tolerance {fmt_num(check['tolerance'], '.2e')}")
    if check.get("applies") is False:
        extras.append("n/a: " + check.get("not_applicable", "not this case"))
    elif "pass" in check:
        extras.append("PASS" if check["pass"] else "FAIL")
    return text + (f" ({', '.join(extras)})" if extras else "")


def save(fig, out_path: str) -> str:
    """Write the figure at the project-wide DPI and free its memory."""
    fig.savefig(out_path, dpi=DPI)
    plt.close(fig)
    return out_path


def field_word(field: str) -> str:
    return {"rho": "density", "p": "pressure"}.get(field, field)
