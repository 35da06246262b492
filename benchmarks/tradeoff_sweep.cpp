// The speed-against-accuracy sweep (docs/TRADEOFFS.md): every knob value measured for speed on
// the standard workloads and real meshes, and for error against ground truth that needs no
// trust in the fast engine: a 256-samples-per-pixel (16x16 grid) reference render for edges,
// z-fighting of two close planes for depth formats, the analytic texture coordinates of a
// receding checkerboard for interpolation, hit counts on watertight meshes for snapping, and a
// 256-samples-per-pixel reference render of a textured floor for texture filters.
// Writes CSV and JSON; scripts/plot-tradeoffs.py draws the charts.
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <numbers>
#include <optional>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/mat4x4.hpp>

#include "benchmarks/frame_times.hpp"
#include "benchmarks/texture_workload.hpp"
#include "tessera/io.hpp"
#include "tessera/tessera.hpp"

namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

// --- The knobs ------------------------------------------------------------------------------

// Everything a knob can change about a render.
struct Settings {
  uint32_t samples = 1;
  uint32_t subpixel_bits = 8;
  tessera::DepthFormat depth_format = tessera::DepthFormat::kFloat32;
  bool reversed_z = false;
  tessera::Interpolation interpolation = tessera::Interpolation::kPerspective;
  bool hiz = true;
  uint32_t bin_tile_size = 64;
  uint32_t block_size = 8;
};

struct KnobValue {
  std::string knob, value;
  Settings settings;
};

// Each knob swept over its values, the others at their defaults.
std::vector<KnobValue> knob_values() {
  std::vector<KnobValue> out;
  for (uint32_t bits = tessera::kMinSubpixelBits; bits <= tessera::kMaxSubpixelBits; ++bits) {
    Settings s;
    s.subpixel_bits = bits;
    out.push_back({"subpixel_bits", std::to_string(bits), s});
  }
  for (uint32_t samples : {1u, 2u, 4u, 8u, 16u}) {
    Settings s;
    s.samples = samples;
    out.push_back({"samples", std::to_string(samples), s});
  }
  const std::pair<const char*, tessera::DepthFormat> formats[] = {
      {"float32", tessera::DepthFormat::kFloat32},
      {"unorm24", tessera::DepthFormat::kUnorm24},
      {"unorm16", tessera::DepthFormat::kUnorm16}};
  for (const auto& [name, format] : formats) {
    Settings s;
    s.depth_format = format;
    out.push_back({"depth_format", name, s});
  }
  {
    Settings s;
    s.reversed_z = true;
    out.push_back({"depth_format", "float32_reversed", s});
  }
  for (bool affine : {false, true}) {
    Settings s;
    s.interpolation =
        affine ? tessera::Interpolation::kAffine : tessera::Interpolation::kPerspective;
    out.push_back({"interpolation", affine ? "affine" : "perspective", s});
  }
  for (bool hiz : {true, false}) {
    Settings s;
    s.hiz = hiz;
    out.push_back({"hiz", hiz ? "on" : "off", s});
  }
  for (uint32_t size : {32u, 64u, 128u}) {
    Settings s;
    s.bin_tile_size = size;
    out.push_back({"bin_tile_size", std::to_string(size), s});
  }
  for (uint32_t size : {8u, 16u, 32u}) {
    Settings s;
    s.block_size = size;
    out.push_back({"block_size", std::to_string(size), s});
  }
  return out;
}

tessera::PipelineState pipeline_for(const Settings& s, tessera::PipelineState p = {}) {
  p.subpixel_bits = s.subpixel_bits;
  p.interpolation = s.interpolation;
  if (s.reversed_z) p.depth_compare = tessera::CompareOp::kGreater;
  return p;
}

tessera::Framebuffer framebuffer_for(const Settings& s, uint32_t width, uint32_t height,
                                     tessera::ColorFormat color = tessera::ColorFormat::kRGBA8) {
  return tessera::Framebuffer({width, height, s.samples, color, s.depth_format});
}

void clear(tessera::Framebuffer& fb, const Settings& s) {
  fb.clear_color({0.05f, 0.06f, 0.08f, 1.0f});
  fb.clear_depth(s.reversed_z ? 0.0f : 1.0f);
}

// --- Progress -------------------------------------------------------------------------------

class Progress {
 public:
  explicit Progress(size_t total) : total_(total) {}
  void step(const std::string& what) {
    ++done_;
    const int width = 30;
    const int filled = static_cast<int>(width * done_ / std::max<size_t>(total_, 1));
    std::fprintf(stderr, "\r[%s%s] %3zu%% %-60.60s", std::string(filled, '#').c_str(),
                 std::string(width - filled, '.').c_str(),
                 100 * done_ / std::max<size_t>(total_, 1), what.c_str());
    if (done_ == total_) std::fprintf(stderr, "\n");
  }

 private:
  size_t total_, done_ = 0;
};

// --- Speed ----------------------------------------------------------------------------------

// One thing to time: a capture (clip-space triangles) or a scene (meshes and a camera).
struct Workload {
  std::string name;
  std::optional<tessera::Capture> capture;
  std::optional<tessera::Scene> scene;
  uint32_t width = 0, height = 0;
  size_t triangles = 0;
};

void draw_workload(tessera::Renderer& renderer, tessera::Framebuffer& fb, const Settings& s,
                   const Workload& w) {
  if (w.capture) {
    tessera::DrawInput input;
    input.positions = w.capture->positions;
    input.attributes = w.capture->varyings;
    input.attribute_count = 4;
    renderer.draw(fb, pipeline_for(s, tessera::capture_pipeline()), input);
  } else {
    tessera::Scene scene = *w.scene;
    scene.camera.reversed_z = s.reversed_z;
    tessera::draw_scene(renderer, fb, pipeline_for(s), scene);
  }
}

