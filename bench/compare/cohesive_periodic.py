"""adhesim against Adhesion/ContactMechanics: the exponential cohesive law on a periodic cell.

Run from the repository root with the harness' environment (compare.py creates it):

    bench/compare/.venv/bin/python bench/compare/cohesive_periodic.py [N ...]

Case (docs/validation.md §13): periodic cell of side λ = 1, N×N elements, E* = 1, bump
z = h(2 − cos 2πx − cos 2πy)/2 with h = 1e-3, exponential law −γ0·exp(−g/ρ) with
γ0 = α²π²h²/2 (α = 0.3) and ρ = γ0/(p*/2), p* = πh. Both codes step the depth (offset)
from −h to 0.6h in 80 steps of h/50, each step warm-started from the previous one:
adhesim's `CohesiveSolver` (the ignored test `peer_side_exponential_approach`), and
Adhesion's `BoundedSmoothContactSystem` (hard wall + `Exponential(γ0, ρ)`) on
`PeriodicFFTElasticHalfSpace`, L-BFGS-B with gtol = 1e-6·(γ0/ρ)/N² (projected gradient,
per-element force). Reported: mean pressure over p* at every depth, the largest
difference over the largest |F|, and the wall time of the 81 steps (setup excluded).
"""
import json
import math
import os
import subprocess
import sys
import time

H = 1e-3
ALPHA = 0.3
GAMMA = ALPHA**2 * math.pi**2 * H**2 / 2
PSTAR = math.pi * H
RHO = GAMMA / (0.5 * PSTAR)
DEPTHS = [-H + i * H / 50 for i in range(81)]


def peer(n):
    import numpy as np
    from Adhesion.Interactions import Exponential
    from Adhesion.System import BoundedSmoothContactSystem
    from ContactMechanics import PeriodicFFTElasticHalfSpace
    from SurfaceTopography import Topography

    x = (np.arange(n) - n // 2) / n
    c = np.cos(2 * np.pi * x)
    z = 0.5 * H * (2 - c[:, None] - c[None, :])
    substrate = PeriodicFFTElasticHalfSpace((n, n), 1.0, (1.0, 1.0))
    system = BoundedSmoothContactSystem(substrate, Exponential(GAMMA, RHO), Topography(-z, (1.0, 1.0), periodic=True))
    curve, disp, failures = [], None, 0
    start = time.perf_counter()
    for d in DEPTHS:
        result = system.minimize_proxy(offset=d, initial_displacements=disp, lbounds="auto",
                                       options=dict(gtol=1e-6 * (GAMMA / RHO) / n**2, ftol=0, maxcor=10,
                                                    maxiter=100000))
        disp = system.disp
        failures += not result.success
        curve.append(float(system.compute_normal_force()) / PSTAR)
    return curve, time.perf_counter() - start, failures


def adhesim(n):
    command = ["cargo", "test", "--release", "-q", "-p", "adhesim", "--test", "validation_cohesive_periodic",
               "peer_side", "--", "--ignored", "--nocapture"]
    out = subprocess.run(command, env=dict(os.environ, ADHESIM_N=str(n)), capture_output=True, text=True,
                         check=True).stdout
    curve, elapsed = [], None
    for line in out.splitlines():
        parts = line.split()
        if len(parts) == 2:
            curve.append(float(parts[1]))
        elif line.startswith(f"N {n}:"):
            elapsed = float(parts[-2])
    return curve, elapsed


def main():
    sizes = [int(a) for a in sys.argv[1:]] or [64, 128]
    rows = []
    for n in sizes:
        ours, our_time = adhesim(n)
        theirs, their_time, failures = peer(n)
        scale = max(abs(f) for f in ours)
        worst = max(abs(a - b) for a, b in zip(ours, theirs)) / scale
        far = abs(ours[0] - theirs[0]) / abs(theirs[0])
        rows.append(dict(n=n, adhesim_s=our_time, peer_s=their_time, peer_failures=failures,
                         max_tension_adhesim=-min(ours), max_tension_peer=-min(theirs),
                         worst_difference=worst, difference_at_minus_h=far))
        print(json.dumps(rows[-1]))
    print("| N | adhesim (s) | Adhesion (s) | ratio | max tension adhesim / peer (p*) | max diff / max|F| |")
    print("|---|---|---|---|---|---|")
    for r in rows:
        print(f"| {r['n']} | {r['adhesim_s']:.2f} | {r['peer_s']:.1f} | {r['peer_s'] / r['adhesim_s']:.1f} | "
              f"{r['max_tension_adhesim']:.5f} / {r['max_tension_peer']:.5f} | {r['worst_difference']:.3f} |")


if __name__ == "__main__":
    main()
