// Fixed-point triangle setup; the conventions (window mapping, snapping, fill rule, culling)
// follow ARCHITECTURE.md section 2 to the bit, as the reference rasterizer does.
#include "engine/src/fast/triangle_setup.hpp"

#include <algorithm>
#include <cmath>

#include "engine/src/fast/block_kernel.hpp"

namespace tessera::fast {

namespace {

struct Snapped {
  int64_t x, y;  // fixed point, y down
  double z;      // z / w
  double inv_w;
  const ClipVertex* clip;
};

// window x = (x / w + 1) * width / 2, window y = (1 - y / w) * height / 2, in double, then
// round to nearest (ties to even) at 2^subpixel_bits: the convention both rasterizers share.
Snapped snap(const ClipVertex& v, const SetupContext& ctx) {
  const double wx = (v.x / v.w + 1.0) * (0.5 * ctx.width);
  const double wy = (1.0 - v.y / v.w) * (0.5 * ctx.height);
  const int bits = static_cast<int>(ctx.subpixel_bits);
  return {static_cast<int64_t>(std::nearbyint(std::ldexp(wx, bits))),
          static_cast<int64_t>(std::nearbyint(std::ldexp(wy, bits))), v.z / v.w, 1.0 / v.w, &v};
}

void setup_snapped(const SetupContext& ctx, std::array<Snapped, 3> v,
                   std::vector<TriangleSetup>& out, Counters& counters) {
  int64_t area = (v[1].x - v[0].x) * (v[2].y - v[0].y) - (v[1].y - v[0].y) * (v[2].x - v[0].x);
  if (area == 0) {
    ++counters.triangles_culled;
    return;
  }
  const PipelineState& p = *ctx.pipeline;
  // y points down in window space: counter-clockwise in NDC (y up) means negative area here.
  const bool front = (area < 0) == (p.front_face == FrontFace::kCounterClockwise);
  if ((p.cull == CullMode::kBack && !front) || (p.cull == CullMode::kFront && front)) {
    ++counters.triangles_culled;
    return;
  }
  if (area < 0) {
    std::swap(v[1], v[2]);
    area = -area;
  }

  const int bits = static_cast<int>(ctx.subpixel_bits);
  TriangleSetup t;
  t.x0 = static_cast<int32_t>(std::max<int64_t>(std::min({v[0].x, v[1].x, v[2].x}) >> bits, 0));
  t.y0 = static_cast<int32_t>(std::max<int64_t>(std::min({v[0].y, v[1].y, v[2].y}) >> bits, 0));
  t.x1 = static_cast<int32_t>(
      std::min<int64_t>(std::max({v[0].x, v[1].x, v[2].x}) >> bits, ctx.width - 1));
  t.y1 = static_cast<int32_t>(
      std::min<int64_t>(std::max({v[0].y, v[1].y, v[2].y}) >> bits, ctx.height - 1));
  if (t.x0 > t.x1 || t.y0 > t.y1) {  // inside the guard band but off screen
    ++counters.triangles_culled;
    return;
  }
  ++counters.triangles_rasterized;

  // Edge k runs from vertex k+1 to vertex k+2: E(p) = (bx - ax)(py - ay) - (by - ay)(px - ax).
  int64_t max_step = 0;
  for (int k = 0; k < 3; ++k) {
    const Snapped& from = v[(k + 1) % 3];
    const Snapped& to = v[(k + 2) % 3];
    const int64_t dx = to.x - from.x, dy = to.y - from.y;
    // Top-left rule (clockwise on screen, y down): a top edge is horizontal running to +x, a
    // left edge runs upwards. Samples exactly on other edges are outside: bias c by -1.
    const bool top_left = dy < 0 || (dy == 0 && dx > 0);
    t.a[k] = static_cast<int32_t>(-dy);
    t.b[k] = static_cast<int32_t>(dx);
    t.c[k] = dy * from.x - dx * from.y - (top_left ? 0 : 1);
    max_step = std::max(max_step, std::abs(dy) + std::abs(dx));
  }
  t.narrow = max_step < narrow_edge_limit(ctx.subpixel_bits);

  // Planes: a vertex value v_k spreads as E_k / area (the barycentric of vertex k), so the
  // gradient per fixed-point unit is sum v_k * a_k / area. Values are taken at the centre of
  // pixel (x0, y0) from the exact (unbiased) edge functions.
  const int shift = bits - 4;
  const int64_t cx = (int64_t{t.x0} * 16 + 8) << shift;
  const int64_t cy = (int64_t{t.y0} * 16 + 8) << shift;
  const double inv_area = 1.0 / static_cast<double>(area);
  const double pixel = std::ldexp(1.0, bits);
  std::array<double, 3> weight0;   // barycentrics at the origin pixel centre
  std::array<double, 3> wdx, wdy;  // their gradients per pixel
  for (int k = 0; k < 3; ++k) {
    const Snapped& from = v[(k + 1) % 3];
    const Snapped& to = v[(k + 2) % 3];
    const int64_t e = (to.x - from.x) * (cy - from.y) - (to.y - from.y) * (cx - from.x);
    weight0[k] = static_cast<double>(e) * inv_area;
    wdx[k] = t.a[k] * inv_area * pixel;
    wdy[k] = t.b[k] * inv_area * pixel;
  }
  auto plane = [&](const std::array<double, 3>& value, double& at0, float& gx, float& gy) {
    at0 = weight0[0] * value[0] + weight0[1] * value[1] + weight0[2] * value[2];
    gx = static_cast<float>(wdx[0] * value[0] + wdx[1] * value[1] + wdx[2] * value[2]);
    gy = static_cast<float>(wdy[0] * value[0] + wdy[1] * value[1] + wdy[2] * value[2]);
  };
  plane({v[0].z, v[1].z, v[2].z}, t.z0, t.z_dx, t.z_dy);
  t.z_min = static_cast<float>(std::clamp(std::min({v[0].z, v[1].z, v[2].z}), 0.0, 1.0));
  t.z_max = static_cast<float>(std::clamp(std::max({v[0].z, v[1].z, v[2].z}), 0.0, 1.0));

  std::array<double, 3> q{1.0, 1.0, 1.0};
  if (p.interpolation == Interpolation::kPerspective) {
    const double q_max = std::max({v[0].inv_w, v[1].inv_w, v[2].inv_w});
    for (int k = 0; k < 3; ++k)
      q[k] = v[k].inv_w / q_max;
  }
  plane(q, t.q0, t.q_dx, t.q_dy);
  for (int c = 0; c < 4; ++c) {
    std::array<double, 3> qa;
    for (int k = 0; k < 3; ++k) {
      const double a = c < static_cast<int>(ctx.attribute_count) ? v[k].clip->attributes[c]
                                                                 : (c == 3 ? 1.0 : 0.0);
      qa[k] = q[k] * a;
    }
    plane(qa, t.qa0[c], t.qa_dx[c], t.qa_dy[c]);
  }
  out.push_back(t);
}

}  // namespace

void setup_triangle(const SetupContext& ctx, const std::array<ClipVertex, 3>& triangle,
                    std::vector<TriangleSetup>& out, Counters& counters) {
  ++counters.triangles_submitted;
  if (!needs_clipping(triangle, ctx.guard_band)) {
    setup_snapped(ctx, {snap(triangle[0], ctx), snap(triangle[1], ctx), snap(triangle[2], ctx)},
                  out, counters);
    return;
  }
  ClipPolygon polygon;
  const ClipResult clip = clip_triangle(triangle, ctx.attribute_count, ctx.guard_band, polygon);
  if (clip.clipped) ++counters.triangles_clipped;
  if (!clip.visible) {
    ++counters.triangles_culled;
    return;
  }
  std::array<Snapped, kMaxClipVertices> s;
  for (int i = 0; i < polygon.count; ++i)
    s[i] = snap(polygon.vertices[i], ctx);
  for (int i = 1; i + 1 < polygon.count; ++i)
    setup_snapped(ctx, {s[0], s[i], s[i + 1]}, out, counters);
}

}  // namespace tessera::fast
