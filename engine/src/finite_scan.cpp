// See finite_scan.hpp. The whole vectors of values take vectors_finite (finite_scan-inl.h),
// whose loop has no branch on the values; the few left over are tested one by one.
#include "engine/src/finite_scan.hpp"

#include <cmath>

#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "engine/src/finite_scan.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>

#include "engine/src/finite_scan-inl.h"

HWY_BEFORE_NAMESPACE();
namespace tessera::HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

bool ValuesFinite(const float* values, size_t n) {
  const hn::ScalableTag<float> df;
  const size_t whole = n - n % hn::Lanes(df);
  bool all = vectors_finite(df, values, whole);
  for (size_t i = whole; i < n; ++i)
    all = all && std::isfinite(values[i]);
  return all;
}

}  // namespace tessera::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace tessera {

HWY_EXPORT(ValuesFinite);

bool values_finite(const float* values, size_t n) {
  return HWY_DYNAMIC_DISPATCH(ValuesFinite)(values, n);
}

}  // namespace tessera
#endif  // HWY_ONCE
