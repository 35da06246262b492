// Internal view of a framebuffer's storage, shared by the rasterizers and the resolve.
// Layout: tiles in row-major order; inside a tile, one 64x64 plane per sample; inside a
// plane, 8x8-pixel blocks in row-major order, and inside a block, pixels row-major. A tile's
// samples are therefore contiguous, and one sample of one block is 64 consecutive values
// (256 bytes of depth), which SIMD kernels load and store whole.
#pragma once

#include <array>
#include <atomic>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <mutex>
#include <vector>

#include "binning/tile_grid.hpp"
#include "engine/src/aligned_allocator.hpp"
#include "engine/src/sample_positions.hpp"
#include "tessera/framebuffer.hpp"
#include "tessera/pipeline.hpp"
#include "tessera/types.hpp"

namespace tessera {

namespace detail {

// Blocks of 8x8 pixels: the unit of hierarchical rejection, Hi-Z and SIMD work.
inline constexpr uint32_t kBlockSizeLog2 = 3;
inline constexpr uint32_t kBlockSize = 1u << kBlockSizeLog2;
inline constexpr uint32_t kBlockPixels = kBlockSize * kBlockSize;
inline constexpr uint32_t kBlocksPerTileSide = binning::kTileSize / kBlockSize;
inline constexpr uint32_t kBlocksPerTile = kBlocksPerTileSide * kBlocksPerTileSide;

// Offset of pixel (x, y) inside its tile's sample plane.
constexpr uint32_t in_tile(uint32_t x, uint32_t y) {
  const uint32_t tx = x & (binning::kTileSize - 1), ty = y & (binning::kTileSize - 1);
  const uint32_t block = (ty >> kBlockSizeLog2) * kBlocksPerTileSide + (tx >> kBlockSizeLog2);
  return block * kBlockPixels + ((ty & (kBlockSize - 1)) << kBlockSizeLog2) +
         (tx & (kBlockSize - 1));
}

// Largest value of a fixed-point depth format (its steps are 1 / scale), or 0 for float depth.
constexpr double depth_scale(DepthFormat format) {
  switch (format) {
    case DepthFormat::kUnorm16:
      return 65535.0;
    case DepthFormat::kUnorm24:
      return 16777215.0;
    case DepthFormat::kFloat32:
      break;
  }
  return 0.0;
}

// Depth z in [0, 1] as the framebuffer stores it: the float itself, or the fixed-point step
// round(z * scale) (ties to even), which a float holds exactly below 2^24.
inline float encode_depth(double z, double scale) {
  return scale > 0.0 ? static_cast<float>(std::nearbyint(z * scale)) : static_cast<float>(z);
}
inline float decode_depth(float stored, double scale) {
  return scale > 0.0 ? static_cast<float>(stored / scale) : stored;
}

// The depth test of one sample: `incoming` against the `stored` value under `op` (both in the
// framebuffer's encoding, which keeps their order). Shared by every scalar writer.
inline bool depth_passes(CompareOp op, float incoming, float stored) {
  switch (op) {
    case CompareOp::kNever:
      return false;
    case CompareOp::kLess:
      return incoming < stored;
    case CompareOp::kEqual:
      return incoming == stored;
    case CompareOp::kLessEqual:
      return incoming <= stored;
    case CompareOp::kGreater:
      return incoming > stored;
    case CompareOp::kNotEqual:
      return incoming != stored;
    case CompareOp::kGreaterEqual:
      return incoming >= stored;
    case CompareOp::kAlways:
      return true;
  }
  return false;
}

// 32-bit words per sample of a colour target's format.
constexpr uint32_t words_per_sample(ColorFormat format) {
  return format == ColorFormat::kRGBA32F ? 4 : 1;
}

// An extra colour target (FramebufferDesc::extra_targets), laid out as the depth values are,
// each sample `words_per_sample` 32-bit words: RGBA8's four bytes in order, RGBA32F's four
// floats, R32F's float, R32UI's integer.
struct ExtraTarget {
  ColorFormat format = ColorFormat::kR32F;
  uint32_t words = 1;
  AlignedVector<uint32_t> data;
};

// Stores one sample's value at `at` (its first word) in `format`: RGBA from `rgba` (RGBA8
// rounded as to_unorm8 does, R32F its R), R32UI `id`. Shared by every writer of the extra
// targets.
inline void store_target_value(ColorFormat format, uint32_t* at, const float* rgba, uint32_t id) {
  switch (format) {
    case ColorFormat::kRGBA8: {
      const uint8_t bytes[4] = {to_unorm8(rgba[0]), to_unorm8(rgba[1]), to_unorm8(rgba[2]),
                                to_unorm8(rgba[3])};
      std::memcpy(at, bytes, 4);
      return;
    }
    case ColorFormat::kRGBA32F:
      std::memcpy(at, rgba, 16);
      return;
    case ColorFormat::kR32F:
      std::memcpy(at, rgba, 4);
      return;
    case ColorFormat::kR32UI:
      *at = id;
      return;
  }
}

struct FramebufferStorage {
  FramebufferDesc desc;
  binning::TileGrid grid;
  AlignedVector<uint8_t> rgba8;  // 4 per sample, when desc.color_format == kRGBA8
  AlignedVector<float> rgba32f;  // 4 per sample, when desc.color_format == kRGBA32F
  AlignedVector<float> depth;    // 1 per sample, encoded (encode_depth)
  std::array<ExtraTarget, kMaxColorTargets - 1> extra;  // the first desc.extra_targets
  // Hi-Z: the nearest and farthest depth over all samples of each 8x8 block (index
  // tile * kBlocksPerTile + block in tile). Valid only while hiz_valid; a writer that does not
  // maintain them (the reference rasterizer) clears the flag.
  std::vector<float> hiz_min;
  std::vector<float> hiz_max;
  bool hiz_valid = false;

