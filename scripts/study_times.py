#!/usr/bin/env python3
"""Per-run and whole-study times of a rolling or sliding study folder (BENCHMARKS.md §How
fast is a run of each kind › Rolling and sliding studies at 16 per λ).

Reads the runs' summary.json (performance) and the normal runs' record.json of
`adhesim study` output (or of its snapshot under docs/data/paper/campaign/) and prints,
per α, the translations' wall time, FFT pairs per step and the share of the approach, then
the totals. A run resumed from a checkpoint reports the wall time of its last process only,
but its phase times add up over the processes: the larger of the two is taken. Runs without a
summary.json (studies before 2026-11-27 kept record.json only) are not counted.

    python3 scripts/study_times.py docs/data/paper/campaign/fig7_rolling_512
"""
import glob
import json
import os
import sys


def main():
    folder = sys.argv[1]
    by_alpha = {}
    normal = []
    for path in sorted(glob.glob(os.path.join(folder, "cases", "*", "record.json"))):
        case = os.path.dirname(path)
        name = os.path.basename(case)
        if name.startswith("normal-"):
            normal.append(json.load(open(path))["wall_seconds"])
            continue
        summary_path = os.path.join(case, "summary.json")
        if not os.path.exists(summary_path):
            continue
        summary = json.load(open(summary_path))
        perf = summary["performance"]
        approach = perf.get("phase_steps", {}).get("approach", 0)
        approach_seconds = perf.get("phase_seconds", {}).get("approach", 0.0)
        alpha_index = int(name.split("-")[1])
        seconds = max(perf["wall_seconds"], sum(perf.get("phase_seconds", {}).values()))
        by_alpha.setdefault(alpha_index, []).append((seconds, perf["fft_pairs_per_step"], approach, approach_seconds))
    total = 0.0
    runs = 0
    for alpha_index in sorted(by_alpha):
        rows = by_alpha[alpha_index]
        walls = [r[0] for r in rows]
        pairs = [r[1] for r in rows]
        share = [r[3] / r[0] for r in rows if r[0] > 0]
        total += sum(walls)
        runs += len(rows)
        print(
            f"alpha #{alpha_index}: {len(rows)} runs, {min(walls):.0f}-{max(walls):.0f} s each "
            f"(sum {sum(walls) / 60:.0f} min), {min(pairs):.0f}-{max(pairs):.0f} FFT pairs per step, "
            f"approach {100 * min(share):.0f}-{100 * max(share):.0f} % of the run"
        )
    print(
        f"{runs} translations: {total / 3600:.2f} h; {len(normal)} normal runs: {sum(normal) / 3600:.2f} h; "
        f"together {(total + sum(normal)) / 3600:.2f} h of wall time"
    )


if __name__ == "__main__":
    main()
