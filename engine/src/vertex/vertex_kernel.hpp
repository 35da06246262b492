// The built-in transform's arithmetic on a batch of vertices, vectorized across vertices and
// compiled for every SIMD target (vertex_kernel.cpp). Each output is a fixed sequence of float
// multiplies and adds (contraction off), so every target computes the same bits.
#pragma once

#include <array>
#include <cstdint>

#include "tessera/types.hpp"
#include "tessera/vertex.hpp"

namespace tessera::vertex {

// The matrices of a TransformShader, multiplied out once per draw (in double, then rounded):
// column-major 4x4 clip and position matrices and a 3x3 normal matrix.
struct TransformMatrices {
  std::array<float, 16> clip;      // projection * view * model
  std::array<float, 16> position;  // view * model, or model (VaryingSpace)
  std::array<float, 9> normal;     // inverse transpose of position's upper 3x3
  bool has_normal = false;
};

// A batch's buffers, structures of arrays of kVertexBatch floats: the inputs [stream][4],
// the outputs [4 + kMaxVaryings] (clip x, y, z, w, then the varyings).
inline constexpr uint32_t kBatchInputs = kMaxVertexStreams * 4;
inline constexpr uint32_t kBatchOutputs = 4 + kMaxVaryings;

// clip, the position (varyings 0..2) and, with a normal, the normal (varyings 3..5) of `count`
// vertices: the position is input stream 0 (x, y, z, w), the normal input stream
// `normal_stream`'s x, y, z.
using TransformFn = void (*)(const TransformMatrices& m, const float* in, uint32_t normal_stream,
                             uint32_t count, float* out);

TransformFn transform_kernel(int64_t target);

}  // namespace tessera::vertex
