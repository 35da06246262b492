// tessera_line_bench: lecture 003's line timing (100,000 random lines in a 500x500 window) for
// each of Tessera's line rules on both backends, at the requested thread counts. One line of
// output per configuration, in the format of tessera_llvmpipe_lines, so the two can be read
// side by side: run both with the same --threads and --frames (tessera_llvmpipe_lines is built
// when OSMesa is found).
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "benchmarks/frame_times.hpp"
#include "benchmarks/random_lines.hpp"
#include "tessera/tessera.hpp"

namespace {

using tessera::bench::median_of;

using Clock = std::chrono::steady_clock;

struct Variant {
  const char* name;
  tessera::LineState state;
  // Depth test LESS and depth writes, no colour writes (the depth buffer cleared each frame),
  // in place of colour without a depth test.
  bool depth_only = false;
};

std::vector<Variant> variants() {
  std::vector<Variant> v;
  tessera::LineState s;
  s.algorithm = tessera::LineAlgorithm::kDiamondExit;
  v.push_back({"diamond", s});
  s.algorithm = tessera::LineAlgorithm::kBresenham;
  v.push_back({"bresenham", s});
  s.algorithm = tessera::LineAlgorithm::kDDA;
  v.push_back({"dda", s});
  s = {};
  s.stipple = {0x0C0F, 1};
  v.push_back({"diamond_stipple", s});
  s = {};
  s.width = 3.0f;
  v.push_back({"wide3", s});
  s = {};
  s.antialiased = true;
  v.push_back({"smooth", s});
  v.push_back({"diamond_depth", {}, true});
  v.push_back({"smooth_depth", s, true});
  return v;
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<uint32_t> threads = {1, 2};
  uint32_t frames = 5;
  std::string only;
  std::string backend = "fast";
  CLI::App app{"tessera_line_bench: 100,000 random lines in 500x500, per line rule"};
  app.add_option("--threads", threads, "renderer thread counts")->check(CLI::Range(1u, 1024u));
  app.add_option("--frames", frames, "timed frames after one warm-up")
      ->check(CLI::Range(1u, 1000u));
  app.add_option("--only", only, "run only this variant (diamond, bresenham, dda, ...)");
  app.add_option("--backend", backend, "fast or reference")
      ->check(CLI::IsMember({"fast", "reference"}));
  CLI11_PARSE(app, argc, argv);

  const tessera::bench::LineWorkload lines = tessera::bench::random_lines();
  const tessera::DrawInput input{lines.positions, lines.colors, 4, {}};
  tessera::PipelineState colour;
  colour.depth_test = false;  // the lecture's timing: lines only, as llvmpipe is run
  tessera::PipelineState depth_only;
  depth_only.color_write = false;
  for (uint32_t t : threads) {
    tessera::RendererOptions options;
    options.threads = t;
    options.backend = backend == "fast" ? tessera::Backend::kFast : tessera::Backend::kReference;
    tessera::Renderer renderer(options);
    tessera::Framebuffer fb({tessera::bench::kLineWindow, tessera::bench::kLineWindow, 1,
                             tessera::ColorFormat::kRGBA8});
    for (const Variant& v : variants()) {
      if (!only.empty() && only != v.name) continue;
      const tessera::PipelineState& pipeline = v.depth_only ? depth_only : colour;
      auto frame = [&] {
        const auto t0 = Clock::now();
        fb.clear_color({0, 0, 0, 1});
        if (v.depth_only) fb.clear_depth(1.0f);
        renderer.draw_lines(fb, pipeline, v.state, input);
        return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
      };
      frame();
      renderer.reset_counters();
      std::vector<double> times;
      for (uint32_t i = 0; i < frames; ++i)
        times.push_back(frame());
      const double median = median_of(times);
      std::printf(
          "tessera backend=%s variant=%s threads=%u frames=%u median_ms=%.3f min_ms=%.3f "
          "mlines_s=%.3f pixels=%llu simd=%s\n",
          backend.c_str(), v.name, renderer.threads(), frames, median,
          *std::min_element(times.begin(), times.end()),
          tessera::bench::kLineCount / (median * 1e-3) / 1e6,
          // Pixels written: shaded, or for depth only the depth test's passes.
          static_cast<unsigned long long>((v.depth_only ? renderer.counters().samples_passed
                                                        : renderer.counters().pixels_shaded) /
                                          frames),
          renderer.simd_target());
      std::fflush(stdout);
    }
  }
  return 0;
}
