// Validation of a draw call's state and vertex data, done before anything is drawn, so that a
// bad call leaves the framebuffer untouched and says exactly what was wrong.
#pragma once

#include "tessera/framebuffer.hpp"
#include "tessera/pipeline.hpp"
#include "tessera/renderer.hpp"

namespace tessera {

// Throws Error(kInvalidArgument) for pipeline state that is out of range or does not fit the
// framebuffer, Error(kInvalidInput) for inconsistent sizes, an index out of range, or a
// position or attribute that is NaN or infinite.
void validate_draw(const Framebuffer& target, const PipelineState& pipeline,
                   const DrawInput& input);

}  // namespace tessera
