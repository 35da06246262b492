// tessera-occlusion: occlusion queries replayed from captures (tessera/occlusion.hpp).
//
//   tessera-occlusion --occluders O.tri --queries Q.tri --group N [--mode exact|conservative]
//
// Draws O's triangles as occluders into a depth buffer of O's size or --width x --height
// (TRI1/TRI2 conventions: clip space, z/w in [0, 1]), then takes Q's triangles N at a time as one
// query each and prints one line per query, 1 (visible) or 0 (hidden), then a summary line with the
// times.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <exception>
#include <span>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "tessera/io.hpp"
#include "tessera/tessera.hpp"

int main(int argc, char** argv) {
  CLI::App app{
      "Occlusion queries: occluder triangles into depth, then query triangles N at a "
      "time, one answer line each (1 visible, 0 hidden) and a summary"};
  std::string occluders_path, queries_path, mode_name = "conservative";
  uint32_t group = 1, threads = 1, samples = 1, width = 0, height = 0, repeat = 1;
  bool quiet = false;
  app.add_option("--occluders", occluders_path, "TRI1/TRI2 capture drawn as occluders")->required();
  app.add_option("--queries", queries_path, "TRI1/TRI2 capture whose triangles are the queries")
      ->required();
  app.add_option("--group", group, "triangles per query (the last query may hold fewer)")
      ->check(CLI::Range(1u, 1u << 30))
      ->capture_default_str();
  app.add_option("--mode", mode_name, "conservative (Hi-Z only) or exact (every sample)")
      ->check(CLI::IsMember({"conservative", "exact"}))
      ->capture_default_str();
  app.add_option("--threads", threads, "worker threads of the occluder draw (0: every core)")
      ->capture_default_str();
  app.add_option("--samples", samples, "samples per pixel of the depth buffer")
      ->capture_default_str();
  app.add_option("--width", width, "the depth buffer's width (default: the occluders' frame)");
  app.add_option("--height", height, "the depth buffer's height (default: the occluders' frame)");
  app.add_option("--repeat", repeat,
                 "draw the occluders this many times (clearing between) and report the median")
      ->check(CLI::Range(1u, 1000u))
      ->capture_default_str();
  app.add_flag("--quiet", quiet, "print the summary line only");
  CLI11_PARSE(app, argc, argv);
  try {
    using Clock = std::chrono::steady_clock;
    const tessera::Capture occluders = tessera::load_capture(occluders_path);
    const tessera::Capture queries = tessera::load_capture(queries_path);
    const tessera::OcclusionMode mode = mode_name == "exact"
                                            ? tessera::OcclusionMode::kExact
                                            : tessera::OcclusionMode::kConservative;
    tessera::OcclusionDesc desc;
    desc.width = width != 0 ? width : occluders.width;
    desc.height = height != 0 ? height : occluders.height;
    desc.samples = samples;
    desc.threads = threads;
    tessera::OcclusionBuffer occlusion(desc);
    tessera::DrawInput input;
    input.positions = occluders.positions;
    // The median of `repeat` draws (the first allocates the renderer's bins and setups).
    std::vector<double> draws;
    for (uint32_t r = 0; r < repeat; ++r) {
      if (r > 0) occlusion.clear();
      const auto t0 = Clock::now();
      occlusion.draw_occluders(input);
      draws.push_back(std::chrono::duration<double, std::milli>(Clock::now() - t0).count());
    }
    std::sort(draws.begin(), draws.end());
    const double draw_ms = draws[draws.size() / 2];
    const size_t triangles = queries.positions.size() / 3;
    size_t visible = 0, count = 0;
    std::string lines;
    const auto t2 = Clock::now();
    for (size_t first = 0; first < triangles; first += group, ++count) {
      const size_t n = std::min<size_t>(group, triangles - first);
      tessera::DrawInput q;
      q.positions = std::span(queries.positions).subspan(first * 3, n * 3);
      const bool v = occlusion.triangles_visible(q, mode);
      visible += v;
      if (!quiet) lines += v ? "1\n" : "0\n";
    }
    const auto t3 = Clock::now();
    std::fputs(lines.c_str(), stdout);
    const double query_ms = std::chrono::duration<double, std::milli>(t3 - t2).count();
    std::printf(
        "occluders: %zu triangles in %.3f ms (%.1f M/s; median of %u draws) at %ux%u; queries: %zu "
        "(%s, %u "
        "triangles each), %zu visible, %zu hidden, in %.3f ms (%.2f us each)\n",
        occluders.positions.size() / 3, draw_ms,
        double(occluders.positions.size() / 3) / (draw_ms * 1e3), repeat, desc.width, desc.height,
        count, mode_name.c_str(), group, visible, count - visible, query_ms,
        count > 0 ? query_ms * 1e3 / double(count) : 0.0);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "tessera-occlusion: %s\n", e.what());
    return 1;
  }
  return 0;
}
