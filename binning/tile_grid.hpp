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

// A grid of square tiles of 2^size_log2 pixels over a width x height image, aligned to its
// top-left corner. The framebuffer's storage grid has kTileSize tiles; a draw's bin grid may
// have 32, 64 or 128 (RendererOptions::bin_tile_size), lines bin to 128.
struct TileGrid {
  uint32_t width = 0;                  // pixels
  uint32_t height = 0;                 // pixels
  uint32_t size_log2 = kTileSizeLog2;  // a tile is 2^size_log2 pixels on a side
  uint32_t tiles_x = 0;                // ceil(width / tile_size())
  uint32_t tiles_y = 0;                // ceil(height / tile_size())

  static constexpr TileGrid for_size(uint32_t width, uint32_t height,
                                     uint32_t size_log2 = kTileSizeLog2) {
    const uint32_t size = 1u << size_log2;
    return {width, height, size_log2, (width + size - 1) >> size_log2,
            (height + size - 1) >> size_log2};
  }
  constexpr uint32_t tile_size() const { return 1u << size_log2; }
  constexpr uint32_t tile_count() const { return tiles_x * tiles_y; }
  constexpr uint32_t tile_of(uint32_t x, uint32_t y) const {
    return (y >> size_log2) * tiles_x + (x >> size_log2);
  }
  // The pixel coordinates of a tile's top-left corner.
  constexpr uint32_t tile_x0(uint32_t tile) const { return (tile % tiles_x) << size_log2; }
  constexpr uint32_t tile_y0(uint32_t tile) const { return (tile / tiles_x) << size_log2; }
};

}  // namespace tessera::binning
