// The speed-against-accuracy sweep (docs/TRADEOFFS.md): every knob value measured for speed on
// the standard workloads and real meshes, and for error against ground truth that needs no
// trust in the fast engine: a 256-samples-per-pixel (16x16 grid) reference render for edges,
// z-fighting of two close planes for depth formats, the analytic texture coordinates of a
// receding checkerboard for interpolation, and hit counts on watertight meshes for snapping.
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

// Median ms per frame (clear + draw) over `frames` frames after one warm-up.
double time_frames(const Settings& s, const Workload& w, uint32_t threads, int frames) {
  tessera::RendererOptions options;
  options.threads = threads;
  options.hiz = s.hiz;
  options.bin_tile_size = s.bin_tile_size;
  options.block_size = s.block_size;
  options.raster_counters = false;
  tessera::Renderer renderer(options);
  tessera::Framebuffer fb = framebuffer_for(s, w.width, w.height);
  Settings timed = s;
  if (w.capture) timed.reversed_z = false;  // a capture's depth is fixed: reversed Z is a camera
  std::vector<double> ms;
  for (int f = -1; f < frames; ++f) {
    const auto t0 = Clock::now();
    clear(fb, timed);
    draw_workload(renderer, fb, timed, w);
    if (f >= 0) ms.push_back(std::chrono::duration<double, std::milli>(Clock::now() - t0).count());
  }
  return tessera::bench::median_of(ms);
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

int main(int argc, char** argv) {
  CLI::App app{
      "Tessera's speed-against-accuracy sweep: CSV and JSON for scripts/plot-tradeoffs.py"};
  std::string out_dir = "build/sweep";
  std::string workload_dir = "build/workloads";
  std::string models = "/usr/share/assimp/models";
  int frames = 5;
  bool quick = false;
  bool depth_only = false;
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
  CLI11_PARSE(app, argc, argv);

  try {
    fs::create_directories(out_dir);
    if (quick) frames = 1;

    // Workloads: the standard captures and real meshes, each at its own size.
    std::vector<Workload> workloads;
    if (!quick) {
      for (const char* name : {"tiny", "small", "medium", "large", "huge", "grid"}) {
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

    Progress progress(1 + knobs.size() * (workloads.size() * thread_counts.size() + 1) +
                      ratios.size() * 4 + 2 + 5);

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

    const fs::path out(out_dir);
    speed.write_csv(out / "speed.csv");
    quality.write_csv(out / "quality.csv");
    depth.write_csv(out / "depth_precision.csv");
    interp.write_csv(out / "interpolation.csv");
    snap.write_csv(out / "snapping.csv");
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
    json << "\n}\n";
    if (!json) throw tessera::Error(tessera::ErrorCode::kIo, "cannot write sweep.json");
    std::printf(
        "wrote %s/{speed,quality,depth_precision,interpolation,snapping}.csv and sweep.json\n",
        out_dir.c_str());
  } catch (const tessera::Error& e) {
    std::fprintf(stderr, "sweep: %s\n", e.what());
    return 1;
  }
  return 0;
}
