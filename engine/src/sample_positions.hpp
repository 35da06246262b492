// The standard MSAA sample positions of D3D11 and Vulkan (D3D11_STANDARD_MULTISAMPLE_PATTERN,
// Vulkan "standard sample locations"), and the colour conversions every path shares.
// Offsets are in 1/16 pixel from the pixel centre, x right and y down, so they are exact in
// fixed point for any subpixel precision of 4 bits or more.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <span>

namespace tessera {

struct SampleOffset {
  int8_t dx;  // 1/16 pixel, from the pixel centre
  int8_t dy;
};

inline constexpr std::array<SampleOffset, 1> kSamples1{{{0, 0}}};
inline constexpr std::array<SampleOffset, 2> kSamples2{{{4, 4}, {-4, -4}}};
inline constexpr std::array<SampleOffset, 4> kSamples4{{{-2, -6}, {6, -2}, {-6, 2}, {2, 6}}};
inline constexpr std::array<SampleOffset, 8> kSamples8{
    {{1, -3}, {-1, 3}, {5, 1}, {-3, -5}, {-5, 5}, {-7, -1}, {3, 7}, {7, -7}}};
inline constexpr std::array<SampleOffset, 16> kSamples16{{{1, 1},
                                                          {-1, -3},
                                                          {-3, 2},
                                                          {4, -1},
                                                          {-5, -2},
                                                          {2, 5},
                                                          {5, 3},
                                                          {3, -5},
                                                          {-2, 6},
                                                          {0, -7},
                                                          {-4, -6},
                                                          {-6, 4},
                                                          {-8, 0},
                                                          {7, -4},
                                                          {6, 7},
                                                          {-7, -8}}};

constexpr bool is_valid_sample_count(uint32_t n) {
  return n == 1 || n == 2 || n == 4 || n == 8 || n == 16;
}

// The pattern for a valid sample count (see is_valid_sample_count).
constexpr std::span<const SampleOffset> sample_pattern(uint32_t n) {
  switch (n) {
    case 2:
      return kSamples2;
    case 4:
      return kSamples4;
    case 8:
      return kSamples8;
    case 16:
      return kSamples16;
    default:
      return kSamples1;
  }
}

// Float colour to unorm8: clamp to [0, 1], scale by 255, round to nearest. NaN becomes 0.
inline uint8_t to_unorm8(float c) {
  if (!(c > 0.0f)) return 0;
  if (c >= 1.0f) return 255;
  return static_cast<uint8_t>(c * 255.0f + 0.5f);
}

}  // namespace tessera