// Median ms per frame (clear + draw(renderer, fb)) over `frames` frames after one warm-up, on a
// width x height framebuffer with the settings' renderer options.
double median_frame_ms(const Settings& s, uint32_t width, uint32_t height, uint32_t threads,
                       int frames,
                       const std::function<void(tessera::Renderer&, tessera::Framebuffer&)>& draw) {
  tessera::RendererOptions options;
  options.threads = threads;
  options.hiz = s.hiz;
  options.bin_tile_size = s.bin_tile_size;
  options.block_size = s.block_size;
  options.raster_counters = false;
  tessera::Renderer renderer(options);
  tessera::Framebuffer fb = framebuffer_for(s, width, height);
  std::vector<double> ms;
  for (int f = -1; f < frames; ++f) {
    const auto t0 = Clock::now();
    clear(fb, s);
    draw(renderer, fb);
    if (f >= 0) ms.push_back(std::chrono::duration<double, std::milli>(Clock::now() - t0).count());
  }
  return tessera::bench::median_of(ms);
}

double time_frames(const Settings& s, const Workload& w, uint32_t threads, int frames) {
  Settings timed = s;
  if (w.capture) timed.reversed_z = false;  // a capture's depth is fixed: reversed Z is a camera
  return median_frame_ms(timed, w.width, w.height, threads, frames,
                         [&](tessera::Renderer& renderer, tessera::Framebuffer& fb) {
                           draw_workload(renderer, fb, timed, w);
                         });
}

// --- Edge quality ---------------------------------------------------------------------------

struct Image {
  uint32_t width = 0, height = 0;
  std::vector<float> rgba;  // resolved, linear, top row first
};

// The scene's colour, resolved.
Image render_colour(const tessera::Scene& scene, const Settings& s, uint32_t width, uint32_t height,
                    tessera::Backend backend) {
  tessera::RendererOptions options;
  options.backend = backend;
  options.threads = 0;
  options.hiz = s.hiz;
  options.bin_tile_size = s.bin_tile_size;
  options.block_size = s.block_size;
  tessera::Renderer renderer(options);
  tessera::Framebuffer fb = framebuffer_for(s, width, height, tessera::ColorFormat::kRGBA32F);
  clear(fb, s);
  tessera::Scene drawn = scene;
  drawn.camera.reversed_z = s.reversed_z;
  tessera::draw_scene(renderer, fb, pipeline_for(s), drawn);
  return {width, height, fb.read_rgba32f()};
}

// The index + 1 of the object seen at each pixel centre (0: background).
std::vector<uint32_t> render_ids(const tessera::Scene& scene, uint32_t width, uint32_t height) {
  tessera::RendererOptions options;
  options.backend = tessera::Backend::kReference;
  tessera::Renderer renderer(options);
  tessera::Framebuffer fb({width, height, 1, tessera::ColorFormat::kRGBA32F});
  fb.clear_color({0, 0, 0, 0});
  const float aspect = static_cast<float>(width) / static_cast<float>(height);
  const glm::mat4 vp = scene.camera.projection(aspect) * scene.camera.view();
  tessera::PipelineState pipeline;
  pipeline.interpolation = tessera::Interpolation::kAffine;  // constant ids stay exact
  float id = 0.0f;
  for (const tessera::SceneObject& o : scene.objects) {
    id += 1.0f;
    const std::vector<tessera::Float4> clip =
        tessera::to_clip_space(o.mesh.positions, vp * o.model);
    std::vector<tessera::Float4> positions;
    std::vector<float> ids;
    for (size_t i = 0; i < o.mesh.indices.size(); i += 3) {
      for (int k = 0; k < 3; ++k) {
        positions.push_back(clip[o.mesh.indices[i + k]]);
        ids.insert(ids.end(), {id, 0.0f, 0.0f, 1.0f});
      }
    }
    tessera::DrawInput input;
    input.positions = positions;
    input.attributes = ids;
    input.attribute_count = 4;
    renderer.draw(fb, pipeline, input);
  }
  const std::vector<float> rgba = fb.read_rgba32f();
  std::vector<uint32_t> out(size_t{width} * height);
  for (size_t p = 0; p < out.size(); ++p)
    out[p] = static_cast<uint32_t>(std::lround(rgba[p * 4]));
  return out;
}

// Ground truth: the reference at `factor` times the resolution with one sample at each pixel
// centre, box-filtered: factor x factor samples on a regular grid per pixel. Edge pixels are
// those whose samples see more than one object (or an object and the background): silhouettes
// and occlusion boundaries, where antialiasing matters.
struct GroundTruth {
  Image image;
  std::vector<bool> edge;
};

GroundTruth ground_truth(const tessera::Scene& scene, uint32_t width, uint32_t height,
                         uint32_t factor) {
  const uint32_t w = width * factor, h = height * factor;
  const Image fine = render_colour(scene, Settings{}, w, h, tessera::Backend::kReference);
  const std::vector<uint32_t> ids = render_ids(scene, w, h);
  GroundTruth gt;
  gt.image = {width, height, std::vector<float>(size_t{width} * height * 4, 0.0f)};
  gt.edge.assign(size_t{width} * height, false);
  const float inv = 1.0f / static_cast<float>(factor * factor);
  for (uint32_t y = 0; y < height; ++y) {
    for (uint32_t x = 0; x < width; ++x) {
      const size_t p = size_t{y} * width + x;
      const uint32_t first = ids[size_t{y * factor} * w + x * factor];
      for (uint32_t j = 0; j < factor; ++j) {
        for (uint32_t i = 0; i < factor; ++i) {
          const size_t q = size_t{y * factor + j} * w + (x * factor + i);
          for (int c = 0; c < 4; ++c)
            gt.image.rgba[p * 4 + c] += fine.rgba[q * 4 + c] * inv;
          if (ids[q] != first) gt.edge[p] = true;
        }
      }
    }
  }
  return gt;
}

