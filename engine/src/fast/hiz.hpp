// Hi-Z: the depth bounds of each 8x8 block (FramebufferStorage::hiz_min, hiz_max) and the
// verdicts they give, for the raster kernels (block_kernel-inl.h) and the occlusion queries
// (engine/src/occlusion).
#pragma once

#include <cmath>
#include <cstdint>

#include "engine/src/framebuffer_storage.hpp"
#include "tessera/pipeline.hpp"

namespace tessera::fast {

struct KernelTable;

enum class HizVerdict { kTest, kReject, kAccept };

// Whether every sample of a block fails (reject) or passes (accept) the depth test, from the
// block's depth bounds and the incoming depth range over it.
inline HizVerdict hiz_test(CompareOp op, float tri_lo, float tri_hi, float block_min,
                           float block_max) {
  switch (op) {
    case CompareOp::kLess:
      if (tri_lo >= block_max) return HizVerdict::kReject;
      if (tri_hi < block_min) return HizVerdict::kAccept;
      break;
    case CompareOp::kLessEqual:
      if (tri_lo > block_max) return HizVerdict::kReject;
      if (tri_hi <= block_min) return HizVerdict::kAccept;
      break;
    case CompareOp::kGreater:
      if (tri_hi <= block_min) return HizVerdict::kReject;
      if (tri_lo > block_max) return HizVerdict::kAccept;
      break;
    case CompareOp::kGreaterEqual:
      if (tri_hi < block_min) return HizVerdict::kReject;
      if (tri_lo >= block_max) return HizVerdict::kAccept;
      break;
    default:
      break;
  }
  return HizVerdict::kTest;
}

// The margin around a depth plane with value z0 at a block's origin and slopes z_dx, z_dy per
// pixel that covers the raster kernels' float rounding of it over a block (so Hi-Z rejects
// only what every sample's depth would fail).
inline double hiz_margin(double z0, float z_dx, float z_dy) {
  return 1e-6 * (1.0 + std::abs(z0) + 16.0 * (std::abs(z_dx) + std::abs(z_dy)));
}

// Depth bounds [lo, hi] as Hi-Z compares them with a block's: for fixed-point formats
// (depth_scale > 0) in steps, where a stored step round(z * scale) lies in [floor(lo * scale),
// ceil(hi * scale)].
inline void hiz_range(float depth_scale, double lo, double hi, float& out_lo, float& out_hi) {
  if (depth_scale > 0.0f) {
    lo = std::floor(lo * depth_scale);
    hi = std::ceil(hi * depth_scale);
  }
  out_lo = static_cast<float>(lo);
  out_hi = static_cast<float>(hi);
}

// A block whose depth changed since its bounds were computed ("dirty": min > max, as
// block_kernel.hpp's mark_hiz_dirty leaves it).
inline bool hiz_dirty(float block_min, float block_max) {
  return !(block_min <= block_max);
}

// Marks every block's Hi-Z bounds out of date (the kernels recompute a block's when they need
// it) and Hi-Z valid: for depth written by someone that does not maintain them.
void invalidate_hiz(detail::FramebufferStorage& fb);

// Computes the bounds of every dirty block of `fb` (with `table`'s SIMD target), so that they
// can be read without a raster kernel. Makes Hi-Z valid first when it is not (every block dirty).
void refresh_dirty_hiz(const KernelTable& table, detail::FramebufferStorage& fb);

}  // namespace tessera::fast
