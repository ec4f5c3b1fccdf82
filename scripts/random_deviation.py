#!/usr/bin/env python3
"""How far the random series of Fig. 3 lies from the amplitude series (docs/paper.md).

Reads docs/data/paper/fig3_amplitude_512.csv and fig3_random_512.csv (the `table.csv` files
of `adhesim sweep sweeps/fig3_amplitude_512.toml` and `sweeps/fig3_random_512.toml`, both
at n = 512). For every finished random case it interpolates the amplitude series at the
case's alpha (linear in log alpha between the two nearest amplitude cases) and prints the
deviation (random minus amplitude) of gamma1/gamma0, gamma2/gamma0 (both radius definitions) and |F_ad|/|F_JKR|, then
the mean and largest absolute deviation over the cases whose JKR contact spans at least 4
wavelengths (a_JKR/lambda >= 4; the amplitude series has 5) and over the others.
a_JKR = (9 pi gamma0 R^2 / (8 E*))^(1/3) with R = 1, as in sweeps/paper_base.toml; the
amplitude series has 16 elements per wavelength, a random case lambda / element size.

    python3 scripts/random_deviation.py            # standard library only
"""

import csv
import math
import os

DATA = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "docs", "data", "paper")
QUANTITIES = [
    ("γ1 (farthest)", "gamma_approach_norm"),
    ("γ2 (farthest)", "gamma_pulloff_norm"),
    ("γ1 (√(A/π))", "gamma_approach_area_norm"),
    ("γ2 (√(A/π))", "gamma_pulloff_area_norm"),
    ("F_ad", "adhesive_force_ratio"),
]


def rows(name):
    with open(os.path.join(DATA, name), newline="") as f:
        return [r for r in csv.DictReader(f) if r.get("status") == "ok"]


def interpolate(series, alpha, key):
    """The amplitude series at alpha, linear in log alpha; None outside its range."""
    points = sorted((float(r["alpha"]), float(r[key])) for r in series)
    for (a0, v0), (a1, v1) in zip(points, points[1:]):
        if a0 <= alpha <= a1:
            t = math.log(alpha / a0) / math.log(a1 / a0)
            return v0 + t * (v1 - v0)
    return None


def a_jkr_over_lambda(row):
    gamma = float(row["adhesion.work_of_adhesion"])
    modulus = float(row["material.contact_modulus"])
    return (9 * math.pi * gamma / (8 * modulus)) ** (1 / 3) / float(row["lambda_over_radius"])


def main():
    amplitude = rows("fig3_amplitude_512.csv")
    random = sorted(rows("fig3_random_512.csv"), key=lambda r: float(r["alpha"]))
    header = ["case", "α", "a_JKR/λ", "elements per λ"] + [name for name, _ in QUANTITIES]
    print("| " + " | ".join(header) + " |")
    print("|" + "---|" * len(header))
    groups = {"a_JKR/λ ≥ 4": [], "a_JKR/λ < 4": []}
    for row in random:
        alpha, size = float(row["alpha"]), a_jkr_over_lambda(row)
        deviations = []
        for _, key in QUANTITIES:
            reference = interpolate(amplitude, alpha, key)
            deviations.append(None if reference is None else float(row[key]) - reference)
        if None in deviations:
            continue
        groups["a_JKR/λ ≥ 4" if size >= 4 else "a_JKR/λ < 4"].append(deviations)
        per_wavelength = float(row["lambda_over_radius"]) / float(row["element_size"])
        cells = [row["case"][:4], f"{alpha:.2f}", f"{size:.2f}", f"{per_wavelength:.1f}"]
        cells += [f"{d:+.3f}" for d in deviations]
        print("| " + " | ".join(cells) + " |")
    print()
    print("| cases | n | " + " | ".join(f"mean / max \\|Δ{name}\\|" for name, _ in QUANTITIES) + " |")
    print("|" + "---|" * (len(QUANTITIES) + 2))
    for label, group in groups.items():
        if not group:
            continue
        cells = []
        for index in range(len(QUANTITIES)):
            values = [abs(d[index]) for d in group]
            cells.append(f"{sum(values) / len(values):.3f} / {max(values):.3f}")
        print(f"| {label} | {len(group)} | " + " | ".join(cells) + " |")


if __name__ == "__main__":
    main()
