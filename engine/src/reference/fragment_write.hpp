// Fragment output for the primitives that are not drawn as triangles (thin and antialiased
// lines, round points, scanline polygons): depth test and write for every sample of the pixel,
// then the colour store, or for antialiased fragments a source-over blend of the colour with
// alpha scaled by the pixel's coverage (what glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA)
// does for GL's smooth points and lines).
#pragma once

#include <array>
#include <cstdint>

#include "engine/src/framebuffer_storage.hpp"
#include "tessera/pipeline.hpp"
#include "tessera/renderer.hpp"

namespace tessera::reference {

struct Fragment {
  uint32_t x = 0, y = 0;       // pixel, inside the framebuffer
  float depth = 0;             // z/w in [0, 1] at the pixel centre
  float dz_dx = 0, dz_dy = 0;  // per pixel: a sample's depth is the plane at its position
  std::array<float, 4> color{0, 0, 0, 1};
  // 1 for aliased fragments (colour stored); below 1 the colour is blended with its alpha
  // multiplied by `coverage`. A fragment with coverage 0 is never written.
  float coverage = 1;
  // Samples the fragment covers (bit s = sample s); all of them for pixel-sized primitives.
  uint32_t sample_mask = 0xFFFFu;
};

// Writes one fragment under the pipeline's depth and colour state; counts samples covered and
// passed and pixels shaded. `blend` selects the source-over blend even at full coverage.
void write_fragment(detail::FramebufferStorage& fb, const PipelineState& pipeline,
                    const Fragment& f, bool blend, Counters& counters);

}  // namespace tessera::reference
