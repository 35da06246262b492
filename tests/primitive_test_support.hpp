// Helpers for the point, line and polygon suites: draws with one colour per vertex in window
// pixel coordinates, and the set of pixels a draw touched, read from depth (cleared to -1, a
// value no draw writes, with compare ALWAYS: a touched pixel's depth is no longer -1).
#pragma once

#include <algorithm>
#include <set>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "tests/reference_test_support.hpp"

namespace tessera::test {

using Pixel = std::pair<int, int>;  // (x, y)
using PixelSet = std::set<Pixel>;

struct WindowVertex {
  double x, y;
  double z = 0.5;
  double w = 1.0;
};

// Clip-space positions and RGBA colours (opaque white unless given) for window vertices.
struct Vertices {
  std::vector<Float4> positions;
  std::vector<float> colors;
  Vertices(const Viewport& vp, std::initializer_list<WindowVertex> vs) {
    for (const WindowVertex& v : vs)
      add(vp, v);
  }
  void add(const Viewport& vp, const WindowVertex& v, std::array<float, 4> rgba = {1, 1, 1, 1}) {
    positions.push_back(vp.at(v.x, v.y, v.z, v.w));
    colors.insert(colors.end(), rgba.begin(), rgba.end());
  }
  DrawInput input() const { return {positions, colors, 4, {}}; }
};

inline PipelineState touch_pipeline() {
  return coverage_pipeline();
}

// The pixels whose sample 0 a draw touched, drawing on a framebuffer with depth -1.
template <typename Draw>
PixelSet touched(uint32_t width, uint32_t height, Draw draw, uint32_t samples = 1,
                 Backend backend = Backend::kReference) {
  Renderer renderer(RendererOptions{1, backend});
  Framebuffer fb({width, height, samples, ColorFormat::kRGBA8});
  fb.clear_depth(-1.0f);
  draw(renderer, fb);
  const std::vector<float> depth = fb.read_depth();
  PixelSet s;
  for (uint32_t y = 0; y < height; ++y) {
    for (uint32_t x = 0; x < width; ++x) {
      if (depth[size_t{y} * width + x] != -1.0f)
        s.insert({static_cast<int>(x), static_cast<int>(y)});
    }
  }
  return s;
}

// One row of pixels as text: 'X' where touched, '.' elsewhere.
inline std::string row_picture(const PixelSet& s, int y, int width) {
  std::string r;
  for (int x = 0; x < width; ++x)
    r += s.count({x, y}) ? 'X' : '.';
  return r;
}

inline std::string describe(const PixelSet& s) {
  std::ostringstream r;
  for (const Pixel& p : s)
    r << "(" << p.first << "," << p.second << ")";
  return r.str();
}

}  // namespace tessera::test
