#!/usr/bin/env bash
# A/B timing of two tessera-render binaries on one capture: they alternate for ROUNDS rounds
# (which goes first alternating), one-thread runs pinned to one CPU, each run `--repeat REPEAT`
# with the raster counters off. Prints each run's min_ms and the new/old ratios of the runs'
# lower quartiles and minima of min_ms and of the medians of median_ms. On a shared machine
# only the ratios mean something; the minima and lower quartiles are the least disturbed.
#
# usage: OLD=path NEW=path scripts/ab-render.sh WORKLOAD SAMPLES THREADS ROUNDS REPEAT [args...]
# environment: TESSERA_WORKLOADS (default build/workloads) holds WORKLOAD.tri; OLD_ARGS and
#   NEW_ARGS add arguments to one side only; OLD_SAMPLES and NEW_SAMPLES replace SAMPLES on one
#   side (with OLD = NEW, the cost of multisampling: NEW_SAMPLES=4 ... WORKLOAD 1 ...); PIN_CPU
#   (default 0) for one-thread runs; extra arguments go to both.
set -euo pipefail
if [ $# -lt 5 ] || [ -z "${OLD:-}" ] || [ -z "${NEW:-}" ]; then
  echo "usage: OLD=path NEW=path $0 WORKLOAD SAMPLES THREADS ROUNDS REPEAT [args...]" >&2
  exit 2
fi
workload=$1 samples=$2 threads=$3 rounds=$4 repeat=$5
shift 5
capture=${TESSERA_WORKLOADS:-build/workloads}/$workload.tri
if [ ! -f "$capture" ]; then
  echo "ab-render: $capture not found (scripts/make-workloads.sh makes it)" >&2
  exit 1
fi
pin=()
if [ "$threads" = 1 ] && command -v taskset > /dev/null; then pin=(taskset -c "${PIN_CPU:-0}"); fi
scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT
old_runs=() new_runs=()
for ((r = 0; r < rounds; r++)); do
  order=(old new)
  if ((r % 2)); then order=(new old); fi
  for side in "${order[@]}"; do
    if [ "$side" = old ]; then
      bin=$OLD extra=${OLD_ARGS:-} side_samples=${OLD_SAMPLES:-$samples}
    else
      bin=$NEW extra=${NEW_ARGS:-} side_samples=${NEW_SAMPLES:-$samples}
    fi
    # shellcheck disable=SC2086  # extra: words to split
    line=$("${pin[@]}" "$bin" "$capture" $extra --no-counters -s "$side_samples" \
      --threads "$threads" --repeat "$repeat" -o "$scratch/$side.png" "$@" | grep 'frames=')
    [[ $line =~ min_ms=([^ ]+) ]] && min=${BASH_REMATCH[1]}
    [[ $line =~ median_ms=([^ ]+) ]] && median=${BASH_REMATCH[1]}
    if [ "$side" = old ]; then old_runs+=("$min:$median"); else new_runs+=("$min:$median"); fi
  done
done
python3 - "${old_runs[*]}" "${new_runs[*]}" << 'PY'
import statistics
import sys

def runs(arg):
    return [tuple(map(float, run.split(":"))) for run in arg.split()]

old, new = runs(sys.argv[1]), runs(sys.argv[2])
lower_quartile = lambda v: sorted(v)[len(v) // 4]
old_min, new_min = [m for m, _ in old], [m for m, _ in new]
print("old min_ms", " ".join(f"{m:.1f}" for m in old_min))
print("new min_ms", " ".join(f"{m:.1f}" for m in new_min))
print(f"new/old: lower quartile {lower_quartile(new_min) / lower_quartile(old_min):.3f}, "
      f"minimum {min(new_min) / min(old_min):.3f}, median of medians "
      f"{statistics.median(m for _, m in new) / statistics.median(m for _, m in old):.3f}")
PY
