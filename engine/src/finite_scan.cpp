// See finite_scan.hpp. Every vector of values takes Highway's IsFinite (one instruction with
// AVX-512), and the lanes' results are combined at the end, so the loop has no branch on them.
#include "engine/src/finite_scan.hpp"

#include <cmath>

#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "engine/src/finite_scan.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>

HWY_BEFORE_NAMESPACE();
namespace tessera::HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

bool ValuesFinite(const float* values, size_t n) {
  const hn::ScalableTag<float> df;
  const size_t lanes = hn::Lanes(df);
  auto finite = hn::FirstN(df, lanes);
  size_t i = 0;
  for (; i + lanes <= n; i += lanes)
    finite = hn::And(finite, hn::IsFinite(hn::LoadU(df, values + i)));
  bool all = hn::AllTrue(df, finite);
  for (; i < n; ++i)
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
