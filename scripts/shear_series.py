#!/usr/bin/env python3
"""Time series of a run with friction at the interface in the style of the paper's Figs. 17
and 19 (docs/tangential.md): a shear, or a roll, slide or translate with [friction].

    adhesim run scenarios/friction/shear_strength.toml --out out/tresca
    python3 scripts/shear_series.py out/tresca docs/img/tangential/shear_strength_series.png
    adhesim run scenarios/friction/slide_shear_strength.toml --out out/slide
    python3 scripts/shear_series.py out/slide docs/img/tangential/slide_series.png "A slide with τ0 (JKR contact)"

Draws, against the step (the indenter goes out and back): the tangential force F_T, the
total, front and rear contact areas, the stick and slip areas, and τ = F_T/A. An optional
third argument is the title. Needs matplotlib.
"""
import csv
import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main() -> None:
    out, path = Path(sys.argv[1]), sys.argv[2]
    title = sys.argv[3] if len(sys.argv) > 3 else "Shear with a constant shear strength τ0 (JKR contact)"
    rows = [r for r in csv.DictReader(open(out / "curve.csv")) if r["phase"] != "approach"]
    step = [int(r["step"]) for r in rows]
    shift = [float(r["x"]) for r in rows]
    force = [float(r["force_tangential"]) for r in rows]
    area = [float(r["area"]) for r in rows]
    element = area[0] / int(rows[0]["n_contact"])
    front = [float(r["area_front"]) for r in rows]
    rear = [float(r["area_rear"]) for r in rows]
    stick = [int(r["n_stick"]) * element for r in rows]
    slip = [int(r["n_slip"]) * element for r in rows]
    tau = [f / a for f, a in zip(force, area)]
    fig, axes = plt.subplots(3, 1, figsize=(7, 8), sharex=True)
    axes[0].plot(step, force, color="C0", label="F_T")
    twin = axes[0].twinx()
    twin.plot(step, shift, color="0.6", ls="--", label="position x")
    axes[0].set(ylabel="tangential force F_T", title=title)
    twin.set_ylabel("position x")
    axes[0].legend(loc="upper left")
    twin.legend(loc="upper right")
    axes[1].plot(step, area, color="k", label="total A")
    axes[1].plot(step, front, color="C3", label="front")
    axes[1].plot(step, rear, color="C2", ls="--", label="rear")
    axes[1].plot(step, stick, color="C0", label="stick")
    axes[1].plot(step, slip, color="C1", label="slip")
    axes[1].set(ylabel="area")
    axes[1].legend(loc="upper center", bbox_to_anchor=(0.5, -0.03), ncol=5, fontsize=8, frameon=False)
    axes[2].plot(step, tau, color="C4")
    axes[2].set(ylabel="τ = F_T/A", xlabel="step (out, then back)")
    fig.tight_layout()
    Path(path).parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(path, dpi=110)
    print(f"wrote {path}")


if __name__ == "__main__":
    main()
