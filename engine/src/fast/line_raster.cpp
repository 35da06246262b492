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
#include <cstring>
#include <limits>
#include <optional>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "binning/tile_grid.hpp"
#include "binning/tile_lists.hpp"
#include "engine/src/fast/fragment_writer.hpp"
#include "engine/src/fast/line_kernel.hpp"
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

// floor(v) for |v| < 2^63, without a library call.
int64_t floor_to_int(double v) {
  const int64_t t = static_cast<int64_t>(v);  // toward zero
  return t - static_cast<int64_t>(v < static_cast<double>(t));
}

int64_t floor_div(int64_t a, int64_t b) {  // b > 0
  return a >= 0 ? a / b : -((-a + b - 1) / b);
}

// The inner columns of a segment (rows, for a y-major line) as a division stepped exactly:
// column i in [i_lo, i_hi] has its pixel on row base + sign q(i), q and r the floor quotient
// and remainder of num + (i - i_lo) step by den > 0; rows outside
// [j_lo, j_hi] (the box) are not drawn. Pixel (i, j) is (x, y) for x-major lines, else (y, x);
// its stipple counter is |i - start|.
struct ColumnRun {
  int64_t i_lo, i_hi;
  int64_t num, step, den;
  int64_t base, sign;
  int64_t j_lo, j_hi;
  bool x_major;
  int64_t start;
};

// q(i) and r(i) of a run, from column to column: the carry is taken without a branch.
struct DivisionStepper {
  int64_t q, r, step_q, step_r, den;
  explicit DivisionStepper(const ColumnRun& run)
      : q(floor_div(run.num, run.den)),
        r(run.num - q * run.den),
        step_q(floor_div(run.step, run.den)),
        step_r(run.step - step_q * run.den),
        den(run.den) {}
  void next() {
    const int64_t carried = r + step_r, wrapped = carried - den;
    q += step_q + static_cast<int64_t>(wrapped >= 0);
    r = wrapped >= 0 ? wrapped : carried;
  }
};

// Visits the drawn pixels of a run one by one.
template <typename Visit>
void for_each_pixel(const ColumnRun& run, Visit visit) {
  DivisionStepper d(run);
  for (int64_t i = run.i_lo; i <= run.i_hi; ++i, d.next()) {
    const int64_t j = run.base + run.sign * d.q;
    if (j >= run.j_lo && j <= run.j_hi) {
      visit(run.x_major ? i : j, run.x_major ? j : i,
            static_cast<uint32_t>(std::abs(i - run.start)));
    }
  }
}

