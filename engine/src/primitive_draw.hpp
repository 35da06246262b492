// Drawing points, lines and polygons (Renderer::draw_points, draw_lines, draw_polygon): each
// draw is assembled and clipped once, then goes either to the triangle pipeline of the
// renderer's backend (square points, wide lines, tessellated polygons) or to the per-pixel
// rasterizers of engine/src/reference/ (one-pixel, antialiased and scanline primitives).
#pragma once

#include <cstdint>
#include <functional>
#include <span>

#include "engine/src/framebuffer_storage.hpp"
#include "tessera/pipeline.hpp"
#include "tessera/primitives.hpp"
#include "tessera/renderer.hpp"

namespace tessera {

// Draws a validated triangle list with the renderer's backend.
using TriangleDraw = std::function<void(const PipelineState&, const DrawInput&)>;

// Each draws a validated draw (draw_validation.hpp).
void draw_points(detail::FramebufferStorage& fb, const PipelineState& pipeline,
                 const PointState& state, const DrawInput& input, const TriangleDraw& triangles,
                 Counters& counters);
void draw_lines(detail::FramebufferStorage& fb, const PipelineState& pipeline,
                const LineState& state, const DrawInput& input, const TriangleDraw& triangles,
                Counters& counters);
void draw_polygon(detail::FramebufferStorage& fb, const PipelineState& pipeline,
                  const PolygonState& state, const DrawInput& input,
                  std::span<const uint32_t> contour_sizes, const TriangleDraw& triangles,
                  Counters& counters);

}  // namespace tessera
