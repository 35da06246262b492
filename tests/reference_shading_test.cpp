// Shading in the reference rasterizer (tessera/shading.hpp): up to 32 varyings, each
// perspective-correct, affine or flat; clipping carries all of them; per-pixel Phong against
// the formula evaluated here; the vision outputs (eye depth, normals, positions,
// barycentrics, primitive and object IDs); the validation of the shading state. Per-pixel Phong
// against the formula and two-sided lighting are checked in both backends.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "tessera/tessera.hpp"
#include "tests/reference_test_support.hpp"

namespace tessera {
namespace {

using test::Viewport;

constexpr uint32_t kSize = 32;

Framebuffer float_target(uint32_t samples = 1) {
  return Framebuffer({kSize, kSize, samples, ColorFormat::kRGBA32F});
}

// One RGBA32F pixel.
std::array<float, 4> pixel(const std::vector<float>& rgba, uint32_t x, uint32_t y) {
  const size_t i = (size_t{y} * kSize + x) * 4;
  return {rgba[i], rgba[i + 1], rgba[i + 2], rgba[i + 3]};
}

// A triangle with varied w, so perspective and affine interpolation differ, covering much of
// the 32x32 target, and one vertex value set per varying: vertex v's varying i is
// (i + 1) * (v + 1) + 0.25 i.
struct Scene {
  std::vector<Float4> positions;
  std::vector<float> varyings;
  uint32_t count = 0;

