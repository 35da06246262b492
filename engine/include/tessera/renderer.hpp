// The renderer: owns its threads (a oneTBB task_arena) and draws triangles, points, lines and
// polygons into framebuffers.
#pragma once

#include <cstdint>
#include <memory>
#include <span>

#include "tessera/export.hpp"
#include "tessera/framebuffer.hpp"
#include "tessera/pipeline.hpp"
#include "tessera/primitives.hpp"
#include "tessera/types.hpp"
#include "tessera/vertex.hpp"

namespace tessera {

enum class Backend {
  kReference,  // the scalar reference rasterizer (ARCHITECTURE.md section 3): the oracle
  kFast,       // binned, tiled, multithreaded SIMD engine; coverage identical to the reference
};

// The SIMD instruction set the fast engine's kernels run on. kAuto takes the environment
// variable TESSERA_SIMD (scalar|sse4|avx2|avx512|neon|sve) when set, else the best target this
// CPU supports. Forcing a target the CPU lacks is an Error(kInvalidArgument).
enum class SimdTarget { kAuto, kScalar, kSSE4, kAVX2, kAVX512, kNEON, kSVE };

// Default bound on the memory the fast engine holds to bin a draw: the set-up triangles, the
// bin references, the per-tile lists and the draw's bookkeeping, counted as allocated (and
// kept for the next draw). A draw that needs more is rasterized in several passes; nothing is
// dropped. Only a single triangle whose own references pass the whole budget (a triangle
// over very many tiles under a tiny budget) is binned anyway, exceeding it by that triangle.
inline constexpr uint64_t kDefaultBinMemoryBudget = uint64_t{256} << 20;

// A triangle draw's answer to non-finite input (a NaN or an infinity in a vertex's position or
// attributes). kError, the default, rejects the draw with Error(kInvalidInput) naming the first
// such vertex, before anything is drawn. kCull draws the rest: the triangles that use such a
// vertex are dropped and counted (Counters::triangles_invalid), as a renderer fed by a
// simulation that may produce the odd bad vertex wants. Points, lines and polygons always
// reject non-finite input.
enum class NonFiniteVertices : uint8_t { kError, kCull };

struct RendererOptions {
  uint32_t threads = 1;  // worker threads of the renderer's arena; 1 = fully serial, 0 = all cores
  Backend backend = Backend::kFast;
  SimdTarget simd = SimdTarget::kAuto;
  uint64_t bin_memory_budget = kDefaultBinMemoryBudget;  // bytes, at least 64 KiB
  // Count the fast engine's raster work: blocks rejected, accepted and partial, Hi-Z
  // decisions, samples covered and passed, pixels shaded. Off, those counters stay 0 and the
  // raster kernels contain no counting code (a separate kernel instance); the triangle and
  // bin counts are kept either way (a few additions per triangle). The kernels without
  // counters also drop a large triangle that Hi-Z finds hidden at every block of its box in a
  // tile before any block test (the same image).
  bool raster_counters = true;
  // Hi-Z: per 8x8 block depth bounds that reject a triangle's blocks hidden behind what is
  // drawn and let fully covered blocks in front skip the depth reads. Off, every block is
  // tested sample by sample (same image; docs/TRADEOFFS.md measures what it buys).
  bool hiz = true;
  // Side in pixels of the screen tiles triangles are binned into and rasterized by, one task
  // each: 32, 64 or 128. Smaller tiles balance threads better and read less per task; larger
  // ones bin fewer references per triangle (docs/TRADEOFFS.md).
  uint32_t bin_tile_size = 64;
  // What draw() does with a vertex whose position or attributes hold a NaN or an infinity.
  NonFiniteVertices non_finite = NonFiniteVertices::kError;
  // Side in pixels of the blocks the hierarchical corner test classifies: 8, 16 or 32. Storage,
  // Hi-Z and the SIMD work stay in 8x8 blocks; with 16 or 32 the test first classifies each
  // 16x16 or 32x32 block under a triangle as a whole, rejecting or accepting all the 8x8 blocks
  // inside at once, and tests those one by one only where an edge crosses it. Same image and
  // same block counters; 8 is the fastest on every workload measured (docs/TRADEOFFS.md).
  uint32_t block_size = 8;
  // Sub-block tests: in a partial block, each SIMD lane group (8x2 pixels with 16 lanes, 8x1
  // with 8, 4x1 with 4) is first classified by the edge values at its corner pixels against
  // the samples' offsets: outside an edge it is skipped, and edges it lies wholly inside are not
  // tested. Same image; off by default because the scalar test costs more than the vector edge
  // compares it saves (benchmarks/RESULTS.md decision 10).
  bool sub_block_tests = false;
  // Tiny-triangle records: at one sample, a triangle whose bounding box is at most 3x3 pixels
  // and which covers one to three pixel centres is set up as those pixels' depth and colour
  // values, a 32-byte record; at two and four samples, one whose box is at most 3 pixels across
  // and 4 down and whose covered samples lie in at most five pixels, as a 64-byte record of
  // their sample masks, depth planes and colours. Each is read in one cache line, instead of a
  // 160-byte setup the kernels evaluate.
  // Only for RGBA8 or no colour. Same image (the values are the kernels'); off, every
  // triangle gets the full setup (what they buy: benchmarks/RESULTS.md decisions 48, 57, 124
  // and 125).
  bool tiny_triangle_records = true;
};

// One draw call's vertex data, all in caller-owned memory that the renderer only reads.
struct DrawInput {
  std::span<const Float4> positions;  // clip space
  // attribute_count floats per vertex (0 to kMaxVaryings), vertex-major: the varyings, each
  // interpolated as PipelineState::varying_modes says and read by the fragment shader and the
  // outputs through PipelineState::roles (the Gouraud colour is varyings 0..3 by default;
  // missing colour components read as (0, 0, 0, 1)). Points, lines and polygons use 0..3.
  std::span<const float> attributes;
  uint32_t attribute_count = 0;
  // Triangle list indices; empty means positions are taken three at a time.
  std::span<const uint32_t> indices;
};

// Counts of what the renderer did since construction or the last reset_counters(). The
// triangle counts are per piece after clipping; the block and bin counts come from the fast
// engine only (the reference has neither).
struct Counters {
  uint64_t triangles_submitted = 0;
  uint64_t triangles_culled = 0;  // back-face, front-face, zero area, or outside the view
  // Triangles dropped before setup for a non-finite vertex (NonFiniteVertices::kCull); not
  // counted as submitted.
  uint64_t triangles_invalid = 0;
  uint64_t triangles_clipped = 0;  // crossed a clip plane and were cut
  uint64_t triangles_rasterized = 0;
  // Fast engine: rasterized triangles (pieces after clipping) recorded in a tile's bin, each
  // in exactly one pass. The others leave at setup: their box holds no sample, or, small
  // enough for the setup to test its samples, they cover none (a binned triangle may still
  // cover no sample).
  uint64_t triangles_binned = 0;
  // (primitive, tile) pairs binned: triangles', and the fast engine's lines' and points'.
  uint64_t bin_references = 0;
  uint64_t bin_passes = 0;       // rasterization passes (the bin budget, the pass size)
  uint64_t blocks_rejected = 0;  // 8x8 blocks of a triangle's tiles outside an edge
  uint64_t blocks_accepted = 0;  // blocks fully inside all three edges
  uint64_t blocks_partial = 0;   // blocks that needed per-sample edge tests
  // Sub-blocks (a partial block's SIMD lane groups: 8x2 pixels with 16 lanes, 8x1 with 8, 4x1
  // with 4) of triangles that are not small: outside an edge, inside every edge crossing
  // their block (no edge tests), or still partial.
  uint64_t subblocks_rejected = 0;
  uint64_t subblocks_accepted = 0;
  uint64_t subblocks_partial = 0;
  uint64_t hiz_rejected = 0;     // blocks skipped because the triangle is behind them
  uint64_t hiz_accepted = 0;     // fully covered blocks written without reading depth
  uint64_t samples_covered = 0;  // inside a triangle and tested (not in Hi-Z-rejected blocks)
  uint64_t samples_passed = 0;   // covered and passed the depth test
  uint64_t pixels_shaded = 0;    // pixels whose colour was computed (once per pixel)
  // Points, line segments and polygons submitted to draw_points, draw_lines, draw_polygon.
  // Those drawn as triangles (square points, wide lines, tessellated polygons) also count in
  // the triangle counters.
  uint64_t points_submitted = 0;
  uint64_t lines_submitted = 0;
  uint64_t polygons_submitted = 0;
};

class TESSERA_API Renderer {
 public:
  explicit Renderer(const RendererOptions& options = {});
  ~Renderer();
  Renderer(Renderer&&) noexcept;
  Renderer& operator=(Renderer&&) noexcept;
  Renderer(const Renderer&) = delete;
  Renderer& operator=(const Renderer&) = delete;

