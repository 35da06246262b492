// The C API (tessera/tessera.h) against the C++ API: the same scenes drawn through each give
// the same bytes in every render target, on both backends, at 1 and 4 samples, in both colour
// formats; the C states' defaults are the C++ defaults; a failing call returns the code and
// the message of the C++ API's error, in the calling thread only; allocator callbacks hold
// the handles. The C side's own checks (values worked out from the conventions, each error
// path) are tests/c_api_test.c.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <new>
#include <ostream>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "tessera/tessera.h"
#include "tessera/tessera.hpp"

namespace {

// A C framebuffer description of one colour target.
tessera_framebuffer_desc framebuffer_desc(uint32_t width, uint32_t height, uint32_t samples,
                                          tessera_color_format color, tessera_depth_format depth) {
  tessera_framebuffer_desc d{};
  d.width = width;
  d.height = height;
  d.samples = samples;
  d.color_format = color;
  d.depth_format = depth;
  return d;
}

// Owners of C handles, so that a failed assertion leaks nothing.
struct CFramebuffer {
  tessera_framebuffer* handle = nullptr;
  CFramebuffer() = default;
  CFramebuffer(const CFramebuffer&) = delete;
  CFramebuffer& operator=(const CFramebuffer&) = delete;
  ~CFramebuffer() { tessera_framebuffer_destroy(handle); }
};
struct CRenderer {
  tessera_renderer* handle = nullptr;
  CRenderer() = default;
  CRenderer(const CRenderer&) = delete;
  CRenderer& operator=(const CRenderer&) = delete;
  ~CRenderer() { tessera_renderer_destroy(handle); }
};

// A small deterministic generator (the scenes must be the same for both APIs, not random).
struct Lcg {
  uint32_t state;
  float next(float lo, float hi) {
    state = state * 1664525u + 1013904223u;
    return lo + (hi - lo) * static_cast<float>(state >> 8) / static_cast<float>(1u << 24);
  }
};

// One draw's vertex data, shared by both APIs.
struct Mesh {
  std::vector<float> positions;  // 4 per vertex
  std::vector<float> attributes;
  uint32_t attribute_count = 0;
  std::vector<uint32_t> indices;

