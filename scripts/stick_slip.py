#!/usr/bin/env python3
"""Stick–slip under a compliant drive (docs/tangential.md, §Stick–slip).

    adhesim run scenarios/friction/stick_slip.toml --out out/stick_slip
    python3 scripts/stick_slip.py out/stick_slip docs/img/tangential/stick_slip.png

Left: the tangential force against the drive's position X, with the kinetic and static
shear strengths times the contact area. Right: the indenter's shift δ and the share of
the contact that sticks, against X (δ jumps ahead in each slip event). Prints every slip
event: the force before and after it and the indenter's jump. Needs matplotlib.
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
    rows = [r for r in csv.DictReader(open(out / "curve.csv")) if r["phase"] == "shear"]
    if "drive_x" not in rows[0]:
        sys.exit(f"{out / 'curve.csv'} has no drive_x column: run with protocol.drive_stiffness")
    scenario = json.load(open(out / "summary.json"))["inputs"]
    friction = scenario["friction"]
    drive = [float(r["drive_x"]) for r in rows]
    shift = [float(r["x"]) for r in rows]
    force = [float(r["force_tangential"]) for r in rows]
    area = [float(r["area"]) for r in rows]
    stuck = [int(r["n_stick"]) / int(r["n_contact"]) for r in rows]
    kinetic = [friction["shear_strength"] * a for a in area]
    static = [friction["static_shear_strength"] * a for a in area]
    for k in range(1, len(rows)):
        if force[k] < force[k - 1] and stuck[k] == 0:
            print(
                f"slip event at X = {drive[k]:.4g}: F {force[k - 1]:.5e} -> {force[k]:.5e} "
                f"(F/(tau0 A) {force[k - 1] / kinetic[k - 1]:.4f} -> {force[k] / kinetic[k]:.6f}), "
                f"delta jumps by {shift[k] - shift[k - 1]:.4e}"
            )
    figure, (left, right) = plt.subplots(1, 2, figsize=(11, 4.2))
    left.plot(drive, force, "o-", ms=3, color="tab:blue", label="$F_T$ (adhesim)")
    left.plot(drive, kinetic, "--", color="tab:orange", label=r"$\tau_0 A$ (kinetic)")
    left.plot(drive, static, ":", color="tab:red", label=r"$\tau_s A$ (static)")
    left.set_xlabel("drive position $X$")
    left.set_ylabel("tangential force $F_T$")
    left.set_ylim(0, 1.1 * max(static))
    left.legend(loc="lower right")
    left.set_title("force: stick phases and slip events")
    right.plot(drive, shift, "o-", ms=3, color="tab:blue", label=r"indenter shift $\delta$")
    right.plot(drive, drive, "-", color="0.6", lw=0.8, label="$X$ (the drive)")
    right.set_xlabel("drive position $X$")
    right.set_ylabel("shift")
    twin = right.twinx()
    twin.step(drive, stuck, where="mid", color="tab:green", lw=1, label="sticking share of $A$")
    twin.set_ylabel("sticking share of the contact", color="tab:green")
    twin.set_ylim(0, 1.05)
    lines = right.get_legend_handles_labels()
    more = twin.get_legend_handles_labels()
    right.legend(lines[0] + more[0], lines[1] + more[1], loc="lower right", framealpha=0.95)
    right.set_title(r"the indenter jumps ahead in each event")
    figure.tight_layout()
    figure.savefig(path, dpi=110)


if __name__ == "__main__":
    main()
