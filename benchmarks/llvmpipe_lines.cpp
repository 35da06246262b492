// tessera_llvmpipe_lines: lecture 003's line timing (100,000 random lines in a 500x500 window,
// benchmarks/random_lines.hpp) drawn by Mesa's llvmpipe through OSMesa as GL_LINES, with the
// state tessera_line_bench uses (no depth test, smooth colour), plain, stippled, 3 pixels wide
// and smooth (antialiased, blended). llvmpipe reads LP_NUM_THREADS once per process, so the
// program re-executes itself with the value that the requested thread count needs, as
// tessera_llvmpipe_bench does.
#define GL_GLEXT_PROTOTYPES 1
#include <GL/osmesa.h>
// osmesa.h includes GL/gl.h, which glext.h needs first.
#include <GL/glext.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "benchmarks/frame_times.hpp"
#include "benchmarks/random_lines.hpp"

namespace {

using tessera::bench::median_of;

using Clock = std::chrono::steady_clock;
constexpr const char* kReexecMarker = "TESSERA_LLVMPIPE_REEXEC";

[[noreturn]] void fail(const std::string& message) {
  std::fprintf(stderr, "tessera_llvmpipe_lines: %s\n", message.c_str());
  std::exit(1);
}

// 1 thread: LP_NUM_THREADS=0 (rasterize on the calling thread); N > 1: N rasterizer threads.
uint32_t lp_num_threads_for(uint32_t threads) {
  return threads == 1 ? 0 : threads;
}

void ensure_llvmpipe_environment(uint32_t threads, char** argv) {
  const std::string want = std::to_string(lp_num_threads_for(threads));
  const char* have = std::getenv("LP_NUM_THREADS");
  const char* driver = std::getenv("GALLIUM_DRIVER");
  if (have && want == have && driver && std::string(driver) == "llvmpipe") return;
  if (std::getenv(kReexecMarker) != nullptr) fail("LP_NUM_THREADS is not set after re-executing");
  setenv("LP_NUM_THREADS", want.c_str(), 1);
  setenv("GALLIUM_DRIVER", "llvmpipe", 1);
  setenv(kReexecMarker, "1", 1);
  std::fflush(nullptr);
  execv("/proc/self/exe", argv);
  fail(std::string("execv /proc/self/exe: ") + std::strerror(errno));
}

struct ContextDeleter {
  void operator()(osmesa_context* c) const { OSMesaDestroyContext(c); }
};

}  // namespace

int main(int argc, char** argv) {
  uint32_t threads = 1;
  uint32_t frames = 5;
  CLI::App app{"tessera_llvmpipe_lines: 100,000 random GL_LINES in 500x500 in llvmpipe"};
  app.add_option("--threads", threads, "cores llvmpipe may use (1 = LP_NUM_THREADS=0)")
      ->check(CLI::Range(1u, 64u));
  app.add_option("--frames", frames, "timed frames after one warm-up")
      ->check(CLI::Range(1u, 1000u));
  CLI11_PARSE(app, argc, argv);
  ensure_llvmpipe_environment(threads, argv);

  const uint32_t size = tessera::bench::kLineWindow;
  std::vector<uint8_t> buffer(size_t{size} * size * 4);
  std::unique_ptr<osmesa_context, ContextDeleter> context(
      OSMesaCreateContextExt(OSMESA_RGBA, 24, 0, 0, nullptr));
  if (!context) fail("OSMesaCreateContextExt failed");
  if (!OSMesaMakeCurrent(context.get(), buffer.data(), GL_UNSIGNED_BYTE, size, size)) {
    fail("OSMesaMakeCurrent failed");
  }
  const char* renderer = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
  if (renderer == nullptr || std::strstr(renderer, "llvmpipe") == nullptr) {
    fail(std::string("OSMesa renders with '") + (renderer ? renderer : "(none)") +
         "', not llvmpipe");
  }

  const tessera::bench::LineWorkload lines = tessera::bench::random_lines();
  std::vector<float> interleaved;
  interleaved.reserve(lines.positions.size() * 8);
  for (size_t i = 0; i < lines.positions.size(); ++i) {
    const tessera::Float4& p = lines.positions[i];
    interleaved.insert(interleaved.end(), {p.x, p.y, p.z, p.w});
    interleaved.insert(interleaved.end(), lines.colors.begin() + static_cast<long>(4 * i),
                       lines.colors.begin() + static_cast<long>(4 * i + 4));
  }
  glViewport(0, 0, size, size);
  glMatrixMode(GL_PROJECTION);
  glLoadIdentity();
  glMatrixMode(GL_MODELVIEW);
  glLoadIdentity();
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_LIGHTING);
  glDisable(GL_DITHER);
  glShadeModel(GL_SMOOTH);
  glClearColor(0, 0, 0, 1);
  GLuint vbo = 0;
  glGenBuffers(1, &vbo);
  glBindBuffer(GL_ARRAY_BUFFER, vbo);
  glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(interleaved.size() * sizeof(float)),
               interleaved.data(), GL_STATIC_DRAW);
  constexpr GLsizei kStride = 8 * sizeof(float);
  glEnableClientState(GL_VERTEX_ARRAY);
  glVertexPointer(4, GL_FLOAT, kStride, nullptr);
  glEnableClientState(GL_COLOR_ARRAY);
  glColorPointer(4, GL_FLOAT, kStride, reinterpret_cast<const void*>(4 * sizeof(float)));
  const auto count = static_cast<GLsizei>(lines.positions.size());

  struct Variant {
    const char* name;
    float width;
    bool stipple, smooth;
  };
  for (const Variant& v :
       {Variant{"gl_lines", 1, false, false}, Variant{"gl_lines_stipple", 1, true, false},
        Variant{"gl_lines_wide3", 3, false, false}, Variant{"gl_lines_smooth", 1, false, true}}) {
    glLineWidth(v.width);
    if (v.stipple) {
      glEnable(GL_LINE_STIPPLE);
      glLineStipple(1, 0x0C0F);
    } else {
      glDisable(GL_LINE_STIPPLE);
    }
    if (v.smooth) {
      glEnable(GL_LINE_SMOOTH);
      glEnable(GL_BLEND);
      glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
    } else {
      glDisable(GL_LINE_SMOOTH);
      glDisable(GL_BLEND);
    }
    auto frame = [&] {
      const auto t0 = Clock::now();
      glClear(GL_COLOR_BUFFER_BIT);
      glDrawArrays(GL_LINES, 0, count);
      glFinish();
      return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
    };
    frame();
    if (glGetError() != GL_NO_ERROR) fail(std::string(v.name) + ": GL error");
    std::vector<double> times;
    for (uint32_t i = 0; i < frames; ++i)
      times.push_back(frame());
    const double median = median_of(times);
    std::printf(
        "llvmpipe variant=%s threads=%u frames=%u median_ms=%.3f min_ms=%.3f mlines_s=%.3f "
        "lp_num_threads=%u\n",
        v.name, threads, frames, median, *std::min_element(times.begin(), times.end()),
        tessera::bench::kLineCount / (median * 1e-3) / 1e6, lp_num_threads_for(threads));
    std::fflush(stdout);
  }
  glDeleteBuffers(1, &vbo);
  return 0;
}
