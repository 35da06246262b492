// Rasterization of one screen tile: every binned triangle in submission order, handed to the
// draw's raster kernel (block_kernel.hpp), which walks the tile's 8x8 blocks under it.
#pragma once

#include <cstdint>
#include <span>

#include "binning/bins.hpp"
#include "engine/src/fast/block_kernel.hpp"
#include "engine/src/fast/triangle_setup.hpp"
#include "engine/src/framebuffer_storage.hpp"

namespace tessera::fast {

// One setup worker's output: its triangles (setups, and pixel or sample records) and its bins.
struct ChunkView {
  const TriangleSetup* setups = nullptr;
  const PixelRecord* pixels = nullptr;
  const SampleRecord* samples = nullptr;
  const binning::Bins* bins = nullptr;
};

// The bin tiles a draw's triangles are sorted into: squares of 2^size_log2 pixels (32, 64 or
// 128, RendererOptions::bin_tile_size), aligned to the framebuffer's 64x64 storage tiles, so a
// bin tile lies inside one storage tile or covers whole ones.
struct BinGrid {
  uint32_t size_log2 = binning::kTileSizeLog2;
  uint32_t tiles_x = 0, tiles_y = 0;

  static BinGrid for_size(uint32_t width, uint32_t height, uint32_t size_log2) {
    const uint32_t size = 1u << size_log2;
    return {size_log2, (width + size - 1) >> size_log2, (height + size - 1) >> size_log2};
  }
  uint32_t tile_count() const { return tiles_x * tiles_y; }
};

// Rasterizes bin tile `tile`: for each storage tile it overlaps, every binned triangle in
// submission order. `draw` holds the per-draw fields of TileContext; pixel records go to
// `pixel_kernel`, and with a non-null `sample_kernel` (a multisample draw) the records are
// sample records and go there.
void raster_tile(const TileContext& draw, TriangleKernel kernel, PixelKernel pixel_kernel,
                 SampleKernel sample_kernel, detail::FramebufferStorage& fb, const BinGrid& bins,
                 uint32_t tile, std::span<const ChunkView> chunks, Counters& counters);

}  // namespace tessera::fast