struct ImageError {
  double rmse = 0, psnr = 0, rmse_edges = 0, psnr_edges = 0;
};

// RMSE of RGB in 8-bit units (colour values clamped to [0, 1] as a display would) and PSNR.
ImageError image_error(const Image& test, const GroundTruth& gt) {
  double all = 0, edges = 0;
  size_t n_all = 0, n_edges = 0;
  for (size_t p = 0; p < gt.edge.size(); ++p) {
    double e = 0;
    for (int c = 0; c < 3; ++c) {
      const double a = std::clamp(test.rgba[p * 4 + c], 0.0f, 1.0f) * 255.0;
      const double b = std::clamp(gt.image.rgba[p * 4 + c], 0.0f, 1.0f) * 255.0;
      e += (a - b) * (a - b);
    }
    all += e;
    n_all += 3;
    if (gt.edge[p]) {
      edges += e;
      n_edges += 3;
    }
  }
  const auto psnr = [](double rmse) { return rmse > 0 ? 20.0 * std::log10(255.0 / rmse) : 99.0; };
  ImageError r;
  r.rmse = std::sqrt(all / static_cast<double>(std::max<size_t>(n_all, 1)));
  r.rmse_edges = std::sqrt(edges / static_cast<double>(std::max<size_t>(n_edges, 1)));
  r.psnr = psnr(r.rmse);
  r.psnr_edges = psnr(r.rmse_edges);
  return r;
}

// --- Depth precision ------------------------------------------------------------------------

// Two parallel planes a relative distance `gap` apart, tilted so depth varies over the image
// (by about 6% of d from the centre to the top and bottom), centred at distance d from the eye:
// the farther (drawn first), then the nearer plane. Returns the fraction of pixels where the
// nearer plane is not visible: the farther one won the depth test, or (a fixed-point buffer at
// the far end) neither plane passed against the cleared far value.
double near_plane_hidden(const Settings& s, double near_plane, double far_plane, double d,
                         double gap, uint32_t size) {
  tessera::Camera camera;
  camera.eye = {0, 0, 0};
  camera.target = {0, 0, -1};
  camera.fov_y_degrees = 60.0f;
  camera.near_plane = static_cast<float>(near_plane);
  camera.far_plane = static_cast<float>(far_plane);
  camera.reversed_z = s.reversed_z;
  const glm::dmat4 vp = glm::dmat4(camera.projection(1.0f)) * glm::dmat4(camera.view());
  std::vector<tessera::Float4> positions;
  std::vector<float> colors;
  const auto plane = [&](double distance, std::array<float, 4> colour) {
    // A 24 x 24 grid of quads just wider than the view at the plane's distance: each vertex's
    // depth rounds to float on its own, as a real mesh's would, rather than four corners
    // deciding every pixel.
    const int cells = 24;
    const double half = 0.65 * distance;
    const auto vertex = [&](int i, int j) {
      const double x = -half + 2.0 * half * i / cells, y = -half + 2.0 * half * j / cells;
      const glm::dvec4 clip = vp * glm::dvec4(x, y, -(distance + 0.1 * y), 1.0);
      return tessera::Float4{static_cast<float>(clip.x), static_cast<float>(clip.y),
                             static_cast<float>(clip.z), static_cast<float>(clip.w)};
    };
    for (int j = 0; j < cells; ++j) {
      for (int i = 0; i < cells; ++i) {
        for (const auto& [di, dj] : {std::pair{0, 0}, {1, 0}, {1, 1}, {0, 0}, {1, 1}, {0, 1}}) {
          positions.push_back(vertex(i + di, j + dj));
          colors.insert(colors.end(), colour.begin(), colour.end());
        }
      }
    }
  };
  plane(d * (1.0 + gap), {0, 1, 0, 1});  // farther: green
  plane(d, {1, 0, 0, 1});                // nearer: red
  tessera::RendererOptions options;
  tessera::Renderer renderer(options);
  tessera::Framebuffer fb({size, size, 1, tessera::ColorFormat::kRGBA8, s.depth_format});
  clear(fb, s);
  tessera::DrawInput input;
  input.positions = positions;
  input.attributes = colors;
  input.attribute_count = 4;
  renderer.draw(fb, pipeline_for(s), input);
  const std::vector<uint8_t> rgba = fb.read_rgba8();
  size_t hidden = 0;
  for (size_t i = 0; i < rgba.size(); i += 4)
    hidden += rgba[i] == 255 ? 0 : 1;
  return static_cast<double>(hidden) / static_cast<double>(rgba.size() / 4);
}

// --- Interpolation --------------------------------------------------------------------------

// A floor y = -1 from z = -1 to z = -1000, viewed from the origin along -z, with texture
// coordinates (u, v) = (x, z) / 2: one checker cell per 2 x 2 world units. Returns the rendered
// and the exact (u, v) at each pixel centre.
struct Checkerboard {
  std::vector<float> uv;      // rendered, 2 per pixel (NaN where the floor is not drawn)
  std::vector<double> exact;  // analytic, 2 per pixel (NaN where the floor is not seen)
};