template <typename Visit, typename VisitRun>
void diamond_exit(const WindowSegment& seg, uint32_t bits, const Box& box, Visit visit,
                  VisitRun visit_run) {
  const int64_t one = int64_t{1} << bits, h = one / 2;
  const int64_t ax = seg.a.fx, ay = seg.a.fy, dx = seg.b.fx - ax, dy = seg.b.fy - ay;
  const bool x_major = std::abs(dx) >= std::abs(dy);
  const int64_t a_major = x_major ? ax : ay, a_minor = x_major ? ay : ax;
  const int64_t d_major = x_major ? dx : dy, d_minor = x_major ? dy : dx;
  const int64_t start = a_major >> bits, end = (a_major + d_major) >> bits;
  // Visit the columns of the box within one of the end pixels.
  const int64_t first = std::min(start, end), last = std::max(start, end);
  const int64_t lo = std::max(x_major ? box.x0 : box.y0, first - 1);
  const int64_t hi = std::min(x_major ? box.x1 : box.y1, last + 1);
  if (lo > hi) return;
  const int64_t minor_lo = x_major ? box.y0 : box.x0, minor_hi = x_major ? box.y1 : box.x1;
  const auto end_column = [&](int64_t i) {
    const double m = static_cast<double>(a_minor) + static_cast<double>(i * one + h - a_major) *
                                                        static_cast<double>(d_minor) /
                                                        static_cast<double>(d_major);
    const int64_t j0 = floor_to_int(m / static_cast<double>(one));
    for (int64_t j = std::max(j0 - 1, minor_lo); j <= std::min(j0 + 1, minor_hi); ++j) {
      const int64_t px = x_major ? i : j, py = x_major ? j : i;
      if (exits_diamond(ax - (px * one + h), ay - (py * one + h), dx, dy, h)) {
        visit(px, py, static_cast<uint32_t>(std::abs(i - start)));
        return;
      }
    }
  };
  // Inner columns: at least two from both end pixels.
  const int64_t inner_lo = std::max(lo, first + 2), inner_hi = std::min(hi, last - 2);
  if (inner_lo > inner_hi) {
    for (int64_t i = lo; i <= hi; ++i)
      end_column(i);
    return;
  }
  for (int64_t i = lo; i < inner_lo; ++i)
    end_column(i);
  // The columns whose crossing can lie in the box's rows, from the line's slope in double,
  // widened by two columns for rounding; the exact row test below decides.
  int64_t run_lo = inner_lo, run_hi = inner_hi;
  if (d_minor != 0) {
    const double slope = static_cast<double>(d_major) / static_cast<double>(d_minor);
    const auto column_at = [&](int64_t row) {  // the column where the line meets `row`
      return (static_cast<double>(row * one - a_minor) * slope + static_cast<double>(a_major - h)) /
             static_cast<double>(one);
    };
    const double c0 = column_at(minor_lo), c1 = column_at(minor_hi + 1);
    run_lo = std::max(run_lo, static_cast<int64_t>(std::floor(std::min(c0, c1))) - 2);
    run_hi = std::min(run_hi, static_cast<int64_t>(std::ceil(std::max(c0, c1))) + 2);
  }
  // Minor coordinate at a column centre c: (a_minor D + (c - a_major) d_minor) / D with
  // D = |d_major| > 0, i.e. the numerator sD (a_minor d_major + (c - a_major) d_minor), sD the
  // sign of d_major; the next column adds sD one d_minor. On a row border (remainder 0) the
  // nudge decides (see the file comment): when it moves the crossing to the upper row, the
  // numerator is one less, which lowers the quotient exactly when the remainder is 0.
  if (run_lo <= run_hi) {
    const int64_t sD = d_major > 0 ? 1 : -1;
    const int64_t tie_to_lower = x_major && d_minor * d_major > 0 ? 1 : 0;
    visit_run(ColumnRun{
        run_lo, run_hi,
        sD * (a_minor * d_major + (run_lo * one + h - a_major) * d_minor) - tie_to_lower,
        sD * d_minor * one, std::abs(d_major) * one, 0, 1, minor_lo, minor_hi, x_major, start});
  }
  for (int64_t i = inner_hi + 1; i <= hi; ++i)
    end_column(i);
}

template <typename VisitRun>
void bresenham(const WindowSegment& seg, uint32_t bits, const Box& box, VisitRun visit_run) {
  int64_t x0 = seg.a.fx >> bits, y0 = seg.a.fy >> bits;
  int64_t x1 = seg.b.fx >> bits, y1 = seg.b.fy >> bits;
  const bool x_major = std::abs(x1 - x0) >= std::abs(y1 - y0);
  const int64_t start_major = x_major ? x0 : y0;
  if (!x_major) std::swap(x0, y0), std::swap(x1, y1);
  if (x0 > x1) std::swap(x0, x1), std::swap(y0, y1);
  const int64_t dx = x1 - x0, ady = std::abs(y1 - y0);
  const int64_t lo = std::max(x0, x_major ? box.x0 : box.y0);
  const int64_t hi = std::min(x1, x_major ? box.x1 : box.y1);
  if (lo > hi) return;
  // Minor steps taken after k = x - x0 major steps: ady k / dx rounded half down, i.e. the
  // floor of (2 ady k + dx - 1) / (2 dx).
  visit_run(ColumnRun{lo, hi, dx == 0 ? 0 : 2 * ady * (lo - x0) + dx - 1, dx == 0 ? 0 : 2 * ady,
                      dx == 0 ? 1 : 2 * dx, y0, y1 >= y0 ? 1 : -1, x_major ? box.y0 : box.x0,
                      x_major ? box.y1 : box.x1, x_major, start_major});
}

