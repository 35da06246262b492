// The vertex stage (vertex_stage.hpp). Vertices are shaded in batches of kVertexBatch, each
// batch gathered from the caller's streams into structures of arrays on the stack, shaded
// (the built-in transform by vertex_kernel.cpp's SIMD code), and scattered into the draw's
// positions and varyings; batches run in parallel on the renderer's arena. Every vertex is
// shaded exactly once per draw, whatever the indices.
#include "engine/src/vertex/vertex_stage.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "engine/src/vertex/vertex_kernel.hpp"
#include "tessera/error.hpp"

namespace tessera::vertex {

namespace {

[[noreturn]] void fail(const std::string& message) {
  throw Error(ErrorCode::kInvalidArgument, message);
}

uint64_t stride_of(const VertexStream& s) {
  return s.stride != 0 ? s.stride : s.components;
}

// c = a * b, column-major 4x4, in double.
std::array<double, 16> multiply(const std::array<double, 16>& a, const std::array<double, 16>& b) {
  std::array<double, 16> c{};
  for (int col = 0; col < 4; ++col) {
    for (int row = 0; row < 4; ++row) {
      double sum = 0.0;
      for (int k = 0; k < 4; ++k)
        sum += a[k * 4 + row] * b[col * 4 + k];
      c[col * 4 + row] = sum;
    }
  }
  return c;
}

std::array<double, 16> widen(const std::array<float, 16>& m) {
  std::array<double, 16> r;
  for (int i = 0; i < 16; ++i)
    r[i] = m[i];
  return r;
}

std::array<float, 16> narrow(const std::array<double, 16>& m) {
  std::array<float, 16> r;
  for (int i = 0; i < 16; ++i)
    r[i] = static_cast<float>(m[i]);
  return r;
}

// The matrices of a transform; false when the normal matrix is wanted but the upper 3x3 of
// the position matrix is singular.
bool transform_matrices(const TransformShader& t, TransformMatrices& out) {
  const std::array<double, 16> model = widen(t.model);
  const std::array<double, 16> view_model = multiply(widen(t.view), model);
  const std::array<double, 16> position = t.space == VaryingSpace::kEye ? view_model : model;
  out.clip = narrow(multiply(widen(t.projection), view_model));
  out.position = narrow(position);
  out.has_normal = t.normal_stream >= 0;
  out.normal = {1, 0, 0, 0, 1, 0, 0, 0, 1};
  if (!out.has_normal) return true;
  // The inverse transpose of the 3x3 part, m(r, c) = position[c * 4 + r]: its cofactors
  // over the determinant.
  const auto m = [&](int r, int c) { return position[c * 4 + r]; };
  double cofactor[3][3];
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) {
      const int r0 = (r + 1) % 3, r1 = (r + 2) % 3, c0 = (c + 1) % 3, c1 = (c + 2) % 3;
      cofactor[r][c] = m(r0, c0) * m(r1, c1) - m(r0, c1) * m(r1, c0);
    }
  }
  const double det = m(0, 0) * cofactor[0][0] + m(0, 1) * cofactor[0][1] + m(0, 2) * cofactor[0][2];
  if (!(std::abs(det) > 0.0) || !std::isfinite(det)) return false;
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c)
      out.normal[c * 3 + r] = static_cast<float>(cofactor[r][c] / det);
  }
  return true;
}

// Components the streams after the first add as varyings, leaving out stream `skip`.
uint32_t other_components(const VertexInput& input, int64_t skip) {
  uint32_t n = 0;
  for (size_t s = 1; s < input.streams.size(); ++s) {
    if (static_cast<int64_t>(s) != skip) n += input.streams[s].components;
  }
  return n;
}

// Copies the components of the streams after the first (but `skip`) of vertices
// [first, first + count) into their varyings from `at` on.
void copy_streams(const VertexInput& input, int64_t skip, size_t first, size_t count,
                  uint32_t per_vertex, uint32_t at, float* varyings) {
  for (size_t s = 1; s < input.streams.size(); ++s) {
    if (static_cast<int64_t>(s) == skip) continue;
    const VertexStream& st = input.streams[s];
    const uint64_t stride = stride_of(st);
    for (size_t v = first; v < first + count; ++v) {
      const float* src = st.data.data() + st.offset + v * stride;
      float* dst = varyings + v * per_vertex + at;
      for (uint32_t c = 0; c < st.components; ++c)
        dst[c] = src[c];
    }
    at += st.components;
  }
}

