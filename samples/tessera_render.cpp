// tessera-render: the command-line renderer. Renders a mesh (OBJ, glTF, PLY, ...), a TRI1
// capture, or with no input the built-in demo scene, to an image through OpenImageIO, and
// prints what it drew and how fast.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "simd/targets.hpp"
#include "tessera/io.hpp"
#include "tessera/tessera.hpp"

namespace {

using Clock = std::chrono::steady_clock;

struct Options {
  std::string input;
  std::string output = "tessera.png";
  std::string depth_output;
  uint32_t width = 1280;
  uint32_t height = 720;
  uint32_t samples = 4;
  uint32_t threads = 0;  // all cores
  uint32_t repeat = 0;
  uint32_t subpixel_bits = 8;
  double bin_budget_mib = 0;
  bool stats = false;
  bool no_counters = false;
  bool reversed_z = false;
  bool no_hiz = false;
  bool no_records = false;
  uint32_t bin_tile = 64;
  uint32_t block_size = 8;
  bool sub_blocks = false;
  std::string depth_format = "float32";
  std::vector<float> eye, target, up;
  float fov = 40.0f;
  bool ortho = false;
  bool no_depth = false;
  bool no_depth_write = false;
  std::string blend = "none";
  std::vector<int64_t> scissor;
  bool affine = false;
  bool float_color = false;
  std::string cull = "none";
  bool wireframe = false;
  bool points = false;
  float point_size = 2.0f;
  bool round_points = false;
  float line_width = 1.0f;
  std::string line_algorithm = "diamond";
  bool smooth_lines = false;
  std::string backend = "fast";
  std::vector<float> clear{0.08f, 0.09f, 0.11f, 1.0f};
  std::string shading;              // empty: phong for meshes and the demo, gouraud otherwise
  std::vector<std::string> lights;  // "x,y,z" each
  std::vector<std::string> aovs;    // "kind=path" each: extra render targets
  std::string texture;              // --shading textured
  std::string filter = "bilinear";
  std::string wrap = "repeat";
  std::vector<float> border_color{0, 0, 0, 0};
  uint32_t anisotropy = 1;
};

// An extra render target written from the same pass as the colour (--aov kind=path).
struct Aov {
  std::string kind;
  std::string path;
  tessera::TargetOutput output;
  tessera::ColorFormat format;
  uint32_t channels;  // written to the file
};

// "No triangle" in an ids target (every index of a draw is below it).
constexpr uint32_t kNoTriangle = 0xFFFFFFFFu;

glm::vec3 vec3_of(const std::vector<float>& v) {
  return {v[0], v[1], v[2]};
}

[[noreturn]] void bad_argument(const std::string& message) {
  throw tessera::Error(tessera::ErrorCode::kInvalidArgument, message);
}

// CLI11's range checks let NaN through (every comparison with NaN is false).
void check_finite(const char* name, const std::vector<float>& values) {
  for (float v : values) {
    if (!std::isfinite(v)) {
      bad_argument(std::string(name) + ": " + std::to_string(v) + " is not a finite number");
    }
  }
}

// An image path whose directory does not exist fails before anything is rendered, not after.
void check_output_directory(const char* option, const std::string& path) {
  if (path.empty()) return;
  const std::filesystem::path dir = std::filesystem::path(path).parent_path();
  std::error_code ec;
  if (!dir.empty() && !std::filesystem::is_directory(dir, ec)) {
    bad_argument(std::string(option) + ": " + path + ": the directory " + dir.string() +
                 " does not exist");
  }
}

// A look-at camera needs a view direction and an up vector not parallel to it.
void check_camera(const tessera::Camera& cam) {
  const glm::vec3 dir = cam.target - cam.eye;
  if (!(glm::length(dir) > 0.0f)) bad_argument("--eye/--target: the eye is at the target point");
  if (!(glm::length(glm::cross(dir, cam.up)) > 0.0f)) {
    bad_argument("--up: the up vector is zero or parallel to the view direction");
  }
}

enum class Mode { kTriangles, kWireframe, kPoints };

// What one frame draws, independent of where it came from.
struct Job {
  std::optional<tessera::Capture> capture;
  std::optional<tessera::Scene> scene;
  size_t triangles = 0;
  Mode mode = Mode::kTriangles;
  std::vector<std::vector<uint32_t>> edges;  // per scene object, for kWireframe
  tessera::SceneShading scene_shading = tessera::SceneShading::kPerVertex;
  tessera::PointState point_state;
  tessera::LineState line_state;
};

// Each edge of a triangle list once, as a line list of index pairs.
std::vector<uint32_t> unique_edges(const std::vector<uint32_t>& triangles) {
  std::vector<std::pair<uint32_t, uint32_t>> edges;
  edges.reserve(triangles.size());
  for (size_t t = 0; t + 2 < triangles.size(); t += 3) {
    for (int k = 0; k < 3; ++k) {
      const uint32_t a = triangles[t + k], b = triangles[t + (k + 1) % 3];
      edges.emplace_back(std::min(a, b), std::max(a, b));
    }
  }
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  std::vector<uint32_t> list;
  list.reserve(edges.size() * 2);
  for (const auto& [a, b] : edges)
    list.insert(list.end(), {a, b});
  return list;
}

// Clip-space depth pushed back by this much (times w) in the wireframe's hidden-surface pass,
// so that an edge wins the depth test against the surface it lies on (a constant polygon
// offset, as glPolygonOffset's units do). Back is toward the depth the compare lets lose:
// larger z under LESS, smaller under GREATER (reversed Z).
constexpr float kWireframeDepthOffset = 2e-4f;

float wireframe_depth_offset(tessera::CompareOp compare) {
  const bool reversed =
      compare == tessera::CompareOp::kGreater || compare == tessera::CompareOp::kGreaterEqual;
  return reversed ? -kWireframeDepthOffset : kWireframeDepthOffset;
}

// Wireframe (the lecture's "perspective + hidden line removal"): the triangles fill the depth
// buffer only, pushed back slightly, then every edge is drawn as a line against it. Points:
// every vertex, in its unlit colour.
void draw_scene_primitives(tessera::Renderer& renderer, tessera::Framebuffer& fb,
                           const tessera::PipelineState& pipeline, const Job& job) {
  const tessera::Scene& scene = *job.scene;
  const float aspect = float(fb.width()) / float(fb.height());
  const glm::mat4 vp = scene.camera.projection(aspect, pipeline.clip_depth) * scene.camera.view();
  for (size_t i = 0; i < scene.objects.size(); ++i) {
    const tessera::SceneObject& o = scene.objects[i];
    std::vector<tessera::Float4> clip = tessera::to_clip_space(o.mesh.positions, vp * o.model);
    if (job.mode == Mode::kPoints) {
      std::vector<float> colors;
      colors.reserve(o.mesh.colors.size() * 4);
      for (const glm::vec4& c : o.mesh.colors)
        colors.insert(colors.end(), {c.r, c.g, c.b, c.a});
      renderer.draw_points(fb, pipeline, job.point_state, {clip, colors, 4, {}});
      continue;
    }
    const std::vector<float> colors =
        tessera::shade_vertices(o.mesh, o.model, scene.camera.eye, scene.light);
    if (pipeline.depth_test) {
      std::vector<tessera::Float4> pushed = clip;
      const float offset = wireframe_depth_offset(pipeline.depth_compare);
      for (tessera::Float4& p : pushed)
        p.z += offset * p.w;
      tessera::PipelineState depth_only = pipeline;
      depth_only.color_write = false;
      renderer.draw(fb, depth_only, {pushed, colors, 4, o.mesh.indices});
    }
    renderer.draw_lines(fb, pipeline, job.line_state, {clip, colors, 4, job.edges[i]});
  }
}

void draw_job(tessera::Renderer& renderer, tessera::Framebuffer& fb,
              const tessera::PipelineState& pipeline, const Job& job) {
  if (job.capture) {
    tessera::DrawInput input;
    input.positions = job.capture->positions;
    input.attributes = job.capture->varyings;
    input.attribute_count = job.capture->varying_count;
    renderer.draw(fb, pipeline, input);
  } else if (job.mode != Mode::kTriangles) {
    draw_scene_primitives(renderer, fb, pipeline, job);
  } else {
    tessera::draw_scene(renderer, fb, pipeline, *job.scene, job.scene_shading);
  }
}

// A mesh, or for --points (and for a PLY file without faces, a point cloud) every vertex.
// Triangles: one object per material, textured where the material has a base colour texture.
// Wireframes: one mesh.
std::vector<tessera::SceneObject> load_input(const std::string& path, Mode& mode) {
  if (mode == Mode::kPoints) return {{tessera::load_point_cloud(path)}};
  try {
    if (mode == Mode::kWireframe) return {{tessera::load_mesh(path)}};
    return tessera::load_scene_objects(path);
  } catch (const tessera::Error& e) {
    const bool ply = std::filesystem::path(path).extension() == ".ply" ||
                     std::filesystem::path(path).extension() == ".PLY";
    if (!ply || std::string(e.what()).find("no triangles") == std::string::npos) throw;
  }
  mode = Mode::kPoints;
  return {{tessera::load_point_cloud(path)}};
}

bool has_extension(const std::string& path, const char* ext) {
  std::string e = std::filesystem::path(path).extension().string();
  std::transform(e.begin(), e.end(), e.begin(), [](unsigned char c) { return std::tolower(c); });
  return e == ext;
}

std::vector<Aov> parse_aovs(const std::vector<std::string>& specs) {
  using tessera::ColorFormat;
  using tessera::TargetOutput;
  if (specs.size() > tessera::kMaxColorTargets - 1) {
    bad_argument("--aov: at most " + std::to_string(tessera::kMaxColorTargets - 1) +
                 " extra targets, " + std::to_string(specs.size()) + " given");
  }
  std::vector<Aov> aovs;
  for (const std::string& spec : specs) {
    const size_t eq = spec.find('=');
    if (eq == std::string::npos || eq + 1 == spec.size()) {
      bad_argument("--aov: " + spec + " is not kind=path (for example normals=normals.exr)");
    }
    Aov a;
    a.kind = spec.substr(0, eq);
    a.path = spec.substr(eq + 1);
    if (a.kind == "normals") {
      a.output = TargetOutput::kNormal, a.format = ColorFormat::kRGBA32F, a.channels = 3;
    } else if (a.kind == "positions") {
      a.output = TargetOutput::kPosition, a.format = ColorFormat::kRGBA32F, a.channels = 3;
    } else if (a.kind == "barycentrics") {
      a.output = TargetOutput::kBarycentrics, a.format = ColorFormat::kRGBA32F, a.channels = 3;
    } else if (a.kind == "depth") {
      a.output = TargetOutput::kEyeDepth, a.format = ColorFormat::kR32F, a.channels = 1;
    } else if (a.kind == "ids") {
      a.output = TargetOutput::kPrimitiveId, a.format = ColorFormat::kR32UI, a.channels = 1;
    } else if (a.kind == "objects") {
      a.output = TargetOutput::kObjectId, a.format = ColorFormat::kR32UI, a.channels = 1;
    } else {
      bad_argument("--aov: " + a.kind +
                   " is not one of normals, positions, barycentrics, depth, ids, objects");
    }
    if (!has_extension(a.path, ".exr")) {
      bad_argument("--aov " + a.kind + ": " + a.path + " is not an .exr file");
    }
    check_output_directory("--aov", a.path);
    aovs.push_back(a);
  }
  return aovs;
}

// --shading and --light. A capture's varyings follow TRI2's layout (tessera/capture.hpp):
// Gouraud colour 0..3; for Phong the eye-space normal 0..2, position 3..5 and, with ten or
// more, the base colour 6..9; lights in eye space. Meshes go through the vertex stage (eye-space
// position, normal and colour; scene.hpp), lights in world space.
void apply_shading(const Options& o, bool is_capture, Job& job, tessera::PipelineState& pipeline) {
  // Meshes and the demo are lit per pixel unless asked otherwise.
  const std::string s = !o.shading.empty()                           ? o.shading
                        : is_capture || job.mode != Mode::kTriangles ? "gouraud"
                                                                     : "phong";
  const bool vision = s == "normals" || s == "depth" || s == "ids" || s == "objects";
  if (!o.texture.empty() && s != "textured")
    bad_argument("--texture: only with --shading textured");
  if (s != "gouraud" && job.mode != Mode::kTriangles) {
    bad_argument("--shading " + s + ": not with --wireframe or --points");
  }
  if (vision && !has_extension(o.output, ".exr")) {
    bad_argument("--shading " + s + " writes float values: the output must be an .exr file");
  }
  if (!o.lights.empty() && s != "phong") bad_argument("--light: only with --shading phong");
  if (o.lights.size() > tessera::kMaxLights) {
    bad_argument("--light: at most " + std::to_string(tessera::kMaxLights) + " lights");
  }
  if (is_capture) pipeline.roles = {6, 0, 3};
  if (s == "flat") {
    if (!is_capture) bad_argument("--shading flat: for TRI1 and TRI2 captures");
    for (uint32_t c = 0; c < 4; ++c)
      pipeline.varying_modes[c] = tessera::VaryingMode::kFlat;
    pipeline.roles.color = 0;
  } else if (s == "gouraud") {
    pipeline.roles.color = 0;
  } else if (s == "phong") {
    pipeline.shader = tessera::FragmentShader::kPhong;
    job.scene_shading = tessera::SceneShading::kPerPixel;
    glm::mat4 to_eye(1.0f);
    if (!is_capture) to_eye = job.scene->camera.view();
    for (const std::string& spec : o.lights) {
      // Exactly three finite numbers between commas.
      std::vector<float> xyz;
      size_t from = 0;
      bool ok = true;
      while (ok && from <= spec.size() && xyz.size() < 4) {
        const size_t comma = std::min(spec.find(',', from), spec.size());
        const std::string part = spec.substr(from, comma - from);
        size_t used = 0;
        try {
          xyz.push_back(std::stof(part, &used));
        } catch (const std::exception&) {
          ok = false;
        }
        ok = ok && used == part.size() && std::isfinite(xyz.back());
        from = comma + 1;
      }
      if (!ok || xyz.size() != 3) bad_argument("--light: " + spec + " is not x,y,z");
      const glm::vec4 p = to_eye * glm::vec4(xyz[0], xyz[1], xyz[2], 1.0f);
      tessera::Light light;
      light.kind = tessera::LightKind::kPoint;
      light.position = {p.x, p.y, p.z};
      pipeline.phong.lights[pipeline.phong.light_count++] = light;
    }
    if (is_capture && pipeline.phong.light_count == 0) {
      pipeline.phong.light_count = 1;  // a light at the eye
    }
  } else if (s == "textured") {
    // Varyings 0 and 1 are (u, v); the texture's colour as it is stored, nothing else.
    if (!is_capture) bad_argument("--shading textured: for TRI2 captures");
    if (job.capture->varying_count < 2) {
      bad_argument("--shading textured reads (u, v) from varyings 0 and 1, but the capture has " +
                   std::to_string(job.capture->varying_count));
    }
    if (o.texture.empty()) bad_argument("--shading textured needs --texture FILE");
    pipeline.shader = tessera::FragmentShader::kTextured;
    pipeline.roles.texcoord = 0;
    pipeline.roles.color = job.capture->varying_count;  // no colour varyings: white
    tessera::Sampler& sampler = pipeline.sampler;
    const tessera::Filter filter =
        o.filter == "nearest" ? tessera::Filter::kNearest : tessera::Filter::kLinear;
    sampler.mag_filter = sampler.min_filter = filter;
    sampler.mip_filter =
        o.filter == "trilinear" ? tessera::MipFilter::kLinear : tessera::MipFilter::kNone;
    sampler.wrap_u = sampler.wrap_v = o.wrap == "clamp"    ? tessera::Wrap::kClampToEdge
                                      : o.wrap == "mirror" ? tessera::Wrap::kMirroredRepeat
                                      : o.wrap == "border" ? tessera::Wrap::kClampToBorder
                                                           : tessera::Wrap::kRepeat;
    std::copy_n(o.border_color.begin(), 4, sampler.border_color.begin());
    sampler.max_anisotropy = static_cast<float>(o.anisotropy);
    pipeline.texture = std::make_shared<tessera::Texture>(
        tessera::load_texture(o.texture, false, o.filter == "trilinear"));
  } else if (s == "normals") {
    pipeline.output = tessera::TargetOutput::kNormal;
  } else if (s == "depth") {
    pipeline.output = tessera::TargetOutput::kEyeDepth;
  } else if (s == "ids") {
    pipeline.output = tessera::TargetOutput::kPrimitiveId;
  } else if (s == "objects") {
    pipeline.output = tessera::TargetOutput::kObjectId;
    pipeline.object_id = 1;
  }
}

int run(const Options& o, const CLI::App& app) {
  check_finite("--fov", {o.fov});
  check_finite("--eye", o.eye);
  check_finite("--target", o.target);
  check_finite("--up", o.up);
  check_finite("--clear", o.clear);
  check_finite("--border-color", o.border_color);
  check_output_directory("--output", o.output);
  check_output_directory("--depth", o.depth_output);
  check_finite("--point-size", {o.point_size});
  check_finite("--line-width", {o.line_width});
  check_finite("--bin-budget", {static_cast<float>(o.bin_budget_mib)});
  if (o.wireframe && o.points) bad_argument("--wireframe/--points: choose one");
  Job job;
  job.mode = o.wireframe ? Mode::kWireframe : o.points ? Mode::kPoints : Mode::kTriangles;
  job.point_state.size = o.point_size;
  job.point_state.shape =
      o.round_points ? tessera::PointShape::kRound : tessera::PointShape::kSquare;
  job.line_state.width = o.line_width;
  job.line_state.antialiased = o.smooth_lines;
  job.line_state.algorithm = o.line_algorithm == "bresenham" ? tessera::LineAlgorithm::kBresenham
                             : o.line_algorithm == "dda"     ? tessera::LineAlgorithm::kDDA
                                                             : tessera::LineAlgorithm::kDiamondExit;
  uint32_t width = o.width, height = o.height;
  tessera::PipelineState pipeline;
  const bool is_capture = !o.input.empty() && has_extension(o.input, ".tri");
  if (is_capture) {
    if (app.count("--width") || app.count("--height")) {
      throw tessera::Error(tessera::ErrorCode::kInvalidArgument,
                           "--width/--height: a capture renders at its own size");
    }
    if (job.mode != Mode::kTriangles) bad_argument("--wireframe/--points: not for a capture");
    job.capture = tessera::load_capture(o.input);
    width = job.capture->width;
    height = job.capture->height;
    job.triangles = job.capture->positions.size() / 3;
    pipeline = tessera::capture_pipeline();
    if (o.reversed_z) {
      throw tessera::Error(tessera::ErrorCode::kInvalidArgument,
                           "--reversed-z: a capture's clip-space depth is already fixed");
    }
  } else {
    if (o.input.empty()) {
      job.scene = tessera::make_demo_scene();
    } else {
      job.scene.emplace();
      job.scene->objects = load_input(o.input, job.mode);
      job.scene->camera = tessera::frame_bounds(job.scene->bounds(), float(width) / float(height),
                                                {0.55f, 0.45f, 1.0f}, o.fov);
    }
    tessera::Camera& cam = job.scene->camera;
    if (!o.eye.empty()) cam.eye = vec3_of(o.eye);
    if (!o.target.empty()) cam.target = vec3_of(o.target);
    if (!o.up.empty()) cam.up = vec3_of(o.up);
    if (app.count("--fov")) cam.fov_y_degrees = o.fov;
    cam.orthographic = o.ortho;
    check_camera(cam);
    if (!o.eye.empty() || !o.target.empty()) {
      // Keep the framed depth range around the new view distance.
      const tessera::Bounds b = job.scene->bounds();
      const float radius = 0.5f * glm::length(b.max - b.min);
      const float d = glm::length(0.5f * (b.min + b.max) - cam.eye);
      cam.near_plane = std::max(d - 1.5f * radius, 1e-3f * std::max(d, radius));
      cam.far_plane = d + 1.5f * radius;
    }
    cam.reversed_z = o.reversed_z;
    job.triangles = job.scene->triangle_count();
    if (job.mode == Mode::kWireframe) {
      for (const tessera::SceneObject& obj : job.scene->objects)
        job.edges.push_back(unique_edges(obj.mesh.indices));
    }
  }
  pipeline.depth_test = !o.no_depth;
  pipeline.depth_write = !o.no_depth_write;
  if (!o.scissor.empty()) {
    const char* names[] = {"x", "y", "width", "height"};
    for (size_t i = 0; i < 4; ++i) {
      const int64_t v = o.scissor[i], lo = i < 2 ? INT32_MIN : 0,
                    hi = i < 2 ? INT32_MAX : UINT32_MAX;
      if (v < lo || v > hi) {
        bad_argument("--scissor: " + std::string(names[i]) + " " + std::to_string(v) +
                     " is out of range (" + std::to_string(lo) + ".." + std::to_string(hi) + ")");
      }
    }
    pipeline.scissor_test = true;
    pipeline.scissor = {static_cast<int32_t>(o.scissor[0]), static_cast<int32_t>(o.scissor[1]),
                        static_cast<uint32_t>(o.scissor[2]), static_cast<uint32_t>(o.scissor[3])};
  }
  pipeline.blend[0] = o.blend == "over"            ? tessera::BlendState::over()
                      : o.blend == "add"           ? tessera::BlendState::additive()
                      : o.blend == "multiply"      ? tessera::BlendState::multiply()
                      : o.blend == "premultiplied" ? tessera::BlendState::premultiplied_over()
                                                   : tessera::BlendState{};
  if (o.reversed_z) pipeline.depth_compare = tessera::CompareOp::kGreater;
  pipeline.subpixel_bits = o.subpixel_bits;
  pipeline.interpolation =
      o.affine ? tessera::Interpolation::kAffine : tessera::Interpolation::kPerspective;
  pipeline.cull = o.cull == "back"    ? tessera::CullMode::kBack
                  : o.cull == "front" ? tessera::CullMode::kFront
                                      : tessera::CullMode::kNone;

  apply_shading(o, is_capture, job, pipeline);
  const std::vector<Aov> aovs = parse_aovs(o.aovs);
  if (!aovs.empty() && job.mode != Mode::kTriangles) {
    bad_argument("--aov: not with --wireframe or --points (they draw the colour only)");
  }
  const bool float_color = o.float_color || has_extension(o.output, ".exr");
  tessera::FramebufferDesc desc{
      width, height, o.samples,
      float_color ? tessera::ColorFormat::kRGBA32F : tessera::ColorFormat::kRGBA8,
      o.depth_format == "unorm16"   ? tessera::DepthFormat::kUnorm16
      : o.depth_format == "unorm24" ? tessera::DepthFormat::kUnorm24
                                    : tessera::DepthFormat::kFloat32};
  desc.extra_targets = static_cast<uint32_t>(aovs.size());
  for (size_t i = 0; i < aovs.size(); ++i) {
    desc.extra_formats[i] = aovs[i].format;
    pipeline.extra_outputs[i] = aovs[i].output;
  }
  if (is_capture) pipeline.object_id = 1;
  tessera::Framebuffer fb(desc);
  tessera::RendererOptions renderer_options;
  renderer_options.threads = o.threads;
  renderer_options.raster_counters = !o.no_counters;
  renderer_options.hiz = !o.no_hiz;
  renderer_options.tiny_triangle_records = !o.no_records;
  renderer_options.bin_tile_size = o.bin_tile;
  renderer_options.block_size = o.block_size;
  renderer_options.sub_block_tests = o.sub_blocks;
  if (o.bin_budget_mib > 0) {
    renderer_options.bin_memory_budget = static_cast<uint64_t>(o.bin_budget_mib * 1048576.0);
  }
  renderer_options.backend =
      o.backend == "fast" ? tessera::Backend::kFast : tessera::Backend::kReference;
  tessera::Renderer renderer(renderer_options);
  // Vision outputs start from zero (no normal, depth, triangle or object) unless asked.
  const bool vision = pipeline.output != tessera::TargetOutput::kColor;
  std::array<float, 4> clear{o.clear[0], o.clear[1], o.clear[2], o.clear[3]};
  if (vision && !app.count("--clear")) clear = {0.0f, 0.0f, 0.0f, 0.0f};

  auto frame = [&] {
    const auto t0 = Clock::now();
    fb.clear_color(clear);
    fb.clear_depth(o.reversed_z ? 0.0f : 1.0f);
    // The extra targets start at zero: no normal, position, depth or object; no triangle is
    // kNoTriangle.
    for (uint32_t t = 1; t < fb.target_count(); ++t) {
      if (aovs[t - 1].output == tessera::TargetOutput::kPrimitiveId) {
        fb.clear_target_uint(t, kNoTriangle);
      } else if (aovs[t - 1].format == tessera::ColorFormat::kR32UI) {
        fb.clear_target_uint(t, 0);
      } else {
        fb.clear_target(t, {0, 0, 0, 0});
      }
    }
    draw_job(renderer, fb, pipeline, job);
    return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
  };

  std::vector<double> times;
  if (o.repeat > 0) frame();  // warm-up
  renderer.reset_counters();
  const uint32_t frames = std::max<uint32_t>(o.repeat, 1);
  for (uint32_t i = 0; i < frames; ++i)
    times.push_back(frame());
  std::vector<double> sorted = times;
  std::sort(sorted.begin(), sorted.end());
  const double median = sorted.size() % 2
                            ? sorted[sorted.size() / 2]
                            : 0.5 * (sorted[sorted.size() / 2 - 1] + sorted[sorted.size() / 2]);
  const double mtri_s = double(job.triangles) / (median * 1e-3) / 1e6;

  if (float_color) {
    const std::vector<float> px = fb.read_rgba32f();
    tessera::write_image(o.output, width, height, 4, std::span<const float>(px));
  } else {
    const std::vector<uint8_t> px = fb.read_rgba8();
    tessera::write_image(o.output, width, height, 4, std::span<const uint8_t>(px));
  }
  if (!o.depth_output.empty()) {
    const std::vector<float> depth = fb.read_depth();
    tessera::write_image(o.depth_output, width, height, 1, std::span<const float>(depth));
  }
  for (uint32_t t = 1; t < fb.target_count(); ++t) {
    const Aov& a = aovs[t - 1];
    if (a.format == tessera::ColorFormat::kR32UI) {
      const std::vector<uint32_t> ids = fb.read_target_uint(t);
      tessera::write_image(a.path, width, height, 1, std::span<const uint32_t>(ids));
      continue;
    }
    std::vector<float> values = fb.read_target(t);
    if (a.channels == 3) {  // RGB of RGBA
      for (size_t p = 0; p < size_t{width} * height; ++p)
        std::copy_n(&values[p * 4], 3, &values[p * 3]);
      values.resize(size_t{width} * height * 3);
    }
    tessera::write_image(a.path, width, height, a.channels, std::span<const float>(values));
  }

  const tessera::Counters& c = renderer.counters();
  const char* mode_name = job.mode == Mode::kWireframe ? " (wireframe)"
                          : job.mode == Mode::kPoints  ? " (points)"
                                                       : "";
  std::printf("%s%s: %zu triangles, %ux%u, %u sample%s, backend %s, %u thread%s\n",
              o.input.empty() ? "demo scene" : o.input.c_str(), mode_name, job.triangles, width,
              height, o.samples, o.samples == 1 ? "" : "s", o.backend.c_str(), renderer.threads(),
              renderer.threads() == 1 ? "" : "s");
  std::printf("rasterized %llu, culled %llu, clipped %llu; samples covered %llu, passed %llu\n",
              (unsigned long long)(c.triangles_rasterized / frames),
              (unsigned long long)(c.triangles_culled / frames),
              (unsigned long long)(c.triangles_clipped / frames),
              (unsigned long long)(c.samples_covered / frames),
              (unsigned long long)(c.samples_passed / frames));
  if (o.stats) {
    const auto per = [frames](uint64_t v) { return static_cast<unsigned long long>(v / frames); };
    std::printf(
        "per frame: submitted %llu, culled %llu, clipped %llu, rasterized %llu, binned %llu, bin "
        "references %llu, bin passes %llu, blocks rejected %llu, accepted %llu, partial %llu, "
        "sub-blocks rejected %llu, accepted %llu, partial %llu, Hi-Z rejected %llu, Hi-Z "
        "accepted %llu, "
        "samples covered %llu, passed %llu, pixels shaded %llu\n",
        per(c.triangles_submitted), per(c.triangles_culled), per(c.triangles_clipped),
        per(c.triangles_rasterized), per(c.triangles_binned), per(c.bin_references),
        per(c.bin_passes), per(c.blocks_rejected), per(c.blocks_accepted), per(c.blocks_partial),
        per(c.subblocks_rejected), per(c.subblocks_accepted), per(c.subblocks_partial),
        per(c.hiz_rejected), per(c.hiz_accepted), per(c.samples_covered), per(c.samples_passed),
        per(c.pixels_shaded));
    std::printf("per frame: points %llu, line segments %llu, polygons %llu\n",
                per(c.points_submitted), per(c.lines_submitted), per(c.polygons_submitted));
  }
  std::printf("time %.2f ms, %.3f Mtri/s\n", median, mtri_s);
  if (o.repeat > 0) {
    std::printf("frames=%u median_ms=%.3f min_ms=%.3f max_ms=%.3f mtri_s=%.3f\n", frames, median,
                sorted.front(), sorted.back(), mtri_s);
  }
  std::string wrote = o.output;
  if (!o.depth_output.empty()) wrote += ", " + o.depth_output;
  for (const Aov& a : aovs)
    wrote += ", " + a.path;
  std::printf("wrote %s\n", wrote.c_str());
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  Options o;
  CLI::App app{
      "tessera-render: render a mesh (OBJ, glTF 2.0, PLY, ...), a TRI1 capture (.tri), "
      "or the built-in demo scene, with the Tessera software rasterizer"};
  app.add_option("input", o.input, "mesh or .tri capture; none renders the demo scene");
  app.add_option("-o,--output", o.output, "colour image (PNG, or EXR for float colour)")
      ->capture_default_str();
  app.add_option("--depth", o.depth_output, "write the depth buffer to this image (EXR)");
  app.add_option("--width", o.width, "image width in pixels")
      ->check(CLI::Range(1u, tessera::kMaxFramebufferSize))
      ->capture_default_str();
  app.add_option("--height", o.height, "image height in pixels")
      ->check(CLI::Range(1u, tessera::kMaxFramebufferSize))
      ->capture_default_str();
  app.add_option("-s,--samples", o.samples, "MSAA samples per pixel")
      ->check(CLI::IsMember({1u, 2u, 4u, 8u, 16u}))
      ->capture_default_str();
  app.add_option("--eye", o.eye, "camera position x,y,z")->delimiter(',')->expected(3);
  app.add_option("--target", o.target, "point the camera looks at x,y,z")
      ->delimiter(',')
      ->expected(3);
  app.add_option("--up", o.up, "camera up vector x,y,z")->delimiter(',')->expected(3);
  app.add_option("--fov", o.fov, "vertical field of view in degrees")
      ->check(CLI::Range(1.0f, 170.0f))
      ->capture_default_str();
  app.add_flag("--ortho", o.ortho, "orthographic projection");
  app.add_option("--backend", o.backend, "rasterizer")
      ->check(CLI::IsMember({"fast", "reference"}))
      ->capture_default_str();
  app.add_option("--threads", o.threads, "worker threads (0 = all cores)")
      ->check(CLI::Range(0u, 1024u))
      ->capture_default_str();
  app.add_option("--repeat", o.repeat,
                 "render K timed frames after one warm-up and print a summary line")
      ->check(CLI::Range(0u, 1000000u));
  app.add_option("--subpixel-bits", o.subpixel_bits, "fixed-point fraction bits (4..8)")
      ->check(CLI::Range(4u, 8u))
      ->capture_default_str();
  app.add_option("--bin-budget", o.bin_budget_mib,
                 "fast engine: MiB of binned triangles per rasterization pass")
      ->check(CLI::Range(0.0625, 65536.0));
  CLI::Option* stats = app.add_flag("--stats", o.stats, "print every renderer counter, per frame");
  app.add_flag("--no-counters", o.no_counters,
               "fast engine: do not count blocks, samples and pixels (kernels without counting)")
      ->excludes(stats);
  app.add_flag("--no-depth", o.no_depth, "no depth test: later triangles overwrite earlier ones");
  app.add_flag("--no-hiz", o.no_hiz, "fast engine: no Hi-Z block rejection and acceptance");
  app.add_flag("--no-records", o.no_records,
               "fast engine: full setups for tiny triangles instead of pixel and sample records");
  app.add_option("--bin-tile", o.bin_tile, "fast engine: bin tile side in pixels")
      ->check(CLI::IsMember({32u, 64u, 128u}))
      ->capture_default_str();
  app.add_option("--block-size", o.block_size,
                 "fast engine: side in pixels of the blocks the corner test classifies (16 and 32 "
                 "reject or accept the 8x8 blocks inside at once)")
      ->check(CLI::IsMember({8u, 16u, 32u}))
      ->capture_default_str();
  app.add_flag("--sub-blocks", o.sub_blocks,
               "fast engine: classify each SIMD lane group of a partial block before its pixels");
  app.add_option("--depth-format", o.depth_format, "depth buffer format")
      ->check(CLI::IsMember({"float32", "unorm24", "unorm16"}))
      ->capture_default_str();
  app.add_flag("--reversed-z", o.reversed_z,
               "mesh and demo scenes: near maps to depth 1, far to 0, compare greater");
  app.add_option("--cull", o.cull, "face culling")
      ->check(CLI::IsMember({"back", "front", "none"}))
      ->capture_default_str();
  app.add_option("--blend", o.blend,
                 "colour blending (OpenGL factors): over (SRC_ALPHA, ONE_MINUS_SRC_ALPHA; alpha "
                 "ONE, ONE_MINUS_SRC_ALPHA), add (ONE, ONE), multiply (DST_COLOR, ZERO), "
                 "premultiplied (ONE, ONE_MINUS_SRC_ALPHA)")
      ->check(CLI::IsMember({"none", "over", "add", "multiply", "premultiplied"}))
      ->capture_default_str();
  app.add_option("--scissor", o.scissor,
                 "draw only inside this rectangle x,y,w,h (window pixels from the top-left)")
      ->delimiter(',')
      ->expected(4);
  app.add_flag("--no-depth-write", o.no_depth_write,
               "test depth without writing it (the usual state for transparent geometry)");
  app.add_flag("--affine", o.affine, "affine (screen-linear) attribute interpolation");
  app.add_flag("--wireframe", o.wireframe,
               "draw triangle edges as lines, hidden lines removed by the depth buffer");
  app.add_flag("--points", o.points,
               "draw every vertex as a point (PLY files without faces are drawn so anyway)");
  app.add_option("--point-size", o.point_size, "point size in pixels")
      ->check(CLI::Range(1.0f, tessera::kMaxPointSize))
      ->capture_default_str();
  app.add_flag("--round-points", o.round_points, "round, antialiased points");
  app.add_option("--line-width", o.line_width, "wireframe line width in pixels")
      ->check(CLI::Range(1.0f, tessera::kMaxLineWidth))
      ->capture_default_str();
  app.add_option("--line-algorithm", o.line_algorithm, "one-pixel line rule")
      ->check(CLI::IsMember({"diamond", "bresenham", "dda"}))
      ->capture_default_str();
  app.add_flag("--smooth-lines", o.smooth_lines, "antialiased wireframe lines");
  app.add_flag("--float", o.float_color, "float colour buffer (implied by an .exr output)");
  app.add_option("--shading", o.shading,
                 "phong (per pixel: the default for meshes and the demo), gouraud (vertex "
                 "colours, the default for captures; meshes lit per vertex), flat (captures), "
                 "textured (TRI2 captures, --texture), or a float output into an .exr file: "
                 "normals, depth (eye), ids (triangle index), "
                 "objects (object ID)")
      ->check(CLI::IsMember(
          {"gouraud", "flat", "phong", "textured", "normals", "depth", "ids", "objects"}));
  app.add_option("--texture", o.texture,
                 "--shading textured: the image (PNG, JPEG, EXR, TIFF, ...) sampled at a TRI2 "
                 "capture's varyings 0 and 1 as (u, v), u right and v down from the image's "
                 "top-left corner; its values as stored (no sRGB decoding)");
  app.add_option("--filter", o.filter, "--shading textured: texture filter")
      ->check(CLI::IsMember({"nearest", "bilinear", "trilinear"}))
      ->capture_default_str();
  app.add_option("--wrap", o.wrap, "--shading textured: wrap mode of u and v")
      ->check(CLI::IsMember({"repeat", "clamp", "mirror", "border"}))
      ->capture_default_str();
  app.add_option("--border-color", o.border_color,
                 "--shading textured --wrap border: the border colour r,g,b,a (default 0,0,0,0)")
      ->delimiter(',')
      ->expected(4);
  app.add_option("--anisotropy", o.anisotropy,
                 "--shading textured: the most samples of anisotropic filtering (1: off)")
      ->check(CLI::Range(1u, tessera::kMaxAnisotropy))
      ->capture_default_str();
  app.add_option("--light", o.lights,
                 "--shading phong: a point light at x,y,z (eye space for captures, world space "
                 "for meshes); repeatable, up to 8")
      ->expected(1)
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
  app.add_option("--aov", o.aovs,
                 "also write kind=path.exr from the same pass, an extra render target: normals, "
                 "positions, barycentrics (RGB), depth (eye), ids (triangle index, 4294967295 "
                 "where none), objects (object ID, 0 where none); repeatable, up to 3")
      ->expected(1)
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
  app.add_option("--clear", o.clear, "clear colour r,g,b,a")->delimiter(',')->expected(4);
  bool info = false;
  app.add_flag("--info", info, "print the SIMD targets this CPU supports and exit");

  // A parse error is one line that names the argument; --help still prints the usage.
  app.failure_message([](const CLI::App*, const CLI::Error& error) {
    std::string message = error.what();
    std::replace(message.begin(), message.end(), '\n', ' ');
    return "tessera-render: " + message + " (see --help)\n";
  });
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  }
  if (info) {
    std::printf("simd targets:");
    for (const std::string& t : tessera::simd::supported_targets())
      std::printf(" %s", t.c_str());
    std::printf("\n");
    return 0;
  }
  try {
    return run(o, app);
  } catch (const std::exception& e) {
    std::string message = e.what();
    std::replace(message.begin(), message.end(), '\n', ' ');
    std::fprintf(stderr, "tessera-render: %s\n", message.c_str());
    return 1;
  }
}
