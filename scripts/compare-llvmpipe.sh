#!/usr/bin/env bash
# Peer comparison: times Tessera's fast engine (tessera-render --backend fast) and Mesa's
# llvmpipe (tessera_llvmpipe_bench, OSMesa) on the same TRI1 captures, interleaving the two
# per workload and thread count so both see the same machine state, and prints a Markdown
# table. Only the ratios within one run mean something on a shared machine. Tessera runs with
# its raster counters off (--no-counters), as llvmpipe counts nothing.
#
# usage: scripts/compare-llvmpipe.sh [WORKLOAD...]   (default: the six standard workloads)
# environment: BUILD_DIR (default build/release) holds samples/tessera-render and
#   benchmarks/tessera_llvmpipe_bench; TESSERA_WORKLOADS (default build/workloads, see
#   scripts/make-workloads.sh); FRAMES timed frames per run (default 10); THREADS (default
#   "1 2"); SAMPLES (default "1 4"); LOG keeps every raw output line (default: a temporary
#   file, removed).
set -euo pipefail

build=${BUILD_DIR:-build/release}
render=$build/samples/tessera-render
peer=$build/benchmarks/tessera_llvmpipe_bench
workloads_dir=${TESSERA_WORKLOADS:-build/workloads}
frames=${FRAMES:-10}
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
    # A failed run leaves its row n/a; its messages are in the log.
    "$render" "$capture" --backend fast --no-counters --samples "$s" --threads "$t" --repeat "$frames" \
      --clear 0,0,0,1 -o "$work/tessera.png" >"$work/tessera.out" 2>&1 || true
    "$peer" "$capture" --threads "$t" --samples "$s" --frames "$frames" >"$work/peer.out" 2>&1 ||
      true
    cat "$work/tessera.out" "$work/peer.out" >>"$log"
    tessera_line=$(grep '^frames=' "$work/tessera.out" || true)
    peer_line=$(grep '^llvmpipe ' "$work/peer.out" || true)
    # tessera-render's summary line starts with frames=; give it a leading space for field().
    tm=$(field median_ms " $tessera_line")
    lm=$(field median_ms "$peer_line")
    ratio=n/a
    if [ "$tm" != n/a ] && [ "$lm" != n/a ]; then
      ratio=$(awk -v l="$lm" -v t="$tm" 'BEGIN { printf "%.2f", l / t }')
    fi
    rows+=("| $w | $s | $t | $tm | $lm | $ratio | $(field mtri_s " $tessera_line") | $(field mtri_s "$peer_line") |")
  done
  done
done

echo
echo "| workload | samples | threads | tessera median ms | llvmpipe median ms | ratio (llvmpipe/tessera) | tessera Mtri/s | llvmpipe Mtri/s |"
echo "| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: |"
printf '%s\n' "${rows[@]}"
echo
echo "$frames timed frames after one warm-up, clear + draw (+ glFinish for llvmpipe)" \
  "per frame; threads 1 = LP_NUM_THREADS=0, 2 = LP_NUM_THREADS=2."
