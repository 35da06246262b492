// Round points: the disc of the point's size, antialiased by the distance of each pixel centre
// from the point (the usual one-pixel-ramp approximation of the disc's area coverage, as GL
// implementations draw smooth points).
#include "engine/src/reference/reference_points.hpp"

#include <algorithm>
#include <cmath>

#include "engine/src/reference/fragment_write.hpp"

namespace tessera::reference {

void draw_round_points(detail::FramebufferStorage& fb, const PipelineState& pipeline,
                       std::span<const WindowPoint> points, float size, Counters& counters) {
  const double reach = 0.5 * size + 0.5;
  for (const WindowPoint& p : points) {
    const int64_t x0 = std::max<int64_t>(0, static_cast<int64_t>(std::floor(p.x - reach)));
    const int64_t y0 = std::max<int64_t>(0, static_cast<int64_t>(std::floor(p.y - reach)));
    const int64_t x1 =
        std::min<int64_t>(fb.desc.width - 1, static_cast<int64_t>(std::floor(p.x + reach)));
    const int64_t y1 =
        std::min<int64_t>(fb.desc.height - 1, static_cast<int64_t>(std::floor(p.y + reach)));
    for (int64_t y = y0; y <= y1; ++y) {
      for (int64_t x = x0; x <= x1; ++x) {
        const double d =
            std::hypot(static_cast<double>(x) + 0.5 - p.x, static_cast<double>(y) + 0.5 - p.y);
        const double coverage = std::clamp(reach - d, 0.0, 1.0);
        if (coverage <= 0.0) continue;
        Fragment f;
        f.x = static_cast<uint32_t>(x);
        f.y = static_cast<uint32_t>(y);
        f.depth = static_cast<float>(p.z);
        f.color = p.color;
        f.coverage = static_cast<float>(coverage);
        write_fragment(fb, pipeline, f, true, counters);
      }
    }
  }
}

}  // namespace tessera::reference
