"""Overhead of `adhesim.run` against the command line for one scenario (BENCHMARKS.md
§The Python call).

Interleaves ROUNDS runs of `adhesim run SCENARIO --quiet` (a process: start-up, run,
curve.csv, snapshots, figures, summary.json) and of `adhesim.run(SCENARIO, out=...)` in
this process (run, curve.csv, summary.json; no figures), alternating which goes first,
and prints per-run wall times, the solver time of each (the sum of
summary.json's performance.phase_seconds), the time spent in the observer between steps
(performance.output_seconds: the CLI's CSV rows and snapshots; Python's signal check,
progress callback and snapshot copies) and the medians. Both curves are checked to be
the same bytes.

    python crates/adhesim-py/examples/run_overhead.py target/release/adhesim scenarios/fig1.toml 3
"""

import json
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import adhesim


def solver_seconds(summary):
    return sum(summary["performance"]["phase_seconds"].values())


def main():
    binary, scenario = sys.argv[1], sys.argv[2]
    rounds = int(sys.argv[3]) if len(sys.argv) > 3 else 3
    extra = sys.argv[4:]  # --set KEY=VALUE pairs for both
    overrides = dict(item.split("=", 1) for item in extra[1::2]) if extra else {}
    with tempfile.TemporaryDirectory() as tmp:
        tmp = Path(tmp)
        rows = []
        for k in range(rounds):
            order = ("cli", "py") if k % 2 == 0 else ("py", "cli")
            for which in order:
                out = tmp / f"{which}{k}"
                start = time.perf_counter()
                if which == "cli":
                    subprocess.run([binary, "run", scenario, "--out", str(out), "--quiet", *extra], check=True)
                else:
                    adhesim.run(scenario, out=out, overrides={key: _toml(v) for key, v in overrides.items()})
                wall = time.perf_counter() - start
                summary = json.loads((out / "summary.json").read_text())
                observer = summary["performance"]["output_seconds"]
                rows.append((which, k, wall, solver_seconds(summary), observer))
                print(
                    f"{which} round {k}: wall {wall:.2f} s, solver {solver_seconds(summary):.2f} s, "
                    f"observer {observer * 1e3:.1f} ms over {summary['performance']['steps']} steps",
                    flush=True,
                )
        assert (tmp / "cli0" / "curve.csv").read_bytes() == (tmp / "py0" / "curve.csv").read_bytes()
    for which in ("cli", "py"):
        walls = [r[2] for r in rows if r[0] == which]
        solver = [r[3] for r in rows if r[0] == which]
        observer = [r[4] for r in rows if r[0] == which]
        print(
            f"{which}: wall median {statistics.median(walls):.2f} s (min {min(walls):.2f}), "
            f"solver median {statistics.median(solver):.2f} s (min {min(solver):.2f}), "
            f"observer median {statistics.median(observer) * 1e3:.1f} ms"
        )
    cli = statistics.median(r[2] for r in rows if r[0] == "cli")
    py = statistics.median(r[2] for r in rows if r[0] == "py")
    print(f"python/cli wall (medians): {py / cli:.3f}")


def _toml(text):
    """A --set VALUE as the Python value adhesim.run takes (TOML scalars)."""
    for convert in (int, float):
        try:
            return convert(text)
        except ValueError:
            pass
    return text.strip('"')


if __name__ == "__main__":
    main()
