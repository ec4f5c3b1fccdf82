#!/usr/bin/env python3
"""Tangential contact side by side: adhesim's shear against Tamaas' PolonskyKeerTan.

    python3 bench/compare/compare.py --peers tamaas --problems hertz --sizes 64   # makes .venv
    bench/compare/.venv/bin/python bench/compare/tangential.py [--n 64 128 256]

The case: a rigid sphere (R = 1) on a periodic elastic half-space (E = 3, ν = 1/2, so G = 1
and Goodman's approximation is exact), a cell of side L = 1 with N × N elements, Coulomb
friction μ = 0.3, no adhesion. adhesim (`adhesim run`, the shear protocol, its defaults):
pressed in one step to a depth of the mean gap, then shifted by δ in one step. Tamaas (`surface_2d`
model, `PolonskyKeerTan`): the same surface under the mean traction adhesim's run ended at,
(F_T, 0, F_N)/L², in one solve. Both solve the same problem: one increment of partial slip
from rest under the final pressure (Tamaas solves pressure and shear together; with the
normal problem independent of the shear at ν = 1/2, that is the same optimum).

Reported per N: the pressure and the shear traction of both, their largest differences
relative to the largest value, the stick sets, and the wall times: adhesim's whole `run`
(process, normal step, shift step, outputs and plots) and its solve (summary.json's
`wall_seconds`), and Tamaas' solve alone.
The two discretise differently (adhesim: uniform traction on each element, an aliased
element kernel; Tamaas: point collocation of the continuous kernel), so fields differ at
the contact's edge by O(Δ). Writes bench/compare/tangential_results.md.
"""
import argparse
import json
import math
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[2]
MU, E, NU, R, L = 0.3, 3.0, 0.5, 1.0, 1.0


def scenario(n, depth, shift):
    return f"""[grid]
n = {n}
size = {L}
boundary = "periodic"
[material]
youngs_modulus = {E}
poisson_ratio = {NU}
[adhesion]
work_of_adhesion = 0.0
[indenter]
shape = "sphere"
radius = {R}
[friction]
law = "coulomb"
coefficient = {MU}
[protocol]
kind = "shear"
depth = {depth}
depth_unit = "length"
approach_steps = 1
distance = {shift}
steps = 1
[output]
snapshot_steps = [1]
"""


def run_adhesim(binary, n, depth, shift, folder):
    path = folder / f"shear_{n}.toml"
    path.write_text(scenario(n, depth, shift))
    out = folder / f"out_{n}"
    start = time.perf_counter()
    subprocess.run([str(binary), "run", str(path), "--out", str(out), "--quiet", "--force"], check=True)
    wall = time.perf_counter() - start
    summary = json.loads((out / "summary.json").read_text())
    fields = np.load(out / "fields.npz")
    steps = list(fields["steps"])
    k = steps.index(1)
    return {
        "wall": wall,
        "solve": summary["performance"]["wall_seconds"],
        "pressure": fields["pressure"][k],
        "shear": fields["shear_traction_x"][k],
        "shear_y": fields["shear_traction_y"][k],
        "state": fields["slip_state"][k],
        "normal_force": summary["results"]["normal_force"],
        "tangential_force": summary["results"]["peak_tangential_force"],
        "fft_pairs": summary["performance"]["fft_pairs"],
    }


