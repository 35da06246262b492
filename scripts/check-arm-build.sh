#!/usr/bin/env bash
# Cross-compiles the engine's sources for 64-bit Arm (NEON and SVE kernels through Highway)
# with warnings as errors, to prove the SIMD code builds off x86. Objects only: nothing links
# or runs. Exit 77 (skipped) when no aarch64 cross compiler is installed.
set -euo pipefail
cd "$(dirname "$0")/.."
cxx=${CXX_AARCH64:-aarch64-linux-gnu-g++}
if ! command -v "$cxx" >/dev/null 2>&1; then
  echo "check-arm-build: $cxx not found (Debian package g++-aarch64-linux-gnu): skipped"
  exit 77
fi
out=$(mktemp -d "${TMPDIR:-/tmp}/tessera-arm.XXXXXX")
trap 'rm -rf "$out"' EXIT
# Every library source but the two that include OpenImageIO and Assimp headers, whose
# Debian packages ship per-architecture configuration.
sources=$(find engine/src simd binning -name '*.cpp' ! -name image_io.cpp ! -name mesh_io.cpp | sort)
# One compiler per core: each source is independent.
export cxx out
# Without optimization: the check is that every source compiles, which -O0 proves in a quarter
# of -O1's time (a raster kernel source: 31 s against 121 s on one core).
echo "$sources" | xargs -P "$(nproc)" -I{} sh -c '"$cxx" -std=c++20 -O0 -ffp-contract=off \
  -Wall -Wextra -Wpedantic -Wshadow -Wconversion -Wno-sign-conversion -Werror -I. \
  -Iengine/include -c "$1" -o "$out/$(basename "$1").o"' sh {}
kernels=$(nm -C "$out/block_kernel.cpp.o" | grep -oE 'N_[A-Z0-9_]+::GetKernelTable' | sort -u |
  tr '\n' ' ')
echo "check-arm-build: $(echo "$sources" | wc -l) sources compiled for aarch64; kernels: $kernels"
case "$kernels" in
  *N_NEON::*) ;;
  *) echo "check-arm-build: no NEON kernels were compiled" >&2; exit 1 ;;
esac
