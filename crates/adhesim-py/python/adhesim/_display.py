"""Rich display of results in a notebook: ``RunResult._repr_html_`` (a summary table and,
when matplotlib is importable, the force curve as an inline PNG)."""

from __future__ import annotations

import base64
import html
import io
from typing import Any, List, Optional, Tuple

# The results the table shows, when the summary has them (docs/output.md, summary.json).
KEY_RESULTS = (
    "max_adhesive_force",
    "pull_off_depth",
    "gamma_approach",
    "gamma_pulloff",
    "gamma_approach_norm",
    "gamma_pulloff_norm",
    "dissipated_energy",
    "mean_tangential_force",
    "largest_contact_elements",
    "border_contact",
)


def number(value: Any) -> str:
    """A summary value as the table and the repr show it: floats with 6 significant digits."""
    if isinstance(value, float):
        return f"{value:.6g}"
    return str(value)


def grid_text(summary: dict) -> Optional[str]:
    """``"64×64, size 0.25, free"`` from the summary's inputs, or None."""
    grid = summary.get("inputs", {}).get("grid")
    if not isinstance(grid, dict) or "n" not in grid:
        return None
    n = grid["n"]
    return f"{n}×{n}, size {number(grid.get('size'))}, {grid.get('boundary', 'free')}"


def summary_rows(result) -> List[Tuple[str, str]]:
    """(name, value) rows: the run's shape, then the key results present and not None."""
    curve = result.curve_arrays
    steps = len(next(iter(curve.values()))) if curve else 0
    rows = []
    grid = grid_text(result.summary)
    if grid is not None:
        rows.append(("grid", grid))
    rows += [("steps", str(steps)), ("snapshots", str(len(result.snapshots)))]
    if result.out is not None:
        rows.append(("out", str(result.out)))
    results = result.summary.get("results", {})
    for key in KEY_RESULTS:
        if results.get(key) is not None:
            rows.append((key, number(results[key])))
    wall = result.summary.get("performance", {}).get("wall_seconds")
    if wall is not None:
        rows.append(("wall_seconds", number(wall)))
    return rows


def force_curve_png(result) -> Optional[str]:
    """The force F against the depth d (one line per phase) as base64 PNG, or None
    without matplotlib or without those columns. matplotlib's object API, not pyplot: no
    global figure state, no backend change."""
    curve = result.curve_arrays
    if "d" not in curve or "force_normal" not in curve:
        return None
    try:
        from matplotlib.figure import Figure
    except ImportError:
        return None
    figure = Figure(figsize=(4.5, 3.2))
    axes = figure.add_subplot()
    phases = curve.get("phase")
    labels = list(dict.fromkeys(phases.tolist())) if phases is not None else [None]
    for phase in labels:
        rows = slice(None) if phase is None else phases == phase
        axes.plot(curve["d"][rows], curve["force_normal"][rows], lw=0.9, label=phase)
    axes.set_xlabel("depth d")
    axes.set_ylabel("force F")
    if phases is not None:
        axes.legend(fontsize="small")
    figure.tight_layout()
    buffer = io.BytesIO()
    figure.savefig(buffer, format="png", dpi=80)
    return base64.b64encode(buffer.getvalue()).decode("ascii")


def run_result_html(result) -> str:
    """The HTML of ``RunResult._repr_html_``."""
    body = "".join(
        f"<tr><th style='text-align:left'>{html.escape(name)}</th>"
        f"<td style='text-align:left'>{html.escape(value)}</td></tr>"
        for name, value in summary_rows(result)
    )
    table = f"<table class='adhesim-summary'><caption>RunResult</caption>{body}</table>"
    png = force_curve_png(result)
    if png is None:
        return f"<div>{table}</div>"
    image = f"<img alt='force curve' src='data:image/png;base64,{png}'/>"
    return f"<div style='display:flex;gap:1em;align-items:flex-start'>{table}{image}</div>"
