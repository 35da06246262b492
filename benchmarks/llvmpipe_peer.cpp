// tessera_llvmpipe_bench: replays TRI1 captures through Mesa's llvmpipe (via OSMesa) with
// exactly the state a capture means, times frames, and can dump llvmpipe's image, so Tessera's
// fast engine is measured and checked against its closest peer on the same triangles.
// llvmpipe reads LP_NUM_THREADS once per process, so the program re-executes itself with the
// environment that the requested thread count needs (see ensure_llvmpipe_environment).
#define GL_GLEXT_PROTOTYPES 1
#include <GL/osmesa.h>
// osmesa.h includes GL/gl.h; glext.h adds the buffer-object and framebuffer-object entry
// points, which libOSMesa exports itself (it is a complete GL library).
#include <GL/glext.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <limits>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "benchmarks/blend_workload.hpp"
#include "benchmarks/frame_times.hpp"
#include "benchmarks/phong_workload.hpp"
#include "benchmarks/texture_workload.hpp"
#include "tessera/io.hpp"
#include "tessera/tessera.hpp"

namespace {

using tessera::bench::median_of;

using Clock = std::chrono::steady_clock;

constexpr const char* kStandardWorkloads[] = {"tiny", "small", "medium", "large", "huge", "grid"};
// Set on the re-executed process, so that an environment which does not survive exec is
// reported instead of re-executing forever.
constexpr const char* kReexecMarker = "TESSERA_LLVMPIPE_REEXEC";

struct Options {
  std::vector<std::string> captures;
  uint32_t threads = 1;
  uint32_t frames = 10;
  uint32_t samples = 1;
  std::string shading = "gouraud";
  std::string write_png;
};

[[noreturn]] void fail(tessera::ErrorCode code, const std::string& message) {
  throw tessera::Error(code, message);
}

// The value of LP_NUM_THREADS that makes llvmpipe use `threads` cores: 0 rasterizes on the
// calling thread (one core in total); N >= 1 starts N rasterizer threads while the calling
// thread bins, so N = 1 would already keep two cores busy. Hence 1 -> 0 and N -> N.
uint32_t lp_num_threads_for(uint32_t threads) {
  return threads == 1 ? 0 : threads;
}

std::string hex(GLenum value) {
  char buf[16];
  std::snprintf(buf, sizeof buf, "0x%x", value);
  return buf;
}

bool env_equals(const char* name, const std::string& value) {
  const char* v = std::getenv(name);
  return v != nullptr && value == v;
}

// llvmpipe reads LP_NUM_THREADS (and OSMesa GALLIUM_DRIVER) when the first context creates
// its screen, from the process environment. Setting them with setenv() before that would work
// with today's Mesa, but depends on Mesa not caching its options earlier (at library load);
// a process that starts with the right environment does not. So when the environment differs,
// set it and execv /proc/self/exe with the same arguments. Returns only when it is right.
void ensure_llvmpipe_environment(uint32_t threads, char** argv) {
  const std::string want = std::to_string(lp_num_threads_for(threads));
  if (env_equals("LP_NUM_THREADS", want) && env_equals("GALLIUM_DRIVER", "llvmpipe")) return;
  if (std::getenv(kReexecMarker) != nullptr) {
    fail(tessera::ErrorCode::kInvalidArgument,
         "LP_NUM_THREADS=" + want +
             " and GALLIUM_DRIVER=llvmpipe are still not set after "
             "re-executing; set them in the caller's environment");
  }
  setenv("LP_NUM_THREADS", want.c_str(), 1);
  setenv("GALLIUM_DRIVER", "llvmpipe", 1);
  setenv(kReexecMarker, "1", 1);
  std::fflush(nullptr);
  execv("/proc/self/exe", argv);
  fail(tessera::ErrorCode::kIo, std::string("execv /proc/self/exe: ") + std::strerror(errno));
}

// llvmpipe names its rasterizer threads "llvmpipe-K"; counting them confirms the thread
// count actually in force (0 for LP_NUM_THREADS=0).
uint32_t count_llvmpipe_threads() {
  uint32_t n = 0;
  std::error_code ec;
  for (const auto& task : std::filesystem::directory_iterator("/proc/self/task", ec)) {
    std::ifstream comm(task.path() / "comm");
    std::string name;
    if (std::getline(comm, name) && name.rfind("llvmpipe-", 0) == 0) ++n;
  }
  return n;
}

struct ContextDeleter {
  void operator()(osmesa_context* c) const { OSMesaDestroyContext(c); }
};
using ContextPtr = std::unique_ptr<osmesa_context, ContextDeleter>;

// A multisampled framebuffer object with colour and 24-bit depth, when the context offers
// 4x MSAA (OSMesa's own buffer is single-sampled; llvmpipe rasterizes MSAA in an FBO).
struct MsaaTarget {
  GLuint fbo = 0;
  GLuint color = 0;
  GLuint depth = 0;
};

// Why `samples`-x MSAA cannot be had in the current context, or "" when it can.
std::string msaa_unavailable_reason(uint32_t samples) {
  GLint max_samples = 0;
  glGetIntegerv(GL_MAX_SAMPLES, &max_samples);
  if (glGetError() != GL_NO_ERROR || max_samples < static_cast<GLint>(samples)) {
    return "GL_MAX_SAMPLES=" + std::to_string(max_samples);
  }
  return "";
}

MsaaTarget make_msaa_target(uint32_t width, uint32_t height, uint32_t samples) {
  MsaaTarget t;
  const auto w = static_cast<GLsizei>(width), h = static_cast<GLsizei>(height);
  const auto s = static_cast<GLsizei>(samples);
  glGenRenderbuffers(1, &t.color);
  glBindRenderbuffer(GL_RENDERBUFFER, t.color);
  glRenderbufferStorageMultisample(GL_RENDERBUFFER, s, GL_RGBA8, w, h);
  glGenRenderbuffers(1, &t.depth);
  glBindRenderbuffer(GL_RENDERBUFFER, t.depth);
  glRenderbufferStorageMultisample(GL_RENDERBUFFER, s, GL_DEPTH_COMPONENT24, w, h);
  glGenFramebuffers(1, &t.fbo);
  glBindFramebuffer(GL_FRAMEBUFFER, t.fbo);
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, t.color);
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, t.depth);
  const GLenum status = glCheckFramebufferStatus(GL_FRAMEBUFFER);
  if (status != GL_FRAMEBUFFER_COMPLETE) {
    fail(tessera::ErrorCode::kInvalidArgument,
         "--samples " + std::to_string(samples) +
             ": the multisampled framebuffer is incomplete (status " + hex(status) + ")");
  }
  glEnable(GL_MULTISAMPLE);
  // The sample positions (GL: from the pixel's bottom-left corner, y up) explain coverage
  // differences at edges from Tessera's D3D positions (from the top-left corner, y down).
  std::fprintf(stderr, "sample positions (x, y up):");
  for (GLuint i = 0; i < samples; ++i) {
    GLfloat pos[2] = {0, 0};
    glGetMultisamplefv(GL_SAMPLE_POSITION, i, pos);
    std::fprintf(stderr, " (%.4g, %.4g)", double(pos[0]), double(pos[1]));
  }
  std::fprintf(stderr, "\n");
  return t;
}

