// Assembly of points, line segments and polygon contours: topology, homogeneous clipping,
// viewport transform and snapping (primitive_assembly.hpp). Polygon contours are clipped by
// Sutherland and Hodgman's (1974) re-entrant algorithm, one plane at a time.
#include "engine/src/primitive_assembly.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <numeric>

#include "engine/src/clip.hpp"

namespace tessera {

std::vector<uint32_t> vertex_order(const DrawInput& input) {
  if (!input.indices.empty()) return {input.indices.begin(), input.indices.end()};
  std::vector<uint32_t> order(input.positions.size());
  std::iota(order.begin(), order.end(), 0u);
  return order;
}

namespace {

bool inside_planes(const ClipVertex& v, GuardBand g) {
  return v.z >= 0.0 && v.w - v.z >= 0.0 && v.w >= kMinClipW && std::abs(v.x) <= g.x * v.w &&
         std::abs(v.y) <= g.y * v.w;
}

}  // namespace

std::vector<WindowPoint> assemble_points(const DrawInput& input, const PipelineState& pipeline,
                                         uint32_t width, uint32_t height) {
  const GuardBand g = GuardBand::for_viewport(width, height);
  std::vector<WindowPoint> points;
  for (uint32_t v : vertex_order(input)) {
    const ClipVertex c = load_clip_vertex(input, pipeline, v);
    if (!inside_planes(c, g)) continue;
    points.push_back(
        to_window_point(c, input.attribute_count, width, height, pipeline.subpixel_bits));
  }
  return points;
}

uint32_t major_steps(const WindowPoint& a, const WindowPoint& b, uint32_t bits) {
  const int64_t dx = std::abs((b.fx >> bits) - (a.fx >> bits));
  const int64_t dy = std::abs((b.fy >> bits) - (a.fy >> bits));
  return static_cast<uint32_t>(std::max(dx, dy));
}

std::vector<WindowSegment> assemble_segments(const DrawInput& input, const PipelineState& pipeline,
                                             const LineState& state, uint32_t width,
                                             uint32_t height) {
  const LineTopology topology = state.topology;
  // A strip's counter grows by up to the guard band's width a segment: kept modulo the
  // pattern's period, it cannot wrap (a wrap at 2^32 would shift the pattern's phase).
  const uint32_t period = 16 * state.stipple.factor;
  const std::vector<uint32_t> order = vertex_order(input);
  std::vector<std::pair<uint32_t, uint32_t>> pairs;
  if (topology == LineTopology::kList) {
    for (size_t i = 0; i + 1 < order.size(); i += 2)
      pairs.emplace_back(order[i], order[i + 1]);
  } else {
    for (size_t i = 0; i + 1 < order.size(); ++i)
      pairs.emplace_back(order[i], order[i + 1]);
    if (topology == LineTopology::kLoop && order.size() > 2) {
      pairs.emplace_back(order.back(), order.front());
    }
  }
  const GuardBand g = GuardBand::for_viewport(width, height);
  const uint32_t bits = pipeline.subpixel_bits;
  std::vector<WindowSegment> segments;
  uint32_t counter = 0;
  bool previous_reaches_end = false;  // the previous segment kept its end vertex
  for (size_t i = 0; i < pairs.size(); ++i) {
    ClipVertex a = load_clip_vertex(input, pipeline, pairs[i].first);
    ClipVertex b = load_clip_vertex(input, pipeline, pairs[i].second);
    const ClipVertex b_in = b, a_in = a;
    const bool visible = clip_line(a, b, input.attribute_count, g, pipeline.interpolation);
    if (!visible) {
      previous_reaches_end = false;
      continue;
    }
    const bool a_kept = a.x == a_in.x && a.y == a_in.y && a.z == a_in.z && a.w == a_in.w;
    const bool b_kept = b.x == b_in.x && b.y == b_in.y && b.z == b_in.z && b.w == b_in.w;
    WindowSegment s;
    s.a = to_window_point(a, input.attribute_count, width, height, bits);
    s.b = to_window_point(b, input.attribute_count, width, height, bits);
    if (topology == LineTopology::kList) {
      s.stipple_base = 0;
    } else {
      s.stipple_base = counter;
      counter = static_cast<uint32_t>((uint64_t{counter} + major_steps(s.a, s.b, bits)) % period);
      if (previous_reaches_end && a_kept && !segments.empty()) segments.back().joins_next = true;
    }
    previous_reaches_end = b_kept;
    segments.push_back(s);
  }
  // A loop's last segment joins the first when both keep the shared vertex.
  if (topology == LineTopology::kLoop && segments.size() > 2 && previous_reaches_end &&
      pairs.size() == segments.size()) {
    segments.back().joins_next = true;
  }
  return segments;
}

namespace {

// Sutherland-Hodgman against one plane d(v) >= 0, in place.
template <typename Distance>
void clip_contour(std::vector<ClipVertex>& poly, Distance distance, uint32_t attribute_count,
                  GuardBand g) {
  if (poly.empty()) return;
  std::vector<double> d(poly.size());
  bool any_out = false;
  for (size_t i = 0; i < poly.size(); ++i) {
    d[i] = distance(poly[i]);
    any_out |= !(d[i] >= 0.0);
  }
  if (!any_out) return;
  std::vector<ClipVertex> out;
  for (size_t i = 0; i < poly.size(); ++i) {
    const size_t j = (i + 1) % poly.size();
    const bool p_in = d[i] >= 0.0, q_in = d[j] >= 0.0;
    if (p_in) out.push_back(poly[i]);
    if (p_in != q_in) {
      // Always from the inside vertex towards the outside one.
      const size_t in = p_in ? i : j, o = p_in ? j : i;
      const double t = d[in] / (d[in] - d[o]);
      const double s = -d[o] / (d[in] - d[o]);
      ClipVertex r = weighted_sum(poly[in], s, poly[o], t, attribute_count);
      r.w = std::max(r.w, kMinClipW);
      r.z = std::clamp(r.z, 0.0, r.w);
      r.x = std::clamp(r.x, -g.x * r.w, g.x * r.w);
      r.y = std::clamp(r.y, -g.y * r.w, g.y * r.w);
      out.push_back(r);
    }
  }
  poly = std::move(out);
}

}  // namespace

std::vector<std::vector<WindowPoint>> assemble_polygon(const DrawInput& input,
                                                       const PipelineState& pipeline,
                                                       std::span<const uint32_t> contour_sizes,
                                                       uint32_t width, uint32_t height) {
  const std::vector<uint32_t> order = vertex_order(input);
  std::vector<uint32_t> sizes(contour_sizes.begin(), contour_sizes.end());
  if (sizes.empty()) sizes.push_back(static_cast<uint32_t>(order.size()));
  const GuardBand g = GuardBand::for_viewport(width, height);
  const uint32_t n_attr = input.attribute_count;
  std::vector<std::vector<WindowPoint>> contours;
  size_t next = 0;
  for (uint32_t size : sizes) {
    std::vector<ClipVertex> poly;
    for (uint32_t k = 0; k < size; ++k)
      poly.push_back(load_clip_vertex(input, pipeline, order[next + k]));
    next += size;
    clip_contour(
        poly, [](const ClipVertex& v) { return v.z; }, n_attr, g);
    clip_contour(
        poly, [](const ClipVertex& v) { return v.w - v.z; }, n_attr, g);
    clip_contour(
        poly, [](const ClipVertex& v) { return v.w - kMinClipW; }, n_attr, g);
    clip_contour(
        poly, [g](const ClipVertex& v) { return v.x + g.x * v.w; }, n_attr, g);
    clip_contour(
        poly, [g](const ClipVertex& v) { return g.x * v.w - v.x; }, n_attr, g);
    clip_contour(
        poly, [g](const ClipVertex& v) { return v.y + g.y * v.w; }, n_attr, g);
    clip_contour(
        poly, [g](const ClipVertex& v) { return g.y * v.w - v.y; }, n_attr, g);
    if (poly.size() < 3) continue;
    std::vector<WindowPoint> contour;
    for (const ClipVertex& v : poly)
      contour.push_back(to_window_point(v, n_attr, width, height, pipeline.subpixel_bits));
    contours.push_back(std::move(contour));
  }
  return contours;
}

DepthPlane polygon_depth_plane(const std::vector<std::vector<WindowPoint>>& contours) {
  double nx = 0, ny = 0, nz = 0, cx = 0, cy = 0, cz = 0;
  size_t n = 0;
  for (const auto& c : contours) {
    for (size_t i = 0; i < c.size(); ++i) {
      const WindowPoint& p = c[i];
      const WindowPoint& q = c[(i + 1) % c.size()];
      nx += (p.y - q.y) * (p.z + q.z);
      ny += (p.z - q.z) * (p.x + q.x);
      nz += (p.x - q.x) * (p.y + q.y);
      cx += p.x;
      cy += p.y;
      cz += p.z;
      ++n;
    }
  }
  DepthPlane plane;
  if (n == 0) return plane;
  cx /= static_cast<double>(n);
  cy /= static_cast<double>(n);
  cz /= static_cast<double>(n);
  if (nz == 0.0 || !std::isfinite(nx / nz) || !std::isfinite(ny / nz)) {
    plane.z0 = contours.front().front().z;
    return plane;
  }
  // n . (p - c) = 0  =>  z = cz - (nx (x - cx) + ny (y - cy)) / nz.
  plane.zx = -nx / nz;
  plane.zy = -ny / nz;
  plane.z0 = cz - plane.zx * cx - plane.zy * cy;
  return plane;
}

}  // namespace tessera
