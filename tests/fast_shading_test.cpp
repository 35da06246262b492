// The fast engine's shaded draws (engine/src/shade/) against the reference: every built-in
// shader and vision output, every varying mode, RGBA8 and RGBA32F targets, one and four samples,
// on a perspective mesh with small, large and clipped triangles under a depth test. Coverage
// is the reference's exactly; values lie within the tolerances docs/SHADING.md states; and
// every SIMD target this CPU runs gives the same bytes at 1, 2 and 3 threads.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "tessera/tessera.hpp"
#include "tests/shading_scene.hpp"

namespace tessera {
namespace {

using shading_scene::Image;
using shading_scene::kClear;
using shading_scene::kHeight;
using shading_scene::kWidth;
using shading_scene::Mesh;
using shading_scene::render;
using shading_scene::Target;
using shading_scene::test_mesh;

struct Case {
  std::string name;
  PipelineState pipeline;
  bool float_only = false;  // IDs need an RGBA32F target
  // Largest difference from the reference, absolute plus relative to its value (float
  // targets); RGBA8 targets may differ by one step where a value lies near a rounding edge.
  double absolute = 0, relative = 0;
};

std::vector<Case> cases() {
  std::vector<Case> out;
  const auto add = [&](std::string name, double absolute, double relative,
                       const auto& set) -> Case& {
    Case c;
    c.name = std::move(name);
    c.absolute = absolute;
    c.relative = relative;
    set(c.pipeline);
    out.push_back(c);
    return out.back();
  };
  add("phong, three point lights", 2e-5, 0, [](PipelineState& p) {
    p.shader = FragmentShader::kPhong;
    p.phong.light_count = 3;
    p.phong.lights[0].position = {1.5f, 2.0f, -1.0f};
    p.phong.lights[1].position = {-2.0f, 0.5f, -2.0f};
    p.phong.lights[1].diffuse = {0.3f, 0.5f, 0.9f};
    p.phong.lights[1].c1 = 0.2f;
    p.phong.lights[2].position = {0.0f, -1.5f, -2.5f};
    p.phong.lights[2].c2 = 0.3f;
    p.phong.shininess = 40;
  });
  add("phong, directional and spot, two-sided, no colour varyings", 2e-5, 0, [](PipelineState& p) {
    p.shader = FragmentShader::kPhong;
    p.roles.color = 8;  // two colour varyings: the base colour alone
    p.phong.two_sided = true;
    p.phong.base_color = {0.8f, 0.7f, 0.3f, 0.75f};
    p.phong.light_count = 2;
    p.phong.lights[0].kind = LightKind::kDirectional;
    p.phong.lights[0].direction = {-0.3f, -0.5f, -1.0f};
    p.phong.lights[1].kind = LightKind::kSpot;
    p.phong.lights[1].position = {0.5f, 0.5f, 0.0f};
    p.phong.lights[1].direction = {-0.1f, -0.2f, -1.0f};
    p.phong.lights[1].spot_cos_cutoff = 0.97f;
    p.phong.lights[1].spot_exponent = 3;
    p.phong.shininess = 7.5f;
  });
  add("phong, affine normals and flat positions", 2e-5, 0, [](PipelineState& p) {
    p.shader = FragmentShader::kPhong;
    p.phong.light_count = 1;
    p.phong.lights[0].position = {0.0f, 1.0f, 0.0f};
    for (uint32_t i = 4; i < 7; ++i)
      p.varying_modes[i] = VaryingMode::kAffine;
    for (uint32_t i = 7; i < 10; ++i)
      p.varying_modes[i] = VaryingMode::kFlat;
  });
  add("flat colour", 0, 0, [](PipelineState& p) {
    for (uint32_t i = 0; i < 4; ++i)
      p.varying_modes[i] = VaryingMode::kFlat;
  });
  add("gouraud, mixed modes", 2e-6, 0, [](PipelineState& p) {
    p.varying_modes[0] = VaryingMode::kAffine;
    p.varying_modes[1] = VaryingMode::kFlat;
    p.varying_modes[2] = VaryingMode::kPerspective;
    p.interpolation = Interpolation::kAffine;  // varying 3 (kDefault) affine
  });
  add("normals", 2e-6, 0, [](PipelineState& p) { p.output = TargetOutput::kNormal; });
  add("positions, affine", 2e-6, 1e-6, [](PipelineState& p) {
    p.output = TargetOutput::kPosition;
    p.interpolation = Interpolation::kAffine;
  });
  add("eye depth", 0, 2e-6, [](PipelineState& p) { p.output = TargetOutput::kEyeDepth; });
  add("barycentrics", 2e-6, 0, [](PipelineState& p) { p.output = TargetOutput::kBarycentrics; });
  add("primitive ids", 0, 0, [](PipelineState& p) {
    p.output = TargetOutput::kPrimitiveId;
  }).float_only = true;
  add("object id", 0, 0, [](PipelineState& p) {
    p.output = TargetOutput::kObjectId;
    p.object_id = 77;
  }).float_only = true;
  return out;
}

TEST(FastShading, EveryShaderAndOutputMatchesTheReferenceOnEveryTargetAndThreadCount) {
  const Mesh mesh = test_mesh();
  const std::vector<Target> targets = shading_scene::fast_targets();
  ASSERT_FALSE(targets.empty());
  for (const Case& c : cases()) {
    for (ColorFormat format : {ColorFormat::kRGBA32F, ColorFormat::kRGBA8}) {
      if (c.float_only && format == ColorFormat::kRGBA8) continue;
      for (uint32_t samples : {1u, 4u}) {
        const std::string what = c.name +
                                 (format == ColorFormat::kRGBA8 ? ", RGBA8" : ", RGBA32F") + ", " +
                                 std::to_string(samples) + " samples";
        PipelineState pipeline = c.pipeline;
        pipeline.cull = CullMode::kNone;
        const Image want = render(mesh, pipeline, format, samples, Backend::kReference);
        const Image first = render(mesh, pipeline, format, samples, Backend::kFast, targets[0]);
        // Same bytes on every target and at every thread count.
        for (const Target& t : targets) {
          const Image got = render(mesh, pipeline, format, samples, Backend::kFast, t);
          ASSERT_EQ(got.rgba32f, first.rgba32f)
              << what << ", target " << int(t.simd) << ", " << t.threads << " threads";
          ASSERT_EQ(got.rgba8, first.rgba8) << what << ", target " << int(t.simd);
        }
        size_t covered = 0;
        if (format == ColorFormat::kRGBA32F) {
          for (size_t i = 0; i < want.rgba32f.size(); ++i) {
            const float w = want.rgba32f[i], g = first.rgba32f[i];
            ASSERT_EQ(w == kClear, g == kClear) << what << ": coverage differs at value " << i;
            if (w == kClear) continue;
            covered += i % 4 == 3;
            const double error = std::abs(double{g} - w);
            ASSERT_LE(error, c.absolute + c.relative * std::abs(w))
                << what << ": value " << i << " (pixel " << i / 4 << ") " << g << " against " << w;
          }
        } else {
          // Alpha is never 0 here: a byte of 0 (the clear) in alpha is an uncovered pixel.
          for (size_t i = 0; i < want.rgba8.size(); ++i) {
            if (i % 4 == 3) {
              ASSERT_EQ(want.rgba8[i] == 0, first.rgba8[i] == 0) << what << ": coverage at " << i;
            }
            const int error = std::abs(int{want.rgba8[i]} - first.rgba8[i]);
            covered += i % 4 == 3 && want.rgba8[i] != 0;
            ASSERT_LE(error, 1) << what << ": byte " << i;
          }
        }
        EXPECT_GT(covered, size_t{kWidth * kHeight / 2}) << what;  // most of the view
      }
    }
  }
}

// A shaded draw writes exactly the samples the Gouraud draw of the same triangles does, and the
// same depth: only the colour differs.
TEST(FastShading, ShadedDrawsCoverAndDepthTestLikeGouraudDraws) {
  const Mesh mesh = test_mesh();
  for (uint32_t samples : {1u, 2u, 4u}) {
    PipelineState gouraud, phong;
    phong.shader = FragmentShader::kPhong;
    phong.phong.light_count = 1;
    RendererOptions options;
    Renderer renderer(options);
    Framebuffer a({kWidth, kHeight, samples, ColorFormat::kRGBA8});
    Framebuffer b({kWidth, kHeight, samples, ColorFormat::kRGBA8});
    renderer.draw(a, gouraud, mesh.input());
    const Counters gouraud_counts = renderer.counters();
    renderer.reset_counters();
    renderer.draw(b, phong, mesh.input());
    const Counters phong_counts = renderer.counters();
    EXPECT_EQ(a.read_depth(), b.read_depth()) << samples;
    EXPECT_EQ(gouraud_counts.samples_covered, phong_counts.samples_covered);
    EXPECT_EQ(gouraud_counts.samples_passed, phong_counts.samples_passed);
    EXPECT_EQ(gouraud_counts.triangles_rasterized, phong_counts.triangles_rasterized);
    EXPECT_NE(a.read_rgba8(), b.read_rgba8());
  }
}

}  // namespace
}  // namespace tessera
