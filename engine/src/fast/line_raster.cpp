// Binned, tile-parallel lines for the fast engine (line_raster.hpp). Each segment is set up
// once: rejected by Cohen-Sutherland outcodes against the grown viewport, its pixel box
// narrowed to the part inside, and referenced from every tile near it. A tile then visits
// only its own columns (rows for y-major lines) of each segment:
//  - diamond exit: a column at least two pixels from both end pixels is crossed at its centre
//    strictly inside the segment, so its pixel is the row whose diamond holds the crossing,
//    found by one exact integer division (a crossing on a row border goes where the (e, e^2)
//    nudge moves it: the upper row when the line falls to the right, else the lower); only
//    the columns at the ends need the full diamond test (OpenGL 4.6 section 14.5.1);
//  - midpoint: the closed form of Bresenham's decision variable, y_k = round-half-down of
//    y0 + k dy / dx, so any column is found without stepping from the start;
//  - DDA: the slope is accumulated from the start exactly as the lecture's loop does (the
//    floating-point sum is what defines its pixels), skipping the writes outside the tile.
// Pixels, stipple counters, depth and colours are computed with the same formulas as the
// reference rasterizer, so the bytes written are the same; tests check it on every target.
#include "engine/src/fast/line_raster.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "binning/tile_lists.hpp"
#include "engine/src/fast/fragment_writer.hpp"
#include "engine/src/sample_positions.hpp"

