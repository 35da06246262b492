// The scene of the shaded-draw tests (fast_shading_test.cpp, user_shader_test.cpp): a
// perspective mesh with small, medium, large and clipped triangles under a depth test, ten
// varyings per vertex, and the draw that renders it on either backend and reads it back.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "simd/dispatch.hpp"
#include "tessera/tessera.hpp"
#include "tests/simd_targets.hpp"

namespace tessera::shading_scene {

constexpr uint32_t kWidth = 100, kHeight = 76;  // two tiles across and down, both partial
constexpr float kClear = -7.0f;                 // no shaded value is this

// Ten varyings per vertex at the default roles: colour 0..3, normal 4..6, eye-space position
// 7..9.
struct Mesh {
  std::vector<Float4> positions;
  std::vector<float> varyings;
  DrawInput input() const { return {positions, varyings, 10, {}}; }
};

// A perspective projection (60 degrees vertically, near 0.5, far 20) of eye-space points.
inline Float4 project(double x, double y, double z) {
  const double f = 1.0 / std::tan(M_PI / 6.0), aspect = double{kWidth} / kHeight;
  const double near = 0.5, far = 20.0;
  return {static_cast<float>(f / aspect * x), static_cast<float>(f * y),
          static_cast<float>((far + near) / (near - far) * z + 2 * far * near / (near - far)),
          static_cast<float>(-z)};
}

inline void add_vertex(Mesh& m, double x, double y, double z, const std::array<double, 3>& normal,
                       const std::array<double, 4>& colour) {
  m.positions.push_back(project(x, y, z));
  for (double c : colour)
    m.varyings.push_back(static_cast<float>(c));
  for (double n : normal)
    m.varyings.push_back(static_cast<float>(n));
  for (double p : {x, y, z})
    m.varyings.push_back(static_cast<float>(p));
}

// A wavy sheet of n x n cells over [x0, x0 + size] x [y0, y0 + size] around depth z0, its
// normals tilting with the waves, and its colours varying across it.
inline void add_sheet(Mesh& m, int n, double x0, double y0, double size, double z0) {
  const auto vertex = [&](int i, int j) {
    const double x = x0 + size * i / n, y = y0 + size * j / n;
    const double z = z0 - 0.4 * std::sin(2.5 * x) * std::cos(1.7 * y) - 0.2 * x;
    add_vertex(m, x, y, z, {0.4 * std::cos(2.5 * x), -0.3 * std::sin(1.7 * y), 1.0},
               {double(i) / n, double(j) / n, 0.5 + 0.4 * std::sin(x * y), 0.6 + 0.3 * i / n});
  };
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      vertex(i, j), vertex(i + 1, j), vertex(i + 1, j + 1);
      vertex(i, j), vertex(i + 1, j + 1), vertex(i, j + 1);
    }
  }
}

inline Mesh test_mesh() {
  Mesh m;
  add_sheet(m, 12, -2.0, -1.6, 3.4, -4.0);  // medium triangles over most of the view
  add_sheet(m, 40, -0.6, -0.3, 0.9, -3.2);  // tiny ones in front, partly hiding it
  add_sheet(m, 2, -1.0, -1.0, 2.2, -6.0);   // large ones behind
  // A triangle reaching behind the eye: the near plane cuts it.
  add_vertex(m, -0.8, -0.9, -1.5, {0.1, 0.2, 1.0}, {1.0, 0.2, 0.1, 0.9});
  add_vertex(m, 0.9, -0.7, 1.0, {-0.2, 0.1, 1.0}, {0.1, 1.0, 0.2, 0.8});
  add_vertex(m, 0.2, -0.2, -2.5, {0.0, -0.3, 1.0}, {0.2, 0.1, 1.0, 1.0});
  return m;
}

// A SIMD target and a thread count for the fast engine.
struct Target {
  SimdTarget simd;
  uint32_t threads;
};

// The SIMD targets this CPU runs, each at 1, 2 and 3 threads.
inline std::vector<Target> fast_targets() {
  std::vector<Target> out;
  for (SimdTarget t : test::runnable_simd_targets()) {
    for (uint32_t threads : {1u, 2u, 3u})
      out.push_back({t, threads});
  }
  return out;
}

// A drawn mesh read back: the resolved colour (in the target's format) and every sample's depth.
struct Image {
  std::vector<float> rgba32f;
  std::vector<uint8_t> rgba8;
  std::vector<float> depth;
};

inline Image render(const Mesh& mesh, const PipelineState& pipeline, ColorFormat format,
                    uint32_t samples, Backend backend, Target target = {SimdTarget::kAuto, 1}) {
  RendererOptions options;
  options.backend = backend;
  options.simd = target.simd;
  options.threads = target.threads;
  Renderer renderer(options);
  Framebuffer fb({kWidth, kHeight, samples, format});
  fb.clear_color({kClear, kClear, kClear, kClear});
  renderer.draw(fb, pipeline, mesh.input());
  Image image;
  if (format == ColorFormat::kRGBA8) {
    image.rgba8 = fb.read_rgba8();
  } else {
    image.rgba32f = fb.read_rgba32f();
  }
  image.depth = fb.read_sample_depth();
  return image;
}

// A 64x32 RGBA8 texture of coloured checks of 4 texels with a ramp across them, so that every
// filter and mip level gives distinct values, with its mip chain.
inline std::shared_ptr<const Texture> checks() {
  constexpr uint32_t w = 64, h = 32;
  std::vector<uint8_t> p;
  for (uint32_t y = 0; y < h; ++y) {
    for (uint32_t x = 0; x < w; ++x) {
      const bool odd = ((x / 4) + (y / 4)) % 2 != 0;
      p.push_back(static_cast<uint8_t>(odd ? 230 : 20 + x));
      p.push_back(static_cast<uint8_t>(odd ? 40 + 3 * y : 200));
      p.push_back(static_cast<uint8_t>((x * 7 + y * 3) % 256));
      p.push_back(static_cast<uint8_t>(odd ? 255 : 128));
    }
  }
  return std::make_shared<Texture>(TextureDesc{w, h, TextureFormat::kRGBA8},
                                   std::as_bytes(std::span<const uint8_t>(p)), true);
}

}  // namespace tessera::shading_scene
