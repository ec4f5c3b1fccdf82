#!/usr/bin/env python3
"""Paired wall-time comparison of `adhesim run` builds (BENCHMARKS.md, "How fast is a run").

Runs the same scenario with each build in turn (A B A B ...: rounds), so that a drift of
the machine's speed during the measurement falls on every build alike, and prints for each
build the median wall and CPU time, the FFT pairs per step and the wall time per FFT pair,
its median ratio to the first build taken round by round, and whether its contact sizes
(`n_contact`, `radius` of curve.csv) equal the first build's at every step. The header
states the machine and its load average before and after.

    python3 bench/wall/paired.py --runs 3 \\
        --build f10981a=/path/to/old/adhesim --build today=target/release/adhesim \\
        -- scenarios/fig1.toml --set grid.n=512 --set protocol.steps=75

Everything after `--` goes to `adhesim run` as given (with `--out`, `--force` and
`--quiet` added); `--threads T` is passed on when given. Only the standard library.
"""
import argparse
import csv
import datetime
import json
import os
import platform
import statistics
import subprocess
import sys
import tempfile
import time


def machine() -> str:
    model = platform.processor() or "unknown CPU"
    try:
        with open("/proc/cpuinfo") as info:
            for line in info:
                if line.startswith("model name"):
                    model = line.split(":", 1)[1].strip()
                    break
    except OSError:
        pass
    memory = ""
    try:
        with open("/proc/meminfo") as info:
            total_kib = int(info.readline().split()[1])
            memory = f", {total_kib / 2**20:.0f} GiB"
    except (OSError, ValueError, IndexError):
        pass
    return f"{model}, {os.cpu_count()} logical CPUs{memory}"


def load() -> str:
    try:
        return "/".join(f"{value:.2f}" for value in os.getloadavg())
    except OSError:
        return "unknown"


def run_once(binary: str, arguments: list, out: str, threads) -> dict:
    command = [binary, "run", *arguments, "--out", out, "--force", "--quiet"]
    if threads is not None:
        command += ["--threads", str(threads)]
    start = time.perf_counter()
    process = subprocess.Popen(command, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    _, status, usage = os.wait4(process.pid, 0)
    wall = time.perf_counter() - start
    stderr = process.stderr.read().decode(errors="replace")
    process.stderr.close()
    if status != 0:
        sys.exit(f"error: `{' '.join(command)}` failed (status {status}):\n{stderr}")
    with open(os.path.join(out, "summary.json")) as file:
        performance = json.load(file)["performance"]
    with open(os.path.join(out, "curve.csv")) as file:
        contact = [(row["n_contact"], row["radius"]) for row in csv.DictReader(file)]
    return {
        "wall": wall,
        "cpu": usage.ru_utime + usage.ru_stime,
        "fft_pairs": performance["fft_pairs"],
        "steps": performance["steps"],
        "contact": contact,
    }


def first_difference(a: list, b: list):
    """The first step where two contact-size lists differ (None: identical)."""
    for step, (x, y) in enumerate(zip(a, b)):
        if x != y:
            return step
    return None if len(a) == len(b) else min(len(a), len(b))


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--build", action="append", required=True, metavar="LABEL=BINARY",
                        help="a build to time (at least two; the first is the reference of the ratios)")
    parser.add_argument("--runs", type=int, default=3, help="rounds (each build once per round; default 3)")
    parser.add_argument("--threads", type=int, default=None, help="passed on as `--threads`")
    parser.add_argument("scenario", nargs=argparse.REMAINDER, help="-- then the arguments of `adhesim run`")
    options = parser.parse_args()
    arguments = options.scenario[1:] if options.scenario[:1] == ["--"] else options.scenario
    if not arguments:
        parser.error("give the scenario after `--`")
    if options.runs < 1:
        parser.error(f"--runs must be at least 1, got {options.runs}")
    builds = []
    for entry in options.build:
        label, separator, binary = entry.partition("=")
        if not separator or not os.access(binary, os.X_OK):
            parser.error(f"--build {entry!r}: expected LABEL=BINARY with an executable BINARY")
        builds.append((label, binary))
    if len(builds) < 2:
        parser.error("give at least two --build")

    started = datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d %H:%M UTC")
    load_before = load()
    results = {label: [] for label, _ in builds}
    with tempfile.TemporaryDirectory(prefix="adhesim-paired-") as scratch:
        for round_index in range(options.runs):
            for label, binary in builds:
                out = os.path.join(scratch, f"{label}-{round_index}")
                result = run_once(binary, arguments, out, options.threads)
                results[label].append(result)
                print(f"round {round_index + 1}/{options.runs} {label}: {result['wall']:.1f} s wall",
                      file=sys.stderr, flush=True)
    load_after = load()

    reference_label = builds[0][0]
    reference = results[reference_label]
    print(f"`adhesim run {' '.join(arguments)}`"
          + (f" --threads {options.threads}" if options.threads else "")
          + f", {options.runs} rounds ({started}; {machine()}; load average before {load_before}, after {load_after})")
    print()
    print(f"| build | wall, median (min–max) | CPU, median | FFT pairs per step | wall per FFT pair "
          f"| wall ratio to {reference_label}, median of rounds | contact sizes as {reference_label} |")
    print("|---|---|---|---|---|---|---|")
    for label, _ in builds:
        runs = results[label]
        walls = [r["wall"] for r in runs]
        wall = statistics.median(walls)
        cpu = statistics.median(r["cpu"] for r in runs)
        pairs, steps = runs[0]["fft_pairs"], runs[0]["steps"]
        ratio = statistics.median(r["wall"] / ref["wall"] for r, ref in zip(runs, reference))
        difference = first_difference(reference[0]["contact"], runs[0]["contact"])
        same = "yes, every step" if difference is None else f"no: first differs at step {difference}"
        print(f"| {label} | {wall:.1f} s ({min(walls):.1f}–{max(walls):.1f}) | {cpu:.1f} s "
              f"| {pairs / steps:.1f} | {1e3 * wall / pairs:.2f} ms | {ratio:.3f} | {same} |")


if __name__ == "__main__":
    main()