// A DDA line's columns [i_lo, i_hi] (rows, for a y-major line): y is the running sum at
// column i_lo, as the lecture's loop reaches it from the start by adding m once per column;
// the pixel is on row floor(y + 1/2), drawn when that is in [j_lo, j_hi].
struct DdaSpan {
  int64_t i_lo, i_hi;
  double y, m;
  int64_t j_lo, j_hi;
  bool x_major;
  int64_t start;
};

template <typename Visit>
void for_each_pixel(const DdaSpan& span, Visit visit) {
  double y = span.y;
  for (int64_t i = span.i_lo; i <= span.i_hi; ++i, y += span.m) {
    const int64_t j = floor_to_int(y + 0.5);
    if (j >= span.j_lo && j <= span.j_hi) {
      visit(span.x_major ? i : j, span.x_major ? j : i,
            static_cast<uint32_t>(std::abs(i - span.start)));
    }
  }
}

template <typename VisitSpan>
void dda(const WindowSegment& seg, uint32_t bits, const Box& box, VisitSpan visit_span) {
  int64_t x0 = seg.a.fx >> bits, y0 = seg.a.fy >> bits;
  int64_t x1 = seg.b.fx >> bits, y1 = seg.b.fy >> bits;
  const bool x_major = std::abs(x1 - x0) >= std::abs(y1 - y0);
  const int64_t start_major = x_major ? x0 : y0;
  if (!x_major) std::swap(x0, y0), std::swap(x1, y1);
  if (x0 > x1) std::swap(x0, x1), std::swap(y0, y1);
  const double m = x1 == x0 ? 0.0 : static_cast<double>(y1 - y0) / static_cast<double>(x1 - x0);
  const int64_t lo = std::max(x0, x_major ? box.x0 : box.y0);
  const int64_t hi = std::min(x1, x_major ? box.x1 : box.y1);
  if (lo > hi) return;
  // The sum is the lecture's: one addition per column from the start, even before the box.
  double y = static_cast<double>(y0);
  for (int64_t x = x0; x < lo; ++x)
    y += m;
  visit_span(DdaSpan{lo, hi, y, m, x_major ? box.y0 : box.x0, x_major ? box.y1 : box.x1, x_major,
                     start_major});
}

// A one-pixel line's pixels in the box by its rule: single pixels (the ends of diamond-exit
// lines) to visit, inner columns as a ColumnRun to visit_run, DDA columns as a DdaSpan.
template <typename Visit, typename VisitRun, typename VisitSpan>
void walk(LineAlgorithm algorithm, const WindowSegment& seg, uint32_t bits, const Box& box,
          Visit visit, VisitRun visit_run, VisitSpan visit_span) {
  switch (algorithm) {
    case LineAlgorithm::kDiamondExit:
      diamond_exit(seg, bits, box, visit, visit_run);
      break;
    case LineAlgorithm::kBresenham:
      bresenham(seg, bits, box, visit_run);
      break;
    case LineAlgorithm::kDDA:
      dda(seg, bits, box, visit_span);
      break;
  }
}

