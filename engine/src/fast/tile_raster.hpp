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

// One setup worker's output: its triangles and its bins.
struct ChunkView {
  const TriangleSetup* setups = nullptr;
  const binning::Bins* bins = nullptr;
};

// `draw` holds the per-draw fields of TileContext; raster_tile fills in the tile's own.
void raster_tile(const TileContext& draw, TriangleKernel kernel, detail::FramebufferStorage& fb,
                 uint32_t tile, std::span<const ChunkView> chunks, Counters& counters);

}  // namespace tessera::fast
