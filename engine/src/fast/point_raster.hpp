// The fast engine's round points: set up and binned to tiles by chunks of the draw in
// parallel, then each tile draws its points in submission order, tiles in parallel.
#pragma once

#include <span>

#include <tbb/task_arena.h>

#include "engine/src/framebuffer_storage.hpp"
#include "engine/src/line_clip.hpp"
#include "tessera/pipeline.hpp"
#include "tessera/renderer.hpp"

namespace tessera::fast {

// Draws round points exactly as reference::draw_round_points does (same bytes).
void draw_round_points(tbb::task_arena& arena, detail::FramebufferStorage& fb,
                       const PipelineState& pipeline, std::span<const WindowPoint> points,
                       float size, Counters& counters);

}  // namespace tessera::fast
