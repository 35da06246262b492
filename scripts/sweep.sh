#!/usr/bin/env bash
# Runs the speed-against-accuracy sweep and draws its charts into docs/tradeoffs (the data of
# docs/TRADEOFFS.md): scripts/sweep.sh [extra tessera_sweep options, e.g. --frames 9]
# Builds the release preset and the standard workloads first when they are missing.
set -euo pipefail
cd "$(dirname "$0")/.."
build=${BUILD_DIR:-build/release}
if [ ! -x "$build/benchmarks/tessera_sweep" ]; then ./scripts/build.sh release; fi
if [ ! -f build/workloads/grid.tri ]; then ./scripts/make-workloads.sh; fi
"$build/benchmarks/tessera_sweep" --workloads build/workloads --out build/sweep "$@"
/usr/bin/python3 scripts/plot-tradeoffs.py build/sweep docs/tradeoffs
