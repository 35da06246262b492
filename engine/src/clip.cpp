// Sutherland-Hodgman clipping of triangles against the near, far, w and guard-band planes.
#include "engine/src/clip.hpp"

#include <algorithm>

namespace tessera {

namespace {

// Which coordinate a plane pins down, so that a vertex the plane creates lies on it exactly.
enum class Pin { kZZero, kZToW, kWMin, kXMinus, kXPlus, kYMinus, kYPlus };

// A plane as the signed distance d(v) = a*x + b*y + c*z + e*w + f; inside when d >= 0.
struct Plane {
  double a, b, c, e, f;
  Pin pin;
  double distance(double x, double y, double z, double w) const {
    return a * x + b * y + c * z + e * w + f;
  }
  double distance(const ClipVertex& v) const { return distance(v.x, v.y, v.z, v.w); }
  // Puts an interpolated vertex exactly on the plane, and back inside the planes applied
  // before this one (they precede it in clip_planes()). Interpolating across a huge range of w
  // (say from 1e38 to 1e-30) cancels catastrophically, and the result could leave an earlier
  // plane or reach w = 0; pinned and clamped, every clipped vertex keeps w >= kMinClipW,
  // 0 <= z <= w and |x|, |y| <= g * w, so window coordinates stay within the guard band.
  void put_on(ClipVertex& v, double gx) const {
    if (pin > Pin::kWMin) v.w = std::max(v.w, kMinClipW);
    switch (pin) {
      case Pin::kZZero:
        v.z = 0.0;
        break;
      case Pin::kZToW:
        v.z = v.w;
        break;
      case Pin::kWMin:
        v.w = kMinClipW;
        break;
      case Pin::kXMinus:
        v.x = -e * v.w;
        break;
      case Pin::kXPlus:
        v.x = e * v.w;
        break;
      case Pin::kYMinus:
        v.y = -e * v.w;
        break;
      case Pin::kYPlus:
        v.y = e * v.w;
        break;
    }
    if (pin > Pin::kZToW) v.z = std::clamp(v.z, 0.0, v.w);
    if (pin > Pin::kXPlus) v.x = std::clamp(v.x, -gx * v.w, gx * v.w);
  }
};

// The point of segment inside -> outside where the distance is 0: s inside + t outside with
// t = d_in / (d_in - d_out) and s = -d_out / (d_in - d_out), the inside vertex's weight computed
// on its own rather than as 1 - t. When the outside vertex's distance is tiny next to the
// inside one's, t rounds to 1, and p + t (q - p) loses the inside vertex entirely: a vertex at
// infinity at a small scale, (0, 1e-20, 0, 0), cut by the top guard-band plane from a vertex A,
// landed on the screen's centre column instead of straight above A, and the homogeneous origin
// (0, 0, 0, 0) cut by the w plane landed on the screen centre instead of on A. Kept as s * p, the
// inside vertex's share fixes the direction.
ClipVertex intersect(const ClipVertex& inside, double d_in, const ClipVertex& outside, double d_out,
                     uint32_t attribute_count) {
  const double t = d_in / (d_in - d_out);
  const double s = -d_out / (d_in - d_out);
  return weighted_sum(inside, s, outside, t, attribute_count);
}

// Clips `poly` against one plane in place. Returns whether the plane cut anything.
bool clip_against(ClipPolygon& poly, const Plane& plane, double gx, uint32_t attribute_count) {
  std::array<double, kMaxClipVertices> d{};
  bool any_out = false;
  for (int i = 0; i < poly.count; ++i) {
    d[i] = plane.distance(poly.vertices[i]);
    any_out |= !(d[i] >= 0.0);
  }
  if (!any_out) return false;

  ClipPolygon result;
  for (int i = 0; i < poly.count; ++i) {
    const int j = (i + 1) % poly.count;
    const ClipVertex& p = poly.vertices[i];
    const ClipVertex& q = poly.vertices[j];
    const bool p_in = d[i] >= 0.0;
    const bool q_in = d[j] >= 0.0;
    if (p_in) result.vertices[result.count++] = p;
    if (p_in && !q_in) {
      result.vertices[result.count] = intersect(p, d[i], q, d[j], attribute_count);
      plane.put_on(result.vertices[result.count++], gx);
    } else if (!p_in && q_in) {
      result.vertices[result.count] = intersect(q, d[j], p, d[i], attribute_count);
      plane.put_on(result.vertices[result.count++], gx);
    }
  }
  poly = result;
  return true;
}

using PlaneSet = std::array<Plane, 7>;

PlaneSet clip_planes(GuardBand guard_band) {
  const double gx = guard_band.x;
  const double gy = guard_band.y;
  return {{
      {0, 0, 1, 0, 0, Pin::kZZero},          // near:   z >= 0
      {0, 0, -1, 1, 0, Pin::kZToW},          // far:    w - z >= 0
      {0, 0, 0, 1, -kMinClipW, Pin::kWMin},  // w >= kMinClipW
      {1, 0, 0, gx, 0, Pin::kXMinus},        // left:   x + g w >= 0
      {-1, 0, 0, gx, 0, Pin::kXPlus},        // right:  g w - x >= 0
      {0, 1, 0, gy, 0, Pin::kYMinus},        // bottom: y + g w >= 0 (NDC y up)
      {0, -1, 0, gy, 0, Pin::kYPlus},        // top:    g w - y >= 0
  }};
}

}  // namespace

bool inside_clip_planes(std::span<const std::array<double, 4>> points, GuardBand guard_band) {
  const PlaneSet planes = clip_planes(guard_band);
  for (const std::array<double, 4>& p : points) {
    for (const Plane& plane : planes) {
      if (!(plane.distance(p[0], p[1], p[2], p[3]) >= 0.0)) return false;
    }
  }
  return true;
}

ClipResult clip_triangle(const std::array<ClipVertex, 3>& in, uint32_t attribute_count,
                         GuardBand guard_band, ClipPolygon& out) {
  const PlaneSet planes = clip_planes(guard_band);
  out.count = 3;
  for (int i = 0; i < 3; ++i)
    out.vertices[i] = in[i];
  ClipResult result;
  for (const Plane& plane : planes) {
    result.clipped |= clip_against(out, plane, guard_band.x, attribute_count);
    if (out.count < 3) {
      out.count = 0;
      return result;
    }
  }
  result.visible = true;
  return result;
}

ClipVertex weighted_sum(const ClipVertex& p, double s, const ClipVertex& q, double t,
                        uint32_t attribute_count) {
  auto mix = [s, t](double u, double v) { return s * u + t * v; };
  ClipVertex r;
  r.x = mix(p.x, q.x);
  r.y = mix(p.y, q.y);
  r.z = mix(p.z, q.z);
  r.w = mix(p.w, q.w);
  for (uint32_t i = 0; i < attribute_count; ++i) {
    r.attributes[i] = mix(p.attributes[i], q.attributes[i]);
  }
  return r;
}

}  // namespace tessera
