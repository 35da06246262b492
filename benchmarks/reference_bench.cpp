// Google Benchmark suite for the reference rasterizer: the demo scene per frame.
#include <benchmark/benchmark.h>

#include "tessera/tessera.hpp"

namespace {

void BM_ReferenceDemoScene(benchmark::State& state) {
  const uint32_t samples = static_cast<uint32_t>(state.range(0));
  const tessera::Scene scene = tessera::make_demo_scene();
  tessera::Framebuffer fb({640, 360, samples, tessera::ColorFormat::kRGBA8});
  tessera::Renderer renderer({1, tessera::Backend::kReference});
  for (auto _ : state) {
    fb.clear_color({0, 0, 0, 1});
    fb.clear_depth(1.0f);
    tessera::draw_scene(renderer, fb, {}, scene);
  }
  state.counters["Mtri/s"] = benchmark::Counter(
      static_cast<double>(scene.triangle_count()) * static_cast<double>(state.iterations()) / 1e6,
      benchmark::Counter::kIsRate);
}
BENCHMARK(BM_ReferenceDemoScene)->Arg(1)->Arg(4)->Unit(benchmark::kMillisecond);

}  // namespace
