#!/usr/bin/env python3
"""A finite-thickness periodic layer side by side: adhesim against ContactMechanics.

    python3 -m venv /tmp/cmvenv && /tmp/cmvenv/bin/pip install ContactMechanics==1.8.3
    /tmp/cmvenv/bin/python bench/compare/layer.py [--adhesim target/release/adhesim] [--n 128 256]
        [--poisson 0.5] [--repeats 3] [--no-element-kernel] [--out bench/compare/layer_results.md]

(or bench/compare/.venv/bin/python after compare.py has made it.)

The case: a rigid paraboloid z = r²/(2R), R = 1, pressed without adhesion into an elastic
layer bonded to a rigid base, E = 3, ν = 1/2 (G = 1, E* = 4), on a periodic cell of side
L = 1 with N × N elements centred at x_i = (i − N/2)L/N, thicknesses t = 0.25, 0.125, 0.0625,
depths d = 0.004, 0.008, 0.012, 0.016 from first contact (the apex at the surface's mean).
Reported per (t, d): the normal force F and the number of contact elements of both codes,
a/t with a = √(A/π) from adhesim's contact area, and each code's wall time per solve.

adhesim: `adhesim run` (`--threads 1`) of an `indent_pulloff` scenario written on the fly
(`material.thickness`, `base = "bonded"`, `grid.boundary = "periodic"`), one run per depth
with a single approach step (a cold solve); F and the contact elements from curve.csv, the
solve time from summary.json's `phase_seconds.approach` less that of a run to a depth of
1e-6·d (the operator's setup, reported on its own).
ContactMechanics: `PeriodicFFTElasticHalfSpace(..., thickness=t, poisson=ν)` and
`constrained_conjugate_gradients` (Polonsky–Keer) at `offset` = d on the topography
h = −r²/(2R) (its gap is u − h − offset ≥ 0: the rigid surface lies below the substrate, so
h is the paraboloid turned over), cold start at each depth, OMP_NUM_THREADS = 1.

The two kernels. ContactMechanics' finite-thickness Green's function (Carbone & Mangialardi
2008, eq. A.30) is a layer bonded to a rigid base; its stiffness factor over the
half-space's, (κ cosh 2s + 2s² + 8ν² − 12ν + 5)/(κ sinh 2s − 2s) with s = kt, κ = 3 − 4ν, is
the inverse of adhesim's bonded `layer_compliance_factor` (8ν² − 12ν + 5 = (1 + κ²)/2).
They differ in two ways: (1) at q = 0 ContactMechanics keeps the layer's uniaxial
stiffness E(1 − ν)/(t(1 − 2ν)(1 + ν)), adhesim drops the q = 0 term (its depth is the mean
gap's); at ν = 1/2 that stiffness is infinite, its compliance 0, and the two agree (with a
Python float E ContactMechanics raises ZeroDivisionError at ν = 1/2: E is passed as a NumPy
float, which gives inf and a warning); (2) the discretisation: ContactMechanics collocates
the continuous kernel at the grid points (Stanley & Kato), adhesim takes uniform pressure on
each element (the element-consistent alias sum over ±40 aliases, docs/physics.md §1b, §9.3).
To separate (2) from the model, a third column runs ContactMechanics' solver with adhesim's
element kernel put into its substrate (`--no-element-kernel` skips it): it must reproduce
adhesim's numbers to the solvers' tolerance if the models are the same. With `--poisson`
below 1/2 the q = 0 difference is bridged: each row also runs adhesim at the depth
d − C(0)F_CM/L², C(0) = t(1 − 2ν)(1 + ν)/(E(1 − ν)), which is ContactMechanics' state at
offset d (its mean displacement C(0)·mean(p) taken out).
Writes bench/compare/layer_results.md (`--out` elsewhere).
"""
import argparse
import csv
import datetime
import json
import math
import os
import platform
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

for variable in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS", "RAYON_NUM_THREADS"):
    os.environ[variable] = "1"

import numpy as np  # noqa: E402

ROOT = Path(__file__).resolve().parents[2]
E, NU, R, L = 3.0, 0.5, 1.0, 1.0  # NU: --poisson
THICKNESSES = (0.25, 0.125, 0.0625)
DEPTHS = (0.004, 0.008, 0.012, 0.016)
ALIASES = 40


