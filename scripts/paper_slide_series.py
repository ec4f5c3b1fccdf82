#!/usr/bin/env python3
"""The paper's sliding experiment as a time series in the style of its Figs. 17 and 19
(docs/experiments-simulated.md): the tangential force, the front, rear and total contact
areas, and τ = F_T/A against the shift, for the run with the layer's coupling and the same
run without it (Goodman's approximation).

    adhesim run scenarios/layer/paper_r22_shear.toml --out out/r22_full
    adhesim run scenarios/layer/paper_r22_shear.toml --out out/r22_none --set friction.coupling='"none"'
    python3 scripts/paper_slide_series.py out/r22_full out/r22_none docs/img/experiment/paper_r22_shear.png

Prints, for each run, the areas at the end of the approach and of the shift and the sliding
τ. Needs matplotlib.
"""
import csv
import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def series(out: Path) -> dict:
    rows = list(csv.DictReader(open(out / "curve.csv")))
    last_approach = max(i for i, r in enumerate(rows) if r["phase"] == "approach")
    rows = rows[last_approach:]
    column = {name: [float(r[name]) for r in rows] for name in ("x", "force_tangential", "area", "area_front", "area_rear")}
    column["tau"] = [f / a if a > 0 else float("nan") for f, a in zip(column["force_tangential"], column["area"])]
    return column


def main() -> None:
    if len(sys.argv) != 4:
        sys.exit("usage: paper_slide_series.py COUPLED_RUN GOODMAN_RUN OUT.png")
    coupled, goodman, path = Path(sys.argv[1]), Path(sys.argv[2]), sys.argv[3]
    runs = {"coupled (friction.coupling = \"full\")": series(coupled), "Goodman (\"none\")": series(goodman)}
    fig, axes = plt.subplots(1, 3, figsize=(15, 4.5))
    styles = ["-", "--"]
    for (label, run), style in zip(runs.items(), styles):
        x = run["x"]
        axes[0].plot(x, run["force_tangential"], style, color="black", label=label)
        axes[1].plot(x, run["area_front"], style, color="tab:red", label=f"front, {label}")
        axes[1].plot(x, run["area_rear"], style, color="tab:blue", label=f"rear, {label}")
        axes[2].plot(x, [1e3 * t for t in run["tau"]], style, color="black", label=label)
        first, last = 0, len(x) - 1
        print(
            f"{label}: front {run['area_front'][first]:.4f} → {run['area_front'][last]:.4f} mm², "
            f"rear {run['area_rear'][first]:.4f} → {run['area_rear'][last]:.4f} mm², "
            f"total {run['area'][first]:.4f} → {run['area'][last]:.4f} mm²; sliding τ = {1e3 * run['tau'][last]:.2f} kPa"
        )
    axes[0].set(xlabel="shift x (mm)", ylabel="tangential force F_T (N)", title="tangential force")
    axes[1].set(xlabel="shift x (mm)", ylabel="contact area (mm²)", title="front and rear contact areas")
    axes[2].set(xlabel="shift x (mm)", ylabel="τ = F_T/A (kPa)", title="mean shear stress")
    for axis in axes:
        axis.grid(True, alpha=0.3)
        axis.legend(fontsize=8)
    fig.suptitle("R = 22 mm on a 5 mm rubber layer, d = 0.2 mm, τ0 = 36 kPa (scenarios/layer/paper_r22_shear.toml)")
    fig.tight_layout()
    fig.savefig(path, dpi=110)


if __name__ == "__main__":
    main()
