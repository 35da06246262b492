#!/usr/bin/env bash
# Installs every Debian package that Tessera's build, tests, benchmarks and samples need.
# Does nothing (and needs no network) when they are all present already.
set -euo pipefail

packages=(
  cmake ninja-build g++ pkg-config python3
  libglm-dev libtbb-dev libhwy-dev libopenimageio-dev openimageio-tools libassimp-dev libcli11-dev
  libgtest-dev libgmock-dev libbenchmark-dev libosmesa6-dev g++-aarch64-linux-gnu
  assimp-testmodels python3-matplotlib
  pybind11-dev python3-dev python3-numpy python3-pytest
)

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
"${sudo_cmd[@]}" apt-get update -q
"${sudo_cmd[@]}" apt-get install -y -q "${missing[@]}"
