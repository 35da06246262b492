// Helpers for the reference rasterizer's specification tests (reference_*_test.cpp): clip-space
// vertices built from window pixel coordinates, draws with explicit state, per-sample hit
// counts, the standard MSAA positions as the specs print them, and the fill rule written out
// independently of the rasterizer (as an infinitesimal nudge of the sample) for whole polygons.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <initializer_list>
#include <span>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "tessera/tessera.hpp"

namespace tessera::test {

// A window point in pixels: x right, y down, origin at the top-left corner.
struct Point {
  double x = 0;
  double y = 0;
};

// The viewport transform run backwards (ARCHITECTURE.md section 2): the clip-space position
// whose window coordinates are (x, y), with NDC depth z and homogeneous w:
//   x_clip = (2 x / width - 1) w,  y_clip = (1 - 2 y / height) w,  z_clip = z w.
// With power-of-two sizes and dyadic pixel coordinates every step is exact in float.
struct Viewport {
  uint32_t width = 16;
  uint32_t height = 16;

  Float4 at(double x, double y, double z = 0.5, double w = 1.0) const {
    return {static_cast<float>((2.0 * x / width - 1.0) * w),
            static_cast<float>((1.0 - 2.0 * y / height) * w), static_cast<float>(z * w),
            static_cast<float>(w)};
  }
  Float4 at(Point p, double z = 0.5, double w = 1.0) const { return at(p.x, p.y, z, w); }
};

// These suites specify the scalar reference rasterizer (ARCHITECTURE.md section 3), so they
// ask for it by name rather than rely on the default backend.
inline RendererOptions reference_options() {
  RendererOptions options;
  options.backend = Backend::kReference;
  options.threads = 1;
  return options;
}
inline Renderer reference_renderer() {
  return Renderer(reference_options());
}

// Draws a triangle list with one RGBA colour per vertex (or none).
inline void draw(Renderer& renderer, Framebuffer& fb, const PipelineState& pipeline,
                 std::span<const Float4> positions, std::span<const float> rgba = {}) {
  DrawInput input;
  input.positions = positions;
  input.attributes = rgba;
  input.attribute_count = rgba.empty() ? 0 : 4;
  renderer.draw(fb, pipeline, input);
}

// Pipeline state that records coverage in depth: every covered sample passes and writes.
inline PipelineState coverage_pipeline(PipelineState base = {}) {
  base.depth_test = true;
  base.depth_write = true;
  base.depth_compare = CompareOp::kAlways;
  return base;
}

// Counts, per sample, how many triangles cover it. Each triangle is drawn on its own into a
// framebuffer whose depth is cleared to -1, a value no draw can write (depth lies in [0, 1]),
// with depth compare ALWAYS; a sample is covered exactly when its depth no longer reads -1.
// Drawing one triangle at a time is what makes a double hit visible.
class SampleHits {
 public:
  explicit SampleHits(uint32_t width, uint32_t height, uint32_t samples = 1)
      : renderer_(reference_options()),
        fb_({width, height, samples, ColorFormat::kRGBA8}),
        hits_(size_t{width} * height * samples, 0) {}

  // Draws every triangle of the list separately with `pipeline`'s cull, winding and snapping.
  void add(std::span<const Float4> triangle_list, const PipelineState& pipeline = {}) {
    for (size_t t = 0; t + 2 < triangle_list.size(); t += 3) {
      fb_.clear_depth(-1.0f);
      draw(renderer_, fb_, coverage_pipeline(pipeline), triangle_list.subspan(t, 3));
      const std::vector<float> depth = fb_.read_sample_depth();
      for (size_t i = 0; i < depth.size(); ++i) {
        hits_[i] += depth[i] != -1.0f ? 1 : 0;
      }
    }
  }
  void add(std::initializer_list<Float4> triangle_list, const PipelineState& pipeline = {}) {
    add(std::span<const Float4>(triangle_list.begin(), triangle_list.size()), pipeline);
  }

  uint32_t width() const { return fb_.width(); }
  uint32_t height() const { return fb_.height(); }
  uint32_t samples() const { return fb_.samples(); }
  int at(uint32_t x, uint32_t y, uint32_t s = 0) const {
    return hits_[(size_t{y} * width() + x) * samples() + s];
  }
  // Total hits over all samples.
  uint64_t total() const {
    uint64_t n = 0;
    for (int h : hits_) {
      n += static_cast<uint64_t>(h);
    }
    return n;
  }
  const Counters& counters() const { return renderer_.counters(); }