  size_t vertices() const { return positions.size() / 4; }
  tessera_draw_input c() const {
    return {positions.data(), vertices(),     attributes.data(),
            attribute_count,  indices.data(), indices.size()};
  }
  tessera::DrawInput cpp() const {
    return {{reinterpret_cast<const tessera::Float4*>(positions.data()), vertices()},
            attributes,
            attribute_count,
            indices};
  }
};

// `count` vertices in the view volume (some beyond the near and far planes, to be clipped)
// with `attribute_count` varyings in 0..1.
Mesh random_mesh(uint32_t seed, size_t count, uint32_t attribute_count) {
  Lcg rng{seed};
  Mesh m;
  m.attribute_count = attribute_count;
  for (size_t v = 0; v < count; ++v) {
    const float w = rng.next(0.5f, 2.0f);
    m.positions.insert(m.positions.end(), {rng.next(-1.1f, 1.1f) * w, rng.next(-1.1f, 1.1f) * w,
                                           rng.next(-0.1f, 1.05f) * w, w});
    for (uint32_t a = 0; a < attribute_count; ++a)
      m.attributes.push_back(rng.next(0, 1));
  }
  return m;
}

// A grid of n x n quads over the window, two indexed triangles each, depth rising to the right.
Mesh grid_mesh(uint32_t n, uint32_t attribute_count) {
  Mesh m;
  m.attribute_count = attribute_count;
  for (uint32_t y = 0; y <= n; ++y) {
    for (uint32_t x = 0; x <= n; ++x) {
      const float fx = static_cast<float>(x) / static_cast<float>(n);
      const float fy = static_cast<float>(y) / static_cast<float>(n);
      m.positions.insert(m.positions.end(),
                         {fx * 1.8f - 0.9f, fy * 1.8f - 0.9f, 0.2f + 0.6f * fx, 1});
      for (uint32_t a = 0; a < attribute_count; ++a)
        m.attributes.push_back(a % 2 == 0 ? fx : fy);
    }
  }
  for (uint32_t y = 0; y < n; ++y) {
    for (uint32_t x = 0; x < n; ++x) {
      const uint32_t i = y * (n + 1) + x;
      m.indices.insert(m.indices.end(), {i, i + 1, i + n + 2, i, i + n + 2, i + n + 1});
    }
  }
  return m;
}

// Every render target, read through the C API.
struct Targets {
  std::vector<uint8_t> rgba8;
  std::vector<float> rgba32f, depth, sample_depth;
  friend bool operator==(const Targets&, const Targets&) = default;
};

Targets read_c(const tessera_framebuffer* fb, const tessera::FramebufferDesc& d) {
  const size_t pixels = size_t{d.width} * d.height;
  Targets t{std::vector<uint8_t>(pixels * 4), std::vector<float>(pixels * 4),
            std::vector<float>(pixels), std::vector<float>(pixels * d.samples)};
  EXPECT_EQ(tessera_framebuffer_read_rgba8(fb, t.rgba8.data(), t.rgba8.size()), TESSERA_OK);
  EXPECT_EQ(tessera_framebuffer_read_rgba32f(fb, t.rgba32f.data(), t.rgba32f.size()), TESSERA_OK);
  EXPECT_EQ(tessera_framebuffer_read_depth(fb, t.depth.data(), t.depth.size()), TESSERA_OK);
  EXPECT_EQ(tessera_framebuffer_read_sample_depth(fb, t.sample_depth.data(), t.sample_depth.size()),
            TESSERA_OK);
  return t;
}

Targets read_cpp(const tessera::Framebuffer& fb) {
  return {fb.read_rgba8(), fb.read_rgba32f(), fb.read_depth(), fb.read_sample_depth()};
}

struct Config {
  tessera::Backend backend;
  uint32_t samples;
  tessera::ColorFormat color;
  tessera::DepthFormat depth;
  friend std::string name(const Config& c) {
    return std::string(c.backend == tessera::Backend::kFast ? "Fast" : "Reference") +
           std::to_string(c.samples) + "x" +
           (c.color == tessera::ColorFormat::kRGBA8 ? "Rgba8" : "Rgba32f");
  }
  friend void PrintTo(const Config& c, std::ostream* os) { *os << name(c); }
};

class CApiEquivalence : public ::testing::TestWithParam<Config> {};

// Clears, a triangle soup culled by winding, an indexed grid with changed depth, raster and
// interpolation state, square and round points, and lines of every topology, algorithm, join,
// stipple and antialiasing, drawn through both APIs: every target's bytes are equal.
TEST_P(CApiEquivalence, TheSameSceneGivesTheSameBytesThroughBothApis) {
  const Config config = GetParam();
  constexpr uint32_t kWidth = 150, kHeight = 100;  // not a whole number of tiles
  const tessera::FramebufferDesc desc{kWidth, kHeight, config.samples, config.color, config.depth};

  CRenderer c_renderer;
  const tessera_renderer_desc c_renderer_desc{2, static_cast<tessera_backend>(config.backend)};
  ASSERT_EQ(tessera_renderer_create(&c_renderer_desc, nullptr, &c_renderer.handle), TESSERA_OK);
  CFramebuffer c_fb;
  const tessera_framebuffer_desc c_desc = framebuffer_desc(
      kWidth, kHeight, config.samples, static_cast<tessera_color_format>(config.color),
      static_cast<tessera_depth_format>(config.depth));
  ASSERT_EQ(tessera_framebuffer_create(&c_desc, nullptr, &c_fb.handle), TESSERA_OK);
  tessera::Renderer renderer({.threads = 2, .backend = config.backend});
  tessera::Framebuffer fb(desc);

  ASSERT_EQ(tessera_framebuffer_clear_color(c_fb.handle, 0.1f, 0.2f, 0.3f, 1), TESSERA_OK);
  ASSERT_EQ(tessera_framebuffer_clear_depth(c_fb.handle, 0.9f), TESSERA_OK);
  fb.clear_color({0.1f, 0.2f, 0.3f, 1});
  fb.clear_depth(0.9f);

  // A soup: back faces culled, clockwise front faces.
  const Mesh soup = random_mesh(7, 300, 4);
  tessera_pipeline_state c_pipeline;
  ASSERT_EQ(tessera_pipeline_state_init(&c_pipeline), TESSERA_OK);
  c_pipeline.cull = TESSERA_CULL_BACK;
  c_pipeline.front_face = TESSERA_FRONT_FACE_CLOCKWISE;
  tessera::PipelineState pipeline;
  pipeline.cull = tessera::CullMode::kBack;
  pipeline.front_face = tessera::FrontFace::kClockwise;
  const tessera_draw_input c_soup = soup.c();
  ASSERT_EQ(tessera_draw_triangles(c_renderer.handle, c_fb.handle, &c_pipeline, &c_soup),
            TESSERA_OK)
      << tessera_last_error_message();
  renderer.draw(fb, pipeline, soup.cpp());

  // An indexed grid with six varyings (colour from 2..5), affine, 4 subpixel bits, OpenGL's
  // depth range, LESS_EQUAL without depth writes, the explicit sample count.
  const Mesh grid = grid_mesh(7, 6);
  ASSERT_EQ(tessera_pipeline_state_init(&c_pipeline), TESSERA_OK);
  c_pipeline.depth_compare = TESSERA_COMPARE_LESS_EQUAL;
  c_pipeline.depth_write = false;
  c_pipeline.interpolation = TESSERA_INTERPOLATION_AFFINE;
  c_pipeline.subpixel_bits = 4;
  c_pipeline.clip_depth = TESSERA_CLIP_DEPTH_NEGATIVE_ONE_TO_ONE;
  c_pipeline.samples = config.samples;
  c_pipeline.roles.color = 2;
  pipeline = {};
  pipeline.depth_compare = tessera::CompareOp::kLessEqual;
  pipeline.depth_write = false;
  pipeline.interpolation = tessera::Interpolation::kAffine;
  pipeline.subpixel_bits = 4;
  pipeline.clip_depth = tessera::ClipDepth::kNegativeOneToOne;
  pipeline.samples = config.samples;
  pipeline.roles.color = 2;
  const tessera_draw_input c_grid = grid.c();
  ASSERT_EQ(tessera_draw_triangles(c_renderer.handle, c_fb.handle, &c_pipeline, &c_grid),
            TESSERA_OK)
      << tessera_last_error_message();
  renderer.draw(fb, pipeline, grid.cpp());

  // The soup again, blended: constant colour against one minus source colour, alpha
  // reverse-subtracted, green not written.
  ASSERT_EQ(tessera_pipeline_state_init(&c_pipeline), TESSERA_OK);
  c_pipeline.depth_test = false;
  c_pipeline.blend[0] = {true,
                         TESSERA_BLEND_CONSTANT_COLOR,
                         TESSERA_BLEND_ONE_MINUS_SRC_COLOR,
                         TESSERA_BLEND_OP_ADD,
                         TESSERA_BLEND_SRC_ALPHA_SATURATE,
                         TESSERA_BLEND_DST_ALPHA,
                         TESSERA_BLEND_OP_REVERSE_SUBTRACT,
                         TESSERA_WRITE_RED | TESSERA_WRITE_BLUE | TESSERA_WRITE_ALPHA};
  const float constant[4] = {0.3f, 0.6f, 0.9f, 0.5f};
  std::copy(constant, constant + 4, c_pipeline.blend_constant);
  pipeline = {};
  pipeline.depth_test = false;
  pipeline.blend[0] = {true,
                       tessera::BlendFactor::kConstantColor,
                       tessera::BlendFactor::kOneMinusSrcColor,
                       tessera::BlendOp::kAdd,
                       tessera::BlendFactor::kSrcAlphaSaturate,
                       tessera::BlendFactor::kDstAlpha,
                       tessera::BlendOp::kReverseSubtract,
                       tessera::kWriteRed | tessera::kWriteBlue | tessera::kWriteAlpha};
  pipeline.blend_constant = {0.3f, 0.6f, 0.9f, 0.5f};
  ASSERT_EQ(tessera_draw_triangles(c_renderer.handle, c_fb.handle, &c_pipeline, &c_soup),
            TESSERA_OK)
      << tessera_last_error_message();
  renderer.draw(fb, pipeline, soup.cpp());

  // Points, square then round, depth test off, colour from varyings 0..3.
  const Mesh dots = random_mesh(11, 40, 4);
  ASSERT_EQ(tessera_pipeline_state_init(&c_pipeline), TESSERA_OK);
  c_pipeline.depth_test = false;
  pipeline = {};
  pipeline.depth_test = false;
  const tessera_draw_input c_dots = dots.c();
  for (const auto& [size, round] : {std::pair{3.0f, false}, std::pair{6.5f, true}}) {
    const tessera_point_state c_point{size, round ? TESSERA_POINT_ROUND : TESSERA_POINT_SQUARE};
    ASSERT_EQ(tessera_draw_points(c_renderer.handle, c_fb.handle, &c_pipeline, &c_point, &c_dots),
              TESSERA_OK)
        << tessera_last_error_message();
    renderer.draw_points(fb, pipeline,
                         {size, round ? tessera::PointShape::kRound : tessera::PointShape::kSquare},
                         dots.cpp());
  }

  // Lines: each topology with another algorithm, width, join, stipple and antialiasing.
  const Mesh path = random_mesh(13, 24, 4);
  const tessera_draw_input c_path = path.c();
  ASSERT_EQ(tessera_pipeline_state_init(&c_pipeline), TESSERA_OK);
  c_pipeline.depth_compare = TESSERA_COMPARE_ALWAYS;
  pipeline = {};
  pipeline.depth_compare = tessera::CompareOp::kAlways;
  struct LineCase {
    tessera_line_state c;
    tessera::LineState cpp;
  };
  const LineCase lines[] = {
      {{TESSERA_LINE_LIST, TESSERA_LINE_BRESENHAM, 1, TESSERA_LINE_JOIN_MITER, 4, 0xFFFF, 1, false},
       {tessera::LineTopology::kList,
        tessera::LineAlgorithm::kBresenham,
        1,
        tessera::LineJoin::kMiter,
        4,
        {0xFFFF, 1},
        false}},
      {{TESSERA_LINE_STRIP, TESSERA_LINE_DDA, 1, TESSERA_LINE_JOIN_NONE, 4, 0xF0F3, 2, false},
       {tessera::LineTopology::kStrip,
        tessera::LineAlgorithm::kDDA,
        1,
        tessera::LineJoin::kNone,
        4,
        {0xF0F3, 2},
        false}},
      {{TESSERA_LINE_LOOP, TESSERA_LINE_DIAMOND_EXIT, 4.5f, TESSERA_LINE_JOIN_ROUND, 4, 0xFFFF, 1,
        false},
       {tessera::LineTopology::kLoop,
        tessera::LineAlgorithm::kDiamondExit,
        4.5f,
        tessera::LineJoin::kRound,
        4,
        {0xFFFF, 1},
        false}},
      {{TESSERA_LINE_STRIP, TESSERA_LINE_DIAMOND_EXIT, 3, TESSERA_LINE_JOIN_MITER, 2.5f, 0xFFFF, 1,
        true},
       {tessera::LineTopology::kStrip,
        tessera::LineAlgorithm::kDiamondExit,
        3,
        tessera::LineJoin::kMiter,
        2.5f,
        {0xFFFF, 1},
        true}},
      {{TESSERA_LINE_LOOP, TESSERA_LINE_DIAMOND_EXIT, 2, TESSERA_LINE_JOIN_BEVEL, 4, 0x00FF, 3,
        false},
       {tessera::LineTopology::kLoop,
        tessera::LineAlgorithm::kDiamondExit,
        2,
        tessera::LineJoin::kBevel,
        4,
        {0x00FF, 3},
        false}},
  };
  for (const LineCase& line : lines) {
    ASSERT_EQ(tessera_draw_lines(c_renderer.handle, c_fb.handle, &c_pipeline, &line.c, &c_path),
              TESSERA_OK)
        << tessera_last_error_message();
    renderer.draw_lines(fb, pipeline, line.cpp, path.cpp());
  }

  const Targets c_targets = read_c(c_fb.handle, desc);
  const Targets cpp_targets = read_cpp(fb);
  EXPECT_TRUE(c_targets.rgba8 == cpp_targets.rgba8);
  EXPECT_TRUE(c_targets.rgba32f == cpp_targets.rgba32f);
  EXPECT_TRUE(c_targets.depth == cpp_targets.depth);
  EXPECT_TRUE(c_targets.sample_depth == cpp_targets.sample_depth);
  // The scene drew something: not every pixel is the clear colour.
  const std::vector<uint8_t> cleared = tessera::Framebuffer(desc).read_rgba8();
  EXPECT_NE(cpp_targets.rgba8, cleared);
  tessera_framebuffer_desc read_desc{};
  ASSERT_EQ(tessera_framebuffer_get_desc(c_fb.handle, &read_desc), TESSERA_OK);
  EXPECT_EQ(read_desc.width, kWidth);
  EXPECT_EQ(read_desc.samples, config.samples);
  EXPECT_EQ(read_desc.color_format, c_desc.color_format);
  EXPECT_EQ(read_desc.depth_format, c_desc.depth_format);
}

INSTANTIATE_TEST_SUITE_P(
    BackendsAndTargets, CApiEquivalence,
    ::testing::Values(Config{tessera::Backend::kFast, 1, tessera::ColorFormat::kRGBA8,
                             tessera::DepthFormat::kFloat32},
                      Config{tessera::Backend::kFast, 4, tessera::ColorFormat::kRGBA32F,
                             tessera::DepthFormat::kUnorm24},
                      Config{tessera::Backend::kReference, 1, tessera::ColorFormat::kRGBA32F,
                             tessera::DepthFormat::kUnorm16},
                      Config{tessera::Backend::kReference, 4, tessera::ColorFormat::kRGBA8,
                             tessera::DepthFormat::kFloat32}),
    [](const ::testing::TestParamInfo<Config>& param) { return name(param.param); });

// The shading state crosses the C API field by field: Phong with a point and a spot light,
// two-sided, changed roles, per-varying modes, and the vision outputs (the reference backend
// draws them all).
TEST(CApi, ShadingStateCrossesFieldByField) {
  constexpr uint32_t kSize = 70;
  // Varyings: normal 0..2, colour 3..6, position 7..9, then two more.
  const Mesh mesh = random_mesh(21, 60, 12);

  tessera_pipeline_state c;
  ASSERT_EQ(tessera_pipeline_state_init(&c), TESSERA_OK);
  tessera::PipelineState p;
  c.roles = {3, 0, 7, 10};
  p.roles = {3, 0, 7};
  c.varying_modes[1] = TESSERA_VARYING_FLAT;
  p.varying_modes[1] = tessera::VaryingMode::kFlat;
  c.varying_modes[4] = TESSERA_VARYING_AFFINE;
  p.varying_modes[4] = tessera::VaryingMode::kAffine;
  c.shader = TESSERA_SHADER_PHONG;
  p.shader = tessera::FragmentShader::kPhong;
  const float base[4] = {0.9f, 0.7f, 0.5f, 0.8f};
  std::memcpy(c.phong.base_color, base, sizeof base);
  p.phong.base_color = {0.9f, 0.7f, 0.5f, 0.8f};
  c.phong.ka = p.phong.ka = 0.2f;
  c.phong.kd = p.phong.kd = 0.6f;
  c.phong.ks = p.phong.ks = 0.4f;
  c.phong.shininess = p.phong.shininess = 12;
  c.phong.ambient[1] = p.phong.ambient[1] = 0.5f;
  c.phong.eye[2] = p.phong.eye[2] = 1;
  c.phong.two_sided = p.phong.two_sided = true;
  c.phong.light_count = p.phong.light_count = 2;
  c.phong.lights[0].kind = TESSERA_LIGHT_POINT;
  p.phong.lights[0].kind = tessera::LightKind::kPoint;
  c.phong.lights[0].position[0] = p.phong.lights[0].position[0] = 0.5f;
  c.phong.lights[0].position[2] = p.phong.lights[0].position[2] = 2;
  c.phong.lights[0].diffuse[2] = p.phong.lights[0].diffuse[2] = 0.3f;
  c.phong.lights[0].c1 = p.phong.lights[0].c1 = 0.25f;
  c.phong.lights[0].c2 = p.phong.lights[0].c2 = 0.125f;
  c.phong.lights[1].kind = TESSERA_LIGHT_SPOT;
  p.phong.lights[1].kind = tessera::LightKind::kSpot;
  c.phong.lights[1].position[2] = p.phong.lights[1].position[2] = 3;
  c.phong.lights[1].direction[0] = p.phong.lights[1].direction[0] = 0.1f;
  c.phong.lights[1].specular[0] = p.phong.lights[1].specular[0] = 0.7f;
  c.phong.lights[1].spot_cos_cutoff = p.phong.lights[1].spot_cos_cutoff = 0.5f;
  c.phong.lights[1].spot_exponent = p.phong.lights[1].spot_exponent = 3;

  CRenderer c_renderer;
  const tessera_renderer_desc c_renderer_desc{1, TESSERA_BACKEND_REFERENCE};
  ASSERT_EQ(tessera_renderer_create(&c_renderer_desc, nullptr, &c_renderer.handle), TESSERA_OK);
  tessera::Renderer renderer({.threads = 1, .backend = tessera::Backend::kReference});
  const tessera_draw_input c_input = mesh.c();
  // The colour, then each vision output (object 99 for the object IDs).
  for (uint32_t output = 0; output <= 6; ++output) {
    SCOPED_TRACE("output " + std::to_string(output));
    c.output = static_cast<tessera_target_output>(output);
    p.output = static_cast<tessera::TargetOutput>(output);
    c.object_id = p.object_id = 99;
    CFramebuffer c_fb;
    const tessera_framebuffer_desc c_desc =
        framebuffer_desc(kSize, kSize, 1, TESSERA_COLOR_RGBA32F, TESSERA_DEPTH_FLOAT32);
    ASSERT_EQ(tessera_framebuffer_create(&c_desc, nullptr, &c_fb.handle), TESSERA_OK);
    tessera::Framebuffer fb({kSize, kSize, 1, tessera::ColorFormat::kRGBA32F});
    ASSERT_EQ(tessera_draw_triangles(c_renderer.handle, c_fb.handle, &c, &c_input), TESSERA_OK)
        << tessera_last_error_message();
    renderer.draw(fb, p, mesh.cpp());
    EXPECT_TRUE(read_c(c_fb.handle, fb.desc()) == read_cpp(fb));
  }
}

// tessera_*_init fill the C++ API's defaults.
TEST(CApi, InitFunctionsGiveTheCppDefaults) {
  tessera_pipeline_state c;
  std::memset(&c, 0xA5, sizeof c);
  ASSERT_EQ(tessera_pipeline_state_init(&c), TESSERA_OK);
  const tessera::PipelineState p;
  EXPECT_EQ(c.depth_test, p.depth_test);
  EXPECT_EQ(c.depth_write, p.depth_write);
  EXPECT_EQ(static_cast<int>(c.depth_compare), static_cast<int>(p.depth_compare));
  EXPECT_EQ(c.color_write, p.color_write);
  EXPECT_EQ(static_cast<int>(c.cull), static_cast<int>(p.cull));
  EXPECT_EQ(static_cast<int>(c.front_face), static_cast<int>(p.front_face));
  EXPECT_EQ(static_cast<int>(c.clip_depth), static_cast<int>(p.clip_depth));
  EXPECT_EQ(static_cast<int>(c.interpolation), static_cast<int>(p.interpolation));
  EXPECT_EQ(c.samples, p.samples);
  EXPECT_EQ(c.subpixel_bits, p.subpixel_bits);
  for (uint32_t i = 0; i < TESSERA_MAX_VARYINGS; ++i)
    EXPECT_EQ(static_cast<int>(c.varying_modes[i]), static_cast<int>(p.varying_modes[i]));
  EXPECT_EQ(static_cast<int>(c.shader), static_cast<int>(p.shader));
  EXPECT_EQ(static_cast<int>(c.output), static_cast<int>(p.output));
  EXPECT_EQ(c.roles.color, p.roles.color);
  EXPECT_EQ(c.roles.normal, p.roles.normal);
  EXPECT_EQ(c.roles.position, p.roles.position);
  for (int i = 0; i < 4; ++i)
    EXPECT_EQ(c.phong.base_color[i], p.phong.base_color[i]);
  EXPECT_EQ(c.phong.ka, p.phong.ka);
  EXPECT_EQ(c.phong.kd, p.phong.kd);
  EXPECT_EQ(c.phong.ks, p.phong.ks);
  EXPECT_EQ(c.phong.shininess, p.phong.shininess);
  for (int i = 0; i < 3; ++i) {
    EXPECT_EQ(c.phong.ambient[i], p.phong.ambient[i]);
    EXPECT_EQ(c.phong.eye[i], p.phong.eye[i]);
  }
  EXPECT_EQ(c.phong.two_sided, p.phong.two_sided);
  EXPECT_EQ(c.phong.light_count, p.phong.light_count);
  for (uint32_t l = 0; l < TESSERA_MAX_LIGHTS; ++l) {
    const tessera_light& cl = c.phong.lights[l];
    const tessera::Light& pl = p.phong.lights[l];
    EXPECT_EQ(static_cast<int>(cl.kind), static_cast<int>(pl.kind));
    for (int i = 0; i < 3; ++i) {
      EXPECT_EQ(cl.position[i], pl.position[i]);
      EXPECT_EQ(cl.direction[i], pl.direction[i]);
      EXPECT_EQ(cl.diffuse[i], pl.diffuse[i]);
      EXPECT_EQ(cl.specular[i], pl.specular[i]);
    }
    EXPECT_EQ(cl.c0, pl.c0);
    EXPECT_EQ(cl.c1, pl.c1);
    EXPECT_EQ(cl.c2, pl.c2);
    EXPECT_EQ(cl.spot_cos_cutoff, pl.spot_cos_cutoff);
    EXPECT_EQ(cl.spot_exponent, pl.spot_exponent);
  }
  EXPECT_EQ(c.object_id, p.object_id);

  tessera_point_state point;
  ASSERT_EQ(tessera_point_state_init(&point), TESSERA_OK);
  const tessera::PointState cpp_point;
  EXPECT_EQ(point.size, cpp_point.size);
  EXPECT_EQ(static_cast<int>(point.shape), static_cast<int>(cpp_point.shape));

  tessera_line_state line;
  ASSERT_EQ(tessera_line_state_init(&line), TESSERA_OK);
  const tessera::LineState cpp_line;
  EXPECT_EQ(static_cast<int>(line.topology), static_cast<int>(cpp_line.topology));
  EXPECT_EQ(static_cast<int>(line.algorithm), static_cast<int>(cpp_line.algorithm));
  EXPECT_EQ(line.width, cpp_line.width);
  EXPECT_EQ(static_cast<int>(line.join), static_cast<int>(cpp_line.join));
  EXPECT_EQ(line.miter_limit, cpp_line.miter_limit);
  EXPECT_EQ(line.stipple_pattern, cpp_line.stipple.pattern);
  EXPECT_EQ(line.stipple_factor, cpp_line.stipple.factor);
  EXPECT_EQ(line.antialiased, cpp_line.antialiased);

  tessera_renderer_desc renderer;
  ASSERT_EQ(tessera_renderer_desc_init(&renderer), TESSERA_OK);
  const tessera::RendererOptions options;
  EXPECT_EQ(renderer.threads, options.threads);
  EXPECT_EQ(static_cast<int>(renderer.backend), static_cast<int>(options.backend));
}

// A call whose C++ counterpart throws returns that error's code and message (after the
// function's name); one whose counterpart draws returns TESSERA_OK. Whatever the backends
// support, both APIs agree.
TEST(CApi, ErrorsAreTheCppApisErrors) {
  const Mesh mesh = random_mesh(5, 30, 10);
  struct Case {
    const char* name;
    tessera_backend backend;
    void (*c)(tessera_pipeline_state&);
    void (*cpp)(tessera::PipelineState&);
  };
  const Case cases[] = {
      {"phong on the fast engine", TESSERA_BACKEND_FAST,
       [](tessera_pipeline_state& s) { s.shader = TESSERA_SHADER_PHONG; },
       [](tessera::PipelineState& s) { s.shader = tessera::FragmentShader::kPhong; }},
      {"object IDs on the fast engine", TESSERA_BACKEND_FAST,
       [](tessera_pipeline_state& s) { s.output = TESSERA_OUTPUT_OBJECT_ID; },
       [](tessera::PipelineState& s) { s.output = tessera::TargetOutput::kObjectId; }},
      {"a flat colour on the fast engine", TESSERA_BACKEND_FAST,
       [](tessera_pipeline_state& s) { s.varying_modes[0] = TESSERA_VARYING_FLAT; },
       [](tessera::PipelineState& s) { s.varying_modes[0] = tessera::VaryingMode::kFlat; }},
      {"object IDs into RGBA8", TESSERA_BACKEND_REFERENCE,
       [](tessera_pipeline_state& s) { s.output = TESSERA_OUTPUT_OBJECT_ID; },
       [](tessera::PipelineState& s) { s.output = tessera::TargetOutput::kObjectId; }},
      {"subpixel bits 9", TESSERA_BACKEND_FAST,
       [](tessera_pipeline_state& s) { s.subpixel_bits = 9; },
       [](tessera::PipelineState& s) { s.subpixel_bits = 9; }},
      {"a NaN light", TESSERA_BACKEND_REFERENCE,
       [](tessera_pipeline_state& s) {
         s.shader = TESSERA_SHADER_PHONG;
         s.phong.light_count = 1;
         s.phong.lights[0].c0 = std::nanf("");
       },
       [](tessera::PipelineState& s) {
         s.shader = tessera::FragmentShader::kPhong;
         s.phong.light_count = 1;
         s.phong.lights[0].c0 = std::nanf("");
       }},
      {"nine lights", TESSERA_BACKEND_REFERENCE,
       [](tessera_pipeline_state& s) {
         s.shader = TESSERA_SHADER_PHONG;
         s.phong.light_count = 9;
       },
       [](tessera::PipelineState& s) {
         s.shader = tessera::FragmentShader::kPhong;
         s.phong.light_count = 9;
       }},
      {"an extra target blending", TESSERA_BACKEND_FAST,
       [](tessera_pipeline_state& s) { s.blend[2].enable = true; },
       [](tessera::PipelineState& s) { s.blend[2].enable = true; }},
      {"a blend constant of infinity", TESSERA_BACKEND_REFERENCE,
       [](tessera_pipeline_state& s) { s.blend_constant[1] = INFINITY; },
       [](tessera::PipelineState& s) {
         s.blend_constant[1] = std::numeric_limits<float>::infinity();
       }},
      {"roles past the varyings", TESSERA_BACKEND_REFERENCE,
       [](tessera_pipeline_state& s) {
         s.output = TESSERA_OUTPUT_NORMAL;
         s.roles.normal = 8;
       },
       [](tessera::PipelineState& s) {
         s.output = tessera::TargetOutput::kNormal;
         s.roles.normal = 8;
       }},
  };
  for (const Case& test : cases) {
    SCOPED_TRACE(test.name);
    CRenderer c_renderer;
    const tessera_renderer_desc c_renderer_desc{1, test.backend};
    ASSERT_EQ(tessera_renderer_create(&c_renderer_desc, nullptr, &c_renderer.handle), TESSERA_OK);
    CFramebuffer c_fb;
    const tessera_framebuffer_desc c_desc =
        framebuffer_desc(32, 32, 1, TESSERA_COLOR_RGBA8, TESSERA_DEPTH_FLOAT32);
    ASSERT_EQ(tessera_framebuffer_create(&c_desc, nullptr, &c_fb.handle), TESSERA_OK);
    tessera_pipeline_state c;
    ASSERT_EQ(tessera_pipeline_state_init(&c), TESSERA_OK);
    test.c(c);
    const tessera_draw_input c_input = mesh.c();
    const tessera_result result =
        tessera_draw_triangles(c_renderer.handle, c_fb.handle, &c, &c_input);

    tessera::Renderer renderer(
        {.threads = 1, .backend = static_cast<tessera::Backend>(test.backend)});
    tessera::Framebuffer fb({32, 32, 1, tessera::ColorFormat::kRGBA8});
    tessera::PipelineState p;
    test.cpp(p);
    try {
      renderer.draw(fb, p, mesh.cpp());
      EXPECT_EQ(result, TESSERA_OK) << tessera_last_error_message();
      EXPECT_STREQ(tessera_last_error_message(), "");
    } catch (const tessera::Error& e) {
      const tessera_result expected[] = {TESSERA_ERROR_INVALID_ARGUMENT,
                                         TESSERA_ERROR_INVALID_INPUT, TESSERA_ERROR_IO,
                                         TESSERA_ERROR_OUT_OF_MEMORY, TESSERA_ERROR_UNSUPPORTED};
      EXPECT_EQ(result, expected[static_cast<int>(e.code())]);
      EXPECT_EQ(tessera_last_error(), result);
      EXPECT_EQ(std::string(tessera_last_error_message()),
                std::string("tessera_draw_triangles: ") + e.what());
    }
  }
}

// The last error belongs to the thread that made the call.
TEST(CApi, TheLastErrorIsPerThread) {
  EXPECT_EQ(tessera_pipeline_state_init(nullptr), TESSERA_ERROR_INVALID_ARGUMENT);
  const std::string here = tessera_last_error_message();
  EXPECT_EQ(here, "tessera_pipeline_state_init: state is NULL");
  std::string there;
  tessera_result there_before = TESSERA_ERROR_INTERNAL, there_after = TESSERA_ERROR_INTERNAL;
  std::thread other([&] {
    there_before = tessera_last_error();
    EXPECT_EQ(tessera_framebuffer_clear_depth(nullptr, 0), TESSERA_ERROR_INVALID_ARGUMENT);
    there_after = tessera_last_error();
    there = tessera_last_error_message();
  });
  other.join();
  EXPECT_EQ(there_before, TESSERA_OK);
  EXPECT_EQ(there_after, TESSERA_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(there, "tessera_framebuffer_clear_depth: framebuffer is NULL");
  EXPECT_EQ(tessera_last_error(), TESSERA_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(std::string(tessera_last_error_message()), here);
}

// Handles created with allocator callbacks live in memory from them, aligned as asked, and
// give it back when destroyed.
TEST(CApi, AllocatorCallbacksHoldTheHandles) {
  struct Log {
    std::vector<std::pair<void*, size_t>> allocations;  // pointer, alignment
    int frees = 0;
  } calls;
  const tessera_allocator allocator{
      [](size_t size, size_t alignment, void* user) -> void* {
        void* p = ::operator new (size, std::align_val_t{alignment});
        static_cast<Log*>(user)->allocations.push_back({p, alignment});
        return p;
      },
      [](void* p, void* user) {
        auto* l = static_cast<Log*>(user);
        for (const auto& [q, alignment] : l->allocations) {
          if (q == p) ::operator delete (p, std::align_val_t{alignment});
        }
        ++l->frees;
      },
      &calls};
  tessera_framebuffer* fb = nullptr;
  const tessera_framebuffer_desc desc =
      framebuffer_desc(16, 16, 2, TESSERA_COLOR_RGBA8, TESSERA_DEPTH_FLOAT32);
  ASSERT_EQ(tessera_framebuffer_create(&desc, &allocator, &fb), TESSERA_OK);
  tessera_renderer* renderer = nullptr;
  tessera_renderer_desc renderer_desc;
  ASSERT_EQ(tessera_renderer_desc_init(&renderer_desc), TESSERA_OK);
  ASSERT_EQ(tessera_renderer_create(&renderer_desc, &allocator, &renderer), TESSERA_OK);
  ASSERT_EQ(calls.allocations.size(), 2u);
  EXPECT_EQ(static_cast<void*>(fb), calls.allocations[0].first);
  EXPECT_EQ(static_cast<void*>(renderer), calls.allocations[1].first);
  for (const auto& [p, alignment] : calls.allocations) {
    EXPECT_NE(alignment, 0u);
    EXPECT_EQ(alignment & (alignment - 1), 0u);
    EXPECT_EQ(reinterpret_cast<uintptr_t>(p) % alignment, 0u);
  }
  tessera_renderer_destroy(renderer);
  tessera_framebuffer_destroy(fb);
  EXPECT_EQ(calls.frees, 2);
}

}  // namespace
