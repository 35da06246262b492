#!/usr/bin/env bash
# Proves that applications can build against Tessera the ways the README documents, with the
# applications of tests/package/consumer (one triangle through the public API, a pixel checked;
# main.cpp through the C++ API, main.c through the C API):
#   1. the static library of BUILD_DIR installed into a temporary prefix holds exactly the public
#      headers (none of engine/src, simd or binning), and its core target's link interface names
#      neither Assimp nor OpenImageIO;
#   2. find_package(Tessera) against that install, core only and with COMPONENTS io;
#   3. pkg-config (tessera, tessera-io) against that install, with no CMake;
#   4. the checkout as a subproject, with add_subdirectory and then FetchContent (a local source
#      directory, no download): no build type, option or flag forced on the parent, nothing but
#      the core library built;
#   5. a shared build (BUILD_SHARED_LIBS=ON) installed and found with find_package, core and io:
#      a soname, and no internal symbol (tessera::detail, fast, reference, simd, binning)
#      exported.
# Steps 4 and 5 compile the library twice more. To keep that time down they compile only the
# portable baseline's kernels (no SSE4, AVX2 or AVX-512: what is checked is the packaging, and
# the release and sanitizer builds test every SIMD target) and without optimization (the
# subproject takes its parent's empty build type; the shared build is configured with build type
# None, as Debian's packaging does), and the FetchContent build reuses the add_subdirectory
# build's objects (same binary directory, same commands).
# Usage: check-package.sh BUILD_DIR CXX_COMPILER [CONFIG]. ctest runs it (tests/CMakeLists.txt).
# Exit 77 (skipped) when pkg-config is missing. TESSERA_PACKAGE_JOBS sets the build's parallel jobs
# (default: the number of cores).
set -euo pipefail
src=$(cd "$(dirname "$0")/.." && pwd)
build=$(cd "$1" && pwd)
cxx=$2
config=${3:-Release}
jobs=${TESSERA_PACKAGE_JOBS:-$(nproc)}
consumer_src=$src/tests/package/consumer

if ! command -v pkg-config >/dev/null 2>&1; then
  echo "check-package: pkg-config not found (Debian package pkg-config): skipped"
  exit 77
fi
generator=()
if command -v ninja >/dev/null 2>&1; then generator=(-G Ninja); fi
reduced_targets="HWY_AVX3|HWY_AVX2|HWY_SSE4"

tmp=$(mktemp -d "${TMPDIR:-/tmp}/tessera-package.XXXXXX")
# TESSERA_PACKAGE_KEEP=1 keeps the builds and installs to look at.
if [ "${TESSERA_PACKAGE_KEEP:-0}" = 1 ]; then
  echo "check-package: working in $tmp (kept)"
else
  trap 'rm -rf "$tmp"' EXIT
fi

step() { echo "== check-package (${SECONDS}s): $*"; }
fail() {
  echo "check-package: FAILED: $*" >&2
  exit 1
}
# consumer DIR -D...: configures the consumer in DIR (its log shown only when that fails),
# builds it and runs it.
configure() {
  local dir=$1
  shift
  if ! cmake -S "$consumer_src" -B "$dir" "${generator[@]}" -DCMAKE_CXX_COMPILER="$cxx" "$@" \
    >"$dir.log" 2>&1; then
    cat "$dir.log"
    fail "configuring the consumer in $dir"
  fi
}
build_and_run() {
  local dir=$1
  cmake --build "$dir" -j "$jobs" >"$dir.build.log" 2>&1 || {
    tail -50 "$dir.build.log"
    fail "building the consumer in $dir"
  }
  "$dir/consumer" "$tmp" || fail "running $dir/consumer"
  "$dir/consumer_c" || fail "running $dir/consumer_c"
}
consumer() {
  local dir=$1
  shift
  configure "$dir" "$@"
  build_and_run "$dir"
}

