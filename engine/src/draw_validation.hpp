// Validation of a draw call's state and vertex data, done before anything is drawn, so that a
// bad call leaves the framebuffer untouched and says exactly what was wrong.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include <tbb/task_arena.h>

#include "tessera/framebuffer.hpp"
#include "tessera/pipeline.hpp"
#include "tessera/primitives.hpp"
#include "tessera/renderer.hpp"

namespace tessera {

// Throws Error(kInvalidArgument) for pipeline state that is out of range or does not fit the
// framebuffer, Error(kInvalidInput) for inconsistent sizes, an index out of range, or a
// position or attribute that is NaN or infinite.
// With finite_values false, NaN and infinite values pass (NonFiniteVertices::kCull drops
// their triangles after). With an arena, the scans of large vertex and index arrays run on its
// threads.
void validate_draw(const Framebuffer& target, const PipelineState& pipeline, const DrawInput& input,
                   bool finite_values = true, tbb::task_arena* arena = nullptr);

// The triangle shading state (tessera/shading.hpp): enums in range, the varyings each role
// the shader and the output read present in the draw, the Phong state finite and its lights'
// attenuation positive, IDs only into a float target and below 2^24. Part of validate_draw.
void validate_shading(const Framebuffer& target, const PipelineState& pipeline,
                      const DrawInput& input, size_t triangles);

// What validate_draw checks except the triangle list's vertex count: the pipeline state,
// attribute sizes, index range and (with finite_values) finite values. Used by every kind of
// draw.
void validate_vertices(const Framebuffer& target, const PipelineState& pipeline,
                       const DrawInput& input, bool finite_values = true,
                       tbb::task_arena* arena = nullptr);

// Throws Error(kInvalidInput) naming the first vertex whose position, then the first whose
// attribute, is NaN or infinite (validate_vertices's finite-value check).
void check_finite_values(const DrawInput& input, tbb::task_arena* arena = nullptr);

// Per vertex, whether its position and attributes are all finite; empty when every vertex is.
std::vector<bool> finite_vertices(const DrawInput& input);

// The draws of points, lines and polygons: their state (Error(kInvalidArgument) naming the
// field), their vertex count (a line list needs pairs; polygon contour sizes must add up to the
// vertex count: Error(kInvalidInput)), then validate_vertices.
void validate_points(const Framebuffer& target, const PipelineState& pipeline,
                     const PointState& state, const DrawInput& input);
void validate_lines(const Framebuffer& target, const PipelineState& pipeline,
                    const LineState& state, const DrawInput& input);
void validate_polygon(const Framebuffer& target, const PipelineState& pipeline,
                      const PolygonState& state, const DrawInput& input,
                      std::span<const uint32_t> contour_sizes);

}  // namespace tessera
