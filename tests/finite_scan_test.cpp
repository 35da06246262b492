// The scan validation runs over vertex arrays for NaN and infinity (engine/src/finite_scan.hpp),
// on every SIMD target this machine runs: every kind of non-finite value is found at every
// place of arrays whose lengths cover the vector loop and the scalar tail, and the largest
// finite values, denormals and -0 pass.
#include <gtest/gtest.h>

#include <bit>
#include <cstdint>
#include <limits>
#include <vector>

#include <hwy/targets.h>

#include "engine/src/finite_scan.hpp"

namespace tessera {
namespace {

// Runs body once per target this build has and this CPU supports, with the scan dispatched to it.
template <typename Body>
void for_each_target(Body body) {
  for (const int64_t target : hwy::SupportedAndGeneratedTargets()) {
    hwy::SetSupportedTargetsForTest(target);
    SCOPED_TRACE(hwy::TargetName(target));
    body();
  }
  hwy::SetSupportedTargetsForTest(0);
}

TEST(FiniteScan, FindsEveryNonFiniteValueAtEveryPlace) {
  const float bad[] = {std::numeric_limits<float>::infinity(),
                       -std::numeric_limits<float>::infinity(),
                       std::numeric_limits<float>::quiet_NaN(),
                       -std::numeric_limits<float>::quiet_NaN(),
                       std::numeric_limits<float>::signaling_NaN(),
                       std::bit_cast<float>(0x7fffffffu),
                       std::bit_cast<float>(0xff800001u)};
  for_each_target([&] {
    for (size_t n = 1; n <= 150; ++n) {
      std::vector<float> values(n, std::numeric_limits<float>::max());
      for (size_t i = 0; i < n; ++i) {
        for (const float b : bad) {
          values[i] = b;
          ASSERT_FALSE(values_finite(values.data(), n)) << "n " << n << ", at " << i;
        }
        values[i] = -std::numeric_limits<float>::max();
      }
    }
  });
}

TEST(FiniteScan, PassesFiniteValues) {
  const float good[] = {0.0f,
                        -0.0f,
                        1.0f,
                        std::numeric_limits<float>::max(),
                        -std::numeric_limits<float>::max(),
                        std::numeric_limits<float>::denorm_min(),
                        -std::numeric_limits<float>::min(),
                        std::bit_cast<float>(0x7f7fffffu)};
  for_each_target([&] {
    EXPECT_TRUE(values_finite(nullptr, 0));
    for (size_t n = 1; n <= 150; ++n) {
      std::vector<float> values(n);
      for (size_t i = 0; i < n; ++i)
        values[i] = good[i % std::size(good)];
      EXPECT_TRUE(values_finite(values.data(), n)) << "n " << n;
      // Only the first n values count: a NaN just past them is not read as theirs.
      values.push_back(std::numeric_limits<float>::quiet_NaN());
      EXPECT_TRUE(values_finite(values.data(), n)) << "n " << n;
    }
  });
}

}  // namespace
}  // namespace tessera
