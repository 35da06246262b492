// Float colour to unorm8 in SIMD lanes, written once against Highway for every target: the
// raster kernel (block_kernel-inl.h), the vectorized setup's pixel and sample records
// (setup_kernel.cpp) and the line kernel (line_kernel.cpp) convert with the same operations, so
// a pixel gets the same byte whichever of them computes it.

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

// to_unorm8 (sample_positions.hpp) in each lane's low byte: k = truncate(clamp(c, 0, 1) * 255 +
// 0.5) (multiply, then add: never fused, the build forbids contraction), NaN 0. k is read off
// floor(...) + 2^23, whose significand is k: no float-to-integer conversion, which Highway
// follows with an overflow fix-up on x86. The bits above the low byte hold 2^23's exponent,
// which a shift left by 8 or more, or a mask, removes.
template <class DF, class VF>
HWY_INLINE auto unorm8_low_byte(DF df, VF c) {
#if HWY_ARCH_X86
  // x86's max returns its second operand when the first is NaN.
  const auto positive = hn::Max(c, hn::Zero(df));
#else
  const auto positive = hn::IfThenElseZero(hn::Gt(c, hn::Zero(df)), c);
#endif
  const auto clamped = hn::Min(positive, hn::Set(df, 1.0f));
  const auto scaled = hn::Add(hn::Mul(clamped, hn::Set(df, 255.0f)), hn::Set(df, 0.5f));
  return hn::BitCast(hn::RebindToUnsigned<DF>(),
                     hn::Add(hn::Floor(scaled), hn::Set(df, 8388608.0f)));
}

// Four channels' lanes as packed RGBA8 (pack_rgba8's bytes): g, b and a shifted left by 8 or
// more, which drops the exponent bits, and r's masked off.
template <class DF, class VF>
HWY_INLINE auto pack_unorm8(DF df, VF r, VF g, VF b, VF a) {
  const hn::RebindToUnsigned<DF> du;
  return hn::Or(
      hn::Or(hn::And(unorm8_low_byte(df, r), hn::Set(du, 0xFFu)),
             hn::ShiftLeft<8>(unorm8_low_byte(df, g))),
      hn::Or(hn::ShiftLeft<16>(unorm8_low_byte(df, b)), hn::ShiftLeft<24>(unorm8_low_byte(df, a))));
}

}  // namespace tessera::fast::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#endif  // per-target include guard
