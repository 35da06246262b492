// Frame times of the standard workloads (TRI1 captures from ../shared/workloads/gen_scene.py,
// see scripts/make-workloads.sh) for each SIMD target, thread count and sample count, and of
// Mesa's llvmpipe on the same captures when the build found OSMesa.
// Reports per case: the median frame in ms (median_ms; for Tessera's cases Google Benchmark's
// own time column is the mean, for llvmpipe's the median), Mtri/s and Gsamples/s (samples
// covered) at that median. llvmpipe's cases carry `speedup`, llvmpipe's median over Tessera's
// on the target a renderer left at SimdTarget::kAuto runs, and a table of those ratios is
// printed after the run (on stdout after the console report, on stderr when
// --benchmark_format asks for JSON or CSV on stdout).
//
// llvmpipe reads LP_NUM_THREADS once per process, so each llvmpipe case runs
// tessera_llvmpipe_bench (built beside this program) as a child process with the thread and
// sample count, and reads its frame times back. Its frame count is $TESSERA_LLVMPIPE_FRAMES
// (default 5): llvmpipe's slowest case here takes about 2 s a frame.
//
// Workloads are read from $TESSERA_WORKLOADS (default build/workloads); missing files are
// skipped with a message.
#include <benchmark/benchmark.h>
#include <sys/wait.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <memory>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

#include "benchmarks/blend_workload.hpp"
#include "benchmarks/frame_times.hpp"
#include "benchmarks/phong_workload.hpp"
#include "benchmarks/texture_workload.hpp"
#include "simd/dispatch.hpp"
#include "tessera/tessera.hpp"

