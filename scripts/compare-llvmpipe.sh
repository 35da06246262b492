#!/usr/bin/env bash
# Peer comparison: times Tessera's fast engine (tessera-render --backend fast) and Mesa's
# llvmpipe (tessera_llvmpipe_bench, OSMesa) on the same TRI1 captures and prints a Markdown
# table. Only the ratios within one run mean something on a shared machine, whose cores slow
# down and speed up by tens of percent over minutes. So, per workload, sample count and thread
# count, the two alternate for ROUNDS rounds (each round one run of each, which goes first
# alternating), one-thread runs are pinned to the same CPU, and the table gives the median over
# the rounds of each renderer's median frame, their ratio, and the range of the per-round
# ratios. Tessera runs with its raster counters off (--no-counters), as llvmpipe counts
# nothing.
#
# usage: scripts/compare-llvmpipe.sh [WORKLOAD...]   (default: the six standard workloads)
# environment: BUILD_DIR (default build/release) holds samples/tessera-render and
#   benchmarks/tessera_llvmpipe_bench; TESSERA_WORKLOADS (default build/workloads, see
#   scripts/make-workloads.sh); FRAMES timed frames per run (default 10); ROUNDS runs of each
#   renderer per row (default 3); THREADS (default "1 2"); SAMPLES (default "1 4"); PIN_CPU the
#   CPU one-thread runs are pinned to (default 0; needs taskset); LOG keeps every raw output
#   line (default: a temporary file, removed).
set -euo pipefail

build=${BUILD_DIR:-build/release}
render=$build/samples/tessera-render
peer=$build/benchmarks/tessera_llvmpipe_bench
workloads_dir=${TESSERA_WORKLOADS:-build/workloads}
frames=${FRAMES:-10}
rounds=${ROUNDS:-3}
pin_cpu=${PIN_CPU:-0}
threads_list=${THREADS:-1 2}
samples_list=${SAMPLES:-1 4}
if [ $# -gt 0 ]; then workloads=("$@"); else workloads=(tiny small medium large huge grid); fi

for exe in "$render" "$peer"; do
  if [ ! -x "$exe" ]; then
    echo "compare-llvmpipe: $exe not built (set BUILD_DIR; tessera_llvmpipe_bench needs" \
      "libosmesa6-dev at configure time)" >&2
    exit 1
  fi
done

work=$(mktemp -d "${TMPDIR:-/tmp}/tessera-llvmpipe.XXXXXX")
trap 'rm -rf "$work"' EXIT
log=${LOG:-$work/log}
: >"$log"

# The value of key=... in a line, or "n/a".
field() { sed -n "s/.*[[:space:]]$1=\([^[:space:]]*\).*/\1/p" <<<"$2" | grep . || echo n/a; }

# The median of its arguments (the mean of the middle two for an even count).
median() {
  printf '%s\n' "$@" | sort -g | awk '{ v[NR] = $1 } END {
    if (NR % 2) printf "%.3f", v[(NR + 1) / 2]; else printf "%.3f", (v[NR / 2] + v[NR / 2 + 1]) / 2 }'
}

# One run of each renderer for the row being measured (capture, s, t, pin: the loop's).
run_tessera() {
  "${pin[@]}" "$render" "$capture" --backend fast --no-counters --samples "$s" --threads "$t" \
    --repeat "$frames" --clear 0,0,0,1 -o "$work/tessera.png" >"$work/tessera.out" 2>&1 || true
}
run_peer() {
  "${pin[@]}" "$peer" "$capture" --threads "$t" --samples "$s" --frames "$frames" \
    >"$work/peer.out" 2>&1 || true
}

rows=()
for w in "${workloads[@]}"; do
  capture=$workloads_dir/$w.tri
  if [ ! -f "$capture" ]; then
    echo "compare-llvmpipe: $capture missing (run scripts/make-workloads.sh), skipped" >&2
    continue
  fi
  for s in $samples_list; do
  for t in $threads_list; do
    echo "compare-llvmpipe: $w, $s sample(s), $t thread(s)" >&2
    pin=()
    if [ "$t" = 1 ] && command -v taskset >/dev/null; then pin=(taskset -c "$pin_cpu"); fi
    # A failed run leaves its round out; a row with no complete round is n/a. The messages
    # are in the log.
    tms=() lms=() tmtri=() lmtri=() ratios=()
    for ((r = 0; r < rounds; ++r)); do
      if ((r % 2 == 0)); then run_tessera; run_peer; else run_peer; run_tessera; fi
      cat "$work/tessera.out" "$work/peer.out" >>"$log"
      tessera_line=$(grep '^frames=' "$work/tessera.out" || true)
      peer_line=$(grep '^llvmpipe ' "$work/peer.out" || true)
      # tessera-render's summary line starts with frames=; give it a leading space for field().
      tm=$(field median_ms " $tessera_line")
      lm=$(field median_ms "$peer_line")
      if [ "$tm" != n/a ] && [ "$lm" != n/a ]; then
        tms+=("$tm") lms+=("$lm")
        tmtri+=("$(field mtri_s " $tessera_line")") lmtri+=("$(field mtri_s "$peer_line")")
        ratios+=("$(awk -v l="$lm" -v t="$tm" 'BEGIN { printf "%.2f", l / t }')")
      fi
    done
    if [ ${#tms[@]} -eq 0 ]; then
      rows+=("| $w | $s | $t | n/a | n/a | n/a | n/a | n/a | n/a |")
      continue
    fi
    tm=$(median "${tms[@]}") lm=$(median "${lms[@]}")
    ratio=$(awk -v l="$lm" -v t="$tm" 'BEGIN { printf "%.2f", l / t }')
    mapfile -t sorted < <(printf '%s\n' "${ratios[@]}" | sort -g)
    range="${sorted[0]} to ${sorted[-1]}"
    rows+=("| $w | $s | $t | $tm | $lm | $ratio | $range | $(median "${tmtri[@]}") | $(median "${lmtri[@]}") |")
  done
  done
done

echo
echo "| workload | samples | threads | tessera median ms | llvmpipe median ms | ratio (llvmpipe/tessera) | per-round ratios | tessera Mtri/s | llvmpipe Mtri/s |"
echo "| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |"
printf '%s\n' "${rows[@]}"
echo
echo "$rounds rounds of one run of each renderer; each run $frames timed frames after one" \
  "warm-up, clear + draw (+ glFinish for llvmpipe) per frame; medians over the rounds of each" \
  "run's median frame; threads 1 = LP_NUM_THREADS=0, pinned to CPU $pin_cpu where taskset" \
  "exists; 2 = LP_NUM_THREADS=2."
