// Tile traversal for the fast engine. The block tests follow the hierarchical rasterization of
// Greene 1996 / McCool et al. 2001 in the form of Abrash 2009 (Larrabee): an edge function's
// extreme values over a rectangle are at two of its corners, so three corner evaluations per
// edge classify a whole block.
#include "engine/src/fast/tile_raster.hpp"

#include <algorithm>
#include <cmath>

namespace tessera::fast {

namespace {

using detail::kBlockSize;
using detail::kBlocksPerTile;
using detail::kBlocksPerTileSide;

// Conservative depth range of a triangle's plane over a block's sample area, widened by a
// margin that covers the kernel's float rounding (a few ulps of the terms it adds).
void block_depth_range(const TriangleSetup& t, int32_t bx, int32_t by, float& lo, float& hi) {
  const double x_lo = bx * 8.0 - t.x0 - 0.5, x_hi = x_lo + 8.0;
  const double y_lo = by * 8.0 - t.y0 - 0.5, y_hi = y_lo + 8.0;
  const double c00 = t.z0 + t.z_dx * x_lo + t.z_dy * y_lo;
  const double c10 = t.z0 + t.z_dx * x_hi + t.z_dy * y_lo;
  const double c01 = t.z0 + t.z_dx * x_lo + t.z_dy * y_hi;
  const double c11 = t.z0 + t.z_dx * x_hi + t.z_dy * y_hi;
  const double margin =
      1e-6 * (1.0 + std::abs(t.z0) + 16.0 * (std::abs(t.z_dx) + std::abs(t.z_dy)));
  lo = static_cast<float>(std::max<double>(std::min({c00, c10, c01, c11}), t.z_min) - margin);
  hi = static_cast<float>(std::min<double>(std::max({c00, c10, c01, c11}), t.z_max) + margin);
}

// Hi-Z verdict for a block: whether every sample fails (reject) or passes (accept).
enum class HizVerdict { kTest, kReject, kAccept };

HizVerdict hiz_test(CompareOp op, float tri_lo, float tri_hi, float block_min, float block_max) {
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
    default: break;
  }
  return HizVerdict::kTest;
}

// Wide path: exact int64 coverage bits for each pixel of the block (see block_kernel.hpp).
void wide_coverage(const TriangleSetup& t, const KernelConstants& k, uint32_t bits, int32_t bx,
                   int32_t by, uint32_t* coverage) {
  const int shift = static_cast<int>(bits) - 4;
  for (int p = 0; p < 64; ++p) {
    const int64_t cx = (int64_t{bx} * 8 + (p & 7)) * 16 + 8;
    const int64_t cy = (int64_t{by} * 8 + (p >> 3)) * 16 + 8;
    uint32_t mask = 0;
    for (uint32_t s = 0; s < k.samples; ++s) {
      const int64_t sx = (cx << shift) + k.sample_x[s];
      const int64_t sy = (cy << shift) + k.sample_y[s];
      bool inside = true;
      for (int e = 0; e < 3; ++e) inside &= t.a[e] * sx + t.b[e] * sy + t.c[e] >= 0;
      mask |= inside ? 1u << s : 0u;
    }
    coverage[p] = mask;
  }
}

}  // namespace

