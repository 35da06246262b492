// The vertex stage (tessera/vertex.hpp): pass-through draws what draw() draws; the built-in
// transform's positions and normals against double-precision arithmetic written out here; the
// same bits on every SIMD target and thread count; each vertex shaded once however many
// triangles share it; interleaved streams; user shaders; and the errors bad streams get.
#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "engine/src/vertex/vertex_stage.hpp"
#include "simd/dispatch.hpp"
#include "tessera/tessera.hpp"
#include "tests/extremes_support.hpp"

namespace tessera {
namespace {

// A 2 x 2 x 2 cube's 8 corners around the origin and its 12 triangles.
const std::vector<float> kCorners = {-1, -1, -1, 1, -1, -1, 1, 1, -1, -1, 1, -1,
                                     -1, -1, 1,  1, -1, 1,  1, 1, 1,  -1, 1, 1};
const std::vector<uint32_t> kCubeIndices = {0, 2, 1, 0, 3, 2, 4, 5, 6, 4, 6, 7, 0, 1, 5, 0, 5, 4,
                                            2, 3, 7, 2, 7, 6, 1, 2, 6, 1, 6, 5, 0, 4, 7, 0, 7, 3};

// Column-major matrices.
std::array<float, 16> translation(float x, float y, float z) {
  return {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, x, y, z, 1};
}
std::array<float, 16> perspective(float near, float far) {
  // OpenGL-style, 90 degrees, aspect 1, looking down -z.
  return {1,
          0,
          0,
          0,
          0,
          1,
          0,
          0,
          0,
          0,
          (far + near) / (near - far),
          -1,
          0,
          0,
          2 * far * near / (near - far),
          0};
}
std::array<double, 4> times(const std::array<float, 16>& m, std::array<double, 4> v) {
  std::array<double, 4> r{};
  for (int row = 0; row < 4; ++row) {
    for (int k = 0; k < 4; ++k)
      r[row] += double{m[k * 4 + row]} * v[k];
  }
  return r;
}

TransformShader cube_transform() {
  TransformShader t;
  // A non-uniform scale and a rotation about y by 30 degrees, then 5 units away.
  const float c = std::cos(0.5235988f), s = std::sin(0.5235988f);
  t.model = {2 * c, 0, -2 * s, 0, 0, 0.5f, 0, 0, s, 0, c, 0, 0, 0, 0, 1};
  t.view = translation(0.25f, -0.5f, -6.0f);
  t.projection = perspective(1.0f, 20.0f);
  return t;
}

struct Shaded {
  std::vector<Float4> positions;
  std::vector<float> varyings;
  uint32_t per_vertex = 0;
};

Shaded shade(const VertexShader& shader, const VertexInput& input,
             SimdTarget target = SimdTarget::kAuto, uint32_t threads = 1) {
  Shaded out;
  out.per_vertex = vertex::validate(shader, input);
  tbb::task_arena arena(static_cast<int>(threads));
  vertex::shade(arena, simd::resolve_target(target), shader, input, out.per_vertex, out.positions,
                out.varyings);
  return out;
}

TEST(VertexStage, TheTransformsPositionsAndNormalsAreTheMatrixProducts) {
  std::vector<float> normals;  // one per corner, pointing outward
  for (size_t i = 0; i < kCorners.size(); ++i)
    normals.push_back(kCorners[i] / std::sqrt(3.0f));
  const VertexStream streams[] = {{kCorners, 3}, {normals, 3}};
  VertexShader shader;
  shader.kind = VertexShaderKind::kTransform;
  shader.transform = cube_transform();
  shader.transform.normal_stream = 1;
  const Shaded out = shade(shader, {streams, 8, kCubeIndices});
  ASSERT_EQ(out.per_vertex, 6u);
  const TransformShader& t = shader.transform;
  for (size_t v = 0; v < 8; ++v) {
    const std::array<double, 4> p = {kCorners[v * 3], kCorners[v * 3 + 1], kCorners[v * 3 + 2], 1};
    const auto eye = times(t.view, times(t.model, p));
    const auto clip = times(t.projection, eye);
    const float got[4] = {out.positions[v].x, out.positions[v].y, out.positions[v].z,
                          out.positions[v].w};
    for (int c = 0; c < 4; ++c)
      EXPECT_NEAR(got[c], clip[c], 1e-5 * (1 + std::abs(clip[c]))) << v << " clip " << c;
    for (int c = 0; c < 3; ++c)
      EXPECT_NEAR(out.varyings[v * 6 + c], eye[c], 1e-5 * (1 + std::abs(eye[c]))) << v;
    // The normal through the inverse transpose of view * model's 3x3 part: for every eye-space
    // tangent direction t = M d (d any object-space direction orthogonal to the normal n),
    // (M^-T n) . (M d) = n . d = 0. Checked for two directions orthogonal to this corner's
    // diagonal normal, which a plain M n (not the inverse transpose) fails under the
    // non-uniform scale.
    const std::array<double, 3> n = {kCorners[v * 3], kCorners[v * 3 + 1], kCorners[v * 3 + 2]};
    const std::array<std::array<double, 4>, 2> tangents = {
        std::array<double, 4>{n[1], -n[0], 0, 0}, std::array<double, 4>{0, n[2], -n[1], 0}};
    for (const auto& d : tangents) {
      const auto te = times(t.view, times(t.model, d));
      double dot = 0, length = 0;
      for (int c = 0; c < 3; ++c) {
        dot += out.varyings[v * 6 + 3 + c] * te[c];
        length += out.varyings[v * 6 + 3 + c] * out.varyings[v * 6 + 3 + c];
      }
      EXPECT_NEAR(dot, 0.0, 1e-5) << v;
      EXPECT_GT(length, 0.01) << v;
    }
  }
  // Face normals through the same stage: the +x face normal against the face's tangents.
  const std::vector<float> face = {0, 0, 0};
  const std::vector<float> x_normal = {1, 0, 0};
  const VertexStream one[] = {{face, 3}, {x_normal, 3}};
  const Shaded n = shade(shader, {one, 1, {}});
  const double nx = n.varyings[3], ny = n.varyings[4], nz = n.varyings[5];
  for (const std::array<double, 4> tangent :
       {std::array<double, 4>{0, 1, 0, 0}, std::array<double, 4>{0, 0, 1, 0}}) {
    const auto te = times(t.view, times(t.model, tangent));
    EXPECT_NEAR(nx * te[0] + ny * te[1] + nz * te[2], 0.0, 1e-6);
  }
  EXPECT_GT(std::abs(nx) + std::abs(ny) + std::abs(nz), 0.1);
}

TEST(VertexStage, TheTransformGivesTheSameBitsOnEveryTargetAndThreadCount) {
  std::vector<float> positions, extra;
  for (int i = 0; i < 1000; ++i) {
    const float f = static_cast<float>(i);
    positions.insert(positions.end(), {std::sin(f * 0.37f) * 3, std::cos(f * 0.11f), f * 0.01f});
    extra.insert(extra.end(), {f * 0.5f, -f * 0.25f});
  }
  const VertexStream streams[] = {{positions, 3}, {extra, 2}};
  VertexShader shader;
  shader.kind = VertexShaderKind::kTransform;
  shader.transform = cube_transform();
  const Shaded first = shade(shader, {streams, 1000, {}}, SimdTarget::kScalar, 1);
  ASSERT_EQ(first.per_vertex, 5u);
  EXPECT_EQ(first.varyings[999 * 5 + 3], 999 * 0.5f);  // the extra stream, passed through
  EXPECT_EQ(first.varyings[999 * 5 + 4], -999 * 0.25f);
  for (SimdTarget target : extremes::available_targets()) {
    for (uint32_t threads : {1u, 2u, 3u}) {
      const Shaded other = shade(shader, {streams, 1000, {}}, target, threads);
      EXPECT_EQ(other.positions, first.positions)
          << simd::target_name(simd::resolve_target(target));
      EXPECT_EQ(other.varyings, first.varyings);
    }
  }
}

TEST(VertexStage, PassThroughDrawsWhatDrawDrawsAndInterleavedStreamsReadTheSame) {
  // Clip-space xyzw and RGBA colour, interleaved 8 floats per vertex.
  const std::vector<float> interleaved = {-0.9f, -0.8f, 0.5f, 1, 1, 0, 0, 1,  //
                                          0.8f,  -0.9f, 0.2f, 1, 0, 1, 0, 1,  //
                                          0.1f,  0.9f,  0.7f, 2, 0, 0, 1, 0.5f};
  std::vector<Float4> positions;
  std::vector<float> colours;
  for (size_t v = 0; v < 3; ++v) {
    const float* p = &interleaved[v * 8];
    positions.push_back({p[0], p[1], p[2], p[3]});
    colours.insert(colours.end(), p + 4, p + 8);
  }
  const VertexStream streams[] = {{interleaved, 4, 8, 0}, {interleaved, 4, 8, 4}};
  for (Backend backend : {Backend::kFast, Backend::kReference}) {
    RendererOptions options;
    options.backend = backend;
    Renderer renderer(options);
    Framebuffer a({64, 64, 4}), b({64, 64, 4});
    renderer.draw(a, {}, {positions, colours, 4, {}});
    renderer.draw_vertices(b, {}, VertexShader{}, {streams, 3, {}});
    EXPECT_EQ(a.read_rgba8(), b.read_rgba8());
    EXPECT_EQ(a.read_sample_depth(), b.read_sample_depth());
  }
}

TEST(VertexStage, EachVertexIsShadedOnceHoweverManyTrianglesShareIt) {
  // A 30 x 30 grid of quads: inner vertices belong to six triangles.
  constexpr uint32_t kSide = 31;
  std::vector<float> xy;
  for (uint32_t y = 0; y < kSide; ++y) {
    for (uint32_t x = 0; x < kSide; ++x)
      xy.insert(xy.end(),
                {static_cast<float>(x) / 15.0f - 1.0f, static_cast<float>(y) / 15.0f - 1.0f});
  }
  std::vector<uint32_t> indices;
  for (uint32_t y = 0; y + 1 < kSide; ++y) {
    for (uint32_t x = 0; x + 1 < kSide; ++x) {
      const uint32_t v = y * kSide + x;
      indices.insert(indices.end(), {v, v + 1, v + kSide, v + 1, v + kSide + 1, v + kSide});
    }
  }
  std::atomic<uint64_t> shaded{0};
  std::vector<std::atomic<uint32_t>> per_vertex(kSide * kSide);
  VertexShader shader;
  shader.kind = VertexShaderKind::kUser;
  shader.user_varyings = 4;
  shader.user = [&](const VertexBatch& b) {
    shaded += b.count;
    for (uint32_t i = 0; i < b.count; ++i) {
      ++per_vertex[b.first + i];
      b.clip(0)[i] = b.input(0, 0)[i];
      b.clip(1)[i] = b.input(0, 1)[i];
      b.clip(2)[i] = 0.5f;
      b.clip(3)[i] = b.input(0, 3)[i];  // a missing fourth component reads 1
      for (uint32_t k = 0; k < 4; ++k)
        b.varying(k)[i] = k == 1 ? 1.0f : b.input(0, 2)[i];  // a missing third reads 0
    }
  };
  const VertexStream streams[] = {{xy, 2}};
  RendererOptions options;
  options.threads = 2;
  Renderer renderer(options);
  Framebuffer fb({64, 64, 1});
  renderer.draw_vertices(fb, {}, shader, {streams, kSide * kSide, indices});
  EXPECT_EQ(shaded.load(), uint64_t{kSide} * kSide);
  for (const auto& n : per_vertex)
    ASSERT_EQ(n.load(), 1u);
  EXPECT_EQ(renderer.counters().triangles_submitted, indices.size() / 3);
  // Every pixel of the screen-filling grid is green (0, 1, 0, 0).
  const std::vector<uint8_t> rgba = fb.read_rgba8();
  for (size_t i = 0; i < rgba.size(); i += 4)
    ASSERT_EQ((std::array<uint8_t, 4>{rgba[i], rgba[i + 1], rgba[i + 2], rgba[i + 3]}),
              (std::array<uint8_t, 4>{0, 255, 0, 0}));
}

TEST(VertexStage, AUserShaderThatThrowsEndsTheDrawBeforeAnythingIsDrawn) {
  const VertexStream streams[] = {{kCorners, 3}};
  VertexShader shader;
  shader.kind = VertexShaderKind::kUser;
  shader.user = [](const VertexBatch&) { throw std::runtime_error("shader says no"); };
  Renderer renderer;
  Framebuffer fb({16, 16, 1});
  fb.clear_color({0.5f, 0.5f, 0.5f, 0.5f});
  const std::vector<uint8_t> before = fb.read_rgba8();
  try {
    renderer.draw_vertices(fb, {}, shader, {streams, 8, kCubeIndices});
    ADD_FAILURE() << "the shader's exception was lost";
  } catch (const Error& e) {
    ADD_FAILURE() << "a tessera::Error instead of the shader's exception: " << e.what();
  } catch (const std::runtime_error& e) {
    EXPECT_EQ(std::string(e.what()), "shader says no");
  }
  EXPECT_EQ(fb.read_rgba8(), before);
}

TEST(VertexStage, BadStreamsAndShadersAreRejectedNamingTheProblem) {
  const std::vector<float> data(64, 0.5f);
  struct Bad {
    const char* what;
    std::vector<VertexStream> streams;
    size_t count;
    VertexShader shader;
  };
  VertexShader transform;
  transform.kind = VertexShaderKind::kTransform;
  VertexShader flat = transform;  // a model that squashes z to nothing: no normal matrix
  flat.transform.model[10] = 0.0f;
  flat.transform.normal_stream = 1;
  VertexShader bad_normal = transform;
  bad_normal.transform.normal_stream = 2;
  VertexShader user;
  user.kind = VertexShaderKind::kUser;
  VertexShader many = user;
  many.user = [](const VertexBatch&) {};
  many.user_varyings = kMaxVaryings + 1;
  const std::vector<Bad> bad = {
      {"1 to 16 streams", {}, 3, VertexShader{}},
      {"vertex stream 0 has 5 components", {{data, 5}}, 3, VertexShader{}},
      {"stride of 2 floats", {{data, 4, 2}}, 3, VertexShader{}},
      {"vertex stream 1 holds 64 floats, but 20 vertices need 80",
       {{data, 3}, {data, 4}},
       20,
       transform},
      {"needs stream 0 as clip-space", {{data, 3}}, 3, VertexShader{}},
      {"normal matrix does not exist", {{data, 3}, {data, 3}}, 3, flat},
      {"normal_stream 2", {{data, 3}, {data, 3}}, 3, bad_normal},
      {"no callable", {{data, 3}}, 3, user},
      {"writes 33 varyings", {{data, 3}}, 3, many},
      {"at most 2^32 - 1 vertices", {{data, 3}}, size_t{1} << 33, transform},
      {"3 vertices need 4294967299", {{data, 3, 0x80000000u}}, 3, transform},
  };
  for (const Bad& b : bad) {
    Renderer renderer;
    Framebuffer fb({16, 16, 1});
    try {
      renderer.draw_vertices(fb, {}, b.shader, {b.streams, b.count, {}});
      ADD_FAILURE() << b.what << ": accepted";
    } catch (const Error& e) {
      EXPECT_EQ(e.code(), ErrorCode::kInvalidArgument) << e.what();
      EXPECT_NE(std::string(e.what()).find(b.what), std::string::npos) << e.what();
    }
  }
  // A shaded position that is not finite is draw()'s error, naming the vertex.
  std::vector<float> nan_corner = kCorners;
  nan_corner[4 * 3 + 1] = std::nanf("");
  const VertexStream streams[] = {{nan_corner, 3}};
  Renderer renderer;
  Framebuffer fb({16, 16, 1});
  try {
    renderer.draw_vertices(fb, {}, transform, {streams, 8, kCubeIndices});
    ADD_FAILURE() << "a NaN position accepted";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ErrorCode::kInvalidInput);
    EXPECT_NE(std::string(e.what()).find("vertex 4"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace tessera
