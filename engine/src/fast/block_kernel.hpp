// The SIMD raster kernel: one triangle over the 8x8-pixel blocks it touches in one tile, with
// the hierarchical block tests, Hi-Z, per-sample coverage, the early depth test, shading once
// per pixel and the colour write. Written once against Highway (block_kernel-inl.h) and
// compiled for every target, one source per depth mode (block_kernel_depth_*.cpp); a draw picks
// the instance for its target and state from block_kernel.cpp's table, so a depth-only draw
// touches no colour and a 1-sample draw tests no sample masks (ARCHITECTURE.md section 5).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <limits>

#include "binning/tile_grid.hpp"

#include "engine/src/blend/blend.hpp"
#include "engine/src/fast/pixel_record.hpp"
#include "engine/src/fast/triangle_setup.hpp"
#include "engine/src/scissor.hpp"
#include "engine/src/shade/layout.hpp"
#include "tessera/pipeline.hpp"
#include "tessera/renderer.hpp"

namespace tessera::shade {
class UserBatch;
}  // namespace tessera::shade

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
};
inline constexpr int kDepthModes = 3;

enum class ColorMode : uint8_t { kOff, kRGBA8, kRGBA32F };
inline constexpr int kColorModes = 3;

// Per-draw constants and the tile being drawn.
struct TileContext {
  uint32_t samples = 1;
  uint32_t subpixel_bits = 8;
  CompareOp compare = CompareOp::kLess;
  bool hiz = false;  // Hi-Z reject/accept (the compare op is one of <, <=, >, >=)
  // 8x8 blocks per side of the coarse blocks the corner test classifies before their blocks
  // (RendererOptions::block_size / 8): 1, 2 or 4.
  uint32_t coarse_blocks = 1;
  bool sub_blocks = false;  // sub-block tests in partial blocks (RendererOptions::sub_block_tests)
  // Fixed-point depth formats store round(z * depth_scale); 0 for float depth.
  float depth_scale = 0.0f;
  // Sample offsets from the pixel centre, in fixed point and in pixels.
  std::array<int32_t, 16> sample_x{}, sample_y{};
  std::array<float, 16> sample_fx{}, sample_fy{};
  // sample_x and sample_y with each sample's value four times (index 4 * s + e): the kernels
  // form a sample's edge thresholds in a row of four lanes.
  alignas(64) std::array<int32_t, 64> sample_x4{}, sample_y4{};

  // The pixels the draw may write (scissor.hpp's draw_box: the framebuffer, or the scissor
  // rectangle inside it).
  PixelBox clip;
  // The region drawn: its first and last pixel (inclusive, inside the framebuffer): a bin tile
  // inside one storage tile, clipped to the draw's pixels (block-aligned except at the edges of
  // a scissor rectangle). The storage tile's first pixel and storage:
  int32_t x0 = 0, y0 = 0, x1 = 0, y1 = 0;
  int32_t tile_x0 = 0, tile_y0 = 0;
  float* depth = nullptr;    // sample plane s of block b at (s * 64 + b) * 64
  uint8_t* rgba8 = nullptr;  // 4 bytes per sample value, same layout
  float* rgba32f = nullptr;  // 4 floats per sample value, same layout
  // The extra colour targets' (FramebufferStorage::extra), same layout, in 32-bit words.
  std::array<uint32_t*, kMaxColorTargets - 1> extra{};
  float* hiz_min = nullptr;  // per block of the tile
  float* hiz_max = nullptr;

  // Colour target 0's blend state where it does not simply store the colour
  // (BlendState::replaces() false: blending or a write mask), with the draw's blend constant;
  // null otherwise. Drawn through the block and window paths and the per-pixel writer
  // (write_pixel): no pixel or sample records, which hold packed colour.
  const BlendState* blend = nullptr;
  blend::Preset blend_preset = blend::Preset::kOther;  // which usual state *blend is
  std::array<float, 4> blend_constant{};

