// Tile traversal for the fast engine: a bin tile's storage is located once per storage tile it
// overlaps, then its bins are read in worker order (submission order) and each triangle goes
// to the raster kernel.
#include "engine/src/fast/tile_raster.hpp"

#include <algorithm>
#include <type_traits>

namespace tessera::fast {

namespace {

void prefetch_for_write(const void* p, size_t bytes) {
  const char* c = static_cast<const char*>(p);
  for (size_t line = 0; line < bytes; line += 64) {
    __builtin_prefetch(c + line, 1, 3);
  }
}

// Fetches a setup's three cache lines, into every level (kLocality 3) or only as far as L2
// (kLocality 1, prefetcht2 on x86).
template <int kLocality = 3>
inline void prefetch_setup(const TriangleSetup* setup) {
  const char* record = reinterpret_cast<const char*>(setup);
  for (size_t line = 0; line < sizeof(TriangleSetup); line += 64)
    __builtin_prefetch(record + line, 0, kLocality);
}

// A place in a tile's references, read through the chunks' lists one after another (chunk
// order is submission order). The draw loop's fetches ahead cross from one list into the next,
// so a list does not begin with its first references' misses: at two threads a draw has 16
// chunks, and a tile's lists hold about a sixteenth of its references each.
class TileReferences {
 public:
  TileReferences(std::span<const ChunkView> chunks, uint32_t tile) : chunks_(chunks), tile_(tile) {
    enter(0);
  }
  bool done() const { return chunk_ >= chunks_.size(); }
  uint32_t reference() const { return *at_; }
  const ChunkView& chunk() const { return chunks_[chunk_]; }
  void next() {
    if (++at_ == end_) enter(chunk_ + 1);
  }

 private:
  // The first reference of the first non-empty list from chunk c on (done() when none).
  void enter(size_t c) {
    for (chunk_ = c; chunk_ < chunks_.size(); ++chunk_) {
      const std::span<const uint32_t> list = chunks_[chunk_].bins->tile(tile_);
      if (!list.empty()) {
        at_ = list.data();
        end_ = list.data() + list.size();
        return;
      }
    }
  }