namespace {

using tessera::bench::median_of;

using Clock = std::chrono::steady_clock;

std::filesystem::path workload_dir() {
  const char* env = std::getenv("TESSERA_WORKLOADS");
  return env ? env : "build/workloads";
}

std::filesystem::path workload_path(const std::string& name) {
  return workload_dir() / (name + ".tri");
}

const tessera::Capture* load(const std::string& name) {
  static std::map<std::string, tessera::Capture> cache;
  auto it = cache.find(name);
  if (it != cache.end()) return &it->second;
  const std::filesystem::path path = workload_path(name);
  if (!std::filesystem::exists(path)) return nullptr;
  return &cache.emplace(name, tessera::load_capture(path)).first->second;
}

// What one case measured, for the ratios: keyed by workload, shading, samples and threads.
using CaseKey = std::tuple<std::string, std::string, uint32_t, uint32_t>;
struct Measured {
  double tessera_ms = 0.0;  // median frame on the best target, colour on
  std::string tessera_target;
  double llvmpipe_ms = 0.0;
};
std::map<CaseKey, Measured>& measured() {
  static std::map<CaseKey, Measured> m;
  return m;
}

void set_frame_counters(benchmark::State& state, double median_ms, double triangles,
                        double samples_covered) {
  state.counters["median_ms"] = median_ms;
  if (median_ms <= 0.0) return;
  state.counters["Mtri/s"] = triangles / (median_ms * 1e-3) / 1e6;
  if (samples_covered > 0.0) {
    state.counters["Gsamples/s"] = samples_covered / (median_ms * 1e-3) / 1e9;
  }
}

// shading "gouraud" draws the capture's colours; "phong" its Phong variant
// (benchmarks/phong_workload.hpp); "user" the capture's colours through a user fragment
// shader that copies them (FragmentShader::kUser); "bilinear" and "trilinear" its textured
// variant (benchmarks/texture_workload.hpp); "blended" its colours at alpha 0.5 blended over
// without depth writes (benchmarks/blend_workload.hpp).
void BM_Workload(benchmark::State& state, std::string name, std::string shading,
                 tessera::SimdTarget target, std::string target_name, bool best, uint32_t threads,
                 uint32_t samples, bool color) {
  const tessera::Capture* capture = load(name);
  if (capture == nullptr) {
    state.SkipWithError(
        ("workload " + workload_path(name).string() + " not found (run scripts/make-workloads.sh)")
            .c_str());
    return;
  }
  tessera::RendererOptions options;
  options.backend = tessera::Backend::kFast;
  options.simd = target;
  options.threads = threads;
  options.raster_counters = false;  // timed as users run it; samples are counted once below
  tessera::Renderer renderer(options);
  tessera::Framebuffer fb({capture->width, capture->height, samples, tessera::ColorFormat::kRGBA8});
  const bool phong = shading == "phong";
  const bool textured = shading == "bilinear" || shading == "trilinear";
  const bool blended = shading == "blended";
  tessera::PipelineState pipeline =
      phong      ? tessera::bench::phong_pipeline()
      : textured ? tessera::bench::textured_pipeline(tessera::bench::benchmark_texture(),
                                                     shading == "trilinear")
      : blended  ? tessera::bench::blended_pipeline()
                 : tessera::capture_pipeline();
  pipeline.color_write = color;
  if (shading == "user") {
    // A user fragment shader that does what the built-in Gouraud does: its colour varyings.
    pipeline.shader = tessera::FragmentShader::kUser;
    pipeline.fragment_function = [](const tessera::FragmentBatch& b,
                                    const tessera::FragmentOutput& out) {
      constexpr uint32_t kStride = tessera::kFragmentBatchStride;
      for (uint32_t c = 0; c < 4; ++c) {
        for (uint32_t i = 0; i < b.count; ++i)
          out.color[c * kStride + i] = b.varyings[c * kStride + i];
      }
    };
  }
  const std::vector<float> varyings = phong      ? tessera::bench::phong_varyings(*capture)
                                      : textured ? tessera::bench::textured_varyings(*capture)
                                      : blended  ? tessera::bench::blended_varyings(*capture)
                                                 : std::vector<float>{};
  tessera::DrawInput input;
  input.positions = capture->positions;
  input.attributes = phong || textured || blended ? varyings : capture->varyings;
  input.attribute_count = phong      ? tessera::bench::kPhongVaryings
                          : textured ? tessera::bench::kTexturedVaryings
                                     : 4;
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
  std::vector<double> frames;
  for (auto _ : state) {
    const auto t0 = Clock::now();
    fb.clear_color({0, 0, 0, 1});
    fb.clear_depth(1.0f);
    renderer.draw(fb, pipeline, input);
    frames.push_back(std::chrono::duration<double, std::milli>(Clock::now() - t0).count());
  }
  const double median = median_of(frames);
  set_frame_counters(state, median, static_cast<double>(capture->positions.size() / 3),
                     static_cast<double>(samples_covered));
  if (best && color) {
    Measured& m = measured()[{name, shading, samples, threads}];
    m.tessera_ms = median;
    m.tessera_target = target_name;
  }
}

#ifdef TESSERA_LLVMPIPE_BENCH
// Runs tessera_llvmpipe_bench on one capture and returns its output line ("llvmpipe ..."), or
// an error message in `error`.
std::string run_llvmpipe(const std::filesystem::path& capture, const std::string& shading,
                         uint32_t threads, uint32_t samples, uint32_t frames, std::string& error) {
  const auto quote = [](const std::string& s) {
    std::string q = "'";
    for (const char c : s)
      q += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return q + "'";
  };
  const std::string command = quote(TESSERA_LLVMPIPE_BENCH) + " --threads " +
                              std::to_string(threads) + " --samples " + std::to_string(samples) +
                              " --frames " + std::to_string(frames) + " --shading " + shading +
                              " -- " + quote(capture.string()) + " 2>/dev/null";
  std::unique_ptr<FILE, int (*)(FILE*)> pipe(popen(command.c_str(), "r"), pclose);
  if (!pipe) {
    error = "cannot start " + std::string(TESSERA_LLVMPIPE_BENCH);
    return "";
  }
  std::string line, found;
  char buf[4096];
  while (std::fgets(buf, sizeof buf, pipe.get()) != nullptr) {
    line += buf;
    if (!line.empty() && line.back() == '\n') {
      if (line.rfind("llvmpipe ", 0) == 0) found = line;
      line.clear();
    }
  }
  const int status = pclose(pipe.release());
  if (found.empty()) {
    const std::string how = status == -1 ? "could not be waited for"
                            : WIFEXITED(status)
                                ? "exit status " + std::to_string(WEXITSTATUS(status))
                            : WIFSIGNALED(status) ? "signal " + std::to_string(WTERMSIG(status))
                                                  : "status " + std::to_string(status);
    error = "tessera_llvmpipe_bench printed no result (" + how + "; run it alone to see why)";
  }
  return found;
}

// The value of `key`=... in an output line, or "" when absent.
std::string field(const std::string& line, const std::string& key) {
  std::istringstream words(line);
  std::string word;
  while (words >> word) {
    if (word.rfind(key + "=", 0) == 0) return word.substr(key.size() + 1);
  }
  return "";
}

void BM_Llvmpipe(benchmark::State& state, std::string name, std::string shading, uint32_t threads,
                 uint32_t samples) {
  const std::filesystem::path path = workload_path(name);
  if (!std::filesystem::exists(path)) {
    state.SkipWithError(
        ("workload " + path.string() + " not found (run scripts/make-workloads.sh)").c_str());
    return;
  }
  uint32_t frames = 5;
  if (const char* env = std::getenv("TESSERA_LLVMPIPE_FRAMES")) {
    frames = static_cast<uint32_t>(std::clamp(std::atol(env), 1L, 1000L));
  }
  std::string error;
  const std::string line = run_llvmpipe(path, shading, threads, samples, frames, error);
  if (!error.empty()) {
    state.SkipWithError(error.c_str());
    return;
  }
  if (field(line, "msaa") == "unavailable") {
    state.SkipWithError(("llvmpipe offers no " + std::to_string(samples) + "x MSAA here").c_str());
    return;
  }
  // llvmpipe's rasterizer threads as counted in the child: a different number means
  // LP_NUM_THREADS did not take effect, and the case would time another thread count.
  if (field(line, "lp_threads_seen") != field(line, "lp_num_threads")) {
    state.SkipWithError(("llvmpipe ran " + field(line, "lp_threads_seen") +
                         " rasterizer threads, not the " + field(line, "lp_num_threads") +
                         " LP_NUM_THREADS asks for")
                            .c_str());
    return;
  }
  std::vector<double> times;
  std::istringstream list(field(line, "times_ms"));
  for (std::string t; std::getline(list, t, ',');)
    times.push_back(std::atof(t.c_str()));
  if (times.empty()) {
    state.SkipWithError("tessera_llvmpipe_bench printed no frame times");
    return;
  }
  // One iteration, timed as the median frame (its own frames ran in the child).
  const double median = median_of(times);
  for (auto _ : state)
    state.SetIterationTime(median * 1e-3);
  const double triangles = std::atof(field(line, "triangles").c_str());
  set_frame_counters(state, median, triangles, 0.0);
  Measured& m = measured()[{name, shading, samples, threads}];
  m.llvmpipe_ms = median;
  if (m.tessera_ms > 0.0) state.counters["speedup"] = median / m.tessera_ms;
}
#endif

void register_all() {
  const char* workloads[] = {"tiny", "small", "medium", "large", "huge", "grid"};
  struct Target {
    tessera::SimdTarget target;
    const char* name;
  };
  const Target targets[] = {
      {tessera::SimdTarget::kAVX512, "avx512"}, {tessera::SimdTarget::kAVX2, "avx2"},
      {tessera::SimdTarget::kSSE4, "sse4"},     {tessera::SimdTarget::kScalar, "scalar"},
      {tessera::SimdTarget::kNEON, "neon"},     {tessera::SimdTarget::kSVE, "sve"}};
  // The target a renderer left at kAuto runs (TESSERA_SIMD's, when set): the ratios' Tessera.
  int64_t automatic = 0;
  try {
    automatic = tessera::simd::resolve_target(tessera::SimdTarget::kAuto);
  } catch (const tessera::Error& e) {
    std::fprintf(stderr, "tessera_workload_bench: %s\n", e.what());
  }
  struct Available {
    Target target;
    bool best;  // the automatic one
  };
  std::vector<Available> available;
  for (const Target& t : targets) {
    if (tessera::simd::is_available(t.target)) {
      available.push_back({t, tessera::simd::resolve_target(t.target) == automatic});
    }
  }
  // Gouraud at one and four samples, colour and depth only; Phong (colour) at one sample; the
  // textured variants (colour, one sample) of the grid and medium; the blended variants
  // (colour, one sample) of small and medium.
  for (const char* w : workloads) {
    for (const char* shading : {"gouraud", "phong", "user", "bilinear", "trilinear", "blended"}) {
      const bool gouraud = std::string(shading) == "gouraud";
      const bool user = std::string(shading) == "user";
      const bool textured =
          std::string(shading) == "bilinear" || std::string(shading) == "trilinear";
      if (textured && std::string(w) != "grid" && std::string(w) != "medium") continue;
      if (std::string(shading) == "blended" && std::string(w) != "small" &&
          std::string(w) != "medium") {
        continue;
      }
      std::string suffix;  // built by appending: GCC 12 warns falsely on "/" + std::string
      if (!gouraud) suffix.append("/").append(shading);
      for (uint32_t samples : {1u, 4u}) {
        if (!gouraud && !user && samples != 1) continue;
        for (uint32_t threads : {1u, 2u}) {
          for (const auto& [t, best] : available) {
            for (bool color : {true, false}) {
              if (!gouraud && !color) continue;
              const std::string label = std::string(w) + suffix + "/fast/" + t.name +
                                        "/threads:" + std::to_string(threads) +
                                        "/samples:" + std::to_string(samples) +
                                        (color ? "" : "/depth_only");
              benchmark::RegisterBenchmark(label.c_str(), BM_Workload, w, shading, t.target, t.name,
                                           best, threads, samples, color)
                  ->Unit(benchmark::kMillisecond)
                  ->UseRealTime();
            }
          }
#ifdef TESSERA_LLVMPIPE_BENCH
          // After Tessera's cases of the same workload, sample and thread count, for the ratio
          // (a user shader's colour is the Gouraud draw's: no llvmpipe case of its own).
          if (user) continue;
          const std::string label = std::string(w) + suffix +
                                    "/llvmpipe/threads:" + std::to_string(threads) +
                                    "/samples:" + std::to_string(samples);
          benchmark::RegisterBenchmark(label.c_str(), BM_Llvmpipe, w, shading, threads, samples)
              ->Unit(benchmark::kMillisecond)
              ->UseManualTime()
              ->Iterations(1);
#endif
        }
      }
    }
  }
}

// The ratios of the cases that ran both renderers, as a Markdown table, to `out`.
void print_ratios(FILE* out) {
  bool header = false;
  for (const auto& [key, m] : measured()) {
    if (m.tessera_ms <= 0.0 || m.llvmpipe_ms <= 0.0) continue;
    if (!header) {
      std::fprintf(
          out,
          "\nTessera (the automatic SIMD target, colour) against llvmpipe, median ms per frame:\n\n"
          "| workload | shading | samples | threads | Tessera target | Tessera ms | llvmpipe ms | "
          "llvmpipe / Tessera |\n| --- | --- | ---: | ---: | --- | ---: | ---: | ---: |\n");
      header = true;
    }
    const auto& [workload, shading, samples, threads] = key;
    std::fprintf(out, "| %s | %s | %u | %u | %s | %.1f | %.1f | %.2fx |\n", workload.c_str(),
                 shading.c_str(), samples, threads, m.tessera_target.c_str(), m.tessera_ms,
                 m.llvmpipe_ms, m.llvmpipe_ms / m.tessera_ms);
  }
}

}  // namespace

int main(int argc, char** argv) {
  // The ratio table follows the console report on stdout, and goes to stderr when stdout
  // carries JSON or CSV.
  bool console = true;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg.rfind("--benchmark_format=", 0) == 0) console = arg == "--benchmark_format=console";
  }
  register_all();
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  print_ratios(console ? stdout : stderr);
  return 0;
}
