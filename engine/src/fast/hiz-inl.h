// Hi-Z bounds of one block from its samples, written once against Highway for every target:
// for the raster kernels (block_kernel-inl.h) and refresh_dirty_hiz (hiz.hpp) through the
// kernel table.

// Per-target include guard (see engine/src/fast/block_kernel-inl.h).
#if defined(TESSERA_ENGINE_SRC_FAST_HIZ_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef TESSERA_ENGINE_SRC_FAST_HIZ_INL_H_
#undef TESSERA_ENGINE_SRC_FAST_HIZ_INL_H_
#else
#define TESSERA_ENGINE_SRC_FAST_HIZ_INL_H_
#endif

#include <cstdint>
#include <limits>

#include <hwy/highway.h>

#include "engine/src/fast/block_kernel.hpp"

HWY_BEFORE_NAMESPACE();
namespace tessera::fast::HWY_NAMESPACE {

// The nearest and farthest of the 64 x `samples` depth values of a block (`depth`: its first
// value in sample plane 0; the planes kSamplePlane apart). A block holding a NaN sample (a NaN
// depth clear), which fails every ordering compare and which Min and Max may drop, is bounded
// by [-inf, inf]: up to date, and neither rejected nor accepted.
HWY_INLINE void RefreshHizBlock(const float* depth, uint32_t samples, float& block_min,
                                float& block_max) {
  namespace hn = hwy::HWY_NAMESPACE;
  const hn::ScalableTag<float> df;
  auto lo = hn::Set(df, std::numeric_limits<float>::infinity());
  auto hi = hn::Set(df, -std::numeric_limits<float>::infinity());
  auto nan = hn::FirstN(df, 0);
  for (uint32_t s = 0; s < samples; ++s) {
    for (size_t i = 0; i < 64; i += hn::Lanes(df)) {
      const auto z = hn::Load(df, depth + s * kSamplePlane + i);
      lo = hn::Min(lo, z);
      hi = hn::Max(hi, z);
      nan = hn::Or(nan, hn::IsNaN(z));
    }
  }
  if (!hn::AllFalse(df, nan)) {
    block_min = -std::numeric_limits<float>::infinity();
    block_max = std::numeric_limits<float>::infinity();
    return;
  }
  block_min = hn::GetLane(hn::MinOfLanes(df, lo));
  block_max = hn::GetLane(hn::MaxOfLanes(df, hi));
}

}  // namespace tessera::fast::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#endif  // per-target include guard
