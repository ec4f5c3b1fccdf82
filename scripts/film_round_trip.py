#!/usr/bin/env python3
"""A simulated run filmed and analysed as an experiment, against its own truth
(docs/experiments.md §6, A simulated run, filmed).

    adhesim run scenarios/layer/paper_r22_stick_slip.toml --set output.snapshot_every=1 --out out/r22_run
    adhesim experiment film out/r22_run --out out/r22_film
    adhesim experiment out/r22_film/experiment.toml --out out/r22_analysis
    python3 scripts/film_round_trip.py out/r22_film out/r22_analysis

Prints the largest and mean relative errors, over the frames, of the measured total, front
and rear areas against the frame's own contact (truth.csv's true_*), of the total against
the run's element area (run_area), and of τ = F_T/A against the run's F_T over its area.
"""
import csv
import sys
from pathlib import Path


def number(text: str) -> float:
    try:
        return float(text)
    except ValueError:  # a label column (phase)
        return float("nan")


def table(path: Path) -> dict:
    rows = list(csv.DictReader(open(path)))
    return {name: [number(r[name]) for r in rows] for name in rows[0]}


def main() -> None:
    film, analysis = Path(sys.argv[1]), Path(sys.argv[2])
    truth, seen = table(film / "truth.csv"), table(analysis / "frames.csv")
    if len(truth["frame"]) != len(seen["frame"]):
        sys.exit(f"{len(truth['frame'])} frames filmed, {len(seen['frame'])} analysed")

    def errors(measured, reference):
        relative = [abs(m / r - 1.0) for m, r in zip(measured, reference)]
        return max(relative), sum(relative) / len(relative)

    rows = [
        ("area against the frame's contact", seen["area"], truth["true_area"]),
        ("front area against the frame's", seen["area_front"], truth["true_area_front"]),
        ("rear area against the frame's", seen["area_rear"], truth["true_area_rear"]),
        ("area against the run's elements", seen["area"], truth["run_area"]),
        ("front against the run's elements", seen["area_front"], truth["run_area_front"]),
        (
            "tau = F_T/A against the run's",
            seen["tangential_stress"],
            [f / a for f, a in zip(seen["force_tangential"], truth["run_area"])],
        ),
    ]
    print(f"{len(seen['frame'])} frames")
    for name, measured, reference in rows:
        largest, mean = errors(measured, reference)
        print(f"{name:36s} largest {100 * largest:6.3f} %  mean {100 * mean:6.3f} %")


if __name__ == "__main__":
    main()