namespace tessera::fast {

namespace {

struct Box {
  int64_t x0, y0, x1, y1;  // pixels, inclusive
  bool contains(int64_t x, int64_t y) const { return x >= x0 && x <= x1 && y >= y0 && y <= y1; }
  Box intersect(const Box& o) const {
    return {std::max(x0, o.x0), std::max(y0, o.y0), std::min(x1, o.x1), std::min(y1, o.y1)};
  }
  bool empty() const { return x0 > x1 || y0 > y1; }
};

// A segment as the tiles read it: a copy, so that a tile's pass over its list reads one
// contiguous record per segment (the records are fetched a few ahead, see draw_thin_lines).
struct LineSetup {
  WindowSegment seg;
  Box box;  // the pixels worth visiting, on screen
};

// ---- Diamond exit at the ends of a segment (symbolic perturbation, as in the reference) ----

struct Poly {
  int64_t c0, c1, c2;
};
int sign(const Poly& p) {
  if (p.c0 != 0) return p.c0 > 0 ? 1 : -1;
  if (p.c1 != 0) return p.c1 > 0 ? 1 : -1;
  return p.c2 > 0 ? 1 : (p.c2 < 0 ? -1 : 0);
}
bool in_diamond(int64_t u, int64_t v, int64_t h) {
  const int64_t su = u >= 0 ? 1 : -1, sv = v >= 0 ? 1 : -1;
  return sign({h - su * u - sv * v, -su, -sv}) > 0;
}
bool exits_diamond(int64_t ua, int64_t va, int64_t du, int64_t dv, int64_t h) {
  if (in_diamond(ua + du, va + dv, h)) return false;
  if (in_diamond(ua, va, h)) return true;
  if (du != 0) {
    const int64_t s = du > 0 ? 1 : -1;
    if (sign({-s * ua, -s, 0}) >= 0 && sign({std::abs(du) + s * ua, s, 0}) >= 0) {
      const Poly n{va * du - dv * ua, -dv, du};
      const int64_t sn = sign(n);
      if (sign({h * std::abs(du) - sn * n.c0, sn * dv, -sn * du}) > 0) return true;
    }
  }
  if (dv != 0) {
    const int64_t s = dv > 0 ? 1 : -1;
    if (sign({-s * va, 0, -s}) >= 0 && sign({std::abs(dv) + s * va, 0, s}) >= 0) {
      const Poly m{ua * dv - du * va, dv, -du};
      const int64_t sm = sign(m);
      if (sign({h * std::abs(dv) - sm * m.c0, -sm * dv, sm * du}) > 0) return true;
    }
  }
  return false;
}

int64_t floor_div(int64_t a, int64_t b) {  // b > 0
  return a >= 0 ? a / b : -((-a + b - 1) / b);
}

template <typename Visit>
void diamond_exit(const WindowSegment& seg, uint32_t bits, const Box& box, Visit visit) {
  const int64_t one = int64_t{1} << bits, h = one / 2;
  const int64_t ax = seg.a.fx, ay = seg.a.fy, dx = seg.b.fx - ax, dy = seg.b.fy - ay;
  const bool x_major = std::abs(dx) >= std::abs(dy);
  const int64_t a_major = x_major ? ax : ay, a_minor = x_major ? ay : ax;
  const int64_t d_major = x_major ? dx : dy, d_minor = x_major ? dy : dx;
  const int64_t dir = d_major > 0 ? 1 : -1;
  const int64_t start = a_major >> bits, end = (a_major + d_major) >> bits;
  // Visit the columns of the box in the direction of travel, within one of the end pixels.
  const int64_t lo = std::max(x_major ? box.x0 : box.y0, std::min(start, end) - 1);
  const int64_t hi = std::min(x_major ? box.x1 : box.y1, std::max(start, end) + 1);
  if (lo > hi) return;
  const int64_t minor_lo = x_major ? box.y0 : box.x0, minor_hi = x_major ? box.y1 : box.x1;
  // Minor coordinate at a column centre: (a_minor D + (c - a_major) d_minor) / D, D > 0.
  const int64_t D = std::abs(d_major), sD = dir;  // sD * d_major = D > 0
  const bool tie_to_lower = x_major && d_minor * d_major > 0;
  // Inner columns step the division exactly: a column further along the line (dir) adds
  // sD * dir * one * d_minor = one * d_minor to the numerator, carried into the quotient q and
  // the remainder r (0 <= r < D one).
  const int64_t denominator = D * one, step = d_minor * one;
  const int64_t step_q = floor_div(step, denominator), step_r = step - step_q * denominator;
  bool stepping = false;
  int64_t q = 0, r = 0;
  for (int64_t i = dir > 0 ? lo : hi; dir > 0 ? i <= hi : i >= lo; i += dir) {
    const uint32_t s = static_cast<uint32_t>(std::abs(i - start));
    if (std::abs(i - start) >= 2 && std::abs(i - end) >= 2) {
      if (!stepping) {
        const int64_t c = i * one + h;
        const int64_t num = sD * (a_minor * d_major + (c - a_major) * d_minor);
        q = floor_div(num, denominator);
        r = num - q * denominator;
        stepping = true;
      } else {
        q += step_q;
        r += step_r;
        if (r >= denominator) r -= denominator, ++q;
      }
      // On a row border (r == 0) the nudge decides (see the file comment).
      const int64_t j = tie_to_lower && r == 0 ? q - 1 : q;
      if (j < minor_lo || j > minor_hi) continue;
      visit(x_major ? i : j, x_major ? j : i, s);
      continue;
    }
    stepping = false;
    const double m = static_cast<double>(a_minor) + static_cast<double>(i * one + h - a_major) *
                                                        static_cast<double>(d_minor) /
                                                        static_cast<double>(d_major);
    const int64_t j0 = static_cast<int64_t>(std::floor(m / static_cast<double>(one)));
    for (int64_t j = std::max(j0 - 1, minor_lo); j <= std::min(j0 + 1, minor_hi); ++j) {
      const int64_t px = x_major ? i : j, py = x_major ? j : i;
      if (exits_diamond(ax - (px * one + h), ay - (py * one + h), dx, dy, h)) {
        visit(px, py, s);
        break;
      }
    }
  }
}

template <typename Visit>
void bresenham(const WindowSegment& seg, uint32_t bits, const Box& box, Visit visit) {
  int64_t x0 = seg.a.fx >> bits, y0 = seg.a.fy >> bits;
  int64_t x1 = seg.b.fx >> bits, y1 = seg.b.fy >> bits;
  const bool x_major = std::abs(x1 - x0) >= std::abs(y1 - y0);
  const int64_t start_major = x_major ? x0 : y0;
  if (!x_major) std::swap(x0, y0), std::swap(x1, y1);
  if (x0 > x1) std::swap(x0, x1), std::swap(y0, y1);
  const int64_t dx = x1 - x0, ady = std::abs(y1 - y0), step = y1 >= y0 ? 1 : -1;
  const int64_t lo = std::max(x0, x_major ? box.x0 : box.y0);
  const int64_t hi = std::min(x1, x_major ? box.x1 : box.y1);
  for (int64_t x = lo; x <= hi; ++x) {
    // Minor steps taken after k major steps: ady k / dx rounded half down.
    const int64_t k = x - x0;
    const int64_t y = dx == 0 ? y0 : y0 + step * ((2 * ady * k + dx - 1) / (2 * dx));
    const int64_t px = x_major ? x : y, py = x_major ? y : x;
    if (box.contains(px, py)) visit(px, py, static_cast<uint32_t>(std::abs(x - start_major)));
  }
}

template <typename Visit>
void dda(const WindowSegment& seg, uint32_t bits, const Box& box, Visit visit) {
  int64_t x0 = seg.a.fx >> bits, y0 = seg.a.fy >> bits;
  int64_t x1 = seg.b.fx >> bits, y1 = seg.b.fy >> bits;
  const bool x_major = std::abs(x1 - x0) >= std::abs(y1 - y0);
  const int64_t start_major = x_major ? x0 : y0;
  if (!x_major) std::swap(x0, y0), std::swap(x1, y1);
  if (x0 > x1) std::swap(x0, x1), std::swap(y0, y1);
  const double m = x1 == x0 ? 0.0 : static_cast<double>(y1 - y0) / static_cast<double>(x1 - x0);
  const int64_t lo = x_major ? box.x0 : box.y0, hi = std::min(x1, x_major ? box.x1 : box.y1);
  double y = static_cast<double>(y0);
  for (int64_t x = x0; x <= hi; ++x, y += m) {
    if (x < lo) continue;
    const int64_t r = static_cast<int64_t>(std::floor(y + 0.5));
    const int64_t px = x_major ? x : r, py = x_major ? r : x;
    if (box.contains(px, py)) visit(px, py, static_cast<uint32_t>(std::abs(x - start_major)));
  }
}

template <typename Visit>
void smooth(const WindowSegment& seg, float width, const Box& box, Visit visit) {
  const double ax = seg.a.x, ay = seg.a.y, dx = seg.b.x - ax, dy = seg.b.y - ay;
  const double length = std::sqrt(dx * dx + dy * dy);
  if (!(length > 0.0)) return;
  const double ux = dx / length, uy = dy / length, half = 0.5 * width;
  const double major = std::max(std::abs(dx), std::abs(dy));
  const double reach = half + 0.5;  // coverage is 0 at this distance across the line
  for (int64_t py = box.y0; py <= box.y1; ++py) {
    // Pixel centres with |(x - ax) uy - (y - ay) ux| < reach: an interval of x when uy != 0,
    // widened by a pixel so that rounding never drops one; the coverage below decides.
    int64_t x_lo = box.x0, x_hi = box.x1;
    if (uy != 0.0) {
      const double base = (static_cast<double>(py) + 0.5 - ay) * ux;
      const double e0 = (base - reach) / uy + ax - 0.5, e1 = (base + reach) / uy + ax - 0.5;
      x_lo = std::max(x_lo, static_cast<int64_t>(std::floor(std::min(e0, e1))) - 1);
      x_hi = std::min(x_hi, static_cast<int64_t>(std::ceil(std::max(e0, e1))) + 1);
    }
    for (int64_t px = x_lo; px <= x_hi; ++px) {
      const double qx = static_cast<double>(px) + 0.5 - ax, qy = static_cast<double>(py) + 0.5 - ay;
      const double along = qx * ux + qy * uy;
      const double across = std::abs(qx * uy - qy * ux);
      const double c_across = std::clamp(half + 0.5 - across, 0.0, 1.0);
      const double c_along = std::clamp(std::min(along, length - along) + 0.5, 0.0, 1.0);
      const double coverage = c_across * c_along;
      if (coverage <= 0.0) continue;
      const double t = std::clamp(along / length, 0.0, 1.0);
      visit(px, py, static_cast<uint32_t>(std::floor(t * major)), static_cast<float>(coverage));
    }
  }
}

void raster_segment(const LineSetup& setup, const Box& tile, const PipelineState& pipeline,
                    const LineState& state, TileWriter& out) {
  const WindowSegment& seg = setup.seg;
  const Box box = setup.box.intersect(tile);
  if (box.empty()) return;
  const double ex = seg.b.x - seg.a.x, ey = seg.b.y - seg.a.y;
  const double len2 = ex * ex + ey * ey;
  const double inv_len2 = len2 > 0.0 ? 1.0 / len2 : 0.0;  // t = projection * inv_len2
  auto shade = [&](int64_t px, int64_t py, uint32_t s, float coverage) {
    if (state.stipple.pattern != 0xFFFF) {
      const uint32_t n = seg.stipple_base + s;
      if (!((state.stipple.pattern >> ((n / state.stipple.factor) % 16)) & 1u)) return;
    }
    double t = 0.0;
    if (len2 > 0.0) {
      t = std::clamp(((static_cast<double>(px) + 0.5 - seg.a.x) * ex +
                      (static_cast<double>(py) + 0.5 - seg.a.y) * ey) *
                         inv_len2,
                     0.0, 1.0);
    }
    double tc = t;
    if (pipeline.interpolation == Interpolation::kPerspective && seg.a.inv_w != seg.b.inv_w) {
      const double qa = (1.0 - t) * seg.a.inv_w, qb = t * seg.b.inv_w;
      tc = qa + qb > 0.0 ? qb / (qa + qb) : t;
    }
    std::array<float, 4> color;
    for (int c = 0; c < 4; ++c)
      color[c] = static_cast<float>(seg.a.color[c] + tc * (seg.b.color[c] - seg.a.color[c]));
    out.write(px, py, static_cast<float>(seg.a.z + t * (seg.b.z - seg.a.z)), color, coverage);
  };
  const uint32_t bits = pipeline.subpixel_bits;
  if (state.antialiased) {
    smooth(seg, state.width, box,
           [&](int64_t x, int64_t y, uint32_t s, float c) { shade(x, y, s, c); });
    return;
  }
  auto visit = [&](int64_t x, int64_t y, uint32_t s) { shade(x, y, s, 1.0f); };
  switch (state.algorithm) {
    case LineAlgorithm::kDiamondExit:
      diamond_exit(seg, bits, box, visit);
      break;
    case LineAlgorithm::kBresenham:
      bresenham(seg, bits, box, visit);
      break;
    case LineAlgorithm::kDDA:
      dda(seg, bits, box, visit);
      break;
  }
}

// Cohen-Sutherland against the viewport grown by the line's reach (line_clip.hpp); false when
// the segment cannot touch the screen. Same box as the reference visits.
bool setup_segment(const WindowSegment& seg, const LineState& state, uint32_t width,
                   uint32_t height, LineSetup& out) {
  if (seg.a.fx == seg.b.fx && seg.a.fy == seg.b.fy) return false;
  const double margin = 2.0 + 0.5 * state.width;
  double t0 = 0, t1 = 1;
  if (!cohen_sutherland(seg.a.x, seg.a.y, seg.b.x, seg.b.y, -margin, -margin, width + margin,
                        height + margin, t0, t1)) {
    return false;
  }
  const double ex = seg.b.x - seg.a.x, ey = seg.b.y - seg.a.y;
  const double cx0 = seg.a.x + t0 * ex, cx1 = seg.a.x + t1 * ex;
  const double cy0 = seg.a.y + t0 * ey, cy1 = seg.a.y + t1 * ey;
  out.seg = seg;
  out.box = Box{static_cast<int64_t>(std::floor(std::min(cx0, cx1) - margin)),
                static_cast<int64_t>(std::floor(std::min(cy0, cy1) - margin)),
                static_cast<int64_t>(std::floor(std::max(cx0, cx1) + margin)),
                static_cast<int64_t>(std::floor(std::max(cy0, cy1) + margin))}
                .intersect({0, 0, int64_t{width} - 1, int64_t{height} - 1});
  return !out.box.empty();
}

// Whether a tile (pixels [x0, x1] x [y0, y1]) can hold pixels within `margin` of the line.
bool near_line(const WindowSegment& seg, double margin, double x0, double y0, double x1,
               double y1) {
  const double dx = seg.b.x - seg.a.x, dy = seg.b.y - seg.a.y;
  const double length = std::sqrt(dx * dx + dy * dy);
  const double reach = margin * length;
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (double x : {x0 - 1.0, x1 + 2.0}) {
    for (double y : {y0 - 1.0, y1 + 2.0}) {
      const double e = (x - seg.a.x) * dy - (y - seg.a.y) * dx;
      lo = std::min(lo, e);
      hi = std::max(hi, e);
    }
  }
  return lo <= reach && hi >= -reach;
}

struct Chunk {
  std::vector<LineSetup> setups;
  binning::TileLists bins;
};

// Segments per chunk below which splitting the setup does not pay.
constexpr size_t kMinChunkSegments = 2048;

}  // namespace

void draw_thin_lines(tbb::task_arena& arena, detail::FramebufferStorage& fb,
                     const PipelineState& pipeline, const LineState& state,
                     std::span<const WindowSegment> segments, Counters& counters) {
  if (segments.empty()) return;
  const binning::TileGrid& grid = fb.grid;
  const uint32_t threads = static_cast<uint32_t>(arena.max_concurrency());
  const size_t chunk_count = std::clamp<size_t>(segments.size() / kMinChunkSegments, 1,
                                                threads <= 1 ? 1 : size_t{4} * threads);
  std::vector<Chunk> chunks(chunk_count);
  const double margin = 2.0 + 0.5 * state.width;

  arena.execute([&] {
    tbb::parallel_for(size_t{0}, chunk_count, [&](size_t c) {
      Chunk& chunk = chunks[c];
      chunk.bins.reset(grid.tile_count());
      const size_t begin = segments.size() * c / chunk_count;
      const size_t end = segments.size() * (c + 1) / chunk_count;
      for (size_t i = begin; i < end; ++i) {
        LineSetup setup;
        if (!setup_segment(segments[i], state, fb.desc.width, fb.desc.height, setup)) continue;
        const uint32_t index = static_cast<uint32_t>(chunk.setups.size());
        chunk.setups.push_back(setup);
        const Box& b = setup.box;
        const uint32_t tx0 = static_cast<uint32_t>(b.x0) >> binning::kTileSizeLog2;
        const uint32_t tx1 = static_cast<uint32_t>(b.x1) >> binning::kTileSizeLog2;
        const uint32_t ty0 = static_cast<uint32_t>(b.y0) >> binning::kTileSizeLog2;
        const uint32_t ty1 = static_cast<uint32_t>(b.y1) >> binning::kTileSizeLog2;
        for (uint32_t ty = ty0; ty <= ty1; ++ty) {
          for (uint32_t tx = tx0; tx <= tx1; ++tx) {
            const double x0 = tx * double{binning::kTileSize}, y0 = ty * double{binning::kTileSize};
            if (tx0 != tx1 && ty0 != ty1 && !state.antialiased &&
                !near_line(setup.seg, margin, x0, y0, x0 + binning::kTileSize - 1,
                           y0 + binning::kTileSize - 1)) {
              continue;
            }
            chunk.bins.add(ty * grid.tiles_x + tx, index);
          }
        }
      }
    });
  });

  std::vector<Counters> tile_counters(grid.tile_count());
  arena.execute([&] {
    tbb::parallel_for(
        tbb::blocked_range<uint32_t>(0, grid.tile_count(), 1),
        [&](const tbb::blocked_range<uint32_t>& r) {
          for (uint32_t tile = r.begin(); tile != r.end(); ++tile) {
            const int64_t x0 = int64_t{tile % grid.tiles_x} * binning::kTileSize;
            const int64_t y0 = int64_t{tile / grid.tiles_x} * binning::kTileSize;
            const Box tile_box{x0, y0, x0 + binning::kTileSize - 1, y0 + binning::kTileSize - 1};
            TileWriter writer{fb, pipeline, state.antialiased, tile_counters[tile]};
            for (const Chunk& chunk : chunks) {
              const std::span<const uint32_t> list = chunk.bins.tile(tile);
              for (size_t n = 0; n < list.size(); ++n) {
                if (n + 4 < list.size()) {
                  const char* ahead = reinterpret_cast<const char*>(&chunk.setups[list[n + 4]]);
                  for (size_t line = 0; line < sizeof(LineSetup); line += 64)
                    __builtin_prefetch(ahead + line);
                }
                raster_segment(chunk.setups[list[n]], tile_box, pipeline, state, writer);
              }
            }
          }
        });
  });
  for (const Chunk& chunk : chunks)
    counters.bin_references += chunk.bins.references();
  ++counters.bin_passes;
  for (const Counters& c : tile_counters) {
    counters.samples_covered += c.samples_covered;
    counters.samples_passed += c.samples_passed;
    counters.pixels_shaded += c.pixels_shaded;
  }
}

}  // namespace tessera::fast
