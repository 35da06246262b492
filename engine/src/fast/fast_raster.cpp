// Draw orchestration for the fast engine (ARCHITECTURE.md sections 1 and 5): the draw is cut
// into contiguous chunks; each chunk's worker sets up its triangles and bins them into its own
// per-tile lists; then every tile is one task that reads the chunks' lists in chunk order,
// which is submission order. The image is therefore the same bytes for any thread count.
// When the chunks' setups and references would pass the memory budget, the binned prefix of
// the draw is rasterized and binning resumes where it stopped.
#include "engine/src/fast/fast_raster.hpp"

#include <algorithm>
#include <bit>
#include <limits>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include "binning/bins.hpp"
#include "engine/src/draw_validation.hpp"
#include "engine/src/fast/block_kernel.hpp"
#include "engine/src/fast/hiz.hpp"
#include "engine/src/fast/setup_kernel.hpp"
#include "engine/src/fast/tile_raster.hpp"
#include "engine/src/fast/triangle_setup.hpp"
#include "engine/src/sample_positions.hpp"
#include "engine/src/scissor.hpp"
#include "engine/src/shading_state.hpp"
#include "tessera/error.hpp"

namespace tessera::fast {

namespace {

// Triangles per chunk below which splitting the setup across workers does not pay.
constexpr size_t kMinChunkTriangles = 4096;

// Chunks per worker in a draw with several workers: kFineChunksPerWorker when each chunk still
// holds at least kFineChunkTriangles triangles, else kChunksPerWorker. A worker takes whole
// chunks, so the setup phase ends with one worker idle while the other finishes its last ones,
// and the chunks of a mesh differ in cost (`grid` at two threads: its first four chunks took
// 7.5 to 9.3 ms each, the last four 6.9 to 7.5). At 4 chunks per worker the two workers were busy
// 91-94% of `grid`'s setup phase, at 8 96-98% (benchmarks/RESULTS.md decision 99). More chunks
// also split each tile's references into more, shorter lists: `medium` (200,000 triangles), whose
// raster phase dominates, took 0.93 to 1.17 times as long with 8 in seven alternating rounds
// (median 1.04), and keeps 4.
constexpr size_t kChunksPerWorker = 4;
constexpr size_t kFineChunksPerWorker = 8;
constexpr size_t kFineChunkTriangles = 32768;

struct Chunk {
  SetupList setups;    // reserved to the pass's capacity: never grows past the budget
  PlaneList planes;    // a shaded draw's, reserved as setups
  PixelList pixels;    // reserved as setups at one sample (each triangle takes one or the other)
  SampleList samples;  // reserved as setups at two and four samples
  binning::Bins bins;
  Counters counters;
  size_t begin = 0, end = 0;  // triangles of the draw given to this chunk
  size_t stopped_at = 0;      // first triangle not binned (== end when all were)
  bool non_finite = false;    // setup read a NaN or infinite position or colour
};

// Runs body, whose allocations the bin budget bounds (the chunks, a pass's setup and
// binning): their std::bad_alloc becomes BinMemoryError.
template <typename Body>
void bin_allocations(const Body& body) {
  try {
    body();
  } catch (const std::bad_alloc&) {
    throw BinMemoryError();
  }
}

// A pass's setup and binning, run in arena.
template <typename Body>
void execute_binning(tbb::task_arena& arena, const Body& body) {
  bin_allocations([&] { arena.execute(body); });
}

}  // namespace

struct FastRasterizer::State {
  int64_t target = 0;
  uint64_t budget = 0;
  bool count = true;  // raster counters
  bool hiz = true;
  bool records = true;  // pixel and sample records for tiny triangles
  uint32_t bin_tile_log2 = binning::kTileSizeLog2;
  uint32_t coarse_blocks = 1;  // 8x8 blocks per side of the blocks the corner test classifies
  bool sub_blocks = false;
  const KernelTable* kernels = nullptr;
  SetupRangeFn setup = nullptr;
  std::vector<Chunk> chunks;
  // Raster counters, one set per thread (summed after the draw: the totals do not depend on
  // which thread drew which tile).
  tbb::enumerable_thread_specific<Counters> raster_counters;
  double references_per_triangle = 1.5;  // of the last pass: splits the bin budget
};

FastRasterizer::FastRasterizer(int64_t simd_target, const RendererOptions& options)
    : state_(std::make_unique<State>()) {
  state_->target = simd_target;
  state_->budget = options.bin_memory_budget;
  state_->count = options.raster_counters;
  state_->hiz = options.hiz;
  state_->records = options.tiny_triangle_records;
  state_->bin_tile_log2 = static_cast<uint32_t>(std::countr_zero(options.bin_tile_size));
  state_->coarse_blocks = options.block_size / detail::kBlockSize;
  state_->sub_blocks = options.sub_block_tests;
  state_->kernels = &kernel_table(simd_target);
  state_->setup = setup_kernel(simd_target);
}
FastRasterizer::~FastRasterizer() = default;
FastRasterizer::FastRasterizer(FastRasterizer&&) noexcept = default;
FastRasterizer& FastRasterizer::operator=(FastRasterizer&&) noexcept = default;

int64_t FastRasterizer::simd_target() const noexcept {
  return state_->target;
}

bool FastRasterizer::checks_finite_values(const DrawInput& input, const PipelineState& pipeline,
                                          const FramebufferDesc& desc) {
  return input.indices.empty() && input.attribute_count <= 4 &&
         (input.attribute_count == 0 || pipeline.roles.color == 0) &&
         shade::layout_for(pipeline, input.attribute_count, desc).shader == shade::Shader::kGouraud;
}

void FastRasterizer::draw(tbb::task_arena& arena, detail::FramebufferStorage& fb,
                          const PipelineState& pipeline, const DrawInput& input, Counters& counters,
                          bool check_finite, std::span<const uint32_t> primitive_ids,
                          bool all_targets) {
  State& st = *state_;
  const bool indexed = !input.indices.empty();
  const size_t triangles = (indexed ? input.indices.size() : input.positions.size()) / 3;
  if (triangles == 0) return;
  const uint32_t samples = fb.desc.samples;
  const uint32_t bits = pipeline.subpixel_bits;
  const auto grid = binning::TileGrid::for_size(fb.desc.width, fb.desc.height, st.bin_tile_log2);

  // Kernel state for this draw.
  TileContext draw;
  draw.samples = samples;
  draw.subpixel_bits = bits;
  draw.compare = pipeline.depth_compare;
  draw.coarse_blocks = st.coarse_blocks;
  draw.sub_blocks = st.sub_blocks;
  draw.depth_scale = static_cast<float>(detail::depth_scale(fb.desc.depth_format));
  const auto pattern = sample_pattern(samples);
  for (uint32_t s = 0; s < samples; ++s) {
    draw.sample_x[s] = pattern[s].dx * (1 << (bits - 4));
    draw.sample_y[s] = pattern[s].dy * (1 << (bits - 4));
    draw.sample_fx[s] = pattern[s].dx / 16.0f;
    draw.sample_fy[s] = pattern[s].dy / 16.0f;
    for (uint32_t e = 0; e < 4; ++e) {
      draw.sample_x4[4 * s + e] = draw.sample_x[s];
      draw.sample_y4[4 * s + e] = draw.sample_y[s];
    }
  }
  const DepthMode depth = !pipeline.depth_test   ? DepthMode::kOff
                          : pipeline.depth_write ? DepthMode::kTestWrite
                                                 : DepthMode::kTest;
  const ColorMode color = !pipeline.color_write                         ? ColorMode::kOff
                          : fb.desc.color_format == ColorFormat::kRGBA8 ? ColorMode::kRGBA8
                                                                        : ColorMode::kRGBA32F;
  // A shaded draw's setups carry its planes, and its kernels read them: no records, which hold
  // a Gouraud colour.
  FramebufferDesc shaded_desc = fb.desc;  // the targets this draw writes
  if (!all_targets) shaded_desc.extra_targets = 0;
  const shade::Layout layout = shade::layout_for(pipeline, input.attribute_count, shaded_desc);
  const bool shaded = layout.shader != shade::Shader::kGouraud;
  if (shaded) draw.layout = &layout;
  const size_t plane_stride = shaded ? size_t{3} * layout.count : 0;
  const TriangleKernel kernel =
      triangle_kernel(*st.kernels, layout.shader, depth, color, samples > 1, st.count);
  // A draw that blends or masks channels reads each sample's colour before it writes it: the
  // paths that blend (records hold packed colour).
  const BlendState& blending = pipeline.blend[0];
  if (color != ColorMode::kOff && !blending.replaces()) {
    draw.blend = &blending;
    draw.blend_preset = blend::preset_of(blending);
    draw.blend_constant = pipeline.blend_constant;
  }
  const bool records = st.records && !shaded && draw.blend == nullptr;
  const PixelKernel pixels_kernel =
      records && samples == 1 ? pixel_kernel(*st.kernels, depth, color, st.count) : nullptr;
  const SampleKernel samples_kernel = records && (samples == 2 || samples == 4)
                                          ? sample_kernel(*st.kernels, depth, color, st.count)
                                          : nullptr;
  draw.clip = draw_box(pipeline, fb.desc.width, fb.desc.height);
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
  ctx.color_first = pipeline.roles.color;
  ctx.pipeline = &pipeline;
  ctx.depth_format = fb.desc.depth_format;
  ctx.guard_band = GuardBand::for_viewport(fb.desc.width, fb.desc.height);
  ctx.check_finite = check_finite;
  ctx.bin_tile_log2 = grid.size_log2;
  ctx.set_sample_pattern(pattern);
  ctx.pixel_records = pixels_kernel != nullptr;
  ctx.sample_records = samples_kernel != nullptr;

  const uint32_t threads = static_cast<uint32_t>(arena.max_concurrency());
  const uint64_t tiles = grid.tile_count();
  // The bin memory budget bounds everything a pass bins, as allocated (capacity, not use): the
  // setups, each triangle's tile rectangle, the references and the per-tile arrays. Each chunk
  // gets an equal share and grows its arrays only within it; fewer chunks when their per-tile
  // arrays would take more than a quarter of the budget. A batch that would pass a chunk's
  // share is undone and ends the chunk's part of the pass.
  const size_t per_worker = triangles >= kFineChunksPerWorker * threads * kFineChunkTriangles
                                ? kFineChunksPerWorker
                                : kChunksPerWorker;
  size_t chunk_count = std::clamp<size_t>(triangles / kMinChunkTriangles, 1,
                                          threads <= 1 ? 1 : per_worker * threads);
  const uint64_t per_tile = binning::Bins::kBytesPerTile;
  while (chunk_count > 1 && chunk_count * (tiles + 1) * per_tile * 4 > st.budget)
    --chunk_count;
  if (st.chunks.size() < chunk_count) bin_allocations([&] { st.chunks.resize(chunk_count); });
  // The chunks themselves, the allocator's headers of their arrays and the draw's own
  // bookkeeping (per-thread counters, task state: kBookkeeping) come out of it too.
  constexpr uint64_t kChunkOverhead = sizeof(Chunk) + 256;
  constexpr uint64_t kBookkeeping = uint64_t{16} << 10;
  const uint64_t overhead = st.chunks.capacity() * kChunkOverhead + kBookkeeping;
  const uint64_t available = st.budget > overhead ? st.budget - overhead : 0;
  const uint64_t chunk_budget = available / chunk_count;
  const uint64_t fixed = (tiles + 1) * per_tile;
  const uint64_t room = chunk_budget > fixed ? chunk_budget - fixed : 0;
  for (Counters& c : st.raster_counters)
    c = {};

  // A triangle's setup or record (both are reserved for each) and its bin entry.
  const uint64_t triangle_bytes =
      sizeof(TriangleSetup) + (ctx.sample_records ? sizeof(SampleRecord) : sizeof(PixelRecord)) +
      binning::Bins::kBytesPerTriangle + plane_stride * sizeof(float);
  constexpr uint64_t kReferenceBytes = binning::Bins::kBytesPerReference;
  constexpr size_t kBatch = 256;
  // A triangle cut by clip planes becomes at most kMaxClipVertices - 2 pieces.
  constexpr size_t kMaxPieces = kMaxClipVertices - 2;

  size_t start = 0;
  while (start < triangles) {
    // The room splits between setups and references as the last pass used them; a pass takes
    // as many triangles as that room holds, so chunks rarely stop early (a chunk that does
    // makes the later ones redo their range in the next pass).
    // (Below kPixelRecordBit: a reference is an index with that bit free.)
    const binning::BinRoom split = binning::split_bin_room(
        room, triangle_bytes, st.references_per_triangle, kMaxPieces, kPixelRecordBit - 1, tiles);
    const uint64_t setup_capacity = split.triangles;
    const uint64_t reference_capacity = split.references;
    const size_t remaining = triangles - start;
    // As many triangles as the budget holds. (A pass is not cut shorter to keep its setups in
    // cache: on `small` one pass took 0.92x the time of 32 MiB passes at one sample and 0.86x
    // at four; see benchmarks/RESULTS.md decision 106.)
    const size_t pass = std::min(remaining, setup_capacity * chunk_count * 9 / 10 + 1);
    for (size_t c = 0; c < chunk_count; ++c) {
      st.chunks[c].begin = start + pass * c / chunk_count;
      st.chunks[c].end = start + pass * (c + 1) / chunk_count;
    }

    // Setup and binning, one task per chunk.
    execute_binning(arena, [&] {
      tbb::parallel_for(size_t{0}, chunk_count, [&](size_t c) {
        Chunk& chunk = st.chunks[c];
        chunk.setups.clear();
        chunk.planes.clear();
        chunk.pixels.clear();
        chunk.samples.clear();
        chunk.bins.reset(grid.tile_count(), grid.tiles_x);
        chunk.counters = {};
        chunk.stopped_at = chunk.end;
        chunk.non_finite = false;
        // Bytes the chunk holds with `setups` setups of capacity and `references` references.
        const auto held = [&](uint64_t setups, uint64_t references) {
          return setups * triangle_bytes +
                 std::max<uint64_t>(chunk.bins.reference_capacity(), references) * kReferenceBytes +
                 fixed;
        };
        if (held(chunk.setups.capacity(), 0) > chunk_budget) {
          // Capacity kept from a draw with fewer chunks or a smaller grid: start afresh.
          SetupList().swap(chunk.setups);
          PlaneList().swap(chunk.planes);
          PixelList().swap(chunk.pixels);
          SampleList().swap(chunk.samples);
          chunk.bins.release();
        }
        size_t t = chunk.begin;
        size_t batch = kBatch;
        while (t < chunk.end) {
          // Room for the batch's worst case (kMaxPieces setups per triangle) without the
          // vector's own growth, which could pass setup_capacity: grow here, within it. The
          // binned triangles are the chunk's setups and pixel records together.
          const size_t binned = chunk.bins.triangles();
          const size_t worst = binned + std::min(batch, chunk.end - t) * kMaxPieces;
          if (worst > chunk.setups.capacity() && chunk.setups.capacity() < setup_capacity) {
            // Enough for the rest of the range at one piece per triangle plus a batch's worst
            // case, so the usual draw grows its setups once, and an eighth more where the
            // budget allows: the next draw's passes, split by the references per triangle this
            // one measured, are often a little longer, and reallocating the arrays (hundreds of
            // megabytes, faulted in afresh) made that draw take several times as long.
            const size_t wanted = std::max(worst, binned + (chunk.end - t) + kBatch * kMaxPieces);
            const size_t exact = std::min<size_t>(setup_capacity, wanted);
            const size_t spare = std::min<size_t>(setup_capacity, wanted + wanted / 8);
            const size_t grown =
                held(spare, chunk.bins.references()) <= chunk_budget ? spare : exact;
            if (held(grown, chunk.bins.references()) <= chunk_budget || chunk.setups.empty()) {
              chunk.setups.reserve(grown);
              if (shaded) chunk.planes.reserve(grown * plane_stride);
              if (ctx.pixel_records) chunk.pixels.reserve(grown);
              if (ctx.sample_records) chunk.samples.reserve(grown);
              chunk.bins.reserve_triangles(chunk.setups.capacity());
            }
          }
          batch = std::min<size_t>(
              batch, std::max<size_t>((chunk.setups.capacity() - binned) / kMaxPieces, 1));
          const size_t batch_end = std::min(chunk.end, t + batch);
          const size_t first = binned;
          const size_t first_setup = chunk.setups.size(), first_pixel = chunk.pixels.size(),
                       first_sample = chunk.samples.size();
          const Counters before = chunk.counters;
          if (shaded) {
            setup_shaded_range(ctx, layout, input, primitive_ids, t, batch_end, chunk.setups,
                               chunk.planes, chunk.bins, chunk.counters);
          } else if (!st.setup(ctx, input, t, batch_end, chunk.setups, chunk.pixels, chunk.samples,
                               chunk.bins, chunk.counters)) {
            // A NaN or infinity (ctx.check_finite): the draw stops with validation's error.
            chunk.non_finite = true;
            chunk.stopped_at = t;
            break;
          }
          const bool fits = chunk.bins.triangles() <= setup_capacity &&
                            chunk.bins.references() <= reference_capacity &&
                            held(chunk.setups.capacity(), chunk.bins.references()) <= chunk_budget;
          if (!fits && (first > 0 || batch > 1)) {
            // Undo the batch; retry smaller, or end the chunk's part of this pass here.
            chunk.setups.resize(first_setup);
            chunk.planes.resize(first_setup * plane_stride);
            chunk.pixels.resize(first_pixel);
            chunk.samples.resize(first_sample);
            chunk.bins.truncate(first);
            chunk.counters = before;
            if (first > 0) {
              chunk.stopped_at = t;
              break;
            }
            batch = std::max<size_t>(batch / 2, 1);
            continue;
          }
          // (A single triangle that does not fit an empty chunk is binned anyway: every pass
          // makes progress; the budget is then exceeded by that one triangle.)
          t = batch_end;
        }
        chunk.bins.place();
      });
    });

    // Everything up to the first chunk that stopped early is complete and in order; later
    // chunks are redone in the next pass.
    size_t used = 0;
    while (used < chunk_count && st.chunks[used].stopped_at == st.chunks[used].end)
      ++used;
    const size_t last = std::min(used, chunk_count - 1);
    if (ctx.check_finite) {
      // A NaN or infinity met in setup, or more passes to come whose vertices this pass did
      // not read: the whole draw's values are checked (throwing validation's error) before
      // this pass draws anything.
      bool non_finite = false;
      for (size_t c = 0; c < chunk_count; ++c)
        non_finite |= st.chunks[c].non_finite;
      if (non_finite || st.chunks[last].stopped_at < triangles) {
        check_finite_values(input, &arena);
        if (non_finite) {
          throw Error(ErrorCode::kInvalidInput, "a vertex value is not finite");
        }
      }
      // Every value is checked now: the later passes' setups need not check theirs again.
      ctx.check_finite = false;
    }
    const size_t kept = last + 1;
    std::vector<ChunkView> views(kept);
    uint64_t kept_setups = 0, kept_references = 0;
    for (size_t c = 0; c < kept; ++c) {
      views[c] = {st.chunks[c].setups.data(), shaded ? st.chunks[c].planes.data() : nullptr,
                  st.chunks[c].pixels.data(), st.chunks[c].samples.data(), &st.chunks[c].bins};
      const Counters& cc = st.chunks[c].counters;
      counters.triangles_submitted += cc.triangles_submitted;
      counters.triangles_culled += cc.triangles_culled;
      counters.triangles_clipped += cc.triangles_clipped;
      counters.triangles_rasterized += cc.triangles_rasterized;
      counters.bin_references += st.chunks[c].bins.references();
      kept_setups += st.chunks[c].bins.triangles();
      kept_references += st.chunks[c].bins.references();
    }
    counters.triangles_binned += kept_setups;
    if (kept_setups > 0) {
      st.references_per_triangle =
          static_cast<double>(kept_references) / static_cast<double>(kept_setups);
    }
    ++counters.bin_passes;

    // Bin tiles smaller than a storage tile share it: its pending clears are written first.
    // Otherwise each storage tile's are written by the one task that draws it.
    if (grid.size_log2 < binning::kTileSizeLog2) fb.write_all_pending();
    arena.execute([&] {
      tbb::parallel_for(tbb::blocked_range<uint32_t>(0, grid.tile_count(), 1),
                        [&](const tbb::blocked_range<uint32_t>& r) {
                          for (uint32_t tile = r.begin(); tile != r.end(); ++tile) {
                            raster_tile(draw, kernel, pixels_kernel, samples_kernel, fb, grid, tile,
                                        views, st.raster_counters.local());
                          }
                        });
    });
    // Tiles no triangle touched keep their pending clears.
    fb.any_pending.store(
        std::any_of(fb.pending.begin(), fb.pending.end(), [](uint8_t p) { return p != 0; }),
        std::memory_order_release);
    start = st.chunks[last].stopped_at;
  }

  for (const Counters& c : st.raster_counters) {
    counters.blocks_rejected += c.blocks_rejected;
    counters.blocks_accepted += c.blocks_accepted;
    counters.blocks_partial += c.blocks_partial;
    counters.subblocks_rejected += c.subblocks_rejected;
    counters.subblocks_accepted += c.subblocks_accepted;
    counters.subblocks_partial += c.subblocks_partial;
    counters.hiz_rejected += c.hiz_rejected;
    counters.hiz_accepted += c.hiz_accepted;
    counters.samples_covered += c.samples_covered;
    counters.samples_passed += c.samples_passed;
    counters.pixels_shaded += c.pixels_shaded;
  }
}

}  // namespace tessera::fast
