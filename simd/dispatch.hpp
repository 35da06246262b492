// Choosing the SIMD target a draw's kernels run on: the best one this CPU supports, or one a
// user forces through RendererOptions::simd or the TESSERA_SIMD environment variable
// (scalar, sse4, avx2, avx512, neon, sve). Targets are Highway target bits (HWY_AVX2, ...).
#pragma once

#include <cstdint>
#include <string>

#include "tessera/renderer.hpp"

namespace tessera::simd {

// The Highway target bit to run on. kAuto consults TESSERA_SIMD, then picks the best target
// that is compiled in and supported by this CPU. Throws Error(kInvalidArgument) when the
// requested target (or the environment variable's value) is unknown or unsupported here.
int64_t resolve_target(SimdTarget requested);

// Whether the target is compiled into this build and supported by this CPU.
bool is_available(SimdTarget target);

// The Highway target bits compiled into this build that this CPU runs, one bit each: every one
// of them is some SimdTarget's choice (resolve_target), so every kernel compiled can be forced
// and tested.
int64_t runnable_target_bits();

// The user-facing name of a target bit ("avx512", "avx2", "sse4", "scalar", ...).
std::string target_name(int64_t target_bit);

}  // namespace tessera::simd
