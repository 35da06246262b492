#!/usr/bin/env bash
# Installs every Debian package that Tessera's build, tests, benchmarks and samples need.
# Does nothing (and needs no network) when they are all present already.
#
#   scripts/install-deps.sh [--arm]
#
# --arm adds what scripts/check-arm-run.sh needs to run the tests on 64-bit Arm under
# emulation: qemu-user and the arm64 builds of oneTBB, Highway and GoogleTest, beside the
# host's (it adds the arm64 architecture to dpkg).
set -euo pipefail
arm=0
if [ "${1:-}" = "--arm" ]; then arm=1; fi

packages=(
  cmake ninja-build g++ pkg-config python3
  libglm-dev libtbb-dev libhwy-dev libopenimageio-dev openimageio-tools libassimp-dev libcli11-dev
  libgtest-dev libgmock-dev libbenchmark-dev libosmesa6-dev g++-aarch64-linux-gnu
  assimp-testmodels python3-matplotlib
  pybind11-dev python3-dev python3-numpy python3-pytest
)

if [ $arm -eq 1 ]; then
  packages+=(qemu-user libtbb-dev:arm64 libhwy-dev:arm64 libgtest-dev:arm64 libgmock-dev:arm64)
fi

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#packages[@]} packages present"
  exit 0
fi

echo "install-deps: installing ${missing[*]}"
sudo_cmd=()
if [ "$(id -u)" -ne 0 ]; then sudo_cmd=(sudo); fi
export DEBIAN_FRONTEND=noninteractive
if [ $arm -eq 1 ] && ! dpkg --print-foreign-architectures | grep -qx arm64; then
  "${sudo_cmd[@]}" dpkg --add-architecture arm64
fi
"${sudo_cmd[@]}" apt-get update -q
"${sudo_cmd[@]}" apt-get install -y -q "${missing[@]}"