// Stream s of vertices [first, first + count) into in[s * 4 + c][i], missing components
// (0, 0, 0, 1).
void gather(const VertexStream& st, size_t first, size_t count, float* in) {
  const uint64_t stride = stride_of(st);
  const float* src = st.data.data() + st.offset + first * stride;
  for (uint32_t c = 0; c < 4; ++c) {
    float* row = in + c * kVertexBatch;
    if (c < st.components) {
      for (size_t i = 0; i < count; ++i)
        row[i] = src[i * stride + c];
    } else {
      std::fill(row, row + count, c == 3 ? 1.0f : 0.0f);
    }
  }
}

}  // namespace

uint32_t validate(const VertexShader& shader, const VertexInput& input) {
  if (static_cast<unsigned>(shader.kind) > static_cast<unsigned>(VertexShaderKind::kUser)) {
    fail("vertex shader kind has the invalid value " +
         std::to_string(static_cast<unsigned>(shader.kind)));
  }
  if (input.vertex_count > UINT32_MAX) {
    fail("a vertex draw takes at most 2^32 - 1 vertices, got " +
         std::to_string(input.vertex_count));
  }
  if (input.streams.empty() || input.streams.size() > kMaxVertexStreams) {
    fail("a vertex draw takes 1 to " + std::to_string(kMaxVertexStreams) + " streams, got " +
         std::to_string(input.streams.size()));
  }
  for (size_t s = 0; s < input.streams.size(); ++s) {
    const VertexStream& st = input.streams[s];
    const std::string name = "vertex stream " + std::to_string(s);
    if (st.components < 1 || st.components > 4) {
      fail(name + " has " + std::to_string(st.components) + " components (1 to 4)");
    }
    if (st.stride != 0 && st.stride < st.components) {
      fail(name + " has a stride of " + std::to_string(st.stride) + " floats, less than its " +
           std::to_string(st.components) + " components");
    }
    if (input.vertex_count == 0) continue;
    // offset + (vertex_count - 1) * stride + components floats, compared without overflow
    // (vertex_count < 2^32 and stride < 2^32: the product fits 64 bits).
    const uint64_t size = st.data.size(), head = uint64_t{st.offset} + st.components;
    const uint64_t needed = head + (input.vertex_count - 1) * stride_of(st);
    if (needed > size) {
      fail(name + " holds " + std::to_string(size) + " floats, but " +
           std::to_string(input.vertex_count) + " vertices need " + std::to_string(needed));
    }
  }
  const VertexStream& position = input.streams[0];
  uint64_t varyings = 0;
  switch (shader.kind) {
    case VertexShaderKind::kPassThrough:
      if (position.components != 4) {
        fail(
            "the pass-through vertex shader needs stream 0 as clip-space x, y, z, w (4 "
            "components), got " +
            std::to_string(position.components));
      }
      varyings = other_components(input, -1);
      break;
    case VertexShaderKind::kTransform: {
      const TransformShader& t = shader.transform;
      if (position.components < 3) {
        fail("the transform vertex shader needs stream 0 as a position of 3 or 4 components, got " +
             std::to_string(position.components));
      }
      for (const auto* m : {&t.model, &t.view, &t.projection}) {
        for (float x : *m) {
          if (!std::isfinite(x)) fail("the transform vertex shader's matrices are not finite");
        }
      }
      if (t.normal_stream >= 0) {
        if (t.normal_stream == 0 || static_cast<size_t>(t.normal_stream) >= input.streams.size() ||
            input.streams[static_cast<size_t>(t.normal_stream)].components != 3) {
          fail("transform normal_stream " + std::to_string(t.normal_stream) +
               " is not a stream of 3 components after the position");
        }
      } else if (t.normal_stream != -1) {
        fail("transform normal_stream " + std::to_string(t.normal_stream) +
             " is not -1 or a stream");
      }
      if (static_cast<unsigned>(t.space) > static_cast<unsigned>(VaryingSpace::kWorld)) {
        fail("transform space has the invalid value " +
             std::to_string(static_cast<unsigned>(t.space)));
      }
      TransformMatrices m;
      if (!transform_matrices(t, m)) {
        fail("the transform's normal matrix does not exist: the upper 3x3 of the " +
             std::string(t.space == VaryingSpace::kEye ? "view * model" : "model") +
             " matrix is singular");
      }
      varyings = 3 + (t.normal_stream >= 0 ? 3 : 0) + other_components(input, t.normal_stream);
      break;
    }
    case VertexShaderKind::kUser:
      if (!shader.user) fail("the user vertex shader has no callable");
      varyings = shader.user_varyings;
      break;
  }
  if (varyings > kMaxVaryings) {
    fail("the vertex shader writes " + std::to_string(varyings) + " varyings, more than " +
         std::to_string(kMaxVaryings));
  }
  return static_cast<uint32_t>(varyings);
}

