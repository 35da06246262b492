// Rasterization of one screen tile: every binned triangle in submission order, handed to the
// draw's raster kernel (block_kernel.hpp), which walks the tile's 8x8 blocks under it.
#pragma once

#include <cstdint>
#include <span>

#include "binning/bins.hpp"
#include "binning/tile_grid.hpp"
#include "engine/src/fast/block_kernel.hpp"
#include "engine/src/fast/triangle_setup.hpp"
#include "engine/src/framebuffer_storage.hpp"

namespace tessera::fast {

// One setup worker's output: its triangles (setups, and pixel or sample records) and its bins.
struct ChunkView {
  const TriangleSetup* setups = nullptr;
  const float* planes = nullptr;  // a shaded draw's (TileContext::layout), else null
  const PixelRecord* pixels = nullptr;
  const SampleRecord* samples = nullptr;
  const binning::Bins* bins = nullptr;
};

// Rasterizes bin tile `tile` of `bins`, the grid a draw's triangles are sorted into: squares of
// 32, 64 or 128 pixels (RendererOptions::bin_tile_size), aligned to the framebuffer's 64x64
// storage tiles, so a bin tile lies inside one storage tile or covers whole ones: for each storage
// tile it overlaps, every binned triangle in submission order. `draw` holds the per-draw fields of
// TileContext; pixel records go to `pixel_kernel`, and with a non-null `sample_kernel` (a
// multisample draw) the records are sample records and go there.
void raster_tile(const TileContext& draw, TriangleKernel kernel, PixelKernel pixel_kernel,
                 SampleKernel sample_kernel, detail::FramebufferStorage& fb,
                 const binning::TileGrid& bins, uint32_t tile, std::span<const ChunkView> chunks,
                 Counters& counters);

}  // namespace tessera::fast
