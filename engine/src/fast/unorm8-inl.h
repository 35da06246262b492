// Float colour to unorm8 in SIMD lanes, written once against Highway for every target: the
// raster kernel (block_kernel-inl.h) and the vectorized setup's pixel records
// (setup_kernel.cpp) convert with the same operations, so a pixel gets the same byte whichever
// of them computes it.

// Per-target include guard (as block_kernel-inl.h's).
#if defined(TESSERA_ENGINE_SRC_FAST_UNORM8_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef TESSERA_ENGINE_SRC_FAST_UNORM8_INL_H_
#undef TESSERA_ENGINE_SRC_FAST_UNORM8_INL_H_
#else
#define TESSERA_ENGINE_SRC_FAST_UNORM8_INL_H_
#endif

#include <hwy/highway.h>

HWY_BEFORE_NAMESPACE();
namespace tessera::fast::HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

// As to_unorm8 (sample_positions.hpp) does for finite values: clamp to [0, 1], then
// truncate(c * 255 + 0.5) (multiply, then add: never fused, the build forbids contraction).
template <class DF, class VF>
HWY_INLINE auto to_unorm8(DF df, VF c) {
  const hn::RebindToUnsigned<DF> du;
  const auto clamped = hn::Min(hn::Max(c, hn::Zero(df)), hn::Set(df, 1.0f));
  const auto scaled = hn::Add(hn::Mul(clamped, hn::Set(df, 255.0f)), hn::Set(df, 0.5f));
  return hn::BitCast(du, hn::ConvertTo(hn::RebindToSigned<DF>(), scaled));
}

}  // namespace tessera::fast::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#endif  // per-target include guard
