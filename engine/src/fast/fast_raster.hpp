// The fast engine's draw: parallel setup and binning of contiguous ranges of the draw, then
// parallel rasterization of the tiles, in passes bounded by the bin memory budget.
#pragma once

#include <cstdint>
#include <memory>
#include <new>
#include <span>

#include <tbb/task_arena.h>

#include "engine/src/framebuffer_storage.hpp"
#include "tessera/pipeline.hpp"
#include "tessera/renderer.hpp"

namespace tessera::fast {

// What draw() throws when a pass's setup and binning, whose memory the bin budget bounds,
// cannot get that memory: a smaller budget would draw in more passes with less.
struct BinMemoryError : std::bad_alloc {
  const char* what() const noexcept override { return "bin memory exhausted"; }
};

class FastRasterizer {
 public:
  // The options' bin memory budget, raster counters and Hi-Z apply; simd_target is the
  // resolved Highway target (simd/dispatch.hpp).
  FastRasterizer(int64_t simd_target, const RendererOptions& options);
  ~FastRasterizer();
  FastRasterizer(FastRasterizer&&) noexcept;
  FastRasterizer& operator=(FastRasterizer&&) noexcept;

  int64_t simd_target() const noexcept;

  // Whether draw() can check `input`'s values for NaN and infinity itself (check_finite): a
  // triangle soup (every vertex is drawn) of the plain Gouraud colour whose attributes are at
  // most the four colour channels the setup reads.
  static bool checks_finite_values(const DrawInput& input, const PipelineState& pipeline,
                                   const FramebufferDesc& desc);

  // Draws a validated draw call (see draw_validation.hpp) inside `arena`: every shading state
  // (shade/layout.hpp), its triangles' primitive indices `primitive_ids[t]`, or t where that is
  // empty. With check_finite,
  // a draw checks_finite_values() accepts whose finite values were not validated: each
  // piece's vertices are checked as it is set up, and a NaN or infinity anywhere throws
  // validation's error (check_finite_values) before anything is drawn or counted. Throws
  // BinMemoryError when a pass cannot allocate its setups and bins. Every colour target is
  // written, or only target 0 without all_targets (the triangles of points, lines and
  // polygons).
  void draw(tbb::task_arena& arena, detail::FramebufferStorage& target,
            const PipelineState& pipeline, const DrawInput& input, Counters& counters,
            bool check_finite = false, std::span<const uint32_t> primitive_ids = {},
            bool all_targets = true);

 private:
  struct State;
  std::unique_ptr<State> state_;
};

}  // namespace tessera::fast
