// Scanline polygon fill (lecture 003, "sorted intersections"; Foley et al. section 3.6): for
// each row of samples, every edge crossing the row gives the first sample column at or right
// of its crossing, with +1 for an edge going down and -1 for one going up; sorted by column,
// the running sum is the winding number of each run of samples, and the fill rule (odd, or
// not zero) decides which runs are inside.
//
// Boundary rule: an edge crosses the sample row at y when y0 <= y < y1 (its ends ordered by
// y), and it counts for a sample whose x is at or right of the crossing. This is the fill rule
// of the triangles (a sample on the boundary is inside when moving it right by e and down by
// e^2 moves it inside), so a simple polygon covers the samples its tessellation covers.
// All in the snapped fixed-point coordinates; x0 dy + (y - y0) dx < 2^51 (coordinates below
// 2^24 after guard-band clipping), exact in int64.
#include "engine/src/reference/reference_polygon.hpp"

#include <algorithm>
#include <cstdint>
#include <utility>

#include "engine/src/primitive_assembly.hpp"
#include "engine/src/reference/fragment_write.hpp"
#include "engine/src/sample_positions.hpp"

namespace tessera::reference {

namespace {

int64_t floor_div(int64_t a, int64_t b) {  // b > 0
  return a >= 0 ? a / b : -((-a + b - 1) / b);
}
int64_t ceil_div(int64_t a, int64_t b) {  // b > 0
  return -floor_div(-a, b);
}

}  // namespace

void draw_scanline_polygon(detail::FramebufferStorage& fb, const PipelineState& pipeline,
                           const std::vector<std::vector<WindowPoint>>& contours, FillRule rule,
                           Counters& counters) {
  if (contours.empty()) return;
  const uint32_t bits = pipeline.subpixel_bits;
  const int shift = static_cast<int>(bits) - 4;
  const int64_t one = int64_t{1} << bits;
  const uint32_t samples = fb.desc.samples;
  const auto pattern = sample_pattern(samples);

  struct Edge {
    int64_t x0, y0, x1, y1;  // y0 < y1
    int winding;
  };
  std::vector<Edge> edges;
  int64_t min_y = INT64_MAX, max_y = INT64_MIN, min_x = INT64_MAX, max_x = INT64_MIN;
  for (const auto& c : contours) {
    for (size_t i = 0; i < c.size(); ++i) {
      const WindowPoint& p = c[i];
      const WindowPoint& q = c[(i + 1) % c.size()];
      min_x = std::min(min_x, p.fx);
      max_x = std::max(max_x, p.fx);
      min_y = std::min(min_y, p.fy);
      max_y = std::max(max_y, p.fy);
      if (p.fy == q.fy) continue;  // horizontal: crosses no sample row
      if (p.fy < q.fy) {
        edges.push_back({p.fx, p.fy, q.fx, q.fy, +1});
      } else {
        edges.push_back({q.fx, q.fy, p.fx, p.fy, -1});
      }
    }
  }
  const int64_t px0 = std::max<int64_t>(0, (min_x >> bits) - 1);
  const int64_t px1 = std::min<int64_t>(fb.desc.width - 1, (max_x >> bits) + 1);
  const int64_t py0 = std::max<int64_t>(0, (min_y >> bits) - 1);
  const int64_t py1 = std::min<int64_t>(fb.desc.height - 1, (max_y >> bits) + 1);
  if (px0 > px1 || py0 > py1) return;
  const size_t cols = static_cast<size_t>(px1 - px0 + 1);
  std::vector<uint32_t> masks(cols * static_cast<size_t>(py1 - py0 + 1), 0);

  std::vector<std::pair<int64_t, int>> events;
  for (uint32_t s = 0; s < samples; ++s) {
    const int64_t offset_x = int64_t{8 + pattern[s].dx} << shift;
    for (int64_t py = py0; py <= py1; ++py) {
      const int64_t sy = (py * 16 + 8 + pattern[s].dy) << shift;
      events.clear();
      for (const Edge& e : edges) {
        if (!(e.y0 <= sy && sy < e.y1)) continue;
        // The crossing is at x = x0 + (sy - y0) dx / dy; sample column k (at k one + offset_x)
        // counts it when k one + offset_x >= x, i.e. k >= (num - offset_x dy) / (one dy).
        const int64_t dy = e.y1 - e.y0;
        const int64_t num = e.x0 * dy + (sy - e.y0) * (e.x1 - e.x0);
        events.emplace_back(ceil_div(num - offset_x * dy, one * dy), e.winding);
      }
      std::sort(events.begin(), events.end());
      int winding = 0;
      for (size_t i = 0; i < events.size(); ++i) {
        winding += events[i].second;
        const bool inside = rule == FillRule::kEvenOdd ? (winding & 1) != 0 : winding != 0;
        if (!inside || i + 1 == events.size()) continue;
        const int64_t from = std::max(events[i].first, px0);
        const int64_t to = std::min(events[i + 1].first - 1, px1);
        for (int64_t x = from; x <= to; ++x) {
          masks[static_cast<size_t>(py - py0) * cols + static_cast<size_t>(x - px0)] |= 1u << s;
        }
      }
    }
  }

  const DepthPlane plane = polygon_depth_plane(contours);
  const std::array<float, 4> color = contours.front().front().color;
  for (int64_t py = py0; py <= py1; ++py) {
    for (int64_t px = px0; px <= px1; ++px) {
      const uint32_t mask =
          masks[static_cast<size_t>(py - py0) * cols + static_cast<size_t>(px - px0)];
      if (mask == 0) continue;
      Fragment f;
      f.x = static_cast<uint32_t>(px);
      f.y = static_cast<uint32_t>(py);
      f.depth = static_cast<float>(
          plane.at(static_cast<double>(px) + 0.5, static_cast<double>(py) + 0.5));
      f.dz_dx = static_cast<float>(plane.zx);
      f.dz_dy = static_cast<float>(plane.zy);
      f.color = color;
      f.sample_mask = mask;
      write_fragment(fb, pipeline, f, false, counters);
    }
  }
}

}  // namespace tessera::reference
