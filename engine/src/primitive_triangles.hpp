// Points and lines that are drawn as triangles: square points as two triangles, wide lines as
// rectangles (cut into dashes by the stipple pattern) with their joins. The triangles go
// through the renderer's triangle pipeline, so both backends rasterize them with the top-left
// fill rule, MSAA, depth and perspective-correct colour exactly as they do any triangle.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <span>
#include <vector>

#include "engine/src/primitive_assembly.hpp"
#include "tessera/pipeline.hpp"
#include "tessera/primitives.hpp"
#include "tessera/types.hpp"

namespace tessera {

// A triangle list in clip space (0 <= z <= w) with four colour floats per vertex.
struct TriangleList {
  std::vector<Float4> positions;
  std::vector<float> colors;
  // Appends a triangle given in window space: pixels (x, y), z/w and 1/w, colour per vertex.
  void add_window(const WindowPoint& a, const WindowPoint& b, const WindowPoint& c, uint32_t width,
                  uint32_t height);
};

// The pipeline the generated triangles are drawn with: the caller's depth, colour, samples and
// snapping; no culling (points and lines have no facing); depth already in 0..1.
PipelineState triangle_pipeline(const PipelineState& pipeline);

// Square points of side `size` centred on each point.
TriangleList square_points(std::span<const WindowPoint> points, float size, uint32_t width,
                           uint32_t height);

// Wide lines: one rectangle per stipple dash, plus the joins of connected segments, handed to
// `sink` in submission order as lists of about kWideLineChunk triangles: a segment's dashes and
// join are never split, and a list is handed on once it holds kWideLineChunk or more, so a
// line draw's triangles take memory bounded by the chunk plus one segment's, not by the draw.
// (Each list is a draw of its own: Counters::bin_passes counts each list's passes.)
inline constexpr size_t kWideLineChunk = size_t{1} << 16;
using TriangleSink = std::function<void(const TriangleList&)>;
void wide_lines(std::span<const WindowSegment> segments, const LineState& state, uint32_t width,
                uint32_t height, const TriangleSink& sink);

}  // namespace tessera
