// Routing of point, line and polygon draws (primitive_draw.hpp): the shapes that are
// triangles go through the triangle pipeline, so both backends bin, clip and rasterize them as
// they do any triangle; thin lines, round points and scanline polygons go to the backend's
// own per-pixel rasterizers. The reference's write depth without keeping the fast engine's
// Hi-Z bounds, so they mark those stale; the fast engine's mark the blocks they write.
#include "engine/src/primitive_draw.hpp"

#include "engine/src/primitive_assembly.hpp"
#include "engine/src/primitive_triangles.hpp"
#include "engine/src/reference/reference_lines.hpp"
#include "engine/src/reference/reference_points.hpp"
#include "engine/src/reference/reference_polygon.hpp"
#include "engine/src/tessellate.hpp"

namespace tessera {

namespace {

void draw_list(const TriangleList& list, const PipelineState& pipeline,
               const TriangleDraw& triangles) {
  if (list.positions.empty()) return;
  DrawInput input;
  input.positions = list.positions;
  input.attributes = list.colors;
  input.attribute_count = 4;
  triangles(triangle_pipeline(pipeline), input);
}

void before_pixel_writes(detail::FramebufferStorage& fb, const PipelineState& pipeline) {
  if (pipeline.depth_test && pipeline.depth_write) fb.hiz_valid = false;
}

size_t vertex_count(const DrawInput& input) {
  return input.indices.empty() ? input.positions.size() : input.indices.size();
}

}  // namespace

void draw_reference_round_points(detail::FramebufferStorage& fb, const PipelineState& pipeline,
                                 std::span<const WindowPoint> points, float size,
                                 Counters& counters) {
  before_pixel_writes(fb, pipeline);
  reference::draw_round_points(fb, pipeline, points, size, counters);
}

void draw_points(detail::FramebufferStorage& fb, const PipelineState& pipeline,
                 const PointState& state, const DrawInput& input, const TriangleDraw& triangles,
                 const RoundPointDraw& round_points, Counters& counters) {
  counters.points_submitted += vertex_count(input);
  const std::vector<WindowPoint> points =
      assemble_points(input, pipeline, fb.desc.width, fb.desc.height);
  if (state.shape == PointShape::kSquare) {
    draw_list(square_points(points, state.size, fb.desc.width, fb.desc.height), pipeline,
              triangles);
  } else {
    round_points(points, state.size);
  }
}

void draw_reference_thin_lines(detail::FramebufferStorage& fb, const PipelineState& pipeline,
                               const LineState& state, std::span<const WindowSegment> segments,
                               Counters& counters) {
  before_pixel_writes(fb, pipeline);
  reference::draw_thin_lines(fb, pipeline, state, segments, counters);
}

void draw_lines(detail::FramebufferStorage& fb, const PipelineState& pipeline,
                const LineState& state, const DrawInput& input, const TriangleDraw& triangles,
                const ThinLineDraw& thin_lines, Counters& counters) {
  const std::vector<WindowSegment> segments =
      assemble_segments(input, pipeline, state, fb.desc.width, fb.desc.height);
  const size_t n = vertex_count(input);
  counters.lines_submitted += state.topology == LineTopology::kList    ? n / 2
                              : n < 2                                  ? 0
                              : state.topology == LineTopology::kStrip ? n - 1
                                                                       : (n > 2 ? n : 1);
  if (state.width > 1.0f && !state.antialiased) {
    wide_lines(segments, state, fb.desc.width, fb.desc.height,
               [&](const TriangleList& list) { draw_list(list, pipeline, triangles); });
  } else {
    thin_lines(state, segments);
  }
}

void draw_reference_scanline_polygon(detail::FramebufferStorage& fb, const PipelineState& pipeline,
                                     const std::vector<std::vector<WindowPoint>>& contours,
                                     FillRule rule, Counters& counters) {
  before_pixel_writes(fb, pipeline);
  reference::draw_scanline_polygon(fb, pipeline, contours, rule, counters);
}

void draw_polygon(detail::FramebufferStorage& fb, const PipelineState& pipeline,
                  const PolygonState& state, const DrawInput& input,
                  std::span<const uint32_t> contour_sizes, const TriangleDraw& triangles,
                  const ScanlineDraw& scanline, Counters& counters) {
  ++counters.polygons_submitted;
  std::vector<std::vector<WindowPoint>> contours =
      assemble_polygon(input, pipeline, contour_sizes, fb.desc.width, fb.desc.height);
  if (contours.empty()) return;
  if (state.method == PolygonMethod::kScanline) {
    scanline(contours, state.fill_rule);
    return;
  }
  // Flat colour (the first vertex's) and the polygon's depth plane at every vertex, as the
  // scanline fill shades it; no perspective left to correct.
  const DepthPlane plane = polygon_depth_plane(contours);
  const std::array<float, 4> color = contours.front().front().color;
  std::vector<WindowPoint> all;
  for (auto& c : contours) {
    for (WindowPoint& p : c) {
      p.z = plane.at(p.x, p.y);
      p.inv_w = 1.0;
      p.color = color;
      all.push_back(p);
    }
  }
  TriangleList list;
  for (const auto& t : tessellate(contours, state.fill_rule)) {
    list.add_window(all[t[0]], all[t[1]], all[t[2]], fb.desc.width, fb.desc.height);
  }
  draw_list(list, pipeline, triangles);
}

}  // namespace tessera
