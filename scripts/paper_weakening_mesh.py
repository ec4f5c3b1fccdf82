#!/usr/bin/env python3
"""The paper's slide through a spring on its layer, at two element sizes, under the static
law and under slip weakening (docs/experiments-simulated.md, §Stick–slip with slip
weakening): τ = F_T/A against the drive's position X, one panel per law, and the slip
events of each run (the steps where the force falls by more than 1e-4 of itself).

    S=scenarios/layer/paper_r22_stick_slip.toml
    common="--set protocol.distance=1.5 --set protocol.steps=150"
    fine="--set grid.n=[768,192]"
    weak="--set friction.slip_weakening_distance=0.008"
    adhesim run $S --out out/static_coarse $common
    adhesim run $S --out out/static_fine $common $fine
    adhesim run $S --out out/weak_coarse $common $weak
    adhesim run $S --out out/weak_fine $common $fine $weak
    python3 scripts/paper_weakening_mesh.py out docs/img/experiment/paper_r22_weakening_mesh.png

Needs matplotlib.
"""
import csv
import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

RUNS = [("static", "static law"), ("weak", "slip weakening, D_c = 8 µm")]
MESHES = [("coarse", "Δ = 0.1 mm", "0.55"), ("fine", "Δ = 0.05 mm", "0.0")]


def series(folder: Path):
    rows = [r for r in csv.DictReader(open(folder / "curve.csv")) if r["phase"] != "approach"]
    x = [float(r["drive_x"]) for r in rows]
    force = [float(r["force_tangential"]) for r in rows]
    tau = [float(r["force_tangential"]) / float(r["area"]) * 1e3 for r in rows]
    return x, force, tau


def events(x, force, tau):
    return [(x[i], tau[i], tau[i + 1]) for i in range(len(force) - 1) if force[i + 1] < force[i] * (1 - 1e-4)]


def main() -> None:
    out, path = Path(sys.argv[1]), sys.argv[2]
    fig, axes = plt.subplots(1, 2, figsize=(11, 4.2), sharey=True)
    for ax, (law, title) in zip(axes, RUNS):
        for mesh, label, grey in MESHES:
            x, force, tau = series(out / f"{law}_{mesh}")
            ax.plot(x, tau, color=grey, lw=1.4, label=label)
            found = events(x, force, tau)
            print(f"{law} {mesh}: {len(found)} events; peak τ {max(tau):.2f} kPa")
            print("   " + " ".join(f"{e[0]:.2f}:{e[1]:.2f}->{e[2]:.2f}" for e in found))
        ax.axhline(36.0, color="0.7", lw=0.8, ls="--")
        ax.axhline(45.0, color="0.7", lw=0.8, ls=":")
        ax.set_title(title)
        ax.set_xlabel("drive position X (mm)")
        ax.set_xlim(0.6, 1.5)
        ax.legend(loc="lower right", frameon=False)
    axes[0].set_ylabel("τ = F_T/A (kPa)")
    axes[0].set_ylim(30, 46)
    fig.suptitle("R = 22 mm on the 5 mm layer, d = 0.2 mm, k = 1 N/mm: τk = 36 kPa (dashed), τs = 45 kPa (dotted)")
    fig.tight_layout()
    fig.savefig(path, dpi=110)


if __name__ == "__main__":
    main()
