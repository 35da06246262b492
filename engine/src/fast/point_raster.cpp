// Binned, tile-parallel round points (point_raster.hpp): each point's pixel box is binned to
// the tiles it overlaps (one bin set per chunk of the draw, binning/bins.hpp), and a tile
// evaluates the reference's coverage, clamp(size/2 + 1/2 - d, 0, 1), on its part of each box,
// blending through the same fragment arithmetic (fragment_writer.hpp).
#include "engine/src/fast/point_raster.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "binning/tile_lists.hpp"
#include "engine/src/fast/fragment_writer.hpp"

namespace tessera::fast {

namespace {

struct PointSetup {
  const WindowPoint* point;
  int64_t x0, y0, x1, y1;  // the pixels within reach, on screen
};

// Points per chunk below which splitting the setup does not pay.
constexpr size_t kMinChunkPoints = 4096;

}  // namespace

void draw_round_points(tbb::task_arena& arena, detail::FramebufferStorage& fb,
                       const PipelineState& pipeline, std::span<const WindowPoint> points,
                       float size, Counters& counters) {
  if (points.empty()) return;
  const binning::TileGrid& grid = fb.grid;
  const double reach = 0.5 * size + 0.5;
  const uint32_t threads = static_cast<uint32_t>(arena.max_concurrency());
  const size_t chunk_count = std::clamp<size_t>(points.size() / kMinChunkPoints, 1,
                                                threads <= 1 ? 1 : size_t{4} * threads);
  std::vector<std::vector<PointSetup>> setups(chunk_count);
  std::vector<binning::TileLists> bins(chunk_count);

  arena.execute([&] {
    tbb::parallel_for(size_t{0}, chunk_count, [&](size_t c) {
      bins[c].reset(grid.tile_count());
      const size_t begin = points.size() * c / chunk_count;
      const size_t end = points.size() * (c + 1) / chunk_count;
      for (size_t i = begin; i < end; ++i) {
        const WindowPoint& p = points[i];
        PointSetup s{
            &p, std::max<int64_t>(0, static_cast<int64_t>(std::floor(p.x - reach))),
            std::max<int64_t>(0, static_cast<int64_t>(std::floor(p.y - reach))),
            std::min<int64_t>(fb.desc.width - 1, static_cast<int64_t>(std::floor(p.x + reach))),
            std::min<int64_t>(fb.desc.height - 1, static_cast<int64_t>(std::floor(p.y + reach)))};
        if (s.x0 > s.x1 || s.y0 > s.y1) continue;
        const uint32_t index = static_cast<uint32_t>(setups[c].size());
        setups[c].push_back(s);
        for (uint32_t ty = static_cast<uint32_t>(s.y0) >> binning::kTileSizeLog2;
             ty <= static_cast<uint32_t>(s.y1) >> binning::kTileSizeLog2; ++ty) {
          for (uint32_t tx = static_cast<uint32_t>(s.x0) >> binning::kTileSizeLog2;
               tx <= static_cast<uint32_t>(s.x1) >> binning::kTileSizeLog2; ++tx) {
            bins[c].add(ty * grid.tiles_x + tx, index);
          }
        }
      }
    });
  });

  std::vector<Counters> tile_counters(grid.tile_count());
  arena.execute([&] {
    tbb::parallel_for(tbb::blocked_range<uint32_t>(0, grid.tile_count(), 1),
                      [&](const tbb::blocked_range<uint32_t>& r) {
                        for (uint32_t tile = r.begin(); tile != r.end(); ++tile) {
                          const int64_t tx0 = grid.tile_x0(tile);
                          const int64_t ty0 = grid.tile_y0(tile);
                          TileWriter writer{fb, pipeline, true, tile_counters[tile]};
                          for (size_t c = 0; c < chunk_count; ++c) {
                            for (uint32_t i : bins[c].tile(tile)) {
                              const PointSetup& s = setups[c][i];
                              const WindowPoint& p = *s.point;
                              const int64_t x0 = std::max(s.x0, tx0),
                                            x1 = std::min(s.x1, tx0 + binning::kTileSize - 1);
                              const int64_t y0 = std::max(s.y0, ty0),
                                            y1 = std::min(s.y1, ty0 + binning::kTileSize - 1);
                              for (int64_t y = y0; y <= y1; ++y) {
                                for (int64_t x = x0; x <= x1; ++x) {
                                  const double d = std::hypot(static_cast<double>(x) + 0.5 - p.x,
                                                              static_cast<double>(y) + 0.5 - p.y);
                                  const double coverage = std::clamp(reach - d, 0.0, 1.0);
                                  if (coverage <= 0.0) continue;
                                  writer.write(x, y, static_cast<float>(p.z), p.color,
                                               static_cast<float>(coverage));
                                }
                              }
                            }
                          }
                        }
                      });
  });
  for (const binning::TileLists& b : bins)
    counters.bin_references += b.references();
  ++counters.bin_passes;
  for (const Counters& c : tile_counters) {
    counters.samples_covered += c.samples_covered;
    counters.samples_passed += c.samples_passed;
    counters.pixels_shaded += c.pixels_shaded;
  }
}

}  // namespace tessera::fast
