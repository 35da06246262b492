#!/usr/bin/env bash
# One command from a fresh clone to a full test run: installs the dependencies, then builds
# and runs the whole test suite twice, in the release configuration (warnings as errors) and
# under AddressSanitizer + UndefinedBehaviorSanitizer.
set -euo pipefail
cd "$(dirname "$0")/.."
./scripts/install-deps.sh
for preset in release asan; do
  echo "== $preset: build"
  ./scripts/build.sh "$preset"
  echo "== $preset: test"
  ctest --preset "$preset" -j "$(nproc)"
done