Checkerboard checkerboard(tessera::Interpolation interpolation, uint32_t width, uint32_t height) {
  tessera::Camera camera;
  camera.eye = {0, 0, 0};
  camera.target = {0, -0.15f, -1};
  camera.fov_y_degrees = 50.0f;
  camera.near_plane = 0.5f;
  camera.far_plane = 2000.0f;
  const float aspect = static_cast<float>(width) / static_cast<float>(height);
  const glm::mat4 view = camera.view(), proj = camera.projection(aspect);
  // 8 columns by 16 rows of quads, rows spaced geometrically from z = -1 to z = -1000 so each
  // covers a similar height on screen: coarse enough that affine interpolation visibly bends
  // the checkers, as in a game's floor mesh.
  std::vector<tessera::Float4> positions;
  std::vector<float> attributes;
  const auto vertex = [&](int i, int j) {
    const glm::vec3 p{-100.0f + 200.0f * static_cast<float>(i) / 8.0f, -1.0f,
                      -std::pow(1000.0f, static_cast<float>(j) / 16.0f)};
    const glm::vec4 clip = proj * view * glm::vec4(p, 1.0f);
    positions.push_back({clip.x, clip.y, clip.z, clip.w});
    // Texture coordinates in checker cells of 2 x 2 world units.
    attributes.insert(attributes.end(), {p.x / 2, p.z / 2, 0.0f, 1.0f});
  };
  for (int j = 0; j < 16; ++j) {
    for (int i = 0; i < 8; ++i) {
      for (const auto& [di, dj] : {std::pair{0, 0}, {1, 0}, {1, 1}, {0, 0}, {1, 1}, {0, 1}})
        vertex(i + di, j + dj);
    }
  }
  tessera::RendererOptions options;
  tessera::Renderer renderer(options);
  tessera::Framebuffer fb({width, height, 1, tessera::ColorFormat::kRGBA32F});
  fb.clear_color({NAN, NAN, 0, 0});
  tessera::PipelineState pipeline;
  pipeline.interpolation = interpolation;
  tessera::DrawInput input;
  input.positions = positions;
  input.attributes = attributes;
  input.attribute_count = 4;
  renderer.draw(fb, pipeline, input);
  const std::vector<float> rgba = fb.read_rgba32f();
  Checkerboard out;
  out.uv.resize(size_t{width} * height * 2);
  out.exact.resize(size_t{width} * height * 2);
  const glm::dmat4 inv = glm::inverse(glm::dmat4(proj) * glm::dmat4(view));
  for (uint32_t y = 0; y < height; ++y) {
    for (uint32_t x = 0; x < width; ++x) {
      const size_t p = size_t{y} * width + x;
      out.uv[p * 2] = rgba[p * 4];
      out.uv[p * 2 + 1] = rgba[p * 4 + 1];
      // The ray through the pixel centre (window y down), met with the floor.
      const double ndc_x = (x + 0.5) / width * 2.0 - 1.0;
      const double ndc_y = 1.0 - (y + 0.5) / height * 2.0;
      glm::dvec4 far_point = inv * glm::dvec4(ndc_x, ndc_y, 1.0, 1.0);
      const glm::dvec3 dir = glm::dvec3(far_point) / far_point.w;
      const double t = dir.y < 0 ? -1.0 / dir.y : -1.0;
      const glm::dvec3 hit = dir * t;
      const bool on_floor = t > 0 && std::abs(hit.x) <= 100 && hit.z <= -1 && hit.z >= -1000;
      out.exact[p * 2] = on_floor ? hit.x / 2 : NAN;
      out.exact[p * 2 + 1] = on_floor ? hit.z / 2 : NAN;
    }
  }
  return out;
}

bool dark_cell(double u, double v) {
  return (static_cast<int64_t>(std::floor(u)) + static_cast<int64_t>(std::floor(v))) % 2 != 0;
}

// --- Texture filtering ----------------------------------------------------------------------

struct FilterChoice {
  std::string name;
  tessera::Sampler sampler;
};

// Nearest and bilinear from level 0 (GL_NEAREST, GL_LINEAR), trilinear
// (GL_LINEAR_MIPMAP_LINEAR), and trilinear with up to 2, 4, 8 and 16 anisotropic samples; repeat
// wrapping.
std::vector<FilterChoice> texture_filters() {
  std::vector<FilterChoice> out;
  tessera::Sampler s;
  s.mag_filter = s.min_filter = tessera::Filter::kNearest;
  s.mip_filter = tessera::MipFilter::kNone;
  out.push_back({"nearest", s});
  s.mag_filter = s.min_filter = tessera::Filter::kLinear;
  out.push_back({"bilinear", s});
  s.mip_filter = tessera::MipFilter::kLinear;
  out.push_back({"trilinear", s});
  for (int n : {2, 4, 8, 16}) {
    s.max_anisotropy = static_cast<float>(n);
    out.push_back({"aniso" + std::to_string(n), s});
  }
  return out;
}

// The floor y = 0 seen from (0, 1, 0) looking 35 degrees down with a 60 degree vertical field of
// view, so it fills the image: its footprints are about square at the bottom and stretched
// about 12:1 at the top (where the view ray meets the floor at 5 degrees). (u, v) = (x, z) / 4:
// one repeat of the 1024-texel benchmark texture per 4 x 4 units, so a pixel covers about 2
// texels at the bottom and 17 by 200 at the top of a 320 x 180 image. Clip space: the same
// triangles at any resolution of the aspect ratio.
struct Floor {
  std::vector<tessera::Float4> positions;
  std::vector<float> uv;  // 2 per vertex
};

Floor textured_floor(float aspect) {
  tessera::Camera camera;
  camera.eye = {0, 1, 0};
  const float pitch = 35.0f * std::numbers::pi_v<float> / 180.0f;
  camera.target = {0, 1 - std::sin(pitch), -std::cos(pitch)};
  camera.fov_y_degrees = 60.0f;
  camera.near_plane = 0.05f;
  camera.far_plane = 100.0f;
  const glm::mat4 vp = camera.projection(aspect) * camera.view();
  // 32 x 32 quads over x in [-30, 30], z in [0.5, -40].
  Floor f;
  const auto vertex = [&](int i, int j) {
    const glm::vec3 p{-30.0f + 60.0f * static_cast<float>(i) / 32.0f, 0.0f,
                      0.5f - 40.5f * static_cast<float>(j) / 32.0f};
    const glm::vec4 clip = vp * glm::vec4(p, 1.0f);
    f.positions.push_back({clip.x, clip.y, clip.z, clip.w});
    f.uv.insert(f.uv.end(), {p.x / 4, p.z / 4});
  };
  for (int j = 0; j < 32; ++j) {
    for (int i = 0; i < 32; ++i) {
      for (const auto& [di, dj] : {std::pair{0, 0}, {1, 0}, {1, 1}, {0, 0}, {1, 1}, {0, 1}})
        vertex(i + di, j + dj);
    }
  }
  return f;
}

