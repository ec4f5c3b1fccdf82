#!/bin/bash
# How one case scales with threads, and how a sweep should split a machine's cores between
# cases and threads (BENCHMARKS.md, "Cases or threads"). Runs, one at a time:
#   1. the Fig. 1 cycle at n = 256 (75 approach steps) on each thread count, paired rounds
#      (bench/wall/paired.py), and
#   2. the sixteen cycles of bench/wall/split_16.toml as `adhesim sweep --jobs J --threads T`
#      for each J:T given, timing the whole sweep.
#
#   bench/wall/scaling.sh BINARY OUTDIR ["1 2 4 8 16"] ["16:1 8:2 4:4 1:16"] [ROUNDS]
#
# Writes OUTDIR/machine.txt, OUTDIR/case256.txt and OUTDIR/split16.txt. Only bash, python3
# and the binary; nothing else may run on the machine meanwhile.
set -u -o pipefail
if [ $# -lt 2 ]; then
    echo "usage: $0 BINARY OUTDIR [THREAD_COUNTS] [JOBS:THREADS ...] [ROUNDS]" >&2
    exit 2
fi
binary=$(realpath "$1") || exit 2
out=$2
threads=${3:-"1 2 4 8 16"}
splits=${4:-"16:1 8:2 4:4 1:16"}
rounds=${5:-2}
here=$(dirname "$(realpath "$0")")
mkdir -p "$out" || exit 2
wrappers=$(mktemp -d)
builds=()
for t in $threads; do  # paired.py compares two builds or more: give two counts or more
    printf '#!/bin/sh\nexec %s "$@" --threads %s\n' "$binary" "$t" > "$wrappers/t$t"
    chmod +x "$wrappers/t$t"
    builds+=(--build "t$t=$wrappers/t$t")
done
{ date -u; nproc; lscpu | grep -E "Model name|Core|Thread|Socket|L3"; cat /proc/loadavg; "$binary" --version; } \
    > "$out/machine.txt" 2>&1
python3 -u "$here/paired.py" --runs "$rounds" "${builds[@]}" -- "$here/../../scenarios/fig1.toml" \
    --set grid.n=256 --set protocol.steps=75 --set indenter.amplitude=0.0025 | tee "$out/case256.txt" || exit 1
for split in $splits; do
    jobs=${split%:*}
    per_case=${split#*:}
    sweep=$(mktemp -d)/sweep
    start=$(date +%s.%N)
    "$binary" sweep "$here/split_16.toml" --out "$sweep" --jobs "$jobs" --threads "$per_case" --quiet > /dev/null
    status=$?
    end=$(date +%s.%N)
    echo "jobs $jobs threads $per_case exit $status wall $(python3 -c "print(round($end - $start, 1))") s load $(cut -d' ' -f1-3 /proc/loadavg)" \
        | tee -a "$out/split16.txt"
    rm -rf "$(dirname "$sweep")"
done
rm -rf "$wrappers"
