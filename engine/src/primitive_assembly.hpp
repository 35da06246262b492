// Primitive assembly for points, lines and polygons (ARCHITECTURE.md section 1): vertices
// gathered by topology, clipped in homogeneous space, mapped to the window and snapped exactly
// as triangle vertices are, so every rasterizer of these primitives starts from the same
// window-space input.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "engine/src/line_clip.hpp"
#include "tessera/pipeline.hpp"
#include "tessera/primitives.hpp"
#include "tessera/renderer.hpp"

namespace tessera {

struct WindowSegment {
  WindowPoint a, b;
  uint32_t stipple_base = 0;  // the stipple counter at a (LineStipple)
  bool joins_next = false;    // the next segment starts at b, neither clipped there
};

// The vertex ids of a validated draw in drawing order (the indices, or 0..n-1).
std::vector<uint32_t> vertex_order(const DrawInput& input);

// The points of a draw whose centre lies inside the near, far, w and guard-band planes.
std::vector<WindowPoint> assemble_points(const DrawInput& input, const PipelineState& pipeline,
                                         uint32_t width, uint32_t height);

// The segments of a line draw, clipped, in window space, in drawing order. Zero-length
// segments are kept (the rasterizers draw nothing for them); wholly clipped ones are dropped.
// The stipple counter is kept modulo its period, 16 x the stipple's factor.
std::vector<WindowSegment> assemble_segments(const DrawInput& input, const PipelineState& pipeline,
                                             const LineState& state, uint32_t width,
                                             uint32_t height);

// Steps along the major axis between the pixels of a and b: the stipple counter's advance.
uint32_t major_steps(const WindowPoint& a, const WindowPoint& b, uint32_t subpixel_bits);

// A polygon's contours, each clipped on its own (Sutherland-Hodgman against the planes of
// clip.hpp; clipping a concave contour may add edges along a plane that cancel in pairs),
// in window space. `contour_sizes` splits the vertex order; empty means one contour.
std::vector<std::vector<WindowPoint>> assemble_polygon(const DrawInput& input,
                                                       const PipelineState& pipeline,
                                                       std::span<const uint32_t> contour_sizes,
                                                       uint32_t width, uint32_t height);

// The depth plane of a polygon, z = z0 + zx * x + zy * y over window pixels, from Newell's
// normal of all its contours' vertices; the first vertex's depth when the polygon has no area.
struct DepthPlane {
  double z0 = 0, zx = 0, zy = 0;
  double at(double x, double y) const { return z0 + zx * x + zy * y; }
};
DepthPlane polygon_depth_plane(const std::vector<std::vector<WindowPoint>>& contours);

}  // namespace tessera
