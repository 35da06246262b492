// The vertex stage: object-space vertex streams in, clip-space positions and varyings out
// (ARCHITECTURE.md section 1). Renderer::draw_vertices runs it in the renderer's threads, each
// vertex of the streams shaded once per draw however many triangles use it, then draws the
// triangles as Renderer::draw does.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <span>

namespace tessera {

// One per-vertex input: vertex v's `components` floats start at data[offset + v * stride].
// Interleaved streams share `data` with different offsets; stride 0 means tightly packed
// (stride = components).
struct VertexStream {
  std::span<const float> data;
  uint32_t components = 3;  // 1 to 4
  uint32_t stride = 0;      // in floats
  uint32_t offset = 0;      // in floats
};

// The most input streams a draw takes, and the vertices a user shader sees per call.
inline constexpr uint32_t kMaxVertexStreams = 16;
inline constexpr uint32_t kVertexBatch = 64;

// What a user vertex shader reads and writes for a batch of up to kVertexBatch vertices, as
// structures of arrays: input(s, c)[i] is component c of stream s at vertex first + i (missing
// components of a stream read as 0, 0, 0, 1, as in OpenGL), clip(c)[i] the clip-space position's
// component c (x, y, z, w) it writes, varying(k)[i] varying k, for stream < the draw's stream
// count, component < 4 and k < VertexShader::user_varyings (the buffers hold no more). Every
// output the draw declares must be written for each of the `count` vertices.
class VertexBatch {
 public:
  uint32_t first;  // the index of the batch's first vertex in the streams
  uint32_t count;  // vertices in the batch, 1 to kVertexBatch

  const float* input(uint32_t stream, uint32_t component) const {
    return inputs_ + (stream * 4 + component) * kVertexBatch;
  }
  float* clip(uint32_t component) const { return outputs_ + component * kVertexBatch; }
  float* varying(uint32_t k) const { return outputs_ + (4 + k) * kVertexBatch; }

  VertexBatch(uint32_t first_vertex, uint32_t vertices, const float* inputs, float* outputs)
      : first(first_vertex), count(vertices), inputs_(inputs), outputs_(outputs) {}

 private:
  const float* inputs_;
  float* outputs_;
};

// The vertex shader: pass-through (stream 0 is the clip-space position, xyzw; the other
// streams' components become the varyings in order), the built-in transform, or a user
// callable. A user shader is called concurrently from the renderer's threads on disjoint
// batches, in no particular order: it must not keep state between calls that changes its
// results, and it must not call into the renderer.
enum class VertexShaderKind : uint8_t { kPassThrough, kTransform, kUser };

// The built-in transform (lecture 001's pipeline): stream 0 is the object-space position
// (w = 1 when it has three components), clip = projection * view * model * position. Its
// varyings, in order: the position in `space` (3), then with a normal stream the normal in
// that space (3: the inverse transpose of the upper 3x3 of view * model or of model, not
// normalized), then every other stream's components in stream order. Matrices are
// column-major, as GLM and OpenGL store them.
enum class VaryingSpace : uint8_t { kEye, kWorld };
struct TransformShader {
  std::array<float, 16> model{1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
  std::array<float, 16> view{1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
  std::array<float, 16> projection{1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
  int32_t normal_stream = -1;  // the stream holding the object-space normal (3), or -1
  VaryingSpace space = VaryingSpace::kEye;
};

struct VertexShader {
  VertexShaderKind kind = VertexShaderKind::kPassThrough;
  TransformShader transform;  // kTransform
  // kUser: the callable, and the varyings it writes per vertex (0 to kMaxVaryings).
  std::function<void(const VertexBatch&)> user;
  uint32_t user_varyings = 0;
};

// A draw's vertex data: vertex_count vertices in every stream (stream 0 the position), and
// optional triangle-list indices into them (empty: the vertices three at a time).
struct VertexInput {
  std::span<const VertexStream> streams;
  size_t vertex_count = 0;
  std::span<const uint32_t> indices;
};

}  // namespace tessera
