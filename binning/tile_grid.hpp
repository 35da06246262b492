// The screen tile grid: how a framebuffer is cut into square tiles.
// Tiles are the unit of storage (each tile's samples are contiguous, so one tile's
// rasterization touches one compact block of memory) and, in the binned engine, of work.
#pragma once

#include <cstdint>

namespace tessera::binning {

// 64x64 pixels (default, ARCHITECTURE.md section 1): a tile of float depth at 1 sample is
// 16 KiB and stays in L1/L2 while the tile is rasterized.
inline constexpr uint32_t kTileSizeLog2 = 6;
inline constexpr uint32_t kTileSize = 1u << kTileSizeLog2;
inline constexpr uint32_t kTilePixels = kTileSize * kTileSize;

struct TileGrid {
  uint32_t width = 0;    // pixels
  uint32_t height = 0;   // pixels
  uint32_t tiles_x = 0;  // ceil(width / kTileSize)
  uint32_t tiles_y = 0;  // ceil(height / kTileSize)

  static constexpr TileGrid for_size(uint32_t width, uint32_t height) {
    return {width, height, (width + kTileSize - 1) >> kTileSizeLog2,
            (height + kTileSize - 1) >> kTileSizeLog2};
  }
  constexpr uint32_t tile_count() const { return tiles_x * tiles_y; }
  constexpr uint32_t tile_of(uint32_t x, uint32_t y) const {
    return (y >> kTileSizeLog2) * tiles_x + (x >> kTileSizeLog2);
  }
};

}  // namespace tessera::binning
