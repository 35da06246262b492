// Tile traversal for the fast engine: a bin tile's storage is located once per storage tile it
// overlaps, then its bins are read in worker order (submission order) and each triangle goes
// to the raster kernel.
#include "engine/src/fast/tile_raster.hpp"

#include <algorithm>
#include <array>
#include <optional>
#include <span>
#include <type_traits>

#include "engine/src/shade/user_batch.hpp"

namespace tessera::fast {

namespace {

// Always inlined, as every prefetching helper here is (see fetch).
[[gnu::always_inline]] inline void prefetch_for_write(const void* p, size_t bytes) {
  const char* c = static_cast<const char*>(p);
  for (size_t line = 0; line < bytes; line += 64) {
    __builtin_prefetch(c + line, 1, 3);
  }
}

// Fetches a setup's three cache lines, into every level (kLocality 3) or only as far as L2
// (kLocality 1, prefetcht2 on x86).
template <int kLocality = 3>
[[gnu::always_inline]] inline void prefetch_setup(const TriangleSetup* setup) {
  const char* record = reinterpret_cast<const char*>(setup);
  for (size_t line = 0; line < sizeof(TriangleSetup); line += 64)
    __builtin_prefetch(record + line, 0, kLocality);
}

// One chunk's list for the tile, with the chunk's setups and records.
template <class Record>
struct ListView {
  std::span<const uint32_t> list;
  const TriangleSetup* setups = nullptr;
  const Record* records = nullptr;
  const float* planes = nullptr;  // a shaded draw's, plane_stride floats per setup
  size_t plane_stride = 0;
};

// What the draw loop fetches ahead, each at its own distance (see draw_list).
enum class Fetch { kSetup, kSetupFar, kRecord };

template <Fetch kFetch, class Record>
constexpr size_t fetch_distance() {
  if constexpr (kFetch == Fetch::kSetup) return 6;
  if constexpr (kFetch == Fetch::kSetupFar) return 24;
  return std::is_same_v<Record, PixelRecord> ? 64 : 16;
}

// Fetches what reference n of `view` names, if it is of kFetch's kind (a setup into every level
// or into L2 only, or a record). Always inlined: GCC otherwise finds a function that only
// prefetches free of side effects, and drops its calls.
template <Fetch kFetch, class Record>
[[gnu::always_inline]] inline void fetch(const ListView<Record>& view, size_t n) {
  if (n >= view.list.size()) return;
  const uint32_t reference = view.list[n];
  if constexpr (kFetch == Fetch::kRecord) {
    if ((reference & kPixelRecordBit) != 0)
      __builtin_prefetch(view.records + (reference & ~kPixelRecordBit));
  } else if ((reference & kPixelRecordBit) == 0) {
    prefetch_setup<kFetch == Fetch::kSetup ? 3 : 1>(view.setups + reference);
  }
}

// Reference n + kFetch's distance, in `here` or past its end in `next`.
template <Fetch kFetch, class Record>
[[gnu::always_inline]] inline void fetch_ahead(const ListView<Record>& here,
                                               const ListView<Record>& next, size_t n) {
  const size_t at = n + fetch_distance<kFetch, Record>();
  if (at < here.list.size()) {
    fetch<kFetch>(here, at);
  } else {
    fetch<kFetch>(next, at - here.list.size());
  }
}

// The references of `here` that the last list's loop did not reach, by the fetch distances:
// each kind's first (distance - `before`), `before` being the last list's length (0 for the
// first list).
template <bool kFar, class Record>
void fetch_first(const ListView<Record>& here, size_t before) {
  const auto first = [&]<Fetch kFetch>() {
    constexpr size_t distance = fetch_distance<kFetch, Record>();
    // Below the nearer distance a setup takes the nearer fetch.
    const size_t from = kFetch == Fetch::kSetupFar ? fetch_distance<Fetch::kSetup, Record>() : 0;
    for (size_t n = from; n + before < distance; ++n)
      fetch<kFetch>(here, n);
  };
  first.template operator()<Fetch::kSetup>();
  if constexpr (kFar) first.template operator()<Fetch::kSetupFar>();
  first.template operator()<Fetch::kRecord>();
}

// One chunk's list for the tile: each reference to a setup goes to `kernel`, each to a record
// (kPixelRecordBit) to `record_kernel`. Records were written long before this tile reads them:
// each is fetched a few references ahead, and as the list runs out, the next list's first ones
// (`next`: the tile's next non-empty list, in the next chunk), so that list does not begin with
// their misses. At two threads a draw has 16 chunks, and a tile's lists hold about a sixteenth
// of its references each: `tiny` took about 0.84x the time at two threads (each list began with
// its first 64 pixel records unfetched), `small`, `grid` and `medium` the same within 2%.
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
void draw_list(const TileContext& tc, const ListView<Record>& here, const ListView<Record>& next,
               TriangleKernel kernel, RecordKernel record_kernel, Counters& counters) {
  for (size_t n = 0; n < here.list.size(); ++n) {
    if constexpr (kFar) fetch_ahead<Fetch::kSetupFar>(here, next, n);
    fetch_ahead<Fetch::kSetup>(here, next, n);
    fetch_ahead<Fetch::kRecord>(here, next, n);
    const uint32_t reference = here.list[n];
    if ((reference & kPixelRecordBit) != 0) {
      record_kernel(tc, here.records[reference & ~kPixelRecordBit], counters);
    } else {
      kernel(tc, here.setups[reference], here.planes + reference * here.plane_stride, counters);
    }
  }
}

// The tile's lists in chunk order (submission order).
template <bool kFar, class Record, class RecordKernel>
void draw_lists(const TileContext& tc, std::span<const ChunkView> chunks, uint32_t tile,
                const Record* ChunkView::*records, TriangleKernel kernel,
                RecordKernel record_kernel, Counters& counters) {
  const size_t stride = tc.layout ? size_t{3} * tc.layout->count : 0;
  // The first non-empty list from chunk c on, and its chunk (chunks.size() when none).
  const auto list_from = [&](size_t c) {
    for (; c < chunks.size(); ++c) {
      const ChunkView& chunk = chunks[c];
      const std::span<const uint32_t> list = chunk.bins->tile(tile);
      if (!list.empty()) {
        return std::pair{
            c, ListView<Record>{list, chunk.setups, chunk.*records, chunk.planes, stride}};
      }
    }
    return std::pair{chunks.size(), ListView<Record>{}};
  };
  auto [c, here] = list_from(0);
  size_t before = 0;
  while (c < chunks.size()) {
    const auto [next_chunk, next] = list_from(c + 1);
    fetch_first<kFar>(here, before);
    draw_list<kFar>(tc, here, next, kernel, record_kernel, counters);
    before = here.list.size();
    c = next_chunk;
    here = next;
  }
}

}  // namespace

void raster_tile(const TileContext& draw, TriangleKernel kernel, PixelKernel pixel_kernel,
                 SampleKernel sample_kernel, detail::FramebufferStorage& fb,
                 const binning::TileGrid& bins, uint32_t tile, std::span<const ChunkView> chunks,
                 Counters& counters) {
  // A tile no triangle of this pass touches is left as it is, a pending clear included: the
  // clear is written when the tile is next drawn or read.
  bool empty = true;
  for (const ChunkView& chunk : chunks)
    empty = empty && chunk.bins->tile(tile).empty();
  if (empty) return;
  const int32_t size = static_cast<int32_t>(bins.tile_size());
  const int32_t bx0 = static_cast<int32_t>(bins.tile_x0(tile));
  const int32_t by0 = static_cast<int32_t>(bins.tile_y0(tile));
  const int32_t bx1 = std::min<int32_t>(bx0 + size, fb.desc.width) - 1;
  const int32_t by1 = std::min<int32_t>(by0 + size, fb.desc.height) - 1;
  constexpr int32_t kStorage = binning::kTileSize;
  // A user fragment function's batch buffers: the task's own.
  std::optional<shade::UserBatch> user_batch;
  if (draw.layout != nullptr && draw.layout->shader == shade::Shader::kUser) {
    const shade::Targets& targets = *draw.layout->targets;
    std::array<ColorFormat, kMaxColorTargets - 1> extra{};
    for (uint32_t t = 1; t < targets.count; ++t)
      extra[t - 1] = targets.target[t].format;
    user_batch.emplace(draw.layout->function_varyings,
                       std::span<const ColorFormat>(extra.data(), targets.count - 1));
  }
  // The storage tiles under the bin tile: one, or 2x2 for 128-pixel bin tiles.
  for (int32_t sy = by0 / kStorage * kStorage; sy <= by1; sy += kStorage) {
    for (int32_t sx = bx0 / kStorage * kStorage; sx <= bx1; sx += kStorage) {
      const uint32_t storage_tile =
          fb.grid.tile_of(static_cast<uint32_t>(sx), static_cast<uint32_t>(sy));
      TileContext tc = draw;
      if (user_batch) tc.user_batch = &*user_batch;
      tc.tile_x0 = sx;
      tc.tile_y0 = sy;
      tc.x0 = std::max({bx0, sx, draw.clip.x0});
      tc.y0 = std::max({by0, sy, draw.clip.y0});
      tc.x1 = std::min({bx1, sx + kStorage - 1, draw.clip.x1});
      tc.y1 = std::min({by1, sy + kStorage - 1, draw.clip.y1});
      if (tc.x0 > tc.x1 || tc.y0 > tc.y1) continue;  // outside the scissor rectangle
      const size_t base = size_t{storage_tile} * fb.desc.samples * binning::kTilePixels;
      tc.depth = fb.depth.data() + base;
      tc.rgba8 = fb.rgba8.empty() ? nullptr : fb.rgba8.data() + base * 4;
      tc.rgba32f = fb.rgba32f.empty() ? nullptr : fb.rgba32f.data() + base * 4;
      for (uint32_t t = 0; t < fb.desc.extra_targets; ++t)
        tc.extra[t] = fb.extra[t].data.data() + base * fb.extra[t].words;
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
        draw_lists<false>(tc, chunks, tile, &ChunkView::samples, kernel, sample_kernel, counters);
      } else if (fb.desc.samples == 1) {
        draw_lists<true>(tc, chunks, tile, &ChunkView::pixels, kernel, pixel_kernel, counters);
      } else {
        draw_lists<false>(tc, chunks, tile, &ChunkView::pixels, kernel, pixel_kernel, counters);
      }
    }
  }
}

}  // namespace tessera::fast
