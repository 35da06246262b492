// The kernels' float-to-unorm8 packing in SIMD lanes (engine/src/fast/unorm8-inl.h), on every
// SIMD target this machine runs: each lane's packed RGBA8 is the scalar pack_rgba8 of its four
// channels, for values around every step between bytes, out of [0, 1], infinite, NaN, denormal
// and -0.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "tests/unorm8_test.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>

#include "engine/src/fast/unorm8-inl.h"

HWY_BEFORE_NAMESPACE();
namespace tessera::fast::HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

// Packs channel values r[i], g[i], b[i], a[i] into out[i], a vector at a time (n: a multiple
// of 64, the most float lanes of any target: 2048-bit SVE vectors).
void PackChannels(const float* r, const float* g, const float* b, const float* a, uint32_t* out,
                  size_t n) {
  const hn::ScalableTag<float> df;
  const hn::RebindToUnsigned<decltype(df)> du;
  for (size_t i = 0; i < n; i += hn::Lanes(df)) {
    hn::StoreU(pack_unorm8(df, hn::LoadU(df, r + i), hn::LoadU(df, g + i), hn::LoadU(df, b + i),
                           hn::LoadU(df, a + i)),
               du, out + i);
  }
}

}  // namespace tessera::fast::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
#include "engine/src/fast/pixel_record.hpp"

namespace tessera::fast {
HWY_EXPORT(PackChannels);

namespace {

// Values around every byte's boundary (k + 0.5) / 255 and at k / 255, and the special ones.
std::vector<float> test_values() {
  std::vector<float> values;
  for (int k = -2; k <= 258; ++k) {
    for (const float centre :
         {(static_cast<float>(k) + 0.5f) / 255.0f, static_cast<float>(k) / 255.0f}) {
      float v = centre;
      for (int step = 0; step < 3; ++step)
        v = std::nextafter(v, -1.0f);
      for (int step = 0; step < 7; ++step) {
        values.push_back(v);
        v = std::nextafter(v, 2.0f);
      }
    }
  }
  for (int i = 0; i <= 4096; ++i)
    values.push_back(-0.5f + static_cast<float>(i) / 2048.0f);
  for (const float special :
       {0.0f, -0.0f, 1.0f, std::numeric_limits<float>::denorm_min(),
        -std::numeric_limits<float>::denorm_min(), std::numeric_limits<float>::min(),
        std::numeric_limits<float>::max(), -std::numeric_limits<float>::max(),
        std::numeric_limits<float>::infinity(), -std::numeric_limits<float>::infinity(),
        std::numeric_limits<float>::quiet_NaN(), -std::numeric_limits<float>::quiet_NaN(),
        std::bit_cast<float>(0x7f800001u), std::bit_cast<float>(0xffc00001u)})
    values.push_back(special);
  while (values.size() % 64 != 0)
    values.push_back(0.5f);
  return values;
}

TEST(Unorm8Lanes, PackAsTheScalarConversionOnEveryTarget) {
  const std::vector<float> values = test_values();
  const size_t n = values.size();
  // Each channel takes the values in another order, so every channel sees every value with
  // different neighbours in the other channels.
  std::vector<float> channel[4];
  for (size_t c = 0; c < 4; ++c) {
    channel[c].resize(n);
    for (size_t i = 0; i < n; ++i)
      channel[c][i] = values[(i * (2 * c + 1) + 7 * c) % n];
  }
  std::vector<uint32_t> expected(n);
  for (size_t i = 0; i < n; ++i) {
    const float v[4] = {channel[0][i], channel[1][i], channel[2][i], channel[3][i]};
    expected[i] = pack_rgba8(v);
  }
  for (const int64_t target : hwy::SupportedAndGeneratedTargets()) {
    hwy::SetSupportedTargetsForTest(target);
    SCOPED_TRACE(hwy::TargetName(target));
    std::vector<uint32_t> packed(n, 0xdeadbeefu);
    HWY_DYNAMIC_DISPATCH(PackChannels)
    (channel[0].data(), channel[1].data(), channel[2].data(), channel[3].data(), packed.data(), n);
    for (size_t i = 0; i < n; ++i) {
      ASSERT_EQ(packed[i], expected[i]) << "r " << channel[0][i] << ", g " << channel[1][i]
                                        << ", b " << channel[2][i] << ", a " << channel[3][i];
    }
  }
  hwy::SetSupportedTargetsForTest(0);
}

}  // namespace
}  // namespace tessera::fast
#endif  // HWY_ONCE
