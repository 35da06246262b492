// Run-time SIMD target selection over Highway's target bits (hwy::SupportedTargets).
#include "simd/dispatch.hpp"

#include <cstdlib>
#include <string_view>

#include <hwy/targets.h>

#include "tessera/error.hpp"

namespace tessera::simd {

namespace {

// Targets compiled into this build that the CPU can run.
int64_t available_bits() {
  return hwy::SupportedTargets() & HWY_TARGETS;
}

// The Highway bits a user-facing target may use, best first.
int64_t candidate_bits(SimdTarget t) {
  switch (t) {
    case SimdTarget::kScalar:
      return HWY_SCALAR | HWY_EMU128;
    case SimdTarget::kSSE4:
      return HWY_SSE4;
    case SimdTarget::kAVX2:
      return HWY_AVX2;
    case SimdTarget::kAVX512:
      return HWY_AVX3;
    case SimdTarget::kNEON:
      return HWY_NEON;
    case SimdTarget::kSVE:
      return HWY_SVE | HWY_SVE2 | HWY_SVE_256 | HWY_SVE2_128;
    case SimdTarget::kAuto:
      return available_bits();
  }
  return 0;
}

SimdTarget parse(std::string_view name) {
  if (name == "scalar") return SimdTarget::kScalar;
  if (name == "sse4") return SimdTarget::kSSE4;
  if (name == "avx2") return SimdTarget::kAVX2;
  if (name == "avx512") return SimdTarget::kAVX512;
  if (name == "neon") return SimdTarget::kNEON;
  if (name == "sve") return SimdTarget::kSVE;
  if (name == "auto" || name.empty()) return SimdTarget::kAuto;
  throw Error(ErrorCode::kInvalidArgument,
              "TESSERA_SIMD=" + std::string(name) +
                  " is not one of scalar, sse4, avx2, avx512, neon, sve, auto");
}

// The best (lowest) bit of `bits` that is available, or 0.
int64_t best_of(int64_t bits) {
  const int64_t usable = bits & available_bits();
  return usable & -usable;
}

std::string_view name_of(SimdTarget t) {
  switch (t) {
    case SimdTarget::kScalar:
      return "scalar";
    case SimdTarget::kSSE4:
      return "sse4";
    case SimdTarget::kAVX2:
      return "avx2";
    case SimdTarget::kAVX512:
      return "avx512";
    case SimdTarget::kNEON:
      return "neon";
    case SimdTarget::kSVE:
      return "sve";
    case SimdTarget::kAuto:
      return "auto";
  }
  return "?";
}

}  // namespace

int64_t resolve_target(SimdTarget requested) {
  bool from_env = false;
  if (requested == SimdTarget::kAuto) {
    if (const char* env = std::getenv("TESSERA_SIMD")) {
      requested = parse(env);
      from_env = requested != SimdTarget::kAuto;
    }
  }
  const int64_t bit = best_of(candidate_bits(requested));
  if (bit == 0) {
    throw Error(ErrorCode::kInvalidArgument,
                std::string(from_env ? "TESSERA_SIMD=" : "SIMD target ") +
                    std::string(name_of(requested)) +
                    " is not supported by this CPU or not compiled into this build");
  }
  return bit;
}

int64_t runnable_target_bits() {
  return available_bits();
}

bool is_available(SimdTarget target) {
  return best_of(candidate_bits(target)) != 0;
}

std::string target_name(int64_t bit) {
  switch (bit) {
    case HWY_SCALAR:
    case HWY_EMU128:
      return "scalar";
    case HWY_SSSE3:
      return "ssse3";
    case HWY_SSE4:
      return "sse4";
    case HWY_AVX2:
      return "avx2";
    case HWY_AVX3:
      return "avx512";
    case HWY_AVX3_DL:
      return "avx512-dl";
    case HWY_NEON:
      return "neon";
    default:
      return hwy::TargetName(bit);
  }
}

}  // namespace tessera::simd
