#!/usr/bin/env bash
# One command from a fresh clone to a rendered image: installs the dependencies, builds the
# release configuration and renders the built-in demo scene to tessera-demo.png (or the path
# given), printing the triangles drawn, the time and triangles per second.
set -euo pipefail
cd "$(dirname "$0")/.."
./scripts/install-deps.sh
./scripts/build.sh release
out="${1:-tessera-demo.png}"
./build/release/samples/tessera-render -o "$out"
