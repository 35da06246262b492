// tessera_vertex_bench: the vertex stage of a 1M-vertex indexed mesh against the rest of its
// frame. A 1000 x 1000 grid of vertices (about 2M triangles) with normals, drawn at 1920x1080
// through the built-in transform (eye-space position and normal as varyings, Gouraud colour
// from a third stream): the stage alone (vertex::shade), the whole frame (clear, stage, draw:
// Renderer::draw_vertices), and the frame without the stage (Renderer::draw of the stage's
// output). Median ms per frame in `median_ms`, at 1 and 2 threads.
#include <benchmark/benchmark.h>

#include <chrono>
#include <cmath>
#include <vector>

#include "benchmarks/frame_times.hpp"
#include "engine/src/vertex/vertex_stage.hpp"
#include "simd/dispatch.hpp"
#include "tessera/tessera.hpp"

namespace {

constexpr uint32_t kSide = 1000;

struct Mesh {
  std::vector<float> positions, normals, colours;
  std::vector<uint32_t> indices;
  Mesh() {
    for (uint32_t y = 0; y < kSide; ++y) {
      for (uint32_t x = 0; x < kSide; ++x) {
        const float u = static_cast<float>(x) / (kSide - 1),
                    v = static_cast<float>(y) / (kSide - 1);
        const float h = 0.1f * std::sin(12.0f * u) * std::cos(9.0f * v);
        positions.insert(positions.end(), {2.0f * u - 1.0f, h, 2.0f * v - 1.0f});
        normals.insert(normals.end(), {-h, 1.0f, h});
        colours.insert(colours.end(), {u, v, 0.5f, 1.0f});
      }
    }
    for (uint32_t y = 0; y + 1 < kSide; ++y) {
      for (uint32_t x = 0; x + 1 < kSide; ++x) {
        const uint32_t i = y * kSide + x;
        indices.insert(indices.end(), {i, i + kSide, i + 1, i + 1, i + kSide, i + kSide + 1});
      }
    }
  }
};

const Mesh& mesh() {
  static const Mesh m;
  return m;
}

tessera::VertexShader shader() {
  tessera::VertexShader s;
  s.kind = tessera::VertexShaderKind::kTransform;
  // Seen from above and in front, a 60-degree perspective (OpenGL conventions).
  s.transform.view = {1, 0, 0, 0, 0, 0.8f, -0.6f, 0, 0, 0.6f, 0.8f, 0, 0, -0.2f, -2.6f, 1};
  const float f = 1.7320508f, near = 0.5f, far = 10.0f;
  s.transform.projection = {f * 1080.0f / 1920.0f,
                            0,
                            0,
                            0,
                            0,
                            f,
                            0,
                            0,
                            0,
                            0,
                            (far + near) / (near - far),
                            -1,
                            0,
                            0,
                            2 * far * near / (near - far),
                            0};
  s.transform.normal_stream = 1;
  return s;
}

// The colour stream is varyings 6..9 after position and normal.
tessera::PipelineState pipeline() {
  tessera::PipelineState p;
  p.clip_depth = tessera::ClipDepth::kNegativeOneToOne;
  return p;
}

std::vector<tessera::VertexStream> streams() {
  const Mesh& m = mesh();
  return {{m.positions, 3}, {m.normals, 3}, {m.colours, 4}};
}

void report(benchmark::State& state, const std::vector<double>& ms) {
  state.counters["median_ms"] = tessera::bench::median_of(ms);
  state.counters["Mvertices/s"] = 1e-3 * kSide * kSide / tessera::bench::median_of(ms);
}

void BM_VertexStageAlone(benchmark::State& state) {
  const uint32_t threads = static_cast<uint32_t>(state.range(0));
  tbb::task_arena arena(static_cast<int>(threads));
  const auto s = streams();
  const tessera::VertexInput input{s, size_t{kSide} * kSide, mesh().indices};
  const tessera::VertexShader vs = shader();
  const uint32_t per_vertex = tessera::vertex::validate(vs, input);
  const int64_t target = tessera::simd::resolve_target(tessera::SimdTarget::kAuto);
  std::vector<tessera::Float4> positions;
  std::vector<float> varyings;
  std::vector<double> ms;
  for (auto _ : state) {
    const auto t0 = std::chrono::steady_clock::now();
    tessera::vertex::shade(arena, target, vs, input, per_vertex, positions, varyings);
    ms.push_back(
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
  }
  report(state, ms);
}

// The whole frame with the stage (kStage) or the frame of the stage's output without it.
template <bool kStage>
void BM_Frame(benchmark::State& state) {
  const uint32_t threads = static_cast<uint32_t>(state.range(0));
  tessera::RendererOptions options;
  options.threads = threads;
  options.raster_counters = false;
  tessera::Renderer renderer(options);
  tessera::Framebuffer fb({1920, 1080, 1});
  const auto s = streams();
  const tessera::VertexInput input{s, size_t{kSide} * kSide, mesh().indices};
  const tessera::VertexShader vs = shader();
  tessera::PipelineState p = pipeline();
  p.roles.color = 6;
  // The stage's output, for the frame without it.
  tbb::task_arena arena(static_cast<int>(threads));
  const uint32_t per_vertex = tessera::vertex::validate(vs, input);
  std::vector<tessera::Float4> positions;
  std::vector<float> varyings;
  tessera::vertex::shade(arena, tessera::simd::resolve_target(tessera::SimdTarget::kAuto), vs,
                         input, per_vertex, positions, varyings);
  std::vector<double> ms;
  for (auto _ : state) {
    const auto t0 = std::chrono::steady_clock::now();
    fb.clear_color({0, 0, 0, 1});
    fb.clear_depth(1.0f);
    if constexpr (kStage) {
      renderer.draw_vertices(fb, p, vs, input);
    } else {
      renderer.draw(fb, p, {positions, varyings, per_vertex, mesh().indices});
    }
    ms.push_back(
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
  }
  report(state, ms);
}

}  // namespace

BENCHMARK(BM_VertexStageAlone)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_Frame<false>)
    ->Name("BM_FrameWithoutStage")
    ->Arg(1)
    ->Arg(2)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK(BM_Frame<true>)
    ->Name("BM_FrameWithStage")
    ->Arg(1)
    ->Arg(2)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK_MAIN();
