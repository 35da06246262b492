// The fast engine's scanline polygon fill (PolygonMethod::kScanline): the polygon's tiles are
// filled in parallel, each from the crossings of its own rows of samples.
#pragma once

#include <vector>

#include <tbb/task_arena.h>

#include "engine/src/framebuffer_storage.hpp"
#include "engine/src/line_clip.hpp"
#include "tessera/pipeline.hpp"
#include "tessera/primitives.hpp"
#include "tessera/renderer.hpp"

namespace tessera::fast {

// Fills the clipped contours exactly as reference::draw_scanline_polygon does (same bytes).
void draw_scanline_polygon(tbb::task_arena& arena, detail::FramebufferStorage& fb,
                           const PipelineState& pipeline,
                           const std::vector<std::vector<WindowPoint>>& contours, FillRule rule,
                           Counters& counters);

}  // namespace tessera::fast
