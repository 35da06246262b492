// The Highway targets compiled into the including translation unit, best first, as an X-macro:
// TESSERA_FOR_EACH_SIMD_TARGET(ENTRY) expands ENTRY(bit, namespace) once per target, for
// building a run-time table of a kernel's per-target instances. Include it after
// hwy/foreach_target.h, in the HWY_ONCE part of a per-target source file, so that it sees that
// file's HWY_TARGETS.
#pragma once

#include <cstddef>
#include <cstdint>

#include <hwy/highway.h>

#if HWY_TARGETS & HWY_AVX3_DL
#define TESSERA_SIMD_TARGET_AVX3_DL(ENTRY) ENTRY(HWY_AVX3_DL, N_AVX3_DL)
#else
#define TESSERA_SIMD_TARGET_AVX3_DL(ENTRY)
#endif
#if HWY_TARGETS & HWY_AVX3
#define TESSERA_SIMD_TARGET_AVX3(ENTRY) ENTRY(HWY_AVX3, N_AVX3)
#else
#define TESSERA_SIMD_TARGET_AVX3(ENTRY)
#endif
#if HWY_TARGETS & HWY_AVX2
#define TESSERA_SIMD_TARGET_AVX2(ENTRY) ENTRY(HWY_AVX2, N_AVX2)
#else
#define TESSERA_SIMD_TARGET_AVX2(ENTRY)
#endif
#if HWY_TARGETS & HWY_SSE4
#define TESSERA_SIMD_TARGET_SSE4(ENTRY) ENTRY(HWY_SSE4, N_SSE4)
#else
#define TESSERA_SIMD_TARGET_SSE4(ENTRY)
#endif
#if HWY_TARGETS & HWY_SSSE3
#define TESSERA_SIMD_TARGET_SSSE3(ENTRY) ENTRY(HWY_SSSE3, N_SSSE3)
#else
#define TESSERA_SIMD_TARGET_SSSE3(ENTRY)
#endif
#if HWY_TARGETS & HWY_SVE2_128
#define TESSERA_SIMD_TARGET_SVE2_128(ENTRY) ENTRY(HWY_SVE2_128, N_SVE2_128)
#else
#define TESSERA_SIMD_TARGET_SVE2_128(ENTRY)
#endif
#if HWY_TARGETS & HWY_SVE_256
#define TESSERA_SIMD_TARGET_SVE_256(ENTRY) ENTRY(HWY_SVE_256, N_SVE_256)
#else
#define TESSERA_SIMD_TARGET_SVE_256(ENTRY)
#endif
#if HWY_TARGETS & HWY_SVE2
#define TESSERA_SIMD_TARGET_SVE2(ENTRY) ENTRY(HWY_SVE2, N_SVE2)
#else
#define TESSERA_SIMD_TARGET_SVE2(ENTRY)
#endif
#if HWY_TARGETS & HWY_SVE
#define TESSERA_SIMD_TARGET_SVE(ENTRY) ENTRY(HWY_SVE, N_SVE)
#else
#define TESSERA_SIMD_TARGET_SVE(ENTRY)
#endif
#if HWY_TARGETS & HWY_NEON
#define TESSERA_SIMD_TARGET_NEON(ENTRY) ENTRY(HWY_NEON, N_NEON)
#else
#define TESSERA_SIMD_TARGET_NEON(ENTRY)
#endif
#if HWY_TARGETS & HWY_EMU128
#define TESSERA_SIMD_TARGET_EMU128(ENTRY) ENTRY(HWY_EMU128, N_EMU128)
#else
#define TESSERA_SIMD_TARGET_EMU128(ENTRY)
#endif
#if HWY_TARGETS & HWY_SCALAR
#define TESSERA_SIMD_TARGET_SCALAR(ENTRY) ENTRY(HWY_SCALAR, N_SCALAR)
#else
#define TESSERA_SIMD_TARGET_SCALAR(ENTRY)
#endif

// clang-format off
#define TESSERA_FOR_EACH_SIMD_TARGET(ENTRY) \
  TESSERA_SIMD_TARGET_AVX3_DL(ENTRY)       \
  TESSERA_SIMD_TARGET_AVX3(ENTRY)          \
  TESSERA_SIMD_TARGET_AVX2(ENTRY)          \
  TESSERA_SIMD_TARGET_SSE4(ENTRY)          \
  TESSERA_SIMD_TARGET_SSSE3(ENTRY)         \
  TESSERA_SIMD_TARGET_SVE2_128(ENTRY)      \
  TESSERA_SIMD_TARGET_SVE_256(ENTRY)       \
  TESSERA_SIMD_TARGET_SVE2(ENTRY)          \
  TESSERA_SIMD_TARGET_SVE(ENTRY)           \
  TESSERA_SIMD_TARGET_NEON(ENTRY)          \
  TESSERA_SIMD_TARGET_EMU128(ENTRY)        \
  TESSERA_SIMD_TARGET_SCALAR(ENTRY)
// clang-format on

// Looks up a per-target instance in a table built with TESSERA_FOR_EACH_SIMD_TARGET; a target
// the table lacks (another architecture's extension) gets the last entry, the portable
// baseline every build compiles.
namespace tessera::simd {

template <typename Fn>
struct TargetEntry {
  int64_t bit;
  Fn fn;
};

template <typename Fn, size_t N>
Fn find_target(const TargetEntry<Fn> (&table)[N], int64_t bit) {
  for (const TargetEntry<Fn>& entry : table) {
    if (entry.bit == bit) return entry.fn;
  }
  return table[N - 1].fn;
}

}  // namespace tessera::simd
