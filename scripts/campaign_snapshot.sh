#!/usr/bin/env bash
# Keeps the finished cases of a sweep or study folder in the repository so that a later
# run (whose machine starts without the folder) resumes the campaign instead of redoing
# them: copies sweep.json (a sweep) and, per finished case, its `done` marker, case.json,
# scenario.toml, summary.json and record.json (a study's run) where present: enough for
# `adhesim sweep` / `adhesim study` to count the case as finished and to rebuild the tables
# (`sweep merge`, `study --tables-only`); curve.csv, fields and plots stay behind.
#
#   scripts/campaign_snapshot.sh SWEEP_DIR docs/data/paper/campaign/NAME   # keep
#   cp -r docs/data/paper/campaign/NAME DIR && adhesim sweep SWEEP.toml --out DIR   # resume
#   (a study: cp -r ... DIR && adhesim study KIND STUDY.toml --out DIR)
set -euo pipefail
src=$1; dest=$2
mkdir -p "$dest/cases"
[ -f "$src/sweep.json" ] && cp "$src/sweep.json" "$dest/"
for case in "$src"/cases/*/; do
    [ -f "$case/done" ] || continue
    id=$(basename "$case")
    mkdir -p "$dest/cases/$id"
    for f in done case.json scenario.toml summary.json record.json; do
        [ -f "$case/$f" ] && cp "$case/$f" "$dest/cases/$id/"
    done
done
echo "$(ls "$dest/cases" | wc -l) finished cases kept in $dest"