def run_tamaas(n, pressure_mean, shear_mean):
    """Tamaas' solve, timed at the smallest iteration count that converges: its error
    measure stalls near 5e-7 on this problem (a tolerance below that never stops it, one
    above stops it with tractions 30 % off), so the iteration limit is doubled from 250
    until the tractions change by less than 1e-6 of their largest value; the time is that
    of the run at the smaller limit, the first already converged."""
    import tamaas as tm

    tm.set_log_level(tm.LogLevel.error)
    x = (np.arange(n) - n // 2) * L / n
    xx, yy = np.meshgrid(x, x)
    surface = -(xx**2 + yy**2) / (2 * R)
    surface -= surface.max()

    def solve(iterations):
        model = tm.ModelFactory.createModel(tm.model_type.surface_2d, [L, L], [n, n])
        model.E, model.nu = E, NU
        solver = tm.PolonskyKeerTan(model, surface, 1e-12, MU)
        solver.max_iter = iterations
        start = time.perf_counter()
        solver.solve([shear_mean, 0.0, pressure_mean])
        return time.perf_counter() - start, np.array(model.traction, copy=True)

    iterations = 250
    wall, traction = solve(iterations)
    while True:
        next_wall, next_traction = solve(2 * iterations)
        if np.abs(next_traction - traction).max() < 1e-6 * np.abs(next_traction).max():
            return {"wall": wall, "traction": traction, "iterations": iterations}
        iterations, wall, traction = 2 * iterations, next_wall, next_traction


def compare(n, binary, folder):
    delta = L / n
    depth = (n / 8 * delta) ** 2 / R  # Hertz's a = N/8 elements; the periodic mean gap widens it
    mine = run_adhesim(binary, n, depth, 0.004, folder)
    area = L * L
    theirs = run_tamaas(n, mine["normal_force"] / area, mine["tangential_force"] / area)
    p_t, q_t = theirs["traction"][..., 2], theirs["traction"][..., 0]
    p_a, q_a = mine["pressure"], mine["shear"]
    contact_a = p_a > 0
    stick_a = mine["state"] == 1
    contact_t = p_t > 0
    slip_t = contact_t & (np.hypot(theirs["traction"][..., 0], theirs["traction"][..., 1]) >= MU * p_t * (1 - 1e-6))
    stick_t = contact_t & ~slip_t
    return {
        "n": n,
        "contact elements (adhesim, Tamaas)": (int(contact_a.sum()), int(contact_t.sum())),
        "stick elements (adhesim, Tamaas)": (int(stick_a.sum()), int(stick_t.sum())),
        "max abs Δp / max p": float(np.abs(p_a - p_t).max() / p_a.max()),
        "max abs Δq_x / max q_x": float(np.abs(q_a - q_t).max() / np.abs(q_a).max()),
        "rms Δq_x / rms q_x (contact)": float(
            np.sqrt(np.mean((q_a - q_t)[contact_a] ** 2)) / np.sqrt(np.mean(q_a[contact_a] ** 2))
        ),
        "F_T/F_N": mine["tangential_force"] / mine["normal_force"],
        "adhesim wall (whole run), s": mine["wall"],
        "adhesim solve (summary.json), s": mine["solve"],
        "adhesim FFT pairs": mine["fft_pairs"],
        "Tamaas wall (one solve), s": theirs["wall"],
        "Tamaas iterations": theirs["iterations"],
    }


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--n", type=int, nargs="+", default=[64, 128, 256])
    parser.add_argument("--adhesim", default=os.environ.get("ADHESIM_BIN", ROOT / "target/release/adhesim"))
    args = parser.parse_args()
    rows = []
    with tempfile.TemporaryDirectory() as folder:
        for n in args.n:
            row = compare(n, Path(args.adhesim), Path(folder))
            print(json.dumps(row), flush=True)
            rows.append(row)
    load = os.getloadavg()
    lines = [
        "# Tangential contact: adhesim against Tamaas' PolonskyKeerTan",
        "",
        f"`bench/compare/tangential.py`, {time.strftime('%Y-%m-%d')}, load average {load[0]:.2f}, "
        f"{os.cpu_count()} CPUs; the case is the script's docstring.",
        "",
        "| " + " | ".join(rows[0].keys()) + " |",
        "|" + "---|" * len(rows[0]),
    ]
    for row in rows:
        cells = [f"{v:.3g}" if isinstance(v, float) else str(v) for v in row.values()]
        lines.append("| " + " | ".join(cells) + " |")
    (Path(__file__).parent / "tangential_results.md").write_text("\n".join(lines) + "\n")
    print("\n".join(lines))


if __name__ == "__main__":
    sys.exit(main())