# Exactly the public headers: engine/include/tessera/*.hpp, the C API's tessera.h and the
# generated version.hpp.
check_headers() {
  local prefix=$1 expected installed
  expected=$( (
    cd "$src/engine/include"
    ls tessera/*.hpp tessera/*.h
    echo tessera/version.hpp
  ) | sort)
  installed=$(cd "$prefix/include" && find . -type f | sed 's|^\./||' | sort)
  if [ "$installed" != "$expected" ]; then
    diff <(echo "$expected") <(echo "$installed") >&2 || true
    fail "$prefix/include is not exactly the public headers (< expected, > installed)"
  fi
}

step "static: install $build into a temporary prefix"
cmake --install "$build" --prefix "$tmp/static" --config "$config" >"$tmp/static-install.log"
static_cmake=$(find "$tmp/static" -name TesseraConfig.cmake -printf '%h')
[ -n "$static_cmake" ] || fail "no TesseraConfig.cmake installed"
check_headers "$tmp/static"
if grep -Eq 'assimp|OpenImageIO' "$static_cmake"/TesseraTargets*.cmake; then
  fail "Tessera::tessera's installed targets refer to Assimp or OpenImageIO"
fi

step "static: find_package(Tessera), core only and with COMPONENTS io"
consumer "$tmp/package-static" -DCMAKE_PREFIX_PATH="$tmp/static" -DCMAKE_BUILD_TYPE=Release
consumer "$tmp/package-static-io" -DCMAKE_PREFIX_PATH="$tmp/static" -DCMAKE_BUILD_TYPE=Release \
  -DTESSERA_CONSUMER_IO=ON

step "static: pkg-config tessera and tessera-io"
pc_dir=$(find "$tmp/static" -name tessera.pc -printf '%h')
export PKG_CONFIG_PATH=$pc_dir
# shellcheck disable=SC2046  # pkg-config's output is a list of words
"$cxx" -std=c++20 "$consumer_src/main.cpp" -o "$tmp/pkgconfig" $(pkg-config --cflags --libs tessera)
"$tmp/pkgconfig" "$tmp" || fail "running the pkg-config consumer"
# shellcheck disable=SC2046
"$cxx" -std=c++20 -DTESSERA_CONSUMER_IO "$consumer_src/main.cpp" -o "$tmp/pkgconfig-io" \
  $(pkg-config --cflags --libs tessera-io)
"$tmp/pkgconfig-io" "$tmp" || fail "running the pkg-config consumer of tessera-io"
# The C program is compiled by the C compiler and linked by the C++ one (Tessera is C++).
# shellcheck disable=SC2046
"${CC:-cc}" -std=c11 -c "$consumer_src/main.c" -o "$tmp/pkgconfig-c.o" \
  $(pkg-config --cflags tessera)
# shellcheck disable=SC2046
"$cxx" "$tmp/pkgconfig-c.o" -o "$tmp/pkgconfig-c" $(pkg-config --libs tessera)
"$tmp/pkgconfig-c" || fail "running the pkg-config consumer of the C API"
unset PKG_CONFIG_PATH

# No CMAKE_BUILD_TYPE: the consumer checks that Tessera does not set one.
step "subproject: add_subdirectory of $src"
consumer "$tmp/subproject" -DTESSERA_CONSUMER_MODE=subdirectory \
  -DTESSERA_CONSUMER_SOURCE_DIR="$src" -DTESSERA_HWY_DISABLED_TARGETS="$reduced_targets"
step "subproject: FetchContent of $src (the same binary directory)"
rm -f "$tmp/subproject/consumer"
consumer "$tmp/subproject" -DTESSERA_CONSUMER_MODE=fetchcontent

step "shared: BUILD_SHARED_LIBS=ON, installed, find_package(Tessera)"
if ! cmake -S "$src" -B "$tmp/shared-build" "${generator[@]}" -DCMAKE_CXX_COMPILER="$cxx" \
  -DBUILD_SHARED_LIBS=ON -DTESSERA_HWY_DISABLED_TARGETS="$reduced_targets" \
  -DCMAKE_BUILD_TYPE=None \
  >"$tmp/shared-build.log" 2>&1; then
  cat "$tmp/shared-build.log"
  fail "configuring the shared build"
fi
cmake --build "$tmp/shared-build" -j "$jobs" >>"$tmp/shared-build.log" 2>&1 || {
  tail -50 "$tmp/shared-build.log"
  fail "building the shared library"
}
cmake --install "$tmp/shared-build" --prefix "$tmp/shared" >"$tmp/shared-install.log"
check_headers "$tmp/shared"
libdir=$(find "$tmp/shared" -name 'libtessera.so.0' -printf '%h')
[ -n "$libdir" ] || fail "no libtessera.so.0 installed"
for lib in libtessera libtessera_io; do
  soname=$(objdump -p "$libdir/$lib.so" | awk '$1 == "SONAME" { print $2 }')
  [ "$soname" = "$lib.so.0" ] || fail "$lib.so has the soname '$soname', not $lib.so.0"
  # The symbols' names, without address and type; a name is internal when it (not merely a
  # parameter's type, or a template argument) is in an internal namespace.
  exported=$(nm -D -C --defined-only "$libdir/$lib.so" | cut -d' ' -f3-)
  internal=$(echo "$exported" |
    grep -E '^[^(<]*(^| )tessera::(detail|fast|reference|simd|binning)::' || true)
  [ -z "$internal" ] || fail "$lib.so exports internal symbols:
$internal"
  echo "$lib.so: soname $soname, $(echo "$exported" | grep -c 'tessera::') tessera symbols exported"
done
# The C API's functions are exported under their C names.
c_exported=$(nm -D --defined-only "$libdir/libtessera.so" | awk '$3 ~ /^tessera_/ { print $3 }')
for symbol in tessera_renderer_create tessera_draw_triangles tessera_framebuffer_read_depth \
  tessera_last_error_message; do
  echo "$c_exported" | grep -qx "$symbol" || fail "libtessera.so does not export $symbol"
done
echo "libtessera.so: $(echo "$c_exported" | wc -l) C API functions exported"
consumer "$tmp/package-shared" -DCMAKE_PREFIX_PATH="$tmp/shared" -DCMAKE_BUILD_TYPE=Release
consumer "$tmp/package-shared-io" -DCMAKE_PREFIX_PATH="$tmp/shared" -DCMAKE_BUILD_TYPE=Release \
  -DTESSERA_CONSUMER_IO=ON

step "every consumer built and drew its triangle"
