#!/usr/bin/env python3
"""Draw the resolution campaign's master curves (docs/paper.md, γ2's peak and γ1 − γ2's extremum).

Reads docs/data/paper/resolution_amplitude.csv (10, 12, 14 elements per λ) and the
16-per-λ amplitude series of fig3_amplitude_512.csv (α = 0.4–1, the campaign's range),
labels each row's series by its elements per λ (n / 32 on this domain) and hands the
tables to `adhesim plot master`, which writes fig3_master.png and fig5_master.png.

    python3 scripts/resolution_plot.py [--adhesim target/release/adhesim] [--out DIR]
"""

import argparse
import csv
import os
import subprocess
import tempfile

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..")
DATA = os.path.join(ROOT, "docs", "data", "paper")
# L = 6.4·a_JKR with a_JKR = 5λ: the domain holds 32 wavelengths, so n / 32 elements per λ.
WAVELENGTHS_PER_DOMAIN = 32


def relabel(source, target, alpha_range):
    with open(source, newline="") as f:
        rows = list(csv.DictReader(f))
    if not rows:
        raise SystemExit(f"{source}: no rows")
    with open(target, "w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=rows[0].keys())
        writer.writeheader()
        for row in rows:
            if alpha_range[0] <= float(row["alpha"]) <= alpha_range[1]:
                per_wavelength = int(row["grid.n"]) // WAVELENGTHS_PER_DOMAIN
                row["series"] = f"{per_wavelength} elements per λ"
                writer.writerow(row)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--adhesim", default=os.path.join(ROOT, "target", "release", "adhesim"))
    parser.add_argument("--out", default=os.path.join(ROOT, "out", "resolution_plot"))
    args = parser.parse_args()
    with tempfile.TemporaryDirectory() as scratch:
        tables = []
        for name in ["resolution_amplitude.csv", "fig3_amplitude_512.csv"]:
            target = os.path.join(scratch, name)
            relabel(os.path.join(DATA, name), target, (0.35, 1.0))
            tables.append(target)
        subprocess.run([args.adhesim, "plot", "master", *tables, "--out", args.out], check=True)


if __name__ == "__main__":
    main()
