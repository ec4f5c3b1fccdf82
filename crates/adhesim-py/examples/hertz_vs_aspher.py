"""One Hertz solve at N = 512 from Python: adhesim against ASPHER, side by side in one
process (BENCHMARKS.md §How do we compare with the peers). The problem of bench/compare
(R = E* = 1, L = 1, contact radius L/4, element centres at (i - N/2) L/N), ROUNDS
interleaved rounds, medians.

    pip install "aspher==0.1.3.post1"   # builds from source; needs libeigen3-dev
    RAYON_NUM_THREADS=1 OMP_NUM_THREADS=1 python crates/adhesim-py/examples/hertz_vs_aspher.py 512 3

adhesim: NestedActiveSet (its default tolerance) and Ccg, the operator and coarse levels
built apart (reported as set-up). ASPHER: `solve_nested` (set-up inside the call) and
`ContactSolver.solve(precond="fourier")`, tol = 1e-8, the settings of bench/compare
(matched accuracy there).
"""

import math
import statistics
import sys
import time

import numpy as np

import adhesim

R, E_STAR, L = 1.0, 1.0, 1.0
DEPTH = (L / 4) ** 2 / R
TOL_ASPHER = 1e-8


def hertz_force(depth):
    return 4.0 / 3.0 * E_STAR * math.sqrt(R) * max(depth, 0.0) ** 1.5


def adhesim_solves(n):
    grid = adhesim.Grid(n, L, "free")
    start = time.perf_counter()
    operator = adhesim.HalfSpace(grid, adhesim.Material(E_STAR))
    nested = adhesim.NestedActiveSet(operator)
    setup = time.perf_counter() - start
    heights = adhesim.geometry.sphere(grid, R)
    start = time.perf_counter()
    report = nested.solve(heights, DEPTH)
    nested_time = time.perf_counter() - start
    nested_error = report.force / hertz_force(DEPTH) - 1.0
    start = time.perf_counter()
    report = adhesim.Ccg(operator).solve(heights, DEPTH)
    ccg_time = time.perf_counter() - start
    ccg_error = report.force / hertz_force(DEPTH) - 1.0
    return {
        "adhesim nested active set": (nested_time, nested_error, setup),
        "adhesim Polonsky-Keer CCG": (ccg_time, ccg_error, setup),
    }


def aspher_solves(n, aspher):
    x = (np.arange(n) - n // 2) * (L / n)
    xx, yy = np.meshgrid(x, x, indexing="ij")
    z = ((xx**2 + yy**2) / (2.0 * R)).ravel()
    force = hertz_force(DEPTH)
    out = {}
    start = time.perf_counter()
    result = aspher.solve_nested(n, z, force / L**2, domain_size=L, E_star=E_STAR, tol=TOL_ASPHER, backend="fft")
    elapsed = time.perf_counter() - start
    # load control: the error at fixed depth is F/F_Hertz(d_computed) - 1
    out["ASPHER solve_nested (set-up inside)"] = (elapsed, force / hertz_force(result.approach) - 1.0, 0.0)
    start = time.perf_counter()
    solver = aspher.ContactSolver(grid_size=n, domain_size=L, E_star=E_STAR, backend="fft")
    setup = time.perf_counter() - start
    start = time.perf_counter()
    result = solver.solve(z, p_nominal=force / L**2, tol=TOL_ASPHER, precond="fourier", max_iter=100000)
    elapsed = time.perf_counter() - start
    out["ASPHER ContactSolver.solve(fourier)"] = (elapsed, force / hertz_force(result.approach) - 1.0, setup)
    return out


def main():
    n = int(sys.argv[1]) if len(sys.argv) > 1 else 512
    rounds = int(sys.argv[2]) if len(sys.argv) > 2 else 3
    try:
        import aspher
    except ImportError as error:
        sys.exit(f"ASPHER is not installed ({error}): pip install 'aspher==0.1.3.post1' (needs libeigen3-dev)")
    rows = {}
    for k in range(rounds):
        parts = (lambda: adhesim_solves(n), lambda: aspher_solves(n, aspher))
        for part in parts if k % 2 == 0 else parts[::-1]:
            for name, entry in part().items():
                rows.setdefault(name, []).append(entry)
                print(f"round {k}: {name}: solve {entry[0]:.3f} s, force error {entry[1]:.2e}", flush=True)
    print(f"\nN = {n}, {rounds} interleaved rounds, medians:")
    for name, entries in rows.items():
        solve = statistics.median(e[0] for e in entries)
        setup = statistics.median(e[2] for e in entries)
        print(f"| {name} | {solve:.3f} s (min {min(e[0] for e in entries):.3f}) | set-up {setup:.3f} s | "
              f"force error {entries[-1][1]:.2e} |")


if __name__ == "__main__":
    main()
