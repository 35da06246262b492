// Square points, wide-line rectangles, dashes and joins as triangles (primitive_triangles.hpp).
// Joins follow the SVG stroke model (miter with a miter limit, round, bevel); the stipple cuts
// the rectangle at whole major-axis pixels, as glLineStipple counts fragments.
#include "engine/src/primitive_triangles.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>

#include "engine/src/line_clip.hpp"
#include "engine/src/reference/reference_lines.hpp"

namespace tessera {

void TriangleList::add_window(const WindowPoint& a, const WindowPoint& b, const WindowPoint& c,
                              uint32_t width, uint32_t height) {
  std::array<std::array<double, 4>, 3> clip;
  double largest = 0.0;
  const std::array<const WindowPoint*, 3> points = {&a, &b, &c};
  for (int i = 0; i < 3; ++i) {
    const WindowPoint& p = *points[i];
    const double w = 1.0 / p.inv_w;
    clip[i] = {(2.0 * p.x / width - 1.0) * w, (1.0 - 2.0 * p.y / height) * w, p.z * w, w};
    for (double v : clip[i])
      largest = std::max(largest, std::abs(v));
  }
  // A wide line's corner or a join's tip lies off the segment, up to a miter's length beyond
  // the guard band: near the largest w its clip coordinates can pass the largest float. All
  // three vertices are then scaled down by one power of two, which moves no window point and
  // changes no z/w, and no ratio of 1/w between them. (Only the w >= kMinClipW plane is not
  // scale-free: a vertex of the same triangle within a factor 2 or 4 of it would be cut.)
  int scale = 0;
  if (largest > std::numeric_limits<float>::max()) scale = 126 - std::ilogb(largest);
  for (int i = 0; i < 3; ++i) {
    positions.push_back({static_cast<float>(std::ldexp(clip[i][0], scale)),
                         static_cast<float>(std::ldexp(clip[i][1], scale)),
                         static_cast<float>(std::ldexp(clip[i][2], scale)),
                         static_cast<float>(std::ldexp(clip[i][3], scale))});
    colors.insert(colors.end(), points[i]->color.begin(), points[i]->color.end());
  }
}

PipelineState triangle_pipeline(const PipelineState& pipeline) {
  PipelineState p = pipeline;
  p.cull = CullMode::kNone;
  p.clip_depth = ClipDepth::kZeroToOne;
  // Points, lines and polygons are coloured by their varyings 0..3, whatever the triangle
  // shading state says; their triangles carry only those four (with the pipeline's
  // interpolation).
  const PipelineState defaults;
  p.varying_modes = defaults.varying_modes;
  p.shader = defaults.shader;
  p.output = defaults.output;
  p.roles = defaults.roles;
  return p;
}

namespace {

WindowPoint offset(const WindowPoint& p, double dx, double dy) {
  WindowPoint r = p;
  r.x += dx;
  r.y += dy;
  return r;
}

// The point at screen parameter t of a segment: position and depth linear in the window, 1/w
// linear in the window, colour perspective-correct (c/w linear).
WindowPoint along(const WindowSegment& s, double t) {
  if (t <= 0.0) return s.a;
  if (t >= 1.0) return s.b;
  WindowPoint r;
  r.x = s.a.x + t * (s.b.x - s.a.x);
  r.y = s.a.y + t * (s.b.y - s.a.y);
  r.z = s.a.z + t * (s.b.z - s.a.z);
  r.inv_w = s.a.inv_w + t * (s.b.inv_w - s.a.inv_w);
  for (int c = 0; c < 4; ++c) {
    r.color[c] = static_cast<float>(
        (s.a.color[c] * s.a.inv_w + t * (s.b.color[c] * s.b.inv_w - s.a.color[c] * s.a.inv_w)) /
        r.inv_w);
  }
  return r;
}

}  // namespace

TriangleList square_points(std::span<const WindowPoint> points, float size, uint32_t width,
                           uint32_t height) {
  TriangleList list;
  const double h = 0.5 * size;
  for (WindowPoint p : points) {
    p.inv_w = 1.0;  // a point's colour and depth are constant: no perspective needed
    const WindowPoint tl = offset(p, -h, -h), tr = offset(p, h, -h);
    const WindowPoint bl = offset(p, -h, h), br = offset(p, h, h);
    list.add_window(tl, tr, br, width, height);
    list.add_window(tl, br, bl, width, height);
  }
  return list;
}

void wide_lines(std::span<const WindowSegment> segments, const LineState& state, uint32_t width,
                uint32_t height, const TriangleSink& sink) {
  TriangleList list;
  const double half = 0.5 * state.width;
  for (size_t i = 0; i < segments.size(); ++i) {
    if (list.positions.size() >= 3 * kWideLineChunk) {
      sink(list);
      list.positions.clear();
      list.colors.clear();
    }
    const WindowSegment& s = segments[i];
    const double dx = s.b.x - s.a.x, dy = s.b.y - s.a.y;
    const double length = std::sqrt(dx * dx + dy * dy);
    if (!(length > 0.0)) continue;
    const double nx = -dy / length * half, ny = dx / length * half;
    auto rectangle = [&](double t0, double t1) {
      const WindowPoint p = along(s, t0), q = along(s, t1);
      const WindowPoint p0 = offset(p, nx, ny), p1 = offset(p, -nx, -ny);
      const WindowPoint q0 = offset(q, nx, ny), q1 = offset(q, -nx, -ny);
      list.add_window(p0, q0, q1, width, height);
      list.add_window(p0, q1, p1, width, height);
    };
    if (state.stipple.pattern == 0xFFFF) {
      rectangle(0.0, 1.0);
    } else {
      // Fragment k of the dash pattern covers major-axis distance [k, k + 1) from a. Only the
      // dashes that reach the viewport grown by the half width can cover a pixel: the part
      // [t0, t1] of the segment inside it, from the start of the dash at its first step on
      // (a segment across the guard band has up to 65,536 steps, and as many dashes).
      const double major = std::max(std::abs(dx), std::abs(dy));
      const auto steps = static_cast<uint32_t>(std::ceil(major));
      const double margin = half + 2.0;
      double t0 = 0.0, t1 = 1.0;
      const bool reaches = cohen_sutherland(s.a.x, s.a.y, s.b.x, s.b.y, -margin, -margin,
                                            width + margin, height + margin, t0, t1);
      const auto on = [&](uint32_t k) {
        return reference::stipple_on(state.stipple, s.stipple_base + k);
      };
      const double limit = static_cast<double>(steps);
      uint32_t k = static_cast<uint32_t>(std::clamp(std::floor(t0 * major) - 1.0, 0.0, limit));
      const uint32_t last =
          reaches ? static_cast<uint32_t>(std::clamp(std::ceil(t1 * major) + 1.0, 0.0, limit)) : 0;
      while (k > 0 && on(k) && on(k - 1))
        --k;
      while (k < last) {
        if (!on(k)) {
          ++k;
          continue;
        }
        uint32_t end = k + 1;
        while (end < steps && on(end))
          ++end;
        rectangle(k / major, std::min(1.0, end / major));
        k = end;
      }
    }

    if (!s.joins_next || state.join == LineJoin::kNone) continue;
    const WindowSegment& n = segments[(i + 1) % segments.size()];
    const double ex = n.b.x - n.a.x, ey = n.b.y - n.a.y;
    const double next_length = std::sqrt(ex * ex + ey * ey);
    if (!(next_length > 0.0)) continue;
    const double u1x = dx / length, u1y = dy / length, u2x = ex / next_length,
                 u2y = ey / next_length;
    const double cross = u1x * u2y - u1y * u2x, dot = u1x * u2x + u1y * u2y;
    if (cross == 0.0) continue;  // straight on, or straight back: no wedge to fill
    const double side = cross > 0.0 ? -1.0 : 1.0;  // the outer side of the turn
    const WindowPoint& p = s.b;
    const WindowPoint c1 = offset(p, side * -u1y * half, side * u1x * half);
    const WindowPoint c2 = offset(p, side * -u2y * half, side * u2x * half);
    switch (state.join) {
      case LineJoin::kBevel:
        list.add_window(p, c1, c2, width, height);
        break;
      case LineJoin::kMiter: {
        // The outer edges meet at distance half / cos(theta / 2) from p along the bisector.
        const double ratio = std::sqrt(2.0 / (1.0 + dot));
        if (!(ratio <= state.miter_limit)) {
          list.add_window(p, c1, c2, width, height);
          break;
        }
        const double bx = (c1.x - p.x) + (c2.x - p.x), by = (c1.y - p.y) + (c2.y - p.y);
        const double bl = std::sqrt(bx * bx + by * by);
        const WindowPoint m = offset(p, bx / bl * half * ratio, by / bl * half * ratio);
        list.add_window(p, c1, m, width, height);
        list.add_window(p, m, c2, width, height);
        break;
      }
      case LineJoin::kRound: {
        const int sides = std::clamp(static_cast<int>(std::ceil(std::numbers::pi * half)), 8, 128);
        for (int k = 0; k < sides; ++k) {
          const double a0 = 2.0 * std::numbers::pi * k / sides;
          const double a1 = 2.0 * std::numbers::pi * (k + 1) / sides;
          list.add_window(p, offset(p, half * std::cos(a0), half * std::sin(a0)),
                          offset(p, half * std::cos(a1), half * std::sin(a1)), width, height);
        }
        break;
      }
      case LineJoin::kNone:
        break;
    }
  }
  if (!list.positions.empty()) sink(list);
}

}  // namespace tessera
