#!/usr/bin/env python3
"""How the simulated sliding experiment depends on the rubber's modulus
(docs/experiments-simulated.md, "The rubber's modulus"): one row per case of a sweep over
`material.youngs_modulus` (sweeps/layer_modulus.toml, sweeps/layer_modulus_d0.toml).

    adhesim sweep sweeps/layer_modulus.toml --out out/layer_modulus
    python3 scripts/modulus_sensitivity.py out/layer_modulus

For each modulus: the contact at rest (area, equivalent radius, normal force), the shift at
which the whole contact slides (no element sticks), the sliding τ = F_T/A, and the change
of the front, rear and total areas from the shear's start to its end. Prints a Markdown
table. Only the standard library.
"""
import csv
import json
import math
import sys
from pathlib import Path


def case_row(case: Path) -> dict:
    values = json.loads((case / "case.json").read_text())["values"]
    rows = list(csv.DictReader(open(case / "curve.csv")))
    shear = [r for r in rows if r["phase"] == "shear"]
    if not shear:
        sys.exit(f"{case}: no shear steps in curve.csv")
    start = [r for r in rows if r["phase"] != "shear"][-1]
    end = shear[-1]
    sliding = next((float(r["x"]) for r in shear if int(r["n_stick"]) == 0 and int(r["n_contact"]) > 0), math.nan)

    def change(key: str) -> float:
        before = float(start[key])
        return 100.0 * (float(end[key]) - before) / before if before > 0 else math.nan

    area = float(start["area"])
    return {
        "modulus": float(values["material.youngs_modulus"]),
        "area": area,
        "radius": math.sqrt(area / math.pi),
        "force_normal": float(start["force_normal"]),
        "sliding_from": sliding,
        "tau": float(end["force_tangential"]) / float(end["area"]) if float(end["area"]) > 0 else math.nan,
        "front": change("area_front"),
        "rear": change("area_rear"),
        "total": change("area"),
    }


def main() -> None:
    if len(sys.argv) != 2:
        sys.exit("usage: modulus_sensitivity.py SWEEP_OUT")
    cases = sorted((Path(sys.argv[1]) / "cases").glob("*/done"))
    if not cases:
        sys.exit(f"{sys.argv[1]}: no finished cases")
    table = sorted((case_row(done.parent) for done in cases), key=lambda row: row["modulus"])
    print("| E (MPa) | area at rest (mm²) | √(A/π) (mm) | F_N (N) | whole contact slides from x (mm) "
          "| τ sliding (kPa) | front | rear | total |")
    print("|---|---|---|---|---|---|---|---|---|")
    for row in table:
        print(f"| {row['modulus']:g} | {row['area']:.2f} | {row['radius']:.3f} | {row['force_normal']:.4f} "
              f"| {row['sliding_from']:.3f} | {1e3 * row['tau']:.2f} | {row['front']:+.1f} % "
              f"| {row['rear']:+.1f} % | {row['total']:+.1f} % |")


if __name__ == "__main__":
    main()
