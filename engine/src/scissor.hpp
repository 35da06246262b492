// The pixels a draw may write: the framebuffer, clipped by the scissor rectangle when the
// pipeline's scissor test is on (tessera/pipeline.hpp). Both backends test pixels against it.
#pragma once

#include <algorithm>
#include <cstdint>

#include "tessera/pipeline.hpp"

namespace tessera {

// First and last pixel, inclusive; empty when x0 > x1 or y0 > y1.
struct PixelBox {
  int32_t x0 = 0, y0 = 0, x1 = -1, y1 = -1;

  bool empty() const { return x0 > x1 || y0 > y1; }
  bool contains(int64_t x, int64_t y) const { return x >= x0 && x <= x1 && y >= y0 && y <= y1; }
};

inline PixelBox draw_box(const PipelineState& pipeline, uint32_t width, uint32_t height) {
  int64_t x0 = 0, y0 = 0, x1 = int64_t{width} - 1, y1 = int64_t{height} - 1;
  if (pipeline.scissor_test) {
    const Rect& r = pipeline.scissor;
    x0 = std::max<int64_t>(x0, r.x);
    y0 = std::max<int64_t>(y0, r.y);
    x1 = std::min<int64_t>(x1, int64_t{r.x} + r.width - 1);
    y1 = std::min<int64_t>(y1, int64_t{r.y} + r.height - 1);
  }
  if (x0 > x1 || y0 > y1) return PixelBox{};
  return {static_cast<int32_t>(x0), static_cast<int32_t>(y0), static_cast<int32_t>(x1),
          static_cast<int32_t>(y1)};
}

}  // namespace tessera
