// Frame times of the standard workloads (TRI1 captures from ../shared/workloads/gen_scene.py,
// see scripts/make-workloads.sh) for each backend, SIMD target, thread count and sample count.
// Reports per frame: ms (Google Benchmark's time), Mtri/s and Gsamples/s (samples tested).
//
// Workloads are read from $TESSERA_WORKLOADS (default build/workloads); missing files are
// skipped with a message.
#include <benchmark/benchmark.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <string>

#include "simd/dispatch.hpp"
#include "tessera/tessera.hpp"

namespace {

std::filesystem::path workload_dir() {
  const char* env = std::getenv("TESSERA_WORKLOADS");
  return env ? env : "build/workloads";
}

const tessera::Capture* load(const std::string& name) {
  static std::map<std::string, tessera::Capture> cache;
  auto it = cache.find(name);
  if (it != cache.end()) return &it->second;
  const std::filesystem::path path = workload_dir() / (name + ".tri");
  if (!std::filesystem::exists(path)) return nullptr;
  return &cache.emplace(name, tessera::load_capture(path)).first->second;
}

void BM_Workload(benchmark::State& state, std::string name, tessera::Backend backend,
                 tessera::SimdTarget target, uint32_t threads, uint32_t samples, bool color) {
  const tessera::Capture* capture = load(name);
  if (capture == nullptr) {
    state.SkipWithError(("workload " + name + ".tri not found in " + workload_dir().string() +
                         " (run scripts/make-workloads.sh)")
                            .c_str());
    return;
  }
  tessera::RendererOptions options;
  options.backend = backend;
  options.simd = target;
  options.threads = threads;
  options.raster_counters = false;  // timed as users run it; samples are counted once below
  tessera::Renderer renderer(options);
  tessera::Framebuffer fb({capture->width, capture->height, samples, tessera::ColorFormat::kRGBA8});
  tessera::PipelineState pipeline = tessera::capture_pipeline();
  pipeline.color_write = color;
  tessera::DrawInput input;
  input.positions = capture->positions;
  input.attributes = capture->colors;
  input.attribute_count = 4;
  renderer.draw(fb, pipeline, input);  // warm-up: the renderer's bins and setups reach size
  uint64_t samples_covered = 0;        // per frame, from one counted draw
  {
    tessera::RendererOptions counting = options;
    counting.raster_counters = true;
    tessera::Renderer counter(counting);
    fb.clear_color({0, 0, 0, 1});
    fb.clear_depth(1.0f);
    counter.draw(fb, pipeline, input);
    samples_covered = counter.counters().samples_covered;
  }
  for (auto _ : state) {
    fb.clear_color({0, 0, 0, 1});
    fb.clear_depth(1.0f);
    renderer.draw(fb, pipeline, input);
  }
  const double frames = static_cast<double>(state.iterations());
  const double triangles = static_cast<double>(capture->positions.size() / 3);
  state.counters["Mtri/s"] =
      benchmark::Counter(triangles * frames / 1e6, benchmark::Counter::kIsRate);
  state.counters["Gsamples/s"] = benchmark::Counter(
      static_cast<double>(samples_covered) * frames / 1e9, benchmark::Counter::kIsRate);
}

void register_all() {
  const char* workloads[] = {"tiny", "small", "medium", "large", "huge", "grid"};
  struct Target {
    tessera::SimdTarget target;
    const char* name;
  };
  const Target targets[] = {{tessera::SimdTarget::kAVX512, "avx512"},
                            {tessera::SimdTarget::kAVX2, "avx2"},
                            {tessera::SimdTarget::kSSE4, "sse4"},
                            {tessera::SimdTarget::kScalar, "scalar"},
                            {tessera::SimdTarget::kNEON, "neon"}};
  for (const char* w : workloads) {
    for (uint32_t samples : {1u, 4u}) {
      for (uint32_t threads : {1u, 2u}) {
        for (const Target& t : targets) {
          if (!tessera::simd::is_available(t.target)) continue;
          for (bool color : {true, false}) {
            const std::string label =
                std::string(w) + "/fast/" + t.name + "/threads:" + std::to_string(threads) +
                "/samples:" + std::to_string(samples) + (color ? "" : "/depth_only");
            benchmark::RegisterBenchmark(label.c_str(), BM_Workload, w, tessera::Backend::kFast,
                                         t.target, threads, samples, color)
                ->Unit(benchmark::kMillisecond)
                ->UseRealTime();
          }
        }
      }
    }
  }
}

}  // namespace

int main(int argc, char** argv) {
  register_all();
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
