// Depth test, depth write and colour store or blend of one fragment (fragment_write.hpp).
// Blending (blend/blend.hpp): the pipeline's blend state, or for antialiased fragments under a
// state that only stores, OpenGL's SRC_ALPHA, ONE_MINUS_SRC_ALPHA for colour and ONE,
// ONE_MINUS_SRC_ALPHA for alpha (Porter and Duff 1984, "over"), computed in float and stored
// as the colour buffer's format stores any colour (to_unorm8 for RGBA8).
#include "engine/src/reference/fragment_write.hpp"

#include <algorithm>

#include "engine/src/blend/blend.hpp"
#include "engine/src/sample_positions.hpp"
#include "engine/src/scissor.hpp"

namespace tessera::reference {

void write_fragment(detail::FramebufferStorage& fb, const PipelineState& pipeline,
                    const Fragment& f, bool blend, Counters& counters) {
  if (!(f.coverage > 0.0f)) return;
  if (pipeline.scissor_test &&
      !draw_box(pipeline, fb.desc.width, fb.desc.height).contains(f.x, f.y)) {
    return;
  }
  const uint32_t samples = fb.desc.samples;
  const auto pattern = sample_pattern(samples);
  const double depth_scale = detail::depth_scale(fb.desc.depth_format);
  bool any = false;
  for (uint32_t s = 0; s < samples; ++s) {
    if (!(f.sample_mask & (1u << s))) continue;
    // The plane at the sample, clamped to [0, 1], stored as the depth format stores it.
    const float depth = detail::encode_depth(
        std::clamp(f.depth + f.dz_dx * (pattern[s].dx / 16.0f) + f.dz_dy * (pattern[s].dy / 16.0f),
                   0.0f, 1.0f),
        depth_scale);
    ++counters.samples_covered;
    const size_t index = fb.sample_index(f.x, f.y, s);
    if (pipeline.depth_test) {
      if (!detail::depth_passes(pipeline.depth_compare, depth, fb.depth[index])) continue;
      if (pipeline.depth_write) fb.depth[index] = depth;
    }
    ++counters.samples_passed;
    any = true;
    if (!pipeline.color_write) continue;
    const bool rgba8 = fb.desc.color_format == ColorFormat::kRGBA8;
    if (blend::write_primitive_sample(pipeline, f.color, f.coverage, blend,
                                      rgba8 ? fb.rgba8.data() + index * 4 : nullptr,
                                      rgba8 ? nullptr : fb.rgba32f.data() + index * 4)) {
      continue;
    }
    for (int c = 0; c < 4; ++c) {
      if (rgba8) {
        fb.rgba8[index * 4 + c] = to_unorm8(f.color[c]);
      } else {
        fb.rgba32f[index * 4 + c] = f.color[c];
      }
    }
  }
  if (any && pipeline.color_write) ++counters.pixels_shaded;
}

}  // namespace tessera::reference
