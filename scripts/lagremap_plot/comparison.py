"""comparison.md: the remap run's checks beside its lagrange partner's, with
the references and the paper's numbers, as a Markdown table."""

import os
from typing import List, Optional

from .figure import fmt_num
from .pairing import overlay_runs
from .readers import Run


def comparison_rows(run: Run) -> List[List[str]]:
    """One row per check of the remap run: its value and reference, the
    lagrange run's value, the lagrange reference and the paper's number."""
    curves = {c.run.mode: c.run for c in overlay_runs(run)}
    remap, lagrange = curves.get("remap"), curves.get("lagrange")
    if remap is None or lagrange is None:
        return []
    rows = []
    for name, check in (remap.summary.get("checks") or {}).items():
        if not isinstance(check, dict):
            continue
        ours = lagrange.check(name) or {}
        numbers = (check.get("value"), check.get("reference"), ours.get("value"),
                   check.get("lagrange_reference"), check.get("paper"))
        verdict = ("n/a" if check.get("applies") is False
                   else {True: "pass", False: "FAIL"}.get(check.get("pass"), "?"))
        if check.get("source"):
            verdict += f" ({check['source']})"
        rows.append([name] + [fmt_num(v, ".5g", "–") for v in numbers] + [verdict])
    return rows


def write_comparison(run: Run, out_dir: str) -> Optional[str]:
    """comparison.md: the remap checks next to the lagrange run's (a
    Markdown table; '–' where a run or the paper gives no number)."""
    rows = comparison_rows(run)
    if not rows:
        return None
    header = ["check", "remap", "remap reference", "lagrange (this pair)",
              "lagrange reference", "paper", "remap check"]
    lines = [f"{run.problem}: remap {run.summary.get('cells', '?')} cells vs lagrange "
             f"{run.partner.summary.get('cells', '?')} cells, t = {fmt_num(run.summary.get('t_end'))} s",
             "", "| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
    lines += ["| " + " | ".join(row) + " |" for row in rows]
    os.makedirs(out_dir, exist_ok=True)
    path = os.path.join(out_dir, "comparison.md")
    with open(path, "w") as f:
        f.write("\n".join(lines) + "\n")
    return path
