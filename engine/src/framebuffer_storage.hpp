// Internal view of a framebuffer's storage, shared by the rasterizers and the resolve.
// Layout: tiles in row-major order; inside a tile, one 64x64 plane per sample; inside a
// plane, pixels row-major. A tile's samples are therefore contiguous, and one sample's pixels
// within a tile are a dense 64x64 array that SIMD kernels can step through.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "binning/tile_grid.hpp"
#include "tessera/framebuffer.hpp"

namespace tessera {

namespace detail {

struct FramebufferStorage {
  FramebufferDesc desc;
  binning::TileGrid grid;
  std::vector<uint8_t> rgba8;  // 4 per sample, when desc.color_format == kRGBA8
  std::vector<float> rgba32f;  // 4 per sample, when desc.color_format == kRGBA32F
  std::vector<float> depth;    // 1 per sample

  size_t sample_index(uint32_t x, uint32_t y, uint32_t s) const {
    const size_t tile = grid.tile_of(x, y);
    const size_t in_tile = ((y & (binning::kTileSize - 1)) << binning::kTileSizeLog2) |
                           (x & (binning::kTileSize - 1));
    return (tile * desc.samples + s) * binning::kTilePixels + in_tile;
  }
};

struct FramebufferAccess {
  static FramebufferStorage& storage(Framebuffer& fb) { return *fb.storage_; }
  static const FramebufferStorage& storage(const Framebuffer& fb) { return *fb.storage_; }
};
}  // namespace detail

}  // namespace tessera
