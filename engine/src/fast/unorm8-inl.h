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

#if HWY_ARCH_X86 && HWY_TARGET != HWY_SCALAR && HWY_TARGET != HWY_EMU128
// x86 converts floats to int32 by truncation in one instruction; Highway's ConvertTo adds a
// fix-up for values past int32, which unorm8_low_byte's (0.5 to 255.5) never are.
inline constexpr bool kTruncateInOne = true;
HWY_INLINE __m128i truncate_to_int(__m128 v) {
  return _mm_cvttps_epi32(v);
}
#if HWY_TARGET <= HWY_AVX2
HWY_INLINE __m256i truncate_to_int(__m256 v) {
  return _mm256_cvttps_epi32(v);
}
#endif
#if HWY_TARGET <= HWY_AVX3
HWY_INLINE __m512i truncate_to_int(__m512 v) {
  return _mm512_cvttps_epi32(v);
}
#endif
#else
inline constexpr bool kTruncateInOne = false;
#endif

#if HWY_ARCH_X86 && HWY_TARGET <= HWY_SSSE3 && HWY_TARGET != HWY_SCALAR && HWY_TARGET != HWY_EMU128
// x86 from SSSE3 packs four channels' int32 lanes into RGBA8 with saturating packs: int32 to
// int16 (signed), int16 to uint8 (unsigned), so any negative value becomes 0 and any value
// from 255 to 2^31 - 1 becomes 255; within each 128-bit block the bytes then lie channel by
// channel (r0-r3, g0-g3, b0-b3, a0-a3), and one byte shuffle puts them pixel by pixel.
inline constexpr bool kPackBySaturation = true;
// The byte order that puts each 128-bit block's channel-by-channel bytes pixel by pixel.
HWY_INLINE __m128i channel_to_pixel_order() {
  return _mm_setr_epi8(0, 4, 8, 12, 1, 5, 9, 13, 2, 6, 10, 14, 3, 7, 11, 15);
}
HWY_INLINE __m128i pack_saturated(__m128i r, __m128i g, __m128i b, __m128i a) {
  return _mm_shuffle_epi8(_mm_packus_epi16(_mm_packs_epi32(r, g), _mm_packs_epi32(b, a)),
                          channel_to_pixel_order());
}
#if HWY_TARGET <= HWY_AVX2
HWY_INLINE __m256i pack_saturated(__m256i r, __m256i g, __m256i b, __m256i a) {
  return _mm256_shuffle_epi8(
      _mm256_packus_epi16(_mm256_packs_epi32(r, g), _mm256_packs_epi32(b, a)),
      _mm256_broadcastsi128_si256(channel_to_pixel_order()));
}
#endif
#if HWY_TARGET <= HWY_AVX3
HWY_INLINE __m512i pack_saturated(__m512i r, __m512i g, __m512i b, __m512i a) {
  return _mm512_shuffle_epi8(
      _mm512_packus_epi16(_mm512_packs_epi32(r, g), _mm512_packs_epi32(b, a)),
      _mm512_broadcast_i32x4(channel_to_pixel_order()));
}
#endif
#else
inline constexpr bool kPackBySaturation = false;
#endif

// to_unorm8 (sample_positions.hpp) in each lane's low byte: k = truncate(clamp(c, 0, 1) * 255 +
// 0.5) (multiply, then add: never fused, the build forbids contraction), NaN 0. On x86, k is
// the truncating conversion of that sum, and the bits above the low byte are 0. Elsewhere k is
// read off floor(...) + 2^23, whose significand is k (no float-to-integer conversion), and the
// bits above the low byte hold 2^23's exponent, which a shift left by 8 or more, or a mask,
// removes.
// Without kClamp, for lanes known to lie in [-0.25 / 255, 1 + 0.25 / 255] (the sum then lies in
// [0.25, 255.75]): the clamp is left out, and k is the same.
template <bool kClamp = true, class DF, class VF>
HWY_INLINE auto unorm8_low_byte(DF df, VF c) {
  VF clamped = c;
  if constexpr (kClamp) {
#if HWY_ARCH_X86
    // x86's max returns its second operand when the first is NaN.
    const auto positive = hn::Max(c, hn::Zero(df));
#else
    const auto positive = hn::IfThenElseZero(hn::Gt(c, hn::Zero(df)), c);
#endif
    clamped = hn::Min(positive, hn::Set(df, 1.0f));
  }
  const auto scaled = hn::Add(hn::Mul(clamped, hn::Set(df, 255.0f)), hn::Set(df, 0.5f));
  using VU = hn::Vec<hn::RebindToUnsigned<DF>>;
  if constexpr (kTruncateInOne) {
    return VU{truncate_to_int(scaled.raw)};
  } else {
    return hn::BitCast(hn::RebindToUnsigned<DF>(),
                       hn::Add(hn::Floor(scaled), hn::Set(df, 8388608.0f)));
  }
}

// Four channels' lanes as packed RGBA8 (pack_rgba8's bytes). x86 from SSSE3: the sums
// converted and packed with saturation (pack_saturated). Elsewhere: g, b and a shifted left by
// 8 or more, which drops any bits above their low bytes, and r's masked off where it has such
// bits. kClamp as unorm8_low_byte's.
template <bool kClamp = true, class DF, class VF>
HWY_INLINE auto pack_unorm8(DF df, VF r, VF g, VF b, VF a) {
  const hn::RebindToUnsigned<DF> du;
  if constexpr (kPackBySaturation) {
    // The packs clamp below 0 (NaN converts to -2^31, so it becomes 0 as well) and from 255 up
    // to 2^31 - 1: the clamp left is the one at 255.5, for sums that would not convert (2^31
    // and more, or infinite). x86's min returns its second operand when either is NaN, so NaN
    // passes it. For c in [0, 1] the sum is to_unorm8's; above, the byte is 255, below, 0.
    const auto to_int = [&](VF c) {
      auto scaled = hn::Add(hn::Mul(c, hn::Set(df, 255.0f)), hn::Set(df, 0.5f));
      if constexpr (kClamp) scaled = hn::Min(hn::Set(df, 255.5f), scaled);
      return truncate_to_int(scaled.raw);
    };
    return hn::Vec<decltype(du)>{pack_saturated(to_int(r), to_int(g), to_int(b), to_int(a))};
  } else {
    auto red = unorm8_low_byte<kClamp>(df, r);
    if constexpr (!kTruncateInOne) red = hn::And(red, hn::Set(du, 0xFFu));
    return hn::Or(hn::Or(red, hn::ShiftLeft<8>(unorm8_low_byte<kClamp>(df, g))),
                  hn::Or(hn::ShiftLeft<16>(unorm8_low_byte<kClamp>(df, b)),
                         hn::ShiftLeft<24>(unorm8_low_byte<kClamp>(df, a))));
  }
}

}  // namespace tessera::fast::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#endif  // per-target include guard
