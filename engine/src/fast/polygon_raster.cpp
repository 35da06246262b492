// Tile-parallel scanline fill (polygon_raster.hpp): one task per tile of the polygon's box. A
// tile walks its own rows of samples; on each, the crossings of every edge (first sample column
// at or right of the crossing, exact integer ceiling division, +1 down and -1 up) are sorted
// and summed from the left edge of the screen, since crossings left of the tile count too, and
// the fill rule marks the tile's samples inside (lecture 003's sorted intersections, with the
// boundary rule of reference_polygon.cpp). Fragments go through fragment_writer.hpp.
#include "engine/src/fast/polygon_raster.hpp"

#include <algorithm>
#include <array>
#include <cstdint>
#include <limits>
#include <utility>

#include <tbb/parallel_for.h>

#include "engine/src/fast/fragment_writer.hpp"
#include "engine/src/primitive_assembly.hpp"
#include "engine/src/sample_positions.hpp"

namespace tessera::fast {

namespace {

int64_t ceil_div(int64_t a, int64_t b) {  // b > 0
  return a >= 0 ? (a + b - 1) / b : -((-a) / b);
}

struct Edge {
  int64_t x0, y0, x1, y1;  // y0 < y1
  int winding;
};

}  // namespace

void draw_scanline_polygon(tbb::task_arena& arena, detail::FramebufferStorage& fb,
                           const PipelineState& pipeline,
                           const std::vector<std::vector<WindowPoint>>& contours, FillRule rule,
                           Counters& counters) {
  if (contours.empty()) return;
  const uint32_t bits = pipeline.subpixel_bits;
  const int shift = static_cast<int>(bits) - 4;
  const int64_t one = int64_t{1} << bits;
  const uint32_t samples = fb.desc.samples;
  const auto pattern = sample_pattern(samples);

  std::vector<Edge> edges;
  int64_t min_x = std::numeric_limits<int64_t>::max(), max_x = std::numeric_limits<int64_t>::min();
  int64_t min_y = min_x, max_y = max_x;
  for (const auto& c : contours) {
    for (size_t i = 0; i < c.size(); ++i) {
      const WindowPoint& p = c[i];
      const WindowPoint& q = c[(i + 1) % c.size()];
      min_x = std::min(min_x, p.fx);
      max_x = std::max(max_x, p.fx);
      min_y = std::min(min_y, p.fy);
      max_y = std::max(max_y, p.fy);
      if (p.fy == q.fy) continue;
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

  const DepthPlane plane = polygon_depth_plane(contours);
  const std::array<float, 4> color = contours.front().front().color;
  const uint32_t tx0 = static_cast<uint32_t>(px0) >> binning::kTileSizeLog2;
  const uint32_t tx1 = static_cast<uint32_t>(px1) >> binning::kTileSizeLog2;
  const uint32_t ty0 = static_cast<uint32_t>(py0) >> binning::kTileSizeLog2;
  const uint32_t ty1 = static_cast<uint32_t>(py1) >> binning::kTileSizeLog2;
  const uint32_t tiles_across = tx1 - tx0 + 1;
  const uint32_t tile_count = tiles_across * (ty1 - ty0 + 1);
  std::vector<Counters> tile_counters(tile_count);

  arena.execute([&] {
    tbb::parallel_for(uint32_t{0}, tile_count, [&](uint32_t t) {
      const int64_t tile_x = int64_t{tx0 + t % tiles_across} * binning::kTileSize;
      const int64_t tile_y = int64_t{ty0 + t / tiles_across} * binning::kTileSize;
      const int64_t x_lo = std::max(px0, tile_x),
                    x_hi = std::min(px1, tile_x + binning::kTileSize - 1);
      const int64_t y_lo = std::max(py0, tile_y),
                    y_hi = std::min(py1, tile_y + binning::kTileSize - 1);
      if (x_lo > x_hi || y_lo > y_hi) return;
      std::array<uint32_t, binning::kTilePixels> masks{};
      std::vector<std::pair<int64_t, int>> events;
      for (uint32_t s = 0; s < samples; ++s) {
        const int64_t offset_x = int64_t{8 + pattern[s].dx} << shift;
        for (int64_t py = y_lo; py <= y_hi; ++py) {
          const int64_t sy = (py * 16 + 8 + pattern[s].dy) << shift;
          events.clear();
          for (const Edge& e : edges) {
            if (!(e.y0 <= sy && sy < e.y1)) continue;
            const int64_t dy = e.y1 - e.y0;
            const int64_t num = e.x0 * dy + (sy - e.y0) * (e.x1 - e.x0);
            events.emplace_back(ceil_div(num - offset_x * dy, one * dy), e.winding);
          }
          std::sort(events.begin(), events.end());
          int winding = 0;
          for (size_t i = 0; i + 1 < events.size(); ++i) {
            winding += events[i].second;
            const bool inside = rule == FillRule::kEvenOdd ? (winding & 1) != 0 : winding != 0;
            if (!inside) continue;
            const int64_t from = std::max(events[i].first, x_lo);
            const int64_t to = std::min(events[i + 1].first - 1, x_hi);
            for (int64_t x = from; x <= to; ++x)
              masks[static_cast<size_t>((py - tile_y) * binning::kTileSize + (x - tile_x))] |= 1u
                                                                                               << s;
          }
        }
      }
      TileWriter writer{fb, pipeline, false, tile_counters[t]};
      for (int64_t py = y_lo; py <= y_hi; ++py) {
        for (int64_t px = x_lo; px <= x_hi; ++px) {
          const uint32_t mask =
              masks[static_cast<size_t>((py - tile_y) * binning::kTileSize + (px - tile_x))];
          if (mask == 0) continue;
          writer.write(px, py,
                       static_cast<float>(
                           plane.at(static_cast<double>(px) + 0.5, static_cast<double>(py) + 0.5)),
                       color, 1.0f, mask, static_cast<float>(plane.zx),
                       static_cast<float>(plane.zy));
        }
      }
    });
  });
  for (const Counters& c : tile_counters) {
    counters.samples_covered += c.samples_covered;
    counters.samples_passed += c.samples_passed;
    counters.pixels_shaded += c.pixels_shaded;
  }
}

}  // namespace tessera::fast