// A capture's vertices interleaved as the GL arrays read them: x y z w, then the vertex's `n`
// values of `varyings` (the capture's own colours: r g b a).
std::vector<float> interleave(const tessera::Capture& capture, const std::vector<float>& varyings,
                              size_t n) {
  std::vector<float> v;
  v.reserve(capture.positions.size() * (4 + n));
  for (size_t i = 0; i < capture.positions.size(); ++i) {
    const tessera::Float4& p = capture.positions[i];
    v.insert(v.end(), {p.x, p.y, p.z, p.w});
    v.insert(v.end(), varyings.begin() + static_cast<std::ptrdiff_t>(n * i),
             varyings.begin() + static_cast<std::ptrdiff_t>(n * i + n));
  }
  return v;
}

// Generic vertex attributes 0, 1, ... of `sizes` floats each, packed in that order per vertex.
void enable_attributes(std::initializer_list<GLint> sizes) {
  GLsizei stride = 0;
  for (const GLint size : sizes)
    stride += size * static_cast<GLsizei>(sizeof(float));
  GLuint index = 0;
  size_t offset = 0;
  for (const GLint size : sizes) {
    glEnableVertexAttribArray(index);
    glVertexAttribPointer(index++, size, GL_FLOAT, GL_FALSE, stride,
                          reinterpret_cast<const void*>(offset * sizeof(float)));
    offset += static_cast<size_t>(size);
  }
}