// The floor's draw: the textured shader with `sampler`, (u, v) the only varyings (so the texel
// is drawn alone).
tessera::PipelineState floor_pipeline(std::shared_ptr<const tessera::Texture> texture,
                                      const tessera::Sampler& sampler) {
  tessera::PipelineState pipeline;
  pipeline.shader = tessera::FragmentShader::kTextured;
  pipeline.roles.texcoord = 0;
  pipeline.roles.color = 2;  // past the varyings: white
  pipeline.texture = std::move(texture);
  pipeline.sampler = sampler;
  return pipeline;
}

tessera::DrawInput floor_input(const Floor& floor) {
  tessera::DrawInput input;
  input.positions = floor.positions;
  input.attributes = floor.uv;
  input.attribute_count = 2;
  return input;
}

Image render_floor(const Floor& floor, std::shared_ptr<const tessera::Texture> texture,
                   const tessera::Sampler& sampler, uint32_t width, uint32_t height,
                   tessera::Backend backend) {
  tessera::RendererOptions options;
  options.backend = backend;
  options.threads = 0;
  tessera::Renderer renderer(options);
  tessera::Framebuffer fb({width, height, 1, tessera::ColorFormat::kRGBA32F});
  fb.clear_color({0, 0, 0, 0});
  renderer.draw(fb, floor_pipeline(std::move(texture), sampler), floor_input(floor));
  return {width, height, fb.read_rgba32f()};
}

// `fine` box-filtered by factor x factor pixels.
Image downsample(const Image& fine, uint32_t factor) {
  Image out{fine.width / factor, fine.height / factor, {}};
  out.rgba.assign(size_t{out.width} * out.height * 4, 0.0f);
  const float inv = 1.0f / static_cast<float>(factor * factor);
  for (uint32_t y = 0; y < fine.height; ++y) {
    for (uint32_t x = 0; x < fine.width; ++x) {
      const size_t p = size_t{y / factor} * out.width + x / factor;
      const size_t q = size_t{y} * fine.width + x;
      for (int c = 0; c < 4; ++c)
        out.rgba[p * 4 + c] += fine.rgba[q * 4 + c] * inv;
    }
  }
  return out;
}

void write_rgb8(const fs::path& path, const Image& img) {
  std::vector<uint8_t> rgb(size_t{img.width} * img.height * 3);
  for (size_t p = 0; p < size_t{img.width} * img.height; ++p) {
    for (int c = 0; c < 3; ++c) {
      rgb[p * 3 + c] =
          static_cast<uint8_t>(std::lround(std::clamp(img.rgba[p * 4 + c], 0.0f, 1.0f) * 255.0f));
    }
  }
  tessera::write_image(path, img.width, img.height, 3, std::span<const uint8_t>(rgb));
}

// --- Output ---------------------------------------------------------------------------------

class Table {
 public:
  explicit Table(std::vector<std::string> columns) : columns_(std::move(columns)) {}
  void add(std::vector<std::string> row) { rows_.push_back(std::move(row)); }
  void write_csv(const fs::path& path) const {
    std::ofstream f(path);
    for (size_t i = 0; i < columns_.size(); ++i)
      f << (i ? "," : "") << columns_[i];
    f << "\n";
    for (const auto& row : rows_) {
      for (size_t i = 0; i < row.size(); ++i)
        f << (i ? "," : "") << row[i];
      f << "\n";
    }
    if (!f) throw tessera::Error(tessera::ErrorCode::kIo, "cannot write " + path.string());
  }
  // An array of objects; values that parse as numbers are written as numbers.
  void write_json(std::ostream& f) const {
    f << "[";
    for (size_t r = 0; r < rows_.size(); ++r) {
      f << (r ? ",\n  {" : "\n  {");
      for (size_t i = 0; i < columns_.size(); ++i) {
        const std::string& v = rows_[r][i];
        char* end = nullptr;
        std::strtod(v.c_str(), &end);
        const bool number = !v.empty() && end == v.c_str() + v.size() && v != "nan" && v != "inf";
        f << (i ? ", " : "") << '"' << columns_[i] << "\": ";
        if (number) {
          f << v;
        } else {
          f << '"' << v << '"';
        }
      }
      f << "}";
    }
    f << "\n]";
  }

 private:
  std::vector<std::string> columns_;
  std::vector<std::vector<std::string>> rows_;
};

std::string num(double v, int precision = 6) {
  std::ostringstream s;
  s.precision(precision);
  s << v;
  return s.str();
}

}  // namespace