  std::span<const ChunkView> chunks_;
  uint32_t tile_;
  size_t chunk_ = 0;
  const uint32_t* at_ = nullptr;
  const uint32_t* end_ = nullptr;
};

// The tile's references, each to a setup to `kernel` or to a record (kPixelRecordBit: the
// chunk's `records` array) to `record_kernel`. Records were written long before this tile reads
// them: each is fetched a few references ahead. The first ones are fetched before the loop.
// - A setup spans three cache lines and is fetched 6 ahead (measured 2% faster than 4 on
//   `tiny`, the same elsewhere; 2 and 12 slower).
// - With kFar (one sample per pixel), it is first fetched into L2 only, 24 ahead: `small` about
//   0.95x the time at one thread and at two, `tiny` about 0.975x, `grid` and `medium` the
//   same. 16 and 32 ahead measured the same as 24; the far fetch into L1 as well, about 1.02x
//   slower. With more samples, whose tiles take much of L2, the far fetch made `small` slower
//   (about 1.015x at one thread, up to 1.08x at two).
// - A record is one line: a pixel record is fetched 64 ahead (`tiny` 0.94x to 1.01x the time of
//   16 ahead at two threads, about 0.98x at one; `grid` within 2%), a sample record, whose
//   samples take longer to draw, 16 ahead (64 made `tiny` at four samples 1-3% slower).
template <bool kFar, class Record, class RecordKernel>
void draw_references(const TileContext& tc, std::span<const ChunkView> chunks, uint32_t tile,
                     TriangleKernel kernel, const Record* ChunkView::*records,
                     RecordKernel record_kernel, Counters& counters) {
  constexpr size_t kSetupAhead = 6;
  constexpr size_t kSetupFar = kFar ? 24 : 0;
  constexpr size_t kRecordAhead = std::is_same_v<Record, PixelRecord> ? 64 : 16;
  TileReferences at(chunks, tile), near = at, far = at, record = at;
  const auto fetch_record = [&](const TileReferences& r) {
    const uint32_t reference = r.reference();
    if ((reference & kPixelRecordBit) != 0)
      __builtin_prefetch(r.chunk().*records + (reference & ~kPixelRecordBit));
  };
  for (size_t n = 0; n < kSetupAhead && !near.done(); ++n, near.next()) {
    if ((near.reference() & kPixelRecordBit) == 0)
      prefetch_setup(near.chunk().setups + near.reference());
  }
  for (size_t n = 0; n < kSetupFar && !far.done(); ++n, far.next()) {
    if (n >= kSetupAhead && (far.reference() & kPixelRecordBit) == 0)
      prefetch_setup<1>(far.chunk().setups + far.reference());
  }
  for (size_t n = 0; n < kRecordAhead && !record.done(); ++n, record.next())
    fetch_record(record);
  for (; !at.done(); at.next()) {
    if (kFar && !far.done()) {
      if ((far.reference() & kPixelRecordBit) == 0)
        prefetch_setup<1>(far.chunk().setups + far.reference());
      far.next();
    }
    if (!near.done()) {
      if ((near.reference() & kPixelRecordBit) == 0)
        prefetch_setup(near.chunk().setups + near.reference());
      near.next();
    }
    if (!record.done()) {
      fetch_record(record);
      record.next();
    }
    const uint32_t reference = at.reference();
    if ((reference & kPixelRecordBit) != 0) {
      record_kernel(tc, (at.chunk().*records)[reference & ~kPixelRecordBit], counters);
    } else {
      kernel(tc, at.chunk().setups[reference], counters);
    }
  }
}

}  // namespace

void raster_tile(const TileContext& draw, TriangleKernel kernel, PixelKernel pixel_kernel,
                 SampleKernel sample_kernel, detail::FramebufferStorage& fb, const BinGrid& bins,
                 uint32_t tile, std::span<const ChunkView> chunks, Counters& counters) {
  // A tile no triangle of this pass touches is left as it is, a pending clear included: the
  // clear is written when the tile is next drawn or read.
  bool empty = true;
  for (const ChunkView& chunk : chunks)
    empty = empty && chunk.bins->tile(tile).empty();
  if (empty) return;
  const int32_t size = 1 << bins.size_log2;
  const int32_t bx0 = static_cast<int32_t>(tile % bins.tiles_x) * size;
  const int32_t by0 = static_cast<int32_t>(tile / bins.tiles_x) * size;
  const int32_t bx1 = std::min<int32_t>(bx0 + size, fb.desc.width) - 1;
  const int32_t by1 = std::min<int32_t>(by0 + size, fb.desc.height) - 1;
  constexpr int32_t kStorage = binning::kTileSize;
  // The storage tiles under the bin tile: one, or 2x2 for 128-pixel bin tiles.
  for (int32_t sy = by0 / kStorage * kStorage; sy <= by1; sy += kStorage) {
    for (int32_t sx = bx0 / kStorage * kStorage; sx <= bx1; sx += kStorage) {
      const uint32_t storage_tile =
          fb.grid.tile_of(static_cast<uint32_t>(sx), static_cast<uint32_t>(sy));
      TileContext tc = draw;
      tc.tile_x0 = sx;
      tc.tile_y0 = sy;
      tc.x0 = std::max(bx0, sx);
      tc.y0 = std::max(by0, sy);
      tc.x1 = std::min(bx1, sx + kStorage - 1);
      tc.y1 = std::min(by1, sy + kStorage - 1);
      const size_t base = size_t{storage_tile} * fb.desc.samples * binning::kTilePixels;
      tc.depth = fb.depth.data() + base;
      tc.rgba8 = fb.rgba8.empty() ? nullptr : fb.rgba8.data() + base * 4;
      tc.rgba32f = fb.rgba32f.empty() ? nullptr : fb.rgba32f.data() + base * 4;
      tc.hiz_min = fb.hiz_min.data() + size_t{storage_tile} * detail::kBlocksPerTile;
      tc.hiz_max = fb.hiz_max.data() + size_t{storage_tile} * detail::kBlocksPerTile;
      // A clear recorded since the tile was last drawn is written now, into cache, by the one
      // task drawing the tile. Otherwise, at one sample, the tile's depth and colour (16 KB
      // each in RGBA8) are fetched all at once, so their misses overlap instead of stalling the
      // first triangle in each block (tiny triangles 4% faster). With more samples the tile is
      // larger than its reuse pays for (measured 1% slower at 4 samples): left to the hardware.
      if (fb.any_pending.load(std::memory_order_relaxed) && fb.pending[storage_tile] != 0) {
        fb.write_pending(storage_tile);
      } else if (fb.desc.samples == 1) {
        prefetch_for_write(tc.depth, binning::kTilePixels * sizeof(float));
        if (tc.rgba8 != nullptr) prefetch_for_write(tc.rgba8, binning::kTilePixels * 4);
        if (tc.rgba32f != nullptr) {
          prefetch_for_write(tc.rgba32f, binning::kTilePixels * 4 * sizeof(float));
        }
      }

      if (sample_kernel != nullptr) {
        draw_references<false>(tc, chunks, tile, kernel, &ChunkView::samples, sample_kernel,
                               counters);
      } else if (fb.desc.samples == 1) {
        draw_references<true>(tc, chunks, tile, kernel, &ChunkView::pixels, pixel_kernel, counters);
      } else {
        draw_references<false>(tc, chunks, tile, kernel, &ChunkView::pixels, pixel_kernel,
                               counters);
      }
    }
  }
}

}  // namespace tessera::fast