// The state a TRI1 capture is drawn with (capture.hpp, tessera::capture_pipeline()): clip
// space straight to gl_Position (identity matrices), OpenGL depth (-w <= z <= w mapped to
// 0..1 by glDepthRange), viewport = capture size, depth test LESS against a depth buffer
// cleared to 1.0, no culling, no blending, smooth (perspective-correct) colour.
void set_capture_state(uint32_t width, uint32_t height) {
  glViewport(0, 0, static_cast<GLsizei>(width), static_cast<GLsizei>(height));
  glDepthRange(0.0, 1.0);
  glMatrixMode(GL_PROJECTION);
  glLoadIdentity();
  glMatrixMode(GL_MODELVIEW);
  glLoadIdentity();
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glDepthMask(GL_TRUE);
  glClearDepth(1.0);
  glDisable(GL_CULL_FACE);
  glDisable(GL_LIGHTING);
  glDisable(GL_BLEND);
  glDisable(GL_DITHER);
  glShadeModel(GL_SMOOTH);
  glHint(GL_PERSPECTIVE_CORRECTION_HINT, GL_NICEST);
  glClearColor(0.0f, 0.0f, 0.0f, 1.0f);
}

// Per-pixel Phong in GLSL (benchmarks/phong_workload.hpp): Tessera's formula
// (tessera/shading.hpp) with its TRI2 defaults and three point lights (c0 = 1: no attenuation).
constexpr const char* kPhongVertexShader = R"(#version 120
attribute vec4 clip;
attribute vec3 normal;
attribute vec3 position;
attribute vec4 colour;
varying vec3 v_normal;
varying vec3 v_position;
varying vec4 v_colour;
void main() {
  gl_Position = clip;
  v_normal = normal;
  v_position = position;
  v_colour = colour;
}
)";
constexpr const char* kPhongFragmentShader = R"(#version 120
uniform vec3 lights[3];
varying vec3 v_normal;
varying vec3 v_position;
varying vec4 v_colour;
void main() {
  vec3 n = normalize(v_normal);
  vec3 v = normalize(-v_position);
  vec3 intensity = vec3(0.1);
  for (int l = 0; l < 3; ++l) {
    vec3 to_light = normalize(lights[l] - v_position);
    float n_dot_l = dot(n, to_light);
    float specular = 0.0;
    if (n_dot_l > 0.0) {
      vec3 r = 2.0 * n_dot_l * n - to_light;
      specular = 0.2 * pow(max(dot(r, v), 0.0), 32.0);
    }
    intensity += vec3(0.7 * max(n_dot_l, 0.0) + specular);
  }
  gl_FragColor = vec4(clamp(intensity * v_colour.rgb, 0.0, 1.0), v_colour.a);
}
)";

// The textured workload (benchmarks/texture_workload.hpp): the texture times the colour.
constexpr const char* kTexturedVertexShader = R"(#version 120
attribute vec4 clip;
attribute vec2 texcoord;
attribute vec4 colour;
varying vec2 v_texcoord;
varying vec4 v_colour;
void main() {
  gl_Position = clip;
  v_texcoord = texcoord;
  v_colour = colour;
}
)";
constexpr const char* kTexturedFragmentShader = R"(#version 120
uniform sampler2D tex;
varying vec2 v_texcoord;
varying vec4 v_colour;
void main() {
  gl_FragColor = texture2D(tex, v_texcoord) * v_colour;
}
)";

