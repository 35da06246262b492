// Rasterization of one screen tile: every binned triangle in submission order, through the
// hierarchy tile -> 8x8 block (corner tests of the edge functions: trivial reject, trivial
// accept, partial), the Hi-Z test per block, then the SIMD block kernel.
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

struct TileDrawState {
  detail::FramebufferStorage* fb = nullptr;
  uint32_t subpixel_bits = 8;
  KernelConstants constants;
  BlockKernel kernel = nullptr;         // the draw's state
  BlockKernel accept_kernel = nullptr;  // DepthMode::kWrite: blocks Hi-Z proved all-passing
  bool hiz = false;                     // Hi-Z reject/accept in use for this draw
  CompareOp compare = CompareOp::kLess;
  bool depth_write = false;
};

void raster_tile(const TileDrawState& state, uint32_t tile, std::span<const ChunkView> chunks,
                 Counters& counters);

}  // namespace tessera::fast