  // Clears recorded by Framebuffer::clear_color and clear_depth but not yet written, per tile:
  // bit 0 colour, bit 1 depth (Hi-Z bounds are cleared at once). The fast triangle path writes
  // a tile's pending clears when it starts drawing that tile, in parallel and into cache, and
  // leaves those of tiles it does not draw; FramebufferAccess::storage writes all of them
  // before any other access.
  static constexpr uint8_t kColorPending = 1, kDepthPending = 2;
  std::vector<uint8_t> pending;
  // Set by the clears (the caller's exclusive access); const reads may write the pending
  // clears from several threads at once, hence the atomic flag and the lock.
  std::atomic<bool> any_pending{false};
  std::mutex pending_lock;
  std::array<uint8_t, 4> clear_rgba8{};
  std::array<float, 4> clear_rgba32f{};
  float clear_depth = 0.0f;  // encoded

  // Writes tile's pending clears (defined in framebuffer.cpp).
  void write_pending(uint32_t tile);
  void write_all_pending() {
    if (!any_pending.load(std::memory_order_acquire)) return;
    const std::lock_guard<std::mutex> hold(pending_lock);
    if (!any_pending.load(std::memory_order_relaxed)) return;
    for (uint32_t t = 0; t < pending.size(); ++t)
      write_pending(t);
    any_pending.store(false, std::memory_order_release);
  }

  size_t sample_index(uint32_t x, uint32_t y, uint32_t s) const {
    const size_t tile = grid.tile_of(x, y);
    return (tile * desc.samples + s) * binning::kTilePixels + in_tile(x, y);
  }
};

struct FramebufferAccess {
  // The storage with every pending clear written.
  static FramebufferStorage& storage(Framebuffer& fb) {
    fb.storage_->write_all_pending();
    return *fb.storage_;
  }
  static const FramebufferStorage& storage(const Framebuffer& fb) {
    fb.storage_->write_all_pending();
    return *fb.storage_;
  }
  // The storage as it is, pending clears included: for the fast triangle path only.
  static FramebufferStorage& deferred_storage(Framebuffer& fb) { return *fb.storage_; }
};
}  // namespace detail

}  // namespace tessera
