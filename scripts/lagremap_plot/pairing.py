"""The runs an overlay draws: the lagrange run a remap run is compared with
(--compare's, or one found next to it), --also's further runs, their line
styles and labels, their CSV tables, and the overlay's title."""

import os
from dataclasses import dataclass
from typing import Dict, List, Optional, Tuple

import numpy as np

from .errors import InputError, note
from .figure import fmt_num, run_title
from .readers import Run, read_run


def partner_candidates(run: Run) -> List[str]:
    """Where a remap run's lagrange reference usually is: a sibling directory
    named after it (``out/taylor`` -> ``out/taylor_lagrange``, what
    scripts/run.sh writes), or after the problem."""
    directory = os.path.normpath(run.dir)
    parent, base = os.path.split(directory)
    names = [base + "_lagrange", base + "-lagrange"]
    if "remap" in base:
        names.append(base.replace("remap", "lagrange"))
    if run.problem:
        names += [run.problem + "_lagrange", run.problem + "-lagrange",
                  os.path.join("lagrange", run.problem)]
    paths = []
    for name in names:
        path = os.path.join(parent, name)
        if os.path.normpath(path) != directory and path not in paths:
            paths.append(path)
    return paths


def find_partner(run: Run, compare: Optional[str], auto: bool) -> Optional[Run]:
    """The run to overlay with DIR's: --compare's, else (remap runs) a
    lagrange run found next to DIR.  Missing or unsuitable: a note, None."""
    if compare:
        try:
            partner = read_run(compare)
        except InputError as exc:
            note(f"--compare: {exc}; drawing {run.dir} alone")
            return None
    elif auto and run.mode == "remap":
        found = [p for p in partner_candidates(run)
                 if os.path.isfile(os.path.join(p, "summary.json"))]
        partner = None
        for path in found:
            try:
                candidate = read_run(path)
            except InputError:
                continue
            if candidate.mode == "lagrange" and candidate.problem == run.problem:
                partner = candidate
                break
        if partner is None:
            note(f"no lagrange run of {run.problem or '?'} next to {run.dir} "
                 f"(looked for {', '.join(os.path.basename(p) for p in partner_candidates(run)[:2])}); "
                 f"the overlays show the remap run alone (--compare LAGRANGE_DIR names one)")
            return None
    else:
        return None
    if partner.problem != run.problem:
        note(f"--compare: {partner.dir} is a '{partner.problem}' run, not "
             f"'{run.problem}'; drawing {run.dir} alone")
        return None
    if os.path.realpath(partner.dir) == os.path.realpath(run.dir):
        return None
    return partner


# Line style per mode, the paper's convention: lagrange solid, remap dashed.
MODE_STYLE = {
    "lagrange": {"ls": "-", "color": "tab:blue"},
    "remap": {"ls": "--", "color": "tab:red"},
}
SECOND_STYLE = {"ls": ":", "color": "tab:green"}  # a compared run of the same mode
EXTRA_STYLES = [{"ls": "-.", "color": "tab:purple"}, {"ls": ":", "color": "tab:orange"}]
LINE_WORDS = {"-": "solid", "--": "dashed", ":": "dotted"}


@dataclass
class Curve:
    """One run as drawn in an overlay: its label and line style."""
    run: Run
    label: str
    style: Dict[str, str]


def overlay_runs(run: Run) -> List[Curve]:
    """DIR's run and its partner, lagrange first (drawn under the remap one).

    Two runs of the same mode (a --compare between two remap runs) are told
    apart by their directory names and a dotted second line."""
    runs = [run] + ([run.partner] if run.partner is not None else [])
    runs.sort(key=lambda r: 0 if r.mode == "lagrange" else 1)
    same_mode = len(runs) == 2 and runs[0].mode == runs[1].mode
    curves = []
    for i, r in enumerate(runs):
        label = r.mode
        if same_mode:
            label += f" ({os.path.basename(os.path.normpath(r.dir))})"
        elif closure_of(r) and any(closure_of(x) for x in run.extras):
            label += f" ({closure_of(r)})"
        style = dict(SECOND_STYLE if same_mode and i == 1
                     else MODE_STYLE.get(r.mode, MODE_STYLE["lagrange"]))
        curves.append(Curve(r, label, style))
    # further runs of the same problem (--also: e.g. the other mixed-cell closure)
    for i, r in enumerate(run.extras):
        label = f"{r.mode} ({closure_of(r) or os.path.basename(os.path.normpath(r.dir))})"
        curves.append(Curve(r, label, dict(EXTRA_STYLES[i % len(EXTRA_STYLES)])))
    return curves


def closure_of(run: Run) -> Optional[str]:
    """The mixed-cell closure of a remap run (summary's mixture.closure)."""
    return ((run.summary or {}).get("config") or {}).get("mixture.closure")


def curve_tables(run: Run, name: str, columns: List[str]) -> List[Tuple[Curve, Dict[str, np.ndarray]]]:
    """The CSV `name` of every run of the overlay.  DIR's own must be
    readable (InputError otherwise); a partner without it is left out with
    a note, so the figure still shows DIR's run."""
    result = []
    for curve in overlay_runs(run):
        if curve.run is run:
            result.append((curve, run.table(name, columns)))
            continue
        if not curve.run.has(name):
            note(f"{curve.run.dir} has no {name}; {name} drawn without its {curve.label} curve")
            continue
        try:
            result.append((curve, curve.run.table(name, columns)))
        except InputError as exc:
            note(f"{curve.run.dir}: {exc}; drawn without its {curve.label} curve")
    return result


def pair_title(run: Run, what: str) -> str:
    """Title of an overlay: the runs it compares, or run_title's line alone."""
    if run.partner is None:
        return run_title(run, what)
    parts = []
    for curve in overlay_runs(run):
        s = curve.run.summary
        cells = f", {s['cells']} cells" if "cells" in s else ""
        line = LINE_WORDS.get(curve.style.get("ls", ""), "points")
        parts.append(f"{curve.label} ({line}{cells})")
    t_end = run.summary.get("t_end")
    when = f", t = {fmt_num(t_end)} s" if t_end is not None else ""
    return f"{what}\n{run.problem}: " + " vs ".join(parts) + when
