// Ear clipping with hole bridging (tessellate.hpp). Orientation and containment tests are
// exact integer arithmetic on the snapped fixed-point vertices: coordinates below 2^24 after
// guard-band clipping, so a cross product of differences stays below 2^51 in int64.
//
// Which contours bound filled regions comes from winding numbers: the winding number just
// outside contour c is the sum of the other contours' winding numbers at a vertex of c, just
// inside it adds c's own orientation; c bounds a filled region (an outline) when the fill rule
// fills its inside and not its outside, a hole when the reverse, and neither (it is dropped)
// otherwise. A hole belongs to the smallest outline around it.
#include "engine/src/tessellate.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

namespace tessera {

namespace {

struct P {
  int64_t x, y;
  size_t id;  // index in the concatenated input
};

int64_t cross(const P& o, const P& a, const P& b) {
  return (a.x - o.x) * (b.y - o.y) - (a.y - o.y) * (b.x - o.x);
}

double signed_area(const std::vector<P>& c) {
  double a = 0;
  for (size_t i = 0; i < c.size(); ++i) {
    const P& p = c[i];
    const P& q = c[(i + 1) % c.size()];
    a += static_cast<double>(p.x) * static_cast<double>(q.y) -
         static_cast<double>(q.x) * static_cast<double>(p.y);
  }
  return a;
}

// Winding number of contour c around p, with the scanline fill's boundary rule (an edge counts
// when y0 <= p.y < y1 and its crossing is at or left of p.x); +1 per edge going down.
int winding(const std::vector<P>& c, const P& p) {
  int w = 0;
  for (size_t i = 0; i < c.size(); ++i) {
    P a = c[i], b = c[(i + 1) % c.size()];
    int dir = 1;
    if (a.y == b.y) continue;
    if (a.y > b.y) std::swap(a, b), dir = -1;
    if (!(a.y <= p.y && p.y < b.y)) continue;
    // crossing x <= p.x  <=>  a.x (b.y - a.y) + (p.y - a.y)(b.x - a.x) <= p.x (b.y - a.y)
    if (a.x * (b.y - a.y) + (p.y - a.y) * (b.x - a.x) <= p.x * (b.y - a.y)) w += dir;
  }
  return w;
}

bool filled(int w, FillRule rule) {
  return rule == FillRule::kEvenOdd ? (w & 1) != 0 : w != 0;
}

// Whether q lies in the closed triangle (a, b, c) of positive orientation.
bool in_triangle(const P& a, const P& b, const P& c, const P& q) {
  return cross(a, b, q) >= 0 && cross(b, c, q) >= 0 && cross(c, a, q) >= 0;
}

bool same_place(const P& a, const P& b) {
  return a.x == b.x && a.y == b.y;
}

// Joins hole h (clockwise, negative area) into outline `poly` (positive area) by a bridge from
// h's rightmost vertex to a vertex of poly it can see (Eberly 2002, section 3).
void bridge(std::vector<P>& poly, const std::vector<P>& h) {
  size_t mi = 0;
  for (size_t i = 1; i < h.size(); ++i) {
    if (h[i].x > h[mi].x || (h[i].x == h[mi].x && h[i].y < h[mi].y)) mi = i;
  }
  const P m = h[mi];
  // The nearest crossing of the ray from m towards +x with an edge of poly.
  double best_x = std::numeric_limits<double>::infinity();
  size_t best = poly.size();
  for (size_t i = 0; i < poly.size(); ++i) {
    const size_t j = (i + 1) % poly.size();
    const P& a = poly[i];
    const P& b = poly[j];
    // Horizontal edges on the ray are found through their endpoints on the adjacent edges.
    if (a.y == b.y || std::min(a.y, b.y) > m.y || std::max(a.y, b.y) < m.y) continue;
    const double x = static_cast<double>(a.x) + static_cast<double>(m.y - a.y) *
                                                    static_cast<double>(b.x - a.x) /
                                                    static_cast<double>(b.y - a.y);
    if (x < static_cast<double>(m.x) || x >= best_x) continue;
    best_x = x;
    // A vertex on the ray is seen directly; otherwise the edge's endpoint with the larger x
    // is the candidate.
    best = a.y == m.y ? i : b.y == m.y ? j : (a.x >= b.x ? i : j);
  }
  if (best == poly.size()) {  // no crossing (a degenerate hole): the nearest vertex
    double d = std::numeric_limits<double>::infinity();
    for (size_t i = 0; i < poly.size(); ++i) {
      const double dx = static_cast<double>(poly[i].x - m.x),
                   dy = static_cast<double>(poly[i].y - m.y);
      if (dx * dx + dy * dy < d) d = dx * dx + dy * dy, best = i;
    }
  } else if (!(poly[best].y == m.y)) {
    // Vertices of poly inside the triangle (m, crossing, candidate) can hide the candidate:
    // take the one making the smallest angle with the ray.
    const P i_pt{static_cast<int64_t>(std::ceil(best_x)), m.y, 0};
    const P cand = poly[best];
    P t0 = m, t1 = i_pt, t2 = cand;
    if (cross(t0, t1, t2) < 0) std::swap(t1, t2);
    double best_angle = std::numeric_limits<double>::infinity();
    for (size_t i = 0; i < poly.size(); ++i) {
      if (i == best || !in_triangle(t0, t1, t2, poly[i]) || poly[i].x <= m.x) continue;
      const P& prev = poly[(i + poly.size() - 1) % poly.size()];
      const P& next = poly[(i + 1) % poly.size()];
      if (cross(prev, poly[i], next) > 0) continue;  // convex vertices cannot hide it
      const double angle =
          std::abs(static_cast<double>(poly[i].y - m.y)) / static_cast<double>(poly[i].x - m.x);
      if (angle < best_angle) best_angle = angle, best = i;
    }
  }
  std::vector<P> out(poly.begin(), poly.begin() + static_cast<std::ptrdiff_t>(best) + 1);
  for (size_t k = 0; k <= h.size(); ++k)
    out.push_back(h[(mi + k) % h.size()]);
  out.insert(out.end(), poly.begin() + static_cast<std::ptrdiff_t>(best), poly.end());
  poly = std::move(out);
}

void clip_ears(const std::vector<P>& poly, std::vector<std::array<size_t, 3>>& out) {
  const size_t n = poly.size();
  if (n < 3) return;
  std::vector<size_t> prev(n), next(n);
  for (size_t i = 0; i < n; ++i) {
    prev[i] = (i + n - 1) % n;
    next[i] = (i + 1) % n;
  }
  size_t remaining = n, cur = 0, failures = 0;
  bool relaxed = false;  // no clean ear found in a full turn: accept any convex vertex
  while (remaining > 3) {
    const size_t p = prev[cur], q = next[cur];
    const int64_t turn = cross(poly[p], poly[cur], poly[q]);
    bool ear = false;
    if (turn > 0) {
      ear = true;
      if (!relaxed) {
        for (size_t k = next[q]; k != p; k = next[k]) {
          const P& v = poly[k];
          if (same_place(v, poly[p]) || same_place(v, poly[cur]) || same_place(v, poly[q]))
            continue;
          if (in_triangle(poly[p], poly[cur], poly[q], v)) {
            ear = false;
            break;
          }
        }
      }
    } else if (turn == 0 && relaxed) {
      // Collinear: removing the vertex loses no area.
      next[p] = q;
      prev[q] = p;
      --remaining;
      cur = q;
      failures = 0;
      continue;
    }
    if (ear) {
      out.push_back({poly[p].id, poly[cur].id, poly[q].id});
      next[p] = q;
      prev[q] = p;
      --remaining;
      cur = q;
      failures = 0;
      relaxed = false;
      continue;
    }
    cur = q;
    if (++failures > remaining) {
      if (relaxed) return;  // nothing left but reflex vertices: no area to fill
      relaxed = true;
      failures = 0;
    }
  }
  const size_t p = prev[cur], q = next[cur];
  if (cross(poly[p], poly[cur], poly[q]) != 0)
    out.push_back({poly[p].id, poly[cur].id, poly[q].id});
}

}  // namespace

std::vector<std::array<size_t, 3>> tessellate(const std::vector<std::vector<WindowPoint>>& contours,
                                              FillRule rule) {
  std::vector<std::vector<P>> c;
  size_t id = 0;
  for (const auto& contour : contours) {
    std::vector<P> pts;
    for (const WindowPoint& w : contour) {
      const P p{w.fx, w.fy, id++};
      if (pts.empty() || !same_place(pts.back(), p)) pts.push_back(p);  // drop repeats
    }
    while (pts.size() > 1 && same_place(pts.front(), pts.back()))
      pts.pop_back();
    c.push_back(std::move(pts));
  }
  const size_t n = c.size();
  std::vector<double> area(n);
  enum class Role { kNone, kOutline, kHole };
  std::vector<Role> role(n, Role::kNone);
  for (size_t i = 0; i < n; ++i) {
    area[i] = c[i].size() >= 3 ? signed_area(c[i]) : 0.0;
    if (area[i] == 0.0) continue;
    int outside = 0;
    for (size_t j = 0; j < n; ++j) {
      if (j != i && c[j].size() >= 3) outside += winding(c[j], c[i][0]);
    }
    // A positive shoelace area (clockwise on screen, y down) winds -1 around its inside.
    const int inside = outside + (area[i] > 0 ? -1 : 1);
    if (filled(inside, rule) && !filled(outside, rule)) role[i] = Role::kOutline;
    if (!filled(inside, rule) && filled(outside, rule)) role[i] = Role::kHole;
  }

  std::vector<std::array<size_t, 3>> triangles;
  for (size_t o = 0; o < n; ++o) {
    if (role[o] != Role::kOutline) continue;
    std::vector<P> poly = c[o];
    if (area[o] < 0) std::reverse(poly.begin(), poly.end());
    // This outline's holes: holes inside it with no smaller outline around them.
    std::vector<size_t> holes;
    for (size_t h = 0; h < n; ++h) {
      if (role[h] != Role::kHole || winding(c[o], c[h][0]) == 0) continue;
      bool nearer = false;
      for (size_t k = 0; k < n && !nearer; ++k) {
        nearer = k != o && role[k] == Role::kOutline && std::abs(area[k]) < std::abs(area[o]) &&
                 winding(c[k], c[h][0]) != 0;
      }
      if (!nearer) holes.push_back(h);
    }
    auto max_x = [&](size_t h) {
      int64_t m = std::numeric_limits<int64_t>::min();
      for (const P& p : c[h])
        m = std::max(m, p.x);
      return m;
    };
    std::sort(holes.begin(), holes.end(), [&](size_t a, size_t b) { return max_x(a) > max_x(b); });
    for (size_t h : holes) {
      std::vector<P> hole = c[h];
      if (area[h] > 0) std::reverse(hole.begin(), hole.end());
      bridge(poly, hole);
    }
    clip_ears(poly, triangles);
  }
  return triangles;
}

}  // namespace tessera