void check_gl(const char* what) {
  const GLenum e = glGetError();
  if (e != GL_NO_ERROR)
    fail(tessera::ErrorCode::kInvalidInput, std::string(what) + ": GL error " + hex(e));
}

GLuint compile_shader(GLenum type, const char* source) {
  const GLuint shader = glCreateShader(type);
  glShaderSource(shader, 1, &source, nullptr);
  glCompileShader(shader);
  GLint ok = GL_FALSE;
  glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  if (ok != GL_TRUE) {
    char log[1024] = {};
    glGetShaderInfoLog(shader, sizeof log, nullptr, log);
    fail(tessera::ErrorCode::kInvalidArgument, std::string("GLSL compile error: ") + log);
  }
  return shader;
}

// A program of the two shaders with `attributes` bound to 0, 1, ..., in use.
GLuint use_program(const char* vertex, const char* fragment,
                   std::initializer_list<const char*> attributes) {
  const GLuint program = glCreateProgram();
  glAttachShader(program, compile_shader(GL_VERTEX_SHADER, vertex));
  glAttachShader(program, compile_shader(GL_FRAGMENT_SHADER, fragment));
  GLuint location = 0;
  for (const char* a : attributes)
    glBindAttribLocation(program, location++, a);
  glLinkProgram(program);
  GLint ok = GL_FALSE;
  glGetProgramiv(program, GL_LINK_STATUS, &ok);
  if (ok != GL_TRUE) {
    char log[1024] = {};
    glGetProgramInfoLog(program, sizeof log, nullptr, log);
    fail(tessera::ErrorCode::kInvalidArgument, std::string("GLSL link error: ") + log);
  }
  glUseProgram(program);
  return program;
}

// The Phong program with the Phong varyings' attributes bound to 0..3, in use.
GLuint use_phong_program() {
  const GLuint program = use_program(kPhongVertexShader, kPhongFragmentShader,
                                     {"clip", "normal", "position", "colour"});
  glUniform3fv(glGetUniformLocation(program, "lights"), 3, &tessera::bench::kPhongLights[0][0]);
  return program;
}

// The textured program, and the benchmark texture bound to unit 0 with every level of
// Tessera's own mip chain (the same texels), filtered as `trilinear` says, repeat wrapping.
GLuint use_textured_program(const tessera::Texture& texture, bool trilinear, GLuint& name) {
  const GLuint program =
      use_program(kTexturedVertexShader, kTexturedFragmentShader, {"clip", "texcoord", "colour"});
  glUniform1i(glGetUniformLocation(program, "tex"), 0);
  glActiveTexture(GL_TEXTURE0);
  glGenTextures(1, &name);
  glBindTexture(GL_TEXTURE_2D, name);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  for (uint32_t level = 0; level < texture.levels(); ++level) {
    glTexImage2D(GL_TEXTURE_2D, static_cast<GLint>(level), GL_RGBA8,
                 static_cast<GLsizei>(texture.width(level)),
                 static_cast<GLsizei>(texture.height(level)), 0, GL_RGBA, GL_UNSIGNED_BYTE,
                 texture.level_bytes(level).data());
  }
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAX_LEVEL, static_cast<GLint>(texture.levels() - 1));
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER,
                  trilinear ? GL_LINEAR_MIPMAP_LINEAR : GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_REPEAT);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_REPEAT);
  return program;
}