void shade(tbb::task_arena& arena, int64_t simd_target, const VertexShader& shader,
           const VertexInput& input, uint32_t per_vertex, std::vector<Float4>& positions,
           std::vector<float>& varyings) {
  const size_t n = input.vertex_count;
  positions.resize(n);
  varyings.resize(n * per_vertex);
  if (n == 0) return;
  TransformMatrices matrices;
  if (shader.kind == VertexShaderKind::kTransform) transform_matrices(shader.transform, matrices);
  const TransformFn transform = transform_kernel(simd_target);
  const uint32_t normal_stream = shader.transform.normal_stream > 0
                                     ? static_cast<uint32_t>(shader.transform.normal_stream)
                                     : 0;

  Float4* pos = positions.data();
  float* var = varyings.data();
  // A batch's outputs (clip x, y, z, w, then `written` varyings, structures of arrays) into
  // the draw's positions and its first `written` varyings per vertex.
  const auto scatter = [&](const float* out, size_t first, size_t count, uint32_t written) {
    for (size_t i = 0; i < count; ++i) {
      pos[first + i] = {out[i], out[kVertexBatch + i], out[2 * kVertexBatch + i],
                        out[3 * kVertexBatch + i]};
      float* dst = var + (first + i) * per_vertex;
      for (uint32_t k = 0; k < written; ++k)
        dst[k] = out[(4 + k) * kVertexBatch + i];
    }
  };
  const auto batch = [&](size_t first, size_t count) {
    switch (shader.kind) {
      case VertexShaderKind::kPassThrough: {
        const VertexStream& st = input.streams[0];
        const uint64_t stride = stride_of(st);
        for (size_t v = first; v < first + count; ++v) {
          const float* src = st.data.data() + st.offset + v * stride;
          pos[v] = {src[0], src[1], src[2], src[3]};
        }
        copy_streams(input, -1, first, count, per_vertex, 0, var);
        return;
      }
      case VertexShaderKind::kTransform: {
        alignas(64) float in[kBatchInputs * kVertexBatch];
        alignas(64) float out[kBatchOutputs * kVertexBatch];
        gather(input.streams[0], first, count, in);
        if (matrices.has_normal) {
          gather(input.streams[normal_stream], first, count, in + normal_stream * 4 * kVertexBatch);
        }
        transform(matrices, in, normal_stream, static_cast<uint32_t>(count), out);
        const uint32_t written = matrices.has_normal ? 6 : 3;
        scatter(out, first, count, written);
        copy_streams(input, matrices.has_normal ? shader.transform.normal_stream : -1, first, count,
                     per_vertex, written, var);
        return;
      }
      case VertexShaderKind::kUser: {
        alignas(64) float in[kBatchInputs * kVertexBatch];
        alignas(64) float out[kBatchOutputs * kVertexBatch];
        for (size_t s = 0; s < input.streams.size(); ++s)
          gather(input.streams[s], first, count, in + s * 4 * kVertexBatch);
        shader.user(
            VertexBatch(static_cast<uint32_t>(first), static_cast<uint32_t>(count), in, out));
        scatter(out, first, count, per_vertex);
        return;
      }
    }
  };

  const size_t batches = (n + kVertexBatch - 1) / kVertexBatch;
  arena.execute([&] {
    tbb::parallel_for(tbb::blocked_range<size_t>(0, batches, 16),
                      [&](const tbb::blocked_range<size_t>& r) {
                        for (size_t b = r.begin(); b != r.end(); ++b) {
                          const size_t first = b * kVertexBatch;
                          batch(first, std::min<size_t>(kVertexBatch, n - first));
                        }
                      });
  });
}

}  // namespace tessera::vertex
