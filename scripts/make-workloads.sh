#!/usr/bin/env bash
# Generates Tessera's six standard benchmark workloads (TRI1 captures, 1920x1080) with the
# shared generator ../shared/workloads/gen_scene.py, which defines them (see its README), so
# every benchmark and peer comparison reads the same bytes. Existing files are kept.
#
# usage: scripts/make-workloads.sh [directory]   (default build/workloads, or $TESSERA_WORKLOADS)
set -euo pipefail

repo=$(cd "$(dirname "$0")/.." && pwd)
generator="$repo/../shared/workloads/gen_scene.py"
python=/usr/bin/python3
out=${1:-${TESSERA_WORKLOADS:-build/workloads}}

if [ ! -f "$generator" ]; then
  echo "make-workloads: $generator not found (the shared folder sits beside the repository)" >&2
  exit 1
fi
mkdir -p "$out"

# name, then gen_scene.py's arguments after OUT (table in ../shared/workloads/README.md)
workloads=(
  "tiny 1920 1080 soup 1000000 2"
  "small 1920 1080 soup 1000000 16"
  "medium 1920 1080 soup 200000 128"
  "large 1920 1080 soup 20000 2048"
  "huge 1920 1080 soup 1000 65536"
  "grid 1920 1080 grid 1000 500"
)
for w in "${workloads[@]}"; do
  read -r name args <<<"$w"
  file="$out/$name.tri"
  if [ -e "$file" ]; then
    echo "make-workloads: $file exists, kept"
    continue
  fi
  echo "make-workloads: generating $file"
  # Written under a temporary name first, so an interrupted run leaves no truncated capture.
  # shellcheck disable=SC2086  # $args is the argument list
  "$python" "$generator" "$file.partial" $args
  mv "$file.partial" "$file"
done