// Texture filters. Speed: the textured grid and medium workloads (benchmarks/
// texture_workload.hpp; `captures`) and the floor with each filter, median ms per frame
// (clear + draw). Error: the floor at
// width x height, fast engine, float colour, against the reference with trilinear filtering at
// 16 times the resolution, box-filtered: 256 samples per pixel, each filtered over its own
// footprint (a 16th of the pixel's). Writes the floor images into out_dir.
void texture_study(const std::vector<const Workload*>& captures,
                   const std::vector<uint32_t>& thread_counts, int frames, uint32_t width,
                   uint32_t height, const fs::path& out_dir, Table& speed, Table& quality,
                   Progress& progress) {
  const std::shared_ptr<const tessera::Texture> texture = tessera::bench::benchmark_texture();
  const std::vector<FilterChoice> filters = texture_filters();
  const Floor floor = textured_floor(static_cast<float>(width) / static_cast<float>(height));
  constexpr uint32_t kFactor = 16;
  tessera::Sampler truth_sampler = filters[2].sampler;  // trilinear
  const Image fine = render_floor(floor, texture, truth_sampler, width * kFactor, height * kFactor,
                                  tessera::Backend::kReference);
  GroundTruth gt{downsample(fine, kFactor), std::vector<bool>(size_t{width} * height, false)};
  write_rgb8(out_dir / "texture_ground_truth.png", gt.image);
  progress.step("texture ground truth: 16x16 samples per pixel, reference");
  // What is timed: the textured captures, and the floor at 1920 x 1080 (the aspect ratio of the
  // error's image), where footprints stretch up to 12:1.
  struct Timed {
    std::string name;
    uint32_t width, height;
    tessera::PipelineState pipeline;
    tessera::DrawInput input;
    std::vector<float> varyings;  // the input's attributes (captures)
  };
  std::vector<Timed> timed;
  for (const Workload* w : captures) {
    timed.push_back({w->name,
                     w->width,
                     w->height,
                     tessera::bench::textured_pipeline(texture, true),
                     {},
                     tessera::bench::textured_varyings(*w->capture)});
    timed.back().input.positions = w->capture->positions;
    timed.back().input.attributes = timed.back().varyings;
    timed.back().input.attribute_count = tessera::bench::kTexturedVaryings;
  }
  const uint32_t floor_scale = captures.empty() ? 1 : 6;  // 1920 x 1080 but in --quick
  timed.push_back({"floor",
                   width * floor_scale,
                   height * floor_scale,
                   floor_pipeline(texture, tessera::Sampler{}),
                   floor_input(floor),
                   {}});
  for (const FilterChoice& f : filters) {
    for (Timed& t : timed) {
      t.pipeline.sampler = f.sampler;
      for (uint32_t threads : thread_counts) {
        const double median =
            median_frame_ms(Settings{}, t.width, t.height, threads, frames,
                            [&](tessera::Renderer& renderer, tessera::Framebuffer& fb) {
                              renderer.draw(fb, t.pipeline, t.input);
                            });
        speed.add({f.name, t.name, std::to_string(threads), num(median)});
        progress.step("texture " + f.name + " " + t.name + " " + std::to_string(threads) +
                      "t: " + num(median, 4) + " ms");
      }
    }
    const Image img =
        render_floor(floor, texture, f.sampler, width, height, tessera::Backend::kFast);
    write_rgb8(out_dir / ("texture_" + f.name + ".png"), img);
    const ImageError e = image_error(img, gt);
    quality.add({f.name, num(e.rmse), num(e.psnr)});
    progress.step("texture " + f.name + ": RMSE " + num(e.rmse, 4));
  }
}