  // A shaded draw's layout (shade/layout.hpp): its setups' planes are the floats from
  // planes + 3 * layout->count * (setup index). Null for a Gouraud draw.
  const shade::Layout* layout = nullptr;
  // A user shader's draw (shade::Shader::kUser): the tile task's batch buffers.
  shade::UserBatch* user_batch = nullptr;
};

// Values between two samples' planes in a tile's storage: sample s of pixel i of block b is
// value (s * kSamplePlane + b * 64 + i) of the tile's depth and colour arrays.
inline constexpr size_t kSamplePlane = binning::kTilePixels;

// Marks block `block`'s Hi-Z bounds stale (min > max) after its depth changed: they are
// recomputed when next needed.
inline void mark_hiz_dirty(const TileContext& tc, size_t block) {
  tc.hiz_min[block] = std::numeric_limits<float>::infinity();
  tc.hiz_max[block] = -std::numeric_limits<float>::infinity();
}

// A triangle kernel draws setup `t`, whose planes (a shaded draw's, else null) are `planes`.
using TriangleKernel = void (*)(const TileContext&, const TriangleSetup& t, const float* planes,
                                Counters&);
using PixelKernel = void (*)(const TileContext&, const PixelRecord&, Counters&);
using SampleKernel = void (*)(const TileContext&, const SampleRecord&, Counters&);

struct KernelTable {
  // [depth][colour][multisample][counting]: the Gouraud colour (shade::Shader::kGouraud).
  TriangleKernel kernels[kDepthModes][kColorModes][2][2];
  // [shader][depth][colour][multisample][counting] for the other shaders (row kGouraud and
  // colour kOff unused: a draw without colour writes is drawn by the Gouraud kernels).
  TriangleKernel shaded_kernels[shade::kShaders][kDepthModes][kColorModes][2][2];
  // [depth][colour][counting]: one sample, and no colour or RGBA8 (null for RGBA32F).
  PixelKernel pixel_kernels[kDepthModes][kColorModes][2];
  // [depth][colour][counting]: two or four samples, and no colour or RGBA8 (null for RGBA32F).
  SampleKernel sample_kernels[kDepthModes][kColorModes][2];
  // The Hi-Z bounds of one block from its samples (hiz-inl.h's RefreshHizBlock).
  void (*refresh_hiz_block)(const float* depth, uint32_t samples, float& block_min,
                            float& block_max) = nullptr;
};

// The kernels compiled for a Highway target bit (see simd/dispatch.hpp).
const KernelTable& kernel_table(int64_t target);

inline TriangleKernel triangle_kernel(const KernelTable& table, DepthMode depth, ColorMode color,
                                      bool multisample, bool count) {
  return table.kernels[static_cast<int>(depth)][static_cast<int>(color)][multisample ? 1 : 0]
                      [count ? 1 : 0];
}

// The kernel for `shader`'s draws (shade::Layout::shader).
inline TriangleKernel triangle_kernel(const KernelTable& table, shade::Shader shader,
                                      DepthMode depth, ColorMode color, bool multisample,
                                      bool count) {
  if (shader == shade::Shader::kGouraud || color == ColorMode::kOff) {
    return triangle_kernel(table, depth, color, multisample, count);
  }
  return table.shaded_kernels[static_cast<int>(shader)][static_cast<int>(depth)]
                             [static_cast<int>(color)][multisample ? 1 : 0][count ? 1 : 0];
}

// The kernel for pixel records, or null where a draw's state has none (colour other than
// RGBA8 or none).
inline PixelKernel pixel_kernel(const KernelTable& table, DepthMode depth, ColorMode color,
                                bool count) {
  return table.pixel_kernels[static_cast<int>(depth)][static_cast<int>(color)][count ? 1 : 0];
}

// The kernel for sample records, or null where a draw's state has none.
inline SampleKernel sample_kernel(const KernelTable& table, DepthMode depth, ColorMode color,
                                  bool count) {
  return table.sample_kernels[static_cast<int>(depth)][static_cast<int>(color)][count ? 1 : 0];
}

}  // namespace tessera::fast
