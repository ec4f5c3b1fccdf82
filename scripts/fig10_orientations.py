#!/usr/bin/env python3
"""Fig. 10a over substrate orientations: per α, the mean and standard error over the sliding
studies' slides of the per-step boundary friction F_B/(2aγ0) and of F_B/|F_JKR| (per step
and work-based), from the `table.csv` of one or more `adhesim study sliding` runs.

    python3 scripts/fig10_orientations.py docs/data/paper/fig10_sliding_320.csv \
        docs/data/paper/fig10_sliding_320_angles.csv > docs/data/paper/fig10_sliding_320_orientations.csv
"""
import csv
import math
import sys
from collections import defaultdict

COLUMNS = [
    "boundary_force_per_width_norm",
    "mean_tangential_force_norm",
    "mean_tangential_force_work_norm",
]


def main(paths):
    if not paths:
        sys.exit("usage: fig10_orientations.py TABLE.csv [TABLE.csv ...]")
    rows = defaultdict(list)
    for path in paths:
        with open(path, newline="") as handle:
            for row in csv.DictReader(handle):
                rows[float(row["alpha"])].append(row)
    out = csv.writer(sys.stdout, lineterminator="\n")
    header = ["alpha", "slides", "substrate_angles"]
    for column in COLUMNS:
        header += [column, column.removesuffix("_norm") + "_sem"]
    out.writerow(header)
    for alpha in sorted(rows):
        cases = rows[alpha]
        angles = " ".join(sorted({f"{float(c['substrate_angle']):g}" for c in cases}, key=float))
        line = [f"{alpha:g}", len(cases), angles]
        for column in COLUMNS:
            values = [float(c[column]) for c in cases]
            mean = sum(values) / len(values)
            if len(values) > 1:
                variance = sum((v - mean) ** 2 for v in values) / (len(values) - 1)
                sem = math.sqrt(variance / len(values))
            else:
                sem = float("nan")
            line += [f"{mean:.6g}", f"{sem:.3g}"]
        out.writerow(line)


if __name__ == "__main__":
    main(sys.argv[1:])
