// refresh_dirty_hiz (hiz.hpp): every dirty block's bounds through the kernel table.
#include "engine/src/fast/hiz.hpp"

#include <algorithm>
#include <limits>

#include "engine/src/fast/block_kernel.hpp"

namespace tessera::fast {

void invalidate_hiz(detail::FramebufferStorage& fb) {
  std::fill(fb.hiz_min.begin(), fb.hiz_min.end(), std::numeric_limits<float>::infinity());
  std::fill(fb.hiz_max.begin(), fb.hiz_max.end(), -std::numeric_limits<float>::infinity());
  fb.hiz_valid = true;
}

void refresh_dirty_hiz(const KernelTable& table, detail::FramebufferStorage& fb) {
  if (!fb.hiz_valid) invalidate_hiz(fb);
  const uint32_t samples = fb.desc.samples;
  for (uint32_t tile = 0; tile < fb.grid.tile_count(); ++tile) {
    const float* depth = fb.depth.data() + size_t{tile} * samples * binning::kTilePixels;
    for (uint32_t b = 0; b < detail::kBlocksPerTile; ++b) {
      const size_t block = size_t{tile} * detail::kBlocksPerTile + b;
      if (!hiz_dirty(fb.hiz_min[block], fb.hiz_max[block])) continue;
      table.refresh_hiz_block(depth + size_t{b} * detail::kBlockPixels, samples, fb.hiz_min[block],
                              fb.hiz_max[block]);
    }
  }
}

}  // namespace tessera::fast