int main(int argc, char** argv) {
  CLI::App app{
      "Tessera's speed-against-accuracy sweep: CSV and JSON for scripts/plot-tradeoffs.py"};
  std::string out_dir = "build/sweep";
  std::string workload_dir = "build/workloads";
  std::string models = "/usr/share/assimp/models";
  int frames = 5;
  bool quick = false;
  bool depth_only = false;
  bool textures_only = false;
  app.add_option("--out", out_dir, "directory for the CSV and JSON files")->capture_default_str();
  app.add_option("--workloads", workload_dir, "directory of the standard TRI1 workloads")
      ->capture_default_str();
  app.add_option("--models", models, "Assimp test models (real meshes)")->capture_default_str();
  app.add_option("--frames", frames, "timed frames per measurement (median)")
      ->check(CLI::Range(1, 1000))
      ->capture_default_str();
  app.add_flag("--quick", quick,
               "small images, one thread count, one frame, no workload files: a smoke run");
  app.add_flag("--depth-only", depth_only,
               "only the depth precision study (its tables stay empty)");
  app.add_flag("--textures-only", textures_only,
               "only the texture filter study (texture_*.csv; the other files are not written)");
  CLI11_PARSE(app, argc, argv);

  try {
    fs::create_directories(out_dir);
    if (quick) frames = 1;

    // Workloads: the standard captures and real meshes, each at its own size.
    std::vector<Workload> workloads;
    if (!quick) {
      for (const char* name : {"tiny", "small", "medium", "large", "huge", "grid"}) {
        if (textures_only && std::string(name) != "medium" && std::string(name) != "grid") continue;
        const fs::path path = fs::path(workload_dir) / (std::string(name) + ".tri");
        if (!fs::exists(path)) {
          std::fprintf(stderr, "sweep: %s is missing (scripts/make-workloads.sh makes it)\n",
                       path.string().c_str());
          return 1;
        }
        Workload w;
        w.name = name;
        w.capture = tessera::load_capture(path);
        w.width = w.capture->width;
        w.height = w.capture->height;
        w.triangles = w.capture->positions.size() / 3;
        workloads.push_back(std::move(w));
      }
    }
    const std::pair<const char*, const char*> meshes[] = {
        {"wuson", "PLY/Wuson.ply"},
        {"engine", "glTF2/2CylinderEngine-glTF-Binary/2CylinderEngine.glb"}};
    for (const auto& [name, file] : meshes) {
      const fs::path path = fs::path(models) / file;
      if (!fs::exists(path)) continue;
      Workload w;
      w.name = name;
      w.width = quick ? 320 : 1920;
      w.height = quick ? 180 : 1080;
      w.scene.emplace();
      w.scene->objects.push_back({tessera::load_mesh(path), glm::mat4(1.0f)});
      w.scene->camera = tessera::frame_bounds(w.scene->bounds(), float(w.width) / float(w.height));
      w.triangles = w.scene->triangle_count();
      workloads.push_back(std::move(w));
    }
    {
      Workload w;
      w.name = "demo";
      w.width = quick ? 320 : 1280;
      w.height = quick ? 180 : 720;
      w.scene = tessera::make_demo_scene();
      w.triangles = w.scene->triangle_count();
      workloads.push_back(std::move(w));
    }

    const std::vector<KnobValue> knobs = knob_values();
    const std::vector<uint32_t> thread_counts =
        quick ? std::vector<uint32_t>{1} : std::vector<uint32_t>{1, 2};
    const uint32_t qw = quick ? 160 : 320, qh = quick ? 90 : 180, factor = 16;
    const std::vector<double> ratios =
        quick ? std::vector<double>{1e3} : std::vector<double>{1e1, 1e2, 1e3, 1e4, 1e5, 1e6};
    const int distances = quick ? 3 : 24;
    const uint32_t grid_sizes[] = {1u, 4u, 16u};

    std::vector<const Workload*> textured;  // the texture study's captures
    for (const Workload& w : workloads) {
      if (w.name == "grid" || w.name == "medium") textured.push_back(&w);
    }
    const size_t texture_steps =
        1 + texture_filters().size() * ((textured.size() + 1) * thread_counts.size() + 1);
    const fs::path out(out_dir);
    Table texture_speed({"filter", "workload", "threads", "ms_median"});
    Table texture_quality({"filter", "rmse", "psnr"});
    const auto write_texture_tables = [&] {
      texture_speed.write_csv(out / "texture_speed.csv");
      texture_quality.write_csv(out / "texture_quality.csv");
    };
    if (textures_only) {
      Progress progress(texture_steps);
      texture_study(textured, thread_counts, frames, qw, qh, out, texture_speed, texture_quality,
                    progress);
      write_texture_tables();
      std::printf("wrote %s/texture_{speed,quality}.csv\n", out_dir.c_str());
      return 0;
    }

    Progress progress(1 + knobs.size() * (workloads.size() * thread_counts.size() + 1) +
                      ratios.size() * 4 + 2 + 5 + texture_steps);

    Table speed({"knob", "value", "workload", "triangles", "threads", "ms_median", "mtri_s"});
    Table quality({"knob", "value", "rmse", "psnr", "rmse_edges", "psnr_edges", "edge_pixels"});
    // Ground truth for edges, once.
    const tessera::Scene demo = tessera::make_demo_scene();
    const GroundTruth gt = depth_only ? GroundTruth{} : ground_truth(demo, qw, qh, factor);
    progress.step("ground truth: 16x16 samples per pixel, reference");
    const size_t edge_pixels =
        static_cast<size_t>(std::count(gt.edge.begin(), gt.edge.end(), true));
    for (const KnobValue& k : depth_only ? std::vector<KnobValue>{} : knobs) {
      for (const Workload& w : workloads) {
        for (uint32_t threads : thread_counts) {
          const double ms = time_frames(k.settings, w, threads, frames);
          speed.add({k.knob, k.value, w.name, std::to_string(w.triangles), std::to_string(threads),
                     num(ms), num(static_cast<double>(w.triangles) / (ms * 1e3))});
          progress.step(k.knob + "=" + k.value + " " + w.name + " " + std::to_string(threads) +
                        "t: " + num(ms, 4) + " ms");
        }
      }
      const Image img = render_colour(demo, k.settings, qw, qh, tessera::Backend::kFast);
      const ImageError e = image_error(img, gt);
      quality.add({k.knob, k.value, num(e.rmse), num(e.psnr), num(e.rmse_edges), num(e.psnr_edges),
                   std::to_string(edge_pixels)});
      progress.step(k.knob + "=" + k.value + " edges: PSNR " + num(e.psnr_edges, 4) + " dB");
    }

    // Depth precision: z-fighting of two planes 0.01% of their distance apart, per format and
    // near/far ratio.
    Table depth({"format", "near_far_ratio", "distance", "near_hidden"});
    for (const KnobValue& k : knobs) {
      if (k.knob != "depth_format") continue;
      for (double ratio : ratios) {
        const double near_plane = 1.0, far_plane = ratio;
        for (int i = 0; i < distances; ++i) {
          // Log-spaced distances from 1.3 near to 0.8 far: the tilted planes stay inside.
          const double t = (i + 0.5) / distances;
          const double d = 1.3 * near_plane * std::pow(0.8 * far_plane / (1.3 * near_plane), t);
          depth.add({k.value, num(ratio), num(d),
                     num(near_plane_hidden(k.settings, near_plane, far_plane, d, 1e-4,
                                           quick ? 32 : 128))});
        }
        progress.step("depth " + k.value + " near/far 1:" + num(ratio));
      }
    }

    // Interpolation: affine against perspective-correct on the receding checkerboard.
    Table interp({"interpolation", "wrong_cells", "uv_rmse", "pixels"});
    for (bool affine : {false, true}) {
      const uint32_t w = quick ? 160 : 640, h = quick ? 90 : 360;
      const Checkerboard c = checkerboard(
          affine ? tessera::Interpolation::kAffine : tessera::Interpolation::kPerspective, w, h);
      size_t pixels = 0, wrong = 0;
      double sq = 0;
      std::vector<uint8_t> picture(size_t{w} * h * 3, 0);
      for (size_t p = 0; p < size_t{w} * h; ++p) {
        const bool rendered = !std::isnan(c.uv[p * 2]);
        if (rendered) {
          const uint8_t shade = dark_cell(c.uv[p * 2], c.uv[p * 2 + 1]) ? 40 : 220;
          picture[p * 3] = picture[p * 3 + 1] = picture[p * 3 + 2] = shade;
        } else {
          picture[p * 3 + 2] = 90;  // sky
        }
        if (!rendered || std::isnan(c.exact[p * 2])) continue;
        ++pixels;
        const double du = c.uv[p * 2] - c.exact[p * 2], dv = c.uv[p * 2 + 1] - c.exact[p * 2 + 1];
        sq += du * du + dv * dv;
        if (dark_cell(c.uv[p * 2], c.uv[p * 2 + 1]) !=
            dark_cell(c.exact[p * 2], c.exact[p * 2 + 1]))
          ++wrong;
      }
      const char* name = affine ? "affine" : "perspective";
      interp.add(
          {name, num(static_cast<double>(wrong) / static_cast<double>(std::max<size_t>(pixels, 1))),
           num(std::sqrt(sq / static_cast<double>(std::max<size_t>(pixels, 1)))),
           std::to_string(pixels)});
      tessera::write_image(fs::path(out_dir) / (std::string("checkerboard_") + name + ".png"), w, h,
                           3, std::span<const uint8_t>(picture));
      progress.step(std::string("checkerboard ") + name);
    }

    // Snapping: vertex displacement, and hits per sample on a watertight jittered grid.
    Table snap({"subpixel_bits", "mean_displacement_px", "max_displacement_px", "bound_px",
                "samples", "uncovered", "extra_hits"});
    for (uint32_t bits = tessera::kMinSubpixelBits; bits <= tessera::kMaxSubpixelBits; ++bits) {
      std::mt19937 rng(bits);
      std::uniform_real_distribution<double> coord(0.0, 1920.0);
      double sum = 0, worst = 0;
      const int n = 100000;
      const double scale = std::ldexp(1.0, static_cast<int>(bits));
      for (int i = 0; i < n; ++i) {
        const double x = coord(rng), y = coord(rng) * 0.5625;
        const double dx = std::nearbyint(x * scale) / scale - x,
                     dy = std::nearbyint(y * scale) / scale - y;
        const double d = std::hypot(dx, dy);
        sum += d;
        worst = std::max(worst, d);
      }
      for (uint32_t samples : grid_sizes) {
        const uint32_t gw = quick ? 64 : 320, gh = quick ? 48 : 200;
        const int cells = quick ? 40 : 300;
        std::mt19937 jrng(1000 + bits);
        std::uniform_real_distribution<float> jitter(-0.2f, 0.2f);
        const int vn = cells + 1;
        std::vector<tessera::Float4> v(static_cast<size_t>(vn) * vn);
        for (int j = 0; j < vn; ++j) {
          for (int i = 0; i < vn; ++i) {
            const bool border = i == 0 || j == 0 || i == vn - 1 || j == vn - 1;
            const float fx = (static_cast<float>(i) + (border ? 0.0f : jitter(jrng))) /
                             static_cast<float>(cells);
            const float fy = (static_cast<float>(j) + (border ? 0.0f : jitter(jrng))) /
                             static_cast<float>(cells);
            const float wgt = 1.0f + 3.0f * fx * fy;  // perspective spread across the grid
            v[static_cast<size_t>(j) * vn + i] = {(2 * fx - 1) * wgt, (1 - 2 * fy) * wgt,
                                                  0.5f * wgt, wgt};
          }
        }
        std::vector<uint32_t> indices;
        for (int j = 0; j < cells; ++j) {
          for (int i = 0; i < cells; ++i) {
            const uint32_t a = j * vn + i, b = a + 1, c = a + vn, d = c + 1;
            indices.insert(indices.end(), {a, b, d, a, d, c});
          }
        }
        tessera::RendererOptions options;
        options.threads = 0;
        tessera::Renderer renderer(options);
        tessera::Framebuffer fb({gw, gh, samples, tessera::ColorFormat::kRGBA8});
        tessera::PipelineState p;
        p.depth_compare = tessera::CompareOp::kAlways;
        p.subpixel_bits = bits;
        renderer.draw(fb, p, {v, {}, 0, indices});
        const std::vector<float> d = fb.read_sample_depth();
        const auto uncovered = static_cast<uint64_t>(std::count(d.begin(), d.end(), 1.0f));
        const uint64_t total = uint64_t{gw} * gh * samples;
        const uint64_t extra = renderer.counters().samples_covered - (total - uncovered);
        snap.add({std::to_string(bits), num(sum / n), num(worst), num(std::sqrt(0.5) / scale),
                  std::to_string(samples), std::to_string(uncovered), std::to_string(extra)});
      }
      progress.step("snapping " + std::to_string(bits) + " bits");
    }

    if (!depth_only) {
      texture_study(textured, thread_counts, frames, qw, qh, out, texture_speed, texture_quality,
                    progress);
    }

    speed.write_csv(out / "speed.csv");
    quality.write_csv(out / "quality.csv");
    depth.write_csv(out / "depth_precision.csv");
    interp.write_csv(out / "interpolation.csv");
    snap.write_csv(out / "snapping.csv");
    write_texture_tables();
    std::ofstream json(out / "sweep.json");
    json << "{\n\"speed\": ";
    speed.write_json(json);
    json << ",\n\"quality\": ";
    quality.write_json(json);
    json << ",\n\"depth_precision\": ";
    depth.write_json(json);
    json << ",\n\"interpolation\": ";
    interp.write_json(json);
    json << ",\n\"snapping\": ";
    snap.write_json(json);
    json << ",\n\"texture_speed\": ";
    texture_speed.write_json(json);
    json << ",\n\"texture_quality\": ";
    texture_quality.write_json(json);
    json << "\n}\n";
    if (!json) throw tessera::Error(tessera::ErrorCode::kIo, "cannot write sweep.json");
    std::printf(
        "wrote %s/{speed,quality,depth_precision,interpolation,snapping,texture_speed,"
        "texture_quality}.csv and sweep.json\n",
        out_dir.c_str());
  } catch (const tessera::Error& e) {
    std::fprintf(stderr, "sweep: %s\n", e.what());
    return 1;
  }
  return 0;
}
