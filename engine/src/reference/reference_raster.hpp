// The scalar reference rasterizer (ARCHITECTURE.md section 3): the oracle that every faster
// path is tested against, selectable by users as Backend::kReference.
#pragma once

#include <cstdint>
#include <span>

#include "engine/src/framebuffer_storage.hpp"
#include "tessera/pipeline.hpp"
#include "tessera/renderer.hpp"

namespace tessera::reference {

// Draws a triangle list that has already been validated (see draw_validation.hpp).
// TargetOutput::kPrimitiveId writes primitive_ids[t] for triangle t of the input, or t when
// primitive_ids is empty (a draw the renderer cut to its finite triangles passes their
// indices in the caller's draw). Every colour target is written, or only target 0 without
// all_targets (the triangles of points, lines and polygons).
void draw(detail::FramebufferStorage& target, const PipelineState& pipeline, const DrawInput& input,
          Counters& counters, std::span<const uint32_t> primitive_ids = {},
          bool all_targets = true);

}  // namespace tessera::reference
