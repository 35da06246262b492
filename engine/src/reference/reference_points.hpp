// Round, antialiased points in the reference rasterizer (PointShape::kRound).
#pragma once

#include <span>

#include "engine/src/framebuffer_storage.hpp"
#include "engine/src/line_clip.hpp"
#include "tessera/pipeline.hpp"
#include "tessera/renderer.hpp"

namespace tessera::reference {

// Each pixel within size/2 + 1/2 of a point gets coverage clamp(size/2 + 1/2 - d, 0, 1), d
// the distance from the pixel centre to the point, blended source-over with the point's
// colour; depth is the point's, tested and written for every sample of the pixel.
void draw_round_points(detail::FramebufferStorage& fb, const PipelineState& pipeline,
                       std::span<const WindowPoint> points, float size, Counters& counters);

}  // namespace tessera::reference
