#!/usr/bin/env python3
"""Cattaneo–Mindlin against a shear run of adhesim (docs/validation.md §17, docs/tangential.md).

    adhesim run scenarios/shear.toml --out out/shear
    python3 scripts/cattaneo_mindlin.py out/shear [--figure docs/img/tangential/cattaneo_mindlin.png]

Reads the run's curve.csv and its inputs in summary.json (μ, E, ν, grid) and prints, per shift step, Q/μP,
the shift δ against Cattaneo–Mindlin's δ(Q) = δ*[1 − (1 − Q/μP)^{2/3}] and the stick ratio
c/a = √(n_stick/n_contact) against (1 − Q/μP)^{1/3}, with δ* = 3μP(2 − ν)/(16Ga) from the
run's own P and a = √(A/π). With --figure it draws both (needs numpy and matplotlib).
"""
import csv
import math
import sys
import json
from pathlib import Path


def main() -> None:
    out = Path(sys.argv[1])
    figure = sys.argv[sys.argv.index("--figure") + 1] if "--figure" in sys.argv else None
    scenario = json.loads((out / "summary.json").read_text())["inputs"]
    mu = scenario["friction"]["coefficient"]
    e, nu = scenario["material"]["youngs_modulus"], scenario["material"]["poisson_ratio"]
    g = e / (2 * (1 + nu))
    n = scenario["grid"]["n"]
    element = scenario["grid"]["size"] / n
    rows = [r for r in csv.DictReader(open(out / "curve.csv")) if r["phase"] == "shear"]
    p = float(rows[-1]["force_normal"])
    radius = math.sqrt(float(rows[-1]["area"]) / math.pi)
    full_slip = 3 * mu * p * (2 - nu) / (16 * g * radius)
    print(f"a = {radius / element:.1f} elements, P = {p:.6g}, delta* = {full_slip:.6g}")
    print("delta/delta*  Q/muP   delta/CM-1   c/a     CM c/a  c/a err  c/Delta")
    points = []
    for r in rows:
        shift, q = float(r["x"]), float(r["force_tangential"]) / (mu * p)
        stick = math.sqrt(int(r["n_stick"]) / int(r["n_contact"]))
        if shift < full_slip:
            cm_shift = full_slip * (1 - (1 - q) ** (2 / 3))
            cm_stick = (1 - q) ** (1 / 3)
            print(f"{shift / full_slip:12.4f} {q:7.4f} {shift / cm_shift - 1:+11.4%} {stick:7.4f} {cm_stick:7.4f}"
                  f" {stick / cm_stick - 1:+8.2%} {cm_stick * radius / element:7.1f}")
        else:
            print(f"{shift / full_slip:12.4f} {q:7.4f}   (gross slip; n_stick = {r['n_stick']})")
        points.append((shift / full_slip, q, stick))
    if figure:
        draw(points, figure, radius / element)


def draw(points, path: str, elements: float) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import numpy as np

    s, q, c = (np.array(v) for v in zip(*points))
    theory = np.linspace(0, 1, 200)
    fig, (left, right) = plt.subplots(1, 2, figsize=(10, 4))
    left.plot(1 - (1 - theory) ** (2 / 3), theory, color="0.6", label="Cattaneo–Mindlin")
    left.plot([1, s.max()], [1, 1], color="0.6")
    left.plot(s, q, "o", ms=4, label=f"adhesim (a = {elements:.0f} elements)")
    left.set(xlabel="shift δ/δ*", ylabel="tangential force Q/μP", title="Force against shift")
    left.legend(loc="lower right")
    right.plot(theory, (1 - theory) ** (1 / 3), color="0.6", label="(1 − Q/μP)^(1/3)")
    right.plot(q, c, "o", ms=4, label="adhesim: √(n_stick/n_contact)")
    right.set(xlabel="Q/μP", ylabel="stick radius c/a", title="Stick zone")
    right.legend(loc="lower left")
    fig.tight_layout()
    Path(path).parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(path, dpi=110)
    print(f"wrote {path}")


if __name__ == "__main__":
    main()
