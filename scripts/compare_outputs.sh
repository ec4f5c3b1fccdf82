#!/usr/bin/env bash
# Behaviour check for refactors: runs every scenario in scenarios/ and its folders (reduced
# in size so that each takes seconds), a Dugdale and a trapezoid roll, the tiny sweep and
# tiny rolling/sliding studies with a given `adhesim` binary into DIR. With a reference folder, compares the outputs:
# curve.csv and the studies' CSV tables byte for byte (minus the *wall_seconds columns),
# summary.json values minus `performance` (timings and counters that vary).
#
#   scripts/compare_outputs.sh BIN DIR            # record
#   scripts/compare_outputs.sh BIN DIR REF_DIR    # record into DIR, compare with REF_DIR
set -euo pipefail
bin=$(realpath "$1"); out=$(realpath -m "$2"); ref=${3:+$(realpath "$3")}
repo=$(cd "$(dirname "$0")/.." && pwd)
rm -rf "$out"; mkdir -p "$out"
# Reduced sizes (the set each run gets on top of its scenario file).
indent_set=(--set grid.n=64)
translate_set=(--set grid.n=32 --set protocol.approach_steps=20 --set protocol.steps=40)
for file in "$repo"/scenarios/*.toml; do
    name=$(basename "$file" .toml)
    if grep -q '^kind = "indent_pulloff"' "$file"; then set_args=("${indent_set[@]}"); else set_args=("${translate_set[@]}"); fi
    "$bin" run "$file" --out "$out/run/$name" --quiet --threads 1 "${set_args[@]}"
done
for file in "$repo"/scenarios/*/*.toml; do
    name=$(basename "$(dirname "$file")")_$(basename "$file" .toml)
    if grep -q '^kind = "indent_pulloff"' "$file"; then set_args=("${indent_set[@]}"); else set_args=("${translate_set[@]}"); fi
    "$bin" run "$file" --out "$out/run/$name" --quiet --threads 1 "${set_args[@]}"
done
# Dugdale's and the trapezoidal law on a roll (their pinning warnings and estimate).
for law in dugdale trapezoid; do
    law_args=(--set "adhesion.law=\"$law\"" --set adhesion.cohesive_stress=0.05)
    [ "$law" = trapezoid ] && law_args+=(--set adhesion.softening_fraction=0.5)
    "$bin" run "$repo/scenarios/fig6.toml" --out "$out/run/fig6_$law" --quiet --threads 1 "${translate_set[@]}" "${law_args[@]}"
done
"$bin" sweep "$repo/sweeps/tiny.toml" --out "$out/sweep_tiny" --jobs 1 --quiet
cat > "$out/rolling.toml" <<TOML
kind = "rolling"
base = "$repo/scenarios/fig6.toml"
alphas = [0.8, 1.2]
depths = [3, 5]
set = ["grid.n=32", "protocol.approach_steps=10", "protocol.steps=8"]
[normal]
max_depth = 5.0
steps = 20
TOML
cat > "$out/sliding.toml" <<TOML
kind = "sliding"
base = "$repo/scenarios/fig9.toml"
alphas = [0.5, 1.0]
substrate_angles = [30, 45]
set = ["grid.n=32", "protocol.approach_steps=10", "protocol.steps=8"]
TOML
"$bin" study rolling "$out/rolling.toml" --out "$out/study_rolling" --jobs 1 --quiet
"$bin" study sliding "$out/sliding.toml" --out "$out/study_sliding" --jobs 1 --quiet
[ -z "$ref" ] && { echo "recorded into $out"; exit 0; }

status=0
strip_wall() { # drops the wall_seconds column of a CSV table
    python3 - "$1" <<'PY'
import csv, sys
rows = list(csv.reader(open(sys.argv[1])))
drop = [i for i, h in enumerate(rows[0]) if h.endswith("wall_seconds")]
for r in rows:
    print(",".join(v for i, v in enumerate(r) if i not in drop))
PY
}
summary_values() { jq -S 'del(.performance)' "$1"; }
cd "$ref"
while IFS= read -r file; do
    if [ ! -f "$out/$file" ]; then echo "MISSING $file"; status=1; continue; fi
    case "$file" in
        */curve.csv) cmp -s "$file" "$out/$file" || { echo "DIFFERS $file"; status=1; } ;;
        */summary.json) diff <(summary_values "$file") <(summary_values "$out/$file") >/dev/null \
            || { echo "DIFFERS $file"; diff <(summary_values "$file") <(summary_values "$out/$file") | head -20; status=1; } ;;
        *.csv) diff <(strip_wall "$file") <(strip_wall "$out/$file") >/dev/null || { echo "DIFFERS $file"; status=1; } ;;
    esac
done < <(find . -type f \( -name '*.csv' -o -name 'summary.json' \) | sort)
checked=$(find . -type f \( -name '*.csv' -o -name 'summary.json' \) | wc -l)
[ $status = 0 ] && echo "same outputs: $checked files compared with $ref"
exit $status
