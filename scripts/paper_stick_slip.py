#!/usr/bin/env python3
"""The paper's slide pulled through a spring, as a time series in the style of its Figs. 17
and 19 (docs/experiments-simulated.md): the tangential force with the kinetic and static
bounds times the area, the front, rear and total contact areas, and τ = F_T/A, against the
drive's position X, with the indenter's axis x beside it.

    adhesim run scenarios/layer/paper_r22_stick_slip.toml --out out/r22_stick_slip
    python3 scripts/paper_stick_slip.py out/r22_stick_slip docs/img/experiment/paper_r22_stick_slip.png

Prints the slip events of the last third of the stroke (the steps where the force falls):
the force before and after each, the axis's jump, and the drive's travel between events.
Needs matplotlib.
"""
import csv
import json
import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main() -> None:
    out, path = Path(sys.argv[1]), sys.argv[2]
    rows = [r for r in csv.DictReader(open(out / "curve.csv")) if r["phase"] != "approach"]
    if not rows or "drive_x" not in rows[0]:
        sys.exit(f"{out / 'curve.csv'} has no drive_x column: run with protocol.drive_stiffness")
    friction = json.load(open(out / "summary.json"))["inputs"]["friction"]
    column = {name: [float(r[name]) for r in rows] for name in ("drive_x", "x", "force_tangential", "area", "area_front", "area_rear")}
    drive, axis, force, area = column["drive_x"], column["x"], column["force_tangential"], column["area"]
    kinetic = friction["shear_strength"]
    static = friction.get("static_shear_strength", kinetic)
    events = [k for k in range(1, len(rows)) if force[k] < force[k - 1]]
    last = [k for k in events if drive[k] >= drive[-1] * 2 / 3]
    for before, k in zip([None] + last, last):
        travel = f", {drive[k] - drive[before]:.4f} of drive since the last" if before is not None else ""
        print(
            f"slip event at X = {drive[k]:.3f}: F {force[k - 1]:.4f} -> {force[k]:.4f} "
            f"(tau {1e3 * force[k - 1] / area[k - 1]:.2f} -> {1e3 * force[k] / area[k]:.2f} kPa), "
            f"axis jumps by {axis[k] - axis[k - 1]:.4f}{travel}"
        )
    print(f"{len(events)} slip events over the stroke")
    figure, (top, middle, bottom) = plt.subplots(3, 1, figsize=(8, 8.4), sharex=True)
    top.plot(drive, force, "-", lw=1, color="tab:blue", label="$F_T$ (adhesim)")
    top.plot(drive, [kinetic * a for a in area], "--", color="tab:orange", label=r"$\tau_0 A$ (kinetic)")
    top.plot(drive, [static * a for a in area], ":", color="tab:red", label=r"$\tau_s A$ (static)")
    top.set_ylabel("tangential force $F_T$ (N)")
    top.legend(loc="lower right")
    twin = top.twinx()
    twin.plot(drive, axis, "-", lw=0.8, color="0.45")
    twin.set_ylabel("indenter's axis $x$ (mm), grey", color="0.45")
    top.set_title("pulled through a spring: stick phases and slip events")
    middle.plot(drive, area, "-", lw=1, color="k", label="total")
    middle.plot(drive, column["area_front"], "-", lw=1, color="tab:red", label="front")
    middle.plot(drive, column["area_rear"], "-", lw=1, color="tab:blue", label="rear")
    middle.set_ylabel("contact area (mm²)")
    middle.legend(loc="center right")
    bottom.plot(drive, [1e3 * f / a for f, a in zip(force, area)], "-", lw=1, color="tab:green")
    bottom.axhline(1e3 * kinetic, ls="--", color="tab:orange", lw=0.8)
    bottom.set_ylabel(r"$\tau = F_T/A$ (kPa)")
    bottom.set_xlabel("drive position $X$ (mm)")
    figure.tight_layout()
    figure.savefig(path, dpi=110)


if __name__ == "__main__":
    main()