// An antialiased line's rows: for each row of the box, the pixel centres that can lie within
// half the width plus half a pixel of the line (reference_lines.cpp's interval), as
// visit_row(py, x_lo, x_hi); the coverage decides which of them are drawn.
template <typename VisitRow>
void smooth_rows(const WindowSegment& seg, float width, const Box& box, VisitRow visit_row) {
  const double ax = seg.a.x, ay = seg.a.y, dx = seg.b.x - ax, dy = seg.b.y - ay;
  const double length = std::sqrt(dx * dx + dy * dy);
  if (!(length > 0.0)) return;
  const double ux = dx / length, uy = dy / length, half = 0.5 * width;
  const double reach = half + 0.5;  // coverage is 0 at this distance across the line
  // Pixel centres with |(x - ax) uy - (y - ay) ux| < reach: an interval of x when uy != 0,
  // widened by a pixel, which holds every pixel the coverage can draw (the reference's
  // interval, computed with a reciprocal: its rounding is far below the pixel of margin).
  const double inv_uy = uy != 0.0 ? 1.0 / uy : 0.0;
  for (int64_t py = box.y0; py <= box.y1; ++py) {
    int64_t x_lo = box.x0, x_hi = box.x1;
    if (uy != 0.0) {
      const double base = (static_cast<double>(py) + 0.5 - ay) * ux;
      const double e0 = (base - reach) * inv_uy + ax - 0.5, e1 = (base + reach) * inv_uy + ax - 0.5;
      x_lo = std::max(x_lo, floor_to_int(std::min(e0, e1)) - 1);
      x_hi = std::min(x_hi, -floor_to_int(-std::max(e0, e1)) + 1);
    }
    if (x_lo <= x_hi) visit_row(py, x_lo, x_hi);
  }
}

template <typename Visit>
void smooth(const WindowSegment& seg, float width, const Box& box, Visit visit) {
  const double ax = seg.a.x, ay = seg.a.y, dx = seg.b.x - ax, dy = seg.b.y - ay;
  const double length = std::sqrt(dx * dx + dy * dy);
  const double ux = dx / length, uy = dy / length, half = 0.5 * width;
  const double major = std::max(std::abs(dx), std::abs(dy));
  smooth_rows(seg, width, box, [&](int64_t py, int64_t x_lo, int64_t x_hi) {
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
  });
}

// The shading of a segment (line_kernel.hpp), with the reference's operands.
LineShading line_shading(const WindowSegment& seg, const PipelineState& pipeline,
                         const LineState& state) {
  LineShading sh;
  sh.ax = seg.a.x;
  sh.ay = seg.a.y;
  sh.ex = seg.b.x - seg.a.x;
  sh.ey = seg.b.y - seg.a.y;
  const double len2 = sh.ex * sh.ex + sh.ey * sh.ey;
  if (len2 > 0.0) {
    sh.inv_len2 = 1.0 / len2;
  } else {
    sh.ex = sh.ey = 0.0;  // t = 0
  }
  sh.perspective =
      pipeline.interpolation == Interpolation::kPerspective && seg.a.inv_w != seg.b.inv_w;
  if (state.antialiased) {
    // The coverage of smooth() (reference_lines.cpp), per pixel in the kernel.
    const double length = std::sqrt(sh.ex * sh.ex + sh.ey * sh.ey);
    sh.smooth = true;
    sh.length = length;
    sh.ux = sh.ex / length;
    sh.uy = sh.ey / length;
    sh.cover_reach = 0.5 * state.width + 0.5;
  }
  sh.inv_wa = seg.a.inv_w;
  sh.inv_wb = seg.b.inv_w;
  sh.z = seg.a.z;
  sh.dz = seg.b.z - seg.a.z;
  for (int c = 0; c < 4; ++c) {
    sh.color[c] = seg.a.color[c];
    sh.dcolor[c] = seg.b.color[c] - seg.a.color[c];  // in float, as the reference
  }
  return sh;
}

// One-pixel lines with one sample into RGBA8 (or no colour): a tile's pixels of a segment are
// gathered into a run, shaded by the SIMD kernel, and written by a short scalar loop that does
// what TileWriter::write does for them (depth test and write, colour store, counters).
struct RunWriter {
  // A constructor, not aggregate initialization: std::optional::emplace of an aggregate from
  // parentheses needs C++20's P0960, which Clang implements only from version 16.
  RunWriter(detail::FramebufferStorage& storage, const PipelineState& state, LineShadeFn shader,
            Counters& tile_counters)
      : fb(storage), pipeline(state), shade(shader), counters(tile_counters) {}