  DrawInput input() const { return {positions, varyings, count, {}}; }
};

Scene perspective_triangle(uint32_t count) {
  const Viewport vp{kSize, kSize};
  Scene s;
  s.positions = {vp.at(1, 1, 0.3, 1.0), vp.at(31, 4, 0.5, 3.0), vp.at(6, 30, 0.7, 7.0)};
  s.count = count;
  for (uint32_t v = 0; v < 3; ++v) {
    for (uint32_t i = 0; i < count; ++i)
      s.varyings.push_back(static_cast<float>((i + 1) * (v + 1)) + 0.25f * static_cast<float>(i));
  }
  return s;
}

std::vector<float> render(const PipelineState& pipeline, const DrawInput& input,
                          uint32_t samples = 1, Backend backend = Backend::kReference) {
  Framebuffer fb = float_target(samples);
  fb.clear_color({-1, -1, -1, -1});
  RendererOptions options = test::reference_options();
  options.backend = backend;
  Renderer renderer(options);
  renderer.draw(fb, pipeline, input);
  return fb.read_rgba32f();
}

// The four varyings from `first` on, read through the Gouraud shader's colour role.
std::vector<float> varyings_at(PipelineState pipeline, const DrawInput& input, uint32_t first) {
  pipeline.roles.color = first;
  return render(pipeline, input);
}

TEST(ReferenceShading, EveryOneOfThirtyTwoVaryingsIsInterpolatedLikeTheColour) {
  const Scene all = perspective_triangle(kMaxVaryings);
  for (Interpolation mode : {Interpolation::kPerspective, Interpolation::kAffine}) {
    PipelineState pipeline;
    pipeline.interpolation = mode;
    for (uint32_t first = 0; first < kMaxVaryings; first += 4) {
      // The same four values as the only varyings of a draw: today's colour path.
      Scene four = perspective_triangle(0);
      four.count = 4;
      for (uint32_t v = 0; v < 3; ++v) {
        for (uint32_t c = 0; c < 4; ++c)
          four.varyings.push_back(all.varyings[v * kMaxVaryings + first + c]);
      }
      EXPECT_EQ(varyings_at(pipeline, all.input(), first), render(pipeline, four.input()))
          << "varyings " << first << ".." << first + 3;
    }
  }
}

TEST(ReferenceShading, EachVaryingTakesItsOwnModeAndFlatOnesTheFirstVertexValue) {
  const Scene s = perspective_triangle(12);
  PipelineState perspective, affine, mixed;
  affine.interpolation = Interpolation::kAffine;
  for (uint32_t i = 4; i < 8; ++i)
    mixed.varying_modes[i] = VaryingMode::kAffine;
  for (uint32_t i = 8; i < 12; ++i)
    mixed.varying_modes[i] = VaryingMode::kFlat;
  EXPECT_EQ(varyings_at(mixed, s.input(), 0), varyings_at(perspective, s.input(), 0));
  EXPECT_EQ(varyings_at(mixed, s.input(), 4), varyings_at(affine, s.input(), 4));
  const std::vector<float> flat = varyings_at(mixed, s.input(), 8);
  uint32_t covered = 0;
  for (uint32_t y = 0; y < kSize; ++y) {
    for (uint32_t x = 0; x < kSize; ++x) {
      const auto p = pixel(flat, x, y);
      if (p[0] == -1.0f) continue;
      ++covered;
      for (uint32_t c = 0; c < 4; ++c)
        ASSERT_EQ(p[c], s.varyings[8 + c]) << x << "," << y;
    }
  }
  EXPECT_GT(covered, 200u);
  // Perspective and affine really differ here, so the comparisons above could fail.
  EXPECT_NE(varyings_at(perspective, s.input(), 4), varyings_at(affine, s.input(), 4));
}

// A triangle whose first vertex lies behind the near plane: clipping removes it, and its
// flat varyings still provoke; the perspective and affine varyings that the clipper cuts
// match a draw of the same values in varyings 0..3.
TEST(ReferenceShading, ClippingCarriesEveryVaryingAndKeepsTheProvokingVertex) {
  const Viewport vp{kSize, kSize};
  Scene s;
  s.positions = {{0.0f, 0.5f, -0.5f, 1.0f}, vp.at(2, 30, 0.5, 1.5), vp.at(30, 28, 0.5, 2.0)};
  s.count = 24;
  for (uint32_t v = 0; v < 3; ++v) {
    for (uint32_t i = 0; i < s.count; ++i)
      s.varyings.push_back(static_cast<float>(i % 4 + 1) * static_cast<float>(v + 2) * 0.1f);
  }
  PipelineState pipeline;
  for (uint32_t i = 8; i < 12; ++i)
    pipeline.varying_modes[i] = VaryingMode::kAffine;
  for (uint32_t i = 20; i < 24; ++i)
    pipeline.varying_modes[i] = VaryingMode::kFlat;
  Renderer renderer(test::reference_options());
  Framebuffer fb = float_target();
  renderer.draw(fb, pipeline, s.input());
  EXPECT_EQ(renderer.counters().triangles_clipped, 1u);
  PipelineState affine = pipeline;
  affine.interpolation = Interpolation::kAffine;
  EXPECT_EQ(varyings_at(pipeline, s.input(), 16), varyings_at(pipeline, s.input(), 0));
  EXPECT_EQ(varyings_at(pipeline, s.input(), 8), varyings_at(affine, s.input(), 0));
  const std::vector<float> flat = varyings_at(pipeline, s.input(), 20);
  uint32_t covered = 0;
  for (uint32_t i = 0; i < kSize * kSize; ++i) {
    if (flat[i * 4] == -1.0f) continue;
    ++covered;
    for (uint32_t c = 0; c < 4; ++c)
      ASSERT_EQ(flat[i * 4 + c], s.varyings[20 + c]);
  }
  EXPECT_GT(covered, 50u);
}

TEST(ReferenceShading, EyeDepthIsTheClipWAtThePixel) {
  // w as a perspective-correct varying interpolates to 1 / (sum b_i / w_i): the eye depth.
  Scene s = perspective_triangle(0);
  s.count = 4;
  for (const Float4& p : s.positions)
    s.varyings.insert(s.varyings.end(), {p.w, p.w, p.w, 1.0f});
  PipelineState depth;
  depth.output = TargetOutput::kEyeDepth;
  const std::vector<float> eye = render(depth, s.input());
  const std::vector<float> w = render(PipelineState{}, s.input());
  uint32_t covered = 0;
  for (uint32_t i = 0; i < kSize * kSize * 4; ++i) {
    if (w[i] == -1.0f) continue;
    ++covered;
    EXPECT_NEAR(eye[i], w[i], 1e-5 * w[i]);
  }
  EXPECT_GT(covered, 800u);
  EXPECT_EQ(eye[0 * 4 + 3], -1.0f);  // pixel (0, 0) is outside the triangle
}

TEST(ReferenceShading, BarycentricsAreThePerspectiveWeightsOfTheDrawnTriangleEvenWhenClipped) {
  const Viewport vp{kSize, kSize};
  for (bool clipped : {false, true}) {
    Scene s;
    s.positions = {clipped ? Float4{0.0f, 0.5f, -0.5f, 1.0f} : vp.at(16, 1, 0.5, 1.0),
                   vp.at(2, 30, 0.5, 1.5), vp.at(30, 28, 0.5, 4.0)};
    s.count = 3;
    s.varyings = {1, 0, 0, 0, 1, 0, 0, 0, 1};
    PipelineState bary;
    bary.output = TargetOutput::kBarycentrics;
    PipelineState explicit_weights;  // the same weights given as varyings 0..2
    const std::vector<float> a = render(bary, s.input());
    const std::vector<float> b = render(explicit_weights, s.input());
    uint32_t covered = 0;
    for (uint32_t i = 0; i < kSize * kSize; ++i) {
      if (b[i * 4] == -1.0f) continue;
      ++covered;
      for (uint32_t c = 0; c < 3; ++c)
        ASSERT_EQ(a[i * 4 + c], b[i * 4 + c]) << "clipped " << clipped;
      EXPECT_NEAR(a[i * 4] + a[i * 4 + 1] + a[i * 4 + 2], 1.0, 1e-6);
    }
    EXPECT_GT(covered, 100u);
  }
}

// Sixteen triangles in a 4x4 grid of 8x8 cells, one covering each cell's lower left half.
Scene id_grid() {
  const Viewport vp{kSize, kSize};
  Scene s;
  for (int cy = 0; cy < 4; ++cy) {
    for (int cx = 0; cx < 4; ++cx) {
      const double x = cx * 8.0, y = cy * 8.0;
      s.positions.insert(s.positions.end(), {vp.at(x, y), vp.at(x, y + 8), vp.at(x + 8, y + 8)});
    }
  }
  return s;
}

TEST(ReferenceShading, PrimitiveIdsAreTheTrianglesIndicesInTheDraw) {
  Scene s = id_grid();
  PipelineState ids;
  ids.output = TargetOutput::kPrimitiveId;
  const std::vector<float> out = render(ids, s.input());
  for (uint32_t t = 0; t < 16; ++t) {
    // A pixel well inside cell t's triangle.
    const auto p = pixel(out, (t % 4) * 8 + 2, (t / 4) * 8 + 6);
    EXPECT_EQ(p[0], static_cast<float>(t));
    EXPECT_EQ(p[1], static_cast<float>(t));
    EXPECT_EQ(p[3], 1.0f);
  }
  // A triangle dropped for a NaN vertex (NonFiniteVertices::kCull) leaves the others' IDs as
  // the caller numbered them.
  s.positions[3 * 5].x = std::numeric_limits<float>::quiet_NaN();
  RendererOptions options = test::reference_options();
  options.non_finite = NonFiniteVertices::kCull;
  Renderer renderer(options);
  Framebuffer fb = float_target();
  fb.clear_color({-1, -1, -1, -1});
  renderer.draw(fb, ids, s.input());
  const std::vector<float> culled = fb.read_rgba32f();
  EXPECT_EQ(pixel(culled, 1 * 8 + 2, 1 * 8 + 6)[0], -1.0f);  // triangle 5 is gone
  EXPECT_EQ(pixel(culled, 0 * 8 + 2, 1 * 8 + 6)[0], 4.0f);
  EXPECT_EQ(pixel(culled, 2 * 8 + 2, 1 * 8 + 6)[0], 6.0f);
  EXPECT_EQ(pixel(culled, 3 * 8 + 2, 3 * 8 + 6)[0], 15.0f);
}

TEST(ReferenceShading, ObjectIdIsTheDrawsOwn) {
  const Scene s = id_grid();
  PipelineState ids;
  ids.output = TargetOutput::kObjectId;
  ids.object_id = 12345;
  const std::vector<float> out = render(ids, s.input());
  EXPECT_EQ(pixel(out, 2, 6)[0], 12345.0f);
  EXPECT_EQ(pixel(out, 6, 2)[0], -1.0f);  // the upper right half of a cell is not drawn
}

TEST(ReferenceShading, NormalsAreNormalizedAndPositionsInterpolated) {
  const Viewport vp{kSize, kSize};
  Scene s;
  s.positions = {vp.at(0, 0), vp.at(0, 64), vp.at(64, 0)};  // w = 1: interpolation is linear
  s.count = 6;
  // Normal (0, 0, 2) everywhere (normalized: (0, 0, 1)); position = the window position.
  s.varyings = {0, 0, 2, 0, 0, 0, 0, 0, 2, 0, 64, 0, 0, 0, 2, 64, 0, 0};
  PipelineState normals;
  normals.output = TargetOutput::kNormal;
  normals.roles.normal = 0;
  PipelineState positions;
  positions.output = TargetOutput::kPosition;
  positions.roles.position = 3;
  const std::vector<float> n = render(normals, s.input());
  const std::vector<float> p = render(positions, s.input());
  for (uint32_t y = 0; y < kSize; y += 5) {
    for (uint32_t x = 0; x + y < kSize; x += 5) {
      EXPECT_EQ(pixel(n, x, y), (std::array<float, 4>{0, 0, 1, 1}));
      const auto at = pixel(p, x, y);
      EXPECT_NEAR(at[0], x + 0.5, 1e-5);
      EXPECT_NEAR(at[1], y + 0.5, 1e-5);
    }
  }
}

// Phong, written out again here from tessera/shading.hpp's formula.
std::array<double, 3> expected_phong(const PhongState& st, std::array<double, 3> n,
                                     std::array<double, 3> p, std::array<double, 4> base) {
  auto dot = [](const std::array<double, 3>& a, const std::array<double, 3>& b) {
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
  };
  auto unit = [&](std::array<double, 3> a) {
    const double l = std::sqrt(dot(a, a));
    return std::array<double, 3>{a[0] / l, a[1] / l, a[2] / l};
  };
  n = unit(n);
  const auto v = unit({st.eye[0] - p[0], st.eye[1] - p[1], st.eye[2] - p[2]});
  std::array<double, 3> out;
  for (int c = 0; c < 3; ++c) {
    double i = st.ka * st.ambient[c];
    for (uint32_t k = 0; k < st.light_count; ++k) {
      const Light& li = st.lights[k];
      std::array<double, 3> l;
      double att = 1;
      if (li.kind == LightKind::kDirectional) {
        l = unit({-li.direction[0], -li.direction[1], -li.direction[2]});
      } else {
        const std::array<double, 3> r = {li.position[0] - p[0], li.position[1] - p[1],
                                         li.position[2] - p[2]};
        const double d = std::sqrt(dot(r, r));
        l = unit(r);
        att = 1 / (li.c0 + li.c1 * d + li.c2 * d * d);
        if (li.kind == LightKind::kSpot) {
          const double cosine = -dot(l, unit({li.direction[0], li.direction[1], li.direction[2]}));
          att = cosine < li.spot_cos_cutoff ? 0 : att * std::pow(cosine, li.spot_exponent);
        }
      }
      const double ndl = dot(n, l);
      const std::array<double, 3> r = {2 * ndl * n[0] - l[0], 2 * ndl * n[1] - l[1],
                                       2 * ndl * n[2] - l[2]};
      const double spec = ndl > 0 ? st.ks * std::pow(std::max(0.0, dot(r, v)), st.shininess) : 0;
      i += att * (st.kd * std::max(0.0, ndl) * li.diffuse[c] + spec * li.specular[c]);
    }
    out[c] = std::clamp(i * base[c], 0.0, 1.0);
  }
  return out;
}

TEST(ReferenceShading, PerPixelPhongMatchesTheFormulaAtEveryPixel) {
  // A plane z = -10 in eye space seen head on, w = 1 so its position varyings are linear in
  // the window: at pixel (x, y) the point is (x + 0.5 - 16, 16 - y - 0.5, -10) / 4.
  const Viewport vp{kSize, kSize};
  Scene s;
  s.positions = {vp.at(0, 0), vp.at(0, 64), vp.at(64, 0)};
  s.count = 10;
  const auto eye_point = [](double x, double y) {
    return std::array<double, 3>{(x - 16) / 4, (16 - y) / 4, -10};
  };
  for (const auto& [x, y] : {std::pair{0.0, 0.0}, {0.0, 64.0}, {64.0, 0.0}}) {
    const auto p = eye_point(x, y);
    // Normal tilted a little toward +x; position; a vertex colour (0.8, 0.6, 1, 1).
    s.varyings.insert(s.varyings.end(),
                      {0.2f, 0.0f, 1.0f, static_cast<float>(p[0]), static_cast<float>(p[1]),
                       static_cast<float>(p[2]), 0.8f, 0.6f, 1.0f, 1.0f});
  }
  PipelineState pipeline;
  pipeline.shader = FragmentShader::kPhong;
  pipeline.roles = {6, 0, 3};
  PhongState& st = pipeline.phong;
  st.base_color = {0.9f, 1.0f, 0.7f, 0.5f};
  st.shininess = 16;
  st.light_count = 3;
  st.lights[0] = {};  // a point light at (1, 2, -4), attenuated
  st.lights[0].position = {1, 2, -4};
  st.lights[0].c1 = 0.05f;
  st.lights[0].c2 = 0.01f;
  st.lights[1].kind = LightKind::kDirectional;
  st.lights[1].direction = {0.3f, -0.2f, -1.0f};
  st.lights[1].diffuse = {0.4f, 0.3f, 0.2f};
  st.lights[2].kind = LightKind::kSpot;  // a cone that lights only part of the plane
  st.lights[2].position = {0, 0, 0};
  st.lights[2].direction = {0.4f, 0.0f, -1.0f};
  st.lights[2].spot_cos_cutoff = 0.95f;
  st.lights[2].spot_exponent = 4;
  // The reference evaluates in double; the fast engine in float, its powers by
  // simd/math-inl.h (docs/SHADING.md states the tolerances).
  for (const auto& [backend, tolerance] :
       {std::pair{Backend::kReference, 1e-5}, std::pair{Backend::kFast, 1e-4}}) {
    const std::vector<float> out = render(pipeline, s.input(), 1, backend);
    double largest = 0;
    int spot_lit = 0;
    for (uint32_t y = 0; y < kSize; ++y) {
      for (uint32_t x = 0; x + y + 1 < kSize; ++x) {
        const auto p = eye_point(x + 0.5, y + 0.5);
        const auto want = expected_phong(st, {0.2, 0, 1}, p, {0.9 * 0.8, 1.0 * 0.6, 0.7, 0.5});
        const auto got = pixel(out, x, y);
        for (int c = 0; c < 3; ++c) {
          EXPECT_NEAR(got[c], want[c], tolerance) << x << "," << y << " channel " << c;
          largest = std::max(largest, want[c]);
        }
        EXPECT_EQ(got[3], 0.5f);
        const double cosine = (0.4 * p[0] - p[2]) / std::sqrt(0.16 + 1.0) /
                              std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
        spot_lit += cosine >= 0.95;
      }
    }
    EXPECT_GT(largest, 0.3);  // lit, not black
    EXPECT_GT(spot_lit, 10);
    EXPECT_LT(spot_lit, 400);  // and the cone's edge crosses the plane
  }
}

TEST(ReferenceShading, TwoSidedPhongTurnsANormalFacingAwayTowardTheEye) {
  const Viewport vp{kSize, kSize};
  Scene toward, away;
  for (Scene* s : {&toward, &away}) {
    s->positions = {vp.at(0, 0), vp.at(0, 64), vp.at(64, 0)};
    s->count = 6;
    const float sign = s == &toward ? 1.0f : -1.0f;
    for (const auto& [x, y] : {std::pair{-4.0f, 4.0f}, {-4.0f, -12.0f}, {12.0f, 4.0f}})
      s->varyings.insert(s->varyings.end(), {0.3f * sign, 0.1f * sign, sign, x, y, -10.0f});
  }
  PipelineState pipeline;
  pipeline.shader = FragmentShader::kPhong;
  pipeline.roles = {6, 0, 3};
  pipeline.phong.light_count = 1;
  pipeline.phong.lights[0].position = {2, 3, 0};
  for (Backend backend : {Backend::kReference, Backend::kFast}) {
    pipeline.phong.two_sided = false;
    const std::vector<float> lit = render(pipeline, toward.input(), 1, backend);
    const std::vector<float> dark = render(pipeline, away.input(), 1, backend);
    pipeline.phong.two_sided = true;
    EXPECT_EQ(render(pipeline, away.input(), 1, backend), lit);
    EXPECT_EQ(render(pipeline, toward.input(), 1, backend), lit);
    EXPECT_NE(dark, lit);
    EXPECT_NEAR(pixel(dark, 10, 10)[0], 0.1f, 1e-6);  // ka Ia alone
  }
}

TEST(ReferenceShading, BadShadingStateIsRejectedNamingItAndLeavesTheTargetAlone) {
  const Scene s = perspective_triangle(6);
  struct Bad {
    const char* what;
    PipelineState pipeline;
    ColorFormat format = ColorFormat::kRGBA32F;
  };
  std::vector<Bad> bad;
  {
    Bad b{"varying_modes[3]", {}};
    b.pipeline.varying_modes[3] = static_cast<VaryingMode>(9);
    bad.push_back(b);
  }
  {
    Bad b{"roles.normal", {}};
    b.pipeline.output = TargetOutput::kNormal;
    b.pipeline.roles.normal = 4;  // 4..6, but the draw has 6 varyings
    bad.push_back(b);
  }
  {
    Bad b{"roles.position", {}};
    b.pipeline.shader = FragmentShader::kPhong;
    b.pipeline.roles.normal = 0;
    b.pipeline.roles.position = 7;
    bad.push_back(b);
  }
  {
    Bad b{"phong.light_count", {}};
    b.pipeline.shader = FragmentShader::kPhong;
    b.pipeline.roles = {0, 0, 3};
    b.pipeline.phong.light_count = 9;
    bad.push_back(b);
  }
  {
    Bad b{"phong.lights[1] attenuation", {}};
    b.pipeline.shader = FragmentShader::kPhong;
    b.pipeline.roles = {0, 0, 3};
    b.pipeline.phong.light_count = 2;
    b.pipeline.phong.lights[1].c0 = 0;
    bad.push_back(b);
  }
  {
    Bad b{"phong.shininess", {}};
    b.pipeline.shader = FragmentShader::kPhong;
    b.pipeline.roles = {0, 0, 3};
    b.pipeline.phong.shininess = std::numeric_limits<float>::infinity();
    bad.push_back(b);
  }
  {
    Bad b{"phong.lights[0].spot_exponent", {}};
    b.pipeline.shader = FragmentShader::kPhong;
    b.pipeline.roles = {0, 0, 3};
    b.pipeline.phong.light_count = 1;
    b.pipeline.phong.lights[0].kind = LightKind::kSpot;
    b.pipeline.phong.lights[0].spot_exponent = -2;
    bad.push_back(b);
  }
  {
    Bad b{"RGBA32F", {}, ColorFormat::kRGBA8};
    b.pipeline.output = TargetOutput::kPrimitiveId;
    bad.push_back(b);
  }
  {
    Bad b{"object_id", {}};
    b.pipeline.output = TargetOutput::kObjectId;
    b.pipeline.object_id = 1u << 24;
    bad.push_back(b);
  }
  for (const Bad& b : bad) {
    for (Backend backend : {Backend::kReference, Backend::kFast}) {
      RendererOptions options = test::reference_options();
      options.backend = backend;
      Renderer renderer(options);
      Framebuffer fb({kSize, kSize, 1, b.format});
      fb.clear_color({0.25f, 0.25f, 0.25f, 0.25f});
      const std::vector<float> before = fb.read_rgba32f();
      try {
        renderer.draw(fb, b.pipeline, s.input());
        ADD_FAILURE() << b.what << " accepted";
      } catch (const Error& e) {
        EXPECT_EQ(e.code(), ErrorCode::kInvalidArgument) << e.what();
        EXPECT_NE(std::string(e.what()).find(b.what), std::string::npos) << e.what();
      }
      EXPECT_EQ(fb.read_rgba32f(), before) << b.what;
    }
  }
}

// The fast engine draws the Gouraud colour of any four varyings, with any number of varyings,
// to the reference's coverage (tests/fast_shading_test.cpp compares every other state).
TEST(ReferenceShading, TheFastEngineDrawsGouraudWithAnyVaryingCount) {
  const Scene s = perspective_triangle(kMaxVaryings);
  // The colour from varyings 0..3, 5..8, and 30..31 (blue and alpha missing: 0 and 1).
  for (uint32_t color : {0u, 5u, 30u}) {
    PipelineState gouraud;
    gouraud.roles.color = color;
    gouraud.varying_modes[color == 0 ? 7 : 0] = VaryingMode::kFlat;  // not a colour varying
    for (uint32_t samples : {1u, 4u}) {
      const std::vector<float> fast = render(gouraud, s.input(), samples, Backend::kFast);
      const std::vector<float> reference = render(gouraud, s.input(), samples, Backend::kReference);
      ASSERT_EQ(fast.size(), reference.size());
      for (size_t i = 0; i < fast.size(); ++i) {
        ASSERT_EQ(fast[i] == -1.0f, reference[i] == -1.0f) << i;  // the same coverage
        ASSERT_NEAR(fast[i], reference[i], 1e-4 * std::abs(reference[i]) + 1e-5)
            << "colour " << color << " pixel " << i / 4;
      }
      if (color == 30) {
        EXPECT_EQ(reference[(16 * kSize + 16) * 4 + 3], 1.0f);
      }
    }
  }
  // A triangle a clip plane cuts takes the fast setup's scalar path: its colour role too.
  {
    const Viewport vp{kSize, kSize};
    Scene clipped;
    clipped.positions = {
        {0.0f, 0.5f, -0.5f, 1.0f}, vp.at(2, 30, 0.5, 1.5), vp.at(30, 28, 0.5, 2.0)};
    clipped.count = 9;
    for (uint32_t v = 0; v < 3; ++v) {
      for (uint32_t i = 0; i < clipped.count; ++i)
        clipped.varyings.push_back(static_cast<float>(i + 1) * 0.1f * static_cast<float>(v + 1));
    }
    PipelineState role;
    role.roles.color = 5;
    const std::vector<float> fast = render(role, clipped.input(), 1, Backend::kFast);
    const std::vector<float> reference = render(role, clipped.input(), 1, Backend::kReference);
    size_t covered = 0;
    for (size_t i = 0; i < fast.size(); ++i) {
      ASSERT_EQ(fast[i] == -1.0f, reference[i] == -1.0f) << i;
      ASSERT_NEAR(fast[i], reference[i], 1e-4 * std::abs(reference[i]) + 1e-5) << i;
      covered += reference[i] != -1.0f;
    }
    EXPECT_GT(covered, 200u);
  }
}

}  // namespace
}  // namespace tessera
