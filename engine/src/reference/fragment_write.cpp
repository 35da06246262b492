// Depth test, depth write and colour store or blend of one fragment (fragment_write.hpp).
// Blending follows OpenGL's SRC_ALPHA, ONE_MINUS_SRC_ALPHA for colour and ONE,
// ONE_MINUS_SRC_ALPHA for alpha (Porter and Duff 1984, "over"), computed in float and stored
// as the colour buffer's format stores any colour (to_unorm8 for RGBA8).
#include "engine/src/reference/fragment_write.hpp"

#include <algorithm>

#include "engine/src/sample_positions.hpp"

namespace tessera::reference {

void write_fragment(detail::FramebufferStorage& fb, const PipelineState& pipeline,
                    const Fragment& f, bool blend, Counters& counters) {
  if (!(f.coverage > 0.0f)) return;
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
    std::array<float, 4> out = f.color;
    if (blend) {
      const float a = std::clamp(f.color[3], 0.0f, 1.0f) * std::min(f.coverage, 1.0f);
      std::array<float, 4> dst;
      for (int c = 0; c < 4; ++c) {
        dst[c] = fb.desc.color_format == ColorFormat::kRGBA8 ? fb.rgba8[index * 4 + c] / 255.0f
                                                             : fb.rgba32f[index * 4 + c];
      }
      for (int c = 0; c < 3; ++c)
        out[c] = f.color[c] * a + dst[c] * (1.0f - a);
      out[3] = a + dst[3] * (1.0f - a);
    }
    if (fb.desc.color_format == ColorFormat::kRGBA8) {
      for (int c = 0; c < 4; ++c)
        fb.rgba8[index * 4 + c] = to_unorm8(out[c]);
    } else {
      for (int c = 0; c < 4; ++c)
        fb.rgba32f[index * 4 + c] = out[c];
    }
  }
  if (any && pipeline.color_write) ++counters.pixels_shaded;
}

}  // namespace tessera::reference
