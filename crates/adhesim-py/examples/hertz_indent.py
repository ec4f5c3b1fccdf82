"""One non-adhesive Hertz solve from a cold start through the Python objects: the same
calls, in the same order, as the Rust example `crates/adhesim/examples/hertz_indent.rs`
(whose timings it is compared with in docs/python.md).

    python crates/adhesim-py/examples/hertz_indent.py [N]
"""

import sys
import time

import adhesim


def main(n: int = 512) -> None:
    grid = adhesim.Grid(n, 1.0, "free")
    start = time.perf_counter()
    operator = adhesim.HalfSpace(grid, adhesim.Material(1.0))
    setup = time.perf_counter() - start
    heights = adhesim.geometry.sphere(grid, 1.0)
    depth = 0.25**2  # contact radius L/4 = N/4 elements
    start = time.perf_counter()
    nested = adhesim.NestedActiveSet(operator)
    nested_setup = time.perf_counter() - start
    hertz = adhesim.reference.hertz(1.0, 1.0, depth)
    start = time.perf_counter()
    report = nested.solve(heights, depth)
    solve = time.perf_counter() - start
    print(
        f"nested active set: setup {nested_setup:.3f} s (+ operator {setup:.3f} s), solve {solve:.3f} s, "
        f"{report.iterations} CG iterations, {report.operator_applications} FFT pairs, "
        f"force error {report.force / hertz['force'] - 1.0:.2e}, force {report.force!r}"
    )
    start = time.perf_counter()
    report = adhesim.Ccg(operator).solve(heights, depth)
    solve = time.perf_counter() - start
    print(
        f"Polonsky-Keer CCG, N = {n}: setup {setup:.3f} s, solve {solve:.3f} s, {report.iterations} iterations, "
        f"{report.operator_applications} FFT pairs, force error {report.force / hertz['force'] - 1.0:.2e}, "
        f"force {report.force!r}"
    )


if __name__ == "__main__":
    main(int(sys.argv[1]) if len(sys.argv) > 1 else 512)