def scenario(n, thickness, max_depth, steps):
    return f"""[grid]
n = {n}
size = {L}
boundary = "periodic"
[material]
youngs_modulus = {E}
poisson_ratio = {NU}
thickness = {thickness}
base = "bonded"
[adhesion]
work_of_adhesion = 0.0
[indenter]
shape = "sphere"
radius = {R}
[protocol]
kind = "indent_pulloff"
max_depth = {max_depth}
depth_unit = "length"
steps = {steps}
"""


def adhesim_once(binary, n, thickness, depth, folder):
    """One run whose approach is a single cold step from first contact to `depth`: the
    force, the contact elements and the approach's time (summary.json `phase_seconds`; it
    includes the operator's setup, which the first step pays)."""
    tag = f"{n}_{thickness}_{depth:.3e}"
    path = folder / f"layer_{tag}.toml"
    path.write_text(scenario(n, thickness, depth, 1))
    out = folder / f"out_{tag}"
    subprocess.run([str(binary), "run", str(path), "--out", str(out), "--quiet", "--force", "--threads", "1"],
                   check=True, stderr=subprocess.DEVNULL)  # its warnings: one step, a one-element setup run
    rows = [row for row in csv.DictReader((out / "curve.csv").open()) if row["phase"] == "approach"]
    if len(rows) != 1 or abs(float(rows[0]["d"]) - depth) > 1e-12 * max(depth, 1e-3):
        raise RuntimeError(f"unexpected approach in {out / 'curve.csv'}: {rows}")
    summary = json.loads((out / "summary.json").read_text())
    return float(rows[0]["force_normal"]), int(rows[0]["n_contact"]), summary["performance"]["phase_seconds"]["approach"]


def run_adhesim(binary, n, thickness, folder, repeats):
    """Returns {depth: (force, contact elements, solve seconds)} and the setup seconds: the
    approach of a run to 1e-6 of the first depth (one element in contact), which the solve
    times have subtracted (the retraction that follows each run is not used); times are
    medians of `repeats` runs."""
    setup = statistics.median(adhesim_once(binary, n, thickness, DEPTHS[0] * 1e-6, folder)[2] for _ in range(repeats))
    found = {}
    for depth in DEPTHS:
        runs = [adhesim_once(binary, n, thickness, depth, folder) for _ in range(repeats)]
        seconds = statistics.median(run[2] for run in runs)
        found[depth] = (runs[0][0], runs[0][1], max(seconds - setup, 0.0))
    return found, setup


