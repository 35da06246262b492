// The fast engine's one-pixel and antialiased lines: segments set up and binned to tiles in
// parallel (one bin set per chunk of the draw, binning/bins.hpp), then each tile draws its
// segments in submission order, in parallel with the other tiles, like the triangle path.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include <tbb/task_arena.h>

#include "engine/src/framebuffer_storage.hpp"
#include "engine/src/primitive_assembly.hpp"
#include "tessera/pipeline.hpp"
#include "tessera/primitives.hpp"
#include "tessera/renderer.hpp"

namespace tessera::fast {

// What a renderer keeps from one line draw to the next: the segments' setups and tile lists,
// whose memory the next draw reuses instead of faulting in fresh pages.
struct LineScratch {
  struct Chunk;
  std::vector<Chunk> chunks;
  LineScratch();
  ~LineScratch();
  LineScratch(LineScratch&&) noexcept;
  LineScratch& operator=(LineScratch&&) noexcept;
};

// Draws assembled segments exactly as reference::draw_thin_lines does (same pixels, same
// bytes), inside `arena`, with the kernels of a Highway target bit (simd/dispatch.hpp).
void draw_thin_lines(tbb::task_arena& arena, int64_t simd_target, LineScratch& scratch,
                     detail::FramebufferStorage& fb, const PipelineState& pipeline,
                     const LineState& state, std::span<const WindowSegment> segments,
                     Counters& counters);

}  // namespace tessera::fast
