// Elementary functions in SIMD lanes, written once against Highway, that give the same bits on
// every target: only multiplies, adds, divisions, floors and exponent bit operations, in one
// fixed order (the build forbids contraction, so nothing is fused). Highway's contrib math may
// fuse where a target has FMA, which would make targets disagree. Accurate to a few units in
// the last place of a float over the ranges stated.

// Per-target include guard (see engine/src/fast/block_kernel-inl.h).
#if defined(TESSERA_SIMD_MATH_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef TESSERA_SIMD_MATH_INL_H_
#undef TESSERA_SIMD_MATH_INL_H_
#else
#define TESSERA_SIMD_MATH_INL_H_
#endif

#include <cstdint>

#include <hwy/highway.h>

HWY_BEFORE_NAMESPACE();
namespace tessera::simd::HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

// log2(x) for normal x > 0 (the smallest normal float, 2^-126, and up; below it, garbage). x =
// 2^e m with m in [sqrt(1/2), sqrt(2)); ln m = 2 atanh(t), t = (m - 1) / (m + 1), |t| < 0.172,
// by its series to t^9 (the next term is below 4e-10).
template <class DF, class VF = hn::Vec<DF>>
HWY_INLINE VF log2_positive(DF df, VF x) {
  const hn::RebindToSigned<DF> di;
  const auto bits = hn::BitCast(di, x);
  // m in [1, 2), then halved where it is at least sqrt(2), raising e by one.
  auto e = hn::Sub(hn::ShiftRight<23>(bits), hn::Set(di, 127));
  auto m = hn::BitCast(df, hn::Or(hn::And(bits, hn::Set(di, 0x007FFFFF)), hn::Set(di, 0x3F800000)));
  const auto high = hn::Ge(m, hn::Set(df, 1.41421356f));
  m = hn::IfThenElse(high, hn::Mul(m, hn::Set(df, 0.5f)), m);
  e = hn::IfThenElse(hn::RebindMask(di, high), hn::Add(e, hn::Set(di, 1)), e);
  const auto t = hn::Div(hn::Sub(m, hn::Set(df, 1.0f)), hn::Add(m, hn::Set(df, 1.0f)));
  const auto t2 = hn::Mul(t, t);
  auto series = hn::Set(df, 1.0f / 9.0f);
  series = hn::Add(hn::Mul(series, t2), hn::Set(df, 1.0f / 7.0f));
  series = hn::Add(hn::Mul(series, t2), hn::Set(df, 1.0f / 5.0f));
  series = hn::Add(hn::Mul(series, t2), hn::Set(df, 1.0f / 3.0f));
  series = hn::Add(hn::Mul(series, t2), hn::Set(df, 1.0f));
  // 2 / ln 2 = 2.88539008...
  const auto log2_m = hn::Mul(hn::Mul(series, t), hn::Set(df, 2.88539008f));
  return hn::Add(hn::ConvertTo(df, e), log2_m);
}

// 2^y for y <= 0 (0 below -126). y = i + f, i = floor(y), f in [0, 1); 2^f = sqrt(2) 2^(f - 1/2)
// by the series of e^(u ln 2), |u| <= 1/2, to u^7 (the next term is below 6e-9).
template <class DF, class VF = hn::Vec<DF>>
HWY_INLINE VF exp2_nonpositive(DF df, VF y) {
  const hn::RebindToSigned<DF> di;
  const auto tiny = hn::Lt(y, hn::Set(df, -126.0f));
  const auto yc = hn::Max(y, hn::Set(df, -126.0f));
  const auto i = hn::Floor(yc);
  const auto u = hn::Mul(hn::Sub(hn::Sub(yc, i), hn::Set(df, 0.5f)), hn::Set(df, 0.693147181f));
  // e^u = 1 + u (1 + u/2 (1 + u/3 (1 + u/4 (1 + u/5 (1 + u/6 (1 + u/7)))))).
  auto p = hn::Add(hn::Mul(u, hn::Set(df, 1.0f / 7.0f)), hn::Set(df, 1.0f));
  p = hn::Add(hn::Mul(hn::Mul(u, p), hn::Set(df, 1.0f / 6.0f)), hn::Set(df, 1.0f));
  p = hn::Add(hn::Mul(hn::Mul(u, p), hn::Set(df, 1.0f / 5.0f)), hn::Set(df, 1.0f));
  p = hn::Add(hn::Mul(hn::Mul(u, p), hn::Set(df, 1.0f / 4.0f)), hn::Set(df, 1.0f));
  p = hn::Add(hn::Mul(hn::Mul(u, p), hn::Set(df, 1.0f / 3.0f)), hn::Set(df, 1.0f));
  p = hn::Add(hn::Mul(hn::Mul(u, p), hn::Set(df, 0.5f)), hn::Set(df, 1.0f));
  p = hn::Add(hn::Mul(u, p), hn::Set(df, 1.0f));
  // 2^i for i in [-126, 0]: its exponent bits.
  const auto scale =
      hn::BitCast(df, hn::ShiftLeft<23>(hn::Add(hn::ConvertTo(di, i), hn::Set(di, 127))));
  const auto result = hn::Mul(hn::Mul(p, hn::Set(df, 1.41421356f)), scale);
  return hn::IfThenZeroElse(tiny, result);
}

// The largest whole exponent pow_unit forms by repeated squaring: at most 2 log2(n) rounded
// products, each within half an ulp, so the result's relative error stays below about n ulp.
inline constexpr float kMaxSquaringExponent = 128.0f;

// x^n for x in [0, 1] and a constant n >= 0, as std::pow gives it there: 1 where n = 0 (0^0
// included), 0 where x = 0 < n. Whole n up to kMaxSquaringExponent (Phong's usual shininess)
// by repeated squaring; other n as 2^(n log2 x), where x below the smallest normal float
// counts as 0.
template <class DF, class VF = hn::Vec<DF>>
HWY_INLINE VF pow_unit(DF df, VF x, float n) {
  if (n == 0.0f) return hn::Set(df, 1.0f);
  if (n <= kMaxSquaringExponent && n == static_cast<float>(static_cast<uint32_t>(n))) {
    uint32_t e = static_cast<uint32_t>(n);
    // The powers x^(2^i) for the set bits of e, lowest first, multiplied together.
    while ((e & 1u) == 0) {
      x = hn::Mul(x, x);
      e >>= 1;
    }
    VF result = x;
    for (e >>= 1; e != 0; e >>= 1) {
      x = hn::Mul(x, x);
      if (e & 1u) result = hn::Mul(result, x);
    }
    return result;
  }
  const auto normal = hn::Ge(x, hn::Set(df, 1.17549435e-38f));
  const auto safe = hn::IfThenElse(normal, x, hn::Set(df, 1.0f));
  const auto y = hn::Mul(log2_positive(df, safe), hn::Set(df, n));
  // log2 of x <= 1 is at most 0 up to rounding: clamp, so exp2's range holds.
  return hn::IfThenElseZero(normal, exp2_nonpositive(df, hn::Min(y, hn::Zero(df))));
}

}  // namespace tessera::simd::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#endif  // per-target include guard
