// See finite_scan.hpp. A float is NaN or infinite when its exponent bits are all set, that is
// when its magnitude bits (all but the sign) are at least those of infinity, 0x7f800000: so
// the scan keeps the largest magnitude bits it meets, one integer maximum per lane, and
// compares once at the end.
#include "engine/src/finite_scan.hpp"

#include <algorithm>
#include <cstring>

#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "engine/src/finite_scan.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>

HWY_BEFORE_NAMESPACE();
namespace tessera::HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

// The largest magnitude bits (value bits & 0x7fffffff) of values[0, n), or 0 when n is 0.
uint32_t LargestMagnitudeBits(const float* values, size_t n) {
  const hn::ScalableTag<float> df;
  const hn::RebindToUnsigned<decltype(df)> du;
  const size_t lanes = hn::Lanes(df);
  const auto magnitude = hn::Set(du, 0x7fffffffu);
  const auto bits = [&](const float* p) {
    return hn::And(hn::BitCast(du, hn::LoadU(df, p)), magnitude);
  };
  // Four independent maxima, so that the loop is not one chain of dependent instructions.
  auto m0 = hn::Zero(du), m1 = m0, m2 = m0, m3 = m0;
  size_t i = 0;
  for (; i + 4 * lanes <= n; i += 4 * lanes) {
    m0 = hn::Max(m0, bits(values + i));
    m1 = hn::Max(m1, bits(values + i + lanes));
    m2 = hn::Max(m2, bits(values + i + 2 * lanes));
    m3 = hn::Max(m3, bits(values + i + 3 * lanes));
  }
  for (; i + lanes <= n; i += lanes)
    m0 = hn::Max(m0, bits(values + i));
  uint32_t largest = hn::GetLane(hn::MaxOfLanes(du, hn::Max(hn::Max(m0, m1), hn::Max(m2, m3))));
  for (; i < n; ++i) {
    uint32_t b;
    std::memcpy(&b, values + i, sizeof b);
    largest = std::max(largest, b & 0x7fffffffu);
  }
  return largest;
}

}  // namespace tessera::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace tessera {

HWY_EXPORT(LargestMagnitudeBits);

bool values_finite(const float* values, size_t n) {
  return HWY_DYNAMIC_DISPATCH(LargestMagnitudeBits)(values, n) < 0x7f800000u;
}

}  // namespace tessera
#endif  // HWY_ONCE
