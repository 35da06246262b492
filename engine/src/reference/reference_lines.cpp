// One-pixel and antialiased lines in the reference rasterizer, each algorithm in its plainest
// form. The diamond-exit rule follows OpenGL 4.6 section 14.5.1 (and D3D11's aliased lines):
// pixel f is drawn when the segment, both endpoints nudged by (e, e^2) for an infinitesimal
// e > 0 (right and down in the window), meets f's open diamond |x - xc| + |y - yc| < 1/2 and
// does not end inside it. Midpoint/Bresenham and DDA follow lecture 003.
//
// Exactness of the diamond test: the distance |u| + |v| from the pixel centre is convex and
// piecewise linear along the segment, so its minimum lies at an endpoint or where u or v is
// zero. Each candidate compares to 1/2 pixel as a polynomial in e, decided by the signs of
// its coefficients in order (symbolic perturbation). Window coordinates after guard-band
// clipping are below 2^24 in fixed point and pixel centres inside the viewport below 2^22, so
// u, v, du, dv < 2^25 and every product below 2^51: exact in int64.
#include "engine/src/reference/reference_lines.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>

#include "engine/src/reference/fragment_write.hpp"

namespace tessera::reference {

namespace {

// c0 + c1 e + c2 e^2 for an infinitesimal e > 0.
struct Poly {
  int64_t c0 = 0, c1 = 0, c2 = 0;
};
int sign(const Poly& p) {
  if (p.c0 != 0) return p.c0 > 0 ? 1 : -1;
  if (p.c1 != 0) return p.c1 > 0 ? 1 : -1;
  if (p.c2 != 0) return p.c2 > 0 ? 1 : -1;
  return 0;
}
int64_t sgn(int64_t v) {
  return v > 0 ? 1 : (v < 0 ? -1 : 0);
}

// Whether the nudged point (u + e, v + e^2), relative to a pixel centre, lies in the open
// diamond of half-diagonal h.
bool in_diamond(int64_t u, int64_t v, int64_t h) {
  const int64_t su = u >= 0 ? 1 : -1;  // sign of u + e
  const int64_t sv = v >= 0 ? 1 : -1;  // sign of v + e^2
  return sign({h - su * u - sv * v, -su, -sv}) > 0;
}

// The diamond-exit rule for the segment (ua, va) + t (du, dv), relative to the pixel centre.
bool exits_diamond(int64_t ua, int64_t va, int64_t du, int64_t dv, int64_t h) {
  if (in_diamond(ua + du, va + dv, h)) return false;  // ends inside: not drawn
  if (in_diamond(ua, va, h)) return true;
  if (du != 0) {  // where u + e + du t = 0, if that t is in [0, 1]
    const int64_t s = sgn(du);
    if (sign({-s * ua, -s, 0}) >= 0 && sign({std::abs(du) + s * ua, s, 0}) >= 0) {
      const Poly n{va * du - dv * ua, -dv, du};  // v there, times du
      const int64_t sn = sign(n);
      if (sign({h * std::abs(du) - sn * n.c0, sn * dv, -sn * du}) > 0) return true;
    }
  }
  if (dv != 0) {  // where v + e^2 + dv t = 0
    const int64_t s = sgn(dv);
    if (sign({-s * va, 0, -s}) >= 0 && sign({std::abs(dv) + s * va, 0, s}) >= 0) {
      const Poly m{ua * dv - du * va, dv, -du};  // u there, times dv
      const int64_t sm = sign(m);
      if (sign({h * std::abs(dv) - sm * m.c0, -sm * dv, sm * du}) > 0) return true;
    }
  }
  return false;
}

struct Bounds {
  int64_t x0, y0, x1, y1;  // pixels, inclusive
  bool contains(int64_t x, int64_t y) const { return x >= x0 && x <= x1 && y >= y0 && y <= y1; }
};

// Calls visit(x, y, s) for the pixels of the segment in order from a to b, s counting the
// major-axis steps from a's pixel; only pixels within `bounds` are visited.
template <typename Visit>
void diamond_exit(const WindowSegment& seg, uint32_t bits, const Bounds& bounds, Visit visit) {
  const int64_t one = int64_t{1} << bits, h = one / 2;
  const int64_t ax = seg.a.fx, ay = seg.a.fy;
  const int64_t dx = seg.b.fx - ax, dy = seg.b.fy - ay;
  if (dx == 0 && dy == 0) return;
  const bool x_major = std::abs(dx) >= std::abs(dy);
  // Major and minor coordinates, so one loop serves both cases.
  const int64_t a_major = x_major ? ax : ay, a_minor = x_major ? ay : ax;
  const int64_t d_major = x_major ? dx : dy, d_minor = x_major ? dy : dx;
  const int64_t dir = d_major > 0 ? 1 : -1;
  const int64_t first = (a_major >> bits) - dir, last = ((a_major + d_major) >> bits) + dir;
  const int64_t lo = x_major ? bounds.x0 : bounds.y0, hi = x_major ? bounds.x1 : bounds.y1;
  const int64_t start_pixel = a_major >> bits;
  for (int64_t i = first; i != last + dir; i += dir) {
    if (i < lo || i > hi) continue;
    const int64_t c_major = i * one + h;
    // The line's minor coordinate at this column's centre, to pick the rows worth testing:
    // for |slope| <= 1 the line meets a diamond only in the row it crosses the centre in.
    const double m = static_cast<double>(a_minor) + static_cast<double>(c_major - a_major) *
                                                        static_cast<double>(d_minor) /
                                                        static_cast<double>(d_major);
    const int64_t j0 = static_cast<int64_t>(std::floor(m / static_cast<double>(one)));
    for (int64_t j = j0 - 1; j <= j0 + 1; ++j) {
      const int64_t px = x_major ? i : j, py = x_major ? j : i;
      if (!bounds.contains(px, py)) continue;
      const int64_t cx = px * one + h, cy = py * one + h;
      if (exits_diamond(ax - cx, ay - cy, dx, dy, h)) {
        visit(px, py, static_cast<uint32_t>(std::abs(i - start_pixel)));
        break;
      }
    }
  }
}

// Midpoint/Bresenham (lecture 003) between the pixels holding the endpoints.
template <typename Visit>
void bresenham(const WindowSegment& seg, uint32_t bits, const Bounds& bounds, Visit visit) {
  int64_t x0 = seg.a.fx >> bits, y0 = seg.a.fy >> bits;
  int64_t x1 = seg.b.fx >> bits, y1 = seg.b.fy >> bits;
  const bool x_major = std::abs(x1 - x0) >= std::abs(y1 - y0);
  const int64_t start_major = x_major ? x0 : y0;
  if (!x_major) std::swap(x0, y0), std::swap(x1, y1);
  if (x0 > x1) std::swap(x0, x1), std::swap(y0, y1);  // the major coordinate increases
  const int64_t dx = x1 - x0, ady = std::abs(y1 - y0), step = y1 >= y0 ? 1 : -1;
  int64_t d = 2 * ady - dx;  // 2 F at the first midpoint
  int64_t y = y0;
  for (int64_t x = x0; x <= x1; ++x) {
    const int64_t px = x_major ? x : y, py = x_major ? y : x;
    if (bounds.contains(px, py)) visit(px, py, static_cast<uint32_t>(std::abs(x - start_major)));
    if (d > 0) {  // the midpoint is on the far side of the line: step the minor axis
      y += step;
      d += 2 * (ady - dx);
    } else {  // on the near side or on the line (the tie): stay
      d += 2 * ady;
    }
  }
}

// DDA (lecture 003): floating-point slope stepping, minor coordinate rounded half up.
template <typename Visit>
void dda(const WindowSegment& seg, uint32_t bits, const Bounds& bounds, Visit visit) {
  int64_t x0 = seg.a.fx >> bits, y0 = seg.a.fy >> bits;
  int64_t x1 = seg.b.fx >> bits, y1 = seg.b.fy >> bits;
  const bool x_major = std::abs(x1 - x0) >= std::abs(y1 - y0);
  const int64_t start_major = x_major ? x0 : y0;
  if (!x_major) std::swap(x0, y0), std::swap(x1, y1);
  if (x0 > x1) std::swap(x0, x1), std::swap(y0, y1);
  const double m = x1 == x0 ? 0.0 : static_cast<double>(y1 - y0) / static_cast<double>(x1 - x0);
  double y = static_cast<double>(y0);
  for (int64_t x = x0; x <= x1; ++x, y += m) {
    const int64_t r = static_cast<int64_t>(std::floor(y + 0.5));
    const int64_t px = x_major ? x : r, py = x_major ? r : x;
    if (bounds.contains(px, py)) visit(px, py, static_cast<uint32_t>(std::abs(x - start_major)));
  }
}

// Antialiased line: every pixel whose centre is within width/2 + 1/2 of the segment's
// rectangle gets coverage clamp(w/2 + 1/2 - d, 0, 1) across times the same along it.
template <typename Visit>
void smooth(const WindowSegment& seg, float width, const Bounds& bounds, Visit visit) {
  const double ax = seg.a.x, ay = seg.a.y, dx = seg.b.x - ax, dy = seg.b.y - ay;
  const double length = std::sqrt(dx * dx + dy * dy);
  if (!(length > 0.0)) return;
  const double ux = dx / length, uy = dy / length, half = 0.5 * width;
  const double reach = half + 1.0;
  const int64_t x0 =
      std::max<int64_t>(bounds.x0, static_cast<int64_t>(std::floor(std::min(ax, ax + dx) - reach)));
  const int64_t x1 =
      std::min<int64_t>(bounds.x1, static_cast<int64_t>(std::floor(std::max(ax, ax + dx) + reach)));
  const int64_t y0 =
      std::max<int64_t>(bounds.y0, static_cast<int64_t>(std::floor(std::min(ay, ay + dy) - reach)));
  const int64_t y1 =
      std::min<int64_t>(bounds.y1, static_cast<int64_t>(std::floor(std::max(ay, ay + dy) + reach)));
  const double major = std::max(std::abs(dx), std::abs(dy));
  for (int64_t py = y0; py <= y1; ++py) {
    // Only centres with |across| < half + 1/2 can be covered: on a row, an interval of x when
    // uy != 0 (widened by a pixel against rounding; the coverage below decides).
    int64_t row_x0 = x0, row_x1 = x1;
    if (uy != 0.0) {
      const double base = (static_cast<double>(py) + 0.5 - ay) * ux;
      const double e0 = (base - (half + 0.5)) / uy + ax - 0.5;
      const double e1 = (base + (half + 0.5)) / uy + ax - 0.5;
      row_x0 = std::max(row_x0, static_cast<int64_t>(std::floor(std::min(e0, e1))) - 1);
      row_x1 = std::min(row_x1, static_cast<int64_t>(std::ceil(std::max(e0, e1))) + 1);
    }
    for (int64_t px = row_x0; px <= row_x1; ++px) {
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

}  // namespace

void draw_thin_lines(detail::FramebufferStorage& fb, const PipelineState& pipeline,
                     const LineState& state, std::span<const WindowSegment> segments,
                     Counters& counters) {
  const uint32_t bits = pipeline.subpixel_bits;
  const Bounds screen{0, 0, fb.desc.width - 1, fb.desc.height - 1};
  for (const WindowSegment& seg : segments) {
    if (seg.a.fx == seg.b.fx && seg.a.fy == seg.b.fy) continue;  // zero length: nothing
    // Cohen-Sutherland against the viewport grown by the line's reach: a segment wholly
    // outside draws nothing; otherwise the pixels visited are narrowed to the part inside.
    const double margin = 2.0 + 0.5 * state.width;
    double t0 = 0, t1 = 1;
    if (!cohen_sutherland(seg.a.x, seg.a.y, seg.b.x, seg.b.y, -margin, -margin,
                          fb.desc.width + margin, fb.desc.height + margin, t0, t1)) {
      continue;
    }
    const double ex = seg.b.x - seg.a.x, ey = seg.b.y - seg.a.y;
    const double cx0 = seg.a.x + t0 * ex, cx1 = seg.a.x + t1 * ex;
    const double cy0 = seg.a.y + t0 * ey, cy1 = seg.a.y + t1 * ey;
    const Bounds bounds{
        std::max<int64_t>(screen.x0, static_cast<int64_t>(std::floor(std::min(cx0, cx1) - margin))),
        std::max<int64_t>(screen.y0, static_cast<int64_t>(std::floor(std::min(cy0, cy1) - margin))),
        std::min<int64_t>(screen.x1, static_cast<int64_t>(std::floor(std::max(cx0, cx1) + margin))),
        std::min<int64_t>(screen.y1,
                          static_cast<int64_t>(std::floor(std::max(cy0, cy1) + margin)))};

    // Colour and depth at the pixel centre's projection onto the segment: depth linear in
    // the window, colour perspective-correct (a/w and 1/w linear) unless affine or both ends
    // have the same w (then the two are the same parameter).
    const double len2 = ex * ex + ey * ey;
    const double inv_len2 = len2 > 0.0 ? 1.0 / len2 : 0.0;  // t = projection * inv_len2
    auto shade = [&](int64_t px, int64_t py, uint32_t s, float coverage) {
      if (!stipple_on(state.stipple, seg.stipple_base + s)) return;
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
      Fragment f;
      f.x = static_cast<uint32_t>(px);
      f.y = static_cast<uint32_t>(py);
      f.depth = static_cast<float>(seg.a.z + t * (seg.b.z - seg.a.z));
      for (int c = 0; c < 4; ++c) {
        f.color[c] = static_cast<float>(seg.a.color[c] + tc * (seg.b.color[c] - seg.a.color[c]));
      }
      f.coverage = coverage;
      write_fragment(fb, pipeline, f, state.antialiased, counters);
    };
    if (state.antialiased) {
      smooth(seg, state.width, bounds,
             [&](int64_t x, int64_t y, uint32_t s, float c) { shade(x, y, s, c); });
      continue;
    }
    auto visit = [&](int64_t x, int64_t y, uint32_t s) { shade(x, y, s, 1.0f); };
    switch (state.algorithm) {
      case LineAlgorithm::kDiamondExit:
        diamond_exit(seg, bits, bounds, visit);
        break;
      case LineAlgorithm::kBresenham:
        bresenham(seg, bits, bounds, visit);
        break;
      case LineAlgorithm::kDDA:
        dda(seg, bits, bounds, visit);
        break;
    }
  }
}

}  // namespace tessera::reference
