// Value types shared by the whole public API.
#pragma once

#include <cstdint>

namespace tessera {

// A clip-space position (x, y, z, w) or an RGBA colour. Same layout as float[4] and glm::vec4.
struct Float4 {
  float x = 0.0f;
  float y = 0.0f;
  float z = 0.0f;
  float w = 0.0f;
  friend bool operator==(const Float4&, const Float4&) = default;
};

// Largest framebuffer side, in pixels (the D3D11 limit).
inline constexpr uint32_t kMaxFramebufferSize = 16384;
// Largest number of float attributes (varyings) per vertex.
inline constexpr uint32_t kMaxVaryings = 32;
inline constexpr uint32_t kMaxAttributes = kMaxVaryings;
// Colour targets per framebuffer: target 0 and up to three extra ones (multiple render
// targets).
inline constexpr uint32_t kMaxColorTargets = 4;

}  // namespace tessera
