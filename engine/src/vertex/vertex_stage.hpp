// The vertex stage (tessera/vertex.hpp): validates a draw's streams and vertex shader, then
// shades every vertex of the streams once, in batches of kVertexBatch on the renderer's
// threads, into the clip-space positions and varyings that the triangle pipeline draws.
#pragma once

#include <cstdint>
#include <vector>

#include <tbb/task_arena.h>

#include "tessera/types.hpp"
#include "tessera/vertex.hpp"

namespace tessera::vertex {

// The varyings per vertex the shader writes for these streams. Throws Error(kInvalidArgument)
// for a shader or stream description that is out of range (stream count, components, a
// stream too short for vertex_count, a normal stream that is not one, more than kMaxVaryings
// varyings, a user shader without a callable, a transform whose normal matrix is singular).
uint32_t validate(const VertexShader& shader, const VertexInput& input);

// Shades vertices [0, input.vertex_count) into positions (one per vertex) and varyings
// (`validate`'s count per vertex, vertex-major), resized to fit. `input` was validated.
void shade(tbb::task_arena& arena, int64_t simd_target, const VertexShader& shader,
           const VertexInput& input, uint32_t varyings_per_vertex, std::vector<Float4>& positions,
           std::vector<float>& varyings);

}  // namespace tessera::vertex
