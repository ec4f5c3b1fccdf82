#!/usr/bin/env python3
"""An adhesive sphere sheared without slip against Savkoor & Briggs' energy balance
(docs/validation.md §17, docs/tangential.md).

    adhesim run scenarios/friction/adhesive_shear.toml --out out/adhesive_shear
    python3 scripts/savkoor_briggs.py out/adhesive_shear [--figure docs/img/tangential/savkoor_briggs.png]

Reads the run's curve.csv and its inputs in summary.json (E, ν, γ, R, the held depth d) and
prints, per shift step δ, the contact area over the area at rest against the brittle
circular-contact balance at fixed depth (docs/physics.md §8.5),

    d = a²/R − √((2πaw − 4G*δ²)/E*),   G* = G/(2 − ν),

its first order in δ², and the tangential force against Mindlin's no-slip T = 8G*aδ with the
run's own a = √(A/π). With fields.npz and numpy it also prints the contact's extent along and
across the shear (second moments, 2√⟨x²⟩ and 2√⟨y²⟩, an ellipse's semi-axes) at rest and at
the end; with --figure it draws A/A0 against δ² (needs numpy and matplotlib).
"""
import csv
import json
import math
import sys
from pathlib import Path


def contact_radius(depth, shift, radius, work, contact_modulus, mindlin_modulus):
    """a solving d = a²/R − √((2πaw − 4G*δ²)/E*) on the stable branch (bisection)."""
    def excess(a):
        energy = max(2 * math.pi * a * work - 4 * mindlin_modulus * shift * shift, 0.0)
        return a * a / radius - math.sqrt(energy / contact_modulus) - depth
    low, high = 1e-12, 10 * math.sqrt(radius * max(depth, 0.0) + radius * radius * work / contact_modulus) + 1e-9
    for _ in range(200):
        middle = 0.5 * (low + high)
        if excess(middle) > 0:
            high = middle
        else:
            low = middle
    return 0.5 * (low + high)


def first_order_slope(depth, radius, work, contact_modulus, mindlin_modulus):
    """d(A/A0)/d(δ²) at δ = 0 from the implicit function theorem on the balance."""
    a0 = contact_radius(depth, 0.0, radius, work, contact_modulus, mindlin_modulus)
    root = math.sqrt(2 * math.pi * a0 * work / contact_modulus)
    along_shift = (2 * mindlin_modulus / contact_modulus) / root
    along_radius = 2 * a0 / radius - (math.pi * work / contact_modulus) / root
    return 2 * (-along_shift / along_radius) / a0


def extents(out):
    """(steps, [(2√⟨x²⟩, 2√⟨y²⟩)]) of the contact snapshots in fields.npz, or None."""
    try:
        import numpy as np
    except ImportError:
        return None
    path = out / "fields.npz"
    if not path.exists():
        return None
    fields = np.load(path)
    x, y = np.meshgrid(fields["x"], fields["y"])
    result = []
    for contact in fields["contact"]:
        inside = contact.astype(bool)
        result.append((2 * math.sqrt(np.mean(x[inside] ** 2)), 2 * math.sqrt(np.mean(y[inside] ** 2))))
    return list(fields["steps"]), result


def main() -> None:
    out = Path(sys.argv[1])
    figure = sys.argv[sys.argv.index("--figure") + 1] if "--figure" in sys.argv else None
    inputs = json.loads((out / "summary.json").read_text())["inputs"]
    e, nu = inputs["material"]["youngs_modulus"], inputs["material"]["poisson_ratio"]
    contact_modulus = e / (1 - nu * nu)
    mindlin_modulus = e / (2 * (1 + nu)) / (2 - nu)
    work = inputs["adhesion"]["work_of_adhesion"]
    radius = inputs["indenter"]["radius"]
    depth = inputs["protocol"]["depth"]
    if inputs["protocol"].get("depth_unit", "jkr") != "length":
        sys.exit("savkoor_briggs.py reads protocol.depth in length units (depth_unit = \"length\")")
    rows = list(csv.DictReader(open(out / "curve.csv")))
    rest = [r for r in rows if r["phase"] == "approach"][-1]
    sheared = [r for r in rows if r["phase"] == "shear"]
    area0 = float(rest["area"])
    a0 = contact_radius(depth, 0.0, radius, work, contact_modulus, mindlin_modulus)
    slope = first_order_slope(depth, radius, work, contact_modulus, mindlin_modulus)
    element = inputs["grid"]["size"] / inputs["grid"]["n"]
    print(f"a0 = {a0:.6g} ({a0 / element:.1f} elements; run: {math.sqrt(area0 / math.pi) / element:.1f}),"
          f" first-order d(A/A0)/d(delta^2) = {slope:.6g}")
    print("delta      A/A0     balance  1st order  loss ratio  F_T/(8G*a delta)")
    points = [(0.0, 1.0, 1.0, 1.0)]
    for r in sheared:
        shift, area = float(r["x"]), float(r["area"])
        expected = (contact_radius(depth, shift, radius, work, contact_modulus, mindlin_modulus) / a0) ** 2
        linear = 1 + slope * shift * shift
        ratio = (1 - area / area0) / (1 - expected) if expected < 1 else float("nan")
        a = math.sqrt(area / math.pi)
        stiffness = float(r["force_tangential"]) / (8 * mindlin_modulus * a * shift) if shift > 0 else float("nan")
        points.append((shift, area / area0, expected, linear))
        print(f"{shift:.3e}  {area / area0:.5f}  {expected:.5f}  {linear:.5f}  {ratio:9.3f}  {stiffness:9.4f}")
    losses = [(1 - p[1], 1 - p[2]) for p in points[1:]]
    factor = sum(a * b for a, b in losses) / sum(b * b for _, b in losses)
    print(f"area lost = {factor:.4f} x the balance's (least squares over the stroke)")
    shape = extents(out)
    if shape:
        for step, (along, across) in zip(*shape):
            print(f"step {int(step)}: extent along the shear {along:.5g}, across {across:.5g}, ratio {along / across:.4f}")
    if figure:
        draw(points, slope, figure, a0 / element)


def draw(points, slope, figure, elements) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    squared = [p[0] ** 2 for p in points]
    fig, ax = plt.subplots(figsize=(6, 4.2))
    fine = [squared[-1] * k / 100 for k in range(101)]
    ax.plot(squared, [p[2] for p in points], "-", color="C0", label="energy balance, circular contact")
    ax.plot(fine, [1 + slope * s for s in fine], ":", color="C0", label="its first order in $\\delta^2$")
    ax.plot(squared, [p[1] for p in points], "o", color="C3", label=f"adhesim, local rule, $a_0/\\Delta$ = {elements:.0f}")
    ax.set_xlabel("shift squared $\\delta^2$")
    ax.set_ylabel("contact area $A/A_0$ at fixed depth")
    ax.set_title("Adhesive sphere sheared without slip (mode mixity 1)")
    ax.legend(frameon=False)
    fig.tight_layout()
    fig.savefig(figure, dpi=130)


if __name__ == "__main__":
    main()
