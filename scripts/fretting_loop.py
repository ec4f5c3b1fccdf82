#!/usr/bin/env python3
"""A fretting loop of adhesim against Mindlin & Deresiewicz (docs/validation.md §17, docs/tangential.md).

    adhesim run scenarios/friction/fretting.toml --out out/fretting
    python3 scripts/fretting_loop.py out/fretting [--figure docs/img/tangential/fretting_loop.png]

Reads the run's curve.csv and its inputs in summary.json (μ, E, ν, steps, cycles) and prints
the last cycle's dissipation (summary.json) against Mindlin–Deresiewicz's loop energy
W = 9μ²P²(2 − ν)/(10Ga)·[1 − (1 − x)^{5/3} − (5x/6)(1 + (1 − x)^{2/3})], x = Q*/μP, with the
run's P, a = √(A/π) and amplitude force Q*, and the loop's area ∮Q dδ. With --figure it
draws the run's force against the shift over the closed-form loading curve and the two
branches of the loop, δ = ±δ_a ∓ 2δ*[1 − (1 − (Q* ∓ Q)/(2μP))^{2/3}] (needs matplotlib).
"""
import csv
import json
import math
import sys
from pathlib import Path


def main() -> None:
    out = Path(sys.argv[1])
    figure = sys.argv[sys.argv.index("--figure") + 1] if "--figure" in sys.argv else None
    summary = json.loads((out / "summary.json").read_text())
    inputs = summary["inputs"]
    mu = inputs["friction"]["coefficient"]
    e, nu = inputs["material"]["youngs_modulus"], inputs["material"]["poisson_ratio"]
    g = e / (2 * (1 + nu))
    steps, cycles = inputs["protocol"]["steps"], inputs["protocol"].get("cycles", 0)
    if cycles < 1:
        sys.exit("fretting_loop.py needs a run with protocol.cycles >= 1")
    rows = [r for r in csv.DictReader(open(out / "curve.csv")) if r["phase"] == "shear"]
    shift = [float(r["x"]) for r in rows]
    force = [float(r["force_tangential"]) for r in rows]
    start, end = steps + 4 * (cycles - 1) * steps - 1, steps + 4 * cycles * steps - 1
    p = float(rows[end]["force_normal"])
    a = math.sqrt(float(rows[end]["area"]) / math.pi)
    amplitude = force[end]
    x = amplitude / (mu * p)
    expected = 9 * mu**2 * p**2 * (2 - nu) / (10 * g * a) * (
        1 - (1 - x) ** (5 / 3) - 5 * x / 6 * (1 + (1 - x) ** (2 / 3))
    )
    dissipated = summary["results"]["fretting_dissipation_per_cycle"]
    loop = sum(0.5 * (force[k] + force[k - 1]) * (shift[k] - shift[k - 1]) for k in range(start + 1, end + 1))
    print(f"Q*/muP = {x:.4f}, P = {p:.6g}, a = {a:.6g}")
    print(f"dissipated in the last cycle {dissipated:.6e}; loop area {loop:.6e}")
    print(f"Mindlin-Deresiewicz {expected:.6e}; ratio {dissipated / expected:.4f}")
    if figure:
        full_slip = 3 * mu * p * (2 - nu) / (16 * g * a)
        control = "imposed force" if "tangential_force" in inputs["protocol"] else "imposed shift"
        title = f"Fretting loop of a sphere ({control}), Coulomb $\\mu$ = {mu:g}, $\\nu$ = {nu:g}"
        draw(shift, force, (start, end), (mu * p, full_slip, amplitude, shift[end]), figure, title)


def draw(shift, force, cycle, constants, figure, title) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    limit, full_slip, amplitude, reach = constants
    samples = [amplitude * (k / 100) for k in range(101)]
    loading = [full_slip * (1 - (1 - q / limit) ** (2 / 3)) for q in samples]
    levels = [amplitude - 2 * amplitude * k / 100 for k in range(101)]
    down = [reach - 2 * full_slip * (1 - (1 - (amplitude - q) / (2 * limit)) ** (2 / 3)) for q in levels]
    fig, ax = plt.subplots(figsize=(6, 4.4))
    ax.plot(loading, [q / limit for q in samples], "-", color="0.6", label="Cattaneo–Mindlin loading")
    ax.plot(down, [q / limit for q in levels], "-", color="C0", label="Mindlin–Deresiewicz loop")
    ax.plot([-d for d in down], [-q / limit for q in levels], "-", color="C0")
    start, end = cycle
    ax.plot(shift[: start + 1], [q / limit for q in force[: start + 1]], "o", ms=3, color="0.3", label="adhesim, first stroke and cycle")
    ax.plot(shift[start:end + 1], [q / limit for q in force[start:end + 1]], "o", ms=3, color="C3", label="adhesim, last cycle")
    ax.set_xlabel("shift $\\delta$")
    ax.set_ylabel("tangential force $Q/\\mu P$")
    ax.set_title(title, fontsize=10)
    ax.axhline(0, color="0.85", lw=0.8)
    ax.axvline(0, color="0.85", lw=0.8)
    ax.legend(frameon=False, fontsize=8, loc="upper left")
    fig.tight_layout()
    fig.savefig(figure, dpi=130)


if __name__ == "__main__":
    main()
