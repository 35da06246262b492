// The scalar reference rasterizer (ARCHITECTURE.md section 3): the oracle that every faster
// path is tested against, selectable by users as Backend::kReference.
#pragma once

#include "engine/src/framebuffer_storage.hpp"
#include "tessera/pipeline.hpp"
#include "tessera/renderer.hpp"

namespace tessera::reference {

// Draws a triangle list that has already been validated (see draw_validation.hpp).
void draw(detail::FramebufferStorage& target, const PipelineState& pipeline, const DrawInput& input,
          Counters& counters);

}  // namespace tessera::reference
