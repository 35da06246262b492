// Fragment writes for the fast engine's per-pixel primitives (one-pixel and antialiased lines,
// round points): depth test and write per sample, colour store or blend (blend/blend.hpp),
// exactly as the reference's fragment_write.cpp computes them (same operations, same bytes), with
// the Hi-Z bounds of every block a fragment writes depth to marked stale.
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <limits>

#include "engine/src/blend/blend.hpp"
#include "engine/src/framebuffer_storage.hpp"
#include "engine/src/sample_positions.hpp"
#include "engine/src/scissor.hpp"
#include "tessera/pipeline.hpp"
#include "tessera/renderer.hpp"

namespace tessera::fast {

// One tile's writer: counters are the tile's own, so tiles write in parallel.
struct TileWriter {
  detail::FramebufferStorage& fb;
  const PipelineState& pipeline;
  bool blend;
  Counters& counters;
  PixelBox box = draw_box(pipeline, fb.desc.width, fb.desc.height);  // the scissor test
  bool plain_rgba8 = fb.desc.samples == 1 && !pipeline.depth_test && !blend &&
                     pipeline.blend[0].replaces() && pipeline.color_write &&
                     fb.desc.color_format == ColorFormat::kRGBA8;

  // Depth test and write for the samples of `mask`, then the colour store or blend. A sample's
  // depth is the plane depth_in + dz_dx x + dz_dy y at its offset from the pixel centre.
  void write(int64_t px, int64_t py, float depth_in, const std::array<float, 4>& color,
             float coverage, uint32_t mask = 0xFFFFu, float dz_dx = 0.0f, float dz_dy = 0.0f) {
    if (!(coverage > 0.0f)) return;
    if (pipeline.scissor_test && !box.contains(px, py)) return;
    const uint32_t x = static_cast<uint32_t>(px), y = static_cast<uint32_t>(py);
    if (plain_rgba8 && (mask & 1u)) {  // the common case: one sample, no depth test, no blend
      uint8_t* p = fb.rgba8.data() + fb.sample_index(x, y, 0) * 4;
      for (int c = 0; c < 4; ++c)
        p[c] = to_unorm8(color[c]);
      ++counters.samples_covered;
      ++counters.samples_passed;
      ++counters.pixels_shaded;
      return;
    }
    if (plain_rgba8) return;  // sample 0 not in the mask
    const auto pattern = sample_pattern(fb.desc.samples);
    const double depth_scale = detail::depth_scale(fb.desc.depth_format);
    bool any = false, wrote_depth = false;
    for (uint32_t s = 0; s < fb.desc.samples; ++s) {
      if (!(mask & (1u << s))) continue;
      const float depth = detail::encode_depth(
          std::clamp(depth_in + dz_dx * (pattern[s].dx / 16.0f) + dz_dy * (pattern[s].dy / 16.0f),
                     0.0f, 1.0f),
          depth_scale);
      ++counters.samples_covered;
      const size_t index = fb.sample_index(x, y, s);
      if (pipeline.depth_test) {
        if (!detail::depth_passes(pipeline.depth_compare, depth, fb.depth[index])) continue;
        if (pipeline.depth_write) {
          fb.depth[index] = depth;
          wrote_depth = true;
        }
      }
      ++counters.samples_passed;
      any = true;
      if (!pipeline.color_write) continue;
      const bool rgba8 = fb.desc.color_format == ColorFormat::kRGBA8;
      if (blend::write_primitive_sample(pipeline, color, coverage, blend,
                                        rgba8 ? fb.rgba8.data() + index * 4 : nullptr,
                                        rgba8 ? nullptr : fb.rgba32f.data() + index * 4)) {
        continue;
      }
      for (int c = 0; c < 4; ++c) {
        if (rgba8) {
          fb.rgba8[index * 4 + c] = to_unorm8(color[c]);
        } else {
          fb.rgba32f[index * 4 + c] = color[c];
        }
      }
    }
    if (any && pipeline.color_write) ++counters.pixels_shaded;
    if (wrote_depth && fb.hiz_valid) {
      // The block's Hi-Z bounds are stale: mark them for recomputation (block_kernel.cpp).
      const size_t block =
          size_t{fb.grid.tile_of(x, y)} * detail::kBlocksPerTile +
          ((y & (binning::kTileSize - 1)) >> detail::kBlockSizeLog2) * detail::kBlocksPerTileSide +
          ((x & (binning::kTileSize - 1)) >> detail::kBlockSizeLog2);
      fb.hiz_min[block] = std::numeric_limits<float>::infinity();
      fb.hiz_max[block] = -std::numeric_limits<float>::infinity();
    }
  }
};

}  // namespace tessera::fast
