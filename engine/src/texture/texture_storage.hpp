// A texture's storage and texel decoding (tessera/texture.hpp), shared by the sampler
// (sampling.hpp) in float and in double, and by the SIMD sampler (sample_lanes-inl.h).
#pragma once

#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <vector>

#include "tessera/texture.hpp"

namespace tessera {

struct Texture::Storage {
  struct Level {
    uint32_t width = 0, height = 0;
    size_t offset = 0;  // into bytes
  };
  TextureDesc desc;
  uint32_t texel = 0;  // bytes per texel
  std::vector<Level> levels;
  std::vector<std::byte> bytes;

  size_t offset(uint32_t level, uint32_t x, uint32_t y) const {
    const Level& l = levels[level];
    return l.offset + (size_t{y} * l.width + x) * texel;
  }
  const std::byte* at(uint32_t level, uint32_t x, uint32_t y) const {
    return bytes.data() + offset(level, x, y);
  }
  std::byte* at(uint32_t level, uint32_t x, uint32_t y) {
    return bytes.data() + offset(level, x, y);
  }
};

namespace detail {
struct TextureAccess {
  static const Texture::Storage& storage(const Texture& t) { return *t.storage_; }
};
}  // namespace detail

namespace texture {

// sRGB-encoded value c in [0, 1] to linear (IEC 61966-2-1), in double.
inline double srgb_to_linear(double c) {
  return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
}

// The linear value of every sRGB-encoded byte in T, computed once in double: the same values
// as the formula's.
template <class T>
const std::array<T, 256>& srgb_table() {
  static const std::array<T, 256> table = [] {
    std::array<T, 256> t;
    for (int i = 0; i < 256; ++i)
      t[i] = static_cast<T>(srgb_to_linear(i / 255.0));
    return t;
  }();
  return table;
}

// An 8-bit unorm value in T: c / 255 rounded to T (in float the same value as c / 255.0
// rounded to float, for every byte), a division the SIMD sampler repeats in lanes.
template <class T>
T unorm8(uint8_t c) {
  return static_cast<T>(c) / T(255);
}

// A texel as linear RGBA in T (float or double): 8-bit values as unorm8 (sRGB's RGB decoded in
// double, then rounded to T), floats as stored, red formats (r, 0, 0, 1).
template <class T>
std::array<T, 4> decode(TextureFormat format, const std::byte* p) {
  const auto unorm = [&](int c) { return unorm8<T>(std::to_integer<uint8_t>(p[c])); };
  const auto f32 = [&](int c) {
    float v;
    std::memcpy(&v, p + 4 * c, sizeof v);
    return static_cast<T>(v);
  };
  switch (format) {
    case TextureFormat::kRGBA8:
      return {unorm(0), unorm(1), unorm(2), unorm(3)};
    case TextureFormat::kRGBA8Srgb: {
      const std::array<T, 256>& table = srgb_table<T>();
      const auto s = [&](int c) { return table[std::to_integer<uint8_t>(p[c])]; };
      return {s(0), s(1), s(2), unorm(3)};
    }
    case TextureFormat::kRGBA32F:
      return {f32(0), f32(1), f32(2), f32(3)};
    case TextureFormat::kR8:
      return {unorm(0), T{0}, T{0}, T{1}};
    case TextureFormat::kR32F:
      return {f32(0), T{0}, T{0}, T{1}};
  }
  return {T{0}, T{0}, T{0}, T{1}};
}

}  // namespace texture
}  // namespace tessera
