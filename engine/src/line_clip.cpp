// Homogeneous Liang-Barsky clipping of segments and window-space Cohen-Sutherland outcodes;
// see line_clip.hpp.
#include "engine/src/line_clip.hpp"

#include <algorithm>
#include <cmath>

namespace tessera {

ClipVertex load_clip_vertex(const DrawInput& input, const PipelineState& pipeline, size_t v) {
  const Float4& p = input.positions[v];
  ClipVertex c;
  c.x = p.x;
  c.y = p.y;
  c.w = p.w;
  c.z = pipeline.clip_depth == ClipDepth::kNegativeOneToOne ? 0.5 * (double{p.z} + p.w) : p.z;
  for (uint32_t a = 0; a < input.attribute_count; ++a) {
    c.attributes[a] = input.attributes[v * input.attribute_count + a];
  }
  return c;
}

namespace {

// Keeps a computed endpoint inside the planes despite rounding (see clip.cpp's put_on).
void pin(ClipVertex& v, GuardBand g) {
  v.w = std::max(v.w, kMinClipW);
  v.z = std::clamp(v.z, 0.0, v.w);
  v.x = std::clamp(v.x, -g.x * v.w, g.x * v.w);
  v.y = std::clamp(v.y, -g.y * v.w, g.y * v.w);
}

}  // namespace

bool clip_line(ClipVertex& a, ClipVertex& b, uint32_t attribute_count, GuardBand g,
               Interpolation interpolation) {
  // Signed distances to the planes of clip.cpp, inside when >= 0.
  auto distances = [g](const ClipVertex& v) {
    return std::array<double, 7>{v.z,
                                 v.w - v.z,
                                 v.w - kMinClipW,
                                 v.x + g.x * v.w,
                                 g.x * v.w - v.x,
                                 v.y + g.y * v.w,
                                 g.y * v.w - v.y};
  };
  const auto da = distances(a), db = distances(b);
  // The cut points (1 - t) a + t b, with 1 - t as s from the distances; among planes whose t
  // rounds the same, the one whose s is nearer the other endpoint cuts. An endpoint outside a
  // plane is always cut and pinned, even when its t rounds to 0 or 1: a vertex at w = 0 kept
  // as it is would be divided by 0 in the viewport transform.
  double t0 = 0.0, t1 = 1.0, s0 = 1.0, s1 = 0.0;
  bool a_out = false, b_out = false;
  for (int i = 0; i < 7; ++i) {
    const bool a_in = da[i] >= 0.0, b_in = db[i] >= 0.0;
    if (!a_in && !b_in) return false;
    const double t = da[i] / (da[i] - db[i]), s = -db[i] / (da[i] - db[i]);
    if (!a_in) {
      a_out = true;
      if (t > t0 || (t == t0 && s < s0)) t0 = t, s0 = s;
    }
    if (!b_in) {
      b_out = true;
      if (t < t1 || (t == t1 && s > s1)) t1 = t, s1 = s;
    }
  }
  if (!(t0 <= t1)) return false;
  if (!a_out && !b_out) return true;

  const bool affine = interpolation == Interpolation::kAffine;
  ClipVertex pa = a, pb = b;
  if (affine) {
    for (uint32_t i = 0; i < attribute_count; ++i) {
      pa.attributes[i] *= pa.w;
      pb.attributes[i] *= pb.w;
    }
  }
  auto cut = [&](double s, double t) {
    ClipVertex v = weighted_sum(pa, s, pb, t, attribute_count);
    pin(v, g);
    if (affine) {
      for (uint32_t i = 0; i < attribute_count; ++i)
        v.attributes[i] /= v.w;
    }
    return v;
  };
  const ClipVertex na = a_out ? cut(s0, t0) : a;
  const ClipVertex nb = b_out ? cut(s1, t1) : b;
  a = na;
  b = nb;
  return true;
}

WindowPoint to_window_point(const ClipVertex& v, uint32_t attribute_count, uint32_t width,
                            uint32_t height, uint32_t bits) {
  const double wx = (v.x / v.w + 1.0) * (0.5 * width);
  const double wy = (1.0 - v.y / v.w) * (0.5 * height);
  // Scaling by 2^bits and 2^-bits is exact (as ldexp is): the values lie far inside the
  // double range, so the products neither overflow nor lose bits.
  const double scale = static_cast<double>(uint32_t{1} << bits), inv_scale = 1.0 / scale;
  WindowPoint p;
  p.fx = static_cast<int64_t>(std::nearbyint(wx * scale));
  p.fy = static_cast<int64_t>(std::nearbyint(wy * scale));
  p.x = static_cast<double>(p.fx) * inv_scale;
  p.y = static_cast<double>(p.fy) * inv_scale;
  p.z = std::clamp(v.z / v.w, 0.0, 1.0);
  p.inv_w = 1.0 / v.w;
  for (uint32_t c = 0; c < std::min(attribute_count, 4u); ++c)
    p.color[c] = static_cast<float>(v.attributes[c]);
  return p;
}

bool cohen_sutherland(double ax, double ay, double bx, double by, double x0, double y0, double x1,
                      double y1, double& t0, double& t1) {
  enum : unsigned { kLeft = 1, kRight = 2, kTop = 4, kBottom = 8 };
  auto code = [&](double x, double y) {
    return (x < x0 ? kLeft : 0u) | (x > x1 ? kRight : 0u) | (y < y0 ? kTop : 0u) |
           (y > y1 ? kBottom : 0u);
  };
  const double dx = bx - ax, dy = by - ay;
  double ta = 0.0, tb = 1.0;
  unsigned ca = code(ax, ay), cb = code(bx, by);
  // Each pass moves one outside endpoint onto the border it is beyond; at most four passes.
  for (int pass = 0; pass < 8; ++pass) {
    if ((ca | cb) == 0) {
      t0 = ta;
      t1 = tb;
      return true;
    }
    if (ca & cb) return false;
    const bool move_a = ca != 0;
    const unsigned c = move_a ? ca : cb;
    double t;
    if (c & kLeft) {
      t = (x0 - ax) / dx;
    } else if (c & kRight) {
      t = (x1 - ax) / dx;
    } else if (c & kTop) {
      t = (y0 - ay) / dy;
    } else {
      t = (y1 - ay) / dy;
    }
    // Snap the crossing onto the border exactly, so the new point's code drops that bit.
    double x = ax + t * dx, y = ay + t * dy;
    if (c & kLeft)
      x = x0;
    else if (c & kRight)
      x = x1;
    else if (c & kTop)
      y = y0;
    else
      y = y1;
    if (move_a) {
      ta = t;
      ca = code(x, y);
    } else {
      tb = t;
      cb = code(x, y);
    }
    if (ta > tb) return false;
  }
  t0 = ta;
  t1 = tb;
  return true;
}

}  // namespace tessera
