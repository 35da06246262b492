#!/usr/bin/env bash
# Runs the test suites on 64-bit Arm under user-mode emulation: cross-compiles the library and
# the suites that read no files (cmake/aarch64-linux-gnu.cmake, Debian's arm64 oneTBB, Highway
# and GoogleTest beside the host's), then runs them under qemu-aarch64 on four CPUs:
#   neon      a Cortex-A72 (NEON, no SVE): the NEON kernels;
#   sve128    qemu's "max" CPU with 128-bit SVE vectors,
#   sve256    ... 256-bit,
#   sve512    ... 512-bit: the SVE kernels (and NEON beside them) at each vector length.
# The suites that loop over SIMD targets run every target the emulated CPU has, and compare the
# fast engine with the reference and with x86's images where they record them.
#
#   scripts/check-arm-run.sh [--install] [build-dir] [gtest-filter]
#
# --install first installs what it needs (scripts/install-deps.sh --arm: adds the arm64
# architecture to dpkg). The filter defaults to every suite; TESSERA_ARM_CPUS picks CPUs
# ("neon sve256"). Exit 77 (skipped) when the cross toolchain, qemu or the arm64 libraries are
# missing. Its last run is recorded in docs/ARM.md.
set -euo pipefail
cd "$(dirname "$0")/.."
if [ "${1:-}" = "--install" ]; then
  ./scripts/install-deps.sh --arm
  shift
fi
build=${1:-build/arm64}
filter=${2:-*}
cpus=${TESSERA_ARM_CPUS:-neon sve128 sve256 sve512}

for tool in aarch64-linux-gnu-g++ qemu-aarch64; do
  if ! command -v "$tool" >/dev/null 2>&1; then
    echo "check-arm-run: $tool not found (scripts/install-deps.sh --arm): skipped"
    exit 77
  fi
done
for pkg in TBB hwy GTest; do
  if [ ! -d "/usr/lib/aarch64-linux-gnu/cmake/$pkg" ]; then
    echo "check-arm-run: no arm64 $pkg package (scripts/install-deps.sh --arm): skipped"
    exit 77
  fi
done

# qemu-user must run threads: the renderers draw with several, and a host whose qemu cannot
# start one (as on a sandboxed kernel) would hang every such test. A two-line program tells,
# before the long cross build.
probe=$(mktemp "${TMPDIR:-/tmp}/tessera-thread-probe.XXXXXX")
trap 'rm -f "$probe"' EXIT
printf '#include <thread>\nint main() { std::thread([] {}).join(); }\n' |
  aarch64-linux-gnu-g++ -x c++ -std=c++20 -pthread - -o "$probe"
if ! timeout 20 qemu-aarch64 -L /usr/aarch64-linux-gnu "$probe"; then
  echo "check-arm-run: qemu-aarch64 cannot start a thread on this host (a std::thread program" \
    "did not finish in 20 s): skipped"
  exit 77
fi

cmake -S . -B "$build" -G Ninja -DCMAKE_TOOLCHAIN_FILE=cmake/aarch64-linux-gnu.cmake \
  -DCMAKE_BUILD_TYPE=Release -DTESSERA_WERROR=ON -DTESSERA_BUILD_TESTS=ON \
  -DTESSERA_BUILD_BENCHMARKS=OFF -DTESSERA_BUILD_SAMPLES=OFF -DTESSERA_BUILD_IO=OFF \
  -DTESSERA_BUILD_PYTHON=OFF -DTESSERA_INSTALL=OFF >/dev/null
cmake --build "$build" -j "$(nproc)" --target tessera_tests tessera_c_api_test

failed=0
for cpu in $cpus; do
  case "$cpu" in
    neon) qemu_cpu=cortex-a72 ;;
    sve128) qemu_cpu=max,sve-default-vector-length=16 ;;
    sve256) qemu_cpu=max,sve-default-vector-length=32 ;;
    sve512) qemu_cpu=max,sve-default-vector-length=64 ;;
    *) echo "check-arm-run: unknown CPU $cpu (neon, sve128, sve256, sve512)" >&2; exit 2 ;;
  esac
  run=(qemu-aarch64 -cpu "$qemu_cpu" -L /usr/aarch64-linux-gnu)
  start=$(date +%s)
  echo "== $cpu (qemu -cpu $qemu_cpu)"
  if ! "${run[@]}" "$build/tests/tessera_c_api_test" >/dev/null; then
    echo "check-arm-run: $cpu: the C API test failed" >&2
    failed=1
  fi
  # One process runs every selected test; the summary lines say what passed.
  if ! "${run[@]}" "$build/tests/tessera_tests" --gtest_filter="$filter" --gtest_brief=1 \
      2>&1 | tail -n 40; then
    failed=1
  fi
  echo "== $cpu: $(($(date +%s) - start)) s"
done
exit $failed
