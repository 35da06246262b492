// The SIMD block kernel: rasterizes one triangle over one 8x8-pixel block of one tile, all
// samples, with the early depth test, shading once per pixel and the colour write. Written once
// against Highway and compiled for every target (block_kernel.cpp); a draw picks the instance
// for its target and state, so a depth-only draw touches no colour and a 1-sample draw tests no
// sample masks (ARCHITECTURE.md section 5).
#pragma once

#include <array>
#include <cstdint>

#include "tessera/pipeline.hpp"

namespace tessera::fast {

// 32-bit stepping bound. Inside a block the kernel evaluates only edges that cross the block,
// so each evaluated edge is zero somewhere in the block's sample region, whose side is
// 8 px = 2^(bits+3) fixed-point units. Then |E| <= (|a| + |b|) * 2^(bits+3) at every sample
// of the block, and every partial sum the kernel forms is E at some point of that region. With
// |a| + |b| < 2^(28-bits), |E| < 2^31: exact in int32 lanes. A triangle with a longer edge
// (over 4096 px at 8 bits) takes the wide path: coverage from exact int64 edge functions.
constexpr int64_t narrow_edge_limit(uint32_t subpixel_bits) {
  return int64_t{1} << (28 - subpixel_bits);
}

enum class DepthMode : uint8_t {
  kOff,        // no depth test, no depth write
  kTest,       // test, no write
  kTestWrite,  // test and write passing samples
  kWrite,      // write without reading (Hi-Z proved every sample passes)
};
inline constexpr int kDepthModes = 4;

enum class ColorMode : uint8_t { kOff, kRGBA8, kRGBA32F };
inline constexpr int kColorModes = 3;

// Per-draw constants.
struct KernelConstants {
  uint32_t samples = 1;
  CompareOp compare = CompareOp::kLess;
  bool perspective = true;
  // Sample offsets from the pixel centre, in fixed point and in pixels.
  std::array<int32_t, 16> sample_x{}, sample_y{};
  std::array<float, 16> sample_fx{}, sample_fy{};
};

// One triangle over one block.
struct BlockJob {
  uint32_t edge_mask = 0;  // edges to test (bit k = edge k); 0: the block is inside all three
  uint32_t cols = 8;       // pixels of the block inside the framebuffer (edge blocks have fewer)
  uint32_t rows = 8;
  // Edge functions at the centre of the block's first pixel (bias included), their steps per
  // pixel (a << bits, b << bits) and per fixed-point unit (for the sample offsets).
  std::array<int32_t, 3> e{}, step_x{}, step_y{}, a{}, b{};
  // Wide path: per-pixel sample coverage bits computed in int64, replacing the edge tests.
  const uint32_t* coverage = nullptr;
  // Planes at the centre of the block's first pixel, gradients per pixel.
  float z = 0, z_dx = 0, z_dy = 0;
  float q = 1, q_dx = 0, q_dy = 0;
  std::array<float, 4> qa{}, qa_dx{}, qa_dy{};
  // Sample 0 of this block in the tile's storage; sample s lies kTilePixels values further.
  float* depth = nullptr;
  uint8_t* rgba8 = nullptr;   // 4 bytes per pixel (R, G, B, A)
  float* rgba32f = nullptr;   // 4 floats per pixel
};

struct BlockStats {
  uint32_t covered = 0;
  uint32_t passed = 0;
  uint32_t shaded = 0;
  bool depth_written = false;
  float z_min = 0, z_max = 0;  // over every sample of the block, when depth_written
};

using BlockKernel = void (*)(const KernelConstants&, const BlockJob&, BlockStats&);

struct KernelTable {
  BlockKernel kernels[kDepthModes][kColorModes][2];  // [depth][colour][multisample]
};

// The kernels compiled for a Highway target bit (see simd/dispatch.hpp).
const KernelTable& kernel_table(int64_t target);

inline BlockKernel block_kernel(const KernelTable& table, DepthMode depth, ColorMode color,
                                bool multisample) {
  return table.kernels[static_cast<int>(depth)][static_cast<int>(color)][multisample ? 1 : 0];
}

}  // namespace tessera::fast
