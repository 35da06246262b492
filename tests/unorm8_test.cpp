// The kernels' float-to-unorm8 packing in SIMD lanes (engine/src/fast/unorm8-inl.h), on every
// SIMD target this machine runs: each lane's packed RGBA8 is the scalar pack_rgba8 of its four
// channels, for values around every step between bytes, out of [0, 1] (up to and past the
// largest whose scaled sum converts to int32), infinite, NaN, denormal and -0.
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
// kClamp as pack_unorm8's.
template <bool kClamp>
void PackChannelsWith(const float* r, const float* g, const float* b, const float* a, uint32_t* out,
                      size_t n) {
  const hn::ScalableTag<float> df;
  const hn::RebindToUnsigned<decltype(df)> du;
  for (size_t i = 0; i < n; i += hn::Lanes(df)) {
    hn::StoreU(pack_unorm8<kClamp>(df, hn::LoadU(df, r + i), hn::LoadU(df, g + i),
                                   hn::LoadU(df, b + i), hn::LoadU(df, a + i)),
               du, out + i);
  }
}

void PackChannels(const float* r, const float* g, const float* b, const float* a, uint32_t* out,
                  size_t n) {
  PackChannelsWith<true>(r, g, b, a, out, n);
}

void PackChannelsUnclamped(const float* r, const float* g, const float* b, const float* a,
                           uint32_t* out, size_t n) {
  PackChannelsWith<false>(r, g, b, a, out, n);
}

}  // namespace tessera::fast::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
#include "engine/src/fast/pixel_record.hpp"

namespace tessera::fast {
HWY_EXPORT(PackChannels);
HWY_EXPORT(PackChannelsUnclamped);

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
  // Past 1 and below 0 by far: past int16 once scaled (128.5), past int32 (8421505).
  for (const float far :
       {2.0f, 128.0f, 128.5f, 129.0f, 257.0f, 8388608.0f, 8421504.0f, 8421505.0f, 1e10f}) {
    values.push_back(far);
    values.push_back(-far);
  }
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

// Packs every value of `values` (a multiple of 64 of them) in each channel, in another order
// per channel, with `pack` on every target, and expects the scalar pack_rgba8's bytes.
template <class Pack>
void expect_scalar_bytes(const std::vector<float>& values, Pack pack) {
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
    pack(channel[0].data(), channel[1].data(), channel[2].data(), channel[3].data(), packed.data(),
         n);
    for (size_t i = 0; i < n; ++i) {
      ASSERT_EQ(packed[i], expected[i]) << "r " << channel[0][i] << ", g " << channel[1][i]
                                        << ", b " << channel[2][i] << ", a " << channel[3][i];
    }
  }
  hwy::SetSupportedTargetsForTest(0);
}

TEST(Unorm8Lanes, PackAsTheScalarConversionOnEveryTarget) {
  expect_scalar_bytes(test_values(), [](auto... args) {
    HWY_DYNAMIC_DISPATCH(PackChannels)(args...);
  });
}

// Without the clamp, every value in [-0.25 / 255, 1 + 0.25 / 255] (the values of test_values
// there, and the floats nearest both ends) packs as with it.
TEST(Unorm8Lanes, PackWithoutTheClampAsTheScalarConversionNearTheUnitRange) {
  const float lo = -0.25f / 255.0f, hi = 1.0f + 0.25f / 255.0f;
  std::vector<float> values;
  for (const float v : test_values()) {
    if (v >= lo && v <= hi) values.push_back(v);
  }
  for (float end : {lo, hi}) {
    for (int step = 0; step < 8; ++step) {
      values.push_back(end);
      end = std::nextafter(end, 0.5f);
    }
  }
  while (values.size() % 64 != 0)
    values.push_back(0.5f);
  ASSERT_GT(values.size(), 3000u);
  expect_scalar_bytes(values, [](auto... args) {
    HWY_DYNAMIC_DISPATCH(PackChannelsUnclamped)(args...);
  });
}

}  // namespace
}  // namespace tessera::fast
#endif  // HWY_ONCE
