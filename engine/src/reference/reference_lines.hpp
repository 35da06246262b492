// The reference rasterizer's lines that are not drawn as triangles: one-pixel lines by the
// diamond-exit rule, midpoint/Bresenham or DDA, and antialiased lines, with stipple, depth
// test and colour and depth interpolated along the line (docs/PRIMITIVES.md).
#pragma once

#include <span>

#include "engine/src/framebuffer_storage.hpp"
#include "engine/src/primitive_assembly.hpp"
#include "tessera/pipeline.hpp"
#include "tessera/primitives.hpp"
#include "tessera/renderer.hpp"

namespace tessera::reference {

// Draws assembled segments (width 1 with state.algorithm, or antialiased with state.width).
void draw_thin_lines(detail::FramebufferStorage& fb, const PipelineState& pipeline,
                     const LineState& state, std::span<const WindowSegment> segments,
                     Counters& counters);

// Whether bit (s / factor) % 16 of the stipple pattern is set.
inline bool stipple_on(const LineStipple& stipple, uint32_t s) {
  return (stipple.pattern >> ((s / stipple.factor) % 16)) & 1u;
}

}  // namespace tessera::reference