  // One text row per pixel row, top row first, each ending in '\n': '.' for a pixel no
  // triangle covers, 'X' for one hit, '2'..'9' for more. Single-sample framebuffers only.
  std::string picture() const {
    EXPECT_EQ(samples(), 1u);
    std::string s;
    for (uint32_t y = 0; y < height(); ++y) {
      for (uint32_t x = 0; x < width(); ++x) {
        const int h = at(x, y);
        s += h == 0 ? '.' : h == 1 ? 'X' : static_cast<char>('0' + std::min(h, 9));
      }
      s += '\n';
    }
    return s;
  }

 private:
  Renderer renderer_;
  Framebuffer fb_;
  std::vector<int> hits_;
};

// The standard sample positions of D3D11 (D3D11_STANDARD_MULTISAMPLE_PATTERN) and Vulkan
// (the "standard sample locations" table of the Vulkan spec), in pixels from the pixel's
// top-left corner, as printed there. Written out here so the tests do not read the engine's
// own table.
inline std::vector<Point> standard_sample_positions(uint32_t samples) {
  switch (samples) {
    case 1:
      return {{0.5, 0.5}};
    case 2:
      return {{0.75, 0.75}, {0.25, 0.25}};
    case 4:
      return {{0.375, 0.125}, {0.875, 0.375}, {0.125, 0.625}, {0.625, 0.875}};
    case 8:
      return {{0.5625, 0.3125}, {0.4375, 0.6875}, {0.8125, 0.5625}, {0.3125, 0.1875},
              {0.1875, 0.8125}, {0.0625, 0.4375}, {0.6875, 0.9375}, {0.9375, 0.0625}};
    case 16:
      return {{0.5625, 0.5625}, {0.4375, 0.3125}, {0.3125, 0.625},  {0.75, 0.4375},
              {0.1875, 0.375},  {0.625, 0.8125},  {0.8125, 0.6875}, {0.6875, 0.1875},
              {0.375, 0.875},   {0.5, 0.0625},    {0.25, 0.125},    {0.125, 0.75},
              {0.0, 0.5},       {0.9375, 0.25},   {0.875, 0.9375},  {0.0625, 0.0}};
    default:
      ADD_FAILURE() << "no standard pattern for " << samples << " samples";
      return {};
  }
}

// Window position of sample s of pixel (x, y).
inline Point sample_position(uint32_t samples, uint32_t x, uint32_t y, uint32_t s) {
  const Point o = standard_sample_positions(samples)[s];
  return {x + o.x, y + o.y};
}

// The fill rule applied to a whole convex polygon (either winding) at 8 subpixel bits, written
// as the rule's geometric meaning rather than its edge classification: a point on the boundary
// counts as inside when nudging it right by an infinitesimal e and down by e*e moves it inside.
// The nudge is the same for every triangle, so a mesh that tiles the polygon covers each of
// the polygon's samples exactly once and no other sample.
inline bool polygon_covers(std::span<const Point> polygon, Point sample) {
  auto fixed = [](double v) { return static_cast<int64_t>(std::nearbyint(v * 256.0)); };
  const int64_t px = fixed(sample.x);
  const int64_t py = fixed(sample.y);
  const size_t n = polygon.size();
  int64_t twice_area = 0;  // > 0 for clockwise on screen (y down)
  for (size_t i = 0; i < n; ++i) {
    const Point& a = polygon[i];
    const Point& b = polygon[(i + 1) % n];
    twice_area += fixed(a.x) * fixed(b.y) - fixed(b.x) * fixed(a.y);
  }
  const int64_t sign = twice_area > 0 ? 1 : -1;
  for (size_t i = 0; i < n; ++i) {
    const int64_t ax = fixed(polygon[i].x), ay = fixed(polygon[i].y);
    const int64_t bx = fixed(polygon[(i + 1) % n].x), by = fixed(polygon[(i + 1) % n].y);
    // Positive on the inside of edge a -> b.
    const int64_t dx = sign * (bx - ax), dy = sign * (by - ay);
    const int64_t e = dx * (py - ay) - dy * (px - ax);
    if (e > 0) continue;
    if (e < 0) return false;
    // e(p + (eps, eps^2)) = -dy * eps + dx * eps^2: the sign of -dy, else of dx.
    if (dy > 0 || (dy == 0 && dx <= 0)) return false;
  }
  return true;
}

}  // namespace tessera::test
