// Drawing points, lines and polygons (Renderer::draw_points, draw_lines, draw_polygon): each
// draw is assembled and clipped once, then goes either to the triangle pipeline of the
// renderer's backend (square points, wide lines, tessellated polygons) or to the per-pixel
// rasterizers of the backend (one-pixel and antialiased lines, round points, scanline
// polygons).
#pragma once

#include <cstdint>
#include <functional>
#include <span>
#include <vector>

#include "engine/src/framebuffer_storage.hpp"
#include "tessera/pipeline.hpp"
#include "tessera/primitives.hpp"
#include "tessera/renderer.hpp"

namespace tessera {

struct WindowSegment;
struct WindowPoint;

// Draws a validated triangle list with the renderer's backend.
using TriangleDraw = std::function<void(const PipelineState&, const DrawInput&)>;
// Draws assembled one-pixel or antialiased segments with the renderer's backend.
using ThinLineDraw = std::function<void(const LineState&, std::span<const WindowSegment>)>;
// Draws assembled round points of a size with the renderer's backend.
using RoundPointDraw = std::function<void(std::span<const WindowPoint>, float)>;
// Fills assembled polygon contours by the scanline method with the renderer's backend.
using ScanlineDraw =
    std::function<void(const std::vector<std::vector<WindowPoint>>& contours, FillRule rule)>;

// Each draws a validated draw (draw_validation.hpp).
void draw_points(detail::FramebufferStorage& fb, const PipelineState& pipeline,
                 const PointState& state, const DrawInput& input, const TriangleDraw& triangles,
                 const RoundPointDraw& round_points, Counters& counters);
void draw_lines(detail::FramebufferStorage& fb, const PipelineState& pipeline,
                const LineState& state, const DrawInput& input, const TriangleDraw& triangles,
                const ThinLineDraw& thin_lines, Counters& counters);

// The reference rasterizer's round points, for RoundPointDraw.
void draw_reference_round_points(detail::FramebufferStorage& fb, const PipelineState& pipeline,
                                 std::span<const WindowPoint> points, float size,
                                 Counters& counters);

// The reference rasterizer's thin lines, for ThinLineDraw.
void draw_reference_thin_lines(detail::FramebufferStorage& fb, const PipelineState& pipeline,
                               const LineState& state, std::span<const WindowSegment> segments,
                               Counters& counters);
void draw_polygon(detail::FramebufferStorage& fb, const PipelineState& pipeline,
                  const PolygonState& state, const DrawInput& input,
                  std::span<const uint32_t> contour_sizes, const TriangleDraw& triangles,
                  const ScanlineDraw& scanline, Counters& counters);

// The reference rasterizer's scanline fill, for ScanlineDraw.
void draw_reference_scanline_polygon(detail::FramebufferStorage& fb, const PipelineState& pipeline,
                                     const std::vector<std::vector<WindowPoint>>& contours,
                                     FillRule rule, Counters& counters);

}  // namespace tessera