  detail::FramebufferStorage& fb;
  const PipelineState& pipeline;
  LineShadeFn shade;
  Counters& counters;
  alignas(64) int32_t x[kLineRunCapacity] = {};
  alignas(64) int32_t y[kLineRunCapacity] = {};
  alignas(64) uint32_t rgba[kLineRunCapacity];
  alignas(64) float depth[kLineRunCapacity];
  alignas(64) uint32_t offset[kLineRunCapacity];
  alignas(64) float coverage[kLineRunCapacity];

  static bool applies(const detail::FramebufferStorage& fb, const PipelineState& pipeline,
                      const LineState& state) {
    return fb.desc.samples == 1 &&
           (fb.desc.color_format == ColorFormat::kRGBA8 || !pipeline.color_write) &&
           !(state.antialiased && state.stipple.pattern != 0xFFFF) &&
           (pipeline.blend[0].replaces() || !pipeline.color_write) && !pipeline.scissor_test;
  }

  // Shades and writes pixels 0 .. n - 1 of the run.
  void flush(const LineShading& sh, size_t n) {
    if (n == 0) return;
    uint8_t* colour = fb.rgba8.data();
    const bool write_colour = pipeline.color_write;
    // Without colour writes an RGBA32F target has no 8-bit colour (applies()): none is read.
    shade(sh, x, y, n,
          LineRunOut{rgba, depth, offset, coverage,
                     write_colour ? reinterpret_cast<const uint32_t*>(colour) : nullptr,
                     fb.grid.tiles_x});
    if (!pipeline.depth_test && !sh.smooth) {
      if (write_colour) {
        for (size_t i = 0; i < n; ++i)
          std::memcpy(colour + size_t{offset[i]} * 4, &rgba[i], 4);
        counters.pixels_shaded += n;
      }
      counters.samples_covered += n;
      counters.samples_passed += n;
      return;
    }
    const double depth_scale = detail::depth_scale(fb.desc.depth_format);
    uint64_t covered = 0, passed = 0;
    for (size_t i = 0; i < n; ++i) {
      if (sh.smooth && !(coverage[i] > 0.0f)) continue;
      ++covered;
      const size_t index = offset[i];
      if (pipeline.depth_test) {
        // The one sample sits at the pixel centre: depth + 0 (offsets) as TileWriter forms it.
        const float z = detail::encode_depth(std::clamp(depth[i] + 0.0f, 0.0f, 1.0f), depth_scale);
        if (!detail::depth_passes(pipeline.depth_compare, z, fb.depth[index])) continue;
        if (pipeline.depth_write) {
          fb.depth[index] = z;
          if (fb.hiz_valid) {
            // The block's Hi-Z bounds are stale: mark them for recomputation (block_kernel.cpp).
            const size_t block = index / detail::kBlockPixels;  // tile * 64 + block in tile
            fb.hiz_min[block] = std::numeric_limits<float>::infinity();
            fb.hiz_max[block] = -std::numeric_limits<float>::infinity();
          }
        }
      }
      ++passed;
      if (write_colour) std::memcpy(colour + index * 4, &rgba[i], 4);
    }
    counters.samples_covered += covered;
    counters.samples_passed += passed;
    if (write_colour) counters.pixels_shaded += passed;
  }
};