// Renders one capture: K timed frames after one warm-up, prints the summary line, and writes
// the last frame's image when asked. Returns false when the capture cannot be drawn as asked
// (MSAA not available), after saying so on stdout.
bool run_capture(const std::filesystem::path& path, const Options& o) {
  const std::string workload = path.stem().string();
  const tessera::Capture capture = tessera::load_capture(path);
  const uint32_t width = capture.width, height = capture.height;
  const size_t vertex_count = capture.positions.size();
  const size_t triangles = vertex_count / 3;
  if (vertex_count > static_cast<size_t>(std::numeric_limits<GLsizei>::max())) {
    fail(tessera::ErrorCode::kInvalidInput,
         path.string() + ": too many vertices for one glDrawArrays");
  }

  std::vector<uint8_t> osmesa_buffer(size_t{width} * height * 4);
  ContextPtr context(OSMesaCreateContextExt(OSMESA_RGBA, 24, 0, 0, nullptr));
  if (!context) fail(tessera::ErrorCode::kInvalidArgument, "OSMesaCreateContextExt failed");
  if (!OSMesaMakeCurrent(context.get(), osmesa_buffer.data(), GL_UNSIGNED_BYTE,
                         static_cast<GLsizei>(width), static_cast<GLsizei>(height))) {
    fail(tessera::ErrorCode::kInvalidArgument,
         "OSMesaMakeCurrent failed at " + std::to_string(width) + "x" + std::to_string(height));
  }
  const char* renderer = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
  if (renderer == nullptr || std::strstr(renderer, "llvmpipe") == nullptr) {
    fail(tessera::ErrorCode::kInvalidArgument,
         std::string("OSMesa renders with '") + (renderer ? renderer : "(none)") +
             "', not llvmpipe: this Mesa build has no llvmpipe (GALLIUM_DRIVER=llvmpipe is set)");
  }
  GLint depth_bits = 0;
  glGetIntegerv(GL_DEPTH_BITS, &depth_bits);
  if (depth_bits < 24) {
    fail(tessera::ErrorCode::kInvalidArgument,
         "the OSMesa context has a " + std::to_string(depth_bits) + "-bit depth buffer, not 24");
  }
  std::fprintf(stderr, "%s: %s, %s\n", workload.c_str(), renderer,
               reinterpret_cast<const char*>(glGetString(GL_VERSION)));

  set_capture_state(width, height);
  MsaaTarget msaa;
  if (o.samples > 1) {
    const std::string reason = msaa_unavailable_reason(o.samples);
    if (!reason.empty()) {
      std::printf("llvmpipe workload=%s samples=%u msaa=unavailable reason=%s\n", workload.c_str(),
                  o.samples, reason.c_str());
      return false;
    }
    msaa = make_msaa_target(width, height, o.samples);
  }

  // Upload once: the timed frames draw from a buffer object, as an application would.
  const bool phong = o.shading == "phong";
  const bool textured = o.shading == "bilinear" || o.shading == "trilinear";
  const bool blended = o.shading == "blended";
  const std::vector<float> vertices =
      textured  ? interleave(capture, tessera::bench::textured_varyings(capture),
                             tessera::bench::kTexturedVaryings)
      : phong   ? interleave(capture, tessera::bench::phong_varyings(capture),
                             tessera::bench::kPhongVaryings)
      : blended ? interleave(capture, tessera::bench::blended_varyings(capture), 4)
                : interleave(capture, capture.varyings, 4);
  if (blended) {  // blend_workload.hpp's state (depth writes off around the draw only, below)
    glEnable(GL_BLEND);
    glBlendEquation(GL_FUNC_ADD);
    glBlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
  }
  GLuint vbo = 0;
  glGenBuffers(1, &vbo);
  glBindBuffer(GL_ARRAY_BUFFER, vbo);
  glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(vertices.size() * sizeof(float)),
               vertices.data(), GL_STATIC_DRAW);
  GLuint program = 0;
  GLuint texture_name = 0;
  if (textured) {
    program = use_textured_program(*tessera::bench::benchmark_texture(), o.shading == "trilinear",
                                   texture_name);
    enable_attributes({4, 2, 4});  // clip, texcoord, colour
  } else if (phong) {
    program = use_phong_program();
    enable_attributes({4, 3, 3, 4});  // clip, normal, position, colour
  } else {
    constexpr GLsizei kStride = 8 * sizeof(float);
    glEnableClientState(GL_VERTEX_ARRAY);
    glVertexPointer(4, GL_FLOAT, kStride, nullptr);
    glEnableClientState(GL_COLOR_ARRAY);
    glColorPointer(4, GL_FLOAT, kStride, reinterpret_cast<const void*>(4 * sizeof(float)));
  }
  check_gl("setting up the capture state");

  const auto count = static_cast<GLsizei>(vertex_count);
  auto frame = [&](bool draw) {
    const auto t0 = Clock::now();
    // glClear writes depth only under glDepthMask(GL_TRUE): the blended draw turns depth
    // writes off after the clear and back on for the next frame's.
    glDepthMask(GL_TRUE);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    if (blended) glDepthMask(GL_FALSE);
    if (draw) glDrawArrays(GL_TRIANGLES, 0, count);
    glFinish();
    return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
  };

  // An empty frame (clear + glFinish, which also copies OSMesa's colour buffer out) is the
  // fixed cost included in every timed frame; reported so small workloads can be read.
  frame(false);
  std::vector<double> empty;
  for (int i = 0; i < 3; ++i)
    empty.push_back(frame(false));
  frame(true);  // warm-up: compiles llvmpipe's shaders for this state
  check_gl("the warm-up frame");
  const uint32_t threads_seen = count_llvmpipe_threads();
  const uint32_t lp_num_threads = lp_num_threads_for(o.threads);
  if (threads_seen != lp_num_threads) {
    std::fprintf(stderr, "warning: %u llvmpipe rasterizer threads running, expected %u\n",
                 threads_seen, lp_num_threads);
  }
  std::vector<double> times;
  for (uint32_t i = 0; i < o.frames; ++i)
    times.push_back(frame(true));
  check_gl("the timed frames");

  const double median = median_of(times);
  const double mtri_s = static_cast<double>(triangles) / (median * 1e-3) / 1e6;
  // Every frame's time last (times_ms=a,b,...), in frame order, for tessera_workload_bench.
  std::string frame_times;
  for (const double t : times) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%s%.3f", frame_times.empty() ? "" : ",", t);
    frame_times += buf;
  }
  std::printf(
      "llvmpipe workload=%s shading=%s threads=%u frames=%u median_ms=%.3f min_ms=%.3f "
      "max_ms=%.3f mtri_s=%.3f samples=%u lp_num_threads=%u lp_threads_seen=%u empty_ms=%.3f "
      "triangles=%zu size=%ux%u times_ms=%s\n",
      workload.c_str(), o.shading.c_str(), o.threads, o.frames, median,
      *std::min_element(times.begin(), times.end()), *std::max_element(times.begin(), times.end()),
      mtri_s, o.samples, lp_num_threads, threads_seen, median_of(empty), triangles, width, height,
      frame_times.c_str());
  std::fflush(stdout);

  if (!o.write_png.empty()) {
    if (msaa.fbo != 0) {  // resolve into OSMesa's buffer (not timed: Tessera resolves on read)
      glBindFramebuffer(GL_READ_FRAMEBUFFER, msaa.fbo);
      glBindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
      const auto w = static_cast<GLint>(width), h = static_cast<GLint>(height);
      glBlitFramebuffer(0, 0, w, h, 0, 0, w, h, GL_COLOR_BUFFER_BIT, GL_NEAREST);
      glBindFramebuffer(GL_FRAMEBUFFER, 0);
    }
    std::vector<uint8_t> pixels(size_t{width} * height * 4);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, static_cast<GLsizei>(width), static_cast<GLsizei>(height), GL_RGBA,
                 GL_UNSIGNED_BYTE, pixels.data());
    check_gl("reading the image back");
    // GL rows are bottom first; Tessera's images (and capture.hpp's NDC y up) are top first.
    const size_t row = size_t{width} * 4;
    std::vector<uint8_t> top_first(pixels.size());
    for (uint32_t y = 0; y < height; ++y) {
      std::memcpy(top_first.data() + size_t{y} * row, pixels.data() + size_t{height - 1 - y} * row,
                  row);
    }
    tessera::write_image(o.write_png, width, height, 4, std::span<const uint8_t>(top_first));
    std::fprintf(stderr, "wrote %s\n", o.write_png.c_str());
  }

  glDeleteBuffers(1, &vbo);
  if (program != 0) glDeleteProgram(program);
  if (texture_name != 0) glDeleteTextures(1, &texture_name);
  if (msaa.fbo != 0) {
    glDeleteFramebuffers(1, &msaa.fbo);
    glDeleteRenderbuffers(1, &msaa.color);
    glDeleteRenderbuffers(1, &msaa.depth);
  }
  return true;
}

