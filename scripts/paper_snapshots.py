#!/usr/bin/env python3
"""Simulated contact snapshots in the style of the paper's Figs. 16, 18 and 21
(docs/experiments-simulated.md): for each run, the contact at rest before the shift and at
later shifts, with the area gained since rest red, the area lost blue, the area kept grey,
and the indenter's axis as a white line (the paper's line "in the center of the contact
with respect to the rigid indenter"); the sphere moves to the right. A shear run's fields
are in the indenter's frame (the contact split into front and rear at its axis, x = 0),
the paper's film in the rubber's: a contact that slides whole is still under the sphere,
so the panels compare shapes about the axis, as the paper's front and rear areas do.

    adhesim run scenarios/layer/paper_r22_shear.toml --set output.snapshot_every=1 --out OUT_A
    adhesim run scenarios/layer/paper_r22_shear.toml --set protocol.press_depth=0.2 \\
        --set protocol.depth=0 --set output.snapshot_every=1 --out OUT_B
    adhesim run scenarios/layer/paper_r22_shear.toml --set protocol.press_depth=0.2 \\
        --set protocol.depth=-0.015 --set output.snapshot_every=1 --out OUT_C
    python3 scripts/paper_snapshots.py OUT.png 0.1,0.3,0.6 OUT_A OUT_B OUT_C

The second argument lists the shifts (in the run's length unit) of the later columns: each
column shows the first recorded step at or beyond it. Prints, per panel, the areas kept,
gained and lost. Needs numpy and matplotlib.
"""
import csv
import sys
from pathlib import Path

import numpy as np
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

KEPT = (0.35, 0.35, 0.35)
GAINED = (0.84, 0.10, 0.11)
LOST = (0.12, 0.35, 0.86)


def load(run: Path):
    """The run's recorded contacts by step, the steps' shifts and phases, and the grid."""
    fields = np.load(run / "fields.npz")
    rows = {int(r["step"]): r for r in csv.DictReader(open(run / "curve.csv"))}
    steps = [int(s) for s in fields["step"]]
    missing = [s for s in steps if s not in rows]
    if missing:
        sys.exit(f"{run}: steps {missing[:3]} of fields.npz are not in curve.csv")
    return fields, steps, rows


def panel(ax, contact, reference, x, y, axis, title):
    image = np.ones(contact.shape + (3,))
    image[contact & reference] = KEPT
    image[contact & ~reference] = GAINED
    image[~contact & reference] = LOST
    ax.imshow(image, origin="lower", extent=(x[0], x[-1], y[0], y[-1]), interpolation="nearest")
    ax.axvline(axis, color="white", linewidth=1.5)
    ax.axvline(axis, color="black", linewidth=0.5, linestyle=":")
    ax.set_title(title, fontsize=9)
    ax.set_xticks([])
    ax.set_yticks([])


def main() -> None:
    if len(sys.argv) < 4:
        sys.exit("usage: paper_snapshots.py OUT.png SHIFT,SHIFT,... RUN [RUN ...]")
    path, shifts = sys.argv[1], [float(s) for s in sys.argv[2].split(",")]
    runs = [Path(p) for p in sys.argv[3:]]
    fig, axes = plt.subplots(len(runs), 1 + len(shifts), figsize=(2.6 * (1 + len(shifts)), 2.7 * len(runs)),
                             squeeze=False)
    for row, run in enumerate(runs):
        fields, steps, rows = load(run)
        x, y = fields["x"], fields["y"]
        at_rest = [s for s in steps if rows[s]["phase"] != "shear"]
        if not at_rest:
            sys.exit(f"{run}: no recorded step before the shift (record it with output.snapshot_every = 1)")
        rest = at_rest[-1]
        contact = {s: fields["contact"][i] for i, s in enumerate(steps)}
        chosen = [rest]
        for shift in shifts:
            later = [s for s in steps if rows[s]["phase"] == "shear" and float(rows[s]["x"]) >= shift - 1e-12]
            if not later:
                sys.exit(f"{run}: no recorded shear step at or beyond x = {shift}")
            chosen.append(later[0])
        union = np.zeros_like(contact[rest])
        for s in chosen:
            union |= contact[s]
        rows_in, cols_in = np.nonzero(union)
        margin = 3
        r0, r1 = max(rows_in.min() - margin, 0), min(rows_in.max() + margin + 1, union.shape[0])
        c0, c1 = max(cols_in.min() - margin, 0), min(cols_in.max() + margin + 1, union.shape[1])
        depth = float(rows[rest]["d"])
        for column, s in enumerate(chosen):
            record = rows[s]
            shift = float(record["x"])
            kept = int((contact[s] & contact[rest]).sum())
            gained = int((contact[s] & ~contact[rest]).sum())
            lost = int((~contact[s] & contact[rest]).sum())
            label = f"d = {depth:g}: at rest" if column == 0 else f"x = {shift:.2f}: +{gained} / −{lost}"
            panel(axes[row][column], contact[s][r0:r1, c0:c1], contact[rest][r0:r1, c0:c1],
                  x[c0:c1], y[r0:r1], 0.0, label)
            print(f"{run.name}: step {s}, x = {shift:.3f}: kept {kept}, gained {gained}, lost {lost} elements")
    handles = [plt.Rectangle((0, 0), 1, 1, color=c) for c in (KEPT, GAINED, LOST)]
    fig.legend(handles, ["kept since rest", "gained", "lost"], loc="lower center", ncol=3, frameon=False)
    fig.tight_layout(rect=(0, 0.05, 1, 1))
    fig.savefig(path, dpi=110)


if __name__ == "__main__":
    main()
