// Polygons in the reference rasterizer by the lectures' scanline fill (PolygonMethod::kScanline).
#pragma once

#include <vector>

#include "engine/src/framebuffer_storage.hpp"
#include "engine/src/line_clip.hpp"
#include "tessera/pipeline.hpp"
#include "tessera/primitives.hpp"
#include "tessera/renderer.hpp"

namespace tessera::reference {

// Fills the polygon whose contours (window space, already clipped) are given, with the fill
// rule, in the colour of `color` and the depth of the polygon's Newell plane.
void draw_scanline_polygon(detail::FramebufferStorage& fb, const PipelineState& pipeline,
                           const std::vector<std::vector<WindowPoint>>& contours, FillRule rule,
                           Counters& counters);

}  // namespace tessera::reference