std::vector<std::filesystem::path> capture_paths(const Options& o) {
  std::vector<std::filesystem::path> paths;
  if (!o.captures.empty()) {
    for (const std::string& c : o.captures)
      paths.emplace_back(c);
    return paths;
  }
  const char* env = std::getenv("TESSERA_WORKLOADS");
  const std::filesystem::path dir = env ? env : "build/workloads";
  for (const char* name : kStandardWorkloads) {
    const std::filesystem::path p = dir / (std::string(name) + ".tri");
    if (std::filesystem::exists(p)) {
      paths.push_back(p);
    } else {
      std::fprintf(stderr, "skipping %s: not found (run scripts/make-workloads.sh)\n",
                   p.string().c_str());
    }
  }
  if (paths.empty()) {
    fail(tessera::ErrorCode::kIo, "no standard workload found in " + dir.string() +
                                      " (set TESSERA_WORKLOADS or run scripts/make-workloads.sh)");
  }
  return paths;
}

}  // namespace

int main(int argc, char** argv) {
  Options o;
  CLI::App app{
      "tessera_llvmpipe_bench: time TRI1 captures in Mesa's llvmpipe (OSMesa), the "
      "peer of Tessera's fast engine; prints one line per capture"};
  app.add_option("captures", o.captures,
                 "TRI1 captures; none: the six standard workloads from $TESSERA_WORKLOADS "
                 "(default build/workloads)");
  app.add_option("--threads", o.threads,
                 "cores llvmpipe may use: 1 sets LP_NUM_THREADS=0 (rasterize on the calling "
                 "thread), N>1 sets LP_NUM_THREADS=N; the program re-executes itself with it")
      ->check(CLI::Range(1u, 64u))
      ->capture_default_str();
  app.add_option("--frames", o.frames, "timed frames after one warm-up")
      ->check(CLI::Range(1u, 100000u))
      ->capture_default_str();
  app.add_option("--samples", o.samples,
                 "1, or 4 for 4x MSAA in a multisampled FBO when the context offers it")
      ->check(CLI::IsMember({1u, 4u}))
      ->capture_default_str();
  app.add_option("--shading", o.shading,
                 "gouraud (the capture's colours); phong: per-pixel Phong in GLSL of the "
                 "varyings benchmarks/phong_workload.hpp makes from the capture; bilinear or "
                 "trilinear: the texture of benchmarks/texture_workload.hpp times the colour; "
                 "blended: the colours at alpha 0.5 blended over without depth writes "
                 "(benchmarks/blend_workload.hpp)")
      ->check(CLI::IsMember({"gouraud", "phong", "bilinear", "trilinear", "blended"}))
      ->capture_default_str();
  app.add_option("--write-png", o.write_png,
                 "write llvmpipe's image of the capture (top row first, like tessera-render); "
                 "needs exactly one capture");
  app.failure_message([](const CLI::App*, const CLI::Error& error) {
    std::string message = error.what();
    std::replace(message.begin(), message.end(), '\n', ' ');
    return "tessera_llvmpipe_bench: " + message + " (see --help)\n";
  });
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  }
  try {
    if (!o.write_png.empty() && o.captures.size() != 1) {
      fail(tessera::ErrorCode::kInvalidArgument, "--write-png: give exactly one capture");
    }
    ensure_llvmpipe_environment(o.threads, argv);
    bool all_drawn = true;
    for (const std::filesystem::path& p : capture_paths(o))
      all_drawn &= run_capture(p, o);
    return all_drawn ? 0 : 2;
  } catch (const std::exception& e) {
    std::string message = e.what();
    std::replace(message.begin(), message.end(), '\n', ' ');
    std::fprintf(stderr, "tessera_llvmpipe_bench: %s\n", message.c_str());
    return 1;
  }
}
