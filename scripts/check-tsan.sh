#!/usr/bin/env bash
# Runs the test suite under ThreadSanitizer (the tsan preset) against a oneTBB built with it.
# Debian's libtbb is not instrumented: ThreadSanitizer cannot see the scheduler hand a task
# from one thread to another, and reports every hand-over as a race. This script therefore
# downloads the upstream source of the installed oneTBB version from Debian's archive (same
# headers, same ABI), builds its libtbb with TBB_SANITIZE=thread into build/tbb-tsan once, and
# runs the tests with it on the library path. Any report fails the run.
#
#   scripts/check-tsan.sh                        # every test
#   GTEST_FILTER='FastEngine*' scripts/check-tsan.sh
#
# Not part of scripts/test.sh: the instrumented kernels and the suite under ThreadSanitizer
# take far longer than the CI's budget.
set -euo pipefail
cd "$(dirname "$0")/.."
root=$PWD
version=$(dpkg-query -W -f='${source:Upstream-Version}' libtbb-dev)
tbb=$root/build/tbb-tsan
if [[ ! -e $tbb/install/lib/libtbb.so.12 ]]; then
  mkdir -p "$tbb"
  tarball=$tbb/onetbb_$version.orig.tar.xz
  [[ -e $tarball ]] ||
    curl -fsSL -o "$tarball" "http://deb.debian.org/debian/pool/main/o/onetbb/onetbb_$version.orig.tar.xz"
  rm -rf "$tbb/src"
  mkdir -p "$tbb/src"
  tar -xf "$tarball" -C "$tbb/src" --strip-components=1
  cmake -S "$tbb/src" -B "$tbb/build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DTBB_TEST=OFF \
    -DTBB_STRICT=OFF -DTBBMALLOC_BUILD=OFF -DTBB_SANITIZE=thread -DCMAKE_INSTALL_PREFIX="$tbb/install"
  cmake --build "$tbb/build" -j "$(nproc)"
  cmake --install "$tbb/build"
fi

cmake --preset tsan
cmake --build build/tsan -j "$(nproc)" --target tessera_tests
# Every report is an error; second_deadlock_stack names both locks of a lock-order report.
export TSAN_OPTIONS="halt_on_error=1 exitcode=66 second_deadlock_stack=1 ${TSAN_OPTIONS:-}"
LD_LIBRARY_PATH="$tbb/install/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}" \
  build/tsan/tests/tessera_tests --gtest_filter="${GTEST_FILTER:-*}"
