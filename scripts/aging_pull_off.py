#!/usr/bin/env python3
"""Aging adhesion against the paper's Eq. 15 (docs/experiments-simulated.md).

    adhesim sweep sweeps/aging_hold.toml --out out/aging_hold
    python3 scripts/aging_pull_off.py out/aging_hold [--figure docs/img/aging/pull_off.png]

Reads the sweep's table.csv (max_adhesive_force against protocol.hold_time) and prints the
log-log slope of the pull-off force against the hold time, the exponent the paper fits as
0.0883. With --figure it draws (a) the force against the indentation of each case's
retraction, whose first, linear part coincides across the holds as in the paper's
Fig. 14a, and (b) the pull-off force against the hold time on log axes with the fitted
power law (needs matplotlib).
"""
import csv
import math
import sys
from pathlib import Path


def main() -> None:
    out = Path(sys.argv[1])
    figure = sys.argv[sys.argv.index("--figure") + 1] if "--figure" in sys.argv else None
    rows = [r for r in csv.DictReader(open(out / "table.csv")) if r["status"] == "ok"]
    rows.sort(key=lambda r: float(r["protocol.hold_time"]))
    times = [float(r["protocol.hold_time"]) for r in rows]
    forces = [float(r["max_adhesive_force"]) for r in rows]
    x = [math.log(t) for t in times]
    y = [math.log(f) for f in forces]
    mx, my = sum(x) / len(x), sum(y) / len(y)
    slope = sum((a - mx) * (b - my) for a, b in zip(x, y)) / sum((a - mx) ** 2 for a in x)
    prefactor = math.exp(my - slope * mx)
    for t, f in zip(times, forces):
        print(f"hold {t:g}: pull-off force {f:.6e}")
    print(f"exponent {slope:.5f} (configured 0.0883: {slope / 0.0883 - 1:+.2%}); prefactor {prefactor:.5e}")
    if figure:
        curves = {}
        for r in rows:
            case = out / "cases" / r["case"] / "curve.csv"
            curves[float(r["protocol.hold_time"])] = [c for c in csv.DictReader(open(case))]
        draw(curves, times, forces, (slope, prefactor), figure)


def draw(curves, times, forces, fit, figure) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, (left, right) = plt.subplots(1, 2, figsize=(10, 4.2))
    for k, (time, rows) in enumerate(sorted(curves.items())):
        pulled = [r for r in rows if r["phase"] in ("hold", "retract")]
        left.plot([float(r["d"]) for r in pulled], [float(r["force_normal"]) for r in pulled], "-",
                  lw=1.2, color=plt.cm.viridis(k / max(1, len(curves) - 1)), label=f"hold {time:g} min")
    left.set_xlabel("indentation $d$")
    left.set_ylabel("normal force $F_N$")
    left.set_title("(a) retraction after holds of 1–30 min", fontsize=10)
    left.axhline(0, color="0.85", lw=0.8)
    left.legend(frameon=False, fontsize=8, loc="upper center")
    slope, prefactor = fit
    right.loglog(times, forces, "o", color="C3", label="adhesim, pull-off force")
    span = [min(times) * 0.8, max(times) * 1.25]
    right.loglog(span, [prefactor * t**slope for t in span], "-", color="0.4", label=f"fit $\\propto t^{{{slope:.4f}}}$")
    right.set_xlabel("hold time $t$ (min)")
    right.set_ylabel("$|F_{N,\\min}|$")
    right.set_title("(b) pull-off force against hold time (bonds age as $t^{0.0883}$)", fontsize=10)
    right.legend(frameon=False, fontsize=8)
    fig.tight_layout()
    fig.savefig(figure, dpi=130)


if __name__ == "__main__":
    main()