  uint32_t threads() const noexcept;
  Backend backend() const noexcept;
  // Name of the SIMD target the fast engine runs on ("avx512", "avx2", "sse4", "scalar", ...).
  const char* simd_target() const noexcept;

  // Draws a triangle list. All input is validated before anything is drawn: on
  // Error(kInvalidArgument / kInvalidInput) the framebuffer is left as it was. Every draw call
  // that cannot get the memory it needs (a bin memory budget larger than the memory there is)
  // ends with Error(kOutOfMemory), whose message names the bin budget when the bins were what
  // could not be allocated. The framebuffer then holds part of the draw: each tile the draw's
  // primitives up to some point in submission order, not the same point in every tile; the
  // counters are left partly updated (the passes drawn before may count their triangles and
  // bins but not their samples). The renderer and the framebuffer stay usable: a later draw
  // draws as it would on a framebuffer that held those pixels.
  void draw(Framebuffer& target, const PipelineState& pipeline, const DrawInput& input);

  // Runs the vertex stage (tessera/vertex.hpp) on every vertex of `input`'s streams, then
  // draws the triangles (the indices, or the vertices three at a time) as draw() does with the
  // shaded positions and varyings. A bad stream or shader is an Error(kInvalidArgument) before
  // anything runs; a shaded position or varying that is not finite is draw()'s error, naming
  // the vertex. A user vertex shader that throws ends the draw with its exception, before
  // anything is drawn.
  void draw_vertices(Framebuffer& target, const PipelineState& pipeline, const VertexShader& shader,
                     const VertexInput& input);

