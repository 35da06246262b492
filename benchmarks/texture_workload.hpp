// The textured variant of a standard workload, drawn the same way by Tessera
// (tessera_workload_bench, FragmentShader::kTextured) and by llvmpipe (tessera_llvmpipe_bench
// --shading bilinear|trilinear, in GLSL): a 1024 x 1024 RGBA8 texture (linear, with its mip
// chain) sampled with repeat wrapping at texture coordinates made from the capture, times the
// capture's colour.
//
// Texture coordinates: the surface point behind each vertex under the camera of
// ../shared/workloads/gen_scene.py's grid (the eye at (0, -7, 5) looking at the origin, z up, a
// 60 degree vertical field of view, the capture's aspect ratio), its world (x, y) times
// kTextureRepeatsPerUnit. So the grid's heightfield is mapped as a terrain is, magnified in
// front and minified towards the horizon, and a soup (w = 1) gets a mapping linear on screen of
// about 1.2 texels per pixel (level of detail 0.3).
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include "tessera/tessera.hpp"

namespace tessera::bench {

inline constexpr uint32_t kTextureSize = 1024;
inline constexpr uint32_t kTexturedVaryings = 6;  // u, v, then the colour r, g, b, a
inline constexpr float kTextureRepeatsPerUnit = 1.1f;

// Level 0 of the benchmark texture: value noise of two octaves over a checkerboard of 32-texel
// cells, RGBA8 with alpha 255, so that every filter sees detail at every level.
inline std::vector<std::byte> texture_texels() {
  std::vector<std::byte> texels(size_t{kTextureSize} * kTextureSize * 4);
  const auto hash = [](uint32_t x) {
    x ^= x >> 16;
    x *= 0x7feb352du;
    x ^= x >> 15;
    x *= 0x846ca68bu;
    x ^= x >> 16;
    return x;
  };
  for (uint32_t y = 0; y < kTextureSize; ++y) {
    for (uint32_t x = 0; x < kTextureSize; ++x) {
      const uint32_t h = hash(y * kTextureSize + x), coarse = hash((y / 8) * 4096 + x / 8);
      const bool dark = ((x / 32) ^ (y / 32)) & 1;
      std::byte* t = texels.data() + (size_t{y} * kTextureSize + x) * 4;
      for (int c = 0; c < 3; ++c) {
        const uint32_t v =
            (dark ? 40u : 150u) + ((coarse >> (8 * c)) & 63u) + ((h >> (8 * c)) & 31u);
        t[c] = std::byte(static_cast<uint8_t>(v));
      }
      t[3] = std::byte{255};
    }
  }
  return texels;
}

inline std::shared_ptr<const Texture> benchmark_texture() {
  const std::vector<std::byte> texels = texture_texels();
  return std::make_shared<const Texture>(
      TextureDesc{kTextureSize, kTextureSize, TextureFormat::kRGBA8}, texels, true);
}

// Six varyings per vertex of `capture` (a TRI1 capture: RGBA per vertex): (u, v) as above, then
// the vertex's colour.
inline std::vector<float> textured_varyings(const Capture& capture) {
  const double aspect = double(capture.width) / capture.height;
  const double f = 1.0 / std::tan(60.0 * 3.14159265358979323846 / 360.0);
  // The camera's basis: right (1, 0, 0), up (0, 5, 7) / |g| and back (0, -7, 5) / |g|.
  const double g = std::sqrt(7.0 * 7.0 + 5.0 * 5.0);
  std::vector<float> out;
  out.reserve(capture.positions.size() * kTexturedVaryings);
  for (size_t i = 0; i < capture.positions.size(); ++i) {
    const Float4& p = capture.positions[i];
    // Eye space from clip space: x_clip = f / aspect x_eye, y_clip = f y_eye, w = -z_eye.
    const double ex = p.x * aspect / f, ey = p.y / f, ez = -p.w;
    const double wx = ex, wy = -7.0 + (5.0 * ey - 7.0 * ez) / g;
    const float* c = capture.varyings.data() + 4 * i;
    out.insert(out.end(),
               {static_cast<float>(wx * kTextureRepeatsPerUnit),
                static_cast<float>(-wy * kTextureRepeatsPerUnit), c[0], c[1], c[2], c[3]});
  }
  return out;
}

// The capture's state (capture_pipeline()) with the textured shader: bilinear (GL_LINEAR, level
// 0 only) or trilinear (GL_LINEAR_MIPMAP_LINEAR), repeat wrapping.
inline PipelineState textured_pipeline(std::shared_ptr<const Texture> texture, bool trilinear) {
  PipelineState pipeline = capture_pipeline();
  pipeline.shader = FragmentShader::kTextured;
  pipeline.roles.texcoord = 0;
  pipeline.roles.color = 2;
  pipeline.texture = std::move(texture);
  pipeline.sampler.mag_filter = Filter::kLinear;
  pipeline.sampler.min_filter = Filter::kLinear;
  pipeline.sampler.mip_filter = trilinear ? MipFilter::kLinear : MipFilter::kNone;
  pipeline.sampler.wrap_u = pipeline.sampler.wrap_v = Wrap::kRepeat;
  return pipeline;
}

}  // namespace tessera::bench