void raster_segment(const LineSetup& setup, const Box& tile, const PipelineState& pipeline,
                    const LineState& state, TileWriter& out, RunWriter* runs) {
  const WindowSegment& seg = setup.seg;
  const Box box = setup.box.intersect(tile);
  if (box.empty()) return;
  const uint32_t bits = pipeline.subpixel_bits;
  const bool stippled = state.stipple.pattern != 0xFFFF;
  const auto stipple_on = [&](uint32_t s) {
    const uint32_t n = seg.stipple_base + s;
    return ((state.stipple.pattern >> ((n / state.stipple.factor) % 16)) & 1u) != 0;
  };
  if (runs != nullptr) {
    const LineShading sh = line_shading(seg, pipeline, state);
    int32_t* xs = runs->x;
    int32_t* ys = runs->y;
    size_t n = 0;  // pixels in the run (a local, so the walk keeps it in a register)
    if (state.antialiased) {
      // Every pixel centre of a row's interval: the kernel computes the coverage and the
      // writes skip the pixels it leaves uncovered.
      smooth_rows(seg, state.width, box, [&](int64_t py, int64_t x_lo, int64_t x_hi) {
        for (int64_t px = x_lo; px <= x_hi; ++px) {
          xs[n] = static_cast<int32_t>(px);
          ys[n] = static_cast<int32_t>(py);
          if (++n >= kLineRunPixels) {
            runs->flush(sh, n);
            n = 0;
          }
        }
      });
      runs->flush(sh, n);
      return;
    }
    auto visit = [&](int64_t px, int64_t py, uint32_t s) {
      if (stippled && !stipple_on(s)) return;
      xs[n] = static_cast<int32_t>(px);
      ys[n] = static_cast<int32_t>(py);
      if (++n >= kLineRunPixels) {
        runs->flush(sh, n);
        n = 0;
      }
    };
    // Appends pixel (i, row) of every column i in [i_lo, i_hi] whose row is in [j_lo, j_hi],
    // without a branch (a column's entry is written and kept or overwritten), in chunks that
    // fit the run arrays; next_row() gives the column's row and moves to the next column.
    auto append_columns = [&](bool x_major, int64_t i_lo, int64_t i_hi, int64_t j_lo, int64_t j_hi,
                              auto next_row) {
      int32_t* major = x_major ? xs : ys;
      int32_t* minor = x_major ? ys : xs;
      const uint64_t j_span = static_cast<uint64_t>(j_hi - j_lo);
      size_t count = n;  // in a register for the loop
      for (int64_t i = i_lo; i <= i_hi;) {
        if (count >= kLineRunPixels) {
          runs->flush(sh, count);
          count = 0;
        }
        const int64_t chunk_end = std::min(i_hi, i + int64_t{kLineRunPixels} - 1);
        for (; i <= chunk_end; ++i) {
          const int64_t j = next_row();
          major[count] = static_cast<int32_t>(i);
          minor[count] = static_cast<int32_t>(j);
          count += static_cast<size_t>(static_cast<uint64_t>(j - j_lo) <= j_span);
        }
      }
      n = count;
    };
    auto visit_run = [&](const ColumnRun& run) {
      if (stippled) {
        for_each_pixel(run, visit);
        return;
      }
      // The row jq = base + sign q steps by sign (step_q + carry). The carry follows the
      // slope's fraction, which a predictor learns poorly: selects, not a branch.
      const DivisionStepper d(run);
      int64_t jq = run.base + run.sign * d.q, r = d.r;
      const int64_t jq_step = run.sign * d.step_q, jq_carry = jq_step + run.sign;
      const int64_t r_step = d.step_r, r_wrap = d.step_r - d.den;
      append_columns(run.x_major, run.i_lo, run.i_hi, run.j_lo, run.j_hi, [&] {
        const int64_t j = jq;
        const int64_t carried = r + r_step, wrapped = r + r_wrap;
        const bool carry = __builtin_expect_with_probability(wrapped >= 0, 1, 0.5);
        jq += carry ? jq_carry : jq_step;
        r = carry ? wrapped : carried;
        return j;
      });
    };
    auto visit_span = [&](const DdaSpan& span) {
      if (stippled) {
        for_each_pixel(span, visit);
        return;
      }
      double y = span.y;
      append_columns(span.x_major, span.i_lo, span.i_hi, span.j_lo, span.j_hi, [&] {
        const int64_t j = floor_to_int(y + 0.5);
        y += span.m;
        return j;
      });
    };
    walk(state.algorithm, seg, bits, box, visit, visit_run, visit_span);
    runs->flush(sh, n);
    return;
  }
  const double ex = seg.b.x - seg.a.x, ey = seg.b.y - seg.a.y;
  const double len2 = ex * ex + ey * ey;
  const double inv_len2 = len2 > 0.0 ? 1.0 / len2 : 0.0;  // t = projection * inv_len2
  auto shade = [&](int64_t px, int64_t py, uint32_t s, float coverage) {
    if (stippled && !stipple_on(s)) return;
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
  if (state.antialiased) {
    smooth(seg, state.width, box,
           [&](int64_t x, int64_t y, uint32_t s, float c) { shade(x, y, s, c); });
    return;
  }
  auto visit = [&](int64_t x, int64_t y, uint32_t s) { shade(x, y, s, 1.0f); };
  walk(
      state.algorithm, seg, bits, box, visit,
      [&](const ColumnRun& run) { for_each_pixel(run, visit); },
      [&](const DdaSpan& span) { for_each_pixel(span, visit); });
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

// The band of pixels within `margin` of a segment's line, for choosing the tiles to reference:
// a tile is near when the line's edge function takes a value within `reach` somewhere on the
// tile grown by a pixel and a half (its extremes lie at two corners).
struct Band {
  double ax, ay, dx, dy, reach;
  Band(const WindowSegment& seg, double margin)
      : ax(seg.a.x),
        ay(seg.a.y),
        dx(seg.b.x - seg.a.x),
        dy(seg.b.y - seg.a.y),
        reach(margin * std::sqrt(dx * dx + dy * dy)) {}
  // Whether tile pixels [x0, x0 + size - 1] x [y0, y0 + size - 1] can hold pixels of the band.
  bool near(double x0, double y0, double size) const {
    const double e = (x0 - 1.0 - ax) * dy - (y0 - 1.0 - ay) * dx;  // at the grown corner
    const double ex = (size + 2.0) * dy, ey = -(size + 2.0) * dx;  // across the grown tile
    const double lo = e + std::min(ex, 0.0) + std::min(ey, 0.0);
    const double hi = e + std::max(ex, 0.0) + std::max(ey, 0.0);
    return lo <= reach && hi >= -reach;
  }
};

}  // namespace

// One worker's range of a draw: its segments' setups and their tile lists.
struct LineScratch::Chunk {
  std::vector<LineSetup> setups;
  binning::TileLists bins;
};

namespace {

// Lines are binned to tiles of 128 x 128 pixels (four storage tiles): a segment's pixels in a
// tile then make runs twice as long, and each segment is set up in half as many tiles, as with
// the storage tiles' 64 pixels.
constexpr uint32_t kLineTileLog2 = 7, kLineTile = 1u << kLineTileLog2;

// Segments per chunk below which splitting the setup does not pay.
constexpr size_t kMinChunkSegments = 2048;

}  // namespace

LineScratch::LineScratch() = default;
LineScratch::~LineScratch() = default;
LineScratch::LineScratch(LineScratch&&) noexcept = default;
LineScratch& LineScratch::operator=(LineScratch&&) noexcept = default;

void draw_thin_lines(tbb::task_arena& arena, int64_t simd_target, LineScratch& scratch,
                     detail::FramebufferStorage& fb, const PipelineState& pipeline,
                     const LineState& state, std::span<const WindowSegment> segments,
                     Counters& counters) {
  if (segments.empty()) return;
  const auto bin_grid = binning::TileGrid::for_size(fb.desc.width, fb.desc.height, kLineTileLog2);
  const uint32_t threads = static_cast<uint32_t>(arena.max_concurrency());
  const size_t chunk_count = std::clamp<size_t>(segments.size() / kMinChunkSegments, 1,
                                                threads <= 1 ? 1 : size_t{4} * threads);
  std::vector<LineScratch::Chunk>& chunks = scratch.chunks;
  if (chunks.size() < chunk_count) chunks.resize(chunk_count);
  const double margin = 2.0 + 0.5 * state.width;
  const bool use_runs = RunWriter::applies(fb, pipeline, state);
  const LineShadeFn shade = line_shade_kernel(simd_target);

  arena.execute([&] {
    tbb::parallel_for(size_t{0}, chunk_count, [&](size_t c) {
      LineScratch::Chunk& chunk = chunks[c];
      chunk.bins.reset(bin_grid.tile_count());
      const size_t begin = segments.size() * c / chunk_count;
      const size_t end = segments.size() * (c + 1) / chunk_count;
      chunk.setups.clear();
      chunk.setups.reserve(end - begin);
      for (size_t i = begin; i < end; ++i) {
        LineSetup setup;
        if (!setup_segment(segments[i], state, fb.desc.width, fb.desc.height, setup)) continue;
        const uint32_t index = static_cast<uint32_t>(chunk.setups.size());
        chunk.setups.push_back(setup);
        const Box& b = setup.box;
        const uint32_t tx0 = static_cast<uint32_t>(b.x0) >> kLineTileLog2;
        const uint32_t tx1 = static_cast<uint32_t>(b.x1) >> kLineTileLog2;
        const uint32_t ty0 = static_cast<uint32_t>(b.y0) >> kLineTileLog2;
        const uint32_t ty1 = static_cast<uint32_t>(b.y1) >> kLineTileLog2;
        if (tx0 == tx1 || ty0 == ty1) {
          for (uint32_t ty = ty0; ty <= ty1; ++ty) {
            for (uint32_t tx = tx0; tx <= tx1; ++tx)
              chunk.bins.add(ty * bin_grid.tiles_x + tx, index);
          }
          continue;
        }
        const Band band(setup.seg, margin);
        for (uint32_t ty = ty0; ty <= ty1; ++ty) {
          for (uint32_t tx = tx0; tx <= tx1; ++tx) {
            if (band.near(tx * double{kLineTile}, ty * double{kLineTile}, double{kLineTile})) {
              chunk.bins.add(ty * bin_grid.tiles_x + tx, index);
            }
          }
        }
      }
    });
  });

  std::vector<Counters> tile_counters(bin_grid.tile_count());
  arena.execute([&] {
    tbb::parallel_for(tbb::blocked_range<uint32_t>(0, bin_grid.tile_count(), 1),
                      [&](const tbb::blocked_range<uint32_t>& r) {
                        for (uint32_t tile = r.begin(); tile != r.end(); ++tile) {
                          const int64_t x0 = bin_grid.tile_x0(tile);
                          const int64_t y0 = bin_grid.tile_y0(tile);
                          const Box tile_box{x0, y0, x0 + kLineTile - 1, y0 + kLineTile - 1};
                          TileWriter writer{fb, pipeline, state.antialiased, tile_counters[tile]};
                          std::optional<RunWriter> runs;
                          if (use_runs) {
                            runs.emplace(fb, pipeline, shade, tile_counters[tile]);
                          }
                          for (size_t c = 0; c < chunk_count; ++c) {
                            const LineScratch::Chunk& chunk = chunks[c];
                            const std::span<const uint32_t> list = chunk.bins.tile(tile);
                            for (size_t n = 0; n < list.size(); ++n) {
                              if (n + 4 < list.size()) {
                                const char* ahead =
                                    reinterpret_cast<const char*>(&chunk.setups[list[n + 4]]);
                                for (size_t line = 0; line < sizeof(LineSetup); line += 64)
                                  __builtin_prefetch(ahead + line);
                              }
                              raster_segment(chunk.setups[list[n]], tile_box, pipeline, state,
                                             writer, runs ? &*runs : nullptr);
                            }
                          }
                        }
                      });
  });
  for (size_t c = 0; c < chunk_count; ++c)
    counters.bin_references += chunks[c].bins.references();
  ++counters.bin_passes;
  for (const Counters& c : tile_counters) {
    counters.samples_covered += c.samples_covered;
    counters.samples_passed += c.samples_passed;
    counters.pixels_shaded += c.pixels_shaded;
  }
}

}  // namespace tessera::fast