  // Draws one point per vertex (per index when there are indices), rules in primitives.hpp.
  // Validated, and failing for memory, like draw(); a bad point state is an
  // Error(kInvalidArgument).
  void draw_points(Framebuffer& target, const PipelineState& pipeline, const PointState& state,
                   const DrawInput& input);
  // Draws lines of the state's topology through the vertices (or indices). A line list needs
  // an even number of them.
  void draw_lines(Framebuffer& target, const PipelineState& pipeline, const LineState& state,
                  const DrawInput& input);
  // Draws one polygon: its vertices (or indices) in order, cut into contours (outlines and
  // holes) of the given sizes, which must add up to the vertex count; empty means a single
  // contour. Flat-shaded with the first vertex's colour, depth from the polygon's plane; not
  // culled.
  void draw_polygon(Framebuffer& target, const PipelineState& pipeline, const PolygonState& state,
                    const DrawInput& input, std::span<const uint32_t> contour_sizes = {});

  const Counters& counters() const noexcept;
  void reset_counters() noexcept;

 private:
  struct Impl;
  void draw_triangles(detail::FramebufferStorage& storage, const PipelineState& pipeline,
                      const DrawInput& input, bool check_finite = false,
                      std::span<const uint32_t> primitive_ids = {}, bool all_targets = true);
  std::unique_ptr<Impl> impl_;
};

}  // namespace tessera
