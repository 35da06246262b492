// Draw orchestration for the fast engine (ARCHITECTURE.md sections 1 and 5): the draw is cut
// into contiguous chunks; each chunk's worker sets up its triangles and bins them into its own
// per-tile lists; then every tile is one task that reads the chunks' lists in chunk order,
// which is submission order. The image is therefore the same bytes for any thread count.
// When the chunks' setups and references would pass the memory budget, the binned prefix of
// the draw is rasterized and binning resumes where it stopped.
#include "engine/src/fast/fast_raster.hpp"

#include <algorithm>
#include <limits>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "binning/bins.hpp"
#include "engine/src/fast/block_kernel.hpp"
#include "engine/src/fast/setup_kernel.hpp"
#include "engine/src/fast/tile_raster.hpp"
#include "engine/src/fast/triangle_setup.hpp"
#include "engine/src/sample_positions.hpp"

namespace tessera::fast {

namespace {

// Triangles per chunk below which splitting the setup across workers does not pay.
constexpr size_t kMinChunkTriangles = 4096;

struct Chunk {
  SetupList setups;
  binning::Bins bins;
  Counters counters;
  size_t begin = 0, end = 0;  // triangles of the draw given to this chunk
  size_t stopped_at = 0;      // first triangle not binned (== end when all were)
};

// Marks every block's Hi-Z bounds out of date (the kernels recompute a block's when they need
// it): for depth written by someone that does not maintain them.
void invalidate_hiz(detail::FramebufferStorage& fb) {
  std::fill(fb.hiz_min.begin(), fb.hiz_min.end(), std::numeric_limits<float>::infinity());
  std::fill(fb.hiz_max.begin(), fb.hiz_max.end(), -std::numeric_limits<float>::infinity());
  fb.hiz_valid = true;
}

}  // namespace

struct FastRasterizer::State {
  int64_t target = 0;
  uint64_t budget = 0;
  bool count = true;  // raster counters
  bool hiz = true;
  const KernelTable* kernels = nullptr;
  SetupRangeFn setup = nullptr;
  std::vector<Chunk> chunks;
  std::vector<Counters> tile_counters;
};

FastRasterizer::FastRasterizer(int64_t simd_target, const RendererOptions& options)
    : state_(std::make_unique<State>()) {
  state_->target = simd_target;
  state_->budget = options.bin_memory_budget;
  state_->count = options.raster_counters;
  state_->hiz = options.hiz;
  state_->kernels = &kernel_table(simd_target);
  state_->setup = setup_kernel(simd_target);
}
FastRasterizer::~FastRasterizer() = default;
FastRasterizer::FastRasterizer(FastRasterizer&&) noexcept = default;
FastRasterizer& FastRasterizer::operator=(FastRasterizer&&) noexcept = default;

int64_t FastRasterizer::simd_target() const noexcept {
  return state_->target;
}

void FastRasterizer::draw(tbb::task_arena& arena, detail::FramebufferStorage& fb,
                          const PipelineState& pipeline, const DrawInput& input,
                          Counters& counters) {
  State& st = *state_;
  const bool indexed = !input.indices.empty();
  const size_t triangles = (indexed ? input.indices.size() : input.positions.size()) / 3;
  if (triangles == 0) return;
  const uint32_t samples = fb.desc.samples;
  const uint32_t bits = pipeline.subpixel_bits;
  const binning::TileGrid& grid = fb.grid;

  // Kernel state for this draw.
  TileContext draw;
  draw.samples = samples;
  draw.subpixel_bits = bits;
  draw.compare = pipeline.depth_compare;
  draw.depth_scale = static_cast<float>(detail::depth_scale(fb.desc.depth_format));
  const auto pattern = sample_pattern(samples);
  for (uint32_t s = 0; s < samples; ++s) {
    draw.sample_x[s] = pattern[s].dx * (1 << (bits - 4));
    draw.sample_y[s] = pattern[s].dy * (1 << (bits - 4));
    draw.sample_fx[s] = pattern[s].dx / 16.0f;
    draw.sample_fy[s] = pattern[s].dy / 16.0f;
  }
  const DepthMode depth = !pipeline.depth_test   ? DepthMode::kOff
                          : pipeline.depth_write ? DepthMode::kTestWrite
                                                 : DepthMode::kTest;
  const ColorMode color = !pipeline.color_write                         ? ColorMode::kOff
                          : fb.desc.color_format == ColorFormat::kRGBA8 ? ColorMode::kRGBA8
                                                                        : ColorMode::kRGBA32F;
  const TriangleKernel kernel = triangle_kernel(*st.kernels, depth, color, samples > 1, st.count);
  const CompareOp op = pipeline.depth_compare;
  draw.hiz = st.hiz && pipeline.depth_test &&
             (op == CompareOp::kLess || op == CompareOp::kLessEqual || op == CompareOp::kGreater ||
              op == CompareOp::kGreaterEqual);
  if (pipeline.depth_test && !fb.hiz_valid) invalidate_hiz(fb);

  SetupContext ctx;
  ctx.width = fb.desc.width;
  ctx.height = fb.desc.height;
  ctx.subpixel_bits = bits;
  ctx.attribute_count = input.attribute_count;
  ctx.pipeline = &pipeline;
  ctx.guard_band = GuardBand::for_viewport(fb.desc.width, fb.desc.height);

  const uint32_t threads = static_cast<uint32_t>(arena.max_concurrency());
  const size_t chunk_count =
      std::clamp<size_t>(triangles / kMinChunkTriangles, 1, threads <= 1 ? 1 : size_t{4} * threads);
  if (st.chunks.size() < chunk_count) st.chunks.resize(chunk_count);
  const uint64_t chunk_budget = std::max<uint64_t>(st.budget / chunk_count, 1);
  st.tile_counters.assign(grid.tile_count(), Counters{});

  size_t start = 0;
  while (start < triangles) {
    const size_t remaining = triangles - start;
    for (size_t c = 0; c < chunk_count; ++c) {
      st.chunks[c].begin = start + remaining * c / chunk_count;
      st.chunks[c].end = start + remaining * (c + 1) / chunk_count;
    }

    // Setup and binning, one task per chunk.
    arena.execute([&] {
      tbb::parallel_for(size_t{0}, chunk_count, [&](size_t c) {
        Chunk& chunk = st.chunks[c];
        chunk.setups.clear();
        chunk.bins.reset(grid.tile_count());
        chunk.counters = {};
        chunk.stopped_at = chunk.end;
        // Setup in small batches, binning each batch and checking the budget after it.
        constexpr size_t kBatch = 256;
        for (size_t t = chunk.begin; t < chunk.end; t += kBatch) {
          const size_t batch_end = std::min(chunk.end, t + kBatch);
          const size_t first = chunk.setups.size();
          st.setup(ctx, input, t, batch_end, chunk.setups, chunk.counters);
          for (size_t i = first; i < chunk.setups.size(); ++i) {
            const TriangleSetup& s = chunk.setups[i];
            const uint32_t tx0 = static_cast<uint32_t>(s.x0) >> binning::kTileSizeLog2;
            const uint32_t tx1 = static_cast<uint32_t>(s.x1) >> binning::kTileSizeLog2;
            const uint32_t ty0 = static_cast<uint32_t>(s.y0) >> binning::kTileSizeLog2;
            const uint32_t ty1 = static_cast<uint32_t>(s.y1) >> binning::kTileSizeLog2;
            for (uint32_t ty = ty0; ty <= ty1; ++ty) {
              for (uint32_t tx = tx0; tx <= tx1; ++tx) {
                chunk.bins.add(ty * grid.tiles_x + tx, static_cast<uint32_t>(i));
              }
            }
          }
          const uint64_t bytes = chunk.setups.size() * sizeof(TriangleSetup) + chunk.bins.bytes();
          if (bytes >= chunk_budget && batch_end < chunk.end) {
            chunk.stopped_at = batch_end;
            break;
          }
        }
      });
    });

    // Everything up to the first chunk that stopped early is complete and in order; later
    // chunks are redone in the next pass.
    size_t used = 0;
    while (used < chunk_count && st.chunks[used].stopped_at == st.chunks[used].end)
      ++used;
    const size_t last = std::min(used, chunk_count - 1);
    const size_t kept = last + 1;
    std::vector<ChunkView> views(kept);
    for (size_t c = 0; c < kept; ++c) {
      views[c] = {st.chunks[c].setups.data(), &st.chunks[c].bins};
      const Counters& cc = st.chunks[c].counters;
      counters.triangles_submitted += cc.triangles_submitted;
      counters.triangles_culled += cc.triangles_culled;
      counters.triangles_clipped += cc.triangles_clipped;
      counters.triangles_rasterized += cc.triangles_rasterized;
      counters.bin_references += st.chunks[c].bins.references();
    }
    ++counters.bin_passes;

    arena.execute([&] {
      tbb::parallel_for(tbb::blocked_range<uint32_t>(0, grid.tile_count(), 1),
                        [&](const tbb::blocked_range<uint32_t>& r) {
                          for (uint32_t tile = r.begin(); tile != r.end(); ++tile) {
                            raster_tile(draw, kernel, fb, tile, views, st.tile_counters[tile]);
                          }
                        });
    });
    start = st.chunks[last].stopped_at;
  }

  for (const Counters& c : st.tile_counters) {
    counters.blocks_rejected += c.blocks_rejected;
    counters.blocks_accepted += c.blocks_accepted;
    counters.blocks_partial += c.blocks_partial;
    counters.hiz_rejected += c.hiz_rejected;
    counters.hiz_accepted += c.hiz_accepted;
    counters.samples_covered += c.samples_covered;
    counters.samples_passed += c.samples_passed;
    counters.pixels_shaded += c.pixels_shaded;
  }
}

}  // namespace tessera::fast