def element_kernel(substrate, n, thickness):
    """adhesim's element-consistent layer compliance (docs/physics.md §9.3) on
    ContactMechanics' Fourier layout: Σ 2 S(Q) f(|Q|t)/(E*|Q|) over Q = q + (2π/Δ)(m, m'),
    |m|, |m'| ≤ 40, zero at q = 0."""
    delta = L / n
    estar = E / (1 - NU**2)
    kappa = 3 - 4 * NU

    def axis(count, start, length):
        index = np.arange(start, start + length, dtype=float)
        index = np.where(index <= n // 2, index, index - n)
        return 2 * np.pi * index / L

    qx = axis(n, substrate.fourier_locations[0], substrate.nb_fourier_grid_pts[0])[:, None]
    qy = axis(n, substrate.fourier_locations[1], substrate.nb_fourier_grid_pts[1])[None, :]
    total = np.zeros((qx.shape[0], qy.shape[1]))
    shifts = 2 * np.pi * np.arange(-ALIASES, ALIASES + 1) / delta
    for gx in shifts:
        big_x = qx + gx
        sx = np.sinc(big_x * delta / (2 * np.pi))  # numpy's sinc is sin(πx)/(πx)
        for gy in shifts:
            big_y = qy + gy
            sy = np.sinc(big_y * delta / (2 * np.pi))
            k = np.sqrt(big_x**2 + big_y**2)
            with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
                s = k * thickness
                f = np.where(s >= 25, 1.0,
                             (kappa * np.sinh(2 * s) - 2 * s)
                             / (kappa * np.cosh(2 * s) + 2 * s * s + 0.5 * (1 + kappa**2)))
                term = 2 * sx * sy * f / (estar * k)
            total += np.where(k > 0, term, 0.0)
    return total


def run_contactmechanics(n, thickness, element, repeats=1):
    from ContactMechanics import PeriodicFFTElasticHalfSpace
    from ContactMechanics.Optimization import constrained_conjugate_gradients
    from SurfaceTopography import Topography
    import warnings

    x = (np.arange(n) - n // 2) * (L / n)
    xx, yy = np.meshgrid(x, x, indexing="ij")
    topography = Topography(-(xx**2 + yy**2) / (2 * R), physical_sizes=(L, L), periodic=True)
    start = time.perf_counter()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)  # E(1 − ν)/(t(1 − 2ν)(1 + ν)) = inf at ν = 1/2
        substrate = PeriodicFFTElasticHalfSpace((n, n), np.float64(E), physical_sizes=(L, L),
                                                thickness=thickness, poisson=NU)
    if element:
        green = element_kernel(substrate, n, thickness)
        substrate.greens_function = green.astype(complex)
        substrate.surface_stiffness = substrate._compute_surface_stiffness()
    setup = time.perf_counter() - start
    results = {}
    for depth in DEPTHS:
        f_scale = 4.0 / 3.0 * E / (1 - NU**2) * math.sqrt(R) * depth**1.5
        walls = []
        for _ in range(repeats):
            start = time.perf_counter()
            result = constrained_conjugate_gradients(substrate, topography, offset=depth, pentol=1e-9 * depth,
                                                     forcetol=1e-10 * f_scale, thermotol=1e-10)
            walls.append(time.perf_counter() - start)
        wall = statistics.median(walls)
        if not result.success:
            raise RuntimeError(f"ContactMechanics did not converge at t = {thickness}, d = {depth}: {result.message}")
        forces = np.asarray(result.jac)
        results[depth] = (float(forces.sum()), int((forces > 0).sum()), wall, int(result.nit))
    return results, setup


def load_average():
    return Path("/proc/loadavg").read_text().split()[:3]


def cpu_model():
    for line in Path("/proc/cpuinfo").read_text().splitlines():
        if line.startswith("model name"):
            return line.split(":", 1)[1].strip()
    return "unknown"


def versions(binary):
    import importlib.metadata as metadata

    found = {"adhesim": subprocess.run([str(binary), "--version"], capture_output=True, text=True).stdout.strip().removeprefix("adhesim ")}
    try:
        found["adhesim commit"] = subprocess.run(["git", "-C", str(ROOT), "rev-parse", "--short", "HEAD"],
                                                 capture_output=True, text=True).stdout.strip()
    except OSError:
        pass
    for package in ("ContactMechanics", "SurfaceTopography", "muGrid", "NuMPI", "numpy"):
        try:
            found[package] = metadata.version(package)
        except metadata.PackageNotFoundError:
            found[package] = "not installed"
    found["python"] = platform.python_version()
    return found


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--adhesim", default=str(ROOT / "target" / "release" / "adhesim"))
    parser.add_argument("--n", type=int, nargs="+", default=[128])
    parser.add_argument("--no-element-kernel", action="store_true")
    parser.add_argument("--poisson", type=float, default=0.5,
                        help="ν of the layer (default 1/2); below 1/2 adhesim's depth for the CM column is "
                             "d − C(0)·F_CM/L² (see the docstring)")
    parser.add_argument("--repeats", type=int, default=3, help="timed runs per solve (median)")
    parser.add_argument("--out", default=str(Path(__file__).resolve().parent / "layer_results.md"))
    args = parser.parse_args()
    global NU
    NU = args.poisson
    binary = Path(args.adhesim).resolve()
    load_before = load_average()
    date = datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d %H:%M UTC")
    header = ("| N | t | d | a/t | F adhesim | F CM | F CM/adhesim − 1 | F CM (element kernel)/adhesim − 1 "
              "| contact elements adhesim / CM / CM (element kernel) | solve ms adhesim / CM |")
    rows = [header, "|" + "---|" * 10]
    setups = []
    print(header, flush=True)
    print(rows[1], flush=True)
    with tempfile.TemporaryDirectory(prefix="adhesim-layer-") as scratch:
        for n in args.n:
            for thickness in THICKNESSES:
                mine, mine_setup = run_adhesim(binary, n, thickness, Path(scratch), args.repeats)
                theirs, their_setup = run_contactmechanics(n, thickness, element=False, repeats=args.repeats)
                element = None
                if not args.no_element_kernel:
                    element, element_setup = run_contactmechanics(n, thickness, element=True)
                setups.append((n, thickness, mine_setup, their_setup))
                for depth in DEPTHS:
                    force, contact, seconds = mine[depth]
                    radius = math.sqrt(contact * (L / n) ** 2 / math.pi)
                    peer = theirs[depth]
                    matched = ""
                    if NU < 0.5:
                        # ContactMechanics' offset includes the uniform compression C(0)·mean(p),
                        # adhesim's depth does not: the same state is adhesim's d − C(0)F/L².
                        compliance = thickness * (1 - 2 * NU) * (1 + NU) / (E * (1 - NU))
                        shifted = depth - compliance * peer[0] / L**2
                        force_at, contact_at, _ = adhesim_once(binary, n, thickness, shifted, Path(scratch))
                        matched = (f" (adhesim at d − C(0)F/L² = {shifted:.5g}: F = {force_at:.6g}, "
                                   f"{contact_at} elements, CM/that − 1 = {peer[0] / force_at - 1:+.2%})")
                    same = f"{element[depth][0] / force - 1:+.1e}" if element else "—"
                    same_contact = str(element[depth][1]) if element else "—"
                    row = (f"| {n} | {thickness} | {depth} | {radius / thickness:.2f} | {force:.6g} | {peer[0]:.6g} "
                           f"| {peer[0] / force - 1:+.2%} | {same} | {contact} / {peer[1]} / {same_contact} "
                           f"| {1e3 * seconds:.1f} / {1e3 * peer[2]:.1f} |{matched}")
                    rows.append(row)
                    print(row, flush=True)
    load_after = load_average()
    lines = [
        "# Finite-thickness periodic layer: adhesim and ContactMechanics",
        "",
        f"Made by `bench/compare/layer.py` ({' '.join(['python', 'bench/compare/layer.py'] + sys.argv[1:])}) "
        f"on {date}; {cpu_model()}, {os.cpu_count()} cores, one thread each; load average "
        f"{' '.join(load_before)} before, {' '.join(load_after)} after.",
        "",
        "Versions: " + ", ".join(f"{k} {v}" for k, v in versions(binary).items()) + ".",
        "",
        f"Case: rigid paraboloid R = {R} on a layer bonded to a rigid base, E = {E}, ν = {NU} (E* = "
        f"{E / (1 - NU**2):g}), periodic cell L = {L}, N × N elements, no adhesion; d from first contact "
        + ("(mean-gap control in both: at ν = 1/2 ContactMechanics' q = 0 compliance is 0). " if NU == 0.5 else
           "(ContactMechanics' offset includes the layer's uniform compression C(0)·F/L², "
           "C(0) = t(1 − 2ν)(1 + ν)/(E(1 − ν)); adhesim's depth does not: the F CM column compares at the same d, "
           "the note after a row at adhesim's depth d − C(0)F_CM/L², the same state; the element-kernel column "
           "has C(0) = 0 as adhesim). ")
        + "a = √(A/π) from "
        "adhesim's contact elements. 'CM (element kernel)': ContactMechanics' solver with adhesim's "
        "element-consistent kernel in its substrate (the same model and discretisation as adhesim). "
        f"Solve times: one cold solve at each depth, median of {args.repeats}; adhesim's "
        "`phase_seconds.approach` less that of its setup run, ContactMechanics' "
        "`constrained_conjugate_gradients` call (pentol 1e-9·d, forcetol 1e-10·F_Hertz(d), thermotol 1e-10; "
        "adhesim's default tolerances).",
        "",
    ] + rows + [
        "",
        "Setup (operator/kernel) seconds, adhesim / ContactMechanics (its native kernel): "
        + "; ".join(f"N = {n}, t = {t}: {a:.3f} / {b:.3f}" for n, t, a, b in setups) + ".",
        "",
    ]
    Path(args.out).write_text("\n".join(lines))
    print(f"wrote {args.out}", file=sys.stderr)


if __name__ == "__main__":
    main()
