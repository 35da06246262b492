// Tile traversal for the fast engine: the tile's storage is located once, then its bins are
// read in worker order (submission order) and each triangle goes to the raster kernel.
#include "engine/src/fast/tile_raster.hpp"

#include <algorithm>

namespace tessera::fast {

void raster_tile(const TileContext& draw, TriangleKernel kernel, detail::FramebufferStorage& fb,
                 uint32_t tile, std::span<const ChunkView> chunks, Counters& counters) {
  TileContext tc = draw;
  tc.x0 = static_cast<int32_t>((tile % fb.grid.tiles_x) * binning::kTileSize);
  tc.y0 = static_cast<int32_t>((tile / fb.grid.tiles_x) * binning::kTileSize);
  tc.x1 = std::min<int32_t>(tc.x0 + binning::kTileSize, fb.desc.width) - 1;
  tc.y1 = std::min<int32_t>(tc.y0 + binning::kTileSize, fb.desc.height) - 1;
  const size_t base = size_t{tile} * fb.desc.samples * binning::kTilePixels;
  tc.depth = fb.depth.data() + base;
  tc.rgba8 = fb.rgba8.empty() ? nullptr : fb.rgba8.data() + base * 4;
  tc.rgba32f = fb.rgba32f.empty() ? nullptr : fb.rgba32f.data() + base * 4;
  tc.hiz_min = fb.hiz_min.data() + size_t{tile} * detail::kBlocksPerTile;
  tc.hiz_max = fb.hiz_max.data() + size_t{tile} * detail::kBlocksPerTile;

  for (const ChunkView& chunk : chunks) {
    const std::span<const uint32_t> list = chunk.bins->tile(tile);
    for (size_t n = 0; n < list.size(); ++n) {
      // Setups were written long before this tile reads them: fetch a few ahead.
      if (n + 4 < list.size()) {
        const char* ahead = reinterpret_cast<const char*>(&chunk.setups[list[n + 4]]);
        for (size_t line = 0; line < sizeof(TriangleSetup); line += 64) {
          __builtin_prefetch(ahead + line);
        }
      }
      kernel(tc, chunk.setups[list[n]], counters);
    }
  }
}

}  // namespace tessera::fast