void raster_tile(const TileDrawState& st, uint32_t tile, std::span<const ChunkView> chunks,
                 Counters& counters) {
  detail::FramebufferStorage& fb = *st.fb;
  const uint32_t samples = fb.desc.samples;
  const uint32_t bits = st.subpixel_bits;
  const int shift = static_cast<int>(bits) - 4;
  const int32_t tile_x = static_cast<int32_t>((tile % fb.grid.tiles_x) * binning::kTileSize);
  const int32_t tile_y = static_cast<int32_t>((tile / fb.grid.tiles_x) * binning::kTileSize);
  const int32_t tile_x1 = std::min<int32_t>(tile_x + binning::kTileSize, fb.desc.width) - 1;
  const int32_t tile_y1 = std::min<int32_t>(tile_y + binning::kTileSize, fb.desc.height) - 1;
  const size_t tile_base = size_t{tile} * samples * binning::kTilePixels;
  float* hiz_min = fb.hiz_min.data() + size_t{tile} * kBlocksPerTile;
  float* hiz_max = fb.hiz_max.data() + size_t{tile} * kBlocksPerTile;
  alignas(64) uint32_t coverage[64];

  for (const ChunkView& chunk : chunks) {
    for (uint32_t index : chunk.bins->tile(tile)) {
      const TriangleSetup& t = chunk.setups[index];
      // Blocks of this tile under the triangle's pixel bounding box.
      const int32_t bx0 = std::max(t.x0, tile_x) >> 3, bx1 = std::min(t.x1, tile_x1) >> 3;
      const int32_t by0 = std::max(t.y0, tile_y) >> 3, by1 = std::min(t.y1, tile_y1) >> 3;
      for (int32_t by = by0; by <= by1; ++by) {
        for (int32_t bx = bx0; bx <= bx1; ++bx) {
          // The block's sample area in fixed point: pixel x covers samples from x*16/16 to
          // (x*16 + 15)/16 of a pixel.
          const int64_t x_lo = (int64_t{bx} * 8 * 16) << shift;
          const int64_t x_hi = ((int64_t{bx} * 8 + 7) * 16 + 15) << shift;
          const int64_t y_lo = (int64_t{by} * 8 * 16) << shift;
          const int64_t y_hi = ((int64_t{by} * 8 + 7) * 16 + 15) << shift;
          uint32_t edge_mask = 0;
          bool rejected = false;
          for (int e = 0; e < 3; ++e) {
            const int64_t ax_lo = t.a[e] * x_lo, ax_hi = t.a[e] * x_hi;
            const int64_t by_lo = t.b[e] * y_lo, by_hi = t.b[e] * y_hi;
            const int64_t e_max = std::max(ax_lo, ax_hi) + std::max(by_lo, by_hi) + t.c[e];
            const int64_t e_min = std::min(ax_lo, ax_hi) + std::min(by_lo, by_hi) + t.c[e];
            if (e_max < 0) {
              rejected = true;
              break;
            }
            if (e_min < 0) edge_mask |= 1u << e;
          }
          if (rejected) {
            ++counters.blocks_rejected;
            continue;
          }
          const uint32_t block = static_cast<uint32_t>(((by - (tile_y >> 3)) * kBlocksPerTileSide) +
                                                       (bx - (tile_x >> 3)));
          BlockJob job;
          job.cols = static_cast<uint32_t>(std::min<int32_t>(8, fb.desc.width - bx * 8));
          job.rows = static_cast<uint32_t>(std::min<int32_t>(8, fb.desc.height - by * 8));
          const bool full = edge_mask == 0 && job.cols == 8 && job.rows == 8;
          if (edge_mask == 0) {
            ++counters.blocks_accepted;
          } else {
            ++counters.blocks_partial;
          }

          BlockKernel kernel = st.kernel;
          if (st.hiz) {
            float lo, hi;
            block_depth_range(t, bx, by, lo, hi);
            const HizVerdict verdict = hiz_test(st.compare, lo, hi, hiz_min[block], hiz_max[block]);
            if (verdict == HizVerdict::kReject) {
              ++counters.hiz_rejected;
              continue;
            }
            if (verdict == HizVerdict::kAccept && full && st.depth_write) {
              ++counters.hiz_accepted;
              kernel = st.accept_kernel;
            }
          }

          job.edge_mask = edge_mask;
          const int64_t cx = (int64_t{bx} * 8 * 16 + 8) << shift;  // first pixel centre
          const int64_t cy = (int64_t{by} * 8 * 16 + 8) << shift;
          if (edge_mask != 0 && !t.narrow) {
            wide_coverage(t, st.constants, bits, bx, by, coverage);
            job.coverage = coverage;
          } else {
            for (int e = 0; e < 3; ++e) {
              if (!(edge_mask & (1u << e))) continue;
              job.e[e] = static_cast<int32_t>(t.a[e] * cx + t.b[e] * cy + t.c[e]);
              job.step_x[e] = t.a[e] << bits;
              job.step_y[e] = t.b[e] << bits;
              job.a[e] = t.a[e];
              job.b[e] = t.b[e];
            }
          }
          const double dx = bx * 8.0 - t.x0, dy = by * 8.0 - t.y0;
          job.z = static_cast<float>(t.z0 + t.z_dx * dx + t.z_dy * dy);
          job.z_dx = t.z_dx;
          job.z_dy = t.z_dy;
          job.q = static_cast<float>(t.q0 + t.q_dx * dx + t.q_dy * dy);
          job.q_dx = t.q_dx;
          job.q_dy = t.q_dy;
          for (int c = 0; c < 4; ++c) {
            job.qa[c] = static_cast<float>(t.qa0[c] + t.qa_dx[c] * dx + t.qa_dy[c] * dy);
            job.qa_dx[c] = t.qa_dx[c];
            job.qa_dy[c] = t.qa_dy[c];
          }
          const size_t offset = tile_base + size_t{block} * detail::kBlockPixels;
          job.depth = fb.depth.data() + offset;
          if (!fb.rgba8.empty()) job.rgba8 = fb.rgba8.data() + offset * 4;
          if (!fb.rgba32f.empty()) job.rgba32f = fb.rgba32f.data() + offset * 4;

          BlockStats stats;
          kernel(st.constants, job, stats);
          counters.samples_covered += stats.covered;
          counters.samples_passed += stats.passed;
          counters.pixels_shaded += stats.shaded;
          if (stats.depth_written) {
            hiz_min[block] = stats.z_min;
            hiz_max[block] = stats.z_max;
          }
        }
      }
    }
  }
}

}  // namespace tessera::fast
